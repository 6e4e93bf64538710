/* cvode-bdf: SUNDIALS CVODE on the first-order form
 * (docs/model.md, 1; docs/integrators.md, 6)
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),   2n unknowns,
 *
 * variable-order variable-step BDF (orders 1..5), Newton iteration with
 * the linear systems (I - gamma J) dy = r,
 * J = [[0, I], [M^-1 df/dx, M^-1 df/dv]] analytic, solved by the linear
 * solver named by opts->linsol (--linsol):
 *
 *   klu-full  SUNLinSol_KLU with AMD ordering (SUNLinSol_KLUSetOrdering(LS,
 *             0)) on the full 2n x 2n matrix, J assembled in CSC from the
 *             pattern computed once (linalg/firstorder.h): the baseline;
 *   any solver of the linear-solver registry (auto the default):
 *             the half-size system (M - gamma df/dv - gamma^2 df/dx) dv =
 *             M rv + gamma df/dx rx, dx = rx + gamma dv solved by that
 *             cl_linsol (sun_reduced.h, linalg/linsol.h).
 *
 * Default auto, by measurement on hang (rtol 1e-4, atol 1e-6, T = 2 s,
 * CPU time): it runs pcg at CVODE's small steps, 5.5x faster than
 * klu-full at n = 16 and 32x at n = 32; the half-size direct solvers gain
 * only 1.0-1.6x (the table is in sun_reduced.h).
 * SUNDIALS 6.x API (SUNContext, sunrealtype).
 *
 * Options (tolerances, max steps, initial step), error capture, the
 * blow-up policy of the RHS and Jacobian functions and the statistics are
 * those of every SUNDIALS integrator here (sun_adapter.h).  klu-full: the
 * KLU solver is wrapped in the adapter's counting shell:
 * lin_solves = solve calls (one per Newton iteration), symbolic_facts = KLU
 * symbolic analyses, 1 for the whole run with the fixed pattern;
 * lin_setups = KLU factor or refactor calls, lin_iters = 0.  Half-size
 * solvers: lin_solves, lin_iters, symbolic_facts, lin_fallbacks,
 * lin_recoveries from the cl_linsol.  linsol names the solver; rhs_evals = CVODE's RHS evaluations
 * (none for the Jacobian, which is analytic). */
#include "integrators/integrator.h"

#include <cvode/cvode.h>

#include "integrators/sun_adapter.h"
#include "integrators/sun_reduced.h"

static cl_status cvb_create(const cl_system *sys, const cl_integrator_opts *o,
                            double t0, const double *x0, const double *v0,
                            void **state, cl_error *err)
{
    cl_sun *s = NULL;
    *state = NULL;
    cl_status st = cl_sun_cvode_create(sizeof *s, "cvode-bdf", CV_BDF, true,
                                       sys, o, t0, x0, v0, &s, err);
    if (st == CL_OK)
        st = cl_sunred_attach(s, o, false, err);
    return cl_sun_finish(s, st, cl_sun_free, state);
}

const cl_integrator_type cl_integrator_cvode_bdf = {
    .name = "cvode-bdf",
    .region = &cl_region_bdf5,
    .doc = "CVODE BDF, Newton, analytic Jacobian; --linsol auto (default) "
           "or any half-size solver (clothode list), klu-full",
    .fixed_step = false,
    .takes_max_order = true,
    .takes_linsol = true,
    .linsol_default = CL_SUNRED_DEFAULT,
    .create = cvb_create,
    .advance = cl_sun_advance,
    .stats = cl_sun_stats,
    .free = cl_sun_free,
};
