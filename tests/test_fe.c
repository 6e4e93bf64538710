/* fe (forward Euler): the update formula of one step, first order on
 * damped oscillators and on the coupled pair, and its energy growth on the
 * undamped oscillator, which is exactly (1 + h^2 w^2) per step.  (Orders on
 * spring2: test_orders_explicit.c; counting, dt and failures:
 * test_fixed_step.c.) */
#include <criterion/criterion.h>

#include "runint.h"

/* x1 = x0 + h v0, v1 = v0 + h M^-1 f(x0, v0) */
Test(fe, one_step_formula)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 2), 0);
    double x0[6], v0[6], x[6], v[6], f[6], x1[6], v1[6], h = 0.01;
    ri_steps("fe", &ts, h, 1, x0, v0, x, v);
    ts_force(&ts, 0.0, x0, v0, f);
    for (int i = 0; i < 6; i++) {
        x1[i] = x0[i] + h * v0[i];
        v1[i] = v0[i] + h * f[i] / ts.mass[i];
    }
    ri_expect_near(x, x1, 6, 1e-15, "x1");
    ri_expect_near(v, v1, 6, 1e-15, "v1");
    ts_free(&ts);
}

Test(fe, first_order_on_damped_and_coupled)
{
    ri_expect_orders_osc_pair("fe", 1e-3, 1, 1, 1, 1);
}

/* w = 2, h = 0.01: E_N = E0 (1 + h^2 w^2)^N, here N = 1000. */
Test(fe, energy_grows_by_exact_factor)
{
    ts_sys ts;
    ri_unit_oscillator(&ts, 4.0);
    double x[3] = {1, 0, 0.5}, v[3] = {0, 1, -0.5}, h = 0.01;
    double E0 = ri_osc_energy(&ts, x, v);
    cl_integrator_opts o = {.dt = h};
    ri_run("fe", &ts.sys, &o, 0.0, 1000 * h, x, v, NULL);
    double want = E0 * pow(1.0 + h * h * 4.0, 1000);
    cr_expect_float_eq(ri_osc_energy(&ts, x, v), want, 1e-11 * want,
                       "energy %.17g, expected %.17g",
                       ri_osc_energy(&ts, x, v), want);
    cr_expect_gt(want, 1.04 * E0);
    ts_free(&ts);
}
