/* KINSOL plumbing of kinsol-be, kinsol-bdf2, kinsol-midpoint and
 * kinsol-galpha (see kinsol_common.h for the equations, the predictor, the
 * tolerance and iteration-cap rules, the failure policy and Rayleigh
 * damping).
 *
 * Per step:  the scheme fills vb, ve0, x1b, the predictor p and c, alpha,
 * beta, alpha1, te;  u (the KINSOL unknown) starts at p;  the scales are
 * set from v_ref = max(1, max |v_n|);  KINSol(KIN_NONE) solves
 *     R(u) = M (u - vb) - c f(te, x_n + alpha (u - p), ve0 + beta u) = 0
 * with Newton matrix M - (c beta) df/dv - (c alpha) df/dx from cl_linsol;
 * then x1 = x1b + alpha1 u, v1 = u, and the history shifts.  Output times,
 * step counting and the finite-state check are the fixed-step loop
 * (cl_fixed_run, fixed_step.h). */
#include "integrators/kinsol_common.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include "core/check.h"
#include "core/stop.h"
#include "integrators/fixed_step.h"
#include "integrators/hint.h"
#include "integrators/sun_adapter.h"
#include "linalg/linsol.h"
#include "linalg/reduced.h"

_Static_assert(sizeof(sunrealtype) == sizeof(double),
               "clothode needs SUNDIALS built in double precision");

#define CL_KIN_TOL 1e-10
#define CL_KIN_MAXIT 50L
#define CL_KIN_VREF_MIN 1.0 /* m/s: floor of the velocity scale */
#define CL_KIN_STEP_FLOOR (10 * DBL_EPSILON) /* update test: round-off */
#define CL_KIN_HALVINGS 30  /* filtered Newton: halvings of a step */
#define CL_KIN_ARMIJO 1e-4  /* ... and the decrease it must give */

typedef struct {
    const cl_kin_scheme *sc;  /* &own */
    cl_kin_scheme own;        /* the scheme, configured by the options */
    const cl_system *sys;
    size_t n;
    double t0, h;
    long done;              /* steps completed */
    long maxit;             /* Newton iterations per step */
    double tol;             /* newton_tol (or DBL_MIN in one-step mode) */
    double *x, *v, *xp, *vp, *x1;     /* history and new position */
    double *acc;                      /* carried acceleration (finish) */
    double *vb, *ve0, *x1b, *pred;    /* scheme data of the step */
    double *xe, *ve, *f;              /* evaluation point and force */
    double *dfdx, *dfdv;              /* block values, 9 nnzb each */
    double ra, rb;                    /* Rayleigh alpha, beta */
    double *kfz, *kv;                 /* frozen df/dx (rb > 0), its
                                         product with ve */
    cl_kin_step step;                 /* the scheme's view of the step */
    /* this step: t_n and the scheme's scalars (times h where due) */
    double t, c, alpha, beta, alpha1, te;
    /* SUNDIALS */
    SUNContext ctx;
    N_Vector u, uscale, fscale;
    N_Vector r, du, ut;     /* the filtered Newton loop's residual, step
                               and trial point (barriers) */
    SUNMatrix J;            /* shell: the matrix lives in the linear solver */
    SUNLinearSolver ls;     /* custom solver calling cl_linsol */
    void *mem;              /* KINSOL memory */
    /* linear solver */
    const cl_linsol_type *lt;
    void *lstate;
    /* counters */
    long nrhs, njac, nni, nfail;
    /* failure bookkeeping of the current step */
    cl_status sys_st;       /* failed force / Jacobian evaluation, or OK */
    bool sys_jac;           /* ... it was the Jacobian */
    bool sys_nonfinite;     /* ... it returned non-finite values */
    cl_status lin_st;       /* failed linear setup / solve, or OK */
    cl_error lin_err;
    double rmax;            /* scaled max-norm of the last residual */
    char kmsg[512];         /* last error message of KINSOL */
} cl_kin;

/* ---- evaluation point and the user functions -------------------------- */

/* xe = x_n + alpha (u - p) (exactly x_n at the predictor), ve = ve0 +
 * beta u. */
