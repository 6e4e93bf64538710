/* Central pair forces (docs/model.md 3.1): loop over pairs, scalar law,
 * blocks. */
#include "forces/pairterm.h"

#include <stdlib.h>
#include <string.h>

cl_status cl_pairterm_init(cl_pairterm *pt, cl_pairset set, cl_pairlaw_fn law,
                           cl_pairlaw_batch_fn batch, const void *params,
                           bool clamp_transverse, int nblk, cl_error *err)
{
    memset(pt, 0, sizeof *pt);
    pt->set = set;
    pt->law = law;
    pt->batch = batch;
    pt->params = params;
    pt->clamp_transverse = clamp_transverse;
    pt->couple = malloc((set.n + 1) * sizeof *pt->couple);
    if (!pt->couple)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pair couplings)");
    for (size_t k = 0; k < set.n; k++) {
        pt->couple[k][0] = set.pair[k].a;
        pt->couple[k][1] = set.pair[k].b;
    }
    return cl_pairkern_init(&pt->kern, &pt->set, nblk, err);
}

void cl_pairterm_free(cl_pairterm *pt)
{
    cl_pairs_free(&pt->set);
    free(pt->couple);
    free(pt->slot);
    free(pt->torn);
    free(pt->broken);
    cl_pairkern_free(&pt->kern);
    memset(pt, 0, sizeof *pt);
}

cl_status cl_pairterm_tear(cl_pairterm *pt, double cut, cl_error *err)
{
    if (!(cut > 0))
        return CL_OK;
    pt->cut = cut;
    pt->torn = calloc(pt->set.n + 1, sizeof *pt->torn);
    pt->broken = malloc((pt->set.n + 1) * sizeof *pt->broken);
    if (!pt->torn || !pt->broken)
        return cl_error_set(err, CL_ENOMEM, "out of memory (tearing)");
    return CL_OK;
}

size_t cl_pairterm_step_done(void *state, const double *x, const double *v)
{
    cl_pairterm *pt = state;
    size_t now = 0;
    (void)v;
    for (size_t k = 0; pt->torn && k < pt->set.n; k++) {
        const cl_pair *pr = &pt->set.pair[k];
        if (pt->torn[k] ||
            !(cl_dist(x + 3 * pr->a, x + 3 * pr->b) > pt->cut * pr->rest))
            continue;
        pt->torn[k] = 1;
        pt->broken[pt->nbroken][0] = pr->a;
        pt->broken[pt->nbroken++][1] = pr->b;
        now++;
    }
    return now;
}

size_t cl_pairterm_broken(const void *state, const int (**pairs)[2])
{
    const cl_pairterm *pt = state;
    *pairs = (const int(*)[2])pt->broken;
    return pt->nbroken;
}

void cl_pair_block(const double u[3], double d, double s, double ds,
                   bool clamp_transverse, double K[9])
{
    double t = (clamp_transverse && s < 0) ? 0.0 : s / d;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            K[3 * r + c] = (ds - t) * u[r] * u[c] + (r == c ? t : 0.0);
}

cl_status cl_pair_slots(const cl_pairset *set, const cl_bpattern *pat,
                        const int *dof, long **slot, cl_error *err)
{
    free(*slot);
    *slot = malloc((4 * set->n + 1) * sizeof **slot);
    if (!*slot)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pair slots)");
    for (size_t k = 0; k < set->n; k++) {
        long a = dof[set->pair[k].a], b = dof[set->pair[k].b];
        long *s = *slot + 4 * k;
        s[0] = cl_bpattern_find(pat, a, a);
        s[1] = cl_bpattern_find(pat, b, b);
        s[2] = cl_bpattern_find(pat, a, b);
        s[3] = cl_bpattern_find(pat, b, a);
    }
    return CL_OK;
}

void cl_block_add(double *vals, long slot, double sign, const double B[9])
{
    if (slot < 0)
        return;
    double *dst = vals + 9 * slot;
    for (int i = 0; i < 9; i++)
        dst[i] += sign * B[i];
}

