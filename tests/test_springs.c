/* Verification of the mass-spring network and the springs term
 * (forces/springs.h; Zischg, Chea and Aigner; the Verlet-and-PBD report;
 * docs/model.md 2, 3.1, 3.4; docs/architecture.md, "Checks every force
 * term passes").
 *
 * Topology, on n x n grids for n = 3..20 (and rectangles, chains):
 *   structural 2 n (n-1), shear 2 (n-1)^2, bend 2 n (n-2),
 *   default (all three) 6 n^2 - 10 n + 2,
 *   level l alone 2 (n-l)(2n-l), levels 1..k
 *   4 n^2 k - 3 n k (k+1) + k (k+1)(2k+1)/3 (k < n; nothing beyond);
 * every pair valid, listed once, equal to a brute-force enumeration; the
 * options consistent (levels = 1 is structural + shear, levels = 2 adds bend
 * and the +-2 diagonals).  Stiffness: bend = structural / 8 by default (Zischg,
 * Chea and Aigner), shear = structural, levels as level_stiffness says.
 * Forces: Jacobian vs central differences, f = -dE/dx, symmetric Hessian,
 * Newton's third law, rigid-motion invariance, the law on a uniform
 * stretch, zero at rest. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"
#include "springcheck.h"


/* ---- topology --------------------------------------------------------- */

typedef struct {
    bool structural, shear, bend;
    int levels; /* > 0: levels 1..levels instead of the named sets */
} spring_sets;

/* Whether grid offset (di, dj) is a spring of `s`. */
static bool in_sets(const spring_sets *s, int di, int dj)
{
    di = abs(di);
    dj = abs(dj);
    if (s->levels) {
        int l = di > dj ? di : dj;
        return l >= 1 && l <= s->levels && (di == 0 || dj == 0 || di == dj);
    }
    return (s->structural && di + dj == 1) ||
           (s->shear && di == 1 && dj == 1) ||
           (s->bend && ((di == 2 && dj == 0) || (di == 0 && dj == 2)));
}

static cl_cloth grid(int nu, int nv, double su, double sv)
{
    cl_cloth c;
    cl_error err = {0};
    cr_assert_eq(cl_cloth_grid(nu, nv, su, sv, 1e-3, &c, &err), CL_OK, "%s",
                 err.msg);
    return c;
}

/* Grid offset of pair k. */
static void pair_offset(const cl_cloth *c, const cl_pair *p, int *di, int *dj)
{
    *di = p->b / c->nv - p->a / c->nv;
    *dj = p->b % c->nv - p->a % c->nv;
}

/* Every pair valid and of the set, rest length bit-equal to cl_dist, listed
 * once (a mark per unordered pair), as many as brute force finds. */
static void check_network(const cl_cloth *c, const cl_springnet *net,
                          const spring_sets *s)
{
    size_t np = c->np;
    unsigned char *seen = calloc(np * np, 1);
    cr_assert_not_null(seen);
    for (size_t k = 0; k < net->set.n; k++) {
        const cl_pair *p = &net->set.pair[k];
        int di, dj;
        cr_assert(p->a >= 0 && p->a < p->b && (size_t)p->b < np);
        pair_offset(c, p, &di, &dj);
        cr_assert(in_sets(s, di, dj), "pair (%d, %d) offset (%d, %d)", p->a,
                  p->b, di, dj);
        cr_assert_eq(p->rest, cl_dist(c->X0 + 3 * p->a, c->X0 + 3 * p->b));
        cr_assert_gt(net->k[k], 0.0);
        cr_assert(!seen[p->a * np + p->b], "pair (%d, %d) twice", p->a, p->b);
        seen[p->a * np + p->b] = 1;
    }
    size_t brute = 0;
    for (size_t a = 0; a < np; a++)
        for (size_t b = a + 1; b < np; b++) {
            int di = (int)(b / c->nv) - (int)(a / c->nv);
            int dj = (int)(b % c->nv) - (int)(a % c->nv);
            brute += in_sets(s, di, dj);
        }
    cr_assert_eq(net->set.n, brute, "%d x %d: %zu pairs, brute force %zu",
                 c->nu, c->nv, net->set.n, brute);
    free(seen);
}

static long levels_count(long n, long k)
{
    if (k > n - 1)
        k = n - 1;
    return 4 * n * n * k - 3 * n * k * (k + 1) + k * (k + 1) * (2 * k + 1) / 3;
}

