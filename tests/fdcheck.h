/* Shared helpers of the force-model verification tests (docs/architecture.md,
 * "Checks every force term passes"): models set up through the config API,
 * full-particle evaluation, dense Jacobians from the block pattern, central
 * finite differences of forces and energies, random rigid motions, an
 * independent reference of the Choi-Ko Type2 buckling law, and the exact-zero
 * rest-state check of the pair terms.  Header only (static inline), included by
 * tests/test_*.c after <criterion/criterion.h>.
 *
 * Conventions: a state is the full-particle arrays x, v (3*np, pinned
 * particles included) as cl_model_eval_full / cl_model_jacobian_full take
 * them; dense matrices are n x n row-major with n = 3*np and
 * J[r*n + c] = df_r/dz_c (z = x or v).
 *
 * Set CLOTHODE_FD_VERBOSE=1 to print every measured error (FDREPORT lines
 * on stderr). */
#ifndef CL_TESTS_FDCHECK_H
#define CL_TESTS_FDCHECK_H

#include <criterion/criterion.h>

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/config.h"
#include "model/cloth.h"
#include "system/model.h"
#include "model/pairs.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- reporting ------------------------------------------------------- */

static inline void fd_report(const char *what, double value)
{
    const char *v = getenv("CLOTHODE_FD_VERBOSE");
    if (v && *v && strcmp(v, "0"))
        fprintf(stderr, "FDREPORT %-48s %.3e\n", what, value);
}

/* ---- deterministic random numbers (splitmix64) ----------------------- */

typedef struct {
    uint64_t s;
} fd_rng;

