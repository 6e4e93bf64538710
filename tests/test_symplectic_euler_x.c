/* symplectic-euler-x (x first, Zischg, Chea and Aigner): the update formula of
 * one step (force at the new positions and the old velocities), first order in
 * x and v on damped oscillators, bounded energy error without drift, and the
 * adjoint relation with symplectic-euler: for conservative forces half a step
 * of symplectic-euler (v first) followed by half a step of symplectic-euler-x
 * is one step of velocity Verlet. */
#include <criterion/criterion.h>

#include "runint.h"

/* x1 = x0 + h v0, v1 = v0 + h M^-1 f(x1, v0) */
Test(symplectic_euler_x, one_step_formula)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    double x0[6], v0[6], x[6], v[6], x1[6], v1[6], h = 0.01;
    ri_steps("symplectic-euler-x", &ts, h, 1, x0, v0, x, v);
    for (int i = 0; i < 6; i++)
        x1[i] = x0[i] + h * v0[i];
    ts_force(&ts, h, x1, v0, v1); /* f(x1, v0) */
    for (int i = 0; i < 6; i++)
        v1[i] = v0[i] + h * v1[i] / ts.mass[i];
    ri_expect_near(x, x1, 6, 1e-15, "x1");
    ri_expect_near(v, v1, 6, 1e-15, "v1");
    ts_free(&ts);
}

/* In general (a0 != 0) both x and v are first order; on spring2, which
 * starts with a0 = 0, the positions happen to be second order. */
Test(symplectic_euler_x, first_order_on_damped_and_coupled)
{
    ri_expect_orders_osc_pair("symplectic-euler-x", 1e-3, 1, 1, 1, 1);
}

/* omega = 1, h = 0.01, 1000 periods: first order in h omega (1.95e-3
 * relative measured). */
Test(symplectic_euler_x, bounded_energy_no_drift)
{
    ri_expect_bounded_energy("symplectic-euler-x", 0.01, 3e-3);
}

Test(symplectic_euler_x, half_steps_compose_to_velocity_verlet)
{
    ts_sys ts;
    cr_assert_eq(ts_pair(&ts, 2.0, 3.0, 1.5), 0);
    double x0[6], v0[6], xa[6], va[6], xb[6], vb[6], h = 0.02;
    ri_start(&ts, x0, v0, xa, va);
    ri_start(&ts, x0, v0, xb, vb);
    cl_integrator_opts half = {.dt = h / 2}, full = {.dt = h};
    ri_run("symplectic-euler", &ts.sys, &half, 0.0, h / 2, xa, va, NULL);
    ri_run("symplectic-euler-x", &ts.sys, &half, h / 2, h, xa, va, NULL);
    ri_run("velocity-verlet", &ts.sys, &full, 0.0, h, xb, vb, NULL);
    cr_expect_lt(ts_maxdiff(xa, xb, 6), 1e-15);
    cr_expect_lt(ts_maxdiff(va, vb, 6), 1e-15);
    ts_free(&ts);
}
