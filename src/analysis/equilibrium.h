/* The static equilibrium of a cloth: f(t, x, 0) = 0 for the free
 * positions x, e.g. the hanging cloth under gravity, whose pins and
 * weight put it in tension (the prestressed state of the numerical
 * damping study, analysis/numdamp.h).
 *
 * Pseudo-transient continuation (Kelley and Keyes, "Convergence analysis
 * of pseudo-transient continuation", 1998): from the initial positions,
 * steps dx = (M / tau^2 - K)^-1 f(x), K = df/dx at x (dense, GSL's LU: so
 * n <= CL_SPECTRUM_MAX_N); each is a backward Euler step of size tau
 * from rest.  tau starts small (1e-3 s, where M / tau^2 dominates K and a
 * step follows the forces) and grows fourfold after every step that
 * lowers the residual |M^-1/2 f|_2; a step that raises it tenfold is
 * undone and tau quartered; so the last steps are Newton's.  The test is
 * max |M^-1 f| <= tol.  It converges in a few steps where the equilibrium
 * is near (the cloth hanging in its plane from a pinned edge: 7 steps
 * from rest at 10 x 10), slowly where it is far (the cloth released
 * horizontally from two corners). */
#ifndef CL_EQUILIBRIUM_H
#define CL_EQUILIBRIUM_H

#include "core/decls.h"
#include "system/model.h"

CL_BEGIN_DECLS

typedef struct {
    int steps;            /* steps taken (accepted or not) */
    double residual;      /* max |M^-1 f(t, x, 0)| at the end (m/s^2) */
} cl_equilibrium_info;

/* x (the free positions, n = sys->n) moved to the equilibrium at time t,
 * max |M^-1 f| <= tol (m/s^2) within max_steps steps: else CL_ESOLVER
 * (x the last accepted state); CL_EUNSUPPORTED above CL_SPECTRUM_MAX_N
 * unknowns. */
cl_status cl_equilibrium_find(cl_model *m, double t, double *x, double tol,
                              int max_steps, cl_equilibrium_info *info,
                              cl_error *err);

CL_END_DECLS

#endif
