/* The SUNDIALS adapter (see sun_adapter.h): the shell linear solvers and
 * matrices, the counting shell; for CVODE and IDA the state and vectors,
 * CVODE's set-up, error capture, the blow-up policy of the user functions,
 * advance, statistics, release in dependency order. */
#include "integrators/sun_adapter.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>
#include <sundials/sundials_matrix.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "core/check.h"
#include "core/stop.h"
#include "integrators/hint.h"
#include "linalg/nvec.h"

_Static_assert(sizeof(sunrealtype) == sizeof(double),
               "clothode needs SUNDIALS built in double precision");

#define CL_SUN_RTOL 1e-6
#define CL_SUN_ATOL 1e-8
#define CL_SUN_MAX_STEPS 10000000L

/* ---- the shell linear solver ------------------------------------------- */

/* The content of a shell solver: its table and the caller's data. */
typedef struct {
    const cl_sun_lsdef *def;
    void *data;
} shell_ls;

static shell_ls *shell_of(SUNLinearSolver S)
{
    return S->content;
}

static SUNLinearSolver_Type shell_gettype(SUNLinearSolver S)
{
    return shell_of(S)->def->type;
}

static SUNLinearSolver_ID shell_getid(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_CUSTOM;
}

static int shell_initialize(SUNLinearSolver S)
{
    shell_ls *c = shell_of(S);
    return c->def->initialize ? c->def->initialize(c->data) : SUNLS_SUCCESS;
}

static int shell_setup(SUNLinearSolver S, SUNMatrix A)
{
    return shell_of(S)->def->setup(shell_of(S)->data, A);
}

static int shell_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x,
                       N_Vector b, sunrealtype tol)
{
    return shell_of(S)->def->solve(shell_of(S)->data, A, x, b, tol);
}

static sunindextype shell_lastflag(SUNLinearSolver S)
{
    return shell_of(S)->def->lastflag(shell_of(S)->data);
}

static int shell_space(SUNLinearSolver S, long *lrw, long *liw)
{
    return shell_of(S)->def->space(shell_of(S)->data, lrw, liw);
}

static int shell_scaling(SUNLinearSolver S, N_Vector s1, N_Vector s2)
{
    return shell_of(S)->def->scaling(shell_of(S)->data, s1, s2);
}

static int shell_numiters(SUNLinearSolver S)
{
    return shell_of(S)->def->numiters(shell_of(S)->data);
}

static N_Vector shell_resid(SUNLinearSolver S)
{
    return shell_of(S)->def->resid(shell_of(S)->data);
}

static int shell_free(SUNLinearSolver S)
{
    if (!S)
        return SUNLS_SUCCESS;
    shell_ls *c = shell_of(S);
    if (c && c->def->free)
        c->def->free(c->data);
    free(c);
    S->content = NULL;
    SUNLinSolFreeEmpty(S);
    return SUNLS_SUCCESS;
}

/* The optional operations of def, only those it has. */
static void shell_optional(SUNLinearSolver S, const cl_sun_lsdef *def)
{
    if (def->lastflag)
        S->ops->lastflag = shell_lastflag;
    if (def->space)
        S->ops->space = shell_space;
    if (def->scaling)
        S->ops->setscalingvectors = shell_scaling;
    if (def->numiters)
        S->ops->numiters = shell_numiters;
    if (def->resid)
        S->ops->resid = shell_resid;
}

SUNLinearSolver cl_sun_shell_linsol(const cl_sun_lsdef *def, void *data,
                                    SUNContext ctx)
{
    shell_ls *c = malloc(sizeof *c);
    SUNLinearSolver S = c ? SUNLinSolNewEmpty(ctx) : NULL;
    if (!S) {
        free(c);
        return NULL;
    }
    *c = (shell_ls){def, data};
    S->content = c;
    S->ops->gettype = shell_gettype;
    S->ops->getid = shell_getid;
    S->ops->initialize = shell_initialize;
    S->ops->setup = shell_setup;
    S->ops->solve = shell_solve;
    S->ops->free = shell_free;
    shell_optional(S, def);
    return S;
}

/* ---- the shell matrix --------------------------------------------------- */

static SUNMatrix_ID shellmat_getid(SUNMatrix A)
{
    (void)A;
    return SUNMATRIX_CUSTOM;
}

static int shellmat_zero(SUNMatrix A)
{
    (void)A;
    return SUNMAT_SUCCESS;
}

