/* cvode-bdf: SUNDIALS CVODE on the first-order form (SPEC 1, 5)
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),   2n unknowns,
 *
 * variable-order variable-step BDF (orders 1..5), Newton iteration, the
 * linear systems (I - gamma J) dy = r solved by SUNLinSol_KLU with AMD
 * ordering (SUNLinSol_KLUSetOrdering(LS, 0)) and the analytic sparse
 * Jacobian J = [[0, I], [M^-1 df/dx, M^-1 df/dv]] assembled in CSC from the
 * pattern computed once (linalg/firstorder.h).  Scalar tolerances
 * opts->rtol, opts->atol (defaults when 0: rtol 1e-6, atol 1e-8), at most
 * opts->max_steps internal steps per advance (default 10^7), initial step
 * opts->dt when > 0.  Output by CVode(..., CV_NORMAL): the state is CVODE's
 * interpolant at t_out.  SUNDIALS 6.x API (SUNContext, sunrealtype).
 *
 * Failures: every SUNDIALS call is checked; a failure returns CL_ESOLVER
 * naming the function, its flag, and the time reached.  A force or
 * Jacobian that is not finite (or a system call returning CL_EBLOWUP) makes
 * the RHS / Jacobian function return 1 (recoverable: CVODE retries with a
 * smaller step), unless CVODE has warned "t + h = t" during this advance
 * (the step has collapsed to round-off; retrying would crawl towards the
 * singularity until max_steps), then -1; any other system error returns -1
 * (unrecoverable).  If CVODE gives up, advance reports CL_EBLOWUP (or the
 * system's status) with the times reached, not a generic solver failure.
 * CVODE's own messages are captured (CVodeSetErrHandlerFn), never printed.
 *
 * Statistics (cl_stats): steps, nonlin_iters, nonlin_fails, err_fails,
 * jac_evals, lin_setups (= KLU factor or refactor calls), lin_iters (0 for
 * a direct solver) are CVODE's counters; rhs_evals = CVODE's RHS
 * evaluations plus the linear solver's (0 with an analytic Jacobian).  The
 * KLU solver is wrapped in a thin counting SUNLinearSolver that forwards
 * every operation: lin_solves = solve calls (one per Newton iteration) and
 * symbolic_facts = setups that ran KLU's symbolic analysis successfully,
 * i.e. setups entered with KLU's first_factorize flag set that left a
 * symbolic object, or after which the symbolic object changed (in
 * sunlinsol_klu.c only the first setup after initialisation or
 * SUNLinSol_KLUReInit analyses; later setups refactor numerically, or
 * factor numerically again when rcond is tiny).  With a fixed pattern it is
 * 1 for the whole run. */
#include "integrators/integrator.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "linalg/firstorder.h"

_Static_assert(sizeof(sunrealtype) == sizeof(double),
               "clothode needs SUNDIALS built in double precision");

#define CL_CVB_RTOL 1e-6
#define CL_CVB_ATOL 1e-8
#define CL_CVB_MAX_STEPS 10000000L

/* Counters kept by the wrapper around the KLU linear solver. */
typedef struct {
    SUNLinearSolver klu;
    long solves, analyses;
} cl_klu_count;

typedef struct {
    const cl_system *sys;
    SUNContext ctx;
    N_Vector y;
    SUNMatrix J;
    SUNLinearSolver klu;    /* the KLU solver */
    SUNLinearSolver ls;     /* counting wrapper handed to CVODE */
    void *mem;              /* CVODE memory */
    cl_firstorder fo;
    double *dfdx, *dfdv;    /* block values, 9 nnzb each */
    cl_klu_count cnt;
    double t_last;          /* last output time */
    cl_status fail_rhs;     /* status of the last failed RHS call, or OK */
    cl_status fail_jac;     /* same for the Jacobian */
    bool collapsed;         /* CVODE warned t + h = t in this advance */
    double fail_t;          /* time of that failure */
    bool fail_nonfinite;    /* it was our finiteness check that failed */
    char cvmsg[512];        /* last message of CVODE's error handler */
} cl_cvbdf;

/* ---- counting wrapper around SUNLinSol_KLU ---------------------------- */

static SUNLinearSolver_Type cnt_gettype(SUNLinearSolver S)
{
    return SUNLinSolGetType(((cl_klu_count *)S->content)->klu);
}

