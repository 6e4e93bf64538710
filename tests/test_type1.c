/* Verification of the Choi-Ko Type1 term (docs/model.md 3.2;
 * docs/architecture.md, "Checks every force term passes"): tension-only
 * springs s(d) = ks (d - L) for d >= L, 0 for d < L, on sequential pairs
 * (type1.compression = spring: ks (d - L) on both sides).
 *
 * Every check runs Type1 alone (type2 off, no damping, no gravity, no pins)
 * on full-particle states: the analytic df/dx, df/dv against central
 * differences at random stretched and half-slack states away from the kink
 * d = L, f = -dE/dx, Newton's third law, rigid-motion invariance, the law
 * itself on uniformly stretched grids, and exact zeros at rest and in
 * compression. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"

#define TYPE1_ONLY(...)                                                     \
    FD_MODEL("type2.enabled=false", "damping.kd=0", "gravity.g=0,0,0",     \
             "pins.at=", __VA_ARGS__)

/* Smallest |d/L - 1| over the Type1 pairs and the number of taut (d > L)
 * and slack pairs. */
static double type1_margin(const cl_model *m, const double *x, size_t *taut,
                           size_t *slack)
{
    cl_pairset set;
    cl_error err;
    cr_assert_eq(cl_pairs_type1(cl_model_cloth(m), &set, &err), CL_OK);
    double margin = INFINITY;
    *taut = *slack = 0;
    for (size_t k = 0; k < set.n; k++) {
        const cl_pair *p = &set.pair[k];
        double r = cl_dist(x + 3 * p->a, x + 3 * p->b) / p->rest - 1.0;
        margin = fmin(margin, fabs(r));
        if (r > 0)
            (*taut)++;
        else
            (*slack)++;
    }
    cl_pairs_free(&set);
    return margin;
}

/* A stretched state (every pair taut) and a half-slack one (axis pairs along
 * z compressed, the others taut). */
static void state_stretched(const cl_model *m, fd_rng *r, double *x)
{
    double A[9];
    fd_scale(1.06, 1.045, A);
    fd_deform(m, A, 0.01, 0.05, r, x);
}

static void state_mixed(const cl_model *m, fd_rng *r, double *x)
{
    double A[9];
    fd_scale(1.08, 0.96, A);
    fd_deform(m, A, 0.003, 0.03, r, x);
}

/* The state of trial k: stretched for even k, half-slack for odd k. */
static void state_alternating(const cl_model *m, fd_rng *r, int trial,
                              double *x)
{
    if (trial % 2)
        state_mixed(m, r, x);
    else
        state_stretched(m, r, x);
}

Test(type1, jacobian_fd_stretched)
{
    cl_model *m = TYPE1_ONLY("cloth.n=5", "type1.ks=173");
    size_t n = fd_n(m), taut, slack;
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_rng r = {11};
    double worst = 0.0;
    for (int trial = 0; trial < 3; trial++) {
        state_stretched(m, &r, x);
        fd_random_vec(&r, 0.3, v, n);
        double margin = type1_margin(m, x, &taut, &slack);
        cr_assert_gt(margin, 0.01, "state too close to the kink d = L");
        cr_assert_eq(slack, 0);
        double ex, ev;
        fd_check_jacobian(m, x, v, 1e-6 * 0.25, 1e-6, false,
                          "type1 stretched", &ex, &ev);
        cr_assert_lt(ex, 1e-8, "type1 df/dx vs FD: rel err %g", ex);
        /* Type1 does not depend on v: both must be exactly zero. */
        cr_assert_eq(ev, 0.0, "type1 df/dv should vanish, err %g", ev);
        worst = fmax(worst, ex);
    }
    fd_report("type1 worst df/dx (stretched)", worst);
    free(x);
    free(v);
    cl_model_free(m);
}

