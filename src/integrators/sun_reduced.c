/* The half-size Newton solver of CVODE and IDA (see sun_reduced.h for the
 * equations and the calling sequence):
 *
 *   CVODE  A = M - gamma Kv - gamma^2 Kx,   A zv = M rv + gamma Kx rx,
 *          zx = rx + gamma zv;
 *   IDA    A = M - Kv / cj - Kx / cj^2,     A zx = (rv + cj M rx - Kv rx)
 *          / cj^2,  zv = cj zx - rx.
 *
 * The shell SUNMatrix carries a pointer to the solver state (its content,
 * shared by CVODE's clone of it) and nothing else, so that the Jacobian
 * function finds the state through the matrix it is given. */
#include "integrators/sun_reduced.h"

#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <ida/ida.h>
#include <sundials/sundials_matrix.h>

#include "linalg/bsym.h"
#include "linalg/reduced.h"

struct cl_sunred {
    cl_sun *base;
    const cl_linsol_type *lt;
    void *lstate;
    bool ida;
    double g;           /* gamma (CVODE) or cj (IDA) of the last setup */
    double *rhs, *z;    /* n: half-size right-hand side and solution */
    double *w;          /* n: half-size weights (iterative solvers) */
    N_Vector weight;    /* the integrator's weights (borrowed), or NULL */
    N_Vector last_x;    /* the solution vector of the last solve (IDA's) */
    cl_bsym sym;        /* the block that red_rhs multiplies by (Kx for
                         * CVODE, Kv for IDA), by halves when symmetric: */
    double *kdiag, *kupper;
    cl_bsym_kind kkind; /* kdiag, kupper hold the last Jacobian's, unless
                         * CL_BSYM_NONE */
    cl_error err;       /* last failure, msg[0] == 0 if none */
};

/* ---- the shell matrix -------------------------------------------------- */

static SUNMatrix_ID shell_getid(SUNMatrix A)
{
    (void)A;
    return SUNMATRIX_CUSTOM;
}

static int shell_noop(SUNMatrix A)
{
    (void)A;
    return SUNMAT_SUCCESS;
}

static int shell_copy(SUNMatrix A, SUNMatrix B)
{
    (void)A, (void)B;
    return SUNMAT_SUCCESS;
}

static int shell_scaleaddi(sunrealtype c, SUNMatrix A)
{
    (void)c, (void)A;
    return SUNMAT_SUCCESS;
}

static void shell_destroy(SUNMatrix A)
{
    if (A) {
        A->content = NULL;
        SUNMatFreeEmpty(A);
    }
}

static SUNMatrix shell_new(cl_sunred *r, SUNContext ctx);

static SUNMatrix shell_clone(SUNMatrix A)
{
    return shell_new(A->content, A->sunctx);
}

static SUNMatrix shell_new(cl_sunred *r, SUNContext ctx)
{
    SUNMatrix A = SUNMatNewEmpty(ctx);
    if (!A)
        return NULL;
    A->content = r;
    A->ops->getid = shell_getid;
    A->ops->clone = shell_clone;
    A->ops->destroy = shell_destroy;
    A->ops->zero = shell_noop;
    A->ops->copy = shell_copy;
    A->ops->scaleaddi = shell_scaleaddi;
    return A;
}

/* ---- Jacobian functions: Kx, Kv at the solver's state ------------------ */

/* Also packs the block red_rhs multiplies by, if it is symmetric, and
 * tells the cl_linsol of the new values. */
static int red_eval(SUNMatrix J, sunrealtype t, N_Vector y)
{
    cl_sunred *r = J->content;
    cl_sun *b = r->base;
    const double *x = N_VGetArrayPointer(y);
    int ret = cl_sun_jacobian(b, t, x, x + b->sys->n);
    if (ret != 0) {
        r->kkind = CL_BSYM_NONE;
        return ret;
    }
    const double *k = r->ida ? b->dfdv : b->dfdx;
    r->kkind = cl_bsym_check(&r->sym, k, CL_BSYM_TOL);
    if (r->kkind != CL_BSYM_NONE)
        cl_bsym_pack(&r->sym, r->kkind, 1.0, k, 0.0, NULL, NULL, r->kdiag,
                     r->kupper);
    cl_linsol_jacobian(r->lt, r->lstate, b->dfdx, b->dfdv);
    return 0;
}

