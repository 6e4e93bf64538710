/* Verification of the Choi-Ko Type2 term (docs/model.md 3.2;
 * docs/architecture.md, "Checks every force term passes"): interlaced pairs,
 * compression d < L: s = max(f_b, cb (d - L)) with the buckling force
 * f_b = kb kappa^2 / (cos(kappa L/2) - sinc(kappa L/2)),
 * kappa = (2/L) asinc(d/L); tension d >= L: ks (d - L) (tension = spring) or
 * 0 (tension = none); variants asinc = seed-poly, fb_sinc = normalised.
 *
 * Type2 runs alone (type1 off, no damping, no gravity, no pins).  With the
 * default kb = 5e-6 and cb = ks = 200 the f_b / cb crossover lies within
 * ~2.4e-6 L of L; "wide" runs use kb = 0.1 so that the cb branch covers
 * ~1.7% (diagonal pairs) to ~5% (axis pairs) compression and every branch
 * can be checked with ordinary steps.  Every random state is checked against
 * an independent reference law (tests/fdcheck.h) for the branch of each pair
 * and its distance from the kinks (d = L and the crossover).
 *
 * Isolated-pair checks use a 3 x 3 grid of side 1 (Type2 needs 3 particles
 * per side): particles 1 = (0,1) and 7 = (2,1) belong to one Type2 pair only,
 * (0,1)-(2,1) with L = 1; particle 7 is put at X0_1 + (d, 0, 0), so the force
 * on particle 1 is s(d) (1, 0, 0) and every other pair stays at rest. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"

#define KB_DEF 5e-6
#define KS_DEF 200.0
#define KB_WIDE 0.1

#define TYPE2_ONLY(...)                                                     \
    FD_MODEL("type1.enabled=false", "damping.kd=0", "gravity.g=0,0,0",     \
             "pins.at=", __VA_ARGS__)

enum { BR_FB, BR_CB, BR_TENSION };

typedef struct {
    size_t count[3];
    double margin; /* smallest distance to a kink, relative to L */
    double emin, emax;
} branches;

/* Branch of every Type2 pair by the reference law (exact asinc and sinc),
 * and the distance to the nearest kink (d = L or the f_b/cb crossover,
 * estimated as |f_b - cb (d - L)| / cb). */
static branches classify(const cl_model *m, const double *x, double kb,
                         double cb)
{
    cl_pairset set;
    cl_error err;
    cr_assert_eq(cl_pairs_type2(cl_model_cloth(m), &set, &err), CL_OK);
    branches b = {{0, 0, 0}, INFINITY, INFINITY, -INFINITY};
    for (size_t k = 0; k < set.n; k++) {
        const cl_pair *p = &set.pair[k];
        double L = p->rest, d = cl_dist(x + 3 * p->a, x + 3 * p->b);
        double e = (L - d) / L, margin = fabs(e);
        b.emin = fmin(b.emin, e);
        b.emax = fmax(b.emax, e);
        if (d >= L) {
            b.count[BR_TENSION]++;
        } else {
            double fb = fd_fb_ref(kb, L, d), lin = cb * (d - L);
            b.count[fb > lin ? BR_FB : BR_CB]++;
            margin = fmin(margin, fabs(fb - lin) / (cb * L));
        }
        b.margin = fmin(b.margin, margin);
    }
    cl_pairs_free(&set);
    return b;
}

/* ---- isolated pair ----------------------------------------------------- */

static cl_model *pair_model(const char *const *extra)
{
    const char *sets[32] = {"cloth.nu=3",       "cloth.nv=3",
                            "cloth.su=1",       "cloth.sv=1",
                            "type1.enabled=false", "damping.kd=0",
                            "gravity.g=0,0,0",  "pins.at="};
    size_t k = 8;
    for (size_t i = 0; extra && extra[i]; i++) {
        cr_assert_lt(k, 31);
        sets[k++] = extra[i];
    }
    sets[k] = NULL;
    return fd_model(sets);
}

#define PA 1 /* particle (0,1) */
#define PB 7 /* particle (2,1) */

/* s(d) and the Type2 energy of the isolated pair (rest length 1). */
static double pair_law(cl_model *m, double d, double *energy)
{
    const cl_cloth *c = cl_model_cloth(m);
    cr_assert_eq(c->np, 9);
    double x[27], v[27] = {0}, f[27];
    memcpy(x, c->X0, sizeof x);
    cr_assert_eq(x[3 * PB] - x[3 * PA], 1.0);
    x[3 * PB] = x[3 * PA] + d;
    cr_assert_eq(cl_dist(x + 3 * PA, x + 3 * PB), d);
    cl_energy e = fd_eval(m, x, v, f);
    for (int i = 0; i < 27; i++) {
        if (i == 3 * PA || i == 3 * PB)
            continue;
        cr_assert_eq(f[i], 0.0, "f[%d] = %g: only one pair may act", i,
                     f[i]);
    }
    cr_assert_eq(f[3 * PB], -f[3 * PA]);
    if (energy)
        *energy = fd_term_energy(&e, "type2");
    return f[3 * PA];
}

