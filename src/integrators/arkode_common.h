/* SUNDIALS ARKODE's ARKStep (docs/integrators.md, 10): the module behind
 * arkode-dirk, arkode-dirk-fixed, arkode-imex and arkode-imex-fixed, on
 * the SUNDIALS adapter (sun_adapter.h) and its Newton linear solvers
 * (sun_reduced.h) exactly as cvode-bdf uses them.
 *
 * Form.  y = (x, v), 2n unknowns, identity mass, as for CVODE:
 *
 *   DIRK  y' = f_I(t, y) = (v, M^-1 f(t, x, v)),
 *   IMEX  y' = f_E(t, y) + f_I(t, y),
 *         f_I = (v, M^-1 f_impl(t, x, v)),   f_E = (0, M^-1 f_expl(t, x, v)),
 *
 * f_impl and f_expl the forces of the terms the system puts in its
 * implicit part (system.h implicit_terms: each term's `imex` key; stiff
 * terms implicit by default, gravity and Type2 bending explicit) and of
 * the rest.  x' = v stays implicit, so a stiff spring is implicit in both
 * of its unknowns.  Every stage's Newton matrix is I - gamma J_I with
 * J_I = [[0, I], [M^-1 Kx, M^-1 Kv]] (Kx, Kv of the implicit terms): the
 * matrix of CVODE's Newton iteration, solved by the same half-size
 * system (M - gamma Kv - gamma^2 Kx) and every --linsol (sun_reduced.h),
 * gamma = h a_ii from ARKStepGetCurrentGamma.
 *
 * Tables (opts->table, --table NAME): DIRK methods take SUNDIALS' built-in
 * DIRK tables by name (ARKodeButcherTable_LoadDIRK; the names without the
 * ARKODE_ prefix, e.g. SDIRK_2_1_2, TRBDF2_3_3_2, ARK436L2SA_DIRK_6_3_4,
 * the default) and two tables of their own, for fixed steps only (no
 * embedded error estimate):
 *
 *   BACKWARD_EULER_1_1     c = 1,   A = 1,   b = 1  (kinsol-be's method)
 *   IMPLICIT_MIDPOINT_1_2  c = 1/2, A = 1/2, b = 1  (kinsol-midpoint's)
 *
 * IMEX methods take Kennedy and Carpenter's additive pairs ("Additive
 * Runge-Kutta schemes for convection-diffusion-reaction equations", 2003)
 * by the pair's name: ARK324L2SA (order 3), ARK436L2SA (4, the default),
 * ARK548L2SA (5): the ERK and DIRK tables ARKODE_<name>_ERK_* and
 * ARKODE_<name>_DIRK_*.
 *
 * Steps.  Adaptive methods: ARKODE's error control at rtol, atol (the
 * adapter's defaults), output by its interpolation at t_out.  Fixed-step
 * methods: ARKStepSetFixedStep(dt) and one ARKStepEvolve(ARK_ONE_STEP) per
 * step, as many as cl_fixed_steps_to counts; rtol and atol then only
 * weigh the Newton convergence test.
 *
 * Newton (ARKODE's own modified Newton iteration on every implicit stage):
 * opts->newton_maxit > 0 sets its iterations per stage
 * (ARKStepSetMaxNonlinIters; default ARKODE's 3 for adaptive steps,
 * CL_ARK_FIXED_MAXIT = 10 for fixed ones, which cannot retry a failed
 * stage with a smaller step: on hang at n = 6, dt = 1e-3, the IMEX pair's
 * modified Newton, whose Jacobian ARKODE keeps for up to 51 steps, needs
 * 3.5 per stage on average and fails with 3); opts->newton_tol > 0 its
 * convergence coefficient (ARKStepSetNonlinConvCoef: the WRMS norm of the
 * last correction, in the weights of rtol and atol, below it; default
 * 0.1).  newton_maxit = 1 is one linearisation per stage: the test is
 * switched off (coefficient 1e100, and ARKStepSetEpsLin scaled down by as
 * much, so that the iterative linear solvers keep their tolerance of
 * 0.05 x 0.1) and the Jacobian and Newton matrix are renewed at every
 * step (ARKStepSetJacEvalFrequency and ARKStepSetLSetupFrequency 1), so
 * that backward Euler with one iteration
 * is Baraff-Witkin's linearised step, like kinsol-be's.  Otherwise the
 * fixed-step methods solve their stages with sun_newton.h's solver:
 * ARKODE's modified Newton iteration, then, where it fails to converge
 * (a kink of the pair forces crossed within the stage), the full one.
 *
 * A solved stage's f_I is deduced from the stage equation
 * (ARKStepSetDeduceImplicitRhs), not evaluated anew: y_{n+1} is then the
 * last stage itself for the stiffly accurate tables, whatever the Newton
 * iterations (docs/integrators.md 10).
 *
 * Statistics: those of the adapter (sun_adapter.h), rhs_evals = ARKODE's
 * evaluations of f_E and f_I together (each of them a force evaluation of
 * its terms). */
#ifndef CL_ARKODE_COMMON_H
#define CL_ARKODE_COMMON_H

#include "core/decls.h"
#include "integrators/define.h"
#include "integrators/integrator.h"
#include "integrators/sun_adapter.h"
#include "integrators/sun_reduced.h"

CL_BEGIN_DECLS

/* The default tables. */
#define CL_ARK_DIRK_DEFAULT "ARK436L2SA_DIRK_6_3_4"
#define CL_ARK_IMEX_DEFAULT "ARK436L2SA"
#define CL_ARK_FIXED_MAXIT 10

typedef struct {
    const char *name;   /* integrator name */
    bool fixed;         /* fixed step opts->dt, else rtol / atol */
    bool imex;          /* an ERK + DIRK pair on the system's split */
} cl_ark_method;

cl_status cl_ark_create(const cl_ark_method *m, const cl_system *sys,
                        const cl_integrator_opts *o, double t0,
                        const double *x0, const double *v0, void **state,
                        cl_error *err);
cl_status cl_ark_advance(void *state, double t_out, double *x, double *v,
                         cl_error *err);

/* One registry row (integrators/registry.c): the table
 * cl_integrator_<ident> of the method {name_, fixed_, imex_}. */
#define CL_ARK_INTEGRATOR(ident, name_, fixed_, imex_, region_, doc_)      \
    static const cl_ark_method ident##_method = {(name_), (fixed_),        \
                                                 (imex_)};                 \
    CL_INTEGRATOR_CREATE(ident, cl_ark_create, &ident##_method)            \
    const cl_integrator_type cl_integrator_##ident = {                     \
        .name = (name_),                                                   \
        .region = (region_),                                               \
        .doc = (doc_),                                                     \
        .fixed_step = (fixed_),                                            \
        .takes_linsol = true,                                              \
        .linsol_default = CL_SUNRED_DEFAULT,                               \
        .takes_newton_maxit = true,                                        \
        .newton_per_stage = true,                                          \
        .takes_table = true,                                               \
        .create = ident##_create,                                          \
        .advance = cl_ark_advance,                                         \
        .stats = cl_sun_stats,                                             \
        .free = cl_sun_free,                                               \
    }

CL_END_DECLS

#endif
