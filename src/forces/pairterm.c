/* Central pair forces (docs/model.md 3.1): loop over pairs, scalar law,
 * blocks. */
#include "forces/pairterm.h"

#include <stdlib.h>
#include <string.h>

cl_status cl_pairterm_init(cl_pairterm *pt, cl_pairset set, cl_pairlaw_fn law,
                           const void *params, bool clamp_transverse,
                           cl_error *err)
{
    memset(pt, 0, sizeof *pt);
    pt->set = set;
    pt->law = law;
    pt->params = params;
    pt->clamp_transverse = clamp_transverse;
    pt->couple = malloc((set.n + 1) * sizeof *pt->couple);
    if (!pt->couple)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pair couplings)");
    for (size_t k = 0; k < set.n; k++) {
        pt->couple[k][0] = set.pair[k].a;
        pt->couple[k][1] = set.pair[k].b;
    }
    return CL_OK;
}

void cl_pairterm_free(cl_pairterm *pt)
{
    cl_pairs_free(&pt->set);
    free(pt->couple);
    free(pt->slot);
    free(pt->torn);
    free(pt->broken);
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
    return cl_pair_slots(&pt->set, pat, dof, &pt->slot, err);
}

/* Add the four blocks +-K of one pair into vals. */
static void add_pair_blocks(double *vals, const long *s, const double K[9])
{
    cl_block_add(vals, s[0], -1.0, K);
    cl_block_add(vals, s[1], -1.0, K);
    cl_block_add(vals, s[2], 1.0, K);
    cl_block_add(vals, s[3], 1.0, K);
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

/* Forces only (no Jacobian, no energy): the path of every right-hand
 * side. */
static void pairterm_forces(const cl_pairterm *pt, size_t k0, size_t k1,
                            const double *restrict x, double *restrict f)
{
    const cl_pair *pair = pt->set.pair;
    for (size_t k = k0; k < k1; k++) {
        if (cl_pairterm_is_torn(pt, k))
            continue;
        const double *xa = x + 3 * pair[k].a, *xb = x + 3 * pair[k].b;
        double d = cl_dist(xa, xb);
        cl_pairlaw law;
        pt->law(pt->params, k, d, pair[k].rest, false, false, &law);
        pair_add_force(f, &pair[k], law.s, pair_dir(xa, xb, d, 0),
                       pair_dir(xa, xb, d, 1), pair_dir(xa, xb, d, 2));
    }
}

void cl_pairterm_eval(void *state, cl_eval *ev)
{
    cl_pairterm *pt = state;
    size_t k0, k1;
    cl_eval_share(ev, pt->set.n, &k0, &k1);
    if (!ev->dfdx && !ev->want_energy) {
        if (ev->f)
            pairterm_forces(pt, k0, k1, ev->x, ev->f);
        return;
    }
    double energy = 0.0;
    for (size_t k = k0; k < k1; k++) {
        if (cl_pairterm_is_torn(pt, k))
            continue; /* no force, energy or Jacobian values */
        const cl_pair *pr = &pt->set.pair[k];
        const double *xa = ev->x + 3 * pr->a, *xb = ev->x + 3 * pr->b;
        double d = cl_dist(xa, xb);
        cl_pairlaw law;
        pt->law(pt->params, k, d, pr->rest, ev->want_energy,
                ev->dfdx != NULL, &law);
        energy += law.e;
        /* Coincident particles have no direction: no force, isotropic K. */
        const double u[3] = {pair_dir(xa, xb, d, 0), pair_dir(xa, xb, d, 1),
                             pair_dir(xa, xb, d, 2)};
        if (ev->f)
            pair_add_force(ev->f, pr, law.s, u[0], u[1], u[2]);
        if (ev->dfdx) {
            double K[9];
            if (d > 0)
                cl_pair_block(u, d, law.s, law.ds, pt->clamp_transverse, K);
            else
                for (int i = 0; i < 9; i++)
                    K[i] = (i % 4 == 0) ? law.ds : 0.0;
            add_pair_blocks(ev->dfdx, pt->slot + 4 * k, K);
        }
    }
    if (ev->want_energy) {
        ev->energy = energy;
        ev->power = 0.0; /* conservative: its power is -dE/dt, not dissipated */
    }
}