static SUNLinearSolver_ID cnt_getid(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_CUSTOM;
}

static int cnt_initialize(SUNLinearSolver S)
{
    return SUNLinSolInitialize(((cl_klu_count *)S->content)->klu);
}

static int cnt_setup(SUNLinearSolver S, SUNMatrix A)
{
    cl_klu_count *c = S->content;
    SUNLinearSolverContent_KLU k = c->klu->content;
    int analyse = k->first_factorize;
    void *sym = SUNLinSol_KLUGetSymbolic(c->klu);
    int ret = SUNLinSolSetup(c->klu, A);
    void *now = SUNLinSol_KLUGetSymbolic(c->klu);
    if (analyse ? now != NULL : now != sym)
        c->analyses++;
    return ret;
}

static int cnt_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b,
                     sunrealtype tol)
{
    cl_klu_count *c = S->content;
    c->solves++;
    return SUNLinSolSolve(c->klu, A, x, b, tol);
}

static sunindextype cnt_lastflag(SUNLinearSolver S)
{
    return SUNLinSolLastFlag(((cl_klu_count *)S->content)->klu);
}

static int cnt_space(SUNLinearSolver S, long *lrw, long *liw)
{
    return SUNLinSolSpace(((cl_klu_count *)S->content)->klu, lrw, liw);
}

/* The counters live in the integrator state; only the shell is freed. */
static int cnt_free(SUNLinearSolver S)
{
    if (S) {
        S->content = NULL;
        SUNLinSolFreeEmpty(S);
    }
    return SUNLS_SUCCESS;
}

static SUNLinearSolver cnt_create(cl_klu_count *c, SUNContext ctx)
{
    SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
    if (!S)
        return NULL;
    S->content = c;
    S->ops->gettype = cnt_gettype;
    S->ops->getid = cnt_getid;
    S->ops->initialize = cnt_initialize;
    S->ops->setup = cnt_setup;
    S->ops->solve = cnt_solve;
    S->ops->lastflag = cnt_lastflag;
    S->ops->space = cnt_space;
    S->ops->free = cnt_free;
    return S;
}

/* ---- error reporting --------------------------------------------------- */

/* A CVODE call returned flag < 0. */
static cl_status cvb_cvfail(cl_cvbdf *s, const char *fn, int flag,
                            cl_error *err)
{
    sunrealtype t = s->t_last;
    if (s->mem)
        CVodeGetCurrentTime(s->mem, &t);
    char *name = CVodeGetReturnFlagName(flag);
    cl_status st = cl_error_set(err, CL_ESOLVER,
                                "cvode-bdf: %s failed with %s (%d) at "
                                "t = %.9g%s%s", fn, name ? name : "?", flag,
                                (double)t, s->cvmsg[0] ? ": " : "", s->cvmsg);
    free(name);
    return st;
}

/* A SUNDIALS constructor returned NULL or a SUNLinSol/SUNMat call a flag. */
static cl_status cvb_sunfail(const char *fn, int flag, cl_error *err)
{
    return cl_error_set(err, CL_ESOLVER, "cvode-bdf: %s failed (flag %d)",
                        fn, flag);
}

static void cvb_errhandler(int code, const char *module, const char *function,
                           char *msg, void *data)
{
    cl_cvbdf *s = data;
    (void)module;
    if (code < 0)
        snprintf(s->cvmsg, sizeof s->cvmsg, "%s: %s", function, msg);
    else if (strstr(msg, "t + h = t"))
        s->collapsed = true;
}

/* Record a failed system call.  A blow-up is recoverable (1: CVODE retries
 * with a smaller step, which cures a trial state that went too far) unless
 * CVODE has already shrunk its step to round-off (its "t + h = t" warning):
 * then the force fails however small the step, as at a singularity in time
 * or state, and retrying would only crawl towards it until max_steps.  Any
 * other system error is unrecoverable (-1). */
static int cvb_sysfail(cl_cvbdf *s, cl_status *slot, cl_status st, double t,
                       bool nonfinite)
{
    *slot = st;
    s->fail_t = t;
    s->fail_nonfinite = nonfinite;
    return st == CL_EBLOWUP && !s->collapsed ? 1 : -1;
}

static bool cvb_finite(const double *a, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(a[i]))
            return false;
    }
    return true;
}

