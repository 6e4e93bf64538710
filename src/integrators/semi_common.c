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
    return CL_OK;
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
    cl_linsol_opts lo = cl_integrator_linsol_opts(o);
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
                  cl_all_finite(s->dfdx, nval) && cl_all_finite(s->dfdv, nval);
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

cl_status cl_semi_solve(cl_semi *s, double a, double b, cl_error *err)
{
    cl_error inner = {0};
    cl_status st = s->lst->setup(s->ls, a, b, s->dfdx, s->dfdv, &inner);
    if (st == CL_OK)
        st = s->lst->solve(s->ls, s->rhs, s->sol, &inner);
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

cl_status cl_semi_be_step(cl_semi *s, cl_error *err)
{
    double h = s->h;
    cl_status st = cl_semi_linearise(s, s->t0 + (double)s->done * h, err);
    if (st != CL_OK)
        return st;
    cl_bmatvec(s->sys->pattern, s->dfdx, s->v, s->work);
    for (size_t i = 0; i < s->n; i++)
        s->rhs[i] = h * (s->f[i] + h * s->work[i]);
    st = cl_semi_solve(s, h, h * h, err);
    if (st != CL_OK)
        return st;
    for (size_t i = 0; s->sys->step_fraction && i < s->n; i++)
        s->rhs[i] = h * (s->v[i] + s->sol[i]); /* the step's move */
    double a = cl_semi_filter(s, s->rhs);
    for (size_t i = 0; i < s->n; i++) {
        s->v[i] = a * (s->v[i] + s->sol[i]);
        s->x[i] += h * s->v[i];
    }
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
    s->lst->stats(s->ls, out);
}