/* Whether the pair at d is on the cb branch: the code returns cb (d - L)
 * there, bit for bit. */
static bool on_cb_branch(cl_model *m, double cb, double d)
{
    return pair_law(m, d, NULL) == cb * (d - 1.0);
}

/* Crossover in (lo, hi): lo on the f_b branch, hi on the cb branch. */
static double find_crossover(cl_model *m, double cb, double lo, double hi)
{
    cr_assert(!on_cb_branch(m, cb, lo) && on_cb_branch(m, cb, hi),
              "crossover not bracketed by [%.17g, %.17g]", lo, hi);
    for (int it = 0; it < 200; it++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
            break;
        if (on_cb_branch(m, cb, mid))
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

/* Every branch change in (1e-3, 1 - 1e-12), ascending: a scan of 400
 * points plus one next to L, each change bisected to the last bit. */
static size_t find_crossovers(cl_model *m, double cb, double *cross,
                              size_t max)
{
    size_t nc = 0;
    double dprev = 1e-3;
    bool prev = on_cb_branch(m, cb, dprev);
    for (int i = 1; i <= 400; i++) {
        double d = i < 400 ? 1e-3 + 0.999 * i / 400.0 : 1.0 - 1e-12;
        bool cur = on_cb_branch(m, cb, d);
        if (cur != prev) {
            double lo = dprev, hi = d;
            for (int it = 0; it < 200; it++) {
                double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi)
                    break;
                if (on_cb_branch(m, cb, mid) == prev)
                    lo = mid;
                else
                    hi = mid;
            }
            cr_assert_lt(nc, max);
            cross[nc++] = 0.5 * (lo + hi);
        }
        prev = cur;
        dprev = d;
    }
    return nc;
}

/* integral_a^b s(r) dr by 5-point Gauss-Legendre on nsub panels. */
static double law_integral(cl_model *m, double a, double b, int nsub)
{
    static const double xg[5] = {-0.9061798459386640, -0.5384693101056831,
                                 0.0, 0.5384693101056831, 0.9061798459386640};
    static const double wg[5] = {0.2369268850561891, 0.4786286704993665,
                                 0.5688888888888889, 0.4786286704993665,
                                 0.2369268850561891};
    double h = (b - a) / nsub, sum = 0.0;
    for (int k = 0; k < nsub; k++) {
        double mid = a + (k + 0.5) * h;
        for (int q = 0; q < 5; q++)
            sum += wg[q] * pair_law(m, mid + 0.5 * h * xg[q], NULL);
    }
    return 0.5 * h * sum;
}

/* ---- Jacobian vs finite differences ------------------------------------ */

/* One Jacobian check on a random state from A and jitters, after checking
 * the branches (want[] > 0: at least that many pairs in the branch, < 0:
 * none) and a kink margin of at least `margin` (relative to L). */
static double jac_case(cl_model *m, const double A[9], double jit_plane,
                       double jit_normal, double kb, double cb,
                       const int want[3], double margin, double hx,
                       fd_rng *r, const char *label)
{
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_deform(m, A, jit_plane, jit_normal, r, x);
    fd_random_vec(r, 0.2, v, n);
    branches b = classify(m, x, kb, cb);
    static const char *const bn[3] = {"f_b", "cb", "tension"};
    for (int k = 0; k < 3; k++) {
        if (want[k] > 0)
            cr_assert_geq(b.count[k], (size_t)want[k], "%s: %zu %s pairs",
                          label, b.count[k], bn[k]);
        if (want[k] < 0)
            cr_assert_eq(b.count[k], 0, "%s: %zu %s pairs", label,
                         b.count[k], bn[k]);
    }
    cr_assert_gt(b.margin, margin, "%s: kink margin %g", label, b.margin);
    double ex, ev;
    fd_check_jacobian(m, x, v, hx, 1e-6, false, label, &ex, &ev);
    /* central differences at steps of 2.5e-7 agree to under 3e-10; at the
     * default parameters' step of 1e-9 round-off leaves 2.3e-8 */
    double tol = hx >= 1e-7 ? 1e-8 : 1e-7;
    cr_assert_lt(ex, tol, "%s: df/dx vs FD rel err %g", label, ex);
    double st = fd_check_structure(m, x, v);
    cr_assert_lt(st, 1e-13, "%s: df/dx not symmetric / row sums %g", label,
                 st);
    cr_assert_eq(ev, 0.0, "%s: Type2 does not depend on v", label);
    free(x);
    free(v);
    return ex;
}

Test(type2, jacobian_fd_fb_branch)
{
    cl_model *m = TYPE2_ONLY("cloth.n=5");
    fd_rng r = {21};
    double A[9], worst = 0.0;
    for (int trial = 0; trial < 3; trial++) {
        fd_scale(0.94 - 0.02 * trial, 0.95, A);
        worst = fmax(worst, jac_case(m, A, 0.01, 0.06, KB_DEF, KS_DEF,
                                     (int[3]){24, -1, -1}, 0.01, 2.5e-7, &r,
                                     "type2 f_b"));
    }
    fd_report("type2 worst df/dx f_b branch", worst);
    cl_model_free(m);
}

/* Default parameters: the cb branch is only ~1e-6 L wide, so the state sits
 * at 4e-7 L compression and the step is 1e-9. */
Test(type2, jacobian_fd_cb_branch_default_params)
{
    cl_model *m = TYPE2_ONLY("cloth.n=5");
    fd_rng r = {22};
    double A[9], worst = 0.0;
    fd_scale(1.0 - 4e-7, 1.0 - 4e-7, A);
    for (int trial = 0; trial < 2; trial++)
        worst = fmax(worst, jac_case(m, A, 2e-8, 2e-4, KB_DEF, KS_DEF,
                                     (int[3]){-1, 24, -1}, 2e-7, 1e-9, &r,
                                     "type2 cb (default)"));
    fd_report("type2 worst df/dx cb branch (default)", worst);
    cl_model_free(m);
}

Test(type2, jacobian_fd_cb_branch_wide)
{
    cl_model *m = TYPE2_ONLY("cloth.n=5", "type2.kb=0.1");
    fd_rng r = {23};
    double A[9], worst = 0.0;
    for (int trial = 0; trial < 3; trial++) {
        fd_scale(0.992 + 0.002 * trial, 0.993, A);
        worst = fmax(worst, jac_case(m, A, 0.001, 0.02, KB_WIDE, KS_DEF,
                                     (int[3]){-1, 24, -1}, 0.002, 2.5e-7, &r,
                                     "type2 cb (wide)"));
    }
    fd_report("type2 worst df/dx cb branch (wide)", worst);
    cl_model_free(m);
}

/* All three branches at once: x stretched 4% (tension), z compressed 7%
 * (axis pairs on f_b), diagonals ~1.3% compressed (cb with kb = 0.1). */
Test(type2, jacobian_fd_all_branches)
{
    cl_model *m = TYPE2_ONLY("cloth.nu=6", "cloth.nv=5", "cloth.su=1.25",
                             "cloth.sv=1", "type2.kb=0.1");
    fd_rng r = {24};
    double A[9];
    fd_scale(1.04, 0.93, A);
    double e = jac_case(m, A, 0.0005, 0.01, KB_WIDE, KS_DEF,
                        (int[3]){5, 5, 5}, 0.001, 2.5e-7, &r,
                        "type2 all branches");
    fd_report("type2 df/dx all branches", e);
    cl_model_free(m);
}

Test(type2, jacobian_fd_tension_spring)
{
    cl_model *m = TYPE2_ONLY("cloth.n=5", "type2.tension=spring",
                             "type1.ks=150");
    fd_rng r = {25};
    double A[9];
    fd_scale(1.05, 1.07, A);
    double e = jac_case(m, A, 0.01, 0.05, KB_DEF, 150.0,
                        (int[3]){-1, -1, 24}, 0.01, 2.5e-7, &r,
                        "type2 tension");
    fd_report("type2 df/dx tension", e);
    cl_model_free(m);
}

/* tension = none: stretched pairs carry nothing, compressed ones f_b. */
Test(type2, jacobian_fd_tension_none)
{
    cl_model *m = TYPE2_ONLY("cloth.n=5", "type2.tension=none");
    fd_rng r = {26};
    double A[9];
    fd_scale(1.05, 0.92, A);
    double e = jac_case(m, A, 0.005, 0.03, KB_DEF, KS_DEF,
                        (int[3]){5, -1, 5}, 0.002, 2.5e-7, &r,
                        "type2 tension=none");
    fd_report("type2 df/dx tension=none", e);
    /* A fully stretched state: exactly zero force, energy and Jacobian. */
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n),
           *Jx = fd_vec(n * n), *Jv = fd_vec(n * n);
    fd_scale(1.05, 1.06, A);
    fd_deform(m, A, 0.005, 0.03, &r, x);
    cr_assert_eq(classify(m, x, KB_DEF, KS_DEF).count[BR_TENSION],
                 4 * 4 * 3);
    cl_energy en = fd_eval(m, x, v, f);
    cr_assert_eq(fd_maxabs(f, n), 0.0);
    cr_assert_eq(fd_term_energy(&en, "type2"), 0.0);
    fd_jacobian(m, x, v, Jx, Jv);
    cr_assert_eq(fd_maxabs(Jx, n * n), 0.0);
    free(x);
    free(v);
    free(f);
    free(Jx);
    free(Jv);
    cl_model_free(m);
}