/* ---- the ODE for CVODE ------------------------------------------------- */

static int cvb_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *data)
{
    cl_cvbdf *s = data;
    size_t n = s->sys->n;
    const double *x = N_VGetArrayPointer(y), *v = x + n;
    double *xd = N_VGetArrayPointer(ydot), *vd = xd + n;
    cl_status st = s->sys->force(s->sys->data, t, x, v, vd);
    if (st != CL_OK)
        return cvb_sysfail(s, &s->fail_rhs, st, t, false);
    memcpy(xd, v, n * sizeof *xd);
    for (size_t i = 0; i < n; i++)
        vd[i] *= s->fo.inv_mass[i];
    if (!cvb_finite(xd, 2 * n))
        return cvb_sysfail(s, &s->fail_rhs, CL_EBLOWUP, t, true);
    s->fail_rhs = CL_OK;
    return 0;
}

static int cvb_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J,
                   void *data, N_Vector t1, N_Vector t2, N_Vector t3)
{
    cl_cvbdf *s = data;
    size_t n = s->sys->n;
    const double *x = N_VGetArrayPointer(y), *v = x + n;
    (void)fy, (void)t1, (void)t2, (void)t3;
    cl_status st = s->sys->jacobian(s->sys->data, t, x, v, NULL, s->dfdx,
                                    s->dfdv);
    if (st != CL_OK)
        return cvb_sysfail(s, &s->fail_jac, st, t, false);
    if (!cvb_finite(s->dfdx, s->fo.nval) || !cvb_finite(s->dfdv, s->fo.nval))
        return cvb_sysfail(s, &s->fail_jac, CL_EBLOWUP, t, true);
    if (cl_firstorder_fill(&s->fo, s->dfdx, s->dfdv, J, NULL) != CL_OK)
        return -1;
    s->fail_jac = CL_OK;
    return 0;
}

/* ---- create / free ----------------------------------------------------- */

static void cvb_free(void *state)
{
    cl_cvbdf *s = state;
    if (!s)
        return;
    if (s->mem)
        CVodeFree(&s->mem);
    if (s->ls)
        SUNLinSolFree(s->ls);
    if (s->klu)
        SUNLinSolFree(s->klu);
    if (s->J)
        SUNMatDestroy(s->J);
    if (s->y)
        N_VDestroy(s->y);
    if (s->ctx)
        SUNContext_Free(&s->ctx);
    cl_firstorder_free(&s->fo);
    free(s->dfdx);
    free(s->dfdv);
    free(s);
}

static cl_status cvb_check_args(const cl_system *sys,
                                const cl_integrator_opts *o, double t0,
                                cl_error *err)
{
    if (sys->n == 0 || !sys->pattern || 3 * sys->pattern->nb != sys->n)
        return cl_error_set(err, CL_EINVAL,
                            "cvode-bdf: system has %zu unknowns and a block "
                            "pattern of %zu rows (need n = 3 nb > 0)", sys->n,
                            sys->pattern ? sys->pattern->nb : 0);
    if (!sys->force || !sys->jacobian)
        return cl_error_set(err, CL_EINVAL, "cvode-bdf: system needs a force "
                            "and an analytic Jacobian");
    if (!isfinite(t0) || !(o->rtol >= 0.0) || !(o->atol >= 0.0) ||
        !isfinite(o->rtol) || !isfinite(o->atol) || !(o->dt >= 0.0) ||
        !isfinite(o->dt) || o->max_steps < 0)
        return cl_error_set(err, CL_EINVAL,
                            "cvode-bdf: bad options t0 = %g, rtol = %g, "
                            "atol = %g, dt = %g, max_steps = %ld (need finite, "
                            ">= 0)", t0, o->rtol, o->atol, o->dt,
                            o->max_steps);
    return CL_OK;
}

/* Our own arrays: pattern, block values. */
static cl_status cvb_alloc(cl_cvbdf *s, cl_error *err)
{
    cl_status st = cl_firstorder_create(s->sys->pattern, s->sys->mass, &s->fo,
                                        err);
    if (st != CL_OK)
        return st;
    size_t nv = s->fo.nval ? s->fo.nval : 1;
    s->dfdx = calloc(nv, sizeof *s->dfdx);
    s->dfdv = calloc(nv, sizeof *s->dfdv);
    if (!s->dfdx || !s->dfdv)
        return cl_error_set(err, CL_ENOMEM, "cvode-bdf: out of memory");
    return CL_OK;
}

