/* Pair damping, linear (Jiao, eq. 14) and axial (the Verlet-and-PBD
 * report, "Spring and Friction"): equations and Jacobians in
 * forces/pairdamp.h. */
#include "forces/pairdamp.h"

cl_status cl_pairdamp_init(cl_pairdamp *pd, cl_pairset set, double kd,
                           cl_damp_model model, cl_error *err)
{
    pd->kd = kd;
    pd->model = model;
    cl_status rc = cl_pairterm_init(&pd->pt, set, NULL, NULL, NULL, false, 2,
                                    err);
    pd->pt.kern.diag = model == CL_DAMP_LINEAR; /* df/dv = kd I */
    return rc ? rc : cl_pairgather_init(&pd->gather, pd->pt.kern.ia,
                                        pd->pt.kern.ib, pd->pt.kern.n,
                                        pd->pt.kern.np, err);
}

void cl_pairdamp_free(cl_pairdamp *pd)
{
    cl_pairterm_free(&pd->pt);
    cl_pairgather_free(&pd->gather);
}

cl_status cl_pairdamp_read_model(cl_config *cfg, const char *sec,
                                 cl_damp_model def, cl_damp_model *model,
                                 cl_error *err)
{
    static const char *const names[] = {"linear", "axial", NULL};
    int k;
    cl_status rc = cl_config_choice(cfg, sec, "model", names, (int)def, &k,
                                    err);
    *model = k == 1 ? CL_DAMP_AXIAL : CL_DAMP_LINEAR;
    return rc;
}

/* -sc B on the aa, bb blocks, +sc B on ab, ba (slots s[0..3]). */
static void add_blocks(double *vals, const long *s, double sc,
                       const double B[9])
{
    cl_block_add(vals, s[0], -sc, B);
    cl_block_add(vals, s[1], -sc, B);
    cl_block_add(vals, s[2], sc, B);
    cl_block_add(vals, s[3], sc, B);
}

/* f_a += fa, f_b -= fa; returns fa . (v_a - v_b). */
static double add_pair_force(cl_eval *ev, const cl_pair *pr,
                             const double fa[3])
{
    double p = 0.0;
    for (int i = 0; i < 3; i++) {
        if (ev->f) {
            ev->f[3 * pr->a + i] += fa[i];
            ev->f[3 * pr->b + i] -= fa[i];
        }
        p += fa[i] * (ev->v[3 * pr->a + i] - ev->v[3 * pr->b + i]);
    }
    return p;
}

/* u . w with w = v_b - v_a (u_0 w_0 + u_1 w_1 + u_2 w_2 from 0). */
static inline double axial_uw(double u0, double u1, double u2, double w0,
                              double w1, double w2)
{
    double uw = 0.0;
    uw += u0 * w0;
    uw += u1 * w1;
    uw += u2 * w2;
    return uw;
}

/* The damping force (g0, g1, g2) on a of a pair whose velocities are
 * at v + a and v + b (a, b: 3 times the particle indices;
 * forces/pairdamp.h): linear -kd (v_a - v_b); axial kd (u . w) u,
 * w = v_b - v_a, none for coincident particles (some false), and then
 * u . w is returned (linear: 0).  The one expression of the pair-by-pair
 * loop, the separate pass and the fused pass (axial: a constant where it
 * is inlined). */
CL_PAIR_INLINE double damp_force(bool axial, double kd, const double *v,
                                 int a, int b, bool some, double u0,
                                 double u1, double u2, double *g0,
                                 double *g1, double *g2)
{
    if (!axial) {
        *g0 = -kd * (v[a] - v[b]);
        *g1 = -kd * (v[a + 1] - v[b + 1]);
        *g2 = -kd * (v[a + 2] - v[b + 2]);
        return 0.0;
    }
    double uw = axial_uw(u0, u1, u2, v[b] - v[a], v[b + 1] - v[a + 1],
                         v[b + 2] - v[a + 2]);
    *g0 = some ? kd * uw * u0 : 0.0;
    *g1 = some ? kd * uw * u1 : 0.0;
    *g2 = some ? kd * uw * u2 : 0.0;
    return uw;
}