static inline uint64_t fd_rng_next(fd_rng *r)
{
    uint64_t z = (r->s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* Uniform in [-1, 1). */
static inline double fd_rand(fd_rng *r)
{
    return (double)(fd_rng_next(r) >> 11) * 0x1.0p-52 - 1.0;
}

/* ---- allocation -------------------------------------------------------- */

static inline double *fd_vec(size_t n)
{
    double *p = calloc(n ? n : 1, sizeof *p);
    cr_assert_not_null(p, "out of memory in a test");
    return p;
}

/* ---- models from "section.key=value" settings ------------------------ */

#define FD_SETS(...) ((const char *const[]){__VA_ARGS__, NULL})

/* Build a model from NULL-terminated settings; also rejects settings that no
 * term asked for (so that a misspelt key in a test cannot pass silently). */
static inline cl_status fd_model_try(const char *const *sets, cl_model **m,
                                     cl_error *err)
{
    cl_config *cfg = cl_config_alloc();
    cr_assert_not_null(cfg);
    cl_status rc = CL_OK;
    *m = NULL;
    for (size_t k = 0; sets[k] && rc == CL_OK; k++)
        rc = cl_config_set(cfg, sets[k], err);
    if (rc == CL_OK)
        rc = cl_model_create(cfg, m, err);
    if (rc == CL_OK && (rc = cl_config_check_unused(cfg, err)) != CL_OK) {
        cl_model_free(*m);
        *m = NULL;
    }
    cl_config_free(cfg);
    return rc;
}

static inline cl_model *fd_model(const char *const *sets)
{
    cl_model *m = NULL;
    cl_error err;
    memset(&err, 0, sizeof err);
    cl_status rc = fd_model_try(sets, &m, &err);
    cr_assert_eq(rc, CL_OK, "model setup failed: %s", err.msg);
    cr_assert_not_null(m);
    return m;
}

#define FD_MODEL(...) fd_model(FD_SETS(__VA_ARGS__))

/* 3 * (all particles). */
static inline size_t fd_n(const cl_model *m)
{
    return 3 * cl_model_cloth(m)->np;
}

/* Whether the model runs a term of this name. */
static inline bool fd_has_term(const cl_model *m, const char *name)
{
    const char *const *names;
    size_t n = cl_model_terms(m, &names);
    for (size_t k = 0; k < n; k++)
        if (!strcmp(names[k], name))
            return true;
    return false;
}

/* ---- states ------------------------------------------------------------ */

/* x_p = A X0_p + jitter: in-plane (x, z) components get jit_plane * h *
 * U(-1, 1), the normal (y) component jit_normal * h * U(-1, 1), with h the
 * smaller rest spacing.  A (3x3 row-major) may be NULL (identity). */
static inline void fd_deform(const cl_model *m, const double A[9],
                             double jit_plane, double jit_normal, fd_rng *r,
                             double *x)
{
    const cl_cloth *c = cl_model_cloth(m);
    double h = c->hu < c->hv ? c->hu : c->hv;
    for (size_t p = 0; p < c->np; p++) {
        const double *X = c->X0 + 3 * p;
        for (int i = 0; i < 3; i++) {
            double y = X[i];
            if (A)
                y = A[3 * i] * X[0] + A[3 * i + 1] * X[1] + A[3 * i + 2] * X[2];
            double jit = (i == 1 ? jit_normal : jit_plane);
            x[3 * p + i] = y + (jit != 0.0 ? jit * h * fd_rand(r) : 0.0);
        }
    }
}

/* Diagonal in-plane scaling: x by sx, z by sz (the cloth lies in x-z). */
static inline void fd_scale(double sx, double sz, double A[9])
{
    for (int i = 0; i < 9; i++)
        A[i] = 0.0;
    A[0] = sx;
    A[4] = 1.0;
    A[8] = sz;
}

static inline void fd_random_vec(fd_rng *r, double scale, double *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        v[i] = scale * fd_rand(r);
}

/* ---- evaluation -------------------------------------------------------- */

static inline cl_energy fd_eval(cl_model *m, const double *x, const double *v,
                                double *f)
{
    cl_energy e;
    cl_error err;
    memset(&e, 0, sizeof e);
    memset(&err, 0, sizeof err);
    cl_status rc = cl_model_eval_full(m, 0.0, x, v, f, &e, &err);
    cr_assert_eq(rc, CL_OK, "cl_model_eval_full: %s", err.msg);
    return e;
}

/* Energy of the term named `name` (must be active). */
static inline double fd_term_energy(const cl_energy *e, const char *name)
{
    for (size_t k = 0; k < e->nterm; k++)
        if (e->name[k] && !strcmp(e->name[k], name))
            return e->value[k];
    cr_assert_fail("no energy column \"%s\"", name);
    return NAN;
}

/* Dense df/dx and df/dv (n x n) from cl_model_jacobian_full. */
static inline void fd_jacobian(cl_model *m, const double *x, const double *v,
                               double *Jx, double *Jv)
{
    size_t n = fd_n(m);
    cl_bpattern pat;
    double *bx = NULL, *bv = NULL;
    cl_error err;
    memset(&err, 0, sizeof err);
    cl_status rc = cl_model_jacobian_full(m, 0.0, x, v, &pat, &bx, &bv, &err);
    cr_assert_eq(rc, CL_OK, "cl_model_jacobian_full: %s", err.msg);
    cr_assert_eq(pat.nb, n / 3);
    memset(Jx, 0, n * n * sizeof *Jx);
    memset(Jv, 0, n * n * sizeof *Jv);
    for (size_t bi = 0; bi < pat.nb; bi++)
        for (size_t k = pat.rowptr[bi]; k < pat.rowptr[bi + 1]; k++) {
            size_t bj = pat.col[k];
            for (size_t r = 0; r < 3; r++)
                for (size_t c = 0; c < 3; c++) {
                    Jx[(3 * bi + r) * n + 3 * bj + c] = bx[9 * k + 3 * r + c];
                    Jv[(3 * bi + r) * n + 3 * bj + c] = bv[9 * k + 3 * r + c];
                }
        }
    free(bx);
    free(bv);
    cl_bpattern_free(&pat);
}

/* Central differences of the full force w.r.t. x (wrt_v false) or v, step h
 * (the actual step (z+h) - (z-h) is used); with richardson, the h and h/2
 * quotients are combined to O(h^4). */
static inline void fd_jacobian_fd(cl_model *m, const double *x,
                                  const double *v, bool wrt_v, double h,
                                  bool richardson, double *J)
{
    size_t n = fd_n(m);
    double *xx = fd_vec(n), *vv = fd_vec(n), *fp = fd_vec(n), *fm = fd_vec(n);
    memcpy(xx, x, n * sizeof *x);
    memcpy(vv, v, n * sizeof *v);
    double *z = wrt_v ? vv : xx;
    for (size_t c = 0; c < n; c++) {
        double z0 = z[c];
        for (int level = 0; level < (richardson ? 2 : 1); level++) {
            double hh = level ? 0.5 * h : h;
            double zp = z0 + hh, zm = z0 - hh;
            z[c] = zp;
            fd_eval(m, xx, vv, fp);
            z[c] = zm;
            fd_eval(m, xx, vv, fm);
            z[c] = z0;
            for (size_t r = 0; r < n; r++) {
                double q = (fp[r] - fm[r]) / (zp - zm);
                if (level == 0)
                    J[r * n + c] = q;
                else
                    J[r * n + c] = (4.0 * q - J[r * n + c]) / 3.0;
            }
        }
    }
    free(xx);
    free(vv);
    free(fp);
    free(fm);
}

static inline double fd_maxabs(const double *a, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++)
        if (fabs(a[i]) > m)
            m = fabs(a[i]);
    return m;
}

/* max |a - b| / max |b| (max |a - b| if b == 0). */
static inline double fd_relerr(const double *a, const double *b, size_t n)
{
    double d = 0.0;
    for (size_t i = 0; i < n; i++)
        if (fabs(a[i] - b[i]) > d || isnan(a[i] - b[i]))
            d = isnan(a[i] - b[i]) ? INFINITY : fabs(a[i] - b[i]);
    double s = fd_maxabs(b, n);
    return s > 0 ? d / s : d;
}

/* Jacobian (x and v) vs central differences of the model's full force at
 * (x, v); returns the larger relative error, each also reported.  hx, hv:
 * steps; richardson as in fd_jacobian_fd.  The analytic Jacobian must not be
 * all zero unless allow_zero (then the error is absolute). */
static inline double fd_check_jacobian(cl_model *m, const double *x,
                                       const double *v, double hx, double hv,
                                       bool richardson, const char *label,
                                       double *errx_out, double *errv_out)
{
    size_t n = fd_n(m);
    double *Jx = fd_vec(n * n), *Jv = fd_vec(n * n), *Fx = fd_vec(n * n),
           *Fv = fd_vec(n * n);
    fd_jacobian(m, x, v, Jx, Jv);
    fd_jacobian_fd(m, x, v, false, hx, richardson, Fx);
    fd_jacobian_fd(m, x, v, true, hv, richardson, Fv);
    /* Relative to the analytic matrix; for an all-zero analytic matrix the
     * finite differences must vanish (absolute). */
    double ex = fd_relerr(Fx, Jx, n * n), ev = fd_relerr(Fv, Jv, n * n);
    char buf[160];
    snprintf(buf, sizeof buf, "%s df/dx", label);
    fd_report(buf, ex);
    snprintf(buf, sizeof buf, "%s df/dv", label);
    fd_report(buf, ev);
    if (errx_out)
        *errx_out = ex;
    if (errv_out)
        *errv_out = ev;
    free(Jx);
    free(Jv);
    free(Fx);
    free(Fv);
    return ex > ev ? ex : ev;
}

/* max_c |f_c + dE/dx_c| / max |f|, E = e.potential (all active potential
 * terms), dE/dx by central differences with step h. */
static inline double fd_check_energy(cl_model *m, const double *x,
                                     const double *v, double h,
                                     const char *label)
{
    size_t n = fd_n(m);
    double *xx = fd_vec(n), *f = fd_vec(n), *w = fd_vec(n);
    memcpy(xx, x, n * sizeof *x);
    fd_eval(m, x, v, f);
    double d = 0.0;
    for (size_t c = 0; c < n; c++) {
        double z0 = xx[c], zp = z0 + h, zm = z0 - h;
        xx[c] = zp;
        double ep = fd_eval(m, xx, v, w).potential;
        xx[c] = zm;
        double em = fd_eval(m, xx, v, w).potential;
        xx[c] = z0;
        double g = -(ep - em) / (zp - zm);
        if (!(fabs(g - f[c]) <= d))
            d = fabs(g - f[c]);
    }
    double s = fd_maxabs(f, n);
    cr_assert_gt(s, 0.0, "%s: the force is zero, nothing to check", label);
    char buf[160];
    snprintf(buf, sizeof buf, "%s f=-dE/dx", label);
    fd_report(buf, d / s);
    free(xx);
    free(f);
    free(w);
    return d / s;
}

/* Structure of df/dx of a conservative pair term: symmetric (a Hessian) and
 * every block row summing to zero (translation invariance).  Returns the
 * larger deviation relative to max |J|. */
static inline double fd_check_structure(cl_model *m, const double *x,
                                        const double *v)
{
    size_t n = fd_n(m);
    double *Jx = fd_vec(n * n), *Jv = fd_vec(n * n);
    fd_jacobian(m, x, v, Jx, Jv);
    double scale = fd_maxabs(Jx, n * n), asym = 0.0, rowsum = 0.0;
    for (size_t r = 0; r < n; r++) {
        double sum[3] = {0.0, 0.0, 0.0};
        for (size_t c = 0; c < n; c++) {
            asym = fmax(asym, fabs(Jx[r * n + c] - Jx[c * n + r]));
            sum[c % 3] += Jx[r * n + c];
        }
        for (int i = 0; i < 3; i++)
            rowsum = fmax(rowsum, fabs(sum[i]));
    }
    free(Jx);
    free(Jv);
    cr_assert_gt(scale, 0.0);
    return fmax(asym, rowsum) / scale;
}

/* ---- rigid motions ----------------------------------------------------- */

/* Rotation matrix from a random unit quaternion (row-major). */
static inline void fd_rotation(fd_rng *r, double R[9])
{
    double q[4], nq;
    do {
        for (int i = 0; i < 4; i++)
            q[i] = fd_rand(r);
        nq = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    } while (nq < 0.1 || nq > 1.0);
    double w = q[0] / nq, a = q[1] / nq, b = q[2] / nq, c = q[3] / nq;
    R[0] = 1 - 2 * (b * b + c * c);
    R[1] = 2 * (a * b - c * w);
    R[2] = 2 * (a * c + b * w);
    R[3] = 2 * (a * b + c * w);
    R[4] = 1 - 2 * (a * a + c * c);
    R[5] = 2 * (b * c - a * w);
    R[6] = 2 * (a * c - b * w);
    R[7] = 2 * (b * c + a * w);
    R[8] = 1 - 2 * (a * a + b * b);
}

/* y_p = R x_p + c for np points (c may be NULL). */
static inline void fd_apply(const double R[9], const double c[3],
                            const double *x, double *y, size_t np)
{
    for (size_t p = 0; p < np; p++) {
        const double *xp = x + 3 * p;
        for (int i = 0; i < 3; i++)
            y[3 * p + i] = R[3 * i] * xp[0] + R[3 * i + 1] * xp[1] +
                           R[3 * i + 2] * xp[2] + (c ? c[i] : 0.0);
    }
}

/* Rigid-motion check: forces at (R x + c, R v + w) against R f(x, v),
 * potential energies against those at (x, v), and the dense Jacobians
 * against R J R^T blockwise.  Returns the worst relative deviation. */
static inline double fd_check_rigid(cl_model *m, const double *x,
                                    const double *v, const double R[9],
                                    const double c[3], const double w[3],
                                    const char *label)
{
    size_t n = fd_n(m), np = n / 3;
    double *y = fd_vec(n), *u = fd_vec(n), *f = fd_vec(n), *g = fd_vec(n),
           *Rf = fd_vec(n), *keep = fd_vec(cl_model_potentials(m) + 1);
    fd_apply(R, c, x, y, np);
    fd_apply(R, w, v, u, np);
    cl_energy e0, e = fd_eval(m, x, v, f);
    cl_energy_keep(&e0, &e, keep);
    cl_energy e1 = fd_eval(m, y, u, g);
    fd_apply(R, NULL, f, Rf, np);
    double ef = fd_relerr(g, Rf, n);
    double ee = 0.0;
    for (size_t k = 0; k < e0.nterm; k++) {
        double scale = fabs(e0.value[k]) > 1e-300 ? fabs(e0.value[k]) : 1.0;
        double d = fabs(e1.value[k] - e0.value[k]) / scale;
        if (d > ee)
            ee = d;
    }
    double pe = fabs(e1.power_diss - e0.power_diss) /
                (fabs(e0.power_diss) > 0 ? fabs(e0.power_diss) : 1.0);
    if (pe > ee)
        ee = pe;
    /* Jacobians: J(y) = (R (x) I) J(x) (R^T (x) I), block by block. */
    double *Jx = fd_vec(n * n), *Jv = fd_vec(n * n), *Kx = fd_vec(n * n),
           *Kv = fd_vec(n * n), *T = fd_vec(n * n);
    fd_jacobian(m, x, v, Jx, Jv);
    fd_jacobian(m, y, u, Kx, Kv);
    double ej = 0.0;
    for (int which = 0; which < 2; which++) {
        const double *J = which ? Jv : Jx, *K = which ? Kv : Kx;
        for (size_t bi = 0; bi < np; bi++)
            for (size_t bj = 0; bj < np; bj++)
                for (int r = 0; r < 3; r++)
                    for (int s = 0; s < 3; s++) {
                        double acc = 0.0;
                        for (int a = 0; a < 3; a++)
                            for (int b = 0; b < 3; b++)
                                acc += R[3 * r + a] *
                                       J[(3 * bi + a) * n + 3 * bj + b] *
                                       R[3 * s + b];
                        T[(3 * bi + r) * n + 3 * bj + s] = acc;
                    }
        double d = fd_relerr(K, T, n * n);
        if (d > ej)
            ej = d;
    }
    char buf[160];
    snprintf(buf, sizeof buf, "%s rigid: force", label);
    fd_report(buf, ef);
    snprintf(buf, sizeof buf, "%s rigid: energy", label);
    fd_report(buf, ee);
    snprintf(buf, sizeof buf, "%s rigid: jacobian", label);
    fd_report(buf, ej);
    free(y);
    free(u);
    free(f);
    free(g);
    free(Rf);
    free(keep);
    free(Jx);
    free(Jv);
    free(Kx);
    free(Kv);
    free(T);
    double worst = ef > ee ? ef : ee;
    return worst > ej ? worst : ej;
}

/* ---- Newton's third law ------------------------------------------------ */

/* |sum_p f_p| (max over components) relative to sum_p |f_p|; *torque_out (if
 * not NULL) likewise for sum_p x_p x f_p relative to sum_p |x_p| |f_p|. */
static inline double fd_net_force(const double *x, const double *f,
                                  size_t np, double *torque_out)
{
    double F[3] = {0, 0, 0}, T[3] = {0, 0, 0}, sf = 0.0, st = 0.0;
    for (size_t p = 0; p < np; p++) {
        const double *xp = x + 3 * p, *fp = f + 3 * p;
        double t[3] = {xp[1] * fp[2] - xp[2] * fp[1],
                       xp[2] * fp[0] - xp[0] * fp[2],
                       xp[0] * fp[1] - xp[1] * fp[0]};
        double nf = sqrt(fp[0] * fp[0] + fp[1] * fp[1] + fp[2] * fp[2]);
        double nx = sqrt(xp[0] * xp[0] + xp[1] * xp[1] + xp[2] * xp[2]);
        for (int i = 0; i < 3; i++) {
            F[i] += fp[i];
            T[i] += t[i];
        }
        sf += nf;
        st += nf * nx;
    }
    double ef = fmax(fabs(F[0]), fmax(fabs(F[1]), fabs(F[2])));
    double et = fmax(fabs(T[0]), fmax(fabs(T[1]), fabs(T[2])));
    cr_assert_gt(sf, 0.0, "net force check on a zero force");
    if (torque_out)
        *torque_out = st > 0 ? et / st : et;
    return ef / sf;
}

/* ---- independent reference of the Type2 buckling law (docs/model.md 3.2) - */

/* g(t) = 1 - sin(t)/t (series below 0.5). */
static inline double fd_g(double t)
{
    if (t < 0.5) {
        double s = t * t, term = s / 6.0, sum = 0.0;
        for (int k = 1; k < 12; k++) {
            sum += term;
            term *= -s / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
        }
        return sum;
    }
    return 1.0 - sin(t) / t;
}

/* t in [0, pi] with sin(t)/t = d/L, by bisection on g(t) = (L - d)/L. */
static inline double fd_asinc_ref(double d, double L)
{
    double e = (L - d) / L, lo = 0.0, hi = M_PI;
    for (int it = 0; it < 2000 && hi - lo > 0.0; it++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
            break;
        if (fd_g(mid) < e)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* f_b(d) = kb kappa^2 / (cos(kappa L/2) - sinc(kappa L/2)), straight from
 * the formula (loses digits near d = L: use for t > ~0.05). */
static inline double fd_fb_ref(double kb, double L, double d)
{
    double t = fd_asinc_ref(d, L), kappa = 2.0 * t / L;
    return kb * kappa * kappa / (cos(t) - sin(t) / t);
}

/* Type2 compressive law s = max(f_b, cb (d - L)). */
static inline double fd_type2_ref(double kb, double cb, double L, double d)
{
    double fb = fd_fb_ref(kb, L, d), lin = cb * (d - L);
    return fb > lin ? fb : lin;
}

/* The pair term `term` alone (`off` disables the other pair term; no
 * damping, gravity or pins) at rest on three grids of awkward spacings:
 * every pair sits exactly on d = L (rest lengths computed with the same
 * expression), so the force and the term's energy are exactly zero. */
static inline void fd_expect_rest_exactly_zero(const char *term,
                                               const char *off)
{
    static const char *const grids[][4] = {
        {"cloth.nu=7", "cloth.nv=7", "cloth.su=0.7", "cloth.sv=0.7"},
        {"cloth.nu=5", "cloth.nv=9", "cloth.su=1.3", "cloth.sv=0.37"},
        {"cloth.nu=11", "cloth.nv=3", "cloth.su=3.1", "cloth.sv=0.1"},
    };
    for (size_t g = 0; g < sizeof grids / sizeof grids[0]; g++) {
        cl_model *m = FD_MODEL(off, "damping.kd=0", "gravity.g=0,0,0",
                               "pins.at=", grids[g][0], grids[g][1],
                               grids[g][2], grids[g][3]);
        size_t n = fd_n(m);
        double *v = fd_vec(n), *f = fd_vec(n);
        cl_energy e = fd_eval(m, cl_model_cloth(m)->X0, v, f);
        cr_assert_eq(fd_maxabs(f, n), 0.0, "grid %zu: force at rest", g);
        cr_assert_eq(fd_term_energy(&e, term), 0.0, "grid %zu: %s energy",
                     g, term);
        free(v);
        free(f);
        cl_model_free(m);
    }
}

#endif