Test(springs, named_set_counts)
{
    static const struct {
        const char *sets[3];
        spring_sets s;
    } cases[] = {
        {{"springs.k_shear=0", "springs.k_bend=0"}, {true, false, false, 0}},
        {{"springs.k_structural=0", "springs.k_shear=7", "springs.k_bend=0"},
         {false, true, false, 0}},
        {{"springs.k_structural=0", "springs.k_bend=3"},
         {false, false, true, 0}},
        {{"springs.k_shear=0"}, {true, false, true, 0}},
        {{NULL}, {true, true, true, 0}},
    };
    for (long n = 3; n <= 20; n++) {
        cl_cloth c = grid((int)n, (int)n, 1.0, 1.0);
        const long want[] = {2 * n * (n - 1), 2 * (n - 1) * (n - 1),
                             2 * n * (n - 2),
                             2 * n * (n - 1) + 2 * n * (n - 2),
                             6 * n * n - 10 * n + 2};
        for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
            const char *sets[4] = {cases[k].sets[0], cases[k].sets[1],
                                   cases[k].sets[2], NULL};
            cl_springnet net = sc_network(&c, sets);
            cr_assert_eq((long)net.set.n, want[k], "n=%ld case %zu: %zu", n,
                         k, net.set.n);
            check_network(&c, &net, &cases[k].s);
            cl_springnet_free(&net);
        }
        cl_cloth_free(&c);
    }
}

Test(springs, level_counts)
{
    for (long n = 3; n <= 20; n++) {
        cl_cloth c = grid((int)n, (int)n, 1.0, 1.0);
        long prev = 0;
        for (long k = 1; k <= n + 1; k++) {
            char lv[64];
            snprintf(lv, sizeof lv, "springs.levels=%ld", k);
            cl_springnet net = sc_network(&c, FD_SETS(lv));
            spring_sets s = {false, false, false, (int)k};
            cr_assert_eq((long)net.set.n, levels_count(n, k),
                         "n=%ld levels=%ld: %zu", n, k, net.set.n);
            /* Level k alone adds 2 (n-k)(2n-k) pairs (none once k >= n). */
            long add = k < n ? 2 * (n - k) * (2 * n - k) : 0;
            cr_assert_eq((long)net.set.n - prev, add);
            prev = (long)net.set.n;
            if (n <= 12)
                check_network(&c, &net, &s);
            cl_springnet_free(&net);
        }
        cl_cloth_free(&c);
    }
}

/* Levels 1 and 2 against the Choi-Ko sets (the same offsets). */
Test(springs, levels_match_choiko_sets)
{
    for (long n = 3; n <= 20; n++) {
        cr_assert_eq(levels_count(n, 1), 2 * (n - 1) * (2 * n - 1));
        cr_assert_eq(levels_count(n, 2) - levels_count(n, 1),
                     4 * (n - 1) * (n - 2));
    }
}

Test(springs, rectangles_and_chains)
{
    static const int dims[][2] = {{1, 6}, {6, 1}, {2, 2}, {2, 9}, {4, 7},
                                  {7, 4}, {12, 5}, {3, 11}};
    for (size_t g = 0; g < sizeof dims / sizeof dims[0]; g++) {
        cl_cloth c = grid(dims[g][0], dims[g][1], 1.3, 0.9);
        cl_springnet net = sc_network(&c, NULL);
        check_network(&c, &net, &(spring_sets){true, true, true, 0});
        cl_springnet_free(&net);
        for (int k = 1; k <= 5; k++) {
            char lv[64];
            snprintf(lv, sizeof lv, "springs.levels=%d", k);
            net = sc_network(&c, FD_SETS(lv));
            check_network(&c, &net, &(spring_sets){false, false, false, k});
            cl_springnet_free(&net);
        }
        cl_cloth_free(&c);
    }
    /* A chain of n: n-1 structural, n-2 bend springs. */
    cl_cloth c = grid(1, 9, 1.0, 2.0);
    cl_springnet net = sc_network(&c, NULL);
    cr_assert_eq(net.set.n, 8 + 7);
    cl_springnet_free(&net);
    cl_cloth_free(&c);
}

/* levels = 1 is exactly structural + shear, levels = 2 is the default named
 * sets plus the +-2 diagonals (2 (n-2)^2 pairs), in stiffness too when all
 * stiffnesses are equal. */
static bool same_pair(const cl_pair *p, const cl_pair *q)
{
    return p->a == q->a && p->b == q->b && p->rest == q->rest;
}

