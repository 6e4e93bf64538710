/* Convergence study: levels of one integrator against a tight reference
 * (see convergence.h for the definitions). */
#include "analysis/convergence.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>

#include "analysis/diagnostics.h"
#include "core/clock.h"


/* Integrate sys with a fresh integrator from the model's initial state to
 * T: the final free state into x, v; statistics with times into *s. */
static cl_status integrate(cl_model *m, const cl_integrator_type *type,
                           const cl_integrator_opts *io, double T, double *x,
                           double *v, cl_stats *s, cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    void *state = NULL;
    double c0 = cl_clock_cpu(), w0 = cl_clock_wall();
    cl_status rc = cl_model_initial_state(m, x, v);
    memset(s, 0, sizeof *s);
    if (!rc && !(rc = type->create(sys, io, 0.0, x, v, &state, err)))
        rc = type->advance(state, T, x, v, err);
    if (state) {
        type->stats(state, s);
        type->free(state);
    }
    s->cpu = cl_clock_cpu() - c0;
    s->wall = cl_clock_wall() - w0;
    return rc;
}

static cl_status reference_run(cl_model *m, const cl_conv_opts *o,
                               double rtol, double *x, double *v,
                               cl_stats *s, cl_error *err)
{
    const cl_integrator_type *type = cl_integrator_find("cvode-bdf");
    cl_integrator_opts io = {.rtol = rtol, .atol = rtol / 100,
                             .linsol = o->ref_linsol};
    cl_error why = {0};
    cl_status rc = integrate(m, type, &io, o->t_end, x, v, s, &why);
    if (rc)
        cl_error_set(err, rc, "reference (cvode-bdf, rtol %g) failed: %s",
                     rtol, why.msg);
    return rc;
}

cl_status cl_conv_reference(cl_model *m, const cl_conv_opts *o,
                            cl_conv_ref *ref, cl_error *err)
{
    size_t n = cl_model_system(m)->n;
    memset(ref, 0, sizeof *ref);
    if (cl_model_system(m)->step_done)
        return cl_error_set(err, CL_EUNSUPPORTED, "a model that tears ([tear] "
                            "cut) changes for good during a run, so runs "
                            "cannot be repeated from its initial state");
    if (!(o->ref_rtol >= 1e-15 && o->ref_rtol <= 1e-4))
        return cl_error_set(err, CL_EINVAL, "reference rtol = %g: expected "
                            "1e-15 .. 1e-4", o->ref_rtol);
    ref->n = n;
    ref->x = malloc(n * sizeof *ref->x);
    ref->v = malloc(n * sizeof *ref->v);
    double *xl = malloc(n * sizeof *xl), *vl = malloc(n * sizeof *vl);
    cl_stats loose;
    cl_status rc = ref->x && ref->v && xl && vl
                       ? CL_OK
                       : cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!rc && !(rc = reference_run(m, o, o->ref_rtol, ref->x, ref->v,
                                    &ref->stats, err)) &&
        !(rc = reference_run(m, o, 10 * o->ref_rtol, xl, vl, &loose, err)))
        ref->err_x = cl_max_distance(xl, ref->x, n / 3);
    free(xl);
    free(vl);
    if (rc)
        cl_conv_ref_free(ref);
    return rc;
}

void cl_conv_ref_free(cl_conv_ref *ref)
{
    free(ref->x);
    free(ref->v);
    memset(ref, 0, sizeof *ref);
}

/* The options of level k. */
static cl_integrator_opts level_opts(const cl_integrator_type *type,
                                     const cl_integrator_opts *io, int k,
                                     double *param)
{
    cl_integrator_opts o = *io;
    if (type->fixed_step) {
        o.dt = ldexp(io->dt, -k);
        *param = o.dt;
    } else {
        double s = pow(10.0, -k);
        o.rtol = io->rtol * s;
        o.atol = io->atol * s;
        *param = o.rtol;
    }
    return o;
}

cl_status cl_conv_check(const cl_integrator_type *type,
                        const cl_integrator_opts *io, int levels,
                        const cl_conv_opts *o, cl_error *err)
{
    if (levels < 2 || levels > CL_CONV_MAX_LEVELS)
        return cl_error_set(err, CL_EINVAL, "levels = %d: expected 2 .. %d",
                            levels, CL_CONV_MAX_LEVELS);
    if (!type->fixed_step &&
        io->rtol * pow(10.0, 1 - levels) < 1e-15)
        return cl_error_set(err, CL_EINVAL, "rtol = %g over %d levels goes "
                            "down to %g: below 1e-15", io->rtol, levels,
                            io->rtol * pow(10.0, 1 - levels));
    double steps = o->t_end / io->dt;
    if (type->fixed_step && fabs(steps - round(steps)) > 1e-9 * steps)
        return cl_error_set(err, CL_EINVAL, "t_end = %g is not a multiple "
                            "of dt = %g (%s takes fixed steps)", o->t_end,
                            io->dt, type->name);
    return CL_OK;
}

