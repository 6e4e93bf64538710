/* Shared plumbing of the fixed-step fully implicit integrators solved by
 * KINSOL (docs/model.md, 1; docs/integrators.md, 4): kinsol-be,
 * kinsol-bdf2, kinsol-midpoint, kinsol-galpha.
 *
 * Reduced velocity form.  For x' = v, M v' = f(t, x, v) each step from
 * t_n to t_{n+1} = t_n + h solves for the new velocity v1 (3 per free
 * particle) the nonlinear system
 *
 *     R(v1) = M (v1 - vb) - c f(te, xe, ve0 + beta v1) = 0,
 *     xe = x_n + alpha (v1 - p)        (p: the predictor, below)
 *
 * and then sets x1 = x1b + alpha1 v1.  Its exact Newton matrix is
 *
 *     dR/dv1 = M - a df/dv - b df/dx,     a = c beta,  b = c alpha,
 *
 * the half-size matrix of linalg/linsol.h, evaluated at the current Newton
 * iterate.  A method (a cl_kin_scheme) gives the scalars c, alpha, beta,
 * alpha1 and te - t_n (in units of h where they are times), the scheme of
 * its first step, and how to fill vb, ve0, x1b and the predictor p from
 * the history (x_n, v_n and, once one step is done, x_{n-1}, v_{n-1});
 * each method file states its own formulas.  If the method evaluates f at
 * the position xe0 + alpha v1, its p is (x_n - xe0)/alpha.
 *
 * Newton.  KINSOL with the KIN_NONE strategy: plain full Newton steps, no
 * line search, no step-length cap (KINSetMaxNewtonStep = DBL_MAX), the
 * Jacobian and the factorisation renewed at every iteration
 * (KINSetMaxSetupCalls = 1), so that iteration counts compare directly with
 * the semi-implicit methods and one iteration is exactly one Newton step.
 * KINSOL sees a custom "direct" SUNLinearSolver and a shell SUNMatrix (both
 * made by the SUNDIALS adapter, sun_adapter.h): its
 * Jacobian callback evaluates df/dx, df/dv at the iterate (the system's
 * block values), the solver's setup calls cl_linsol setup with (a, b) and
 * its solve calls cl_linsol solve (opts->linsol, default klu).
 *
 * Predictor.  Newton starts from the v1 = p that leaves the evaluation
 * position at x_n, i.e. from "the cloth does not move": f and its Jacobian
 * are first evaluated at x_n -- bit for bit, since xe is computed as
 * x_n + alpha (v1 - p), so that pairs sitting exactly on a kink (d = L at
 * rest; docs/architecture.md, "Checks every force term passes") see the
 * same branch as the semi-implicit methods do.
 * Then one Newton iteration is the linearly implicit method obtained by
 * linearising f about (x_n, v_n) -- backward Euler: Baraff-Witkin's step;
 * BDF2: Jiao's eq. (15) -- exactly whenever f is affine in v with a
 * df/dx that does not depend on v (no damping, Choi-Ko pair damping,
 * linear drag), and on every linear model.  (The predictor v1 = v_n would
 * linearise about x_n + alpha v_n instead and give that equivalence only
 * on linear models.)
 *
 * Tolerance and iteration cap (opts->newton_tol, default 1e-10;
 * opts->newton_maxit, default 50).  With v_ref = max(1 m/s, max |v_n|):
 *  - the residual is measured in velocity units relative to v_ref: KINSOL's
 *    fscale_i = 1 / (m_i v_ref), so max_i |R_i| / (m_i v_ref) is the
 *    relative velocity defect of the step; uscale_i = 1 / v_ref;
 *  - a step converges when that defect is <= newton_tol (KIN_SUCCESS), or
 *    when the last Newton update is <= newton_tol relative
 *    (max_i |dv_i| / (v_ref + |v1_i|), KINSetScaledStepTol, reported as
 *    KIN_STEP_LT_STPTOL: with full steps and the exact Jacobian this is the
 *    usual update test, and the one that still works for stiff forces whose
 *    round-off in R exceeds the defect tolerance; its threshold is never
 *    below 10 DBL_EPSILON, where an update is round-off and the iterate
 *    cannot improve), or when the predictor already satisfies the system
 *    (KIN_INITIAL_GUESS_OK);
 *  - newton_maxit = 1 is the linearly implicit mode: exactly one full
 *    Newton step from the predictor, whatever its residual (newton_tol is
 *    ignored; both KINSOL tolerances are set to DBL_MIN so that it neither
 *    stops before nor reports after), and the cap KINSOL then reports
 *    (KIN_MAXITER_REACHED) is a valid outcome.  The one exception: a
 *    predictor with an exactly zero residual takes no step (its Newton
 *    step would be exactly zero);
 *  - newton_maxit >= 2 (or 0: the default 50) asks for convergence: the
 *    cap reached without it is a failure.
 *
 * Failures.  Fixed-step methods do not retry: a step whose Newton solve
 * fails stops the run (x, v keep the last completed step), counted in
 * nonlin_fails, with a message naming the method, the step, its times and
 * KINSOL's flag: CL_ESOLVER for a Newton or KINSOL failure, the linear
 * solver's status and message when it failed, the system's status
 * (CL_EBLOWUP for non-finite values) when a force or Jacobian evaluation
 * failed (the residual and Jacobian callbacks then return -1:
 * unrecoverable, so KINSOL never silently halves a step).  KINSOL's own
 * messages are captured (KINSetErrHandlerFn), never printed.
 *
 * Barriers.  On a system with a step_fraction (barrier obstacles,
 * contact/barrier.h) KINSOL's line search cannot take the filter, so each
 * step is solved by a Newton loop of this file instead (docs/
 * integrators.md 4.1): the Newton step du of the same matrix and linear
 * solver, cut to the fraction of it that keeps the evaluation point
 * outside every barrier obstacle (0.8 of the first time of impact), then
 * halved until the scaled residual norm decreases (Armijo, 1e-4; at most
 * 30 halvings, after which the last feasible trial is taken; an
 * infeasible trial is halved).  The initial-guess test (scaled residual
 * <= 0.01 newton_tol), the convergence tests (scaled residual <=
 * newton_tol, or the full update du below it relative), newton_maxit and
 * the one-step mode are KINSOL's; iterations are counted the same way.
 * Systems without barriers use KINSOL as above, unchanged.
 *
 * Rayleigh damping (opts->rayleigh_alpha, rayleigh_beta; docs/
 * integrators.md 4.4).  With either > 0 the force in R is
 * f - (ra M + rb K*) ve, K* = -df/dx at (te, x_n + (te - t_n) v_n, v_n),
 * evaluated once per step before the Newton solve (the predicted
 * evaluation point: O(h^2) from it, so a second-order method stays
 * second order).  The Newton matrix is exact: sr M - a (df/dv - rb K*)
 * - b df/dx, sr = 1 + a ra, which the linear solver gets as
 * M - (a/sr) df/dv' - (b/sr) df/dx (df/dv' = df/dv + rb df/dx*), and the
 * solution is divided by sr.  Without it nothing changes (outputs
 * byte-identical).
 *
 * Carried acceleration (cl_kin_scheme.finish; generalized-alpha): M^-1 f
 * at the initial state (one force evaluation in create, counted), then
 * what finish sets after each converged step; a contact projection after
 * the step moves x and v, not it.
 *
 * Statistics: steps; rhs_evals = force evaluations (residuals); jac_evals
 * = system Jacobian evaluations (Rayleigh's K* included); lin_setups,
 * lin_solves, lin_iters,
 * symbolic_facts from the linear solver's counters; nonlin_iters = the sum
 * of KINGetNumNonlinSolvIters over the steps; nonlin_fails = steps whose
 * solve failed.  Output times must be whole multiples of h from t0
 * (cl_fixed_steps_to); the time after step k is t0 + k h.  Everything is
 * allocated in create; a step allocates nothing. */
