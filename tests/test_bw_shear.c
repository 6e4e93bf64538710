/* Verification of the Baraff-Witkin shear term and its damping (docs/model.md
 * 3.3; docs/architecture.md, "Checks every force term passes";
 * forces/bw_shear.c): C = a w_u . w_v per triangle.
 *
 * bw-shear (or bw-shear-damping) alone on full-particle states: Jacobians
 * against central differences, f = -dE/dx, Newton's third law, rotation
 * invariance, force and energy against an independent reference written here
 * from docs/model.md 3.3, a simple shear with known energy, pure stretches that
 * carry no shear, and the damping with its documented approximation of dd/dx.
 */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwcheck.h"

/* C = a w_u . w_v, dC/dx_m = a (dw_u/dx_m w_v + dw_v/dx_m w_u). */
static void ref_shear(const bw_ref *r, const int *v, const double *xe,
                      double *C, double (*g)[CL_BW_NX])
{
    double w[2][3], dW[2][3];
    double a = bw_ref_w(r->cloth, v, xe, w, dW);
    C[0] = a * (w[0][0] * w[1][0] + w[0][1] * w[1][1] + w[0][2] * w[1][2]);
    for (int m = 0; m < 3; m++)
        for (int i = 0; i < 3; i++)
            g[0][3 * m + i] = a * (dW[0][m] * w[1][i] + dW[1][m] * w[0][i]);
}

static bw_ref shear_ref(const cl_model *m, cl_diagonal diag)
{
    bw_ref r = bw_ref_elements(m, 3, 1, diag);
    r.cond = ref_shear;
    return r;
}

/* Sheared in the plane (x += s z), scaled, jittered in and out of it. */
static void state(const cl_model *m, fd_rng *r, double *x, double *v)
{
    double A[9] = {1.03, 0, 0.15 * fd_rand(r), 0, 1, 0, 0, 0, 0.98};
    bw_state(m, A, 0.1, 0.3, 1.0, r, x, v);
}

Test(bw_shear, jacobian_fixed_diagonal)
{
    cl_model *m = BW_ONLY("cloth.n=4", "bw-shear.enabled=true",
                          "bw-shear.k=2e5");
    bw_potential_case(m, shear_ref(m, CL_DIAGONAL_FIXED),
                      (double[2]){2e5, 0.0}, "bw-shear", state, 301,
                      "bw-shear fixed");
}

Test(bw_shear, jacobian_alternate_rectangular)
{
    cl_model *m = BW_ONLY("cloth.nu=3", "cloth.nv=5", "cloth.su=0.6",
                          "cloth.sv=1.4", "cloth.diagonal=alternate",
                          "bw-shear.enabled=true", "bw-shear.k=5e4");
    bw_potential_case(m, shear_ref(m, CL_DIAGONAL_ALTERNATE),
                      (double[2]){5e4, 0.0}, "bw-shear", state, 302,
                      "bw-shear alternate");
}

/* x += s z: w_u = (1,0,0), w_v = (s,0,1), C = a s on every triangle:
 * E = ntri k a^2 s^2 / 2.  A pure stretch keeps w_u . w_v = 0: no
 * energy, no force. */
Test(bw_shear, simple_shear_energy_and_pure_stretch)
{
    const double k = 3e5, s = 0.12;
    cl_model *m = BW_ONLY("cloth.nu=5", "cloth.nv=4", "cloth.su=1.2",
                          "cloth.sv=0.9", "bw-shear.enabled=true",
                          "bw-shear.k=3e5");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    double A[9] = {1, 0, s, 0, 1, 0, 0, 0, 1};
    fd_rng r = {303};
    fd_deform(m, A, 0.0, 0.0, &r, x);
    cl_energy e = fd_eval(m, x, v, f);
    double a = 0.5 * (1.2 / 4) * (0.9 / 3), ntri = 2 * 4 * 3;
    double want = ntri * 0.5 * k * a * a * s * s;
    double got = fd_term_energy(&e, "bw-shear");
    cr_assert(fabs(got - want) <= 1e-12 * want, "%.17g vs %.17g", got, want);
    fd_scale(1.2, 0.85, A);
    fd_deform(m, A, 0.0, 0.0, &r, x);
    e = fd_eval(m, x, v, f);
    cr_assert_lt(fabs(fd_term_energy(&e, "bw-shear")), 1e-20);
    cr_assert_lt(fd_maxabs(f, n), 1e-9, "pure stretch: force %g",
                 fd_maxabs(f, n));
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

Test(bw_shear, rotation_invariance)
{
    cl_model *m = BW_ONLY("cloth.n=4", "bw-shear.enabled=true",
                          "bw-shear.k=1e5");
    bw_rigid_trials(m, state, 304, 3, 1e-11, "bw-shear");
    cl_model_free(m);
}

Test(bw_shear, damping)
{
    cl_model *m = BW_ONLY("cloth.nu=4", "cloth.nv=3", "cloth.su=0.8",
                          "cloth.sv=0.7", "bw-shear.enabled=true",
                          "bw-shear.k=0", "bw-shear.kd=40");
    bw_ref ref = shear_ref(m, CL_DIAGONAL_FIXED);
    double kd[2] = {40.0, 0.0};
    bw_damping_trials(m, "bw-shear", &ref, kd, state, 305, 2,
                      "bw-shear-damping");
    bw_ref_free(&ref);
    cl_model_free(m);
}
