/* A full Newton iteration for SUNDIALS' implicit integrators, through
 * SUNDIALS' generic nonlinear solver interface (SUNNonlinearSolver):
 * SUNDIALS' own SUNNonlinSol_Newton keeps the Newton matrix of its first
 * iteration for the whole solve (a modified Newton, or chord, iteration;
 * it renews it only when a solve fails with a stale matrix), and no
 * setting of ARKODE's (ARKStepSetLSetupFrequency,
 * ARKStepSetJacEvalFrequency, ARKStepSetNonlinConvCoef, ...) renews it
 * within a solve.  This one asks the integrator's linear solver setup
 * for a fresh Jacobian (jbad) at every iterate, as KINSOL does with
 * KINSetMaxSetupCalls(1) for the kinsol-* integrators; the integrator's
 * own residual, linear solve and convergence test are used unchanged.
 *
 * Where the Newton matrix changes within a step, at the kinks of Choi-Ko's
 * pair forces (a pair going taut adds ks u u^T), a chord iteration built
 * on the slack side diverges; a fixed-step method cannot retry with a
 * smaller step, so ARKODE's fixed-step methods use this one
 * (arkode_common.c). */
#ifndef CL_SUN_NEWTON_H
#define CL_SUN_NEWTON_H

#include <sundials/sundials_nonlinearsolver.h>

#include "core/decls.h"

CL_BEGIN_DECLS

/* A new full Newton solver on vectors like y, or NULL (out of memory);
 * SUNNonlinSolFree releases it. */
SUNNonlinearSolver cl_sun_newton_full(N_Vector y, SUNContext ctx);

CL_END_DECLS

#endif
