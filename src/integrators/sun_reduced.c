/* The Newton linear solvers of CVODE and IDA (see sun_reduced.h for the
 * equations and the calling sequence): klu-full, and the half-size
 *
 *   CVODE  A = M - gamma Kv - gamma^2 Kx,   A zv = M rv + gamma Kx rx,
 *          zx = rx + gamma zv;
 *   IDA    A = M - Kv / cj - Kx / cj^2,     A zx = (rv + cj M rx - Kv rx)
 *          / cj^2,  zv = cj zx - rx.
 *
 * Either is plugged into the integrator state (sun_adapter.h), where the
 * Jacobian functions find it; the half-size solver's SUNMatrix is the
 * adapter's shell, which holds no values. */
#include "integrators/sun_reduced.h"

#include <stdlib.h>
#include <string.h>

#include <ida/ida.h>

#include "linalg/bsym.h"
#include "linalg/firstorder.h"
#include "linalg/reduced.h"

typedef struct {
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
} cl_sunred;

/* ---- Jacobian functions: Kx, Kv at the solver's state ------------------ */

/* Also packs the block red_rhs multiplies by, if it is symmetric, and
 * tells the cl_linsol of the new values. */
static int red_eval(cl_sun *b, sunrealtype t, N_Vector y)
{
    cl_sunred *r = b->plug_data;
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
    (void)fy, (void)J, (void)t1, (void)t2, (void)t3;
    return red_eval(data, t, y);
}

