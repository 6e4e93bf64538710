/* Position-based distance constraints (the Verlet-and-PBD report,
 * "Positional constraint"; Mueller, Heidelberger, Hennix, Ratcliff,
 * "Position based dynamics", JVRCI 2007; docs/model.md 3.4), the term
 * `pbd`.
 *
 * Constraints C_ab(x) = |x_a - x_b| - L_ab = 0 on the pairs of constraint
 * levels 1..k (model/pairs.h: level l joins particles l apart along the
 * axes and both diagonals; level 1 = axis and diagonal neighbours).  On a
 * mesh cloth level 1 is the triangle edges and level 2 adds the bend pairs
 * (the far vertices of neighbouring triangles, as the mass-spring mesh
 * network of forces/springs.h); levels > 2 are refused there.  The
 * term has no force, no Jacobian and no potential: it acts only through
 * the system's `project` hook, which position-based integrators
 * (verlet-pbd) call after each step; xpbd takes its pairs as hard
 * constraints (compliance 0) and pd refuses them.  Every other
 * integrator ignores it.
 *
 * Projection (non-linear Gauss-Seidel, `iterations` sweeps over all
 * intact pairs in a fixed order), for a pair a-b with d = |x_a - x_b|,
 * u = (x_a - x_b)/d and inverse masses w (w = 0 for a pinned particle,
 * which therefore never moves):
 *     dx_a = -w_a / (w_a + w_b) K (d - L) u,
 *     dx_b = +w_b / (w_a + w_b) K (d - L) u,
 * K = `stiffness` in (0, 1] (K = 1 satisfies the pair exactly).  The
 * corrections conserve the mass-weighted centre sum m_a x_a + m_b x_b of
 * two free particles, hence the centre of mass of a cloth without pins.
 * The Verlet-and-PBD report's code moves both (equal-mass) particles by
 * K_rep (d - L), so its recommended K_rep = 0.5 is K = 1 here
 * (K = 2 K_rep).  K applies per sweep, as in that code (Mueller et al.'s
 * iteration-independent 1 - (1 - K)^(1/n) is not used); pairs with
 * w_a + w_b = 0 or d = 0 are skipped.
 *
 * Energy: none.  The term is reported as non-conservative with zero
 * dissipated power: a constraint "potential" (K/2) sum (d - L)^2 would be
 * a diagnostic with no force behind it, and counting it as potential
 * energy would make the energy balance meaningless.
 *
 * Tearing ([tear] cut > 0): a constraint breaks for good when d > cut L
 * after an accepted step (forces/pairterm.h), the same rule as springs.
 *
 * INI section [pbd]: enabled (false), levels (>= 1, default 1), stiffness
 * (K in (0, 1], default 1), iterations (>= 1, default 10). */
#ifndef CL_PBD_H
#define CL_PBD_H

#include "core/decls.h"
#include "forces/term.h"

CL_BEGIN_DECLS

extern const cl_term_type cl_term_pbd;

CL_END_DECLS

#endif
