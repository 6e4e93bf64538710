/* Verification of the Choi-Ko pair damping (Jiao, eq. 14; docs/model.md
 * 3.2; docs/architecture.md, "Checks every force term passes"):
 * f_a = -kd (v_a - v_b), f_b = -f_a on every Type1 and Type2 pair, with
 * where = always (default) or engaged (a Type1 pair only while d > L, a
 * Type2 pair only while d < L, as Jiao's own code).
 *
 * Damping is isolated by switching Type1 off and giving Type2 a zero law
 * (kb = cb = 0, tension = none): Type2 stays enabled so that its pairs are
 * damped, but exerts no force.  Expected forces are computed here from the
 * pair lists (cl_pairs_type1/2, whose counts test_pairs.c checks). */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"

#define DAMPING_ONLY(...)                                                   \
    FD_MODEL("type1.enabled=false", "type2.kb=0", "type2.cb=0",            \
             "type2.tension=none", "gravity.g=0,0,0", "pins.at=",          \
             __VA_ARGS__)

/* Expected damping force and power from the pair lists.  engaged: only
 * pairs engaged at x (Type1 d > L, Type2 d < L).  Returns the number of
 * damped pairs. */
static size_t expected(const cl_model *m, double kd, bool type2, bool engaged,
                       const double *x, const double *v, double *f,
                       double *power)
{
    const cl_cloth *c = cl_model_cloth(m);
    memset(f, 0, 3 * c->np * sizeof *f);
    *power = 0.0;
    size_t count = 0;
    for (int t = 0; t < (type2 ? 2 : 1); t++) {
        cl_pairset set;
        cl_error err;
        cr_assert_eq(t ? cl_pairs_type2(c, &set, &err)
                       : cl_pairs_type1(c, &set, &err),
                     CL_OK);
        for (size_t k = 0; k < set.n; k++) {
            const cl_pair *p = &set.pair[k];
            if (engaged) {
                double d = cl_dist(x + 3 * p->a, x + 3 * p->b);
                if (t ? !(d < p->rest) : !(d > p->rest))
                    continue;
            }
            count++;
            for (int i = 0; i < 3; i++) {
                double dv = v[3 * p->a + i] - v[3 * p->b + i];
                f[3 * p->a + i] -= kd * dv;
                f[3 * p->b + i] += kd * dv;
                *power -= kd * dv * dv;
            }
        }
        cl_pairs_free(&set);
    }
    return count;
}

Test(damping, force_and_power_match_formula)
{
    static const struct {
        const char *t2;
        bool type2;
    } cases[] = {{"type2.enabled=true", true}, {"type2.enabled=false", false}};
    for (size_t k = 0; k < 2; k++) {
        cl_model *m = DAMPING_ONLY("cloth.nu=5", "cloth.nv=6",
                                   "damping.kd=0.37", cases[k].t2);
        cr_assert(fd_has_term(m, "damping"));
        size_t n = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n),
               *g = fd_vec(n), power;
        fd_rng r = {51 + k};
        fd_deform(m, NULL, 0.1, 0.1, &r, x);
        fd_random_vec(&r, 1.0, v, n);
        cl_energy e = fd_eval(m, x, v, f);
        size_t cnt = expected(m, 0.37, cases[k].type2, false, x, v, g, &power);
        /* 5 x 6: Type1 axis 4*6 + 5*5, diagonals 2*4*5; Type2 axis
         * 3*6 + 5*4, diagonals 2*3*4. */
        cr_assert_eq(cnt, 4 * 6 + 5 * 5 + 2 * 4 * 5 +
                              (cases[k].type2 ? 3 * 6 + 5 * 4 + 2 * 3 * 4 : 0));
        double err = fd_relerr(f, g, n);
        cr_assert_lt(err, 1e-14, "damping force vs formula %g", err);
        cr_assert(fabs(e.power_diss - power) <= 1e-13 * fabs(power),
                  "power %.17g vs %.17g", e.power_diss, power);
        cr_assert_lt(e.power_diss, 0.0);
        /* Not a potential: no energy column, nothing added to it. */
        for (size_t t = 0; t < e.nterm; t++)
            cr_assert_str_neq(e.name[t], "damping");
        cr_assert_eq(e.potential, 0.0);
        free(x);
        free(v);
        free(f);
        free(g);
        cl_model_free(m);
    }
}

Test(damping, jacobian_fd)
{
    cl_model *m = DAMPING_ONLY("cloth.n=5", "damping.kd=0.02");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_rng r = {53};
    for (int trial = 0; trial < 2; trial++) {
        double A[9];
        fd_scale(1.03, 0.96, A);
        fd_deform(m, A, 0.05, 0.1, &r, x);
        fd_random_vec(&r, 2.0, v, n);
        double ex, ev;
        fd_check_jacobian(m, x, v, 1e-6, 1e-6, false, "damping always", &ex,
                          &ev);
        cr_assert_lt(ev, 1e-9, "damping df/dv vs FD: rel err %g", ev);
        /* No position dependence: both exactly zero. */
        cr_assert_eq(ex, 0.0, "damping df/dx should vanish, err %g", ex);
    }
    free(x);
    free(v);
    cl_model_free(m);
}

/* where = engaged: x stretched 6%, z compressed 4% (diagonals ~1.1%
 * stretched): Type1 axis-x and diagonal pairs engaged, axis-z not; Type2
 * axis-z pairs engaged, the others not. */