static cl_status cvb_vectors(cl_cvbdf *s, const double *x0, const double *v0,
                             cl_error *err)
{
    int flag = SUNContext_Create(NULL, &s->ctx);
    if (flag != 0)
        return cvb_sunfail("SUNContext_Create", flag, err);
    size_t n = s->sys->n;
    s->y = N_VNew_Serial((sunindextype)(2 * n), s->ctx);
    if (!s->y)
        return cvb_sunfail("N_VNew_Serial", 0, err);
    double *y = N_VGetArrayPointer(s->y);
    memcpy(y, x0, n * sizeof *y);
    memcpy(y + n, v0, n * sizeof *y);
    return CL_OK;
}

static cl_status cvb_cvode(cl_cvbdf *s, const cl_integrator_opts *o,
                           double t0, cl_error *err)
{
    double rtol = o->rtol > 0 ? o->rtol : CL_CVB_RTOL;
    double atol = o->atol > 0 ? o->atol : CL_CVB_ATOL;
    long mxs = o->max_steps > 0 ? o->max_steps : CL_CVB_MAX_STEPS;
    int flag;
    s->mem = CVodeCreate(CV_BDF, s->ctx);
    if (!s->mem)
        return cvb_sunfail("CVodeCreate", 0, err);
    if ((flag = CVodeSetErrHandlerFn(s->mem, cvb_errhandler, s)) < 0)
        return cvb_cvfail(s, "CVodeSetErrHandlerFn", flag, err);
    if ((flag = CVodeInit(s->mem, cvb_rhs, t0, s->y)) < 0)
        return cvb_cvfail(s, "CVodeInit", flag, err);
    if ((flag = CVodeSetUserData(s->mem, s)) < 0)
        return cvb_cvfail(s, "CVodeSetUserData", flag, err);
    if ((flag = CVodeSStolerances(s->mem, rtol, atol)) < 0)
        return cvb_cvfail(s, "CVodeSStolerances", flag, err);
    if ((flag = CVodeSetMaxNumSteps(s->mem, mxs)) < 0)
        return cvb_cvfail(s, "CVodeSetMaxNumSteps", flag, err);
    if (o->dt > 0 && (flag = CVodeSetInitStep(s->mem, o->dt)) < 0)
        return cvb_cvfail(s, "CVodeSetInitStep", flag, err);
    return CL_OK;
}

static cl_status cvb_linsol(cl_cvbdf *s, cl_error *err)
{
    int flag;
    s->J = SUNSparseMatrix(s->fo.size, s->fo.size, s->fo.nnz, CSC_MAT, s->ctx);
    if (!s->J)
        return cvb_sunfail("SUNSparseMatrix", 0, err);
    s->klu = SUNLinSol_KLU(s->y, s->J, s->ctx);
    if (!s->klu)
        return cvb_sunfail("SUNLinSol_KLU", 0, err);
    if ((flag = SUNLinSol_KLUSetOrdering(s->klu, 0)) != SUNLS_SUCCESS)
        return cvb_sunfail("SUNLinSol_KLUSetOrdering", flag, err);
    s->cnt.klu = s->klu;
    s->ls = cnt_create(&s->cnt, s->ctx);
    if (!s->ls)
        return cvb_sunfail("SUNLinSolNewEmpty", 0, err);
    if ((flag = CVodeSetLinearSolver(s->mem, s->ls, s->J)) < 0)
        return cvb_cvfail(s, "CVodeSetLinearSolver", flag, err);
    if ((flag = CVodeSetJacFn(s->mem, cvb_jac)) < 0)
        return cvb_cvfail(s, "CVodeSetJacFn", flag, err);
    return CL_OK;
}

