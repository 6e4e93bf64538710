/* Choi-Ko Type2 interaction: buckling of interlaced pairs (Jiao,
 * eqs. 8-13; docs/model.md 3.2).  Pairs (i+-2, j), (i, j+-2), (i+-2, j+-2).
 *
 * Compression, d < L: the pair is taken to bend into a circular arc of
 * length L and chord d, with curvature kappa = (2/L) asinc(d/L) (eq. 8).
 * Writing t = kappa L / 2,
 *     f_b(d) = kb kappa^2 / (cos t - sinc t) = (4 kb / L^2) t^2 / D(t)  (9)
 * with D(t) = cos t - sinc t = (1 - sinc t) - 2 sin^2(t/2) (no cancellation).
 * f_b -> -12 kb/L^2 as d -> L and -4 pi^2 kb/L^2 as d -> 0, and
 * f_b <= -12 kb/L^2.  Imperfection (eq. 10): s(d) = max(f_b(d), cb (d - L)).
 * s'(d) = (4 kb/L^2) G'(t) dt/dd, G = t^2/D, dt/dd = -1/(L d(1-sinc)/dt).
 * Energy of the f_b branch: E_b = kb L kappa^2 / 2 = 2 kb t^2 / L
 * (dE_b/dd = f_b); the full energy integral_L^d s(r) dr is summed over the
 * branch segments, whose crossing points are found once per rest length.
 *
 * Tension, d >= L: type2.tension = spring gives ks (d - L) (ks of [type1]),
 * none gives 0 (Jiao's own code).
 *
 * Reproductions of Jiao's own code (each measurable on its own):
 *   asinc = seed-poly: t = p(d/L) with the fifth-order polynomial of Jiao,
 *     section 4.6, which fits the *normalised* inverse sinc, i.e. ~asinc/pi;
 *   fb_sinc = normalised: D(t) = cos t - sin(pi t)/(pi t) (numpy's sinc).
 * With either, f_b is no longer the gradient of E_b; the energy is then
 * integrated numerically (GSL QAGS) from the force.
 *
 * INI section [type2]: enabled (true), kb (N m^2), cb (N/m), tension
 * (spring|none), asinc (exact|seed-poly), fb_sinc (exact|normalised). */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>
#include <math.h>
#include <stdlib.h>

#include "forces/asinc.h"
#include "forces/choiko.h"
#include "forces/pairterm.h"
#include "model/cloth_read.h"

#define CROSS_SAMPLES 512
#define MAX_CROSS 8
#define QUAD_LIMIT 200
#define CHEB_PIECES 8   /* G(e) on [j/8, (j+1)/8], j = 0..7 */
#define CHEB_TERMS 16   /* Chebyshev coefficients per piece */

typedef enum { TENSION_SPRING, TENSION_NONE } tension_kind;
typedef enum { ASINC_EXACT, ASINC_SEED_POLY } asinc_kind;
typedef enum { FBSINC_EXACT, FBSINC_NORMALISED } fbsinc_kind;

typedef struct {
    double L;
    int ncross;
    double cross[MAX_CROSS]; /* crossings of f_b and cb (d - L), ascending */
} rest_length;

typedef struct {
    cl_pairterm pt; /* first member: the pairterm hooks use it */
    double kb, cb, ks;
    tension_kind tension;
    asinc_kind asinc;
    fbsinc_kind fbsinc;
    double poly[6];
    size_t nlen;
    rest_length *len;      /* distinct rest lengths */
    size_t *len_of;        /* pair -> index into len */
    gsl_integration_workspace *quad;
    /* The exact model's G(e) = t^2 / D(t) by pieces (buckling_cheb) */
    double cheb[CHEB_PIECES][CHEB_TERMS];
    double *fbc;           /* per pair: 4 kb/L^2 (scale_setup) */
} type2_state;