/* The reproductions of Jiao's own code: polynomial asinc, numpy's normalised
 * sinc in the denominator, and both, in compression (f_b branch, 3-9%). */
static const char *const variants[][2] = {
    {"type2.asinc=seed-poly", "type2.fb_sinc=exact"},
    {"type2.asinc=exact", "type2.fb_sinc=normalised"},
    {"type2.asinc=seed-poly", "type2.fb_sinc=normalised"},
};

Test(type2, jacobian_fd_seed_variants)
{
    for (size_t k = 0; k < 3; k++) {
        cl_model *m = TYPE2_ONLY("cloth.n=5", variants[k][0],
                                 variants[k][1]);
        size_t n = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n), A[9];
        fd_rng r = {27 + k};
        for (int trial = 0; trial < 2; trial++) {
            fd_scale(0.93 - 0.02 * trial, 0.95, A);
            fd_deform(m, A, 0.01, 0.06, &r, x);
            branches b = classify(m, x, KB_DEF, KS_DEF);
            cr_assert(b.emin > 0.02 && b.emax < 0.2, "e in [%g, %g]",
                      b.emin, b.emax);
            char label[96];
            snprintf(label, sizeof label, "type2 %s %s", variants[k][0] + 6,
                     variants[k][1] + 6);
            double ex, ev;
            fd_check_jacobian(m, x, v, 2.5e-7, 1e-6, false, label, &ex, &ev);
            cr_assert_lt(ex, 1e-8, "%s: df/dx rel err %g", label, ex);
            cr_assert_eq(ev, 0.0);
            double ee = fd_check_energy(m, x, v, 2.5e-7, label);
            cr_assert_lt(ee, 1e-8, "%s: f vs -dE/dx rel err %g", label, ee);
        }
        free(x);
        free(v);
        cl_model_free(m);
    }
}