static void kin_point(cl_kin *s, const double *u)
{
    for (size_t i = 0; i < s->n; i++) {
        s->xe[i] = s->x[i] + s->alpha * (u[i] - s->pred[i]);
        s->ve[i] = s->ve0[i] + s->beta * u[i];
    }
}

/* A failed system call: remember it and stop KINSOL (-1, unrecoverable). */
static int kin_sysfail(cl_kin *s, cl_status st, bool jac, bool nonfinite)
{
    s->sys_st = st;
    s->sys_jac = jac;
    s->sys_nonfinite = nonfinite;
    return -1;
}

/* Rayleigh damping added to the force: f -= (ra M + rb K*) ve, K* = -kfz
 * (kinsol_common.h, "Rayleigh damping"). */
static void kin_rayleigh(cl_kin *s)
{
    const double *m = s->sys->mass;
    if (s->rb > 0.0)
        cl_bmatvec(s->sys->pattern, s->kfz, s->ve, s->kv);
    for (size_t i = 0; i < s->n; i++) {
        s->f[i] -= s->ra * m[i] * s->ve[i];
        if (s->rb > 0.0)
            s->f[i] += s->rb * s->kv[i];
    }
}

static int kin_residual(N_Vector uv, N_Vector rv, void *data)
{
    cl_kin *s = data;
    const double *u = N_VGetArrayPointer(uv), *m = s->sys->mass;
    const double *fs = N_VGetArrayPointer(s->fscale);
    double *r = N_VGetArrayPointer(rv), c = s->c, rmax = 0.0;
    kin_point(s, u);
    cl_status st = s->sys->force(s->sys->data, s->te, s->xe, s->ve,
                                 s->f);
    s->nrhs++;
    if (st != CL_OK)
        return kin_sysfail(s, st, false, false);
    if (s->ra > 0.0 || s->rb > 0.0)
        kin_rayleigh(s);
    for (size_t i = 0; i < s->n; i++) {
        r[i] = m[i] * (u[i] - s->vb[i]) - c * s->f[i];
        rmax = fmax(rmax, fabs(r[i]) * fs[i]);
    }
    if (!cl_all_finite(r, s->n))
        return kin_sysfail(s, CL_EBLOWUP, false, true);
    s->rmax = rmax;
    return 0;
}

static int kin_jac(N_Vector uv, N_Vector fu, SUNMatrix J, void *data,
                   N_Vector t1, N_Vector t2)
{
    cl_kin *s = data;
    const cl_system *sys = s->sys;
    size_t nval = 9 * sys->pattern->nnzb;
    (void)fu, (void)J, (void)t1, (void)t2;
    kin_point(s, N_VGetArrayPointer(uv));
    cl_status st = sys->jacobian(sys->data, s->te, s->xe, s->ve, NULL,
                                 s->dfdx, s->dfdv);
    s->njac++;
    if (st != CL_OK)
        return kin_sysfail(s, st, true, false);
    if (!cl_all_finite(s->dfdx, nval) || !cl_all_finite(s->dfdv, nval))
        return kin_sysfail(s, CL_EBLOWUP, true, true);
    for (size_t k = 0; s->rb > 0.0 && k < nval; k++)
        s->dfdv[k] += s->rb * s->kfz[k]; /* dR/dv of rb K* ve */
    cl_linsol_jacobian(s->lt, s->lstate, s->dfdx, s->dfdv);
    return 0;
}

static void kin_errhandler(int code, const char *module, const char *function,
                           char *msg, void *data)
{
    cl_kin *s = data;
    (void)module;
    if (code < 0)
        snprintf(s->kmsg, sizeof s->kmsg, "%s: %s", function, msg);
}

/* ---- the cl_linsol as KINSOL's direct solver (sun_adapter.h) ---------- */

/* The Newton matrix's factor sr of M under Rayleigh damping (1 without):
 * dR/dv1 = sr M - (c beta) df/dv' - (c alpha) df/dx, sr = 1 + c beta ra,
 * df/dv' = df/dv + rb K* (kin_jac); the linear solver gets it divided by
 * sr, and ls_solve divides the solution by sr. */
static double kin_mass_factor(const cl_kin *s)
{
    return 1.0 + s->c * s->beta * s->ra;
}

/* A = M - (c beta) df/dv - (c alpha) df/dx at the iterate of kin_jac
 * (over kin_mass_factor under Rayleigh damping). */
