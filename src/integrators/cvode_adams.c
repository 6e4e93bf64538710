/* cvode-adams: SUNDIALS CVODE Adams-Moulton with fixed-point iteration,
 * the non-stiff reference (docs/integrators.md, 6)
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),   2n unknowns,
 *
 * variable-order (1..12) variable-step Adams-Moulton; the implicit
 * corrector equations are solved by plain functional iteration
 * (SUNNonlinSol_FixedPoint without Anderson acceleration, CVODE's default
 * of at most 3 iterations per attempt): no Jacobian and no linear solver.
 * Its step is bounded by the stiffness of the cloth (roughly h < 1 /
 * |largest eigenvalue of J|), so on stiff problems it takes many steps;
 * it is the reference for how much an implicit method's Newton solves buy.
 *
 * Options, error capture, blow-up policy and statistics as in
 * sun_adapter.h; jac_evals, lin_setups, lin_solves, lin_iters and
 * symbolic_facts are 0, nonlin_iters counts fixed-point iterations. */
#include "integrators/integrator.h"

#include <cvode/cvode.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include "integrators/sun_adapter.h"

static cl_status adams_nls(cl_sun *s, cl_error *err)
{
    s->nls = SUNNonlinSol_FixedPoint(s->y, 0, s->ctx);
    if (!s->nls)
        return cl_sun_sunfail(s, "SUNNonlinSol_FixedPoint", 0, err);
    int flag = CVodeSetNonlinearSolver(s->mem, s->nls);
    if (flag < 0)
        return cl_sun_fail(s, "CVodeSetNonlinearSolver", flag, err);
    return CL_OK;
}

static cl_status adams_create(const cl_system *sys,
                              const cl_integrator_opts *o, double t0,
                              const double *x0, const double *v0,
                              void **state, cl_error *err)
{
    cl_sun *s = NULL;
    *state = NULL;
    cl_status st = cl_sun_cvode_create(sizeof *s, "cvode-adams", CV_ADAMS,
                                       false, sys, o, t0, x0, v0, &s, err);
    if (st == CL_OK)
        st = adams_nls(s, err);
    return cl_sun_finish(s, st, cl_sun_free, state);
}

const cl_integrator_type cl_integrator_cvode_adams = {
    .name = "cvode-adams",
    .region = &cl_region_adaptive,
    .doc = "CVODE Adams-Moulton, fixed-point iteration (non-stiff reference)",
    .fixed_step = false,
    .takes_max_order = true,
    .takes_linsol = false,
    .create = adams_create,
    .advance = cl_sun_advance,
    .stats = cl_sun_stats,
    .free = cl_sun_free,
};