/* The exact model: the exact inverse sinc and exact sinc in f_b, the
 * only one whose f_b is bounded by -12 kb/L^2 and tabled by pieces. */
static inline bool exact_model(const type2_state *st)
{
    return st->asinc == ASINC_EXACT && st->fbsinc == FBSINC_EXACT;
}

/* t = kappa L/2 at distance d < L, and dt/dd. */
static double curvature_t(const type2_state *st, double d, double L,
                          double *dt_dd)
{
    if (st->asinc == ASINC_SEED_POLY) {
        double dp;
        double t = cl_seed_poly_eval(st->poly, d / L, &dp);
        *dt_dd = dp / L;
        return t;
    }
    double t = cl_asinc_1m((L - d) / L);
    *dt_dd = -1.0 / (L * cl_one_minus_sinc_deriv(t));
    return t;
}

/* D(t) = cos t - S(t), S the chosen sinc, and D'(t). */
static double denominator(const type2_state *st, double t, double *dD)
{
    double h = sin(0.5 * t);
    if (st->fbsinc == FBSINC_NORMALISED) {
        *dD = M_PI * cl_one_minus_sinc_deriv(M_PI * t) - sin(t);
        return cl_one_minus_sinc(M_PI * t) - 2.0 * h * h;
    }
    *dD = cl_one_minus_sinc_deriv(t) - sin(t);
    return cl_one_minus_sinc(t) - 2.0 * h * h;
}

/* N(t) = 2 t D - t^2 D' for D(t) = cos t - sinc(a t) (a = 1: exact, a = pi:
 * normalised).  Its t^3 terms cancel, so the direct form loses ~10 eps/t^2
 * relative (df_b/dd wrong in the 5th digit at t ~ 1e-5).  For |t| < 0.5 it
 * is summed from D = sum_k d_k t^2k, d_k = (-1)^(k+1) (a^2k/(2k+1)! -
 * 1/(2k)!), as N = sum_{k>=2} (2 - 2k) d_k t^(2k+1). */
static double numerator_series(double t, double a)
{
    double s = t * t, A = a * a * s / 6.0, B = 0.5 * s, sum = 0.0;
    for (int k = 1; k < 24; k++) {
        if (k >= 2) {
            double term = (2.0 - 2.0 * k) * (k % 2 ? A - B : B - A);
            sum += term;
            if (fabs(term) <= 1e-17 * fabs(sum))
                break;
        }
        A *= a * a * s / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
        B *= s / ((2.0 * k + 1.0) * (2.0 * k + 2.0));
    }
    return sum * t;
}

/* The factor 4 kb/L^2 of f_b (eq. 9); exact f_b never exceeds -3 times
 * it, the bound above which cb (d - L) wins. */
static inline double buckling_scale(double kb, double L)
{
    return 4.0 * kb / (L * L);
}

/* f_b(d) and, if dfb is not NULL, df_b/dd (eq. 9 and its derivative). */
static double buckling_force(const type2_state *st, double d, double L,
                             double *dfb)
{
    double dt_dd, t = curvature_t(st, d, L, &dt_dd);
    double c = buckling_scale(st->kb, L);
    if (fabs(t) < 1e-8) {
        /* G(t) = t^2/D(t) is even with G(0) = 1/(D''(0)/2). */
        double d2 = st->fbsinc == FBSINC_NORMALISED
                        ? M_PI * M_PI / 6.0 - 0.5 : -1.0 / 3.0;
        if (dfb)
            *dfb = 0.0;
        return c / d2;
    }
    double dD, D = denominator(st, t, &dD);
    if (!dfb)
        return c * (t * t / D);
    double N = fabs(t) < 0.5
                   ? numerator_series(t, st->fbsinc == FBSINC_NORMALISED
                                             ? M_PI : 1.0)
                   : 2.0 * t * D - t * t * dD;
    double G = t * t / D, dG = N / (D * D);
    *dfb = c * dG * dt_dd;
    return c * G;
}