static int red_cvode_jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J,
                         void *data, N_Vector t1, N_Vector t2, N_Vector t3)
{
    (void)fy, (void)data, (void)t1, (void)t2, (void)t3;
    return red_eval(J, t, y);
}

static int red_ida_jac(sunrealtype t, sunrealtype cj, N_Vector yy,
                       N_Vector yp, N_Vector rr, SUNMatrix J, void *data,
                       N_Vector t1, N_Vector t2, N_Vector t3)
{
    (void)cj, (void)yp, (void)rr, (void)data, (void)t1, (void)t2, (void)t3;
    return red_eval(J, t, yy);
}

/* ---- the linear solver ------------------------------------------------- */

/* SUNDIALS flag of a cl_linsol failure: recoverable if the solver failed. */
static int red_flag(cl_status st)
{
    if (st == CL_OK)
        return SUNLS_SUCCESS;
    return st == CL_ESOLVER ? SUNLS_PACKAGE_FAIL_REC
                            : SUNLS_PACKAGE_FAIL_UNREC;
}

static SUNLinearSolver_Type red_gettype(SUNLinearSolver S)
{
    const cl_sunred *r = S->content;
    return r->lt->solve_tol ? SUNLINEARSOLVER_MATRIX_ITERATIVE
                            : SUNLINEARSOLVER_DIRECT;
}

static SUNLinearSolver_ID red_getid(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_CUSTOM;
}

static int red_initialize(SUNLinearSolver S)
{
    (void)S;
    return SUNLS_SUCCESS;
}

static int red_scaling(SUNLinearSolver S, N_Vector s1, N_Vector s2)
{
    cl_sunred *r = S->content;
    (void)s2;
    r->weight = s1;
    return SUNLS_SUCCESS;
}

/* The solution is always in x: IDA would take the solver's residual vector
 * for it after a solve reported with 0 iterations.  The true counts come
 * from the cl_linsol (cl_sunred_stats). */
static int red_numiters(SUNLinearSolver S)
{
    (void)S;
    return 1;
}

/* IDA insists on this operation for iterative solvers; it would only use
 * it after 0 iterations.  The last solution is what it would want. */
static N_Vector red_resid(SUNLinearSolver S)
{
    const cl_sunred *r = S->content;
    return r->last_x;
}

/* A from the stored Kx, Kv and the current gamma or cj. */
static int red_setup(SUNLinearSolver S, SUNMatrix A)
{
    cl_sunred *r = S->content;
    cl_sun *b = r->base;
    sunrealtype g = 0;
    (void)A;
    int flag = r->ida ? IDAGetCurrentCj(b->mem, &g)
                      : CVodeGetCurrentGamma(b->mem, &g);
    if (flag < 0 || !(g > 0))
        return SUNLS_PACKAGE_FAIL_UNREC;
    r->g = g;
    double a = r->ida ? 1.0 / g : g;
    cl_status st = r->lt->setup(r->lstate, a, a * a, b->dfdx, b->dfdv,
                                &r->err);
    if (st == CL_OK)
        r->err.msg[0] = '\0';
    return red_flag(st);
}

/* r->rhs = K rx, K = Kx (CVODE) or Kv (IDA). */
static void red_kprod(cl_sunred *r, const double *rx)
{
    const cl_sun *s = r->base;
    if (r->kkind != CL_BSYM_NONE)
        cl_bsym_matvec(&r->sym, r->kkind, r->kdiag, r->kupper, rx, r->rhs);
    else
        cl_bmatvec(s->sys->pattern, r->ida ? s->dfdv : s->dfdx, rx, r->rhs);
}