static int shellmat_copy(SUNMatrix A, SUNMatrix B)
{
    (void)A, (void)B;
    return SUNMAT_SUCCESS;
}

static int shellmat_scaleaddi(sunrealtype c, SUNMatrix A)
{
    (void)c, (void)A;
    return SUNMAT_SUCCESS;
}

static void shellmat_destroy(SUNMatrix A)
{
    if (A)
        SUNMatFreeEmpty(A);
}

static SUNMatrix shellmat_clone(SUNMatrix A)
{
    return cl_sun_shell_matrix(A->sunctx);
}

SUNMatrix cl_sun_shell_matrix(SUNContext ctx)
{
    SUNMatrix A = SUNMatNewEmpty(ctx);
    if (!A)
        return NULL;
    A->ops->getid = shellmat_getid;
    A->ops->clone = shellmat_clone;
    A->ops->destroy = shellmat_destroy;
    A->ops->zero = shellmat_zero;
    A->ops->copy = shellmat_copy;
    A->ops->scaleaddi = shellmat_scaleaddi;
    return A;
}

/* ---- the counting shell around a direct solver -------------------------- */

/* KLU analyses the pattern at the first setup after its initialisation
 * (and again at the next setup while that one fails); the symbolic object
 * it leaves, read by the public accessor, tells whether the analysis
 * succeeded. */
static int count_initialize(void *data)
{
    cl_sun_count *c = data;
    c->analyse = true;
    return SUNLinSolInitialize(c->inner);
}

static int count_setup_klu(cl_sun_count *c, SUNMatrix A)
{
    void *sym = SUNLinSol_KLUGetSymbolic(c->inner);
    int ret = SUNLinSolSetup(c->inner, A);
    void *now = SUNLinSol_KLUGetSymbolic(c->inner);
    if (c->analyse ? now != NULL : now != sym)
        c->analyses++;
    if (ret == SUNLS_SUCCESS)
        c->analyse = false;
    return ret;
}

static int count_setup(void *data, SUNMatrix A)
{
    cl_sun_count *c = data;
    if (SUNLinSolGetID(c->inner) == SUNLINEARSOLVER_KLU)
        return count_setup_klu(c, A);
    return SUNLinSolSetup(c->inner, A);
}

static int count_solve(void *data, SUNMatrix A, N_Vector x, N_Vector b,
                       sunrealtype tol)
{
    cl_sun_count *c = data;
    c->solves++;
    return SUNLinSolSolve(c->inner, A, x, b, tol);
}

static sunindextype count_lastflag(void *data)
{
    return SUNLinSolLastFlag(((cl_sun_count *)data)->inner);
}

static int count_space(void *data, long *lrw, long *liw)
{
    return SUNLinSolSpace(((cl_sun_count *)data)->inner, lrw, liw);
}

static const cl_sun_lsdef count_def = {
    .type = SUNLINEARSOLVER_DIRECT,
    .initialize = count_initialize,
    .setup = count_setup,
    .solve = count_solve,
    .lastflag = count_lastflag,
    .space = count_space,
};

/* ---- CVODE's entry in the package table -------------------------------- */

/* The step CVODE just accepted, to t: the state before its projection
 * (sun_project's trial) recorded (system.h, CL_CONTACT_RECORD). */
static int cv_accept(cl_sun *s, double t)
{
    size_t n = s->sys->n;
    double *before = s->proj + 2 * n;
    if (!s->trial)
        return CV_SUCCESS;
    s->trial = false;
    cl_status st = s->sys->contact(s->sys->data, t, before, before + n,
                                   CL_CONTACT_RECORD);
    return st == CL_OK ? CV_SUCCESS : CV_PROJFUNC_FAIL;
}

/* CVODE to t_out.  A system that projects steps one at a time to t_out
 * as a stop time: the output is the end of a step, never interpolated
 * across a projection (whose correction, entered in the Nordsieck
 * history, the interpolant would spread over the step), and each accepted
 * step's state before its projection is recorded.  CVODE counts its step
 * limit per call, one step here: the advance counts them itself. */
static int cv_solve(cl_sun *s, double t_out)
{
    sunrealtype tret = s->t_last;
    if (!s->proj)
        return CVode(s->mem, t_out, s->y, &tret, CV_NORMAL);
    int flag = CVodeSetStopTime(s->mem, t_out);
    for (long steps = 0;
         flag >= 0 && flag != CV_TSTOP_RETURN && tret < t_out; steps++) {
        if (steps == s->max_steps)
            return CV_TOO_MUCH_WORK;
        s->trial = false;
        flag = CVode(s->mem, t_out, s->y, &tret, CV_ONE_STEP);
        if (flag >= 0) {
            int acc = cv_accept(s, tret);
            flag = acc < 0 ? acc : flag;
        }
    }
    return flag;
}