/* The compressive law s = max(f_b, cb (d - L)) and s' (eq. 10); s' only
 * if want_ds (else *ds is left as it is). */
static void compression_law(const type2_state *st, double d, double L,
                            bool want_ds, double *s, double *ds)
{
    double lin = st->cb * (d - L);
    /* Exact f_b never exceeds -12 kb/L^2: skip asinc where cb wins. */
    if (exact_model(st) && lin >= -3.0 * buckling_scale(st->kb, L)) {
        *s = lin;
        *ds = st->cb;
        return;
    }
    double dfb = 0.0, fb = buckling_force(st, d, L, want_ds ? &dfb : NULL);
    if (lin >= fb) {
        *s = lin;
        *ds = st->cb;
    } else {
        *s = fb;
        *ds = dfb;
    }
}

static double fb_only(double d, void *params)
{
    const type2_state *st = ((void **)params)[0];
    double L = *(const double *)((void **)params)[1], dfb;
    return buckling_force(st, d, L, &dfb);
}

static double cross_fn(double d, void *params)
{
    const type2_state *st = ((void **)params)[0];
    double L = *(const double *)((void **)params)[1];
    return st->cb * (d - L) - fb_only(d, params);
}

/* Integral of f_b over [a, b]: closed form for the exact model, else QAGS. */
static double fb_integral(type2_state *st, double a, double b, double L)
{
    if (exact_model(st)) {
        double dt, ta = curvature_t(st, a, L, &dt);
        double tb = curvature_t(st, b, L, &dt);
        return 2.0 * st->kb * (tb * tb - ta * ta) / L;
    }
    void *par[2] = {st, &L};
    gsl_function F = {fb_only, par};
    double val, abserr;
    int status = gsl_integration_qags(&F, a, b, 0.0, 1e-12, QUAD_LIMIT,
                                      st->quad, &val, &abserr);
    /* A failed quadrature (e.g. divergent: with fb_sinc = normalised, f_b
     * has a pole near d = 0.578 L) gives no energy rather than a wrong one;
     * the model then reports a non-finite energy. */
    if (status != GSL_SUCCESS && !(abserr <= 1e-9 * fabs(val)))
        return NAN;
    return val;
}

/* integral_L^d s(r) dr for d < L, segment by segment between crossings. */
static double compression_energy(type2_state *st, const rest_length *rl,
                                 double d)
{
    double L = rl->L, e = 0.0, hi = L;
    for (int k = rl->ncross - 1; k >= -1; k--) {
        double lo = k >= 0 ? rl->cross[k] * L : d;
        if (lo < d)
            lo = d;
        if (lo >= hi)
            continue;
        double s, ds, mid = 0.5 * (lo + hi);
        compression_law(st, mid, L, false, &s, &ds);
        if (s == st->cb * (mid - L))
            e -= 0.5 * st->cb * ((hi - L) * (hi - L) - (lo - L) * (lo - L));
        else
            e -= fb_integral(st, lo, hi, L);
        hi = lo;
        if (lo <= d)
            break;
    }
    return e;
}

static void type2_law(const void *params, size_t k, double d, double L,
                      bool want_energy, bool want_ds, cl_pairlaw *out)
{
    type2_state *st = (type2_state *)params;
    out->e = 0.0;
    if (d >= L) { /* the rest state d == L takes this branch */
        double ks = st->tension == TENSION_SPRING ? st->ks : 0.0;
        out->s = ks * (d - L);
        out->ds = ks;
        if (want_energy)
            out->e = 0.5 * ks * (d - L) * (d - L);
        return;
    }
    compression_law(st, d, L, want_ds, &out->s, &out->ds);
    if (want_energy)
        out->e = compression_energy(st, &st->len[st->len_of[k]], d);
}

/* G(e) = t^2 / D(t) at t = asinc_1m(e) by the scalar functions (exact
 * model): f_b = (4 kb / L^2) G (eq. 9) with e = (L - d) / L. */
