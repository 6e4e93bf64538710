/* Spectrum of the linearised cloth at a state and the explicit step limits
 * it predicts (`clothode spectrum`, README "Using it"; the limits-* figures
 * of README "Reports", predicted against measured explicit limits).
 *
 * Two eigenvalue problems, both dense (GSL), so n <= CL_SPECTRUM_MAX_N:
 *  - stiffness: mu_i, eigenvalues of -M^-1/2 S M^-1/2, S the symmetric part
 *    of df/dx (symmetric for conservative forces): mu = w^2 > 0 for an
 *    oscillating mode, mu < 0 for a mode the forces push away (a buckling
 *    direction of compressed pairs), ascending;
 *  - first order: lambda_j, eigenvalues of the Jacobian of y' = (v, M^-1 f)
 *    (2n of them, damping and non-symmetric parts included).
 *
 * Predicted limits (linear stability, all modes at once), from each
 * integrator's stability region (integrators/region.h), not its name:
 *  - a method with stability function R (CL_REGION_TAYLOR; fe: 1 + z; rk4:
 *    the degree-4 Taylor polynomial) is stable with step h when
 *    |R(h lambda)| <= 1 for every lambda.  With tol = 1e-6 |lambda|_max:
 *    eigenvalues with Re lambda > tol, modes the true solution grows along
 *    too, cannot be stabilised and are left out (their number and the
 *    largest growth rate are reported); |Re lambda| <= tol counts as
 *    undamped (Re = 0), which gives fe a limit of 0; |lambda| <= tol
 *    (round-off zeros, e.g. the out-of-plane modes of a flat cloth at
 *    rest) constrains nothing;
 *  - the symplectic methods (CL_REGION_SYMPLECTIC: symplectic Euler either
 *    way, position and velocity Verlet): each stiffness mode z read as a
 *    damped oscillator x'' = -w^2 x - c x', w^2 = mu, c = z^T D z with D
 *    = -M^-1/2 sym(df/dv) M^-1/2 (exact for proportional damping,
 *    overdamped modes included), the largest h at which the method's step
 *    on it (region.h, oscillator) has spectral radius <= 1; 2/w on an
 *    undamped one; position Verlet's own velocity damping (run.
 *    verlet_damping) is not counted;
 *  - an implicit method whose region contains the sector
 *    |arg(-z)| <= alpha (CL_REGION_SECTOR) is stable for every h when
 *    every lambda, taken as above, lies in that sector; an undamped one
 *    lies on the imaginary axis, inside only for an A-stable method. */
#ifndef CL_SPECTRUM_H
#define CL_SPECTRUM_H

#include <stddef.h>
#include <stdio.h>

#include "core/decls.h"
#include "integrators/region.h"
#include "system/model.h"

CL_BEGIN_DECLS

#define CL_SPECTRUM_MAX_N (3 * 24 * 24)

typedef struct {
    size_t n;             /* unknowns, 3 nfree */
    double *mu;           /* n, ascending */
    double *c;            /* n: each stiffness mode's damping rate z^T D z,
                           * D = -M^-1/2 sym(df/dv) M^-1/2 (1/s) */
    double *re, *im;      /* 2n first-order eigenvalues, by decreasing |.| */
    double w_max;         /* sqrt(mu_max) (rad/s) */
    double lambda_max;    /* |lambda| of the first, largest eigenvalue */
    size_t n_negative;    /* mu < -tol^2 mu_max (tol as below): buckling */
    size_t n_zero;        /* |mu| <= tol^2 mu_max: zero to round-off */
    size_t n_growing;     /* first-order eigenvalues with Re > tol */
    double growth_max;    /* their largest real part (1/s), 0 if none */
} cl_spectrum;

/* At the free state (x, v) and time t.  CL_EUNSUPPORTED above
 * CL_SPECTRUM_MAX_N unknowns; CL_ESOLVER if GSL's QR iteration fails. */
cl_status cl_spectrum_compute(cl_model *m, double t, const double *x,
                              const double *v, cl_spectrum *s, cl_error *err);
void cl_spectrum_free(cl_spectrum *s);

/* The predicted largest stable step for region r: the limit of a Taylor
 * or symplectic region; for a sector, INFINITY when every eigenvalue lies
 * in it, else NAN (no prediction); NAN for the regions without one
 * (adaptive, projected). */
double cl_spectrum_step_limit(const cl_spectrum *s, const cl_region *r);

/* An explicit integrator whose step limit is predicted, with how. */
typedef struct {
    const char *integrator;
    const char *basis;    /* how, e.g. "|R(h lambda)| <= 1" */
    double h;             /* predicted largest stable step (inf: none) */
} cl_spectrum_limit;

/* The predicted limits of the registry's integrators with a Taylor region,
 * then of those with a symplectic one, each in registry order (fe, rk4,
 * symplectic-euler, symplectic-euler-x, verlet, velocity-verlet, and any
 * added to the registry): the first `cap` into out; returns how many
 * there are (out may be NULL with cap 0, to count them). */
size_t cl_spectrum_limits(const cl_spectrum *s, cl_spectrum_limit *out,
                          size_t cap);

/* kind,index,re,im rows (kind "mu" with im 0, or "lambda"), header first. */
void cl_spectrum_write(FILE *fp, const cl_spectrum *s);

/* The stiffness problem's modes at the free state (x, v) and time t
 * (n = sys->n <= CL_SPECTRUM_MAX_N): mu (n, ascending) and phi (n x n,
 * row-major, column k the orthonormal eigenvector of mu[k] in the
 * mass-weighted coordinates y = M^1/2 x), by GSL's gsl_eigen_symmv:
 * a displacement dx oscillates in mode k with amplitude phi_k . M^1/2 dx.
 * CL_EUNSUPPORTED above CL_SPECTRUM_MAX_N unknowns. */
cl_status cl_spectrum_modes(cl_model *m, double t, const double *x,
                            const double *v, double *mu, double *phi,
                            cl_error *err);

CL_END_DECLS

#endif
