/* cvode-bdf: SUNDIALS CVODE on the first-order form (SPEC 1, 5)
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),   2n unknowns,
 *
 * variable-order variable-step BDF (orders 1..5), Newton iteration, the
 * linear systems (I - gamma J) dy = r solved by SUNLinSol_KLU with AMD
 * ordering (SUNLinSol_KLUSetOrdering(LS, 0)) and the analytic sparse
 * Jacobian J = [[0, I], [M^-1 df/dx, M^-1 df/dv]] assembled in CSC from the
 * pattern computed once (linalg/firstorder.h).  SUNDIALS 6.x API
 * (SUNContext, sunrealtype).
 *
 * Options (tolerances, max steps, initial step), error capture, the
 * blow-up policy of the RHS and Jacobian functions and the statistics are
 * those of every SUNDIALS integrator here (sun_common.h).  The KLU solver
 * is wrapped in a counting SUNLinearSolver (lscount.h): lin_solves = solve
 * calls (one per Newton iteration), symbolic_facts = KLU symbolic analyses,
 * 1 for the whole run with the fixed pattern; lin_setups = KLU factor or
 * refactor calls, lin_iters = 0, rhs_evals = CVODE's RHS evaluations (none
 * for the Jacobian, which is analytic). */
#include "integrators/integrator.h"

#include <cvode/cvode.h>

#include "integrators/sun_common.h"
#include "linalg/firstorder.h"

typedef struct {
    cl_sun base;     /* first: CVODE's user data is the whole state */
    cl_firstorder fo;
} cl_cvbdf;

static int cvb_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J,
                   void *data, N_Vector t1, N_Vector t2, N_Vector t3)
{
    cl_cvbdf *s = data;
    size_t n = s->base.sys->n;
    const double *x = N_VGetArrayPointer(y), *v = x + n;
    (void)fy, (void)t1, (void)t2, (void)t3;
    int ret = cl_sun_jacobian(&s->base, t, x, v);
    if (ret != 0)
        return ret;
    if (cl_firstorder_fill(&s->fo, s->base.dfdx, s->base.dfdv, J, NULL) !=
        CL_OK)
        return -1;
    return 0;
}

static void cvb_free(void *state)
{
    cl_cvbdf *s = state;
    if (s)
        cl_firstorder_free(&s->fo);
    cl_sun_free(state);
}

/* The pattern, then KLU on it and the Jacobian function. */
static cl_status cvb_linsol(cl_cvbdf *s, cl_error *err)
{
    cl_sun *b = &s->base;
    cl_status st = cl_firstorder_create(b->sys->pattern, b->sys->mass, &s->fo,
                                        err);
    if (st == CL_OK)
        st = cl_sun_attach_klu(b, s->fo.size, s->fo.nnz, err);
    if (st != CL_OK)
        return st;
    int flag = CVodeSetJacFn(b->mem, cvb_jac);
    return flag < 0 ? cl_sun_fail(b, "CVodeSetJacFn", flag, err) : CL_OK;
}

static cl_status cvb_create(const cl_system *sys, const cl_integrator_opts *o,
                            double t0, const double *x0, const double *v0,
                            void **state, cl_error *err)
{
    cl_sun *s = NULL;
    *state = NULL;
    cl_status st = cl_sun_cvode_create(sizeof(cl_cvbdf), "cvode-bdf", CV_BDF,
                                       true, sys, o, t0, x0, v0, &s, err);
    if (st == CL_OK)
        st = cvb_linsol((cl_cvbdf *)s, err);
    return cl_sun_finish(s, st, cvb_free, state);
}

const cl_integrator_type cl_integrator_cvode_bdf = {
    .name = "cvode-bdf",
    .doc = "CVODE BDF, Newton, KLU (AMD) with the analytic sparse Jacobian",
    .fixed_step = false,
    .create = cvb_create,
    .advance = cl_sun_advance,
    .stats = cl_sun_stats,
    .free = cvb_free,
};
