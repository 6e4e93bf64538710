/* Small test systems with closed-form solutions, implementing cl_system by
 * hand (header-only, shared by the integrator tests).
 *
 * Oscillators: nb independent particles; every component i obeys
 *     m_i x_i'' = -k_i x_i - c_i x_i'
 * (underdamped or overdamped, never exactly critical).
 *
 * Pair: two particles of mass m anchored by isotropic springs k and joined
 * by a linear coupling spring with a symmetric 3x3 stiffness a*A,
 * A = [[2,1,0],[1,2,0],[0,0,1]] (eigenvalues 3a, a, a):
 *     m x0'' = -k x0 - a A (x0 - x1),   m x1'' = -k x1 + a A (x0 - x1).
 * s = x0 + x1 obeys m s'' = -k s, d = x0 - x1 obeys m d'' = -(k + 2aA) d;
 * both are solved in A's eigenbasis.
 *
 * Failure injection: from time t_bad on, the force (and Jacobian) return NaN
 * values (TS_FAIL_NAN) or a status (TS_FAIL_STATUS, fail_status); or the
 * first fail_left force calls at t >= t_bad return NaN values and later ones
 * are exact (TS_FAIL_TRANSIENT: a trial state a solver can retry). */
#ifndef CL_TESTSYS_H
#define CL_TESTSYS_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/bpattern.h"
#include "system/system.h"

enum { TS_FAIL_NONE, TS_FAIL_NAN, TS_FAIL_STATUS, TS_FAIL_TRANSIENT };

typedef struct {
    size_t nb, n;
    double *mass, *k, *c; /* n each */
    int coupled;          /* pair system: particles 0 and 1 coupled by a A */
    double a;
    int fail;             /* TS_FAIL_* */
    double t_bad;
    cl_status fail_status;
    int fail_left;        /* TS_FAIL_TRANSIENT: failures still to inject */
    long *diag_blk;       /* nb: block index of (i, i) */
    long blk01, blk10;    /* coupling blocks of the pair */
    cl_bpattern pat;
    cl_system sys;
    double pot;           /* the one term energy of the last evaluation */
    long nforce, njac;    /* force and Jacobian calls seen, for checking
                           * the integrators' counters */
} ts_sys;

static const double ts_A[9] = {2, 1, 0, 1, 2, 0, 0, 0, 1};

static inline cl_status ts_failing(ts_sys *ts, double t)
{
    if (ts->fail == TS_FAIL_NONE || t < ts->t_bad)
        return CL_OK;
    if (ts->fail == TS_FAIL_TRANSIENT)
        return ts->fail_left > 0 ? (ts->fail_left--, CL_EBLOWUP) : CL_OK;
    return ts->fail == TS_FAIL_STATUS ? ts->fail_status : CL_EBLOWUP;
}

static inline cl_status ts_force(void *data, double t, const double *x,
                                 const double *v, double *f)
{
    ts_sys *ts = data;
    ts->nforce++;
    cl_status st = ts_failing(ts, t);
    if (st != CL_OK && ts->fail == TS_FAIL_STATUS)
        return st;
    for (size_t i = 0; i < ts->n; i++)
        f[i] = -ts->k[i] * x[i] - ts->c[i] * v[i];
    if (ts->coupled) {
        for (int r = 0; r < 3; r++) {
            double g = 0;
            for (int q = 0; q < 3; q++)
                g += ts->a * ts_A[3 * r + q] * (x[q] - x[3 + q]);
            f[r] -= g;
            f[3 + r] += g;
        }
    }
    if (st != CL_OK)
        f[0] = NAN;
    return CL_OK;
}

static inline void ts_add_block(double *val, long blk, double s,
                                const double *B)
{
    for (int q = 0; q < 9; q++)
        val[9 * blk + q] += s * B[q];
}

static inline cl_status ts_jacobian(void *data, double t, const double *x,
                                    const double *v, double *f, double *dfdx,
                                    double *dfdv)
{
    ts_sys *ts = data;
    ts->njac++;
    cl_status st = ts->fail == TS_FAIL_TRANSIENT ? CL_OK : ts_failing(ts, t);
    if (st != CL_OK && ts->fail == TS_FAIL_STATUS)
        return st;
    size_t nval = 9 * ts->pat.nnzb;
    memset(dfdx, 0, nval * sizeof *dfdx);
    memset(dfdv, 0, nval * sizeof *dfdv);
    for (size_t b = 0; b < ts->nb; b++) {
        for (int r = 0; r < 3; r++) {
            dfdx[9 * ts->diag_blk[b] + 4 * r] = -ts->k[3 * b + r];
            dfdv[9 * ts->diag_blk[b] + 4 * r] = -ts->c[3 * b + r];
        }
    }
    if (ts->coupled) {
        ts_add_block(dfdx, ts->diag_blk[0], -ts->a, ts_A);
        ts_add_block(dfdx, ts->diag_blk[1], -ts->a, ts_A);
        ts_add_block(dfdx, ts->blk01, ts->a, ts_A);
        ts_add_block(dfdx, ts->blk10, ts->a, ts_A);
    }
    if (st != CL_OK)
        dfdx[0] = NAN;
    return f ? ts_force(data, t, x, v, f) : CL_OK;
}