/* ---- energy ------------------------------------------------------------ */

Test(type2, force_is_minus_energy_gradient)
{
    static const struct {
        double sx, sz, jit, h, kb;
        const char *kbset, *label;
    } cases[] = {
        {0.94, 0.95, 0.01, 2.5e-7, KB_DEF, "type2.kb=5e-6", "type2 E f_b"},
        {0.993, 0.994, 0.001, 2.5e-7, KB_WIDE, "type2.kb=0.1",
         "type2 E cb (wide)"},
        {1.04, 0.93, 0.0002, 2.5e-7, KB_WIDE, "type2.kb=0.1",
         "type2 E all branches"},
        {1.05, 1.06, 0.01, 2.5e-7, KB_DEF, "type2.kb=5e-6",
         "type2 E tension"},
        {1.0 - 4e-7, 1.0 - 4e-7, 2e-8, 1e-9, KB_DEF, "type2.kb=5e-6",
         "type2 E cb (default)"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        /* Unequal spacings: three distinct Type2 rest lengths. */
        cl_model *m = TYPE2_ONLY("cloth.nu=5", "cloth.nv=6", "cloth.su=1",
                                 "cloth.sv=1.4", cases[k].kbset);
        size_t n = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n), A[9];
        fd_rng r = {31 + k};
        fd_scale(cases[k].sx, cases[k].sz, A);
        fd_deform(m, A, cases[k].jit, cases[k].jit * 10, &r, x);
        branches b = classify(m, x, cases[k].kb, KS_DEF);
        cr_assert_gt(b.margin, 100 * cases[k].h, "%s: kink margin %g",
                     cases[k].label, b.margin);
        double e = fd_check_energy(m, x, v, cases[k].h, cases[k].label);
        /* under 8e-10 at steps of 2.5e-7; 1.0e-7 at the step of 1e-9 */
        double tol = cases[k].h >= 1e-7 ? 1e-8 : 1e-6;
        cr_assert_lt(e, tol, "%s: rel err %g", cases[k].label, e);
        free(x);
        free(v);
        cl_model_free(m);
    }
}

/* E(d) = integral_L^d s(r) dr (pieces split at the crossovers found from
 * the code's own branch choice), for the exact law with default and wide
 * parameters, with kb = 1, cb = 35 (two crossovers: cb near d = 0 and near
 * L, f_b in between), and for the variants of Jiao's code (energy by
 * quadrature). */
Test(type2, energy_is_integral_of_law)
{
    /* dmin: the normalised sinc makes cos t - sinc(pi t) vanish at
     * d = 0.5767 L (a pole of f_b), so those cases stay above it and are not
     * scanned for crossovers. */
    static const struct {
        const char *set[3];
        double cb;
        size_t ncross;
        double dmin;
    } cases[] = {
        {{"type2.kb=5e-6", NULL, NULL}, KS_DEF, 1, 0.0},
        {{"type2.kb=0.1", NULL, NULL}, KS_DEF, 1, 0.0},
        {{"type2.kb=1", "type2.cb=35", NULL}, 35.0, 2, 0.0},
        {{"type2.asinc=seed-poly", NULL, NULL}, KS_DEF, 1, 0.0},
        {{"type2.fb_sinc=normalised", NULL, NULL}, KS_DEF, 0, 0.7},
        {{"type2.asinc=seed-poly", "type2.fb_sinc=normalised", NULL}, KS_DEF,
         0, 0.0},
    };
    static const double ds[] = {0.9999, 0.999, 0.98, 0.9,  0.75,
                                0.62,   0.3,   0.1,  0.02, 0.005};
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        cl_model *m = pair_model(cases[k].set);
        double cross[8];
        size_t nc = 0;
        if (cases[k].ncross)
            nc = find_crossovers(m, cases[k].cb, cross, 8);
        else
            cr_assert(!on_cb_branch(m, cases[k].cb, 1.0 - 1e-9));
        cr_assert_eq(nc, cases[k].ncross, "case %zu: %zu crossovers", k, nc);
        for (size_t i = 0; i < sizeof ds / sizeof ds[0]; i++) {
            double E, d = ds[i];
            if (d < cases[k].dmin)
                continue;
            pair_law(m, d, &E);
            /* integral_L^d s = -(integral_d^L), split at the crossovers. */
            double want = 0.0, lo = d;
            for (size_t c = 0; c <= nc; c++) {
                double hi = c < nc ? cross[c] : 1.0;
                if (hi <= lo)
                    continue;
                want -= law_integral(m, lo, hi, 40);
                lo = hi;
            }
            cr_assert(fabs(E - want) <= 1e-9 * fabs(want),
                      "case %zu d=%g: E %.17g vs integral %.17g", k, d, E,
                      want);
        }
        cl_model_free(m);
    }
}

