/* Verification of the Baraff-Witkin stretch term and its damping (docs/model.md
 * 3.3; docs/architecture.md, "Checks every force term passes";
 * forces/bw_stretch.c): C = a (|w_u| - bu, |w_v| - bv) per triangle.
 *
 * Each check runs bw-stretch (or bw-stretch-damping) alone on full-particle
 * states: the u and v conditions separately (kv = 0, ku = 0) and together,
 * Jacobians against central differences, f = -dE/dx, Newton's third law,
 * rotation invariance, the force and energy against an independent reference
 * written here from docs/model.md 3.3, uniform stretches with known energies,
 * exact zeros at rest, and the damping with its documented approximation of
 * dd/dx. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwcheck.h"

static void ref_stretch(const bw_ref *r, const int *v, const double *xe,
                        double *C, double (*g)[CL_BW_NX])
{
    double w[2][3], dW[2][3];
    double a = bw_ref_w(r->cloth, v, xe, w, dW);
    const double *b = r->b;
    for (int c = 0; c < 2; c++) {
        double len = sqrt(w[c][0] * w[c][0] + w[c][1] * w[c][1] +
                          w[c][2] * w[c][2]);
        C[c] = a * (len - b[c]);
        for (int m = 0; m < 3; m++)
            for (int i = 0; i < 3; i++)
                g[c][3 * m + i] = a * dW[c][m] * w[c][i] / len;
    }
}

static bw_ref stretch_ref(const cl_model *m, cl_diagonal diag, double bu,
                          double bv)
{
    bw_ref r = bw_ref_elements(m, 3, 2, diag);
    r.cond = ref_stretch;
    r.b[0] = bu;
    r.b[1] = bv;
    return r;
}

static void state(const cl_model *m, fd_rng *r, double *x, double *v)
{
    double A[9];
    fd_scale(1.04 + 0.03 * fd_rand(r), 0.97 + 0.03 * fd_rand(r), A);
    bw_state(m, A, 0.1, 0.3, 1.0, r, x, v);
}

/* ---- the potential part ------------------------------------------------- */

Test(bw_stretch, stretch_u_alone)
{
    cl_model *m = BW_ONLY("cloth.n=4", "bw-stretch.enabled=true",
                          "bw-stretch.k=3e5", "bw-stretch.kv=0");
    bw_potential_case(m, stretch_ref(m, CL_DIAGONAL_FIXED, 1.0, 1.0),
                      (double[2]){3e5, 0.0}, "bw-stretch", state, 101,
                      "bw-stretch u");
}

Test(bw_stretch, stretch_v_alone)
{
    cl_model *m = BW_ONLY("cloth.n=4", "bw-stretch.enabled=true",
                          "bw-stretch.k=3e5", "bw-stretch.ku=0");
    bw_potential_case(m, stretch_ref(m, CL_DIAGONAL_FIXED, 1.0, 1.0),
                      (double[2]){0.0, 3e5}, "bw-stretch", state, 102,
                      "bw-stretch v");
}

/* Both, anisotropic, with targets bu, bv != 1, a rectangular grid and the
 * alternating diagonal. */
Test(bw_stretch, stretch_uv_anisotropic)
{
    cl_model *m = BW_ONLY("cloth.nu=5", "cloth.nv=4", "cloth.su=1.3",
                          "cloth.sv=0.8", "cloth.diagonal=alternate",
                          "bw-stretch.enabled=true", "bw-stretch.ku=2e5",
                          "bw-stretch.kv=7e5", "bw-stretch.bu=0.95",
                          "bw-stretch.bv=1.02");
    bw_potential_case(m, stretch_ref(m, CL_DIAGONAL_ALTERNATE, 0.95, 1.02),
                      (double[2]){2e5, 7e5}, "bw-stretch", state, 103,
                      "bw-stretch uv");
}

/* At rest w_u = (1,0,0), w_v = (0,0,1) exactly: no force, no energy. */
Test(bw_stretch, rest_is_exactly_free_of_force)
{
    cl_model *m = BW_ONLY("cloth.nu=7", "cloth.nv=5", "cloth.su=1.1",
                          "cloth.sv=0.7", "bw-stretch.enabled=true");
    size_t n = fd_n(m);
    double *v = fd_vec(n), *f = fd_vec(n);
    cl_energy e = fd_eval(m, cl_model_cloth(m)->X0, v, f);
    cr_assert_eq(fd_maxabs(f, n), 0.0, "force at rest %g", fd_maxabs(f, n));
    cr_assert_eq(fd_term_energy(&e, "bw-stretch"), 0.0);
    free(v);
    free(f);
    cl_model_free(m);
}

