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
 *   klu, pcg, pcg-jacobi, cholmod, auto (the default)
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
 * those of every SUNDIALS integrator here (sun_common.h).  klu-full: the
 * KLU solver is wrapped in a counting SUNLinearSolver (lscount.h):
 * lin_solves = solve calls (one per Newton iteration), symbolic_facts = KLU
 * symbolic analyses, 1 for the whole run with the fixed pattern;
 * lin_setups = KLU factor or refactor calls, lin_iters = 0.  Half-size
 * solvers: lin_solves, lin_iters, symbolic_facts, lin_fallbacks from the
 * cl_linsol.  linsol names the solver; rhs_evals = CVODE's RHS evaluations
 * (none for the Jacobian, which is analytic). */
#include "integrators/integrator.h"

#include <cvode/cvode.h>

#include "integrators/sun_common.h"
#include "integrators/sun_reduced.h"
#include "linalg/firstorder.h"

typedef struct {
    cl_sun base;     /* first: CVODE's user data is the whole state */
    cl_firstorder fo; /* klu-full */
    cl_sunred *red;  /* half-size solvers */
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
    if (s) {
        cl_firstorder_free(&s->fo);
        cl_sunred_free(s->red);
    }
    cl_sun_free(state);
}

/* klu-full: the pattern, then KLU on it and the Jacobian function;
 * otherwise the half-size solver. */
static cl_status cvb_linsol(cl_cvbdf *s, const cl_integrator_opts *o,
                            cl_error *err)
{
    cl_sun *b = &s->base;
    const cl_linsol_type *lt;
    cl_status st = cl_sunred_choose(b, o->linsol, &lt, err);
    if (st != CL_OK || lt)
        return st != CL_OK ? st
                           : cl_sunred_attach(b, lt, o, false, &s->red, err);
    st = cl_firstorder_create(b->sys->pattern, b->sys->mass, &s->fo, err);
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
        st = cvb_linsol((cl_cvbdf *)s, o, err);
    return cl_sun_finish(s, st, cvb_free, state);
}

static cl_status cvb_advance(void *state, double t_out, double *x, double *v,
                             cl_error *err)
{
    return cl_sunred_advance(state, ((cl_cvbdf *)state)->red, t_out, x, v, err);
}

static void cvb_stats(const void *state, cl_stats *out)
{
    cl_sunred_stats(state, ((const cl_cvbdf *)state)->red, out);
}

const cl_integrator_type cl_integrator_cvode_bdf = {
    .name = "cvode-bdf",
    .region = &cl_region_bdf5,
    .doc = "CVODE BDF, Newton, analytic Jacobian; --linsol auto (default), "
           "klu, pcg, pcg-jacobi, cholmod on the half-size matrix, klu-full",
    .fixed_step = false,
    .takes_max_order = true,
    .takes_linsol = true,
    .create = cvb_create,
    .advance = cvb_advance,
    .stats = cvb_stats,
    .free = cvb_free,
};
