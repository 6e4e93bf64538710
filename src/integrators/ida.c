/* ida: SUNDIALS IDA on the implicit form
 * (docs/model.md, 1; docs/integrators.md, 6)
 *
 *   F(t, y, y') = [ x' - v ; M v' - f(t, x, v) ] = 0,   y = (x, v),
 *   2n unknowns,
 *
 * variable-order (1..5) variable-step BDF in fixed-leading-coefficient
 * form, Newton iteration, the linear systems with the iteration matrix
 *
 *   G = dF/dy + c_j dF/dy' = [ c_j I       -I            ]
 *                            [ -df/dx      c_j M - df/dv ]
 *
 * solved by the linear solver named by opts->linsol (--linsol):
 *
 *   klu-full  SUNLinSol_KLU with AMD ordering (SUNLinSol_KLUSetOrdering(LS,
 *             0)): G is assembled analytically in CSC from the pattern and
 *             value map of the first-order Jacobian, built once
 *             (linalg/firstorder.h: the same pattern, every diagonal entry
 *             stored; column pointers and row indices are rewritten on every
 *             call because IDA's SUNMatZero wipes them), so KLU analyses
 *             once and refactors numerically afterwards: the baseline;
 *   every solver of the linear-solver registry, auto the default (as for
 *   cvode-bdf)
 *             the half-size system (M - df/dv / c_j - df/dx / c_j^2) dx =
 *             (rv + c_j M rx - df/dv rx) / c_j^2, dv = c_j dx - rx solved by
 *             that cl_linsol (sun_reduced.h, linalg/linsol.h).
 *
 * dF/dy' = diag(I, M) is nonsingular: the system is an implicit ODE
 * (differential index 0, inside IDA's index-1 class) and every component
 * is differential (IDASetId all ones; the error test covers all of y).
 *
 * Consistent initial conditions are computed from the system directly,
 * not by IDACalcIC: y'(0) = (v0, M^-1 f(t0, x0, v0)) solves
 * F(t0, y0, y'(0)) = 0 for the given y0 exactly up to rounding (what
 * IDACalcIC(IDA_YA_YDP_INIT) would reach by Newton iteration on the same
 * equations).  It costs one force evaluation, counted in rhs_evals; a
 * failing or non-finite initial force fails create (CL_EBLOWUP or the
 * system's status).
 *
 * Options, error capture, blow-up policy of the residual and Jacobian
 * functions and statistics as in sun_adapter.h (rhs_evals = residual
 * evaluations + 1; lin_setups = factor or refactor calls; klu-full:
 * lin_solves = KLU solve calls, symbolic_facts = KLU analyses, 1 with the
 * fixed pattern; half-size solvers: as in cvode_bdf.c). */
#include "integrators/integrator.h"

#include <string.h>

#include <ida/ida.h>

#include "integrators/sun_adapter.h"
#include "integrators/sun_reduced.h"

static int ida_solve(cl_sun *s, double t_out)
{
    sunrealtype tret;
    return IDASolve(s->mem, t_out, &tret, s->y, s->yp, IDA_NORMAL);
}

static cl_status ida_reinit(cl_sun *s, double t, cl_error *err);

static const cl_sun_api ida_api = {
    .pkg = "IDA",
    .solve_name = "IDASolve",
    .has_yp = true,
    .set_err_handler = IDASetErrHandlerFn,
    .set_user_data = IDASetUserData,
    .sstolerances = IDASStolerances,
    .set_max_num_steps = IDASetMaxNumSteps,
    .set_init_step = IDASetInitStep,
    .set_max_ord = IDASetMaxOrd,
    .set_linear_solver = IDASetLinearSolver,
    .get_current_time = IDAGetCurrentTime,
    .get_current_step = IDAGetCurrentStep,
    .flag_name = IDAGetReturnFlagName,
    .collapse_warning = 0, /* IDA does not warn of t + h = t */
    .free_mem = IDAFree,
    .solve = ida_solve,
    .reinit = ida_reinit,
    .steps = IDAGetNumSteps,
    .rhs = IDAGetNumResEvals,
    .lin_rhs = IDAGetNumLinResEvals,
    .jac = IDAGetNumJacEvals,
    .setups = IDAGetNumLinSolvSetups,
    .lin_iters = IDAGetNumLinIters,
    .nl_iters = IDAGetNumNonlinSolvIters,
    .nl_fails = IDAGetNumNonlinSolvConvFails,
    .err_fails = IDAGetNumErrTestFails,
};

/* ---- residual ---------------------------------------------------------- */