static size_t count_common(const cl_springnet *x, const cl_springnet *y)
{
    size_t common = 0;
    for (size_t i = 0; i < x->set.n; i++)
        for (size_t j = 0; j < y->set.n; j++)
            if (same_pair(&x->set.pair[i], &y->set.pair[j])) {
                cr_assert_eq(x->k[i], y->k[j]);
                common++;
            }
    return common;
}

Test(springs, levels_consistent_with_named_sets)
{
    const long n = 7;
    cl_cloth c = grid((int)n, (int)n, 1.0, 1.0);
    cl_springnet l1 = sc_network(&c, FD_SETS("springs.levels=1"));
    cl_springnet l2 = sc_network(&c, FD_SETS("springs.levels=2"));
    cl_springnet ss = sc_network(&c, FD_SETS("springs.k_bend=0"));
    cl_springnet all = sc_network(&c, FD_SETS("springs.k_bend=200"));
    cr_assert_eq(l1.set.n, ss.set.n);
    cr_assert_eq(count_common(&l1, &ss), ss.set.n);
    cr_assert_eq(count_common(&l2, &all), all.set.n);
    cr_assert_eq((long)(l2.set.n - all.set.n), 2 * (n - 2) * (n - 2));
    cl_springnet_free(&l1);
    cl_springnet_free(&l2);
    cl_springnet_free(&ss);
    cl_springnet_free(&all);
    cl_cloth_free(&c);
}

/* ---- stiffness -------------------------------------------------------- */

/* Stiffness by offset class: axis 1, diagonal 1, axis 2, level l. */
static void check_stiffness(const cl_cloth *c, const cl_springnet *net,
                            double k1, double kd, double k2)
{
    for (size_t k = 0; k < net->set.n; k++) {
        int di, dj;
        pair_offset(c, &net->set.pair[k], &di, &dj);
        di = abs(di);
        dj = abs(dj);
        double want = di + dj == 1 ? k1 : (di == 1 && dj == 1 ? kd : k2);
        cr_assert_eq(net->k[k], want, "offset (%d, %d): %g, want %g", di, dj,
                     net->k[k], want);
    }
}

Test(springs, default_bend_is_one_eighth_of_structural)
{
    cl_cloth c = grid(6, 6, 1.0, 1.0);
    cl_springnet net = sc_network(&c, FD_SETS("springs.k_structural=173"));
    check_stiffness(&c, &net, 173.0, 173.0, 173.0 / 8.0);
    cl_springnet_free(&net);
    net = sc_network(&c, NULL); /* defaults: 200, 200, 25 */
    check_stiffness(&c, &net, 200.0, 200.0, 25.0);
    cl_springnet_free(&net);
    net = sc_network(&c, FD_SETS("springs.k_shear=3", "springs.k_bend=40"));
    check_stiffness(&c, &net, 200.0, 3.0, 40.0);
    cl_springnet_free(&net);
    cl_cloth_free(&c);
}

Test(springs, level_stiffness)
{
    cl_cloth c = grid(8, 8, 1.0, 1.0);
    for (int inverse = 0; inverse < 2; inverse++) {
        cl_springnet net = sc_network(
            &c, FD_SETS("springs.levels=4", "springs.k_structural=120",
                        inverse ? "springs.level_stiffness=inverse"
                                : "springs.level_stiffness=same"));
        for (size_t k = 0; k < net.set.n; k++) {
            int di, dj;
            pair_offset(&c, &net.set.pair[k], &di, &dj);
            int l = abs(di) > abs(dj) ? abs(di) : abs(dj);
            cr_assert_eq(net.k[k], inverse ? 120.0 / l : 120.0);
        }
        cl_springnet_free(&net);
    }
    cl_cloth_free(&c);
}

/* Status of a springs model with these settings (an error must name
 * [springs]). */
static cl_status network_status(const char *const *sets)
{
    const char *all[8] = {"pins.at=", "springs.enabled=true"};
    for (size_t k = 0; sets[k]; k++)
        all[2 + k] = sets[k];
    cl_model *m = NULL;
    cl_error err = {0};
    cl_status rc = fd_model_try(all, &m, &err);
    if (rc == CL_OK)
        cl_model_free(m);
    else
        cr_assert(strstr(err.msg, "springs"), "message: %s", err.msg);
    return rc;
}