static cl_status cv_reinit(cl_sun *s, double t, cl_error *err)
{
    int flag = CVodeReInit(s->mem, t, s->y);
    return flag < 0 ? cl_sun_fail(s, "CVodeReInit", flag, err) : CL_OK;
}

const cl_sun_api cl_sun_cvode_api = {
    .pkg = "CVode",
    .solve_name = "CVode",
    .has_yp = false,
    .set_err_handler = CVodeSetErrHandlerFn,
    .set_user_data = CVodeSetUserData,
    .sstolerances = CVodeSStolerances,
    .set_max_num_steps = CVodeSetMaxNumSteps,
    .set_init_step = CVodeSetInitStep,
    .set_max_ord = CVodeSetMaxOrd,
    .set_linear_solver = CVodeSetLinearSolver,
    .get_current_time = CVodeGetCurrentTime,
    .get_current_step = CVodeGetCurrentStep,
    .get_gamma = CVodeGetCurrentGamma,
    .set_jac_fn = CVodeSetJacFn,
    .flag_name = CVodeGetReturnFlagName,
    .collapse_warning = CV_WARNING,
    .free_mem = CVodeFree,
    .solve = cv_solve,
    .reinit = cv_reinit,
    .steps = CVodeGetNumSteps,
    .rhs = CVodeGetNumRhsEvals,
    .lin_rhs = CVodeGetNumLinRhsEvals,
    .jac = CVodeGetNumJacEvals,
    .setups = CVodeGetNumLinSolvSetups,
    .lin_iters = CVodeGetNumLinIters,
    .nl_iters = CVodeGetNumNonlinSolvIters,
    .nl_fails = CVodeGetNumNonlinSolvConvFails,
    .err_fails = CVodeGetNumErrTestFails,
};

/* ---- errors ------------------------------------------------------------ */

cl_status cl_sun_fail(cl_sun *s, const char *fn, int flag, cl_error *err)
{
    sunrealtype t = s->t_last;
    if (s->mem)
        s->api->get_current_time(s->mem, &t);
    char *name = s->api->flag_name(flag);
    cl_status st = cl_error_set(err, CL_ESOLVER,
                                "%s: %s failed with %s (%d) at t = %.9g%s%s;"
                                " to change: %s", s->name, fn,
                                name ? name : "?", flag, (double)t,
                                s->msg[0] ? ": " : "", s->msg,
                                cl_solver_hint(name, s->fixed_steps));
    free(name);
    return st;
}

cl_status cl_sun_sunfail(const cl_sun *s, const char *fn, int flag,
                         cl_error *err)
{
    return cl_error_set(err, CL_ESOLVER, "%s: %s failed (flag %d)", s->name,
                        fn, flag);
}

/* The solver's messages: errors are kept for the report, the "t + h = t"
 * warning marks a collapsed step (see the blow-up policy); CVODE gives it,
 * and after mxhnil of them the notice that it stops repeating it, the code
 * CV_WARNING, its only warning in our use. */
static void sun_errhandler(int code, const char *module, const char *function,
                           char *msg, void *data)
{
    cl_sun *s = data;
    (void)module;
    if (code < 0)
        snprintf(s->msg, sizeof s->msg, "%s: %s", function, msg);
    else if (code > 0 && code == s->api->collapse_warning)
        s->collapsed = true;
}

/* Calls a package setter `s->api->field(s->mem, ...)` and returns the
 * failure naming pkg + suffix. */
#define CL_SUN_SET(s, err, field, suffix, ...)                               \
    do {                                                                     \
        int flag_ = (s)->api->field((s)->mem, __VA_ARGS__);                  \
        if (flag_ < 0) {                                                     \
            char fn_[64];                                                    \
            snprintf(fn_, sizeof fn_, "%s%s", (s)->api->pkg, suffix);        \
            return cl_sun_fail((s), fn_, flag_, (err));                      \
        }                                                                    \
    } while (0)

/* ---- the blow-up policy ------------------------------------------------ */

/* The solver's step has shrunk to round-off at time t (a step of 0 means
 * none chosen yet). */
