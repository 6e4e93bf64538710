/* kinsol-galpha (generalized-alpha, Chung and Hulbert 1993): second order
 * on spring2 at rho_inf = 0, 0.5 and 1; at rho_inf = 1 the same steps as
 * kinsol-midpoint, energy conserved to the Newton tolerance on the linear
 * spring and, on hang-smooth (nonlinear springs), an energy error that is
 * the midpoint rule's bounded O(h^2) oscillation, not a drift; at
 * rho_inf = 0 the amplitude of a stiff spring (w h = 1e4) annihilated
 * within a few steps, as the spectral radius formula says; a rho_inf
 * outside [0, 1] refused. */
#include <criterion/criterion.h>

#include "integrators/region.h"
#include "kinsol_test.h"
#include "problem.h"

/* Energy of spring2 at (x, v). */
static double kg_energy(const s2_problem *p, double t, const double *x,
                        const double *v)
{
    cl_energy e;
    cr_assert_eq(p->sys->energy(p->sys->data, t, x, v, &e), CL_OK);
    return e.total;
}

Test(kinsol_galpha, second_order_on_spring2)
{
    kt_check_order("kinsol-galpha", 2.0, 1e-2); /* rho_inf = 0 */
    for (int k = 1; k <= 2; k++) {
        s2_problem p;
        st_load(&p, NULL);
        double h[4], e[4];
        for (int j = 0; j < 4; j++) {
            cl_integrator_opts o = {.dt = 1e-2 / (1 << j),
                                    .rho_inf = 0.5 * k,
                                    .newton_tol = 1e-13};
            double x[3], v[3];
            cl_stats s;
            kt_run("kinsol-galpha", &p, &o, 1.0, x, v, &s);
            s2_error er = s2_state_error(x, v, 1.0);
            h[j] = o.dt;
            e[j] = er.ex;
        }
        double q = s2_slope(h, e, 4);
        cr_log_info("kinsol-galpha rho_inf %.1f: order %.3f", 0.5 * k, q);
        cr_assert(fabs(q - 2.0) < 0.2, "rho_inf %g: order %g", 0.5 * k, q);
        s2_free(&p);
    }
}

/* rho_inf = 1 is the implicit midpoint rule (kinsol_galpha.c): equal
 * states, here on the nonlinear, damped spring2. */
Test(kinsol_galpha, rho_one_is_midpoint)
{
    const char *const sets[] = {"init.velocity=1,0.8,0", "damping.kd=0.3",
                                NULL};
    s2_problem p;
    st_load(&p, sets);
    cl_integrator_opts o = {.dt = 0.05, .rho_inf = 1.0};
    double xa[3], va[3], xb[3], vb[3];
    cl_stats sa, sb;
    kt_run("kinsol-galpha", &p, &o, 1.0, xa, va, &sa);
    kt_run("kinsol-midpoint", &p, &o, 1.0, xb, vb, &sb);
    double d = fmax(kt_diff3(xa, xb), kt_diff3(va, vb));
    cr_log_info("kinsol-galpha rho_inf 1 vs kinsol-midpoint: %.3e", d);
    cr_assert_lt(d, 1e-14);
    cr_assert_eq(sa.nonlin_iters, sb.nonlin_iters);
    s2_free(&p);
}

Test(kinsol_galpha, rho_one_conserves_energy_of_linear_spring)
{
    s2_problem p;
    st_load(&p, NULL);
    const cl_integrator_type *it = cl_integrator_find("kinsol-galpha");
    cl_integrator_opts o = {.dt = 0.05, .rho_inf = 1.0, .newton_tol = 1e-13};
    void *st = kt_create("kinsol-galpha", &p, &o);
    double x[3], v[3], e0 = kg_energy(&p, 0, p.x0, p.v0), worst = 0;
    cl_error err = {0};
    for (int k = 1; k <= 1000; k++) {
        cr_assert_eq(it->advance(st, 0.05 * k, x, v, &err), CL_OK, "%s",
                     err.msg);
        worst = fmax(worst, fabs(kg_energy(&p, 0.05 * k, x, v) - e0) / e0);
    }
    cr_log_info("kinsol-galpha rho_inf 1: energy error over 1000 steps "
                "(w h = 0.5): %.3e", worst);
    cr_assert_lt(worst, 1e-12);
    it->free(st);
    s2_free(&p);
}

/* The largest |E(t) - E(0)| of hang-smooth (n = 6) over 1000 steps of
 * dt = 1e-3 (and of 5e-4, 2000 steps) at rho_inf = 1, relative to the
 * largest kinetic energy; the error at the end beside it. */