static double damp_linear(double kd, const cl_pair *pr, const long *s,
                          cl_eval *ev)
{
    static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    double fa[3];
    damp_force(false, kd, ev->v, 3 * pr->a, 3 * pr->b, true, 0.0, 0.0, 0.0,
               &fa[0], &fa[1], &fa[2]);
    if (ev->dfdv)
        add_blocks(ev->dfdv, s, kd, I3);
    return add_pair_force(ev, pr, fa);
}

/* G = (kd/d) [u (P w)^T + (u . w) P], P = I - u u^T (row-major). */
static void axial_dx_block(double kd, double d, const double u[3],
                           const double w[3], double uw, double G[9])
{
    double pw[3];
    for (int i = 0; i < 3; i++)
        pw[i] = w[i] - uw * u[i];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            G[3 * r + c] = kd / d *
                           (u[r] * pw[c] + uw * ((r == c) - u[r] * u[c]));
}

static double damp_axial(double kd, const cl_pair *pr, const long *s,
                         cl_eval *ev)
{
    const double *xa = ev->x + 3 * pr->a, *xb = ev->x + 3 * pr->b;
    const double *va = ev->v + 3 * pr->a, *vb = ev->v + 3 * pr->b;
    double d = cl_dist(xa, xb);
    if (!(d > 0))
        return 0.0;
    double u[3], w[3], fa[3], B[9];
    for (int i = 0; i < 3; i++) {
        u[i] = (xb[i] - xa[i]) / d;
        w[i] = vb[i] - va[i];
    }
    double uw = damp_force(true, kd, ev->v, 3 * pr->a, 3 * pr->b, true, u[0],
                           u[1], u[2], &fa[0], &fa[1], &fa[2]);
    if (ev->dfdv) {
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                B[3 * r + c] = kd * u[r] * u[c];
        add_blocks(ev->dfdv, s, 1.0, B);
    }
    if (ev->dfdx) {
        axial_dx_block(kd, d, u, w, uw, B);
        add_blocks(ev->dfdx, s, 1.0, B);
    }
    return add_pair_force(ev, pr, fa);
}

typedef struct {
    const cl_pairdamp *pd;
    const double *x, *v;
    bool dv, dx;     /* blocks: df/dv (block 0), df/dx (block 1) */
} damp_job;

/* The outputs of a force loop: per pair k, o0[k], o1[k], o2[k] (the
 * pointers offset by the caller); or with s (a fused pass) the central
 * force s[k] u_k added to the damping's, into o4[4k .. 4k + 3]
 * (forces/pairgather.h). */
typedef struct {
    const double *s;
    double *o0, *o1, *o2, *o4;
} force_out;

/* (f0, f1, f2, 0), pair k's place in a cl_pairgather. */
CL_PAIR_INLINE void put_pair(double *restrict o4, size_t k, double f0,
                             double f1, double f2)
{
    double *o = o4 + 4 * k;
    o[0] = f0;
    o[1] = f1;
    o[2] = f2;
    o[3] = 0.0;
}

/* Pair k's force (f0, f1, f2): o's arrays, or with `central` into the
 * per-particle sums' buffer. */
CL_PAIR_INLINE void put_force(force_out o, bool central, size_t k,
                              double f0, double f1, double f2)
{
    if (central) {
        put_pair(o.o4, k, f0, f1, f2);
    } else {
        o.o0[k] = f0;
        o.o1[k] = f1;
        o.o2[k] = f2;
    }
}

/* Entry e = (r, q) of kd u u^T into Bk[e] and of G into Bk[9 + e], as
 * damp_axial and axial_dx_block round them (c = kd/d, pwq = (P w)_q,
 * delta = 1 on the diagonal); zeros where z is false (d = 0). */
static inline void axial_entry(double *Bk, int e, bool z, double kd,
                               double c, double uw, double ur, double uq,
                               double pwq, double delta)
{
    double bv = kd * ur * uq, g = c * (ur * pwq + uw * (delta - ur * uq));
    Bk[e] = z ? bv : 0.0;
    Bk[9 + e] = z ? g : 0.0;
}

/* The df/dv block kd u u^T and the df/dx block G (forces/pairdamp.h) of
 * pairs [k0, k1) into blocks 0 and 1; zeros for coincident particles. */