static bool sun_collapsed(const cl_sun *s, double t)
{
    sunrealtype h = 0;
    if (s->collapsed)
        return true;
    if (!s->mem || s->api->get_current_step(s->mem, &h) < 0)
        return false;
    return h != 0 && fabs(h) <= 100 * DBL_EPSILON * fabs(t);
}

/* Record a failed system call.  A blow-up, or a state outside a barrier's
 * feasible set (CL_EINFEASIBLE, contact/barrier.h), is recoverable (1)
 * unless the step has already shrunk to round-off: then the force fails
 * however small the step, as at a singularity in time or state.  Any other
 * system error is unrecoverable (-1), and -1 is latched (see the
 * header). */
static int sun_sysfail(cl_sun *s, cl_status *slot, cl_status st, double t,
                       bool nonfinite)
{
    *slot = st;
    s->fail_t = t;
    s->fail_nonfinite = nonfinite;
    if ((st == CL_EBLOWUP || st == CL_EINFEASIBLE) && !sun_collapsed(s, t))
        return 1;
    s->fatal = true;
    return -1;
}

int cl_sun_force(cl_sun *s, double t, const double *x, const double *v,
                 double *f)
{
    if (s->fatal)
        return -1;
    cl_status st = s->sys->force(s->sys->data, t, x, v, f);
    return st == CL_OK ? 0 : sun_sysfail(s, &s->fail_rhs, st, t, false);
}

int cl_sun_force_terms(cl_sun *s, uint64_t mask, double t, const double *x,
                       const double *v, double *f)
{
    if (s->fatal)
        return -1;
    cl_status st = s->sys->force_terms(s->sys->data, mask, t, x, v, f);
    return st == CL_OK ? 0 : sun_sysfail(s, &s->fail_rhs, st, t, false);
}

int cl_sun_rhs_finite(cl_sun *s, const double *out, size_t len, double t)
{
    if (!cl_all_finite(out, len))
        return sun_sysfail(s, &s->fail_rhs, CL_EBLOWUP, t, true);
    s->fail_rhs = CL_OK;
    return 0;
}

int cl_sun_jacobian(cl_sun *s, double t, const double *x, const double *v)
{
    if (s->fatal)
        return -1;
    s->njac++;
    const cl_system *sys = s->sys;
    cl_status st = s->split ? sys->jacobian_terms(sys->data, s->implicit, t,
                                                  x, v, NULL, s->dfdx,
                                                  s->dfdv)
                            : sys->jacobian(sys->data, t, x, v, NULL, s->dfdx,
                                            s->dfdv);
    if (st != CL_OK)
        return sun_sysfail(s, &s->fail_jac, st, t, false);
    if (!cl_all_finite(s->dfdx, s->nval) || !cl_all_finite(s->dfdv, s->nval))
        return sun_sysfail(s, &s->fail_jac, CL_EBLOWUP, t, true);
    s->fail_jac = CL_OK;
    return 0;
}

int cl_sun_cvode_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *data)
{
    cl_sun *s = data;
    size_t n = s->sys->n;
    const double *x = N_VGetArrayPointer(y), *v = x + n;
    double *xd = N_VGetArrayPointer(ydot), *vd = xd + n;
    int ret = cl_sun_force(s, t, x, v, vd);
    if (ret != 0)
        return ret;
    memcpy(xd, v, n * sizeof *xd);
    for (size_t i = 0; i < n; i++)
        vd[i] *= s->inv_mass[i];
    return cl_sun_rhs_finite(s, xd, 2 * n, t);
}

/* ---- create / free ----------------------------------------------------- */

static cl_status sun_check(const char *name, const cl_system *sys,
                           const cl_integrator_opts *o, double t0,
                           bool need_jac, cl_error *err)
{
    if (sys->n == 0 || !sys->pattern || 3 * sys->pattern->nb != sys->n)
        return cl_error_set(err, CL_EINVAL,
                            "%s: system has %zu unknowns and a block pattern "
                            "of %zu rows (need n = 3 nb > 0)", name, sys->n,
                            sys->pattern ? sys->pattern->nb : 0);
    if (!sys->force || !sys->mass || (need_jac && !sys->jacobian))
        return cl_error_set(err, CL_EINVAL, "%s: system needs masses, a "
                            "force%s", name,
                            need_jac ? " and an analytic Jacobian" : "");
    if (!isfinite(t0) || !(o->rtol >= 0.0) || !(o->atol >= 0.0) ||
        !isfinite(o->rtol) || !isfinite(o->atol) || !(o->dt >= 0.0) ||
        !isfinite(o->dt) || o->max_steps < 0 || o->max_order < 0)
        return cl_error_set(err, CL_EINVAL,
                            "%s: bad options t0 = %g, rtol = %g, atol = %g, "
                            "dt = %g, max_steps = %ld, max_order = %d (need "
                            "finite, >= 0)", name, t0, o->rtol, o->atol,
                            o->dt, o->max_steps, o->max_order);
    return CL_OK;
}

