/* Counting shell around a direct SUNLinearSolver (see lscount.h).  Every
 * operation a direct solver provides to CVODE and IDA (type, id,
 * initialize, setup, solve, last flag, space, free) is forwarded; the
 * shell reports SUNLINEARSOLVER_CUSTOM as its id. */
#include "integrators/lscount.h"

#include <sunlinsol/sunlinsol_klu.h>

#include "linalg/sunls.h"

static SUNLinearSolver inner(SUNLinearSolver S)
{
    return ((cl_lscount *)S->content)->inner;
}

static SUNLinearSolver_Type cnt_gettype(SUNLinearSolver S)
{
    return SUNLinSolGetType(inner(S));
}

static int cnt_initialize(SUNLinearSolver S)
{
    return SUNLinSolInitialize(inner(S));
}

static int cnt_setup_klu(cl_lscount *c, SUNMatrix A)
{
    SUNLinearSolverContent_KLU k = c->inner->content;
    int analyse = k->first_factorize;
    void *sym = SUNLinSol_KLUGetSymbolic(c->inner);
    int ret = SUNLinSolSetup(c->inner, A);
    void *now = SUNLinSol_KLUGetSymbolic(c->inner);
    if (analyse ? now != NULL : now != sym)
        c->analyses++;
    return ret;
}

static int cnt_setup(SUNLinearSolver S, SUNMatrix A)
{
    cl_lscount *c = S->content;
    if (SUNLinSolGetID(c->inner) == SUNLINEARSOLVER_KLU)
        return cnt_setup_klu(c, A);
    return SUNLinSolSetup(c->inner, A);
}

static int cnt_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b,
                     sunrealtype tol)
{
    cl_lscount *c = S->content;
    c->solves++;
    return SUNLinSolSolve(c->inner, A, x, b, tol);
}

static sunindextype cnt_lastflag(SUNLinearSolver S)
{
    return SUNLinSolLastFlag(inner(S));
}

static int cnt_space(SUNLinearSolver S, long *lrw, long *liw)
{
    return SUNLinSolSpace(inner(S), lrw, liw);
}

/* The counters live in caller memory; only the shell is freed. */
static int cnt_free(SUNLinearSolver S)
{
    if (S) {
        S->content = NULL;
        SUNLinSolFreeEmpty(S);
    }
    return SUNLS_SUCCESS;
}

SUNLinearSolver cl_lscount_create(cl_lscount *c, SUNContext ctx)
{
    SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
    if (!S)
        return NULL;
    S->content = c;
    S->ops->gettype = cnt_gettype;
    S->ops->getid = cl_sunls_id_custom;
    S->ops->initialize = cnt_initialize;
    S->ops->setup = cnt_setup;
    S->ops->solve = cnt_solve;
    S->ops->lastflag = cnt_lastflag;
    S->ops->space = cnt_space;
    S->ops->free = cnt_free;
    return S;
}