static int ls_setup(void *data, SUNMatrix A)
{
    cl_kin *s = data;
    double sr = kin_mass_factor(s);
    (void)A;
    s->lin_st = s->lt->setup(s->lstate, s->c * s->beta / sr,
                             s->c * s->alpha / sr, s->dfdx, s->dfdv,
                             &s->lin_err);
    return s->lin_st == CL_OK ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_UNREC;
}

static int ls_solve(void *data, SUNMatrix A, N_Vector x, N_Vector b,
                    sunrealtype tol)
{
    cl_kin *s = data;
    double *xd = N_VGetArrayPointer(x);
    (void)A, (void)tol;
    s->lin_st = s->lt->solve(s->lstate, N_VGetArrayPointer(b), xd,
                             &s->lin_err);
    double sr = kin_mass_factor(s);
    for (size_t i = 0; sr != 1.0 && i < s->n; i++)
        xd[i] /= sr;
    if (s->lin_st == CL_OK && !cl_all_finite(xd, s->n))
        s->lin_st = cl_error_set(&s->lin_err, CL_EBLOWUP, "%s solve: "
                                 "Newton step not finite", s->lt->name);
    return s->lin_st == CL_OK ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_UNREC;
}

/* KINSOL zeroes a direct solver's matrix before each Jacobian call; the
 * matrix is the adapter's shell, which holds no values. */
static const cl_sun_lsdef kin_lsdef = {
    .type = SUNLINEARSOLVER_DIRECT,
    .setup = ls_setup,
    .solve = ls_solve,
};

/* ---- create / free ------------------------------------------------------ */

void cl_kin_free(void *state)
{
    cl_kin *s = state;
    if (!s)
        return;
    if (s->mem)
        KINFree(&s->mem);
    if (s->ls)
        SUNLinSolFree(s->ls);
    if (s->J)
        SUNMatDestroy(s->J);
    if (s->lstate)
        s->lt->free(s->lstate);
    N_Vector vec[] = {s->u, s->uscale, s->fscale, s->r, s->du, s->ut};
    for (size_t k = 0; k < sizeof vec / sizeof vec[0]; k++) {
        if (vec[k])
            N_VDestroy(vec[k]);
    }
    if (s->ctx)
        SUNContext_Free(&s->ctx);
    double *arr[] = {s->x, s->v, s->xp, s->vp, s->x1, s->vb, s->ve0,
                     s->x1b, s->pred, s->xe, s->ve, s->f, s->dfdx, s->dfdv,
                     s->acc, s->kfz, s->kv};
    for (size_t k = 0; k < sizeof arr / sizeof arr[0]; k++)
        free(arr[k]);
    free(s);
}

static cl_status kin_check_args(const cl_kin_scheme *sc, const cl_system *sys,
                                const cl_integrator_opts *o, double t0,
                                cl_error *err)
{
    if (sys->n == 0 || !sys->pattern || 3 * sys->pattern->nb != sys->n ||
        !sys->force || !sys->jacobian)
        return cl_error_set(err, CL_EINVAL, "%s: system needs n = 3 nb > 0 "
                            "unknowns (has %zu), a block pattern, a force and "
                            "an analytic Jacobian", sc->name, sys->n);
    if (!isfinite(o->dt) || !(o->dt > 0.0) || !isfinite(t0))
        return cl_error_set(err, CL_EINVAL, "%s: step dt = %g and initial "
                            "time %g must be finite, dt > 0", sc->name, o->dt,
                            t0);
    if (!(o->rayleigh_alpha >= 0.0 && o->rayleigh_alpha < INFINITY) ||
        !(o->rayleigh_beta >= 0.0 && o->rayleigh_beta < INFINITY))
        return cl_error_set(err, CL_EINVAL, "%s: rayleigh_alpha = %g, "
                            "rayleigh_beta = %g (need finite >= 0)",
                            sc->name, o->rayleigh_alpha, o->rayleigh_beta);
    if (!isfinite(o->newton_tol) || o->newton_tol < 0.0 ||
        o->newton_maxit < 0)
        return cl_error_set(err, CL_EINVAL, "%s: newton_tol = %g, "
                            "newton_maxit = %ld (need finite >= 0, >= 0; 0: "
                            "default)", sc->name, o->newton_tol,
                            o->newton_maxit);
    return cl_check_masses(sys->mass, sys->n, sc->name, err);
}