static cl_status sun_arrays(cl_sun *s, bool need_jac, cl_error *err)
{
    size_t n = s->sys->n;
    cl_status st = cl_check_masses(s->sys->mass, n, s->name, err);
    if (st != CL_OK)
        return st;
    s->inv_mass = malloc(n * sizeof *s->inv_mass);
    if (!s->inv_mass)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    for (size_t i = 0; i < n; i++)
        s->inv_mass[i] = 1.0 / s->sys->mass[i];
    if (!need_jac)
        return CL_OK;
    s->nval = 9 * s->sys->pattern->nnzb;
    s->dfdx = calloc(s->nval ? s->nval : 1, sizeof *s->dfdx);
    s->dfdv = calloc(s->nval ? s->nval : 1, sizeof *s->dfdv);
    if (!s->dfdx || !s->dfdv)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    return CL_OK;
}

static cl_status sun_vectors(cl_sun *s, const double *x0, const double *v0,
                             cl_error *err)
{
    int flag = SUNContext_Create(NULL, &s->ctx);
    if (flag != 0)
        return cl_sun_sunfail(s, "SUNContext_Create", flag, err);
    size_t n = s->sys->n;
    s->y = cl_nvec_new((sunindextype)(2 * n), s->ctx); /* linalg/nvec.h */
    if (!s->y)
        return cl_sun_sunfail(s, "N_VNew_Serial", 0, err);
    double *y = N_VGetArrayPointer(s->y);
    memcpy(y, x0, n * sizeof *y);
    memcpy(y + n, v0, n * sizeof *y);
    if (!s->api->has_yp)
        return CL_OK;
    s->yp = N_VClone(s->y);
    if (!s->yp)
        return cl_sun_sunfail(s, "N_VClone", 0, err);
    N_VConst(0.0, s->yp);
    return CL_OK;
}

cl_status cl_sun_alloc(size_t size, const char *name, const cl_sun_api *api,
                       const cl_system *sys, const cl_integrator_opts *o,
                       double t0, const double *x0, const double *v0,
                       bool need_jac, bool projects, cl_sun **out,
                       cl_error *err)
{
    *out = NULL;
    cl_status st = sun_check(name, sys, o, t0, need_jac, err);
    if (st != CL_OK)
        return st;
    if ((!projects && (st = cl_integrator_refuse_projection(name, sys, err))) ||
        (st = cl_integrator_refuse_constraints(name, sys, err)))
        return st;
    cl_sun *s = calloc(1, size);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", name);
    s->name = name;
    s->api = api;
    s->sys = sys;
    s->t_last = t0;
    st = sun_arrays(s, need_jac, err);
    if (st == CL_OK)
        st = sun_vectors(s, x0, v0, err);
    if (st != CL_OK) {
        cl_sun_free(s);
        return st;
    }
    *out = s;
    return CL_OK;
}

cl_status cl_sun_created(cl_sun *s, void *mem, const char *fn, cl_error *err)
{
    if (!mem)
        return cl_sun_sunfail(s, fn, 0, err);
    s->mem = mem;
    CL_SUN_SET(s, err, set_err_handler, "SetErrHandlerFn", sun_errhandler, s);
    return CL_OK;
}

cl_status cl_sun_configure(cl_sun *s, const cl_integrator_opts *o,
                           cl_error *err)
{
    double rtol = o->rtol > 0 ? o->rtol : CL_SUN_RTOL;
    double atol = o->atol > 0 ? o->atol : CL_SUN_ATOL;
    long mxs = o->max_steps > 0 ? o->max_steps : CL_SUN_MAX_STEPS;
    s->max_steps = mxs;
    CL_SUN_SET(s, err, set_user_data, "SetUserData", s);
    CL_SUN_SET(s, err, sstolerances, "SStolerances", rtol, atol);
    CL_SUN_SET(s, err, set_max_num_steps, "SetMaxNumSteps", mxs);
    if (o->dt > 0)
        CL_SUN_SET(s, err, set_init_step, "SetInitStep", o->dt);
    if (o->max_order > 0 && !s->api->set_max_ord)
        return cl_error_set(err, CL_EINVAL, "%s: max_order = %d: the method "
                            "has no choice of order", s->name, o->max_order);
    /* SUNDIALS refuses an order above the method's own (CVODE: BDF 5,
     * Adams 12; IDA 5): an input to refuse, not a solver failure */
    if (o->max_order > 0 && s->api->set_max_ord(s->mem, o->max_order))
        return cl_error_set(err, CL_EINVAL, "%s: max_order = %d: above the "
                            "method's highest order (5 for BDF, 12 for "
                            "Adams)", s->name, o->max_order);
    return CL_OK;
}