Test(springs, option_errors)
{
    static const struct {
        const char *a, *b;
        cl_status want;
    } cases[] = {
        {"springs.levels=2", "springs.k_bend=3", CL_EINVAL},
        {"springs.levels=2", "springs.k_shear=3", CL_EINVAL},
        {"springs.level_stiffness=inverse", NULL, CL_EINVAL},
        {"springs.k_structural=-1", NULL, CL_EINVAL},
        {"springs.k_bend=nan", NULL, CL_EINVAL},
        {"springs.levels=-1", NULL, CL_EINVAL},
        {"springs.level_stiffness=half", "springs.levels=1", CL_EINVAL},
        {"springs.levels=3", "springs.k_structural=5", CL_OK},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        cr_assert_eq(network_status(FD_SETS(cases[k].a, cases[k].b)),
                     cases[k].want, "case %zu (%s %s)", k, cases[k].a,
                     cases[k].b ? cases[k].b : "");
}

Test(springs, off_by_default)
{
    cl_model *m = FD_MODEL("cloth.n=4", "pins.at=");
    cr_assert(!fd_has_term(m, "springs"));
    cr_assert(!fd_has_term(m, "spring-damping"));
    cl_model_free(m);
    m = sc_model(SC_BASE, FD_SETS("springs.enabled=true", "cloth.n=4"));
    cr_assert(fd_has_term(m, "springs"));
    cr_assert(!fd_has_term(m, "type1"));
    cl_model_free(m);
}

/* ---- forces ----------------------------------------------------------- */

static const char *const *const force_cases[] = {
    FD_SETS("springs.enabled=true", "cloth.n=5"),
    FD_SETS("springs.enabled=true", "cloth.nu=5", "cloth.nv=4",
            "cloth.su=1.2", "cloth.sv=0.9", "springs.k_shear=31",
            "springs.k_bend=7"),
    FD_SETS("springs.enabled=true", "cloth.n=6", "springs.levels=3",
            "springs.level_stiffness=inverse"),
};
#define NFORCE_CASES (sizeof force_cases / sizeof force_cases[0])

/* Case k in a random state: stretched 4% along x, compressed 5% along z,
 * jittered in and out of the plane, so that springs pull and push. */
static sc_case force_case(size_t k, uint64_t seed)
{
    sc_case c = sc_open(force_cases[k], seed);
    sc_state(&c, 1.04, 0.95, 0.05, 0.1, 0.3);
    return c;
}

Test(springs, jacobian_fd)
{
    double worst = 0.0;
    for (size_t k = 0; k < NFORCE_CASES; k++) {
        sc_case c = force_case(k, 100 + k);
        for (int trial = 0; trial < 2; trial++) {
            double ex, ev;
            fd_check_jacobian(c.m, c.x, c.v, 1e-6 * c.h, 1e-6, false,
                              "springs", &ex, &ev);
            cr_assert_lt(ex, 1e-8, "case %zu: df/dx vs FD: rel err %g", k,
                         ex);
            cr_assert_eq(ev, 0.0, "springs do not depend on v");
            worst = fmax(worst, ex);
            double st = fd_check_structure(c.m, c.x, c.v);
            cr_assert_lt(st, 1e-13, "df/dx symmetry / row sums %g", st);
            sc_state(&c, 0.97, 1.03, 0.05, 0.1, 0.3);
        }
        sc_close(&c);
    }
    fd_report("springs worst df/dx", worst);
}

/* f = -dE/dx, Newton's third law, no net torque (central forces). */
Test(springs, energy_gradient_and_balance)
{
    for (size_t k = 0; k < NFORCE_CASES; k++) {
        sc_case c = force_case(k, 110 + k);
        double e = fd_check_energy(c.m, c.x, c.v, 1e-6 * c.h, "springs");
        cr_assert_lt(e, 1e-8, "case %zu: f vs -dE/dx: rel err %g", k, e);
        fd_eval(c.m, c.x, c.v, c.f);
        double torque, net = fd_net_force(c.x, c.f, c.n / 3, &torque);
        cr_assert_lt(net, 1e-14, "net force %g", net);
        cr_assert_lt(torque, 1e-14, "net torque %g", torque);
        sc_close(&c);
    }
}

Test(springs, rigid_motion_invariance)
{
    for (size_t k = 0; k < NFORCE_CASES; k++) {
        sc_case c = force_case(k, 130 + k);
        for (int trial = 0; trial < 2; trial++) {
            double R[9], t[3], w[3];
            fd_rotation(&c.r, R);
            fd_random_vec(&c.r, 3.0, t, 3);
            fd_random_vec(&c.r, 1.0, w, 3);
            double e = fd_check_rigid(c.m, c.x, c.v, R, t, w, "springs");
            cr_assert_lt(e, 1e-11, "case %zu: rigid-motion deviation %g", k,
                         e);
            sc_state(&c, 1.02, 0.98, 0.05, 0.1, 0.5);
        }
        sc_close(&c);
    }
}

/* Uniform scaling by lambda: every spring at lambda L, energy
 * 0.5 (lambda-1)^2 sum k L^2; corner (0,0) pulled by its structural,
 * shear and bend neighbours: f = (lambda-1) (ks hu + ksh hu + 2 kb hu, 0,
 * ks hv + ksh hv + 2 kb hv) (each spring k (d-L) u, (d-L) u = (lambda-1)
 * times the rest offset); interior particles balanced. */
Test(springs, law_on_uniform_stretch)
{
    const int nu = 5, nv = 6;
    const double su = 1.5, sv = 2.0, ks = 90, ksh = 40, kb = 13, lam = 0.97;
    sc_case c = sc_open(FD_SETS("springs.enabled=true", "cloth.nu=5",
                                "cloth.nv=6", "cloth.su=1.5", "cloth.sv=2.0",
                                "springs.k_structural=90",
                                "springs.k_shear=40", "springs.k_bend=13"),
                        140);
    sc_state(&c, lam, lam, 0.0, 0.0, 0.0);
    cl_energy e = fd_eval(c.m, c.x, c.v, c.f);
    double hu = su / (nu - 1), hv = sv / (nv - 1);
    double sum = ks * ((nu - 1) * nv * hu * hu + nu * (nv - 1) * hv * hv) +
                 ksh * 2.0 * (nu - 1) * (nv - 1) * (hu * hu + hv * hv) +
                 kb * 4 * ((nu - 2) * nv * hu * hu + nu * (nv - 2) * hv * hv);
    double want = 0.5 * (lam - 1) * (lam - 1) * sum;
    double got = fd_term_energy(&e, "springs");
    cr_assert(fabs(got - want) <= 1e-12 * want, "energy %.17g vs %.17g", got,
              want);
    double fc[3] = {(lam - 1) * (ks + ksh + 2 * kb) * hu, 0.0,
                    (lam - 1) * (ks + ksh + 2 * kb) * hv};
    double scale = fabs(lam - 1) * ks * hv;
    for (int i = 0; i < 3; i++)
        cr_assert(fabs(c.f[i] - fc[i]) <= 1e-12 * scale,
                  "corner f[%d] %g %g", i, c.f[i], fc[i]);
    for (int i = 2; i < nu - 2; i++)
        for (int j = 2; j < nv - 2; j++)
            for (int k = 0; k < 3; k++)
                cr_assert_lt(fabs(c.f[3 * (i * nv + j) + k]), 1e-12 * scale);
    /* At rest every spring sits exactly at d = L. */
    e = fd_eval(c.m, cl_model_cloth(c.m)->X0, c.v, c.f);
    cr_assert_eq(fd_maxabs(c.f, c.n), 0.0);
    cr_assert_eq(fd_term_energy(&e, "springs"), 0.0);
    sc_close(&c);
}

/* ms-hang as shipped: springs, spring-damping and gravity only, every key
 * used; the springs at Zischg, Chea and Aigner's ratio. */
Test(springs, ms_hang_problem)
{
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(cl_config_load(cfg, "problems/ms-hang.ini", &err), CL_OK,
                 "%s", err.msg);
    cl_config_ignore_section(cfg, "run");
    cl_model *m = NULL;
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_OK, "%s", err.msg);
    const char *const *names;
    size_t nt = cl_model_terms(m, &names);
    cr_assert_eq(nt, 4);
    cr_assert_str_eq(names[0], "springs");
    cr_assert_str_eq(names[1], "spring-damping");
    cr_assert_str_eq(names[2], "gravity");
    cr_assert_str_eq(names[3], "pbd"); /* for verlet-pbd only */
    cl_springnet net;
    cr_assert_eq(cl_springs_network(cfg, cl_model_cloth(m), &net, &err),
                 CL_OK);
    cr_assert_eq(net.set.n, 6 * 16 * 16 - 10 * 16 + 2);
    check_stiffness(cl_model_cloth(m), &net, 200.0, 200.0, 25.0);
    cl_springnet_free(&net);
    cl_model_free(m);
    cl_config_free(cfg);
}