Test(type1, jacobian_fd_half_slack)
{
    cl_model *m = TYPE1_ONLY("cloth.nu=5", "cloth.nv=4", "cloth.su=1.2",
                             "cloth.sv=0.9");
    size_t n = fd_n(m), taut, slack;
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_rng r = {12};
    for (int trial = 0; trial < 3; trial++) {
        state_mixed(m, &r, x);
        double margin = type1_margin(m, x, &taut, &slack);
        cr_assert_gt(margin, 0.005, "state too close to the kink d = L");
        cr_assert(taut > 0 && slack > 0, "want both branches (%zu, %zu)",
                  taut, slack);
        double ex, ev;
        fd_check_jacobian(m, x, v, 1e-6 * 0.3, 1e-6, false,
                          "type1 half-slack", &ex, &ev);
        cr_assert_lt(ex, 1e-8, "type1 df/dx vs FD: rel err %g", ex);
        cr_assert_eq(ev, 0.0);
        double st = fd_check_structure(m, x, v);
        cr_assert_lt(st, 1e-13, "df/dx not symmetric / row sums %g", st);
    }
    free(x);
    free(v);
    cl_model_free(m);
}

Test(type1, force_is_minus_energy_gradient)
{
    cl_model *m = TYPE1_ONLY("cloth.n=5");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_rng r = {13};
    for (int trial = 0; trial < 4; trial++) {
        state_alternating(m, &r, trial, x);
        double e = fd_check_energy(m, x, v, 1e-6 * 0.25, "type1");
        cr_assert_lt(e, 1e-8, "type1 f vs -dE/dx: rel err %g", e);
    }
    free(x);
    free(v);
    cl_model_free(m);
}

Test(type1, newton_third_law_and_no_torque)
{
    cl_model *m = TYPE1_ONLY("cloth.n=6");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    fd_rng r = {14};
    for (int trial = 0; trial < 4; trial++) {
        state_alternating(m, &r, trial, x);
        fd_eval(m, x, v, f);
        double torque, net = fd_net_force(x, f, n / 3, &torque);
        cr_assert_lt(net, 1e-14, "net force %g", net);
        /* Central pair forces exert no net torque either. */
        cr_assert_lt(torque, 1e-14, "net torque %g", torque);
    }
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

Test(type1, rigid_motion_invariance)
{
    cl_model *m = TYPE1_ONLY("cloth.n=4");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_rng r = {15};
    for (int trial = 0; trial < 4; trial++) {
        double R[9], c[3], w[3];
        fd_rotation(&r, R);
        fd_random_vec(&r, 3.0, c, 3);
        fd_random_vec(&r, 1.0, w, 3);
        state_alternating(m, &r, trial, x);
        fd_random_vec(&r, 0.5, v, n);
        double e = fd_check_rigid(m, x, v, R, c, w, "type1");
        cr_assert_lt(e, 1e-11, "type1 rigid-motion deviation %g", e);
    }
    free(x);
    free(v);
    cl_model_free(m);
}

/* Uniform stretch by lambda: every pair at d = lambda L.  Energy
 * 0.5 ks (lambda-1)^2 sum L^2; corner (0,0) pulled by its three neighbours,
 * f = ks (lambda-1) (2 hu, 0, 2 hv); every interior particle balanced. */
Test(type1, law_on_uniform_stretch)
{
    const int nu = 4, nv = 5;
    const double su = 1.5, sv = 2.0, ks = 321.0, lam = 1.05;
    cl_model *m = TYPE1_ONLY("cloth.nu=4", "cloth.nv=5", "cloth.su=1.5",
                             "cloth.sv=2.0", "type1.ks=321");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), A[9];
    fd_rng r = {16};
    fd_scale(lam, lam, A);
    fd_deform(m, A, 0.0, 0.0, &r, x);
    cl_energy e = fd_eval(m, x, v, f);
    double hu = su / (nu - 1), hv = sv / (nv - 1), dg = hypot(hu, hv);
    double sumL2 = (double)((nu - 1) * nv) * hu * hu +
                   (double)(nu * (nv - 1)) * hv * hv +
                   2.0 * (double)((nu - 1) * (nv - 1)) * dg * dg;
    double want = 0.5 * ks * (lam - 1) * (lam - 1) * sumL2;
    double got = fd_term_energy(&e, "type1");
    cr_assert_float_eq(got, want, 1e-12 * want, "energy %.17g vs %.17g", got,
                       want);
    /* Corner (0,0): neighbours (1,0) along x, (0,1) along z, (1,1). */
    double s = ks * (lam - 1);
    double fc[3] = {s * (hu + hu), 0.0, s * (hv + hv)};
    for (int i = 0; i < 3; i++)
        cr_assert_float_eq(f[i], fc[i], 1e-12 * s * dg, "corner f[%d] %g %g",
                           i, f[i], fc[i]);
    /* Interior particles are balanced. */
    for (int i = 1; i < nu - 1; i++)
        for (int j = 1; j < nv - 1; j++)
            for (int k = 0; k < 3; k++)
                cr_assert_lt(fabs(f[3 * (i * nv + j) + k]), 1e-12 * s * dg);
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

/* Tension only: any compressed state (rotated too) gives exactly zero force,
 * energy and Jacobian. */
Test(type1, slack_under_compression_is_exactly_zero)
{
    cl_model *m = TYPE1_ONLY("cloth.n=5");
    size_t n = fd_n(m), taut, slack;
    double *x = fd_vec(n), *y = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n),
           *Jx = fd_vec(n * n), *Jv = fd_vec(n * n), A[9], R[9];
    fd_rng r = {17};
    fd_scale(0.95, 0.93, A);
    fd_deform(m, A, 0.005, 0.0, &r, x);
    cr_assert_gt(type1_margin(m, x, &taut, &slack), 0.01);
    cr_assert_eq(taut, 0);
    fd_rotation(&r, R);
    fd_apply(R, (double[3]){1, 2, 3}, x, y, n / 3);
    cl_energy e = fd_eval(m, y, v, f);
    cr_assert_eq(fd_maxabs(f, n), 0.0);
    cr_assert_eq(fd_term_energy(&e, "type1"), 0.0);
    fd_jacobian(m, y, v, Jx, Jv);
    cr_assert_eq(fd_maxabs(Jx, n * n), 0.0);
    cr_assert_eq(fd_maxabs(Jv, n * n), 0.0);
    free(x);
    free(y);
    free(v);
    free(f);
    free(Jx);
    free(Jv);
    cl_model_free(m);
}