/* The error estimate of a particle the projection moved (see the
 * header): its position error and velocity error lose the part along the
 * move (the normal), which the projection sets. */
static void sun_project_error(const cl_sun *s, const double *corr,
                              double *e)
{
    size_t n = s->sys->n;
    for (size_t p = 0; p < n; p += 3) {
        const double *c = corr + p;
        double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (len == 0.0)
            continue;
        double ex = 0.0, ev = 0.0;
        for (int i = 0; i < 3; i++) {
            ex += e[p + i] * c[i] / len;
            ev += e[n + p + i] * c[i] / len;
        }
        for (int i = 0; i < 3; i++) {
            e[p + i] -= ex * c[i] / len;
            e[n + p + i] -= ev * c[i] / len;
        }
    }
}

/* Contact projection (see the header): corr = P(ycur) - ycur. */
static int sun_project(sunrealtype t, N_Vector ycur, N_Vector corr,
                       sunrealtype eps, N_Vector errv, void *data)
{
    cl_sun *s = data;
    size_t n2 = 2 * s->sys->n;
    const double *y = N_VGetArrayPointer(ycur);
    double *c = N_VGetArrayPointer(corr);
    (void)eps;
    memcpy(s->proj, y, n2 * sizeof *y);
    memcpy(s->proj + n2, y, n2 * sizeof *y); /* the state before it */
    cl_status st = s->sys->contact(s->sys->data, t, s->proj,
                                   s->proj + s->sys->n, CL_CONTACT_PROJECT);
    if (st != CL_OK)
        return 1; /* recoverable: CVODE retries with a smaller step */
    s->trial = true;
    for (size_t i = 0; i < n2; i++)
        c[i] = s->proj[i] - y[i];
    if (errv)
        sun_project_error(s, c, N_VGetArrayPointer(errv));
    return 0;
}

static cl_status sun_set_projection(cl_sun *s, cl_error *err)
{
    s->proj = malloc(4 * s->sys->n * sizeof *s->proj);
    if (!s->proj)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    int flag = CVodeSetProjFn(s->mem, sun_project);
    if (flag < 0)
        return cl_sun_fail(s, "CVodeSetProjFn", flag, err);
    return CL_OK;
}

cl_status cl_sun_cvode_create(size_t size, const char *name, int lmm,
                              bool need_jac, const cl_system *sys,
                              const cl_integrator_opts *o, double t0,
                              const double *x0, const double *v0,
                              cl_sun **out, cl_error *err)
{
    cl_status st = cl_sun_alloc(size, name, &cl_sun_cvode_api, sys, o, t0, x0,
                                v0, need_jac, lmm == CV_BDF, out, err);
    if (st != CL_OK)
        return st;
    cl_sun *s = *out;
    st = cl_sun_created(s, CVodeCreate(lmm, s->ctx), "CVodeCreate", err);
    if (st != CL_OK)
        return st;
    int flag = CVodeInit(s->mem, cl_sun_cvode_rhs, t0, s->y);
    if (flag < 0)
        return cl_sun_fail(s, "CVodeInit", flag, err);
    if (sys->projects_friction)
        return cl_error_set(err, CL_EUNSUPPORTED, "%s cannot apply a contact "
                            "response = project with friction (mu > 0 or "
                            "zero_velocity): the friction acts on the "
                            "velocity after CVODE's step, which its error "
                            "control cannot follow; use a fixed-step "
                            "method, mu = 0, or response = penalty", name);
    if (sys->projects && (st = sun_set_projection(s, err)) != CL_OK)
        return st;
    return cl_sun_configure(s, o, err);
}