static inline cl_status ts_energy(void *data, double t, const double *x,
                                  const double *v, cl_energy *e)
{
    static const char *const ts_term[] = {"springs"};
    ts_sys *ts = data;
    (void)t;
    memset(e, 0, sizeof *e);
    double pot = 0;
    for (size_t i = 0; i < ts->n; i++) {
        e->kinetic += 0.5 * ts->mass[i] * v[i] * v[i];
        pot += 0.5 * ts->k[i] * x[i] * x[i];
    }
    if (ts->coupled) {
        for (int r = 0; r < 3; r++)
            for (int q = 0; q < 3; q++)
                pot += 0.5 * ts->a * (x[r] - x[3 + r]) * ts_A[3 * r + q] *
                       (x[q] - x[3 + q]);
    }
    ts->pot = pot;
    e->nterm = 1;
    e->name = ts_term;
    e->value = &ts->pot;
    e->potential = pot;
    e->total = e->kinetic + pot;
    return CL_OK;
}

static inline void ts_free(ts_sys *ts)
{
    free(ts->mass);
    free(ts->k);
    free(ts->c);
    free(ts->diag_blk);
    cl_bpattern_free(&ts->pat);
    memset(ts, 0, sizeof *ts);
}

/* Common set-up: arrays (zeroed), pattern, system table; 0 on success. */
static inline int ts_init(ts_sys *ts, size_t nb, int coupled)
{
    memset(ts, 0, sizeof *ts);
    ts->nb = nb;
    ts->n = 3 * nb;
    ts->coupled = coupled;
    ts->mass = calloc(ts->n, sizeof *ts->mass);
    ts->k = calloc(ts->n, sizeof *ts->k);
    ts->c = calloc(ts->n, sizeof *ts->c);
    ts->diag_blk = calloc(nb, sizeof *ts->diag_blk);
    int *dof = calloc(nb, sizeof *dof);
    const int pair[1][2] = {{0, 1}};
    if (!ts->mass || !ts->k || !ts->c || !ts->diag_blk || !dof) {
        free(dof);
        return -1;
    }
    for (size_t b = 0; b < nb; b++)
        dof[b] = (int)b;
    cl_status st = cl_bpattern_build(nb, dof, nb, coupled ? 1 : 0, pair,
                                     &ts->pat, NULL);
    free(dof);
    if (st != CL_OK)
        return -1;
    for (size_t b = 0; b < nb; b++)
        ts->diag_blk[b] = cl_bpattern_find(&ts->pat, (long)b, (long)b);
    ts->blk01 = cl_bpattern_find(&ts->pat, 0, 1);
    ts->blk10 = cl_bpattern_find(&ts->pat, 1, 0);
    ts->sys = (cl_system){.n = ts->n, .mass = ts->mass, .pattern = &ts->pat,
                          .data = ts, .force = ts_force,
                          .jacobian = ts_jacobian, .energy = ts_energy};
    return 0;
}

/* nb oscillator particles; particle b gets mass 1 + 0.5 b, stiffness
 * (1, 4, 9) (1 + b) and damping (0, 0.3, 1.0) on its three components
 * (undamped, light, moderate).  Callers may change mass, k, c afterwards. */
static inline int ts_oscillators(ts_sys *ts, size_t nb)
{
    if (ts_init(ts, nb, 0) != 0)
        return -1;
    for (size_t b = 0; b < nb; b++) {
        for (int r = 0; r < 3; r++) {
            ts->mass[3 * b + r] = 1.0 + 0.5 * (double)b;
            ts->k[3 * b + r] = (double)((r + 1) * (r + 1)) * (1.0 + (double)b);
            ts->c[3 * b + r] = r == 0 ? 0.0 : (r == 1 ? 0.3 : 1.0);
        }
    }
    return 0;
}