#ifndef CL_KINSOL_COMMON_H
#define CL_KINSOL_COMMON_H

#include "core/decls.h"
#include "integrators/define.h"
#include "integrators/integrator.h"

CL_BEGIN_DECLS

struct cl_kin_scheme;

/* One step's vectors.  Inputs (filled by the common code): n, h, x, v
 * (x_n, v_n), xp, vp (x_{n-1}, v_{n-1}), the step's scheme sc and, for a
 * scheme with a finish hook, acc (its carried acceleration a_n, kept by
 * the common code: M^-1 f(t0, x0, v0) before the first step, then what
 * finish wrote).  Outputs (n each, filled by the scheme): vb, ve0, x1b
 * and pred (the predictor p of v1). */
typedef struct {
    size_t n;
    double h;
    const double *x, *v, *xp, *vp;
    const struct cl_kin_scheme *sc;
    double *acc;
    double *vb, *ve0, *x1b, *pred;
} cl_kin_step;

typedef struct cl_kin_scheme {
    const char *name;  /* registry name, for messages */
    double c;          /* R = M (v1 - vb) - (c h) f(te, xe, ve) */
    double alpha;      /* xe = x_n + (alpha h)(v1 - pred) */
    double beta;       /* ve = ve0 + beta v1 */
    double alpha1;     /* x1 = x1b + (alpha1 h) v1 */
    double te;         /* f is evaluated at t_n + te h */
    /* scheme of the first step (no x_{-1}, v_{-1} yet); NULL: this one */
    const struct cl_kin_scheme *start;
    void (*prepare)(cl_kin_step *st); /* fill the outputs of st */
    /* A scheme whose scalars depend on the options (generalized-alpha's
     * rho_inf): configure checks them and sets c, alpha, beta, alpha1,
     * te and par in the state's own copy of the scheme; NULL: fixed. */
    cl_status (*configure)(const cl_integrator_opts *o,
                           struct cl_kin_scheme *own, cl_error *err);
    /* A scheme that carries an acceleration: after each converged step,
     * before the history moves on, finish sets st->acc to a_{n+1} from
     * the new velocity v1 (st->v is still v_n); NULL: none. */
    void (*finish)(cl_kin_step *st, const double *v1);
    double par[4];     /* the scheme's parameters, set by configure */
} cl_kin_scheme;

