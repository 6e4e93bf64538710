/* verlet (position Verlet with velocity damping, the Verlet-and-PBD report):
 * the consistent start and the two-step recurrence, the backward-difference
 * velocity, the documented orders (positions 2 and velocity 1 for conservative
 * forces; positions 1 with velocity-dependent forces), bounded energy without
 * drift for vdamp = 0, dissipation for vdamp > 0 (the velocity of a free
 * particle decays exactly by (1 - vdamp) per step), and rejected vdamp. */
#include <criterion/criterion.h>

#include "runint.h"

/* x1 = x0 + h v0 + h^2/2 a0, v1 = (x1 - x0)/h; then
 * x2 = 2 x1 - x0 + h^2 a(x1, v1), v2 = (x2 - x1)/h. */
Test(verlet, consistent_start_and_recurrence)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    double x0[6], v0[6], x[6], v[6], f[6], x1[6], v1[6], h = 0.01;
    ri_steps("verlet", &ts, h, 1, x0, v0, x, v);
    ts_force(&ts, 0.0, x0, v0, f);
    for (int i = 0; i < 6; i++) {
        x1[i] = x0[i] + h * v0[i] + 0.5 * h * h * f[i] / ts.mass[i];
        v1[i] = (x1[i] - x0[i]) / h;
    }
    ri_expect_near(x, x1, 6, 1e-15, "x1");
    ri_expect_near(v, v1, 6, 1e-12, "v1");
    ri_steps("verlet", &ts, h, 2, x0, v0, x, v);
    ts_force(&ts, h, x1, v1, f);
    for (int i = 0; i < 6; i++) {
        double x2 = 2 * x1[i] - x0[i] + h * h * f[i] / ts.mass[i];
        v1[i] = (x2 - x1[i]) / h; /* now v2 */
        x1[i] = x2;               /* now x2 */
    }
    ri_expect_near(x, x1, 6, 1e-15, "x2");
    ri_expect_near(v, v1, 6, 1e-12, "v2");
    ts_free(&ts);
}

Test(verlet, orders_conservative_and_damped)
{
    /* damped oscillators: positions order 1; undamped pair: order 2 */
    ri_expect_orders_osc_pair("verlet", 1e-3, 1, 1, 2, 1);
}

/* omega = 1, h = 0.01, 1000 periods: first order in h omega through the
 * one-sided velocity (1.01e-3 relative measured). */
Test(verlet, bounded_energy_no_drift)
{
    ri_expect_bounded_energy("verlet", 0.01, 1.5e-3);
}

/* No force: v_N = (1 - d)^N v0 exactly (to round-off). */
Test(verlet, vdamp_scales_velocity_per_step)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    memset(ts.k, 0, 3 * sizeof *ts.k);
    memset(ts.c, 0, 3 * sizeof *ts.c);
    double x[3] = {0.3, -1, 2}, v[3] = {1, -2, 0.5}, v0[3], d = 0.02;
    memcpy(v0, v, sizeof v0);
    cl_integrator_opts o = {.dt = 0.01, .vdamp = d};
    ri_run("verlet", &ts.sys, &o, 0.0, 0.5, x, v, NULL);
    for (int r = 0; r < 3; r++)
        cr_expect_float_eq(v[r], pow(1 - d, 50) * v0[r], 1e-12, "v[%d]", r);
    ts_free(&ts);
}

/* Undamped oscillator, vdamp = 0.01: the energy sampled once per period
 * falls every period and ends far below E0. */
Test(verlet, vdamp_dissipates)
{
    ts_sys ts;
    ri_unit_oscillator(&ts, 1.0);
    double x[3] = {1, 0, 0.5}, v[3] = {0, 1, -0.5}, h = 0.01;
    double E = ri_osc_energy(&ts, x, v), E0 = E;
    cl_integrator_opts o = {.dt = h, .vdamp = 0.01};
    const cl_integrator_type *it = ri_find("verlet");
    void *st;
    cl_error err;
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK);
    for (int p = 1; p <= 10; p++) {
        double t = (double)lround(p * 6.283185307179586 / h) * h;
        cr_assert_eq(it->advance(st, t, x, v, &err), CL_OK, "%s", err.msg);
        double En = ri_osc_energy(&ts, x, v);
        cr_expect_lt(En, E, "period %d: energy %g after %g", p, En, E);
        E = En;
    }
    it->free(st);
    /* drag d/h = 1 per unit time: energy ~ exp(-t), t = 62.8 */
    cr_expect_lt(E, 1e-20 * E0);
    ts_free(&ts);
}

Test(verlet, rejects_bad_vdamp)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 1), 0);
    double x[3] = {0}, v[3] = {0};
    const double bad[] = {-0.1, 1.0, 1.5, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cl_integrator_opts o = {.dt = 0.01, .vdamp = bad[i]};
        void *st = (void *)1;
        cl_error err;
        cr_expect_eq(ri_find("verlet")->create(&ts.sys, &o, 0.0, x, v, &st,
                                               &err),
                     CL_EINVAL, "vdamp = %g", bad[i]);
        cr_expect_null(st);
        cr_expect_not_null(strstr(err.msg, "vdamp"), "%s", err.msg);
    }
    ts_free(&ts);
}