/* The coupled pair: mass m, anchor k, coupling a (no damping). */
static inline int ts_pair(ts_sys *ts, double m, double k, double a)
{
    if (ts_init(ts, 2, 1) != 0)
        return -1;
    for (size_t i = 0; i < 6; i++) {
        ts->mass[i] = m;
        ts->k[i] = k;
    }
    ts->a = a;
    return 0;
}

/* m x'' = -k x - c x': exact x(t), v(t) (not critically damped). */
static inline void ts_osc1(double m, double k, double c, double x0, double v0,
                           double t, double *x, double *v)
{
    double w2 = k / m, g = c / (2 * m), disc = g * g - w2;
    if (disc < 0) {
        double wd = sqrt(-disc), e = exp(-g * t);
        double cs = cos(wd * t), sn = sin(wd * t);
        *x = e * (x0 * cs + (v0 + g * x0) / wd * sn);
        *v = e * (v0 * cs - (w2 * x0 + g * v0) / wd * sn);
    } else {
        double r2 = -g - sqrt(disc), r1 = w2 / r2; /* no cancellation */
        double a = (v0 - r2 * x0) / (r1 - r2), b = x0 - a;
        *x = a * exp(r1 * t) + b * exp(r2 * t);
        *v = a * r1 * exp(r1 * t) + b * r2 * exp(r2 * t);
    }
}

/* d'' = -(k + 2 a A) d / m in A's orthonormal eigenbasis. */
static inline void ts_pair_modes(const ts_sys *ts, const double *d0,
                                 const double *dv0, double t, double *d,
                                 double *dv)
{
    const double h = sqrt(0.5);
    const double E[3][3] = {{h, h, 0}, {h, -h, 0}, {0, 0, 1}};
    const double lam[3] = {3, 1, 1};
    double m = ts->mass[0], k = ts->k[0];
    memset(d, 0, 3 * sizeof *d);
    memset(dv, 0, 3 * sizeof *dv);
    for (int e = 0; e < 3; e++) {
        double p = 0, pv = 0, q, qv;
        for (int r = 0; r < 3; r++) {
            p += E[e][r] * d0[r];
            pv += E[e][r] * dv0[r];
        }
        ts_osc1(m, k + 2 * ts->a * lam[e], 0, p, pv, t, &q, &qv);
        for (int r = 0; r < 3; r++) {
            d[r] += q * E[e][r];
            dv[r] += qv * E[e][r];
        }
    }
}

static inline void ts_exact_pair(const ts_sys *ts, const double *x0,
                                 const double *v0, double t, double *x,
                                 double *v)
{
    double d0[3], dv0[3], d[3], dv[3];
    for (int r = 0; r < 3; r++) {
        double s, sv;
        ts_osc1(ts->mass[r], ts->k[r], 0, x0[r] + x0[3 + r],
                v0[r] + v0[3 + r], t, &s, &sv);
        x[r] = x[3 + r] = 0.5 * s;
        v[r] = v[3 + r] = 0.5 * sv;
        d0[r] = x0[r] - x0[3 + r];
        dv0[r] = v0[r] - v0[3 + r];
    }
    ts_pair_modes(ts, d0, dv0, t, d, dv);
    for (int r = 0; r < 3; r++) {
        x[r] += 0.5 * d[r];
        x[3 + r] -= 0.5 * d[r];
        v[r] += 0.5 * dv[r];
        v[3 + r] -= 0.5 * dv[r];
    }
}

/* Exact state at t from (x0, v0) at time 0. */
static inline void ts_exact(const ts_sys *ts, const double *x0,
                            const double *v0, double t, double *x, double *v)
{
    if (ts->coupled) {
        ts_exact_pair(ts, x0, v0, t, x, v);
        return;
    }
    for (size_t i = 0; i < ts->n; i++)
        ts_osc1(ts->mass[i], ts->k[i], ts->c[i], x0[i], v0[i], t, &x[i],
                &v[i]);
}

/* Deterministic initial state in [-1, 1]. */
static inline void ts_initial(const ts_sys *ts, double *x0, double *v0)
{
    for (size_t i = 0; i < ts->n; i++) {
        x0[i] = sin(1.0 + 1.7 * (double)i);
        v0[i] = cos(0.3 + 2.3 * (double)i);
    }
}

/* max_i |a_i - b_i| */
static inline double ts_maxdiff(const double *a, const double *b, size_t n)
{
    double e = 0;
    for (size_t i = 0; i < n; i++)
        e = fmax(e, fabs(a[i] - b[i]));
    return e;
}

#endif