size_t cl_pairterm_couplings(const void *state, const int (**pairs)[2])
{
    const cl_pairterm *pt = state;
    *pairs = (const int (*)[2])pt->couple;
    return pt->set.n;
}

cl_status cl_pairterm_bind(void *state, const cl_bpattern *pat,
                           const int *dof, cl_error *err)
{
    cl_pairterm *pt = state;
    cl_status rc = cl_pair_slots(&pt->set, pat, dof, &pt->slot, err);
    return rc ? rc : cl_pairkern_bind(&pt->kern, pt->slot, pat->nnzb, err);
}

cl_status cl_pairterm_threads(void *state, int threads, cl_error *err)
{
    cl_pairterm *pt = state;
    return cl_pairkern_threads(&pt->kern, threads, err);
}

/* f_a += s u, f_b -= s u: one expression for both evaluation paths, so
 * that their forces agree bit for bit (and a pair along an axis gives
 * exactly s). */
static inline void pair_add_force(double *restrict f, const cl_pair *pr,
                                  double s, double u0, double u1, double u2)
{
    cl_pair_scatter(f, pr, s * u0, s * u1, s * u2);
}

/* Component i of u = x_ab / d, or 0 for coincident particles (no
 * direction).  Scalars, not an array: a direction stored entry by entry
 * and read back two at a time stalls on store forwarding. */
static inline double pair_dir(const double *xa, const double *xb, double d,
                              int i)
{
    return d > 0 ? (xb[i] - xa[i]) / d : 0.0;
}

void cl_pairterm_phase1(cl_pairterm *pt, const double *x, bool blocks,
                        bool recip, size_t k0, size_t k1, size_t base)
{
    cl_pairkern *pk = &pt->kern;
    size_t i = k0 - base;
    cl_pairkern_geometry(pk, k0, k1, base, x, recip);
    pt->batch(pt->params, k0, k1 - k0, pk->d + i, pk->L, pk->s + i,
              blocks ? pk->ds + i : NULL);
    cl_pairkern_central(pk, k0, k1, base, blocks, pt->clamp_transverse);
}

typedef struct {
    cl_pairterm *pt;
    const double *x;
    bool blocks;
} pair_job;

/* Phase 1 (forces/pairkern.h): geometry, law, force and block K. */
static void pair_chunk(void *ctx, cl_pairkern *pk, size_t k0, size_t k1,
                       size_t base)
{
    const pair_job *j = ctx;
    (void)pk; /* j->pt's own */
    cl_pairterm_phase1(j->pt, j->x, j->blocks, false, k0, k1, base);
}

void cl_pairterm_eval(void *state, cl_eval *ev)
{
    cl_pairterm *pt = state;
    pair_job j = {pt, ev->x, ev->dfdx != NULL};
    double *vals[2] = {ev->dfdx, NULL};
    /* Forces and blocks by the kernels; with energies, forces by the
     * scalar loop below (equal to the kernels' to rounding). */
    double *f = ev->want_energy ? NULL : ev->f;
    if (f || ev->dfdx)
        cl_pairkern_eval(&pt->kern, pair_chunk, &j, pt->torn, f, vals);
    if (!ev->want_energy)
        return;
    double energy = 0.0;
    for (size_t k = 0; k < pt->set.n; k++) {
        if (cl_pairterm_is_torn(pt, k))
            continue; /* no force, energy or Jacobian values */
        const cl_pair *pr = &pt->set.pair[k];
        const double *xa = ev->x + 3 * pr->a, *xb = ev->x + 3 * pr->b;
        double d = cl_dist(xa, xb);
        cl_pairlaw law;
        pt->law(pt->params, k, d, pr->rest, true, false, &law);
        energy += law.e;
        /* Coincident particles have no direction: no force, isotropic K. */
        const double u[3] = {pair_dir(xa, xb, d, 0), pair_dir(xa, xb, d, 1),
                             pair_dir(xa, xb, d, 2)};
        if (ev->f)
            pair_add_force(ev->f, pr, law.s, u[0], u[1], u[2]);
    }
    ev->energy = energy;
    ev->power = 0.0; /* conservative: its power is -dE/dt, not dissipated */
}