/* At rest every pair sits exactly on d = L (rest lengths computed with the
 * same expression): force and energy exactly zero, for awkward spacings. */
Test(type1, rest_state_exactly_zero)
{
    fd_expect_rest_exactly_zero("type1", "type2.enabled=false");
}

/* s >= 0 everywhere: jacobian.transverse = clamp changes nothing. */
Test(type1, clamp_keeps_tension_transverse_term)
{
    cl_model *full = TYPE1_ONLY("cloth.n=4");
    cl_model *clamp = TYPE1_ONLY("cloth.n=4", "jacobian.transverse=clamp");
    size_t n = fd_n(full);
    double *x = fd_vec(n), *v = fd_vec(n), *J1 = fd_vec(n * n),
           *J2 = fd_vec(n * n), *W = fd_vec(n * n);
    fd_rng r = {18};
    state_mixed(full, &r, x);
    fd_jacobian(full, x, v, J1, W);
    fd_jacobian(clamp, x, v, J2, W);
    cr_assert_gt(fd_maxabs(J1, n * n), 0.0);
    cr_assert_eq(memcmp(J1, J2, n * n * sizeof *J1), 0,
                 "clamp altered a Type1 Jacobian (s >= 0 everywhere)");
    free(x);
    free(v);
    free(J1);
    free(J2);
    free(W);
    cl_model_free(full);
    cl_model_free(clamp);
}

Test(type1, enabled_switch)
{
    cl_model *on = FD_MODEL("cloth.n=3", "pins.at=");
    cl_model *off = FD_MODEL("cloth.n=3", "pins.at=", "type1.enabled=false");
    cr_assert(fd_has_term(on, "type1"));
    cr_assert(!fd_has_term(off, "type1"));
    cl_model_free(on);
    cl_model_free(off);
}

/* ---- compression = spring: a linear spring on both sides --------------- */

