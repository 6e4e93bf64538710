/* Central pair forces (SPEC 3.1), shared by every pair model (Choi-Ko Type1,
 * Type2, springs).
 *
 * For a pair a-b: x_ab = x_b - x_a, d = |x_ab|, u = x_ab/d.  The force on a is
 * f_a = s(d) u, on b it is -f_a.  With
 *     K = s'(d) u u^T + (s(d)/d) (I - u u^T)
 * df_a/dx_b = df_b/dx_a = K and df_a/dx_a = df_b/dx_b = -K.  The energy is
 * E(d) = integral_L^d s(r) dr.  The "transverse" term (s/d)(I - uu^T) is
 * negative under compression and makes -df/dx indefinite; with
 * clamp_transverse it is dropped where s < 0 (jacobian.transverse = clamp).
 *
 * A model supplies the scalar law s, s', E through a cl_pairlaw_fn. */
#ifndef CL_PAIRTERM_H
#define CL_PAIRTERM_H

#include <stdbool.h>

#include "forces/term.h"
#include "model/pairs.h"

typedef struct {
    double s;   /* s(d): > 0 pulls the pair together */
    double ds;  /* s'(d) */
    double e;   /* E(d) = integral_L^d s(r) dr (only if asked for) */
} cl_pairlaw;

/* Scalar law of pair k (rest length L) at distance d. */
typedef void (*cl_pairlaw_fn)(const void *params, size_t k, double d,
                              double L, bool want_energy, cl_pairlaw *out);

typedef struct {
    cl_pairset set;
    int (*couple)[2];   /* set.pair as plain (a, b) rows for the pattern */
    long *slot;         /* per pair: blocks aa, bb, ab, ba (-1: not a dof) */
    cl_pairlaw_fn law;
    const void *params;
    bool clamp_transverse;
} cl_pairterm;

/* Takes ownership of `set`. */
cl_status cl_pairterm_init(cl_pairterm *pt, cl_pairset set, cl_pairlaw_fn law,
                           const void *params, bool clamp_transverse,
                           cl_error *err);
void cl_pairterm_free(cl_pairterm *pt);

/* The block K of SPEC 3.1 (row-major 3x3) for direction u, distance d. */
void cl_pair_block(const double u[3], double d, double s, double ds,
                   bool clamp_transverse, double K[9]);

/* Slots of the four blocks of every pair (a, b) in `set`, 4 per pair. */
cl_status cl_pair_slots(const cl_pairset *set, const cl_bpattern *pat,
                        const int *dof, long **slot, cl_error *err);

/* Add +sign*B to block `slot` of vals (no-op for slot < 0). */
void cl_block_add(double *vals, long slot, double sign, const double B[9]);

/* cl_term_type hooks for a cl_pairterm stored first in a term's state. */
size_t cl_pairterm_couplings(const void *state, const int (**pairs)[2]);
cl_status cl_pairterm_bind(void *state, const cl_bpattern *pat,
                           const int *dof, cl_error *err);
void cl_pairterm_eval(void *state, cl_eval *ev);

#endif