CL_PAIR_KERNEL
static void axial_blocks(const cl_pairdamp *pd, cl_pairkern *pk, size_t k0,
                         size_t k1, size_t base, const double *v)
{
    double kd = pd->kd, *restrict B = pk->blk - 18 * base;
    const int *ia = pk->ia, *ib = pk->ib;
    const double *restrict d = pk->d - base, *restrict u0 = pk->u0 - base;
    const double *restrict u1 = pk->u1 - base, *restrict u2 = pk->u2 - base;
#pragma omp simd
    for (size_t k = k0; k < k1; k++) {
        int a = 3 * ia[k], b = 3 * ib[k];
        double w0 = v[b] - v[a], w1 = v[b + 1] - v[a + 1];
        double w2 = v[b + 2] - v[a + 2];
        double uw = axial_uw(u0[k], u1[k], u2[k], w0, w1, w2);
        double c = kd / d[k], x = u0[k], y = u1[k], q = u2[k];
        double p0 = w0 - uw * x, p1 = w1 - uw * y, p2 = w2 - uw * q;
        double *Bk = B + 18 * k;
        bool z = d[k] > 0;
        axial_entry(Bk, 0, z, kd, c, uw, x, x, p0, 1.0);
        axial_entry(Bk, 1, z, kd, c, uw, x, y, p1, 0.0);
        axial_entry(Bk, 2, z, kd, c, uw, x, q, p2, 0.0);
        axial_entry(Bk, 3, z, kd, c, uw, y, x, p0, 0.0);
        axial_entry(Bk, 4, z, kd, c, uw, y, y, p1, 1.0);
        axial_entry(Bk, 5, z, kd, c, uw, y, q, p2, 0.0);
        axial_entry(Bk, 6, z, kd, c, uw, q, x, p0, 0.0);
        axial_entry(Bk, 7, z, kd, c, uw, q, y, p1, 0.0);
        axial_entry(Bk, 8, z, kd, c, uw, q, q, p2, 1.0);
    }
}

/* The damping forces of pairs [k0, k1) (damp_force; axial: from the
 * geometry in pk), plus s u with central (axial, central: constants
 * where it is inlined, so each loop has no select). */
CL_PAIR_INLINE void damp_loop(double kd, const cl_pairkern *pk,
                              const double *v, size_t k0, size_t k1,
                              size_t base, bool axial, bool central,
                              force_out o)
{
    const double *restrict d = pk->d - base, *restrict u0 = pk->u0 - base;
    const double *restrict u1 = pk->u1 - base, *restrict u2 = pk->u2 - base;
    const double *restrict s = o.s;
    const int *ia = pk->ia, *ib = pk->ib;
#pragma omp simd
    for (size_t k = k0; k < k1; k++) {
        int a = 3 * ia[k], b = 3 * ib[k];
        double g0, g1, g2;
        if (axial)
            damp_force(true, kd, v, a, b, d[k] > 0, u0[k], u1[k], u2[k], &g0,
                       &g1, &g2);
        else
            damp_force(false, kd, v, a, b, true, 0.0, 0.0, 0.0, &g0, &g1,
                       &g2);
        put_force(o, central, k, central ? s[k] * u0[k] + g0 : g0,
                  central ? s[k] * u1[k] + g1 : g1,
                  central ? s[k] * u2[k] + g2 : g2);
    }
}

/* The damping forces of pairs [k0, k1), model by model, into o (with
 * o.s: a fused pass, s u added): each loop inlined with central a
 * constant. */
CL_PAIR_KERNEL
static void damp_forces(const cl_pairdamp *pd, const cl_pairkern *pk,
                        const double *v, size_t k0, size_t k1, size_t base,
                        force_out o)
{
    double kd = pd->kd;
    if (pd->model == CL_DAMP_AXIAL && o.s)
        damp_loop(kd, pk, v, k0, k1, base, true, true, o);
    else if (pd->model == CL_DAMP_AXIAL)
        damp_loop(kd, pk, v, k0, k1, base, true, false, o);
    else if (o.s)
        damp_loop(kd, pk, v, k0, k1, base, false, true, o);
    else
        damp_loop(kd, pk, v, k0, k1, base, false, false, o);
}

/* Into pk's own force buffers (the separate evaluation). */
static force_out own_buffers(const cl_pairkern *pk, size_t base)
{
    return (force_out){NULL, pk->f0 - base, pk->f1 - base, pk->f2 - base,
                       NULL};
}