/* Energy continuity across the crossover and at d = L; E(L) = 0. */
Test(type2, energy_continuous_at_kinks)
{
    static const char *const kbs[] = {"type2.kb=5e-6", "type2.kb=0.1",
                                      "type2.asinc=seed-poly"};
    for (size_t k = 0; k < 3; k++) {
        cl_model *m = pair_model((const char *const[]){kbs[k], NULL});
        double Em, Ep, E0, cross = find_crossover(m, KS_DEF, 0.5, 1 - 1e-12);
        double eps = 1e-6 * (1.0 - cross);
        double s = pair_law(m, cross - eps, &Em);
        pair_law(m, cross + eps, &Ep);
        cr_assert(fabs(Ep - Em) <= 2.0 * eps * fabs(s) * 1.01 + 1e-300,
                  "energy jumps by %g across the crossover at %.17g",
                  Ep - Em, cross);
        pair_law(m, 1.0, &E0);
        cr_assert_eq(E0, 0.0);
        pair_law(m, 1.0 - 1e-9, &Em);
        pair_law(m, 1.0 + 1e-9, &Ep);
        cr_assert_lt(fabs(Em), 1e-9 * 1e-9 * KS_DEF);
        cr_assert_lt(fabs(Ep), 1e-9 * 1e-9 * KS_DEF);
        cl_model_free(m);
    }
}

/* fb_sinc = normalised: cos t - sinc(pi t) vanishes at t = 1.71580, i.e.
 * d = 0.576704 L, where f_b has a pole (f_b > 0 above it, < 0 below).
 * Below the pole the energy integral diverges: the model must report a
 * non-finite energy (CL_EBLOWUP), not a number (regression: the quadrature
 * status was ignored and a divergent integral came back as a value). */
Test(type2, normalised_sinc_pole_has_no_energy)
{
    cl_model *m = pair_model(
        (const char *const[]){"type2.fb_sinc=normalised", NULL});
    double E;
    cr_assert_gt(pair_law(m, 0.58, &E), 0.0);
    cr_assert(isfinite(E) && E < 0);
    cr_assert_gt(pair_law(m, 0.5768, NULL), 1e3 * KB_DEF);
    const cl_cloth *c = cl_model_cloth(m);
    double x[27], v[27] = {0}, f[27];
    cl_energy e;
    cl_error err;
    for (double d = 0.5766; d > 0.05; d -= 0.1) {
        memcpy(x, c->X0, sizeof x);
        x[3 * PB] = x[3 * PA] + d;
        cl_status rc = cl_model_eval_full(m, 0.0, x, v, f, &e, &err);
        cr_assert_eq(rc, CL_EBLOWUP, "d=%g: energy %g accepted", d,
                     e.potential);
        cr_assert(isfinite(f[3 * PA]) && f[3 * PA] < 0, "d=%g: s = %g", d,
                  f[3 * PA]);
    }
    cl_model_free(m);
}

/* ---- the law itself ---------------------------------------------------- */

/* f_b -> -12 kb/L^2 as d -> L: f_b/(-12 kb/L^2) = 1 + 3e/5 + 72e^2/175
 * + 52e^3/175 + O(e^4), e = 1 - d/L (series of t^2/(cos t - sinc t)). */