Test(damping, engaged_pairs_only)
{
    cl_model *m = DAMPING_ONLY("cloth.n=5", "damping.kd=0.5",
                               "damping.where=engaged");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), *g = fd_vec(n),
           A[9], power;
    fd_rng r = {54};
    fd_scale(1.06, 0.96, A);
    fd_deform(m, A, 0.002, 0.02, &r, x);
    fd_random_vec(&r, 1.0, v, n);
    cl_energy e = fd_eval(m, x, v, f);
    size_t cnt = expected(m, 0.5, true, true, x, v, g, &power);
    /* Type1: 20 axis-x + 32 diagonals; Type2: 5*3 axis-z pairs. */
    cr_assert_eq(cnt, 20 + 32 + 15, "engaged pairs: %zu", cnt);
    double err = fd_relerr(f, g, n);
    cr_assert_lt(err, 1e-14, "engaged damping force vs formula %g", err);
    cr_assert(fabs(e.power_diss - power) <= 1e-13 * fabs(power));
    double ex, ev;
    fd_check_jacobian(m, x, v, 1e-7, 1e-6, false, "damping engaged", &ex,
                      &ev);
    cr_assert_lt(ev, 1e-9, "engaged df/dv vs FD: rel err %g", ev);
    cr_assert_eq(ex, 0.0);
    free(x);
    free(v);
    free(f);
    free(g);
    cl_model_free(m);
}

Test(damping, newton_third_law)
{
    static const char *const where[] = {"damping.where=always",
                                        "damping.where=engaged"};
    for (size_t k = 0; k < 2; k++) {
        cl_model *m = DAMPING_ONLY("cloth.n=6", "damping.kd=1.5", where[k]);
        size_t n = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), A[9];
        fd_rng r = {55 + k};
        fd_scale(1.03, 0.97, A);
        fd_deform(m, A, 0.01, 0.05, &r, x);
        fd_random_vec(&r, 1.0, v, n);
        fd_eval(m, x, v, f);
        double net = fd_net_force(x, f, n / 3, NULL);
        cr_assert_lt(net, 1e-14, "net damping force %g", net);
        free(x);
        free(v);
        free(f);
        cl_model_free(m);
    }
}

/* f(R x + c, R v + w) = R f(x, v); a uniform velocity is not damped at all;
 * a rigid rotation is (isotropic pair damping acts on all relative
 * velocity, docs/model.md 3.2; Jiao, eq. 14). */
Test(damping, rigid_motion)
{
    cl_model *m = DAMPING_ONLY("cloth.n=4", "damping.kd=0.8");
    size_t n = fd_n(m), np = n / 3;
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), *g = fd_vec(n),
           R[9], c[3], w[3], power;
    fd_rng r = {57};
    for (int trial = 0; trial < 3; trial++) {
        fd_deform(m, NULL, 0.05, 0.05, &r, x);
        fd_random_vec(&r, 1.0, v, n);
        fd_rotation(&r, R);
        fd_random_vec(&r, 2.0, c, 3);
        fd_random_vec(&r, 2.0, w, 3);
        double e = fd_check_rigid(m, x, v, R, c, w, "damping");
        cr_assert_lt(e, 1e-12, "damping rigid-motion deviation %g", e);
    }
    /* Uniform velocity: exactly no force, no power. */
    for (size_t p = 0; p < np; p++)
        memcpy(v + 3 * p, w, sizeof w);
    cl_energy e = fd_eval(m, x, v, f);
    cr_assert_eq(fd_maxabs(f, n), 0.0);
    cr_assert_eq(e.power_diss, 0.0);
    /* Rigid rotation v = omega x x: damped, as the formula says. */
    double om[3] = {0.3, -1.1, 0.7};
    for (size_t p = 0; p < np; p++) {
        const double *xp = x + 3 * p;
        v[3 * p] = om[1] * xp[2] - om[2] * xp[1];
        v[3 * p + 1] = om[2] * xp[0] - om[0] * xp[2];
        v[3 * p + 2] = om[0] * xp[1] - om[1] * xp[0];
    }
    fd_eval(m, x, v, f);
    expected(m, 0.8, true, false, x, v, g, &power);
    cr_assert_gt(fd_maxabs(g, n), 0.0);
    cr_assert_lt(fd_relerr(f, g, n), 1e-14);
    free(x);
    free(v);
    free(f);
    free(g);
    cl_model_free(m);
}

Test(damping, kd_zero_switches_it_off)
{
    cl_model *m = DAMPING_ONLY("cloth.n=3", "damping.kd=0");
    cr_assert(!fd_has_term(m, "damping"));
    cl_model_free(m);
    m = DAMPING_ONLY("cloth.n=3", "damping.kd=1e-4");
    cr_assert(fd_has_term(m, "damping"));
    cl_model_free(m);
}

/* Damping never adds energy; its Jacobian -df/dv is positive semidefinite
 * (v^T df/dv v = power <= 0 for any v). */
Test(damping, dissipative)
{
    cl_model *m = DAMPING_ONLY("cloth.n=4", "damping.kd=2");
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n),
           *Jx = fd_vec(n * n), *Jv = fd_vec(n * n);
    fd_rng r = {58};
    fd_deform(m, NULL, 0.05, 0.05, &r, x);
    fd_jacobian(m, x, v, Jx, Jv);
    for (int trial = 0; trial < 20; trial++) {
        fd_random_vec(&r, 1.0, v, n);
        cl_energy e = fd_eval(m, x, v, f);
        double q = 0.0;
        for (size_t i = 0; i < n; i++)
            for (size_t j = 0; j < n; j++)
                q += v[i] * Jv[i * n + j] * v[j];
        cr_assert_leq(e.power_diss, 0.0);
        cr_assert(fabs(q - e.power_diss) <= 1e-12 * fabs(q), "%g vs %g", q,
                  e.power_diss);
    }
    free(x);
    free(v);
    free(f);
    free(Jx);
    free(Jv);
    cl_model_free(m);
}