/* Linear damping of pairs [k0, k1): forces and the df/dv block kd I
 * (forces/pairkern.h phase 1). */
static void linear_chunk(void *ctx, cl_pairkern *pk, size_t k0, size_t k1,
                         size_t base)
{
    const damp_job *j = ctx;
    double kd = j->pd->kd;
    damp_forces(j->pd, pk, j->v, k0, k1, base, own_buffers(pk, base));
    for (size_t k = k0; j->dv && k < k1; k++)
        for (int i = 0; i < 9; i += 4) /* a diagonal block */
            pk->blk[18 * (k - base) + i] = kd;
}

/* Axial damping of pairs [k0, k1): geometry, forces and the blocks. */
static void axial_chunk(void *ctx, cl_pairkern *pk, size_t k0, size_t k1,
                        size_t base)
{
    const damp_job *j = ctx;
    const double *v = j->v;
    cl_pairkern_geometry(pk, k0, k1, base, j->x, false);
    damp_forces(j->pd, pk, v, k0, k1, base, own_buffers(pk, base));
    if (j->dv || j->dx)
        axial_blocks(j->pd, pk, k0, k1, base, v);
}

/* Whether pd damps exactly the pairs of pt[0], ..., pt[npt - 1], one
 * list after the other, in the same order (decided once per pt[0] and
 * npt: pair sets do not change). */
static bool same_pairs(cl_pairdamp *pd, cl_pairterm *const *pt, size_t npt)
{
    const cl_pairkern *a = &pd->pt.kern;
    if (pd->fuse_with == pt[0] && pd->fuse_npt == npt)
        return pd->fuse_same;
    pd->fuse_with = pt[0];
    pd->fuse_npt = npt;
    size_t k = 0;
    bool same = true;
    for (size_t i = 0; same && i < npt; i++) {
        const cl_pairkern *b = &pt[i]->kern;
        same = k + b->n <= a->n;
        for (size_t j = 0; same && j < b->n; j++, k++)
            same = a->ia[k] == b->ia[j] && a->ib[k] == b->ib[j];
    }
    pd->fuse_same = same && k == a->n;
    return pd->fuse_same;
}

typedef struct {
    cl_pairterm *const *pt;
    size_t npt;
    const cl_pairdamp *pd;
    const double *x, *v;
} fused_job;

/* A linear law k (d - L) (forces/pairterm.h, k_linear; none below L if
 * k_tension_only) and the damping in one loop, pairs [k0, k1) of pd's
 * list, those of pt from `off` on: the arithmetic of the three loops of
 * fused_segment (cl_pairkern_geometry with recip, the term's law,
 * damp_forces), so the same forces bit for bit, without storing d, u
 * and s in between (axial, and uniform: k_linear one k for all pairs,
 * constants where it is inlined). */
CL_PAIR_INLINE void linear_dashpot(const fused_job *j, const cl_pairterm *pt,
                                   size_t off, size_t k0, size_t k1,
                                   bool axial, bool uniform)
{
    const cl_pairkern *pk = &j->pd->pt.kern;
    const int *ia = pk->ia, *ib = pk->ib;
    const double *restrict L = pk->L;
    const double *restrict K = pt->k_linear - (uniform ? 0 : off);
    const double *x = j->x, *v = j->v;
    double kd = j->pd->kd, *restrict o4 = j->pd->gather.f4;
    bool tension_only = pt->k_tension_only;
#pragma omp simd
    for (size_t k = k0; k < k1; k++) {
        int a = 3 * ia[k], b = 3 * ib[k];
        double d, u0, u1, u2;
        cl_pairkern_dir(x, a, b, true, &d, &u0, &u1, &u2);
        double st = d - L[k], sv = (uniform ? K[0] : K[k]) * st;
        double s = st >= 0 || !tension_only ? sv : 0.0;
        double g0, g1, g2;
        damp_force(axial, kd, v, a, b, d > 0, u0, u1, u2, &g0, &g1, &g2);
        put_pair(o4, k, s * u0 + g0, s * u1 + g1, s * u2 + g2);
    }
}

