/* A full Newton iteration as a SUNNonlinearSolver (see sun_newton.h). */
#include "integrators/sun_newton.h"

#include <stdbool.h>
#include <stdlib.h>

typedef struct {
    SUNNonlinSolSysFn sys;
    SUNNonlinSolLSetupFn lsetup;
    SUNNonlinSolLSolveFn lsolve;
    SUNNonlinSolConvTestFn ctest;
    void *ctest_data;
    N_Vector delta;
    booleantype jcur;     /* the Newton matrix is fresh */
    int maxiters, curiter;
    long niters, nconvfails;
} fn_content;

#define FN(nls) ((fn_content *)(nls)->content)

static SUNNonlinearSolver_Type fn_type(SUNNonlinearSolver nls)
{
    (void)nls;
    return SUNNONLINEARSOLVER_ROOTFIND;
}

static int fn_initialize(SUNNonlinearSolver nls)
{
    fn_content *c = FN(nls);
    if (!c->sys || !c->lsetup || !c->lsolve || !c->ctest)
        return SUN_NLS_MEM_NULL;
    return SUN_NLS_SUCCESS;
}

/* The Newton loop from the correction ycor, its residual in delta: delta
 * = -J^-1 F, ycor += delta, the integrator's convergence test, the next
 * residual; with `full` a fresh Newton matrix (lsetup with jbad) at
 * every iterate, else the current one.  SUN_NLS_CONV_RECVR after
 * maxiters iterations. */
static int fn_iterate(SUNNonlinearSolver nls, N_Vector ycor, N_Vector w,
                      realtype tol, bool full, void *mem)
{
    fn_content *c = FN(nls);
    int rc = SUN_NLS_SUCCESS;
    c->curiter = 0;
    for (;;) {
        if (full && (rc = c->lsetup(SUNTRUE, &c->jcur, mem)))
            return rc;
        c->niters++;
        N_VScale(-1.0, c->delta, c->delta);
        if ((rc = c->lsolve(c->delta, mem)))
            return rc;
        N_VLinearSum(1.0, ycor, 1.0, c->delta, ycor);
        rc = c->ctest(nls, ycor, c->delta, tol, w, c->ctest_data);
        if (rc != SUN_NLS_CONTINUE)
            return rc;
        if (++c->curiter >= c->maxiters)
            return SUN_NLS_CONV_RECVR;
        if ((rc = c->sys(ycor, c->delta, mem)))
            return rc;
    }
}

/* Solves for the correction ycor (ARKODE gives 0) to tolerance tol in the
 * weights w.  First SUNNonlinSol_Newton's modified Newton, step for step:
 * the Newton matrix set up only when the integrator asks (callLSetup),
 * and once more, from ycor = 0, when the iteration fails with a matrix
 * that was not fresh.  If that fails to converge too, the full Newton
 * iteration from ycor = 0.  y0 is not needed.  The counts are of this
 * solve: ARKODE adds them up after every solve. */
static int fn_solve(SUNNonlinearSolver nls, N_Vector y0, N_Vector ycor,
                    N_Vector w, realtype tol, booleantype callLSetup,
                    void *mem)
{
    fn_content *c = FN(nls);
    booleantype jbad = SUNFALSE;
    int rc;
    (void)y0;
    c->niters = c->nconvfails = 0;
    for (;;) {
        rc = c->sys(ycor, c->delta, mem);
        if (!rc && callLSetup)
            rc = c->lsetup(jbad, &c->jcur, mem);
        if (rc)
            break; /* as SUNNonlinSol_Newton: no second attempt */
        rc = fn_iterate(nls, ycor, w, tol, false, mem);
        if (rc <= 0 || c->jcur)
            break;
        c->nconvfails++;
        callLSetup = jbad = SUNTRUE;
        N_VConst(0.0, ycor);
    }
    if (rc == SUN_NLS_CONV_RECVR) {
        c->nconvfails++;
        N_VConst(0.0, ycor);
        if (!(rc = c->sys(ycor, c->delta, mem)))
            rc = fn_iterate(nls, ycor, w, tol, true, mem);
    }
    if (rc == SUN_NLS_SUCCESS)
        c->jcur = SUNFALSE;
    else
        c->nconvfails++;
    return rc;
}

static int fn_free(SUNNonlinearSolver nls)
{
    if (!nls)
        return SUN_NLS_SUCCESS;
    if (nls->content) {
        if (FN(nls)->delta)
            N_VDestroy(FN(nls)->delta);
        free(nls->content);
        nls->content = NULL;
    }
    SUNNonlinSolFreeEmpty(nls);
    return SUN_NLS_SUCCESS;
}

static int fn_set_sys(SUNNonlinearSolver nls, SUNNonlinSolSysFn f)
{
    FN(nls)->sys = f;
    return SUN_NLS_SUCCESS;
}

static int fn_set_lsetup(SUNNonlinearSolver nls, SUNNonlinSolLSetupFn f)
{
    FN(nls)->lsetup = f;
    return SUN_NLS_SUCCESS;
}

static int fn_set_lsolve(SUNNonlinearSolver nls, SUNNonlinSolLSolveFn f)
{
    FN(nls)->lsolve = f;
    return SUN_NLS_SUCCESS;
}

static int fn_set_ctest(SUNNonlinearSolver nls, SUNNonlinSolConvTestFn f,
                        void *data)
{
    FN(nls)->ctest = f;
    FN(nls)->ctest_data = data;
    return SUN_NLS_SUCCESS;
}

static int fn_set_maxiters(SUNNonlinearSolver nls, int maxiters)
{
    if (maxiters < 1)
        return SUN_NLS_ILL_INPUT;
    FN(nls)->maxiters = maxiters;
    return SUN_NLS_SUCCESS;
}

static int fn_get_iters(SUNNonlinearSolver nls, long *n)
{
    *n = FN(nls)->niters;
    return SUN_NLS_SUCCESS;
}

static int fn_get_curiter(SUNNonlinearSolver nls, int *iter)
{
    *iter = FN(nls)->curiter;
    return SUN_NLS_SUCCESS;
}

static int fn_get_convfails(SUNNonlinearSolver nls, long *n)
{
    *n = FN(nls)->nconvfails;
    return SUN_NLS_SUCCESS;
}

SUNNonlinearSolver cl_sun_newton_full(N_Vector y, SUNContext ctx)
{
    SUNNonlinearSolver nls = SUNNonlinSolNewEmpty(ctx);
    if (!nls)
        return NULL;
    nls->ops->gettype = fn_type;
    nls->ops->initialize = fn_initialize;
    nls->ops->solve = fn_solve;
    nls->ops->free = fn_free;
    nls->ops->setsysfn = fn_set_sys;
    nls->ops->setlsetupfn = fn_set_lsetup;
    nls->ops->setlsolvefn = fn_set_lsolve;
    nls->ops->setctestfn = fn_set_ctest;
    nls->ops->setmaxiters = fn_set_maxiters;
    nls->ops->getnumiters = fn_get_iters;
    nls->ops->getcuriter = fn_get_curiter;
    nls->ops->getnumconvfails = fn_get_convfails;
    fn_content *c = calloc(1, sizeof *c);
    nls->content = c;
    if (c) {
        c->maxiters = 3;
        c->delta = N_VClone(y);
    }
    if (!c || !c->delta) {
        fn_free(nls);
        return NULL;
    }
    return nls;
}