static double buckling_g(const type2_state *st, double e)
{
    double t = cl_asinc_1m(e), dD;
    if (fabs(t) < 1e-8)
        return -3.0; /* G(0) = 1 / (D''(0) / 2), D''(0) = -2/3 */
    return t * t / denominator(st, t, &dD);
}

/* Chebyshev interpolation of G on each piece [j/P, (j+1)/P] of e in
 * [0, 1] (P = CHEB_PIECES) at the CHEB_TERMS Chebyshev points of the
 * first kind (Trefethen, "Approximation Theory and Approximation
 * Practice", ch. 3 and 8).  G is analytic on [0, 1]: its nearest
 * singularity is at e = 1.217 (t = 4.493, where g'(t) and D(t) vanish),
 * so the last piece's coefficients fall by a factor of about 9 per
 * degree and 16 terms leave an error below the scalar path's rounding
 * (tests/test_type2.c: within 3.3e-15 relative of it over [0, 1]). */
static void build_cheb(type2_state *st)
{
    const int N = CHEB_TERMS;
    for (int j = 0; j < CHEB_PIECES; j++) {
        double mid = (j + 0.5) / CHEB_PIECES, half = 0.5 / CHEB_PIECES;
        double g[CHEB_TERMS];
        for (int m = 0; m < N; m++)
            g[m] = buckling_g(st, mid + half * cos(M_PI * (m + 0.5) / N));
        for (int k = 0; k < N; k++) {
            long double c = 0.0L;
            for (int m = 0; m < N; m++)
                c += (long double)g[m] * cos(M_PI * k * (m + 0.5) / N);
            st->cheb[j][k] = (double)(c * (k ? 2.0L : 1.0L) / N);
        }
    }
}

/* Per pair the factor 4 kb/L^2 of f_b, formed once as the scalar law
 * forms it (the bound of linear_branches, and exact_max's factor). */
static cl_status scale_setup(type2_state *st, cl_error *err)
{
    const cl_pairset *set = &st->pt.set;
    st->fbc = malloc((set->n + 1) * sizeof *st->fbc);
    if (!st->fbc)
        return cl_error_set(err, CL_ENOMEM, "out of memory (type2)");
    for (size_t k = 0; k < set->n; k++) {
        st->fbc[k] = buckling_scale(st->kb, set->pair[k].rest);
    }
    return CL_OK;
}

/* G at e in [0, 1] from its piece's coefficients by Clenshaw's
 * recurrence (Trefethen, ch. 3); the piece index clamped for e outside
 * (the tension lanes, whose value is not used). */
static inline double buckling_cheb(const double (*cheb)[CHEB_TERMS],
                                   double e)
{
    double u = e * CHEB_PIECES;
    int j = (int)u;
    j = j < 0 ? 0 : j > CHEB_PIECES - 1 ? CHEB_PIECES - 1 : j;
    double x = 2.0 * (u - j) - 1.0, b1 = 0.0, b2 = 0.0;
#pragma GCC unroll 16
    for (int k = CHEB_TERMS - 1; k > 0; k--) {
        double b0 = cheb[j][k] + 2.0 * x * b1 - b2;
        b2 = b1;
        b1 = b0;
    }
    return cheb[j][0] + x * b1 - b2;
}

/* The linear branches over pairs [0, m) (those of the term from k0 on):
 * s = ks (d - L) in tension (tension = spring; else 0), cb (d - L) in
 * compression, and ds = ks or cb; need[i] where the law is left to f_b:
 * every pair in compression, or with the exact model only those where
 * f_b may win, cb (d - L) < -3 (4 kb/L^2) = -12 kb/L^2 (f_b's bound,
 * eq. 9); e[i] = (L - d)/L for buckling_cheb. */