/* Half-size right-hand side from b = (rx, rv), into r->rhs. */
static void red_rhs(cl_sunred *r, const double *rx, const double *rv)
{
    const cl_sun *s = r->base;
    const double *m = s->sys->mass;
    size_t n = s->sys->n;
    double g = r->g;
    red_kprod(r, rx);
    if (!r->ida) {
        for (size_t i = 0; i < n; i++)
            r->rhs[i] = m[i] * rv[i] + g * r->rhs[i];
        return;
    }
    for (size_t i = 0; i < n; i++)
        r->rhs[i] = (rv[i] + g * m[i] * rx[i] - r->rhs[i]) / (g * g);
}

/* The half-size solve into r->z, to the integrator's tolerance if the
 * cl_linsol is iterative and weights were given. */
static cl_status red_solve_half(cl_sunred *r, double delta)
{
    const cl_sun *s = r->base;
    size_t n = s->sys->n;
    if (!r->lt->solve_tol || !r->weight || !(delta > 0))
        return r->lt->solve(r->lstate, r->rhs, r->z, &r->err);
    const double *wv = N_VGetArrayPointer(r->weight) + n;
    const double *im = s->inv_mass, g2 = r->g * r->g;
    for (size_t i = 0; i < n; i++)
        r->w[i] = r->ida ? g2 * wv[i] : wv[i] * im[i];
    return r->lt->solve_tol(r->lstate, r->rhs, r->z, r->w, delta, &r->err);
}

static int red_solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b,
                     sunrealtype delta)
{
    cl_sunred *r = S->content;
    size_t n = r->base->sys->n;
    const double *rx = N_VGetArrayPointer(b), *rv = rx + n;
    double *zx = N_VGetArrayPointer(x), *zv = zx + n, g = r->g;
    (void)A;
    r->last_x = x;
    red_rhs(r, rx, rv);
    cl_status st = red_solve_half(r, delta);
    if (st != CL_OK)
        return red_flag(st);
    for (size_t i = 0; i < n; i++) {
        double zi = r->z[i];
        if (r->ida) {
            zv[i] = g * zi - rx[i];
            zx[i] = zi;
        } else {
            zx[i] = rx[i] + g * zi;
            zv[i] = zi;
        }
    }
    return SUNLS_SUCCESS;
}

/* Only the shell: the state belongs to the integrator (cl_sunred_free). */
static int red_free_shell(SUNLinearSolver S)
{
    if (S) {
        S->content = NULL;
        SUNLinSolFreeEmpty(S);
    }
    return SUNLS_SUCCESS;
}

static SUNLinearSolver red_solver(cl_sunred *r, SUNContext ctx)
{
    SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
    if (!S)
        return NULL;
    S->content = r;
    S->ops->gettype = red_gettype;
    S->ops->getid = red_getid;
    S->ops->initialize = red_initialize;
    S->ops->setup = red_setup;
    S->ops->solve = red_solve;
    S->ops->free = red_free_shell;
    if (r->lt->solve_tol) {
        S->ops->setscalingvectors = red_scaling;
        S->ops->numiters = red_numiters;
        S->ops->resid = red_resid;
    }
    return S;
}

/* ---- create / free / statistics ---------------------------------------- */

void cl_sunred_free(cl_sunred *r)
{
    if (!r)
        return;
    if (r->lstate)
        r->lt->free(r->lstate);
    free(r->rhs);
    free(r->z);
    free(r->w);
    free(r->kdiag);
    free(r->kupper);
    cl_bsym_free(&r->sym);
    free(r);
}