static int red_ida_jac(sunrealtype t, sunrealtype cj, N_Vector yy,
                       N_Vector yp, N_Vector rr, SUNMatrix J, void *data,
                       N_Vector t1, N_Vector t2, N_Vector t3)
{
    (void)cj, (void)yp, (void)rr, (void)J, (void)t1, (void)t2, (void)t3;
    return red_eval(data, t, yy);
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

static int red_scaling(void *data, N_Vector s1, N_Vector s2)
{
    cl_sunred *r = data;
    (void)s2;
    r->weight = s1;
    return SUNLS_SUCCESS;
}

/* The solution is always in x: IDA would take the solver's residual vector
 * for it after a solve reported with 0 iterations.  The true counts come
 * from the cl_linsol (red_stats). */
static int red_numiters(void *data)
{
    (void)data;
    return 1;
}

/* IDA insists on this operation for iterative solvers; it would only use
 * it after 0 iterations.  The last solution is what it would want. */
static N_Vector red_resid(void *data)
{
    const cl_sunred *r = data;
    return r->last_x;
}

/* A from the stored Kx, Kv and the current gamma or cj. */
static int red_setup(void *data, SUNMatrix A)
{
    cl_sunred *r = data;
    cl_sun *b = r->base;
    sunrealtype g = 0;
    (void)A;
    int flag = r->ida ? IDAGetCurrentCj(b->mem, &g)
                      : b->api->get_gamma(b->mem, &g);
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

static int red_solve(void *data, SUNMatrix A, N_Vector x, N_Vector b,
                     sunrealtype delta)
{
    cl_sunred *r = data;
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

/* The state belongs to the integrator (its plug), not to the solver. */
static const cl_sun_lsdef red_direct = {
    .type = SUNLINEARSOLVER_DIRECT,
    .setup = red_setup,
    .solve = red_solve,
};

/* Iterative cl_linsols get the integrator's weights and tolerance. */
static const cl_sun_lsdef red_iterative = {
    .type = SUNLINEARSOLVER_MATRIX_ITERATIVE,
    .setup = red_setup,
    .solve = red_solve,
    .scaling = red_scaling,
    .numiters = red_numiters,
    .resid = red_resid,
};

/* ---- the half-size solver as the integrator's plug -------------------- */

/* The package's Jacobian function: cv for the y' = f packages (CVODE,
 * ARKODE), id for IDA. */
static cl_status red_jacfn(cl_sun *s, bool ida, cl_sun_jacfn cv,
                           IDALsJacFn id, cl_error *err)
{
    int flag = ida ? IDASetJacFn(s->mem, id) : s->api->set_jac_fn(s->mem, cv);
    if (flag < 0) {
        char fn[64];
        snprintf(fn, sizeof fn, "%sSetJacFn", s->api->pkg);
        return cl_sun_fail(s, fn, flag, err);
    }
    return CL_OK;
}

static void red_free(void *data)
{
    cl_sunred *r = data;
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

/* The counters the cl_linsol keeps (steps, setups, Jacobian evaluations
 * stay the integrator's). */
static void red_stats(const void *data, cl_stats *out)
{
    const cl_sunred *r = data;
    cl_stats ls = {0};
    cl_linsol_report(r->lt, r->lstate, &ls);
    out->lin_solves = ls.lin_solves;
    out->lin_iters = ls.lin_iters;
    out->symbolic_facts = ls.symbolic_facts;
    out->lin_fallbacks = ls.lin_fallbacks;
    out->lin_recoveries = ls.lin_recoveries;
    memcpy(out->linsol, ls.linsol, sizeof out->linsol);
}

static const char *red_last_error(const void *data)
{
    return ((const cl_sunred *)data)->err.msg;
}

static const cl_sun_plug red_plug = {
    .stats = red_stats,
    .last_error = red_last_error,
    .free = red_free,
};

static cl_status red_alloc(cl_sun *s, cl_sunred *r, const cl_integrator_opts *o,
                           cl_error *err)
{
    size_t n = s->sys->n;
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
    cl_linsol_opts lo = cl_integrator_linsol_opts(o, s->sys);
    st = r->lt->create(s->sys->pattern, s->sys->mass, &lo, &r->lstate,
                       &inner);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: %s", s->name, inner.msg);
    return CL_OK;
}

/* The half-size solver with cl_linsol lt: shell matrix into s->A, solver
 * into s->ls, state plugged into s. */
static cl_status red_attach(cl_sun *s, const cl_linsol_type *lt,
                            const cl_integrator_opts *o, bool ida,
                            cl_error *err)
{
    cl_sunred *r = calloc(1, sizeof *r);
    if (!r)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    cl_sun_plug_in(s, &red_plug, r);
    r->base = s;
    r->lt = lt;
    r->ida = ida;
    cl_status st = red_alloc(s, r, o, err);
    if (st != CL_OK)
        return st;
    s->A = cl_sun_shell_matrix(s->ctx);
    s->ls = s->A ? cl_sun_shell_linsol(lt->solve_tol ? &red_iterative
                                                      : &red_direct,
                                       r, s->ctx)
                 : NULL;
    if (!s->ls)
        return cl_sun_sunfail(s, "cl_sun_shell_matrix/cl_sun_shell_linsol", 0, err);
    char fn[64];
    snprintf(fn, sizeof fn, "%sSetLinearSolver", s->api->pkg);
    int flag = s->api->set_linear_solver(s->mem, s->ls, s->A);
    if (flag < 0)
        return cl_sun_fail(s, fn, flag, err);
    return red_jacfn(s, ida, red_cvode_jac, red_ida_jac, err);
}

/* ---- klu-full: KLU on the first-order matrix --------------------------- */

static int full_cvode_jac(sunrealtype t, N_Vector y, N_Vector fy,
                          SUNMatrix J, void *data, N_Vector t1, N_Vector t2,
                          N_Vector t3)
{
    cl_sun *s = data;
    const double *x = N_VGetArrayPointer(y);
    (void)fy, (void)t1, (void)t2, (void)t3;
    int ret = cl_sun_jacobian(s, t, x, x + s->sys->n);
    if (ret != 0)
        return ret;
    if (cl_firstorder_fill(s->plug_data, s->dfdx, s->dfdv, J, NULL) != CL_OK)
        return -1;
    return 0;
}

static int full_ida_jac(sunrealtype t, sunrealtype cj, N_Vector yy,
                        N_Vector yp, N_Vector rr, SUNMatrix G, void *data,
                        N_Vector t1, N_Vector t2, N_Vector t3)
{
    cl_sun *s = data;
    const double *x = N_VGetArrayPointer(yy);
    (void)yp, (void)rr, (void)t1, (void)t2, (void)t3;
    int ret = cl_sun_jacobian(s, t, x, x + s->sys->n);
    if (ret != 0)
        return ret;
    if (cl_firstorder_fill_implicit(s->plug_data, s->dfdx, s->dfdv, cj, G,
                                    NULL) != CL_OK)
        return -1;
    return 0;
}

static void full_stats(const void *data, cl_stats *out)
{
    (void)data;
    snprintf(out->linsol, sizeof out->linsol, "klu-full");
}

static void full_free(void *data)
{
    cl_firstorder_free(data);
    free(data);
}

static const cl_sun_plug full_plug = {
    .stats = full_stats,
    .free = full_free,
};

/* The first-order pattern and KLU on it (the counting shell counts its
 * solves and analyses), the Jacobian function. */
static cl_status full_attach(cl_sun *s, bool ida, cl_error *err)
{
    cl_firstorder *fo = calloc(1, sizeof *fo);
    if (!fo)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    cl_sun_plug_in(s, &full_plug, fo);
    cl_status st = cl_firstorder_create(s->sys->pattern, s->sys->mass, fo,
                                        err);
    if (st == CL_OK)
        st = cl_sun_attach_klu(s, fo->size, fo->nnz, err);
    if (st != CL_OK)
        return st;
    return red_jacfn(s, ida, full_cvode_jac, full_ida_jac, err);
}

/* ---- the choice --------------------------------------------------------- */

cl_status cl_sunred_attach(cl_sun *s, const cl_integrator_opts *o, bool ida,
                           cl_error *err)
{
    const char *name = o->linsol && o->linsol[0] ? o->linsol
                                                 : CL_SUNRED_DEFAULT;
    if (strcmp(name, "klu-full") == 0)
        return full_attach(s, ida, err);
    const cl_linsol_type *lt;
    cl_status rc = cl_linsol_get(s->name, name, "klu-full", &lt, err);
    return rc ? rc : red_attach(s, lt, o, ida, err);
}