CL_PAIR_KERNEL
static void linear_branches(const type2_state *st, size_t k0, size_t m,
                            const double *d, const double *L, double *s,
                            double *ds, double *e, unsigned char *need)
{
    double ks = st->tension == TENSION_SPRING ? st->ks : 0.0;
    double cb = st->cb;
    bool exact = exact_model(st);
    const double *restrict C = st->fbc + k0;
#pragma omp simd
    for (size_t i = 0; i < m; i++) {
        double dd = d[i], l = L[i], lin = cb * (dd - l);
        bool tension = dd >= l, lin_wins = lin >= -3.0 * C[i];
        s[i] = tension ? ks * (dd - l) : lin;
        ds[i] = tension ? ks : cb;
        e[i] = (l - dd) / l;
        need[i] = !tension && !(exact && lin_wins);
    }
}

/* f_b = (4 kb/L^2) G(e) of the n pairs idx[] (buckling_cheb). */
CL_PAIR_KERNEL
static void exact_fb(const type2_state *st, size_t k0, size_t n,
                     const size_t *idx, const double *e, double *fb)
{
    const double(*cheb)[CHEB_TERMS] = st->cheb;
    const double *restrict C = st->fbc + k0;
#pragma omp simd
    for (size_t j = 0; j < n; j++)
        fb[j] = C[idx[j]] * buckling_cheb(cheb, e[idx[j]]);
}

/* The exact model's s = max(f_b, cb (d - L)) over pairs [0, m) (at most
 * CL_PAIRKERN_CHUNK) where need[i] (linear_branches: f_b may win), f_b
 * by buckling_cheb for those alone. */
static void exact_max(const type2_state *st, size_t k0, size_t m,
                      const double *e, const unsigned char *need, double *s)
{
    double fb[CL_PAIRKERN_CHUNK];
    size_t idx[CL_PAIRKERN_CHUNK], n = 0;
    for (size_t i = 0; i < m; i++) {
        idx[n] = i;
        n += need[i];
    }
    exact_fb(st, k0, n, idx, e, fb);
    for (size_t j = 0; j < n; j++)
        s[idx[j]] = s[idx[j]] >= fb[j] ? s[idx[j]] : fb[j];
}

/* Pairs [0, m) of at most CL_PAIRKERN_CHUNK: the linear branches, then
 * the pairs left to f_b, by buckling_cheb (exact model) or the scalar
 * law.  s is the same with and without ds (the Jacobian's forces are the
 * right-hand side's, bit for bit); s' of the f_b branch comes from the
 * scalar law. */
static void type2_piece(const type2_state *st, size_t k0, size_t m,
                        const double *d, const double *L, double *s,
                        double *ds)
{
    double dsw[CL_PAIRKERN_CHUNK], e[CL_PAIRKERN_CHUNK], one;
    unsigned char need[CL_PAIRKERN_CHUNK];
    bool exact = exact_model(st);
    linear_branches(st, k0, m, d, L, s, ds ? ds : dsw, e, need);
    if (exact)
        exact_max(st, k0, m, e, need, s);
    if (exact && !ds)
        return;
    for (size_t i = 0; i < m; i++)
        if (need[i])
            compression_law(st, d[i], L[i], ds != NULL, exact ? &one : &s[i],
                            ds ? &ds[i] : &dsw[i]);
}

/* The law over pairs [k0, k0 + m) (cl_pairlaw_batch_fn). */
static void type2_batch(const void *params, size_t k0, size_t m,
                        const double *d, const double *L, double *s,
                        double *ds)
{
    for (size_t i = 0; i < m; i += CL_PAIRKERN_CHUNK) {
        size_t p = m - i < CL_PAIRKERN_CHUNK ? m - i : CL_PAIRKERN_CHUNK;
        type2_piece(params, k0 + i, p, d + i, L + k0 + i, s + i,
                    ds ? ds + i : NULL);
    }
}

