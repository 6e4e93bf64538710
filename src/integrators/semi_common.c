/* Shared state, evaluation, linear solve and the linearised backward-Euler
 * step of semi-be and semi-bdf2 (docs/integrators.md, 3;
 * integrators/semi_common.h):
 *
 *     (M - h df/dv - h^2 df/dx) dv = h (f0 + h df/dx v0),
 *     v1 = v0 + dv,   x1 = x0 + h v1.
 *
 * The products df/dx v0 (and semi-bdf2's df/dv w) are block products over
 * the system's cl_bpattern (cl_bmatvec). */
#include "integrators/semi_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/stop.h"
#include "linalg/reduced.h"

static cl_status semi_check_args(const char *name, const cl_system *sys,
                                 const cl_integrator_opts *o, double t0,
                                 cl_error *err)
{
    if (!isfinite(o->dt) || !(o->dt > 0.0))
        return cl_error_set(err, CL_EINVAL, "%s: step dt = %g, must be "
                            "finite and > 0", name, o->dt);
    if (!isfinite(t0))
        return cl_error_set(err, CL_EINVAL, "%s: initial time %g", name, t0);
    if (sys->n == 0 || !sys->pattern || 3 * sys->pattern->nb != sys->n)
        return cl_error_set(err, CL_EINVAL, "%s: system has %zu unknowns "
                            "and a block pattern of %zu rows (need n = 3 nb "
                            "> 0)", name, sys->n,
                            sys->pattern ? sys->pattern->nb : 0);
    if (!sys->force || !sys->jacobian)
        return cl_error_set(err, CL_EINVAL, "%s: system needs a force and "
                            "an analytic Jacobian", name);
    return cl_check_masses(sys->mass, sys->n, name, err);
}

/* The arrays of the constraints, when the system has them. */
static cl_status semi_alloc_constraints(cl_semi *s, cl_error *err)
{
    size_t n = s->n, nval = 9 * s->sys->pattern->nnzb;
    if (!s->sys->constrain)
        return CL_OK;
    double **vec[] = {&s->cs.z, &s->cs.y, &s->cs.g, &s->pres, &s->imp};
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++)
        *vec[i] = calloc(n, sizeof(double));
    s->cs.S = calloc(3 * n, sizeof *s->cs.S);
    s->fdx = calloc(nval, sizeof *s->fdx);
    s->fdv = calloc(nval, sizeof *s->fdv);
    if (!s->cs.z || !s->cs.y || !s->cs.g || !s->pres || !s->imp ||
        !s->cs.S || !s->fdx || !s->fdv)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    return CL_OK;
}

static cl_status semi_alloc(cl_semi *s, cl_error *err)
{
    size_t n = s->n, nval = 9 * s->sys->pattern->nnzb;
    double **vec[] = {&s->x, &s->v, &s->f, &s->rhs, &s->sol, &s->work};
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++)
        *vec[i] = calloc(n, sizeof(double));
    s->dfdx = calloc(nval, sizeof *s->dfdx);
    s->dfdv = calloc(nval, sizeof *s->dfdv);
    if (!s->x || !s->v || !s->f || !s->rhs || !s->sol || !s->work ||
        !s->dfdx || !s->dfdv)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", s->name);
    return semi_alloc_constraints(s, err);
}

cl_status cl_semi_init(cl_semi *s, const char *name, const cl_system *sys,
                       const cl_integrator_opts *o, double t0,
                       const double *x0, const double *v0, cl_error *err)
{
    memset(s, 0, sizeof *s);
    s->name = name;
    s->sys = sys;
    cl_status st = semi_check_args(name, sys, o, t0, err);
    if (st == CL_OK)
        st = cl_linsol_get(s->name, o->linsol, NULL, &s->lst, err);
    if (st != CL_OK)
        return st;
    s->n = sys->n;
    s->t0 = t0;
    s->h = o->dt;
    st = semi_alloc(s, err);
    cl_linsol_opts lo = cl_integrator_linsol_opts(o, sys);
    if (st == CL_OK)
        st = s->lst->create(sys->pattern, sys->mass, &lo, &s->ls, err);
    if (st != CL_OK) {
        cl_semi_release(s);
        return st;
    }
    memcpy(s->x, x0, s->n * sizeof *s->x);
    memcpy(s->v, v0, s->n * sizeof *s->v);
    return CL_OK;
}

void cl_semi_release(cl_semi *s)
{
    if (s->lst && s->ls)
        s->lst->free(s->ls);
    free(s->x);
    free(s->v);
    free(s->f);
    free(s->dfdx);
    free(s->dfdv);
    free(s->rhs);
    free(s->sol);
    free(s->work);
    free(s->cs.S);
    free(s->cs.z);
    free(s->cs.y);
    free(s->cs.g);
    free(s->fdx);
    free(s->fdv);
    free(s->pres);
    free(s->imp);
    memset(s, 0, sizeof *s);
}

