/* Verification of the uniform body force (docs/model.md 3.4): f_p = m_p g + F
 * on every particle (pinned ones included in full-particle evaluations), energy
 * E = -sum_p (m_p g + F) . x_p, no Jacobian.  Gravity runs alone (Type1 and
 * Type2 off, no damping). */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"

#define GRAVITY_ONLY(...)                                                   \
    FD_MODEL("type1.enabled=false", "type2.enabled=false", "damping.kd=0", \
             __VA_ARGS__)

static const double G[3] = {0.5, -9.81, 1.25}, F[3] = {0.125, -0.01, 0.02};

Test(gravity, force_per_particle)
{
    cl_model *m = GRAVITY_ONLY("cloth.nu=4", "cloth.nv=5", "cloth.mass=0.3",
                               "gravity.g=0.5, -9.81, 1.25",
                               "gravity.per_particle=0.125 -0.01 0.02",
                               "pins.at=0,0");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    fd_rng r = {61};
    fd_deform(m, NULL, 0.3, 0.3, &r, x);
    fd_random_vec(&r, 1.0, v, n);
    fd_eval(m, x, v, f);
    double pm = 0.3 / 20.0;
    for (size_t p = 0; p < n / 3; p++)
        for (int i = 0; i < 3; i++) {
            double want = pm * G[i] + F[i];
            cr_assert(fabs(f[3 * p + i] - want) <= 1e-15 * fabs(want),
                      "f[%zu][%d] = %.17g, want %.17g", p, i, f[3 * p + i],
                      want);
        }
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

Test(gravity, particle_mass_overrides_total_mass)
{
    cl_model *m = GRAVITY_ONLY("cloth.n=3", "cloth.mass=5",
                               "cloth.particle_mass=0.002",
                               "gravity.g=0,-10,0", "pins.at=");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    memcpy(x, cl_model_cloth(m)->X0, n * sizeof *x);
    fd_eval(m, x, v, f);
    for (size_t p = 0; p < n / 3; p++) {
        cr_assert_eq(cl_model_cloth(m)->mass[p], 0.002);
        cr_assert_float_eq(f[3 * p + 1], -0.02, 1e-17);
        cr_assert_eq(f[3 * p], 0.0);
        cr_assert_eq(f[3 * p + 2], 0.0);
    }
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

Test(gravity, energy_and_its_gradient)
{
    cl_model *m = GRAVITY_ONLY("cloth.n=4", "cloth.mass=0.3",
                               "gravity.g=0.5, -9.81, 1.25",
                               "gravity.per_particle=0.125 -0.01 0.02",
                               "pins.at=");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    fd_rng r = {62};
    fd_deform(m, NULL, 0.5, 0.5, &r, x);
    cl_energy e = fd_eval(m, x, v, f);
    double want = 0.0;
    for (size_t p = 0; p < n / 3; p++)
        for (int i = 0; i < 3; i++)
            want -= (0.3 / 16 * G[i] + F[i]) * x[3 * p + i];
    double got = fd_term_energy(&e, "gravity");
    cr_assert(fabs(got - want) <= 1e-14 * fabs(want), "E %.17g vs %.17g",
              got, want);
    cr_assert_eq(e.potential, got);
    double err = fd_check_energy(m, x, v, 1e-6, "gravity");
    cr_assert_lt(err, 1e-8, "gravity f vs -dE/dx: %g", err);
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

/* Constant force: zero Jacobians, exactly, analytic and by differences. */
Test(gravity, no_jacobian)
{
    cl_model *m = GRAVITY_ONLY("cloth.n=3", "gravity.per_particle=1,2,3",
                               "pins.at=");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_rng r = {63};
    fd_deform(m, NULL, 0.1, 0.1, &r, x);
    fd_random_vec(&r, 1.0, v, n);
    double ex, ev;
    fd_check_jacobian(m, x, v, 1e-6, 1e-6, false, "gravity", &ex, &ev);
    cr_assert_eq(ex, 0.0);
    cr_assert_eq(ev, 0.0);
    free(x);
    free(v);
    cl_model_free(m);
}

/* A uniform field does not turn with the cloth: forces are unchanged by any
 * rigid motion of the state; the energy shifts by -F_total . c under a
 * translation c. */
Test(gravity, rigid_motion)
{
    cl_model *m = GRAVITY_ONLY("cloth.n=4", "cloth.mass=0.3",
                               "gravity.g=0.5, -9.81, 1.25",
                               "gravity.per_particle=0.125 -0.01 0.02",
                               "pins.at=");
    size_t n = fd_n(m), np = n / 3;
    double *x = fd_vec(n), *y = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n),
           *g = fd_vec(n), R[9], I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1},
           c[3] = {0.25, -1.5, 3.0};
    fd_rng r = {64};
    fd_deform(m, NULL, 0.2, 0.2, &r, x);
    fd_rotation(&r, R);
    cl_energy e0 = fd_eval(m, x, v, f);
    fd_apply(R, c, x, y, np);
    fd_eval(m, y, v, g);
    cr_assert_eq(memcmp(f, g, n * sizeof *f), 0);
    fd_apply(I, c, x, y, np);
    cl_energy e1 = fd_eval(m, y, v, g);
    double shift = 0.0;
    for (int i = 0; i < 3; i++)
        shift -= (double)np * (0.3 / 16 * G[i] + F[i]) * c[i];
    cr_assert(fabs(e1.potential - e0.potential - shift) <= 1e-12 * fabs(shift),
              "energy shift %.17g vs %.17g", e1.potential - e0.potential,
              shift);
    free(x);
    free(y);
    free(v);
    free(f);
    free(g);
    cl_model_free(m);
}

Test(gravity, switched_off_when_zero)
{
    cl_model *m = GRAVITY_ONLY("cloth.n=3", "gravity.g=0,0,0", "pins.at=");
    cr_assert(!fd_has_term(m, "gravity"));
    cl_model_free(m);
    m = GRAVITY_ONLY("cloth.n=3", "gravity.g=0,0,0",
                     "gravity.per_particle=0,-0.01,0", "pins.at=");
    cr_assert(fd_has_term(m, "gravity"));
    cl_model_free(m);
    /* Default: on, -9.81 along y. */
    m = GRAVITY_ONLY("cloth.n=3", "pins.at=");
    cr_assert(fd_has_term(m, "gravity"));
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    fd_eval(m, cl_model_cloth(m)->X0, v, f);
    cr_assert_float_eq(f[1], -9.81 * 0.1 / 9, 1e-16);
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

/* Pinned particles: the full evaluation includes their weight, the system
 * (free particles) does not see it. */
Test(gravity, pinned_particles)
{
    cl_model *m = GRAVITY_ONLY("cloth.n=3", "pins.at=0,0 -1,-1");
    const cl_system *sys = cl_model_system(m);
    const cl_cloth *c = cl_model_cloth(m);
    cr_assert_eq(sys->n, 3 * 7);
    size_t n = fd_n(m);
    double *xf = fd_vec(n), *vf = fd_vec(n), *ff = fd_vec(n),
           *x = fd_vec(sys->n), *v = fd_vec(sys->n), *f = fd_vec(sys->n);
    cl_model_initial_state(m, x, v);
    cr_assert_eq(sys->force(sys->data, 0.0, x, v, f), CL_OK);
    cl_cloth_scatter(c, 0.0, x, v, xf, vf);
    fd_eval(m, xf, vf, ff);
    cr_assert_float_eq(ff[1], -9.81 * 0.1 / 9, 1e-16);
    cr_assert_float_eq(ff[3 * 8 + 1], -9.81 * 0.1 / 9, 1e-16);
    for (size_t k = 0; k < c->nfree; k++)
        for (int i = 0; i < 3; i++)
            cr_assert_eq(f[3 * k + i], ff[3 * c->free_p[k] + i]);
    free(xf);
    free(vf);
    free(ff);
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}
