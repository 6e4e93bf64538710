/* rk4: fourth order on damped oscillators and on the coupled pair, four
 * force evaluations per step, and its slight dissipation on the undamped
 * oscillator: the energy shrinks exactly by |R(i h w)|^2 =
 * 1 - (h w)^6/72 + (h w)^8/576 per step. */
#include <criterion/criterion.h>

#include "runint.h"

Test(rk4, fourth_order_on_damped_and_coupled)
{
    ri_expect_orders_osc_pair("rk4", 1e-2, 4, 4, 4, 4);
}

/* w = 2, h = 0.1 (h w = 0.2), 1000 steps. */
Test(rk4, energy_decays_by_exact_factor)
{
    ts_sys ts;
    ri_unit_oscillator(&ts, 4.0);
    double x[3] = {1, 0, 0.5}, v[3] = {0, 1, -0.5}, h = 0.1, z = 0.2;
    double E0 = ri_osc_energy(&ts, x, v);
    cl_integrator_opts o = {.dt = h};
    cl_stats s;
    ri_run("rk4", &ts.sys, &o, 0.0, 1000 * h, x, v, &s);
    cr_expect_eq(s.rhs_evals, 4000);
    double r2 = 1 - pow(z, 6) / 72 + pow(z, 8) / 576;
    double want = E0 * pow(r2, 1000);
    cr_expect_float_eq(ri_osc_energy(&ts, x, v), want, 1e-11 * want,
                       "energy %.17g, expected %.17g",
                       ri_osc_energy(&ts, x, v), want);
    cr_expect_lt(want, (1 - 5e-4) * E0);
    ts_free(&ts);
}