/* Orders between consecutive levels and the least-squares fit. */
static void fit_orders(cl_conv_result *r)
{
    double q = log(r->fixed ? 2.0 : 10.0);
    double lp[CL_CONV_MAX_LEVELS], lx[CL_CONV_MAX_LEVELS],
        lv[CL_CONV_MAX_LEVELS];
    r->nfit = 0;
    for (int k = 0; k < r->nlev; k++) {
        cl_conv_level *l = &r->lev[k], *prev = k ? &r->lev[k - 1] : NULL;
        l->order = prev && !prev->rc && !l->rc && prev->err_x > 0 &&
                           l->err_x > 0
                       ? log(prev->err_x / l->err_x) / q
                       : NAN;
        if (!l->fitted)
            continue;
        lp[r->nfit] = log(l->param);
        lx[r->nfit] = log(l->err_x);
        lv[r->nfit++] = log(fmax(l->err_v, 1e-300));
    }
    double c0, cov00, cov01, cov11, sumsq;
    r->slope_x = r->slope_v = NAN;
    if (r->nfit < 2)
        return;
    gsl_fit_linear(lp, 1, lx, 1, (size_t)r->nfit, &c0, &r->slope_x, &cov00,
                   &cov01, &cov11, &sumsq);
    gsl_fit_linear(lp, 1, lv, 1, (size_t)r->nfit, &c0, &r->slope_v, &cov00,
                   &cov01, &cov11, &sumsq);
}

/* Work space of the levels: the free state, the full one and the Type1
 * neighbours for the stretch test. */
typedef struct {
    double *x, *v, *xf, *vf;
    cl_pairset type1;
} conv_work;

static cl_status work_alloc(cl_model *m, conv_work *w, cl_error *err)
{
    const cl_cloth *c = cl_model_cloth(m);
    size_t n = cl_model_system(m)->n;
    w->x = malloc(n * sizeof *w->x);
    w->v = malloc(n * sizeof *w->v);
    w->xf = malloc(3 * c->np * sizeof *w->xf);
    w->vf = malloc(3 * c->np * sizeof *w->vf);
    if (!w->x || !w->v || !w->xf || !w->vf)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    return cl_pairs_type1(c, &w->type1, err);
}

static void work_free(conv_work *w)
{
    free(w->x);
    free(w->v);
    free(w->xf);
    free(w->vf);
    cl_pairs_free(&w->type1);
}

/* A run that ends finite but stretched beyond max_stretch has blown up
 * as surely as one that overflowed (the test `run` applies). */
static cl_status check_stretch(cl_model *m, const cl_conv_opts *o,
                               conv_work *w, cl_error *err)
{
    cl_cloth_scatter(cl_model_cloth(m), o->t_end, w->x, w->v, w->xf, w->vf);
    double q = cl_max_stretch(&w->type1, w->xf);
    if (!(q <= o->max_stretch))
        return cl_error_set(err, CL_EBLOWUP, "max stretch d/L = %.3g at "
                            "t = %g exceeds max_stretch = %g", q, o->t_end,
                            o->max_stretch);
    return CL_OK;
}

cl_status cl_convergence(cl_model *m, const cl_integrator_type *type,
                         const cl_integrator_opts *io, int levels,
                         const cl_conv_opts *o, const cl_conv_ref *ref,
                         cl_conv_result *r, cl_error *err)
{
    size_t n = ref->n;
    conv_work w = {0};
    memset(r, 0, sizeof *r);
    r->type = type;
    r->fixed = type->fixed_step;
    cl_status rc = cl_conv_check(type, io, levels, o, err);
    if (!rc)
        rc = work_alloc(m, &w, err);
    for (int k = 0; !rc && k < levels; k++, r->nlev++) {
        cl_conv_level *l = &r->lev[k];
        cl_integrator_opts lo = level_opts(type, io, k, &l->param);
        l->rc = integrate(m, type, &lo, o->t_end, w.x, w.v, &l->stats,
                          &l->why);
        if (!l->rc)
            l->rc = check_stretch(m, o, &w, &l->why);
        l->err_x = l->rc ? NAN : cl_max_distance(w.x, ref->x, n / 3);
        l->err_v = l->rc ? NAN : cl_max_distance(w.v, ref->v, n / 3);
        l->fitted = !l->rc && l->err_x > ref->err_x;
    }
    fit_orders(r);
    work_free(&w);
    return rc;
}

void cl_conv_write_rows(FILE *fp, const cl_conv_result *r, bool header)
{
    if (header)
        fprintf(fp, "integrator,param,value,err_x,err_v,order,fitted,steps,"
                    "rhs_evals,cpu,status\n");
    for (int k = 0; k < r->nlev; k++) {
        const cl_conv_level *l = &r->lev[k];
        fprintf(fp, "%s,%s,%.9g,%.9g,%.9g,%.6g,%d,%ld,%ld,%.6g,%s\n",
                r->type->name, r->fixed ? "dt" : "rtol", l->param, l->err_x,
                l->err_v, l->order, l->fitted, l->stats.steps,
                l->stats.rhs_evals, l->stats.cpu,
                l->rc ? cl_status_name(l->rc) : "ok");
    }
}