static cl_status kin_alloc(cl_kin *s, cl_error *err)
{
    size_t n = s->n, nval = 9 * s->sys->pattern->nnzb;
    double **arr[] = {&s->x, &s->v, &s->xp, &s->vp, &s->x1, &s->vb, &s->ve0,
                      &s->x1b, &s->pred, &s->xe, &s->ve, &s->f};
    bool ok = true;
    for (size_t k = 0; k < sizeof arr / sizeof arr[0]; k++)
        ok = (*arr[k] = calloc(n, sizeof(double))) != NULL && ok;
    if (s->sc->finish)
        ok = (s->acc = calloc(n, sizeof(double))) != NULL && ok;
    if (s->rb > 0.0) {
        ok = (s->kv = calloc(n, sizeof(double))) != NULL && ok;
        ok = (s->kfz = calloc(nval ? nval : 1, sizeof(double))) != NULL && ok;
    }
    s->dfdx = calloc(nval ? nval : 1, sizeof(double));
    s->dfdv = calloc(nval ? nval : 1, sizeof(double));
    if (!ok || !s->dfdx || !s->dfdv)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory",
                            s->sc->name);
    return CL_OK;
}

static cl_status kin_sunfail(const cl_kin *s, const char *fn, int flag,
                             cl_error *err)
{
    return cl_error_set(err, CL_ESOLVER, "%s: %s failed (flag %d)%s%s",
                        s->sc->name, fn, flag, s->kmsg[0] ? ": " : "",
                        s->kmsg);
}

static cl_status kin_vectors(cl_kin *s, cl_error *err)
{
    int flag = SUNContext_Create(NULL, &s->ctx);
    if (flag != 0)
        return kin_sunfail(s, "SUNContext_Create", flag, err);
    sunindextype n = (sunindextype)s->n;
    s->u = N_VNew_Serial(n, s->ctx);
    s->uscale = N_VNew_Serial(n, s->ctx);
    s->fscale = N_VNew_Serial(n, s->ctx);
    if (!s->u || !s->uscale || !s->fscale)
        return kin_sunfail(s, "N_VNew_Serial", 0, err);
    if (!s->sys->step_fraction)
        return CL_OK;
    s->r = N_VNew_Serial(n, s->ctx);
    s->du = N_VNew_Serial(n, s->ctx);
    s->ut = N_VNew_Serial(n, s->ctx);
    if (!s->r || !s->du || !s->ut)
        return kin_sunfail(s, "N_VNew_Serial", 0, err);
    return CL_OK;
}

static cl_status kin_linsol(cl_kin *s, const cl_integrator_opts *o,
                            cl_error *err)
{
    cl_status st = cl_linsol_get(s->sc->name, o->linsol, NULL, &s->lt,
                                 err);
    if (st != CL_OK)
        return st;
    cl_linsol_opts lo = cl_integrator_linsol_opts(o, s->sys);
    st = s->lt->create(s->sys->pattern, s->sys->mass, &lo,
                                 &s->lstate, err);
    if (st != CL_OK)
        return st;
    s->J = cl_sun_shell_matrix(s->ctx);
    s->ls = cl_sun_shell_linsol(&kin_lsdef, s, s->ctx);
    if (!s->J || !s->ls)
        return kin_sunfail(s, s->J ? "cl_sun_shell_linsol"
                                    : "cl_sun_shell_matrix",
                           0, err);
    return CL_OK;
}

/* KINSOL's tolerances and cap (kinsol_common.h): one-step mode for
 * newton_maxit = 1, convergence mode otherwise. */
