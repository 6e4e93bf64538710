/* Self-contact: repulsion between particles of the cloth that are not
 * topological neighbours (docs/model.md 3.5).
 *
 * Two particles a, b more than `ring` steps apart in the nearest-neighbour
 * graph (model/ring.h) and closer than the thickness h_s repel along
 * their separation with the penalty law
 *     s(d) = -k_s (h_s - d),   E(d) = k_s (h_s - d)^2 / 2   (d < h_s),
 * or (law = barrier) IPC's clamped log barrier E(d) = k_s b(d),
 * s(d) = k_s b'(d) (forces/logbarrier.h), on the central-pair machinery of docs/model.md 3.1 (forces/pairterm.h:
 * f_a = s u, u = (x_b - x_a)/d, blocks K = s'(d) u u^T + (s/d)(I - u u^T),
 * s' = k_s for the penalty, k_s b''(d) for the barrier).
 * The pairs are found at every evaluation by a spatial hash with cells of
 * side h_s (forces/sphash.h), never by trying all pairs, with no
 * allocation.
 *
 * The Jacobian is lumped (docs/model.md 3.5, eq. 3.8): the pairs change
 * from one evaluation to the next while the system's block pattern is
 * built once, so the term writes only the diagonal blocks
 * df_a/dx_a = df_b/dx_b = -s'(d) u u^T of each pair, the normal part of -K
 * (the transverse part is a negative stiffness, unbounded as d -> 0), and
 * leaves out the coupling blocks +K: implicit methods run a modified
 * Newton iteration on contact.  cl_selfcontact_dense gives the exact
 * Jacobian.
 *
 * INI section [selfcontact]:
 *   enabled    (false) switches the term on;
 *   thickness  h_s (m, > 0; required): smaller than the rest distance of
 *              every pair more than `ring` steps apart (checked);
 *   stiffness  k_s (N/m, > 0; required): the penalty's spring, or the
 *              barrier's factor kappa;
 *   law        penalty (default) | barrier;
 *   ring       (1 .. 8, default 2): pairs within this many steps do not
 *              repel (on a grid: within a (2 ring + 1)^2 block). */
#ifndef CL_SELFCONTACT_H
#define CL_SELFCONTACT_H

#include "core/decls.h"
#include "forces/term.h"

CL_BEGIN_DECLS

extern const cl_term_type cl_term_selfcontact;

/* The smallest distance between two particles more than `ring` steps
 * apart at full-particle positions x (3 np), among those closer than the
 * thickness; INFINITY if none is. */
double cl_selfcontact_closest(void *state, const double *x);

/* The exact df/dx of the term at x added into J (dense, row-major,
 * 3 np x 3 np): the coupling blocks the lumped Jacobian leaves out
 * included. */
void cl_selfcontact_dense(void *state, const double *x, double *J);

CL_END_DECLS

#endif