static cl_status red_alloc(cl_sun *s, const cl_linsol_type *lt,
                           const cl_integrator_opts *o, bool ida,
                           cl_sunred **out, cl_error *err)
{
    size_t n = s->sys->n;
    cl_sunred *r = *out = calloc(1, sizeof *r);
    if (!r)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    r->base = s;
    r->lt = lt;
    r->ida = ida;
    r->rhs = malloc(n * sizeof *r->rhs);
    r->z = malloc(n * sizeof *r->z);
    r->w = malloc(n * sizeof *r->w);
    if (!r->rhs || !r->z || !r->w)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    cl_error inner = {0};
    cl_status st = cl_bsym_create(s->sys->pattern, &r->sym, &inner);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: %s", s->name, inner.msg);
    r->kdiag = malloc(9 * r->sym.nb * sizeof *r->kdiag);
    r->kupper = malloc((9 * r->sym.ne + 1) * sizeof *r->kupper);
    if (!r->kdiag || !r->kupper)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    cl_linsol_opts lo = cl_integrator_linsol_opts(o);
    st = lt->create(s->sys->pattern, s->sys->mass, &lo, &r->lstate,
                    &inner);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: %s", s->name, inner.msg);
    return CL_OK;
}

cl_status cl_sunred_attach(cl_sun *s, const cl_linsol_type *lt,
                           const cl_integrator_opts *o, bool ida,
                           cl_sunred **out, cl_error *err)
{
    cl_status st = red_alloc(s, lt, o, ida, out, err);
    if (st != CL_OK)
        return st;
    s->A = shell_new(*out, s->ctx);
    s->ls = s->A ? red_solver(*out, s->ctx) : NULL;
    if (!s->ls)
        return cl_sun_sunfail(s, "SUNMatNewEmpty/SUNLinSolNewEmpty", 0, err);
    char fn[64];
    snprintf(fn, sizeof fn, "%sSetLinearSolver", s->api->pkg);
    int flag = s->api->set_linear_solver(s->mem, s->ls, s->A);
    if (flag < 0)
        return cl_sun_fail(s, fn, flag, err);
    flag = ida ? IDASetJacFn(s->mem, red_ida_jac)
               : CVodeSetJacFn(s->mem, red_cvode_jac);
    if (flag < 0)
        return cl_sun_fail(s, ida ? "IDASetJacFn" : "CVodeSetJacFn", flag,
                           err);
    return CL_OK;
}

cl_status cl_sunred_choose(const cl_sun *s, const char *name,
                           const cl_linsol_type **lt, cl_error *err)
{
    *lt = NULL;
    if (!name || !name[0])
        name = CL_SUNRED_DEFAULT;
    if (strcmp(name, "klu-full") == 0)
        return CL_OK;
    *lt = cl_linsol_find(name);
    if (*lt)
        return CL_OK;
    char names[256];
    return cl_error_set(err, CL_EINVAL, "%s: unknown linear solver \"%s\" "
                        "(known: klu-full, %s)", s->name, name,
                        cl_linsol_names(names, sizeof names));
}

void cl_sunred_stats(const cl_sun *s, const cl_sunred *r, cl_stats *out)
{
    cl_sun_stats(s, out);
    if (!r) {
        snprintf(out->linsol, sizeof out->linsol, "klu-full");
        return;
    }
    cl_stats ls = {0};
    r->lt->stats(r->lstate, &ls);
    out->lin_solves = ls.lin_solves;
    out->lin_iters = ls.lin_iters;
    out->symbolic_facts = ls.symbolic_facts;
    out->lin_fallbacks = ls.lin_fallbacks;
    snprintf(out->linsol, sizeof out->linsol, "%s",
             ls.linsol[0] ? ls.linsol : r->lt->name);
}

cl_status cl_sunred_advance(cl_sun *s, const cl_sunred *r, double t_out,
                            double *x, double *v, cl_error *err)
{
    cl_status st = cl_sun_advance(s, t_out, x, v, err);
    if (st == CL_OK || !r || !r->err.msg[0])
        return st;
    size_t len = strlen(err->msg);
    snprintf(err->msg + len, sizeof err->msg - len,
             "; last linear-solver failure: %s", r->err.msg);
    return st;
}