static cl_status kin_options(cl_kin *s, const cl_integrator_opts *o,
                             cl_error *err)
{
    int flag;
    s->maxit = o->newton_maxit > 0 ? o->newton_maxit : CL_KIN_MAXIT;
    s->tol = o->newton_tol > 0 ? o->newton_tol : CL_KIN_TOL;
    if (s->maxit == 1)
        s->tol = DBL_MIN;
    if ((flag = KINSetNumMaxIters(s->mem, s->maxit)) < 0)
        return kin_sunfail(s, "KINSetNumMaxIters", flag, err);
    if ((flag = KINSetFuncNormTol(s->mem, s->tol)) < 0)
        return kin_sunfail(s, "KINSetFuncNormTol", flag, err);
    if ((flag = KINSetScaledStepTol(s->mem, s->maxit == 1 ? s->tol :
                                    fmax(s->tol, CL_KIN_STEP_FLOOR))) < 0)
        return kin_sunfail(s, "KINSetScaledStepTol", flag, err);
    if ((flag = KINSetMaxSetupCalls(s->mem, 1)) < 0)
        return kin_sunfail(s, "KINSetMaxSetupCalls", flag, err);
    if ((flag = KINSetNoResMon(s->mem, SUNTRUE)) < 0)
        return kin_sunfail(s, "KINSetNoResMon", flag, err);
    if ((flag = KINSetMaxNewtonStep(s->mem, DBL_MAX)) < 0)
        return kin_sunfail(s, "KINSetMaxNewtonStep", flag, err);
    return CL_OK;
}

static cl_status kin_kinsol(cl_kin *s, const cl_integrator_opts *o,
                            cl_error *err)
{
    int flag;
    s->mem = KINCreate(s->ctx);
    if (!s->mem)
        return kin_sunfail(s, "KINCreate", 0, err);
    if ((flag = KINSetErrHandlerFn(s->mem, kin_errhandler, s)) < 0)
        return kin_sunfail(s, "KINSetErrHandlerFn", flag, err);
    if ((flag = KINInit(s->mem, kin_residual, s->u)) < 0)
        return kin_sunfail(s, "KINInit", flag, err);
    if ((flag = KINSetUserData(s->mem, s)) < 0)
        return kin_sunfail(s, "KINSetUserData", flag, err);
    cl_status st = kin_options(s, o, err);
    if (st != CL_OK)
        return st;
    if ((st = kin_linsol(s, o, err)) != CL_OK)
        return st;
    if ((flag = KINSetLinearSolver(s->mem, s->ls, s->J)) < 0)
        return kin_sunfail(s, "KINSetLinearSolver", flag, err);
    if ((flag = KINSetJacFn(s->mem, kin_jac)) < 0)
        return kin_sunfail(s, "KINSetJacFn", flag, err);
    return CL_OK;
}

/* The carried acceleration's start, a_0 = M^-1 f(t0, x0, v0). */
static cl_status kin_initial_acc(cl_kin *s, cl_error *err)
{
    cl_status st = s->sys->force(s->sys->data, s->t0, s->x, s->v, s->acc);
    s->nrhs++;
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: force evaluation at the initial "
                            "state failed (%s)", s->sc->name,
                            cl_status_name(st));
    for (size_t i = 0; i < s->n; i++)
        s->acc[i] /= s->sys->mass[i];
    if (!cl_all_finite(s->acc, s->n))
        return cl_error_set(err, CL_EBLOWUP, "%s: initial acceleration not "
                            "finite", s->sc->name);
    return CL_OK;
}