static int ida_res(sunrealtype t, N_Vector yy, N_Vector yp, N_Vector rr,
                   void *data)
{
    cl_sun *s = data;
    size_t n = s->sys->n;
    const double *x = N_VGetArrayPointer(yy), *v = x + n;
    const double *xd = N_VGetArrayPointer(yp), *vd = xd + n;
    double *rx = N_VGetArrayPointer(rr), *rv = rx + n;
    int ret = cl_sun_force(s, t, x, v, rv);
    if (ret != 0)
        return ret;
    for (size_t i = 0; i < n; i++) {
        rx[i] = xd[i] - v[i];
        rv[i] = s->sys->mass[i] * vd[i] - rv[i];
    }
    return cl_sun_rhs_finite(s, rx, 2 * n, t);
}

/* ---- create / free ----------------------------------------------------- */

/* y'(0) = (v0, M^-1 f(t0, x0, v0)) into s->yp. */
static cl_status ida_initial_yp(cl_sun *s, double t0, cl_error *err)
{
    size_t n = s->sys->n;
    const double *x = N_VGetArrayPointer(s->y), *v = x + n;
    double *xd = N_VGetArrayPointer(s->yp), *vd = xd + n;
    s->own_rhs++;
    if (cl_sun_force(s, t0, x, v, vd) == 0) {
        memcpy(xd, v, n * sizeof *xd);
        for (size_t i = 0; i < n; i++)
            vd[i] *= s->inv_mass[i];
        if (cl_sun_rhs_finite(s, xd, 2 * n, t0) == 0)
            return CL_OK;
    }
    return cl_error_set(err, s->fail_rhs, "ida: the initial force for "
                        "y'(0) = (v0, M^-1 f) failed (%s%s) at t = %.9g",
                        cl_status_name(s->fail_rhs),
                        s->fail_nonfinite ? ": values not finite" : "", t0);
}

/* Restart after a change of the model (tearing, sun_adapter.h) from the
 * current y with the consistent y' = (v, M^-1 f(t, x, v)). */
static cl_status ida_reinit(cl_sun *s, double t, cl_error *err)
{
    cl_status st = ida_initial_yp(s, t, err);
    if (st != CL_OK)
        return st;
    int flag = IDAReInit(s->mem, t, s->y, s->yp);
    return flag < 0 ? cl_sun_fail(s, "IDAReInit", flag, err) : CL_OK;
}

static cl_status ida_memory(cl_sun *s, const cl_integrator_opts *o,
                            double t0, cl_error *err)
{
    cl_status st = cl_sun_created(s, IDACreate(s->ctx), "IDACreate", err);
    if (st != CL_OK)
        return st;
    int flag = IDAInit(s->mem, ida_res, t0, s->y, s->yp);
    if (flag < 0)
        return cl_sun_fail(s, "IDAInit", flag, err);
    if ((st = cl_sun_configure(s, o, err)) != CL_OK)
        return st;
    N_Vector id = N_VClone(s->y);
    if (!id)
        return cl_sun_sunfail(s, "N_VClone", 0, err);
    N_VConst(1.0, id);
    flag = IDASetId(s->mem, id); /* IDA keeps its own copy */
    N_VDestroy(id);
    if (flag < 0)
        return cl_sun_fail(s, "IDASetId", flag, err);
    return CL_OK;
}

static cl_status ida_create(const cl_system *sys, const cl_integrator_opts *o,
                            double t0, const double *x0, const double *v0,
                            void **state, cl_error *err)
{
    cl_sun *s = NULL;
    *state = NULL;
    cl_status st = cl_sun_alloc(sizeof *s, "ida", &ida_api, sys, o, t0, x0,
                                v0, true, false, &s, err);
    if (st == CL_OK)
        st = ida_initial_yp(s, t0, err);
    if (st == CL_OK)
        st = ida_memory(s, o, t0, err);
    if (st == CL_OK)
        st = cl_sunred_attach(s, o, true, err);
    return cl_sun_finish(s, st, cl_sun_free, state);
}

const cl_integrator_type cl_integrator_ida = {
    .name = "ida",
    .region = &cl_region_bdf5,
    .doc = "IDA on F = [x' - v; M v' - f] = 0, Newton, analytic Jacobian; "
           "--linsol as cvode-bdf (default auto)",
    .fixed_step = false,
    .takes_max_order = true,
    .takes_linsol = true,
    .linsol_default = CL_SUNRED_DEFAULT,
    .create = ida_create,
    .advance = cl_sun_advance,
    .stats = cl_sun_stats,
    .free = cl_sun_free,
};