cl_status cl_kin_create(const cl_kin_scheme *sc, const cl_system *sys,
                        const cl_integrator_opts *o, double t0,
                        const double *x0, const double *v0, void **state,
                        cl_error *err);
cl_status cl_kin_advance(void *state, double t_out, double *x, double *v,
                         cl_error *err);
void cl_kin_stats(const void *state, cl_stats *out);
void cl_kin_free(void *state);

/* Backward Euler (kinsol-be, and kinsol-bdf2's first step). */
extern const cl_kin_scheme cl_kin_scheme_be;

/* Define the integrator table `ident` for the scheme `scheme`, with the
 * stability region region_; rho_inf_ true when the scheme reads
 * opts->rho_inf. */
#define CL_KIN_INTEGRATOR(ident, scheme, name_, region_, doc_, rho_inf_)    \
    CL_INTEGRATOR_CREATE(ident, cl_kin_create, &(scheme))                   \
    const cl_integrator_type ident = {                                      \
        .name = (name_),                                                    \
        .region = (region_),                                                \
        .doc = (doc_),                                                      \
        .fixed_step = true,                                                 \
        .takes_linsol = true,                                               \
        .takes_newton_maxit = true,                                         \
        .takes_lin_tol = true,                                              \
        .takes_rayleigh = true,                                             \
        .takes_rho_inf = (rho_inf_),                                        \
        .create = ident##_create,                                           \
        .advance = cl_kin_advance,                                          \
        .stats = cl_kin_stats,                                              \
        .free = cl_kin_free,                                                \
    }

CL_END_DECLS

#endif