CL_PAIR_KERNEL
static void linear_segment(const fused_job *j, const cl_pairterm *pt,
                           size_t off, size_t k0, size_t k1)
{
    bool axial = j->pd->model == CL_DAMP_AXIAL;
    if (axial && pt->k_uniform)
        linear_dashpot(j, pt, off, k0, k1, true, true);
    else if (axial)
        linear_dashpot(j, pt, off, k0, k1, true, false);
    else if (pt->k_uniform)
        linear_dashpot(j, pt, off, k0, k1, false, true);
    else
        linear_dashpot(j, pt, off, k0, k1, false, false);
}

/* Pairs [k0, k1) of pd's list, those of pt from `off` on, by three
 * loops: geometry, the term's law, f = s u + the damping's force. */
static void fused_segment(const fused_job *j, const cl_pairterm *pt,
                          size_t off, cl_pairkern *pk, size_t k0, size_t k1,
                          size_t base)
{
    cl_pairkern_geometry(pk, k0, k1, base, j->x, true);
    pt->batch(pt->params, k0 - off, k1 - k0, pk->d + (k0 - base),
              pt->kern.L, pk->s + (k0 - base), NULL);
    force_out o = {pk->s - base, NULL, NULL, NULL, j->pd->gather.f4};
    damp_forces(j->pd, pk, j->v, k0, k1, base, o);
}

/* Phase 1 of the fused pass, pairs [k0, k1) of pd's list: each central
 * term's pairs by its one loop (a linear law) or three, the forces into
 * the per-pair sums' buffer. */
static void fused_chunk(void *ctx, cl_pairkern *pk, size_t k0, size_t k1,
                        size_t base)
{
    const fused_job *j = ctx;
    size_t off = 0;
    for (size_t i = 0; i < j->npt; i++) {
        const cl_pairterm *pt = j->pt[i];
        size_t lo = k0 > off ? k0 : off, end = off + pt->kern.n;
        size_t hi = k1 < end ? k1 : end;
        if (lo < hi && pt->k_linear)
            linear_segment(j, pt, off, lo, hi);
        else if (lo < hi)
            fused_segment(j, pt, off, pk, lo, hi, base);
        off = end;
    }
}

bool cl_pairdamp_fused(cl_pairterm *const *pt, size_t npt, cl_pairdamp *pd,
                       cl_eval *ev)
{
    if (!ev->f || ev->dfdx || ev->dfdv || ev->want_energy || pd->pt.torn)
        return false;
    for (size_t i = 0; i < npt; i++)
        if (pt[i]->torn || !pt[i]->batch)
            return false;
    if (!same_pairs(pd, pt, npt))
        return false;
    fused_job j = {pt, npt, pd, ev->x, ev->v};
    cl_pairkern_eval(&pd->pt.kern, fused_chunk, &j, NULL, NULL, NULL);
    cl_pairgather_add(&pd->gather, pd->pt.kern.threads, ev->f);
    return true;
}

void cl_pairdamp_eval(cl_pairdamp *pd, cl_eval *ev, cl_pairdamp_keep keep,
                      const void *ctx)
{
    bool axial = pd->model == CL_DAMP_AXIAL;
    if (!keep && !ev->want_energy) {
        damp_job j = {pd, ev->x, ev->v, ev->dfdv != NULL,
                      axial && ev->dfdx != NULL};
        double *vals[2] = {ev->dfdv, axial ? ev->dfdx : NULL};
        if (ev->f || j.dv || j.dx)
            cl_pairkern_eval(&pd->pt.kern, axial ? axial_chunk : linear_chunk,
                             &j, pd->pt.torn, ev->f, vals);
        return;
    }
    /* Engaged pairs only, or energies: the scalar loop, pair by pair. */
    double power = 0.0;
    for (size_t k = 0; k < pd->pt.set.n; k++) {
        if (cl_pairterm_is_torn(&pd->pt, k) ||
            (keep && !keep(ctx, k, ev->x)))
            continue;
        const cl_pair *pr = &pd->pt.set.pair[k];
        const long *s = pd->pt.slot ? pd->pt.slot + 4 * k : NULL;
        power += axial ? damp_axial(pd->kd, pr, s, ev)
                       : damp_linear(pd->kd, pr, s, ev);
    }
    if (ev->want_energy) {
        ev->energy = 0.0;
        ev->power = power;
    }
}