/* Uniform stretch x -> lu x, z -> lv z: w_u = (lu,0,0), w_v = (0,0,lv) on
 * every triangle, E = ntri k/2 a^2 ((lu-bu)^2 + (lv-bv)^2). */
Test(bw_stretch, uniform_stretch_energy)
{
    const double k = 4e5, lu = 1.1, lv = 0.93, bu = 1.0, bv = 0.98;
    cl_model *m = BW_ONLY("cloth.nu=6", "cloth.nv=4", "cloth.su=1.5",
                          "cloth.sv=0.6", "bw-stretch.enabled=true",
                          "bw-stretch.k=4e5", "bw-stretch.bv=0.98");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), A[9];
    fd_rng r = {104};
    fd_scale(lu, lv, A);
    fd_deform(m, A, 0.0, 0.0, &r, x);
    cl_energy e = fd_eval(m, x, v, f);
    double a = 0.5 * (1.5 / 5) * (0.6 / 3), ntri = 2 * 5 * 3;
    double want = ntri * 0.5 * k * a * a *
                  ((lu - bu) * (lu - bu) + (lv - bv) * (lv - bv));
    double got = fd_term_energy(&e, "bw-stretch");
    cr_assert(fabs(got - want) <= 1e-12 * want, "%.17g vs %.17g", got, want);
    /* Interior particles feel no net force under a uniform stretch. */
    const cl_cloth *c = cl_model_cloth(m);
    for (int i = 1; i + 1 < c->nu; i++)
        for (int j = 1; j + 1 < c->nv; j++)
            for (int d = 0; d < 3; d++)
                cr_assert(fabs(f[3 * cl_cloth_index(c, i, j) + d]) <=
                              1e-9 * k * a,
                          "interior force at (%d,%d)", i, j);
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

Test(bw_stretch, rotation_invariance)
{
    cl_model *m = BW_ONLY("cloth.n=4", "bw-stretch.enabled=true",
                          "bw-stretch.ku=2e5", "bw-stretch.kv=5e5",
                          "bw-stretch.bu=1.01");
    bw_rigid_trials(m, state, 105, 3, 1e-11, "bw-stretch");
    cl_model_free(m);
}

/* ---- damping ------------------------------------------------------------ */

static void check_damping(const char *ku_set, const char *kv_set, double kdu,
                          double kdv, unsigned seed, const char *label)
{
    cl_model *m = BW_ONLY("cloth.nu=4", "cloth.nv=3", "cloth.su=0.9",
                          "cloth.sv=0.5", "bw-stretch.enabled=true",
                          "bw-stretch.k=0", ku_set, kv_set);
    bw_ref ref = stretch_ref(m, CL_DIAGONAL_FIXED, 1.0, 1.0);
    double kd[2] = {kdu, kdv};
    bw_damping_trials(m, "bw-stretch", &ref, kd, state, seed, 2, label);
    bw_ref_free(&ref);
    cl_model_free(m);
}

Test(bw_stretch, damping_u)
{
    check_damping("bw-stretch.kdu=30", "bw-stretch.kdv=0", 30.0, 0.0, 106,
                  "bw-stretch-damping u");
}

Test(bw_stretch, damping_v)
{
    check_damping("bw-stretch.kdu=0", "bw-stretch.kdv=30", 0.0, 30.0, 107,
                  "bw-stretch-damping v");
}

Test(bw_stretch, damping_uv)
{
    check_damping("bw-stretch.kd=20", "bw-stretch.kdv=45", 20.0, 45.0, 108,
                  "bw-stretch-damping uv");
}

/* A rigid motion of the velocities (uniform v, or a rotation about any
 * axis) does not change C: no damping force, no power. */
Test(bw_stretch, damping_ignores_rigid_velocities)
{
    cl_model *m = BW_ONLY("cloth.n=4", "bw-stretch.enabled=true",
                          "bw-stretch.k=0", "bw-stretch.kd=50");
    size_t n = fd_n(m), np = n / 3;
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    fd_rng r = {109};
    state(m, &r, x, v);
    double om[3] = {0.4, -1.3, 0.8}, u[3] = {0.2, 0.5, -0.7};
    for (size_t p = 0; p < np; p++) {
        const double *xp = x + 3 * p;
        v[3 * p] = u[0] + om[1] * xp[2] - om[2] * xp[1];
        v[3 * p + 1] = u[1] + om[2] * xp[0] - om[0] * xp[2];
        v[3 * p + 2] = u[2] + om[0] * xp[1] - om[1] * xp[0];
    }
    cl_energy e = fd_eval(m, x, v, f);
    cr_assert_lt(fd_maxabs(f, n), 1e-12, "force %g", fd_maxabs(f, n));
    cr_assert_lt(fabs(e.power_diss), 1e-12);
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}