cl_status cl_semi_linearise(cl_semi *s, double t, cl_error *err)
{
    const cl_system *sys = s->sys;
    size_t nval = 9 * sys->pattern->nnzb;
    cl_status st = sys->jacobian(sys->data, t, s->x, s->v, s->f, s->dfdx,
                                 s->dfdv);
    s->nlin++;
    bool finite = st == CL_OK && cl_all_finite(s->f, s->n) &&
                  cl_all_finite_threads(s->dfdx, nval, sys->threads) &&
                  cl_all_finite_threads(s->dfdv, nval, sys->threads);
    if (st == CL_OK && !finite)
        st = CL_EBLOWUP;
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: force/Jacobian evaluation failed "
                            "(%s%s) at t = %.9g (step %ld, dt = %g)", s->name,
                            cl_status_name(st),
                            st == CL_EBLOWUP ? ": values not finite" : "", t,
                            s->done, s->h);
    cl_linsol_jacobian(s->lst, s->ls, s->dfdx, s->dfdv);
    return CL_OK;
}

/* Set up with dfdx, dfdv and solve for s->sol from rhs; a failure once
 * a stop is requested is the stop's (cl_stop_status). */
static cl_status semi_linsolve(cl_semi *s, double a, double b,
                               const double *dfdx, const double *dfdv,
                               const double *rhs, cl_error *err)
{
    cl_error inner = {0};
    cl_status st = s->lst->setup(s->ls, a, b, dfdx, dfdv, &inner);
    if (st == CL_OK)
        st = s->lst->solve(s->ls, rhs, s->sol, &inner);
    st = cl_stop_status(st);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: linear solve failed at t = %.9g "
                            "(step %ld, dt = %g): %s", s->name,
                            s->t0 + (double)s->done * s->h, s->done, s->h,
                            inner.msg);
    return CL_OK;
}

double cl_semi_filter(cl_semi *s, const double *dx)
{
    const cl_system *sys = s->sys;
    if (!sys->step_fraction)
        return 1.0;
    double t = s->t0 + (double)s->done * s->h;
    for (size_t i = 0; i < s->n; i++)
        s->work[i] = s->x[i] + dx[i];
    return sys->step_fraction(sys->data, t, s->x, t + s->h, s->work);
}

cl_status cl_semi_solve(cl_semi *s, double a, double b, cl_error *err)
{
    return semi_linsolve(s, a, b, s->dfdx, s->dfdv, s->rhs, err);
}

/* ---- Baraff-Witkin constraints (docs/integrators.md, 3.4) ------------- */

/* s->pres = coef[0] (I - S) v + coef[1] z + coef[2] y. */
static void semi_prescribe(cl_semi *s, const double coef[3])
{
    cl_bdiag_apply(s->n / 3, s->cs.S, s->v, s->pres);
    for (size_t i = 0; i < s->n; i++)
        s->pres[i] = coef[0] * (s->v[i] - s->pres[i]) + coef[1] * s->cs.z[i] +
                     coef[2] * s->cs.y[i];
}

/* One filtered solve (BW98 section 5.3, as the projected system
 * S A S w = S r, solved by any linear solver: with pcg it is their
 * modified conjugate gradient; docs/integrators.md, 3.4), then the
 * impulses. */
static cl_status semi_filtered_solve(cl_semi *s, double a, double b,
                                     cl_error *err)
{
    const cl_bpattern *pat = s->sys->pattern;
    const double *m = s->sys->mass, *S = s->cs.S;
    size_t nb = s->n / 3;
    cl_reduced_matvec(pat, m, a, b, s->dfdx, s->dfdv, s->pres, s->work);
    for (size_t i = 0; i < s->n; i++)
        s->work[i] = s->rhs[i] + s->cs.g[i] - s->work[i];
    cl_bdiag_apply(nb, S, s->work, s->imp);
    cl_reduced_filter(pat, S, s->dfdx, s->fdx);
    cl_reduced_filter(pat, S, s->dfdv, s->fdv);
    cl_status st = semi_linsolve(s, a, b, s->fdx, s->fdv, s->imp, err);
    if (st != CL_OK)
        return st;
    cl_bdiag_apply(nb, S, s->sol, s->sol);
    for (size_t i = 0; i < s->n; i++)
        s->sol[i] += s->pres[i];
    cl_reduced_matvec(pat, m, a, b, s->dfdx, s->dfdv, s->sol, s->imp);
    for (size_t i = 0; i < s->n; i++)
        s->imp[i] -= s->rhs[i] + s->cs.g[i];
    return CL_OK;
}

static cl_status semi_constrain(cl_semi *s, double t, const double *impulse,
                                bool *changed, cl_error *err)
{
    const cl_system *sys = s->sys;
    cl_status st = sys->constrain(sys->data, t, s->h, s->x, s->v, impulse,
                                  &s->cs, changed);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: contact constraints failed (%s) "
                            "at t = %.9g (step %ld, dt = %g)", s->name,
                            cl_status_name(st), t, s->done, s->h);
    return CL_OK;
}

