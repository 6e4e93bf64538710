/* Central pair forces (docs/model.md 3.1), shared by every pair model
 * (Choi-Ko Type1, Type2, springs).
 *
 * For a pair a-b: x_ab = x_b - x_a, d = |x_ab|, u = x_ab/d.  The force on a is
 * f_a = s(d) u, on b it is -f_a.  With
 *     K = s'(d) u u^T + (s(d)/d) (I - u u^T)
 * df_a/dx_b = df_b/dx_a = K and df_a/dx_a = df_b/dx_b = -K.  The energy is
 * E(d) = integral_L^d s(r) dr.  The "transverse" term (s/d)(I - uu^T) is
 * negative under compression and makes -df/dx indefinite; with
 * clamp_transverse it is dropped where s < 0 (jacobian.transverse = clamp).
 *
 * A model supplies the scalar law s, s', E through a cl_pairlaw_fn.
 *
 * Tearing (docs/model.md 3.4; the Verlet-and-PBD report's "cutting
 * distance"): with cut > 0 (cl_pairterm_tear, [tear] cut), a pair breaks
 * for good, after an accepted step, once d > cut L.  A broken pair
 * contributes no force, no energy and no Jacobian values: its blocks stay
 * in the pattern and simply receive nothing (zeros), so the sparsity
 * pattern and KLU's symbolic analysis are unchanged.  Every term decides on
 * its own pairs with the same d and L, so a spring and the damper on the
 * same pair break together. */
#ifndef CL_PAIRTERM_H
#define CL_PAIRTERM_H

#include <stdbool.h>

#include "core/decls.h"
#include "forces/pairkern.h"
#include "forces/term.h"
#include "model/pairs.h"

CL_BEGIN_DECLS

typedef struct {
    double s;   /* s(d): > 0 pulls the pair together */
    double ds;  /* s'(d) (only if asked for; else any value) */
    double e;   /* E(d) = integral_L^d s(r) dr (only if asked for) */
} cl_pairlaw;

/* Scalar law of pair k (rest length L) at distance d; s' and E only when
 * asked for (a law may skip work for them: forces alone are every
 * right-hand side). */
typedef void (*cl_pairlaw_fn)(const void *params, size_t k, double d,
                              double L, bool want_energy, bool want_ds,
                              cl_pairlaw *out);

/* The law of pairs [k0, k0 + m): s[i] (and ds[i] if ds is not NULL) at
 * distance d[i], rest length L[k0 + i]; the same values as the scalar law
 * to rounding (forces/pairkern.h: vectorised, run-time dispatched). */
typedef void (*cl_pairlaw_batch_fn)(const void *params, size_t k0, size_t m,
                                    const double *d, const double *L,
                                    double *s, double *ds);

typedef struct {
    cl_pairset set;
    int (*couple)[2];   /* set.pair as plain (a, b) rows for the pattern */
    long *slot;         /* per pair: blocks aa, bb, ab, ba (-1: not a dof) */
    cl_pairlaw_fn law;
    cl_pairlaw_batch_fn batch; /* forces and Jacobians (NULL: pairdamp) */
    const void *params;
    const double *k_linear; /* k of a law that is k (d - L), per pair
                             * (springs) or one for all (Type1,
                             * k_uniform), for the fused pass's one loop
                             * (forces/pairdamp.h); else NULL */
    bool k_uniform;         /* k_linear is one k for every pair (Type1) */
    bool k_tension_only;    /* that law is 0 for d < L (Type1) */
    cl_pairkern kern;   /* the vectorised, threaded evaluation */
    bool clamp_transverse;
    double cut;         /* tearing: a pair breaks when d > cut L (0: never) */
    unsigned char *torn; /* per pair, nonzero once broken (NULL: no cut) */
    int (*broken)[2];   /* broken pairs (a, b) in the order they broke */
    size_t nbroken;
} cl_pairterm;

/* Takes ownership of `set`; nblk Jacobian blocks per pair in the kernel
 * buffers (1; 2 for pair damping's df/dv and df/dx). */
cl_status cl_pairterm_init(cl_pairterm *pt, cl_pairset set, cl_pairlaw_fn law,
                           cl_pairlaw_batch_fn batch, const void *params,
                           bool clamp_transverse, int nblk, cl_error *err);
void cl_pairterm_free(cl_pairterm *pt);

/* Switch tearing on for cut > 0 (allocates the per-pair flags once); cut = 0
 * leaves the term intact for ever. */
cl_status cl_pairterm_tear(cl_pairterm *pt, double cut, cl_error *err);

/* Whether pair k has broken. */
static inline bool cl_pairterm_is_torn(const cl_pairterm *pt, size_t k)
{
    return pt->torn && pt->torn[k];
}

/* f_a += (f0, f1, f2), f_b -= (f0, f1, f2): a pair's force into the
 * force array f (3 per particle); the force-only paths' scatter. */
static inline void cl_pair_scatter(double *CL_RESTRICT f, const cl_pair *pr,
                                   double f0, double f1, double f2)
{
    cl_pairkern_scatter(f, (size_t)pr->a, (size_t)pr->b, f0, f1, f2);
}

/* The block K of docs/model.md (3.1) (row-major 3x3) for direction u,
 * distance d. */
void cl_pair_block(const double u[3], double d, double s, double ds,
                   bool clamp_transverse, double K[9]);

/* Slots of the four blocks of every pair (a, b) in `set`, 4 per pair. */
cl_status cl_pair_slots(const cl_pairset *set, const cl_bpattern *pat,
                        const int *dof, long **slot, cl_error *err);

/* Add +sign*B to block `slot` of vals (no-op for slot < 0). */
void cl_block_add(double *vals, long slot, double sign, const double B[9]);

/* Phase 1 of pairs [k0, k1) into pt's kernel buffers (forces/pairkern.h):
 * geometry (recip: cl_pairkern_geometry's), law, forces s u and, with
 * blocks, K. */
void cl_pairterm_phase1(cl_pairterm *pt, const double *x, bool blocks,
                        bool recip, size_t k0, size_t k1, size_t base);

/* cl_term_type hooks for a cl_pairterm stored first in a term's state. */
size_t cl_pairterm_couplings(const void *state, const int (**pairs)[2]);
cl_status cl_pairterm_bind(void *state, const cl_bpattern *pat,
                           const int *dof, cl_error *err);
void cl_pairterm_eval(void *state, cl_eval *ev);
/* cl_term_type.threads for the same kind of state. */
cl_status cl_pairterm_threads(void *state, int threads, cl_error *err);
/* Tearing hooks for the same kind of state: step_done breaks every intact
 * pair with d > cut L at full-particle positions x and returns how many
 * broke now (0 without tearing); broken lists those broken so far. */
size_t cl_pairterm_step_done(void *state, const double *x, const double *v);
size_t cl_pairterm_broken(const void *state, const int (**pairs)[2]);

CL_END_DECLS

#endif