Test(type2, limit_at_rest_length)
{
    cl_model *m = pair_model(NULL);
    double fb0 = -12.0 * KB_DEF;
    static const double es[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
    for (size_t k = 0; k < sizeof es / sizeof es[0]; k++) {
        double e = es[k], ratio = pair_law(m, 1.0 - e, NULL) / fb0;
        double series = 1 + e * (0.6 + e * (72.0 / 175 + e * 52.0 / 175));
        cr_assert(fabs(ratio - series) < 2 * e * e * e * e + 1e-12,
                  "e=%g: f_b/(-12 kb/L^2) = %.17g, series %.17g", e, ratio,
                  series);
    }
    cl_model_free(m);
    /* With kb tiny the crossover moves to ~1e-14 L: f_b itself is seen at
     * e = 1e-9 and equals the limit to ~1e-9. */
    m = pair_model((const char *const[]){"type2.kb=1e-12", NULL});
    double ratio = pair_law(m, 1.0 - 1e-9, NULL) / (-12.0 * 1e-12);
    cr_assert(fabs(ratio - 1.0) < 2e-9, "ratio %.17g", ratio);
    cl_model_free(m);
}

/* df_b/dd of the isolated pair (rest length 1) from the analytic Jacobian:
 * the (x, x) entry of df_1/dx_7 = K = s' u u^T + (s/d)(I - u u^T), u = x. */
static double pair_stiffness(cl_model *m, double d)
{
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *Jx = fd_vec(n * n),
           *Jv = fd_vec(n * n);
    memcpy(x, cl_model_cloth(m)->X0, n * sizeof *x);
    x[3 * PB] = x[3 * PA] + d;
    fd_jacobian(m, x, v, Jx, Jv);
    double ds = Jx[(3 * PA) * n + 3 * PB];
    free(x);
    free(v);
    free(Jx);
    free(Jv);
    return ds;
}

/* df_b/dd -> 7.2 kb/L^3 as d -> L: ratio 1 + 48e/35 + 52e^2/35 + O(e^3).
 * The f_b branch reaches e ~ 1e-13 with kb = 1e-12; 2 t D - t^2 D' loses
 * ~10 eps/t^2 there unless summed as a series (regression: 1e-4 relative
 * error at e = 1e-11 before). */
Test(type2, buckling_stiffness_near_rest_length)
{
    cl_model *m = pair_model((const char *const[]){"type2.kb=1e-12", NULL});
    for (double e = 1e-4; e > 5e-13; e /= 10) {
        double ratio = pair_stiffness(m, 1.0 - e) / (7.2e-12);
        double series = 1 + e * (48.0 / 35 + e * 52.0 / 35);
        cr_assert(fabs(ratio - series) < 2 * e * e * e + 1e-12,
                  "e=%g: f_b'/(7.2 kb/L^3) = %.17g, series %.17g", e, ratio,
                  series);
    }
    cl_model_free(m);
    /* Normalised sinc: no closed form here, but s' must be smooth as
     * d -> L (f_b > 0 is the active branch all the way). */
    m = pair_model((const char *const[]){"type2.fb_sinc=normalised", NULL});
    double ref = pair_stiffness(m, 1.0 - 1e-8);
    for (double e = 1e-9; e > 5e-14; e /= 10) {
        double ds = pair_stiffness(m, 1.0 - e);
        cr_assert(fabs(ds - ref) < 1e-7 * fabs(ref),
                  "normalised: s'(1 - %g) = %.17g vs %.17g", e, ds, ref);
    }
    cl_model_free(m);
}

/* f_b -> -4 pi^2 kb/L^2 as d -> 0: ratio 1 - 3y + (6 + pi^2/2) y^2
 * - (10 + 10 pi^2/3) y^3 + O(y^4), y = d/L. */
Test(type2, limit_at_full_compression)
{
    cl_model *m = pair_model(NULL);
    double fbpi = -4.0 * M_PI * M_PI * KB_DEF;
    static const double ys[] = {1e-2, 1e-3, 1e-4, 1e-6, 1e-9};
    for (size_t k = 0; k < sizeof ys / sizeof ys[0]; k++) {
        double y = ys[k], ratio = pair_law(m, y, NULL) / fbpi;
        double series = 1 + y * (-3 + y * (6 + M_PI * M_PI / 2 -
                                           y * (10 + 10 * M_PI * M_PI / 3)));
        cr_assert(fabs(ratio - series) < 500 * y * y * y * y + 1e-12,
                  "y=%g: f_b/(-4 pi^2 kb/L^2) = %.17g, series %.17g", y,
                  ratio, series);
    }
    cl_model_free(m);
}

/* s(d) against the reference formula at chords d = L sinc(t) for known t,
 * the cb branch exactly cb (d - L), the tension branch ks (d - L). */
Test(type2, law_matches_reference)
{
    static const double kbs[] = {KB_DEF, 0.01};
    for (size_t k = 0; k < 2; k++) {
        char set[64];
        snprintf(set, sizeof set, "type2.kb=%.17g", kbs[k]);
        cl_model *m = pair_model((const char *const[]){set, "type2.cb=150",
                                                       "type1.ks=120", NULL});
        double kb = kbs[k];
        for (double t = 0.2; t < 3.1; t += 0.35) {
            double d = sin(t) / t, s = pair_law(m, d, NULL);
            double fb = 4 * kb * t * t / (cos(t) - sin(t) / t);
            double want = fmax(fb, 150.0 * (d - 1.0));
            cr_assert(fabs(s - want) <= 1e-10 * fabs(want),
                      "kb=%g t=%g: s %.17g vs %.17g", kb, t, s, want);
            cr_assert(fabs(s - fd_type2_ref(kb, 150.0, 1.0, d)) <=
                      1e-10 * fabs(want));
        }
        for (double d = 1.0001; d < 1.5; d += 0.1)
            cr_assert_float_eq(pair_law(m, d, NULL), 120.0 * (d - 1.0),
                               1e-14, "tension at d=%g", d);
        cl_model_free(m);
    }
    /* kb = 10: f_b <= -120 < cb (d - L) for e < 0.8: s = cb (d - L)
     * exactly. */
    cl_model *m = pair_model((const char *const[]){"type2.kb=10",
                                                   "type2.cb=150", NULL});
    for (double d = 0.7; d < 1.0; d += 0.05)
        cr_assert_eq(pair_law(m, d, NULL), 150.0 * (d - 1.0), "d=%g", d);
    cl_model_free(m);
}

/* The force path's f_b (Chebyshev pieces of G(e), forces/type2.c) against
 * the scalar law's (inverse sinc and D(t) pair by pair, the energy path)
 * at 4001 compressions e = (L - d)/L over (0, 1), the ends included: the
 * same to 1e-14 relative (3.3e-15 measured: both a few ulp from the
 * exact value). */
Test(type2, force_path_matches_scalar_law)
{
    cl_model *m = pair_model((const char *const[]){"type2.cb=1e12", NULL});
    const cl_cloth *c = cl_model_cloth(m);
    const cl_system *sys = cl_model_system(m);
    double x[27], v[27] = {0}, f[27], worst = 0.0;
    cr_assert_eq(sys->n, 27); /* no pins: the system's x is the full x */
    memcpy(x, c->X0, sizeof x);
    for (int i = 0; i <= 4000; i++) {
        double e = i == 0 ? 1e-7 : i == 4000 ? 1.0 - 1e-9 : i / 4000.0;
        double d = 1.0 - e, fs = pair_law(m, d, NULL);
        x[3 * PB] = x[3 * PA] + d;
        cr_assert_eq(sys->force(sys->data, 0.0, x, v, f), CL_OK);
        worst = fmax(worst, fabs(f[3 * PA] - fs) / fabs(fs));
    }
    cr_assert_leq(worst, 1e-14, "worst relative difference %.3g", worst);
    cl_model_free(m);
}

/* With a huge cb the f_b branch covers (almost) everything: f_b is
 * monotone in d, below -12 kb/L^2 and above -4 pi^2 kb/L^2. */
Test(type2, buckling_force_bounds_and_monotonicity)
{
    cl_model *m = pair_model((const char *const[]){"type2.cb=1e12", NULL});
    double prev = -12.0 * KB_DEF;
    for (double d = 1.0 - 1e-6; d > 1e-4; d -= 0.0137) {
        double s = pair_law(m, d, NULL);
        cr_assert_leq(s, -12.0 * KB_DEF, "f_b(%g) = %g above -12 kb/L^2", d,
                      s);
        cr_assert_geq(s, -4 * M_PI * M_PI * KB_DEF);
        cr_assert_leq(s, prev, "f_b not monotone at d=%g", d);
        prev = s;
    }
    cl_model_free(m);
}

/* The crossover of f_b and cb (d - L) (docs/model.md (3.3)) lies within ~1e-4 L
 * of L, where cb e L = 12 kb/L^2 (1 + 3e/5 + ...). */
Test(type2, crossover_location)
{
    cl_model *m = pair_model(NULL);
    double cross = find_crossover(m, KS_DEF, 0.999, 1 - 1e-12);
    double a = 12 * KB_DEF / KS_DEF;      /* L = 1 */
    double e_ref = a * (1 + 0.6 * a);     /* fixed point, to O(a^3) */
    cr_assert(fabs((1 - cross) / e_ref - 1) < 1e-6, "crossover e %.17g vs %.17g",
              1 - cross, e_ref);
    cr_assert_lt(1 - cross, 1e-4);
    cl_model_free(m);
}

/* ---- invariances --------------------------------------------------------- */

Test(type2, newton_third_law_and_no_torque)
{
    static const char *const kbs[] = {"type2.kb=5e-6", "type2.kb=0.1"};
    for (size_t k = 0; k < 2; k++) {
        cl_model *m = TYPE2_ONLY("cloth.n=6", kbs[k]);
        size_t n = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), A[9];
        fd_rng r = {41 + k};
        fd_scale(1.04, 0.93, A);
        fd_deform(m, A, 0.01, 0.05, &r, x);
        fd_eval(m, x, v, f);
        double torque, net = fd_net_force(x, f, n / 3, &torque);
        cr_assert_lt(net, 1e-13, "net force %g", net);
        cr_assert_lt(torque, 1e-13, "net torque %g", torque);
        free(x);
        free(v);
        free(f);
        cl_model_free(m);
    }
}