cl_status cl_semi_solve_constrained(cl_semi *s, double t, void *state,
                                    cl_semi_rhs_fn fill_rhs, double a,
                                    double b, const double coef[3],
                                    cl_error *err)
{
    if (!s->sys->constrain) {
        fill_rhs(state);
        return cl_semi_solve(s, a, b, err);
    }
    bool changed;
    cl_status st = semi_constrain(s, t, NULL, &changed, err);
    /* every pass but the last releases or demotes a constraint (from
     * sticking to sliding to free), so at most 2 nb + 1 passes; more
     * would be a fault of the release rule, reported, not looped on */
    long pass = 0, most = 2 * (long)(s->n / 3) + 1;
    for (changed = true; st == CL_OK && changed; pass++) {
        if (pass == most)
            return cl_error_set(err, CL_ESOLVER, "%s: contact constraints "
                                "still changing after %ld passes at t = "
                                "%.9g (step %ld, dt = %g)", s->name, most, t,
                                s->done, s->h);
        fill_rhs(state);
        semi_prescribe(s, coef);
        st = semi_filtered_solve(s, a, b, err);
        if (st == CL_OK)
            st = semi_constrain(s, t, s->imp, &changed, err);
    }
    return st;
}

/* a_i = S_i a_i + (I - S_i) b_i, with s->work */
static void semi_keep_filtered(cl_semi *s, double *a, const double *b)
{
    for (size_t i = 0; i < s->n; i++)
        s->work[i] = a[i] - b[i];
    cl_bdiag_apply(s->n / 3, s->cs.S, s->work, s->work);
    for (size_t i = 0; i < s->n; i++)
        a[i] = s->work[i] + b[i];
}

void cl_semi_hold_velocity(cl_semi *s, const double *vold)
{
    if (!s->sys->constrain)
        return;
    for (size_t i = 0; i < s->n; i++)
        s->sol[i] = vold[i] + s->cs.z[i];
    semi_keep_filtered(s, s->v, s->sol);
}

void cl_semi_hold_history(cl_semi *s, double *xprev, double *vprev)
{
    if (!s->sys->constrain)
        return;
    for (size_t i = 0; i < s->n; i++)
        s->sol[i] = s->x[i] - s->h * s->v[i];
    semi_keep_filtered(s, xprev, s->sol);
    semi_keep_filtered(s, vprev, s->v);
}

/* ---- the linearised backward-Euler step ------------------------------- */

/* rhs = h (f + h K v), and + h K y under constraints (BW98 eq. 18). */
static void semi_be_rhs(void *state)
{
    cl_semi *s = state;
    double h = s->h;
    cl_bmatvec_threads(s->sys->pattern, s->dfdx, s->v, s->work,
                       s->sys->threads);
    for (size_t i = 0; i < s->n; i++)
        s->rhs[i] = h * (s->f[i] + h * s->work[i]);
    if (!s->sys->constrain)
        return;
    cl_bmatvec_threads(s->sys->pattern, s->dfdx, s->cs.y, s->work,
                       s->sys->threads);
    for (size_t i = 0; i < s->n; i++)
        s->rhs[i] += h * s->work[i];
}

cl_status cl_semi_be_step(cl_semi *s, cl_error *err)
{
    static const double coef[3] = {0.0, 1.0, 0.0}; /* dv's part: z */
    double h = s->h, t = s->t0 + (double)s->done * h;
    cl_status st = cl_semi_linearise(s, t, err);
    if (st == CL_OK)
        st = cl_semi_solve_constrained(s, t, s, semi_be_rhs, h, h * h, coef,
                                       err);
    if (st != CL_OK)
        return st;
    for (size_t i = 0; s->sys->step_fraction && i < s->n; i++)
        s->rhs[i] = h * (s->v[i] + s->sol[i]); /* the step's move */
    double a = cl_semi_filter(s, s->rhs);
    for (size_t i = 0; i < s->n; i++) {
        s->v[i] = a * (s->v[i] + s->sol[i]);
        s->x[i] += h * s->v[i];
    }
    for (size_t i = 0; s->cs.y && i < s->n; i++)
        s->x[i] += s->cs.y[i];
    return CL_OK;
}

cl_status cl_semi_advance(cl_semi *s, void *state, cl_fixed_step_fn step,
                          double t_out, double *x, double *v, cl_error *err)
{
    cl_fixed_clock c = {s->name, s->n, s->t0, s->h, &s->done, &s->x, &s->v,
                        s->sys};
    return cl_fixed_run(&c, step, state, t_out, x, v, err);
}

void cl_semi_stats(const cl_semi *s, cl_stats *out)
{
    memset(out, 0, sizeof *out);
    out->steps = s->done;
    out->rhs_evals = s->nlin;
    out->jac_evals = s->nlin;
    cl_linsol_report(s->lst, s->ls, out);
}
