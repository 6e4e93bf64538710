/* velocity-verlet: the kick-drift-kick formulas of one step, second order
 * in x and v also with damping (the velocity predictor v_k + h a_k handed
 * to velocity-dependent forces), one force evaluation per step plus one,
 * bounded energy error without drift, and time reversibility for
 * conservative forces (N steps, velocities negated, N steps: back to the
 * start to round-off). */
#include <criterion/criterion.h>

#include "runint.h"

/* With damping: v_half = v0 + h/2 a0, x1 = x0 + h v_half,
 * a1 = a(x1, v0 + h a0), v1 = v_half + h/2 a1. */
Test(velocity_verlet, one_step_formula)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    double x0[6], v0[6], x[6], v[6], f[6], vh[6], x1[6], vp[6], h = 0.01;
    ri_steps("velocity-verlet", &ts, h, 1, x0, v0, x, v);
    ts_force(&ts, 0.0, x0, v0, f);
    for (int i = 0; i < 6; i++) {
        double a0 = f[i] / ts.mass[i];
        vh[i] = v0[i] + 0.5 * h * a0;
        x1[i] = x0[i] + h * vh[i];
        vp[i] = v0[i] + h * a0;
    }
    ts_force(&ts, h, x1, vp, f);
    for (int i = 0; i < 6; i++)
        vp[i] = vh[i] + 0.5 * h * f[i] / ts.mass[i]; /* v1 */
    ri_expect_near(x, x1, 6, 1e-15, "x1");
    ri_expect_near(v, vp, 6, 1e-15, "v1");
    ts_free(&ts);
}

Test(velocity_verlet, second_order_with_damping)
{
    ri_expect_orders_osc_pair("velocity-verlet", 2e-3, 2, 2, 2, 2);
}

/* omega = 1, h = 0.05: the energy error is O((h w)^2) (6.3e-5 relative
 * measured) and does not drift over 1000 periods. */
Test(velocity_verlet, bounded_energy_no_drift)
{
    ri_expect_bounded_energy("velocity-verlet", 0.05, 1e-4);
}

Test(velocity_verlet, time_reversible)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 2.0, 3.0, 1.5), 0);
    double x0[6], v0[6], x[6], v[6], h = 0.01;
    ri_start(&ts, x0, v0, x, v);
    cl_integrator_opts o = {.dt = h};
    ri_run("velocity-verlet", &ts.sys, &o, 0.0, 500 * h, x, v, NULL);
    for (int i = 0; i < 6; i++)
        v[i] = -v[i];
    ri_run("velocity-verlet", &ts.sys, &o, 0.0, 500 * h, x, v, NULL);
    for (int i = 0; i < 6; i++)
        v[i] = -v[i];
    cr_expect_lt(ts_maxdiff(x, x0, 6), 1e-12);
    cr_expect_lt(ts_maxdiff(v, v0, 6), 1e-12);
    ts_free(&ts);
}