/* Sign changes of cb (d - L) - f_b(d) on [0, L], refined by Brent. */
static cl_status find_crossings(type2_state *st, rest_length *rl,
                                cl_error *err)
{
    void *par[2] = {st, &rl->L};
    gsl_function F = {cross_fn, par};
    gsl_root_fsolver *rs = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!rs)
        return cl_error_set(err, CL_ENOMEM, "out of memory (root solver)");
    rl->ncross = 0;
    double L = rl->L, a = 0.0, fa = cross_fn(0.0, par);
    for (int i = 1; i <= CROSS_SAMPLES; i++) {
        double b = L * i / CROSS_SAMPLES, fbv = cross_fn(b, par);
        if ((fa < 0) != (fbv < 0) && rl->ncross < MAX_CROSS) {
            int rc = gsl_root_fsolver_set(rs, &F, a, b);
            double lo = a, hi = b;
            for (int it = 0; !rc && it < 200 && hi - lo > 1e-15 * L; it++) {
                rc = gsl_root_fsolver_iterate(rs);
                lo = gsl_root_fsolver_x_lower(rs);
                hi = gsl_root_fsolver_x_upper(rs);
            }
            if (rc) {
                gsl_root_fsolver_free(rs);
                return cl_error_set(err, CL_ESOLVER, "[type2] the crossing "
                                    "of the buckling law with cb (d - L) in "
                                    "[%g, %g] L = %g: GSL's Brent solver "
                                    "failed (%s)", a / L, b / L, L,
                                    gsl_strerror(rc));
            }
            rl->cross[rl->ncross++] = gsl_root_fsolver_root(rs) / L;
        }
        a = b;
        fa = fbv;
    }
    gsl_root_fsolver_free(rs);
    return CL_OK;
}

/* Distinct rest lengths (to 1e-12 relative) and their crossings. */
static cl_status build_lengths(type2_state *st, cl_error *err)
{
    const cl_pairset *set = &st->pt.set;
    st->len = malloc((set->n + 1) * sizeof *st->len);
    st->len_of = malloc((set->n + 1) * sizeof *st->len_of);
    if (!st->len || !st->len_of)
        return cl_error_set(err, CL_ENOMEM, "out of memory (type2)");
    for (size_t k = 0; k < set->n; k++) {
        double L = set->pair[k].rest;
        size_t j = 0;
        while (j < st->nlen && fabs(st->len[j].L - L) > 1e-12 * L)
            j++;
        if (j == st->nlen) {
            st->len[j].L = L;
            cl_status rc = find_crossings(st, &st->len[j], err);
            if (rc)
                return rc;
            st->nlen++;
        }
        st->len_of[k] = j;
    }
    return CL_OK;
}

static void type2_free(void *state)
{
    type2_state *st = state;
    if (!st)
        return;
    cl_pairterm_free(&st->pt);
    free(st->len);
    free(st->len_of);
    free(st->fbc);
    if (st->quad)
        gsl_integration_workspace_free(st->quad);
    free(st);
}

static cl_status read_params(cl_config *cfg, type2_state *st, cl_error *err)
{
    static const char *const tension[] = {"spring", "none", NULL};
    static const char *const asinc[] = {"exact", "seed-poly", NULL};
    static const char *const fbsinc[] = {"exact", "normalised", NULL};
    int tk, ak, fk;
    cl_status rc;
    if ((rc = cl_choiko_ks(cfg, &st->ks, err)) ||
        (rc = cl_config_double(cfg, "type2", "kb", 5e-6, 0.0, INFINITY,
                               &st->kb, err)) ||
        (rc = cl_config_double(cfg, "type2", "cb", st->ks, 0.0, INFINITY,
                               &st->cb, err)) ||
        (rc = cl_config_choice(cfg, "type2", "tension", tension, 0, &tk,
                               err)) ||
        (rc = cl_config_choice(cfg, "type2", "asinc", asinc, 0, &ak, err)) ||
        (rc = cl_config_choice(cfg, "type2", "fb_sinc", fbsinc, 0, &fk,
                               err)))
        return rc;
    st->tension = (tension_kind)tk;
    st->asinc = (asinc_kind)ak;
    st->fbsinc = (fbsinc_kind)fk;
    return CL_OK;
}