cl_status cl_kin_create(const cl_kin_scheme *sc, const cl_system *sys,
                        const cl_integrator_opts *o, double t0,
                        const double *x0, const double *v0, void **state,
                        cl_error *err)
{
    *state = NULL;
    cl_status st = kin_check_args(sc, sys, o, t0, err);
    if (st == CL_OK)
        st = cl_integrator_refuse_constraints(sc->name, sys, err);
    if (st != CL_OK)
        return st;
    cl_kin *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", sc->name);
    s->own = *sc;
    s->sc = &s->own;
    s->sys = sys;
    s->n = sys->n;
    s->t0 = t0;
    s->h = o->dt;
    s->ra = o->rayleigh_alpha;
    s->rb = o->rayleigh_beta;
    if (sc->configure)
        st = sc->configure(o, &s->own, err);
    if (st == CL_OK)
        st = kin_alloc(s, err);
    if (st == CL_OK)
        st = kin_vectors(s, err);
    if (st == CL_OK)
        st = kin_kinsol(s, o, err);
    if (st != CL_OK) {
        cl_kin_free(s);
        return st;
    }
    memcpy(s->x, x0, s->n * sizeof *s->x);
    memcpy(s->v, v0, s->n * sizeof *s->v);
    if (s->acc && (st = kin_initial_acc(s, err)) != CL_OK) {
        cl_kin_free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

/* ---- one step ----------------------------------------------------------- */

/* The step's scheme (the start scheme for the first step), scalars and
 * vectors; u starts at the predictor. */
static void kin_scheme(cl_kin *s)
{
    const cl_kin_scheme *sc = s->done == 0 && s->sc->start ? s->sc->start
                                                           : s->sc;
    double h = s->h;
    s->t = s->t0 + (double)s->done * h;
    s->c = sc->c * h;
    s->alpha = sc->alpha * h;
    s->beta = sc->beta;
    s->alpha1 = sc->alpha1 * h;
    s->te = s->t + sc->te * h;
    s->step = (cl_kin_step){
        .n = s->n, .h = h, .x = s->x, .v = s->v, .xp = s->xp, .vp = s->vp,
        .sc = sc, .acc = s->acc, .vb = s->vb, .ve0 = s->ve0, .x1b = s->x1b,
        .pred = s->pred,
    };
    sc->prepare(&s->step);
    memcpy(N_VGetArrayPointer(s->u), s->pred, s->n * sizeof *s->pred);
}

/* The scales of v_ref = max(1 m/s, max |v_n|) (kinsol_common.h). */
static void kin_scales(cl_kin *s)
{
    double vref = CL_KIN_VREF_MIN;
    for (size_t i = 0; i < s->n; i++)
        vref = fmax(vref, fabs(s->v[i]));
    double *us = N_VGetArrayPointer(s->uscale);
    double *fs = N_VGetArrayPointer(s->fscale);
    for (size_t i = 0; i < s->n; i++) {
        us[i] = 1.0 / vref;
        fs[i] = 1.0 / (s->sys->mass[i] * vref);
    }
}

static bool kin_flag_ok(const cl_kin *s, int flag)
{
    return flag == KIN_SUCCESS || flag == KIN_INITIAL_GUESS_OK ||
           flag == KIN_STEP_LT_STPTOL ||
           (flag == KIN_MAXITER_REACHED && s->maxit == 1);
}

/* The step failed with KINSol flag `flag` after nni iterations. */
static cl_status kin_stepfail(cl_kin *s, int flag, long nni, cl_error *err)
{
    double t = s->t, t1 = t + s->h;
    const char *name = s->sc->name;
    s->nfail++;
    if (s->sys_st != CL_OK)
        return cl_error_set(err, s->sys_st, "%s: %s evaluation failed "
                            "(%s%s) at t = %.9g in step %ld (t = %.9g -> "
                            "%.9g, dt = %g), Newton iteration %ld", name,
                            s->sys_jac ? "Jacobian" : "force",
                            cl_status_name(s->sys_st),
                            s->sys_nonfinite ? ": values not finite" : "",
                            s->te, s->done + 1, t, t1, s->h, nni);
    if (s->lin_st != CL_OK)
        return cl_error_set(err, cl_stop_status(s->lin_st),
                            "%s: linear solver failed in step %ld (t = "
                            "%.9g -> %.9g, dt = %g), Newton iteration %ld: "
                            "%s", name, s->done + 1, t, t1, s->h, nni,
                            s->lin_err.msg);
    char *fname = KINGetReturnFlagName(flag);
    cl_status st = cl_error_set(
        err, CL_ESOLVER, "%s: Newton solve failed in step %ld (t = %.9g -> "
        "%.9g, dt = %g): %s (%d) after %ld iterations (cap %ld), scaled "
        "residual %.3g, tolerance %.3g%s%s; to change: %s", name,
        s->done + 1, t, t1, s->h, fname ? fname : "?", flag, nni, s->maxit,
        s->rmax, s->tol, s->kmsg[0] ? "; " : "", s->kmsg,
        cl_solver_hint(fname, true));
    free(fname);
    return st;
}

/* x1 = x1b + alpha1 v1; the history moves one step on (cl_fixed_run then
 * counts the step). */
static void kin_commit(cl_kin *s)
{
    const double *u = N_VGetArrayPointer(s->u);
    if (s->step.sc->finish)
        s->step.sc->finish(&s->step, u);
    for (size_t i = 0; i < s->n; i++)
        s->x1[i] = s->x1b[i] + s->alpha1 * u[i];
    double *tx = s->xp, *tv = s->vp;
    s->xp = s->x;
    s->x = s->x1;
    s->x1 = tx;
    s->vp = s->v;
    s->v = tv;
    memcpy(s->v, u, s->n * sizeof *s->v);
}

/* ---- the filtered Newton loop (barrier obstacles) ----------------------- */

/* The scaled 2-norm of the residual in s->r. */
static double kin_rnorm(const cl_kin *s)
{
    const double *r = N_VGetArrayPointer(s->r);
    const double *fs = N_VGetArrayPointer(s->fscale);
    double sum = 0.0;
    for (size_t i = 0; i < s->n; i++)
        sum += (r[i] * fs[i]) * (r[i] * fs[i]);
    return sqrt(sum);
}

/* The residual at ut = u + lam du into s->r: 0, 1 when ut is infeasible
 * (a particle at d <= 0 of a barrier obstacle), -1 on another failure. */
static int kin_try(cl_kin *s, double lam)
{
    N_VLinearSum(1.0, s->u, lam, s->du, s->ut);
    if (kin_residual(s->ut, s->r, s) == 0)
        return 0;
    if (s->sys_st != CL_EINFEASIBLE)
        return -1;
    s->sys_st = CL_OK;
    return 1;
}

/* The fraction of the Newton step du the barriers' filter allows: the
 * evaluation point moves straight from xe(u) to xe(u + du), and, for a
 * scheme that evaluates inside the step (the midpoint rule), the step's
 * end point from x1(u) to x1(u + du) as well, so that neither crosses an
 * obstacle (s->x1 is free scratch until kin_commit, s->xe until the next
 * kin_point). */
static double kin_filter(cl_kin *s)
{
    const double *u = N_VGetArrayPointer(s->u), *du = N_VGetArrayPointer(s->du);
    kin_point(s, u);
    for (size_t i = 0; i < s->n; i++)
        s->x1[i] = s->xe[i] + s->alpha * du[i];
    double lam = s->sys->step_fraction(s->sys->data, s->te, s->xe, s->te,
                                       s->x1);
    double t1 = s->t + s->h;
    if (s->te == t1)
        return lam; /* x1(u) = xe(u) */
    for (size_t i = 0; i < s->n; i++) {
        s->xe[i] = s->x1b[i] + s->alpha1 * u[i];
        s->x1[i] = s->xe[i] + s->alpha1 * du[i];
    }
    return fmin(lam, s->sys->step_fraction(s->sys->data, t1, s->xe, t1,
                                           s->x1));
}

/* One filtered Newton iteration from u, whose residual is in s->r with
 * scaled norm *rnorm: du = -J^{-1} R, the filter's fraction of it, then
 * halvings until the norm decreases (Armijo's test; in one-step mode the
 * first feasible point is taken).  KIN_SUCCESS, or the failure's flag. */
static int kin_filtered_iteration(cl_kin *s, double *rnorm)
{
    if (kin_jac(s->u, NULL, NULL, s, NULL, NULL) != 0 ||
        ls_setup(s, NULL) != SUNLS_SUCCESS ||
        ls_solve(s, NULL, s->du, s->r, 0.0) != SUNLS_SUCCESS)
        return KIN_LSETUP_FAIL;
    N_VScale(-1.0, s->du, s->du);
    double lam = kin_filter(s);
    for (int k = 0; k <= CL_KIN_HALVINGS; k++, lam *= 0.5) {
        int rc = kin_try(s, lam);
        if (rc < 0)
            return KIN_SYSFUNC_FAIL;
        double rn = rc == 0 ? kin_rnorm(s) : INFINITY;
        if (rc == 0 && (rn <= (1.0 - CL_KIN_ARMIJO * lam) * *rnorm ||
                        s->maxit == 1 || k == CL_KIN_HALVINGS)) {
            N_VScale(1.0, s->ut, s->u);
            *rnorm = rn;
            return KIN_SUCCESS;
        }
    }
    return KIN_LINESEARCH_NONCONV;
}

/* The full Newton update du is round-off or below newton_tol relative
 * (the test of KINSetScaledStepTol, kinsol_common.h). */
static bool kin_small_update(const cl_kin *s)
{
    const double *u = N_VGetArrayPointer(s->u), *du = N_VGetArrayPointer(s->du);
    const double *us = N_VGetArrayPointer(s->uscale);
    double worst = 0.0;
    for (size_t i = 0; i < s->n; i++)
        worst = fmax(worst, fabs(du[i]) * us[i] / (1.0 + fabs(u[i]) * us[i]));
    return worst <= fmax(s->tol, CL_KIN_STEP_FLOOR);
}

/* The step's Newton solve with the barriers' filter (kinsol_common.h,
 * "Barriers"); the convergence tests and one-step mode are KINSOL's. */
static cl_status kin_filtered_solve(cl_kin *s, cl_error *err)
{
    long it = 0;
    int flag = KIN_SUCCESS;
    if (kin_residual(s->u, s->r, s) != 0)
        return kin_stepfail(s, KIN_SYSFUNC_FAIL, 0, err);
    double rnorm = kin_rnorm(s);
    bool done = s->rmax <= 0.01 * s->tol;
    while (!done && it < s->maxit && flag == KIN_SUCCESS) {
        it++;
        flag = kin_filtered_iteration(s, &rnorm);
        done = flag == KIN_SUCCESS &&
               (s->rmax <= s->tol || s->maxit == 1 || kin_small_update(s));
    }
    s->nni += it;
    if (!done)
        return kin_stepfail(s, flag == KIN_SUCCESS ? KIN_MAXITER_REACHED
                                                   : flag, it, err);
    kin_commit(s);
    return CL_OK;
}

/* Rayleigh's K* = -df/dx frozen for the step at the predicted evaluation
 * point (te, x_n + (te - t_n) v_n, v_n) into kfz (s->xe, s->dfdv are
 * scratch until the Newton solve); 0, or -1 when the evaluation failed. */
static int kin_freeze_stiffness(cl_kin *s)
{
    const cl_system *sys = s->sys;
    double dt = s->te - s->t;
    for (size_t i = 0; i < s->n; i++)
        s->xe[i] = s->x[i] + dt * s->v[i];
    cl_status st = sys->jacobian(sys->data, s->te, s->xe, s->v, NULL,
                                 s->kfz, s->dfdv);
    s->njac++;
    if (st != CL_OK)
        return kin_sysfail(s, st, true, false);
    if (!cl_all_finite(s->kfz, 9 * sys->pattern->nnzb))
        return kin_sysfail(s, CL_EBLOWUP, true, true);
    return 0;
}

static cl_status kin_step(void *state, cl_error *err)
{
    cl_kin *s = state;
    kin_scheme(s);
    kin_scales(s);
    s->sys_st = s->lin_st = CL_OK;
    s->kmsg[0] = '\0';
    if (s->rb > 0.0 && kin_freeze_stiffness(s) != 0)
        return kin_stepfail(s, KIN_SYSFUNC_FAIL, 0, err);
    if (s->sys->step_fraction)
        return kin_filtered_solve(s, err);
    int flag = KINSol(s->mem, s->u, KIN_NONE, s->uscale, s->fscale);
    long nni = 0;
    int gflag = KINGetNumNonlinSolvIters(s->mem, &nni);
    s->nni += nni;
    if (!kin_flag_ok(s, flag))
        return kin_stepfail(s, flag, nni, err);
    if (gflag < 0)
        return kin_sunfail(s, "KINGetNumNonlinSolvIters", gflag, err);
    kin_commit(s);
    return CL_OK;
}

cl_status cl_kin_advance(void *state, double t_out, double *x, double *v,
                         cl_error *err)
{
    cl_kin *s = state;
    cl_fixed_clock c = {s->sc->name, s->n, s->t0, s->h, &s->done, &s->x,
                        &s->v, s->sys};
    return cl_fixed_run(&c, kin_step, s, t_out, x, v, err);
}

void cl_kin_stats(const void *state, cl_stats *out)
{
    const cl_kin *s = state;
    memset(out, 0, sizeof *out);
    out->steps = s->done;
    out->rhs_evals = s->nrhs;
    out->jac_evals = s->njac;
    out->nonlin_iters = s->nni;
    out->nonlin_fails = s->nfail;
    cl_linsol_report(s->lt, s->lstate, out);
}