cl_status cl_sun_finish(cl_sun *s, cl_status st, void (*free_fn)(void *),
                        void **state)
{
    if (st != CL_OK) {
        free_fn(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

cl_status cl_sun_attach_direct(cl_sun *s, SUNMatrix A, SUNLinearSolver inner,
                               cl_error *err)
{
    s->A = A;
    s->inner = inner;
    if (!A)
        return cl_sun_sunfail(s, "matrix constructor", 0, err);
    if (!inner)
        return cl_sun_sunfail(s, "linear solver constructor", 0, err);
    s->cnt.inner = inner;
    s->ls = cl_sun_shell_linsol(&count_def, &s->cnt, s->ctx);
    if (!s->ls)
        return cl_sun_sunfail(s, "cl_sun_shell_linsol", 0, err);
    CL_SUN_SET(s, err, set_linear_solver, "SetLinearSolver", s->ls, s->A);
    return CL_OK;
}

cl_status cl_sun_attach_klu(cl_sun *s, sunindextype size, sunindextype nnz,
                            cl_error *err)
{
    SUNMatrix A = SUNSparseMatrix(size, size, nnz, CSC_MAT, s->ctx);
    SUNLinearSolver klu = A ? SUNLinSol_KLU(s->y, A, s->ctx) : NULL;
    cl_status st = cl_sun_attach_direct(s, A, klu, err);
    if (st != CL_OK)
        return st;
    int flag = SUNLinSol_KLUSetOrdering(klu, 0);
    if (flag != SUNLS_SUCCESS)
        return cl_sun_sunfail(s, "SUNLinSol_KLUSetOrdering", flag, err);
    return CL_OK;
}

void cl_sun_plug_in(cl_sun *s, const cl_sun_plug *p, void *data)
{
    s->plug = p;
    s->plug_data = data;
}

/* Solver memory first (it refers to the solvers), the context last. */
void cl_sun_free(void *state)
{
    cl_sun *s = state;
    if (!s)
        return;
    if (s->mem)
        s->api->free_mem(&s->mem);
    if (s->plug)
        s->plug->free(s->plug_data);
    free(s->proj);
    if (s->ls)
        SUNLinSolFree(s->ls);
    if (s->inner)
        SUNLinSolFree(s->inner);
    if (s->nls)
        SUNNonlinSolFree(s->nls);
    if (s->A)
        SUNMatDestroy(s->A);
    if (s->y)
        N_VDestroy(s->y);
    if (s->yp)
        N_VDestroy(s->yp);
    if (s->ctx)
        SUNContext_Free(&s->ctx);
    free(s->inv_mass);
    free(s->dfdx);
    free(s->dfdv);
    free(s);
}

/* ---- advance ----------------------------------------------------------- */

static void sun_copy_out(const cl_sun *s, double *x, double *v)
{
    size_t n = s->sys->n;
    const double *y = N_VGetArrayPointer(s->y);
    memcpy(x, y, n * sizeof *x);
    memcpy(v, y + n, n * sizeof *v);
}

/* The solver returned flag < 0: a blow-up of the system, its own error, a
 * stop (the system's evaluations, or an iterative linear solve, end with
 * CL_EINTR once one is requested: core/stop.h, linalg/linsol.h), or a
 * solver failure. */
static cl_status sun_advance_fail(cl_sun *s, int flag, double t_out,
                                  cl_error *err)
{
    cl_status sys_st = s->fail_rhs != CL_OK ? s->fail_rhs : s->fail_jac;
    if (sys_st == CL_OK && cl_stop_requested())
        return cl_error_set(err, CL_EINTR, "%s: stopped by %s in a linear "
                            "solve on the way to t = %.9g", s->name,
                            cl_stop_signal_name(cl_stop_requested()), t_out);
    if (sys_st == CL_OK)
        return cl_sun_fail(s, s->api->solve_name, flag, err);
    sunrealtype t = s->t_last;
    s->api->get_current_time(s->mem, &t);
    char *name = s->api->flag_name(flag);
    cl_status st = cl_error_set(
        err, sys_st,
        "%s: %s evaluation failed (%s%s) at t = %.9g; state reached t = %.9g "
        "on the way to %.9g; %s gave up with %s; to change: reduce --rtol or"
        " check the parameters for a blow-up", s->name,
        s->fail_rhs != CL_OK ? "force" : "Jacobian", cl_status_name(sys_st),
        s->fail_nonfinite ? ": values not finite" : "", s->fail_t, (double)t,
        t_out, s->api->solve_name, name ? name : "?");
    free(name);
    return st;
}

static void sun_solver_counts(const cl_sun *s, cl_stats *out);
static void sun_add_counts(cl_stats *to, const cl_stats *c);

/* Tearing at the output time t (see the header): the system's step_done,
 * and a restart of the solver when the model changed. */
static cl_status sun_step_done(cl_sun *s, double t, cl_error *err)
{
    const cl_system *sys = s->sys;
    const double *y = N_VGetArrayPointer(s->y);
    bool changed = false;
    cl_status st = sys->step_done(sys->data, t, y, y + sys->n, &changed);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: update after t = %.9g failed (%s)",
                            s->name, t, cl_status_name(st));
    if (!changed || !s->api->reinit)
        return CL_OK;
    cl_stats now;
    sun_solver_counts(s, &now);
    sun_add_counts(&s->before, &now);
    return s->api->reinit(s, t, err);
}

static cl_status sun_advance(cl_sun *s, double t_out, double *x, double *v,
                             cl_error *err)
{
    cl_status st = cl_output_time_check(s->name, t_out, s->t_last, err);
    if (st != CL_OK)
        return st;
    if (t_out > s->t_last) {
        s->fail_rhs = s->fail_jac = CL_OK;
        s->collapsed = s->fatal = false;
        s->msg[0] = '\0';
        int flag = s->api->solve(s, t_out);
        sun_copy_out(s, x, v);
        if (flag < 0)
            return sun_advance_fail(s, flag, t_out, err);
        s->t_last = t_out;
    } else {
        sun_copy_out(s, x, v);
    }
    if (!cl_all_finite(N_VGetArrayPointer(s->y), 2 * s->sys->n))
        return cl_error_set(err, CL_EBLOWUP, "%s: state not finite at "
                            "t = %.9g", s->name, t_out);
    if (s->sys->contact) { /* the figures, and the output projected */
        double *y = N_VGetArrayPointer(s->y);
        cl_status st = cl_integrator_contact_at(s->name, s->sys, t_out, y,
                                                y + s->sys->n, err);
        if (st != CL_OK)
            return st;
        sun_copy_out(s, x, v);
    }
    return s->sys->step_done ? sun_step_done(s, t_out, err) : CL_OK;
}

cl_status cl_sun_advance(void *state, double t_out, double *x, double *v,
                         cl_error *err)
{
    cl_sun *s = state;
    cl_status st = sun_advance(s, t_out, x, v, err);
    const char *last = st != CL_OK && s->plug && s->plug->last_error
                           ? s->plug->last_error(s->plug_data)
                           : "";
    if (last[0]) {
        size_t len = strlen(err->msg);
        snprintf(err->msg + len, sizeof err->msg - len,
                 "; last linear-solver failure: %s", last);
    }
    return st;
}

/* ---- statistics -------------------------------------------------------- */

static long sun_count(const cl_sun *s, cl_sun_getter get)
{
    long v = 0;
    if (get(s->mem, &v) < 0)
        return 0;
    return v;
}

/* The solver's own counters (a re-initialisation resets them). */
static void sun_solver_counts(const cl_sun *s, cl_stats *out)
{
    const cl_sun_api *a = s->api;
    memset(out, 0, sizeof *out);
    out->steps = sun_count(s, a->steps);
    out->rhs_evals = sun_count(s, a->rhs);
    out->lin_setups = sun_count(s, a->setups);
    if (s->ls) { /* the linear-solver getters fail (and say so) without */
        out->rhs_evals += sun_count(s, a->lin_rhs);
        out->jac_evals = sun_count(s, a->jac);
        out->lin_iters = sun_count(s, a->lin_iters);
    }
    out->nonlin_iters = sun_count(s, a->nl_iters);
    out->nonlin_fails = sun_count(s, a->nl_fails);
    out->err_fails = sun_count(s, a->err_fails);
}

static void sun_add_counts(cl_stats *to, const cl_stats *c)
{
    to->steps += c->steps;
    to->rhs_evals += c->rhs_evals;
    to->lin_setups += c->lin_setups;
    to->jac_evals += c->jac_evals;
    to->lin_iters += c->lin_iters;
    to->nonlin_iters += c->nonlin_iters;
    to->nonlin_fails += c->nonlin_fails;
    to->err_fails += c->err_fails;
}

void cl_sun_stats(const void *state, cl_stats *out)
{
    const cl_sun *s = state;
    sun_solver_counts(s, out);
    sun_add_counts(out, &s->before);
    out->rhs_evals += s->own_rhs;
    out->lin_solves = s->cnt.solves;
    out->symbolic_facts = s->cnt.analyses;
    if (s->plug)
        s->plug->stats(s->plug_data, out);
}