static cl_status cvb_create(const cl_system *sys, const cl_integrator_opts *o,
                            double t0, const double *x0, const double *v0,
                            void **state, cl_error *err)
{
    *state = NULL;
    cl_status st = cvb_check_args(sys, o, t0, err);
    if (st != CL_OK)
        return st;
    cl_cvbdf *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "cvode-bdf: out of memory");
    s->sys = sys;
    s->t_last = t0;
    st = cvb_alloc(s, err);
    if (st == CL_OK)
        st = cvb_vectors(s, x0, v0, err);
    if (st == CL_OK)
        st = cvb_cvode(s, o, t0, err);
    if (st == CL_OK)
        st = cvb_linsol(s, err);
    if (st != CL_OK) {
        cvb_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

/* ---- advance ----------------------------------------------------------- */

static void cvb_copy_out(const cl_cvbdf *s, double *x, double *v)
{
    size_t n = s->sys->n;
    const double *y = N_VGetArrayPointer(s->y);
    memcpy(x, y, n * sizeof *x);
    memcpy(v, y + n, n * sizeof *v);
}

/* CVode returned flag < 0: a blow-up of the system, its own error, or a
 * solver failure. */
static cl_status cvb_advance_fail(cl_cvbdf *s, int flag, double t_out,
                                  cl_error *err)
{
    cl_status sys_st = s->fail_rhs != CL_OK ? s->fail_rhs : s->fail_jac;
    if (sys_st == CL_OK)
        return cvb_cvfail(s, "CVode", flag, err);
    sunrealtype t = s->t_last;
    CVodeGetCurrentTime(s->mem, &t);
    char *name = CVodeGetReturnFlagName(flag);
    cl_status st = cl_error_set(
        err, sys_st,
        "cvode-bdf: %s evaluation failed (%s%s) at t = %.9g; state reached "
        "t = %.9g on the way to %.9g; CVode gave up with %s",
        s->fail_rhs != CL_OK ? "force" : "Jacobian", cl_status_name(sys_st),
        s->fail_nonfinite ? ": values not finite" : "", s->fail_t, (double)t,
        t_out, name ? name : "?");
    free(name);
    return st;
}

static cl_status cvb_advance(void *state, double t_out, double *x, double *v,
                             cl_error *err)
{
    cl_cvbdf *s = state;
    if (!isfinite(t_out) || t_out < s->t_last)
        return cl_error_set(err, CL_EINVAL, "cvode-bdf: output time %.17g "
                            "lies behind the last one, %.17g", t_out,
                            s->t_last);
    if (t_out > s->t_last) {
        s->fail_rhs = s->fail_jac = CL_OK;
        s->collapsed = false;
        s->cvmsg[0] = '\0';
        sunrealtype tret;
        int flag = CVode(s->mem, t_out, s->y, &tret, CV_NORMAL);
        cvb_copy_out(s, x, v);
        if (flag < 0)
            return cvb_advance_fail(s, flag, t_out, err);
        s->t_last = t_out;
    } else {
        cvb_copy_out(s, x, v);
    }
    if (!cvb_finite(N_VGetArrayPointer(s->y), 2 * s->sys->n))
        return cl_error_set(err, CL_EBLOWUP, "cvode-bdf: state not finite "
                            "at t = %.9g", t_out);
    return CL_OK;
}

/* The getters cannot fail on a created CVODE memory with a linear solver
 * attached; a counter they did not fill stays 0. */
static void cvb_stats(const void *state, cl_stats *out)
{
    const cl_cvbdf *s = state;
    long nfe = 0, nfels = 0, nli = 0;
    memset(out, 0, sizeof *out);
    CVodeGetNumSteps(s->mem, &out->steps);
    CVodeGetNumRhsEvals(s->mem, &nfe);
    CVodeGetNumLinRhsEvals(s->mem, &nfels);
    CVodeGetNumJacEvals(s->mem, &out->jac_evals);
    CVodeGetNumLinSolvSetups(s->mem, &out->lin_setups);
    CVodeGetNumLinIters(s->mem, &nli);
    CVodeGetNumNonlinSolvIters(s->mem, &out->nonlin_iters);
    CVodeGetNumNonlinSolvConvFails(s->mem, &out->nonlin_fails);
    CVodeGetNumErrTestFails(s->mem, &out->err_fails);
    out->rhs_evals = nfe + nfels;
    out->lin_iters = nli;
    out->lin_solves = s->cnt.solves;
    out->symbolic_facts = s->cnt.analyses;
}

const cl_integrator_type cl_integrator_cvode_bdf = {
    .name = "cvode-bdf",
    .doc = "CVODE BDF, Newton, KLU (AMD) with the analytic sparse Jacobian",
    .fixed_step = false,
    .create = cvb_create,
    .advance = cvb_advance,
    .stats = cvb_stats,
    .free = cvb_free,
};