Test(type1, compression_spring_jacobian_and_energy)
{
    cl_model *m = TYPE1_ONLY("cloth.nu=5", "cloth.nv=4", "cloth.su=1.2",
                             "cloth.sv=0.9", "type1.compression=spring");
    size_t n = fd_n(m), taut, slack;
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_rng r = {19};
    for (int trial = 0; trial < 2; trial++) {
        state_mixed(m, &r, x);
        cr_assert(type1_margin(m, x, &taut, &slack) > 0.005 && taut > 0 &&
                  slack > 0);
        double ex, ev;
        fd_check_jacobian(m, x, v, 1e-6 * 0.3, 1e-6, false,
                          "type1 compression=spring", &ex, &ev);
        cr_assert_lt(ex, 1e-8, "df/dx vs FD: rel err %g", ex);
        cr_assert_eq(ev, 0.0);
        double ee = fd_check_energy(m, x, v, 1e-6 * 0.3,
                                    "type1 compression=spring");
        cr_assert_lt(ee, 1e-8, "f vs -dE/dx: rel err %g", ee);
    }
    /* Uniform compression: E = 0.5 ks (lambda - 1)^2 sum L^2 (3x3 grid of
     * side 1: 12 axis pairs of 0.5, 8 diagonals of 0.5 sqrt 2). */
    cl_model_free(m);
    m = TYPE1_ONLY("cloth.n=3", "type1.compression=spring", "type1.ks=10");
    n = fd_n(m);
    double A[9], *f = fd_vec(n);
    fd_scale(0.9, 0.9, A);
    fd_deform(m, A, 0.0, 0.0, &r, x);
    cl_energy e = fd_eval(m, x, v, f);
    double want = 0.5 * 10 * 0.01 * (12 * 0.25 + 8 * 0.5);
    cr_assert(fabs(fd_term_energy(&e, "type1") - want) <= 1e-13 * want);
    /* corner pushed outwards: f = ks (lambda-1) (2 h, 0, 2 h), h = 0.5 */
    cr_assert(fabs(f[0] - 10 * -0.1 * 1.0) <= 1e-13);
    cr_assert(fabs(f[2] - 10 * -0.1 * 1.0) <= 1e-13);
    free(f);
    free(x);
    free(v);
    cl_model_free(m);
}

/* With compression = spring s < 0 on compressed pairs: clamp must drop
 * exactly (s/d)(I - u u^T), s = ks (d - L), there and nowhere else. */
Test(type1, clamp_drops_compressive_transverse_term)
{
    const double ks = 200.0;
    cl_model *full = TYPE1_ONLY("cloth.n=3", "type1.compression=spring");
    cl_model *clamp = TYPE1_ONLY("cloth.n=3", "type1.compression=spring",
                                 "jacobian.transverse=clamp");
    size_t n = fd_n(full);
    double *x = fd_vec(n), *v = fd_vec(n), *J1 = fd_vec(n * n),
           *J2 = fd_vec(n * n), *W = fd_vec(n * n);
    fd_rng r = {20};
    size_t taut, slack;
    state_mixed(full, &r, x);
    cr_assert(type1_margin(full, x, &taut, &slack) > 0.005 && taut > 0 &&
              slack > 0);
    fd_jacobian(full, x, v, J1, W);
    fd_jacobian(clamp, x, v, J2, W);
    /* Expected clamp = full + T on the aa, bb blocks, - T on ab, ba. */
    cl_pairset set;
    cl_error err;
    cr_assert_eq(cl_pairs_type1(cl_model_cloth(full), &set, &err), CL_OK);
    double dropped = 0.0;
    for (size_t k = 0; k < set.n; k++) {
        const cl_pair *p = &set.pair[k];
        double d = cl_dist(x + 3 * p->a, x + 3 * p->b), s = ks * (d - p->rest);
        if (s >= 0)
            continue;
        double u[3];
        for (int i = 0; i < 3; i++)
            u[i] = (x[3 * p->b + i] - x[3 * p->a + i]) / d;
        const int q[2] = {p->a, p->b};
        for (int bi = 0; bi < 2; bi++)
            for (int bj = 0; bj < 2; bj++)
                for (int i = 0; i < 3; i++)
                    for (int j = 0; j < 3; j++) {
                        double T = (s / d) * ((i == j) - u[i] * u[j]);
                        J1[(3 * (size_t)q[bi] + i) * n + 3 * (size_t)q[bj] +
                           j] += bi == bj ? T : -T;
                        dropped = fmax(dropped, fabs(T));
                    }
    }
    cl_pairs_free(&set);
    cr_assert_gt(dropped, 1e-3);
    double dev = fd_relerr(J2, J1, n * n);
    cr_assert_lt(dev, 1e-14, "clamp vs full - T: rel dev %g", dev);
    free(x);
    free(v);
    free(J1);
    free(J2);
    free(W);
    cl_model_free(full);
    cl_model_free(clamp);
}