static void kg_hang_energy(double dt, double *worst, double *end)
{
    pr_problem p;
    pr_load(&p, "problems/hang-smooth.ini", "cloth.n=6", NULL);
    const cl_system *sys = cl_model_system(p.m);
    const cl_integrator_type *it = cl_integrator_find("kinsol-galpha");
    double *x = malloc(sys->n * sizeof *x), *v = malloc(sys->n * sizeof *v);
    cr_assert(x && v);
    cl_model_initial_state(p.m, x, v);
    cl_integrator_opts o = {.dt = dt, .rho_inf = 1.0};
    void *st = NULL;
    cl_error err = {0};
    cl_energy e0, e;
    cr_assert_eq(it->create(sys, &o, 0.0, x, v, &st, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(sys->energy(sys->data, 0, x, v, &e0), CL_OK);
    double de = 0, kmax = 0;
    for (int k = 1; k <= 100; k++) {
        cr_assert_eq(it->advance(st, 0.01 * k, x, v, &err), CL_OK, "%s",
                     err.msg);
        cr_assert_eq(sys->energy(sys->data, 0.01 * k, x, v, &e), CL_OK);
        de = fmax(de, fabs(e.total - e0.total));
        kmax = fmax(kmax, e.kinetic);
    }
    *worst = de / kmax;
    *end = fabs(e.total - e0.total) / kmax;
    it->free(st);
    free(x);
    free(v);
    pr_free(&p);
}

Test(kinsol_galpha, rho_one_energy_on_hang_smooth_is_bounded)
{
    double w1, end1, w2, end2;
    kg_hang_energy(1e-3, &w1, &end1);
    kg_hang_energy(5e-4, &w2, &end2);
    cr_log_info("kinsol-galpha rho_inf 1, hang-smooth n = 6, T = 1 s: "
                "largest energy error / largest kinetic energy %.3e at dt "
                "1e-3 (end %.3e), %.3e at 5e-4 (end %.3e), ratio %.3f", w1,
                end1, w2, end2, w1 / w2);
    cr_assert_lt(w1, 5e-5);
    cr_assert(fabs(w1 / w2 - 4.0) < 0.4, "ratio %g", w1 / w2);
    cr_assert_leq(end1, w1);
}

/* rho_inf = 0 on spring2 made stiff (ks = 1e8: w = 1e4 rad/s) with h = 1
 * s, w h = 1e4: the amplitude (the square root of the energy ratio) falls
 * to 3e-8 of its start in three steps, about 3e-3 per step; the spectral
 * radius there is 2.2e-3 (three roots near 0, each about (w h)^(-2/3)),
 * and it tends to rho_inf as w h grows: 0 for rho_inf = 0, 0.5 for 0.5, 1
 * for 1 (the eigenvalues of nearly coincident roots are computed to about
 * 1e-8). */
Test(kinsol_galpha, rho_zero_annihilates_high_frequencies)
{
    const char *const sets[] = {"type1.ks=1e8", NULL};
    s2_problem p;
    st_load(&p, sets);
    const cl_integrator_type *it = cl_integrator_find("kinsol-galpha");
    cl_integrator_opts o = {.dt = 1.0, .rho_inf = 0.0, .newton_tol = 1e-13};
    void *st = kt_create("kinsol-galpha", &p, &o);
    double x[3], v[3], e0 = kg_energy(&p, 0, p.x0, p.v0), e = e0;
    cl_error err = {0};
    for (int k = 1; k <= 3; k++) {
        cr_assert_eq(it->advance(st, k, x, v, &err), CL_OK, "%s", err.msg);
        e = kg_energy(&p, k, x, v);
        cr_log_info("kinsol-galpha rho_inf 0, w h = 1e4: step %d amplitude "
                    "ratio %.3e", k, sqrt(e / e0));
    }
    /* 0.5, 1e-4, 3e-8: measured */
    cr_assert_float_eq(sqrt(e / e0), 3e-8, 3e-9, "%g", sqrt(e / e0));
    cr_assert_lt(cbrt(sqrt(e / e0)), 5e-3);
    it->free(st);
    s2_free(&p);
    double r4 = cl_region_galpha.amplification(1e4, 0.0);
    cr_log_info("spectral radius at w h = 1e4: rho_inf 0 %.3e, 0.5 %.6f, 1 "
                "%.15f", r4, cl_region_galpha.amplification(1e4, 0.5),
                cl_region_galpha.amplification(1e4, 1.0));
    cr_assert(r4 > 1e-3 && r4 < 5e-3, "%g", r4);
    cr_assert_lt(cl_region_galpha.amplification(1e8, 0.0), 1e-4);
    cr_assert_float_eq(cl_region_galpha.amplification(1e8, 0.5), 0.5, 1e-5);
    cr_assert_float_eq(cl_region_galpha.amplification(1e4, 1.0), 1.0, 1e-7);
    cr_assert_float_eq(cl_region_galpha.amplification(1e-6, 0.0), 1.0, 1e-9);
}

Test(kinsol_galpha, rho_outside_unit_interval_refused)
{
    s2_problem p;
    st_load(&p, NULL);
    const cl_integrator_type *it = cl_integrator_find("kinsol-galpha");
    const double bad[] = {-0.1, 1.5, NAN};
    for (int k = 0; k < 3; k++) {
        cl_integrator_opts o = {.dt = 0.01, .rho_inf = bad[k]};
        void *st = NULL;
        cl_error err = {0};
        cr_assert_eq(it->create(p.sys, &o, 0.0, p.x0, p.v0, &st, &err),
                     CL_EINVAL);
        cr_assert_null(st);
        cr_assert(strstr(err.msg, "rho_inf") && strstr(err.msg, "[0, 1]"),
                  "%s", err.msg);
    }
    s2_free(&p);
}