Test(type2, rigid_motion_invariance)
{
    static const char *const sets[][2] = {
        {"type2.kb=5e-6", "type2.asinc=exact"},
        {"type2.kb=0.1", "type2.asinc=exact"},
        {"type2.kb=5e-6", "type2.asinc=seed-poly"},
    };
    for (size_t k = 0; k < 3; k++) {
        cl_model *m = TYPE2_ONLY("cloth.n=5", sets[k][0], sets[k][1]);
        size_t n = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n), A[9], R[9], c[3], w[3];
        fd_rng r = {45 + k};
        for (int trial = 0; trial < 2; trial++) {
            fd_scale(1.04, 0.93, A);
            fd_deform(m, A, 0.002, 0.05, &r, x);
            fd_rotation(&r, R);
            fd_random_vec(&r, 5.0, c, 3);
            fd_random_vec(&r, 1.0, w, 3);
            double e = fd_check_rigid(m, x, v, R, c, w, "type2");
            cr_assert_lt(e, 1e-9, "type2 rigid-motion deviation %g", e);
        }
        free(x);
        free(v);
        cl_model_free(m);
    }
}

/* At rest every Type2 pair is exactly at d = L: zero force and energy. */
Test(type2, rest_state_exactly_zero)
{
    fd_expect_rest_exactly_zero("type2", "type1.enabled=false");
}