static cl_status type2_setup(type2_state *st, const cl_cloth *cloth,
                             const cl_term_opts *opts, cl_error *err)
{
    cl_status rc;
    cl_pairset set;
    if (st->asinc == ASINC_SEED_POLY &&
        (rc = cl_seed_poly_coeffs(st->poly, err)))
        return rc;
    st->quad = gsl_integration_workspace_alloc(QUAD_LIMIT);
    if (!st->quad)
        return cl_error_set(err, CL_ENOMEM, "out of memory (quadrature)");
    if ((rc = cl_pairs_type2(cloth, &set, err)) ||
        (rc = cl_pairterm_init(&st->pt, set, type2_law, type2_batch, st,
                               opts->clamp_transverse, 1, err)) ||
        (rc = cl_pairterm_tear(&st->pt, opts->tear_cut, err)))
        return rc;
    if ((rc = scale_setup(st, err)))
        return rc;
    if (exact_model(st))
        build_cheb(st);
    return build_lengths(st, err);
}

/* The key that set the grid: nu if given, else n. */
static const char *grid_key(cl_config *cfg)
{
    return cl_config_string(cfg, "cloth", "nu", NULL) ? "nu" : "n";
}

/* Interlaced pairs span two spacings: a grid with fewer than 3 particles
 * along both sides has none, which would silently switch the term off. */
static cl_status check_grid(cl_config *cfg, const cl_cloth *cloth,
                            cl_error *err)
{
    if (cloth->nu >= 3 || cloth->nv >= 3)
        return CL_OK;
    char where[256];
    return cl_error_set(err, CL_EINVAL,
                        "%s: [cloth] grid %d x %d: Type2 (interlaced) pairs "
                        "need at least 3 particles along one side; use n >= 3 or "
                        "set type2.enabled = false",
                        cl_config_origin(cfg, "cloth", grid_key(cfg),
                                         where, sizeof where),
                        cloth->nu, cloth->nv);
}

static cl_status type2_create(cl_config *cfg, const cl_cloth *cloth,
                              const cl_term_opts *opts, void **state,
                              cl_error *err)
{
    bool enabled;
    cl_status rc;
    *state = NULL;
    if ((rc = cl_choiko_type2_enabled(cfg, &enabled, err)))
        return rc;
    type2_state *st = calloc(1, sizeof *st);
    if (!st)
        return cl_error_set(err, CL_ENOMEM, "out of memory (type2)");
    /* Parameters are read even when disabled, so that they are validated
     * and not reported as unknown keys. */
    if ((rc = read_params(cfg, st, err)) || !enabled ||
        (rc = cl_cloth_grid_only(cfg, cloth, "type2", "enabled",
                                 "Choi-Ko Type2 acts on the grid's interlaced "
                                 "pairs; a mesh cloth needs [type2] enabled = "
                                 "false", err)) ||
        (rc = check_grid(cfg, cloth, err)) ||
        (rc = type2_setup(st, cloth, opts, err))) {
        type2_free(st);
        return rc;
    }
    *state = st;
    return CL_OK;
}

const cl_term_type cl_term_type2 = {
    .name = "type2",
    .doc = "Choi-Ko Type2: buckling f_b = kb kappa^2/(cos - sinc) with "
           "imperfection max(f_b, cb (d-L)) on interlaced pairs",
    .conservative = true,
    .soft = true,
    .threads = cl_pairterm_threads,
    .create = type2_create,
    .couplings = cl_pairterm_couplings,
    .bind = cl_pairterm_bind,
    .eval = cl_pairterm_eval,
    .step_done = cl_pairterm_step_done,
    .broken = cl_pairterm_broken,
    .free = type2_free,
};