/* ---- jacobian.transverse = clamp --------------------------------------- */

/* Two isolated pairs: A = (0,1)-(2,1) compressed out of plane (s < 0), B =
 * (1,0)-(1,2) stretched (s > 0).  clamp must equal full minus
 * (s_A/d_A)(I - u u^T) in A's four blocks (signs +, -, -, +) and leave every
 * other entry bit-identical. */
static void clamp_case(const char *kb, const double xA[3], int want_branch)
{
    cl_model *full = pair_model((const char *const[]){kb, NULL});
    cl_model *clamp = pair_model(
        (const char *const[]){kb, "jacobian.transverse=clamp", NULL});
    size_t n = fd_n(full);
    cr_assert_eq(n, 27);
    double x[27], v[27] = {0}, f[27];
    double *J1 = fd_vec(n * n), *J2 = fd_vec(n * n), *W = fd_vec(n * n);
    memcpy(x, cl_model_cloth(full)->X0, sizeof x);
    for (int i = 0; i < 3; i++)
        x[3 * PB + i] = x[3 * PA + i] + xA[i];
    x[3 * 5 + 0] += 0.05; /* particle (1,2): pair B stretched */
    x[3 * 5 + 1] -= 0.03;
    x[3 * 5 + 2] += 0.02;
    fd_eval(full, x, v, f);
    double d = cl_dist(x + 3 * PA, x + 3 * PB), u[3];
    for (int i = 0; i < 3; i++)
        u[i] = (x[3 * PB + i] - x[3 * PA + i]) / d;
    const double *fa = f + 3 * PA;
    double s = fa[0] * u[0] + fa[1] * u[1] + fa[2] * u[2];
    /* Independent value and branch of s. */
    double kbv = strtod(kb + strlen("type2.kb="), NULL);
    double fb = fd_fb_ref(kbv, 1.0, d), lin = KS_DEF * (d - 1.0);
    cr_assert_eq(fb > lin ? BR_FB : BR_CB, want_branch);
    cr_assert(fabs(s - fmax(fb, lin)) < 1e-10 * fabs(s), "s %g ref %g", s,
              fmax(fb, lin));
    cr_assert_lt(s, 0.0);
    fd_jacobian(full, x, v, J1, W);
    fd_jacobian(clamp, x, v, J2, W);
    double scale = 0.0, dev = 0.0; /* largest entry of pair A's blocks */
    for (size_t row = 0; row < n; row++)
        for (size_t col = 0; col < n; col++) {
            int bi = (int)row / 3, bj = (int)col / 3;
            if ((bi == PA || bi == PB) && (bj == PA || bj == PB))
                scale = fmax(scale, fabs(J1[row * n + col]));
        }
    for (size_t row = 0; row < n; row++)
        for (size_t col = 0; col < n; col++) {
            int bi = (int)row / 3, bj = (int)col / 3, r = row % 3, c = col % 3;
            double want = J1[row * n + col];
            if ((bi == PA || bi == PB) && (bj == PA || bj == PB)) {
                /* df_a/dx_a = -K: dropping T from K adds T there. */
                double T = (s / d) * ((r == c) - u[r] * u[c]);
                want += (bi == bj) ? T : -T;
                dev = fmax(dev, fabs(J2[row * n + col] - want));
            } else {
                cr_assert_eq(J2[row * n + col], want,
                             "clamp changed entry (%zu, %zu) outside pair A",
                             row, col);
            }
        }
    cr_assert_lt(dev, 1e-13 * scale, "clamp differs from full - T by %g",
                 dev);
    /* ... and the dropped part is not negligible. */
    cr_assert_gt(fabs(s / d), 1e-3 * scale);
    free(J1);
    free(J2);
    free(W);
    cl_model_free(full);
    cl_model_free(clamp);
}

Test(type2, clamp_drops_compressive_transverse_term)
{
    clamp_case("type2.kb=5e-6", (double[3]){0.9, 0.2, 0.1}, BR_FB);
    clamp_case("type2.kb=0.1", (double[3]){0.996, 0.03, -0.02}, BR_CB);
}

Test(type2, enabled_switch)
{
    cl_model *on = FD_MODEL("cloth.n=3", "pins.at=");
    cl_model *off = FD_MODEL("cloth.n=3", "pins.at=", "type2.enabled=false");
    cr_assert(fd_has_term(on, "type2"));
    cr_assert(!fd_has_term(off, "type2"));
    cl_model_free(on);
    cl_model_free(off);
}
