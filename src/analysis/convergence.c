/* Convergence study: levels of one integrator against a tight reference
 * (see convergence.h for the definitions). */
#include "analysis/convergence.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_fit.h>

#include "analysis/diagnostics.h"
#include "analysis/trial.h"

/* x to 15 significant digits: the double of the decimal a table prints
 * for it, so that a level's tolerance is the one printed (1e-4 x 10^-2
 * is 1.0000000000000002e-06 in floating point, and CVODE's steps and
 * error at that tolerance differ from those at 1e-06 by up to 2x on hang)
 * and `run` with the printed value reproduces the level. */
static double decimal(double x)
{
    char text[32];
    snprintf(text, sizeof text, "%.15g", x);
    return strtod(text, NULL);
}

/* The reference run at rtol; its final state is in t->x, t->v. */
static cl_status reference_run(cl_trial *t, const cl_conv_opts *o,
                               double rtol, cl_stats *s, cl_error *err)
{
    const cl_integrator_type *type = cl_integrator_find("cvode-bdf");
    cl_integrator_opts io = {.rtol = rtol, .atol = decimal(rtol / 100),
                             .linsol = o->ref_linsol};
    cl_error why = {0};
    cl_status rc = cl_trial_run(t, type, &io, o->t_end, 1, o->max_stretch,
                                s, &why);
    if (rc)
        cl_error_set(err, rc, "reference (cvode-bdf, rtol %g) failed: %s",
                     rtol, why.msg);
    return rc;
}

cl_status cl_conv_reference(cl_model *m, const cl_conv_opts *o,
                            cl_conv_ref *ref, cl_error *err)
{
    size_t n = cl_model_system(m)->n;
    cl_trial t = {0};
    cl_stats loose;
    memset(ref, 0, sizeof *ref);
    cl_status rc = cl_trial_repeatable(m, err);
    if (rc)
        return rc;
    if (!(o->ref_rtol >= 1e-15 && o->ref_rtol <= 1e-4))
        return cl_error_set(err, CL_EINVAL, "reference rtol = %g: expected "
                            "1e-15 .. 1e-4", o->ref_rtol);
    ref->n = n;
    ref->x = malloc(n * sizeof *ref->x);
    ref->v = malloc(n * sizeof *ref->v);
    rc = ref->x && ref->v ? cl_trial_init(&t, m, err)
                          : cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!rc && !(rc = reference_run(&t, o, o->ref_rtol, &ref->stats, err))) {
        memcpy(ref->x, t.x, n * sizeof *ref->x);
        memcpy(ref->v, t.v, n * sizeof *ref->v);
        if (!(rc = reference_run(&t, o, decimal(10 * o->ref_rtol), &loose,
                                 err))) {
            ref->err_x = cl_max_distance(t.x, ref->x, n / 3);
            ref->err_v = cl_max_distance(t.v, ref->v, n / 3);
        }
    }
    cl_trial_free(&t);
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
    if (cl_integrator_fixed(type, io->dt)) {
        o.dt = ldexp(io->dt, -k);
        *param = o.dt;
    } else {
        double s = pow(10.0, -k);
        o.rtol = decimal(io->rtol * s);
        o.atol = decimal(io->atol * s);
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
    if (!cl_integrator_fixed(type, io->dt) &&
        io->rtol * pow(10.0, 1 - levels) < 1e-15)
        return cl_error_set(err, CL_EINVAL, "rtol = %g over %d levels goes "
                            "down to %g: below 1e-15", io->rtol, levels,
                            io->rtol * pow(10.0, 1 - levels));
    return cl_trial_whole_steps(type, io->dt, o->t_end, err);
}

/* The least-squares slope of ly against lp over n points; NaN for fewer
 * than 2, or a fit GSL refuses (e.g. all levels at one parameter). */
static double fit_slope(const double *lp, const double *ly, int n)
{
    double c0, c1, cov00, cov01, cov11, sumsq;
    if (n < 2 || gsl_fit_linear(lp, 1, ly, 1, (size_t)n, &c0, &c1, &cov00,
                                &cov01, &cov11, &sumsq))
        return NAN;
    return c1;
}

void cl_conv_fit(cl_conv_result *r)
{
    double step = r->fixed ? 2.0 : 10.0, q = log(step);
    double lp[CL_CONV_MAX_LEVELS], lx[CL_CONV_MAX_LEVELS],
        lpv[CL_CONV_MAX_LEVELS], lv[CL_CONV_MAX_LEVELS];
    r->nfit = r->nfit_v = 0;
    for (int k = 0; k < r->nlev; k++) {
        cl_conv_level *l = &r->lev[k], *prev = k ? &r->lev[k - 1] : NULL;
        /* levels of a sweep need not be a factor 2 (10) apart */
        double ratio = prev ? prev->param / l->param : step;
        double qk = fabs(ratio - step) <= 1e-9 * step ? q : log(ratio);
        l->order = prev && !prev->rc && !l->rc && prev->err_x > 0 &&
                           l->err_x > 0
                       ? log(prev->err_x / l->err_x) / qk
                       : NAN;
        if (l->fitted) {
            lp[r->nfit] = log(l->param);
            lx[r->nfit++] = log(l->err_x);
        }
        if (l->fitted_v) {
            lpv[r->nfit_v] = log(l->param);
            lv[r->nfit_v++] = log(l->err_v);
        }
    }
    r->slope_x = fit_slope(lp, lx, r->nfit);
    r->slope_v = fit_slope(lpv, lv, r->nfit_v);
}

cl_status cl_convergence(cl_model *m, const cl_integrator_type *type,
                         const cl_integrator_opts *io, int levels,
                         const cl_conv_opts *o, const cl_conv_ref *ref,
                         cl_conv_result *r, cl_error *err)
{
    size_t n = ref->n;
    cl_trial t = {0};
    memset(r, 0, sizeof *r);
    r->type = type;
    r->label = type->name;
    r->fixed = cl_integrator_fixed(type, io->dt);
    cl_status rc = cl_conv_check(type, io, levels, o, err);
    if (!rc)
        rc = cl_trial_init(&t, m, err);
    for (int k = 0; !rc && k < levels; k++, r->nlev++) {
        cl_conv_level *l = &r->lev[k];
        cl_integrator_opts lo = level_opts(type, io, k, &l->param);
        l->rc = cl_trial_run(&t, type, &lo, o->t_end, 1, o->max_stretch,
                             &l->stats, &l->why);
        l->err_x = l->rc ? NAN : cl_max_distance(t.x, ref->x, n / 3);
        l->err_v = l->rc ? NAN : cl_max_distance(t.v, ref->v, n / 3);
        l->fitted = !l->rc && l->err_x > CL_CONV_FLOOR_MARGIN * ref->err_x;
        l->fitted_v = l->fitted &&
                      l->err_v > CL_CONV_FLOOR_MARGIN * ref->err_v;
        if (l->rc == CL_EINTR) /* a stopped study keeps no part-row */
            rc = cl_error_set(err, CL_EINTR, "%s", l->why.msg);
    }
    cl_conv_fit(r);
    cl_trial_free(&t);
    return rc;
}

double cl_conv_cheapest(const cl_conv_result *r, double target)
{
    double cpu = NAN;
    for (int k = 0; k < r->nlev; k++)
        if (!r->lev[k].rc && r->lev[k].err_x <= target &&
            !(r->lev[k].stats.cpu >= cpu))
            cpu = r->lev[k].stats.cpu;
    return cpu;
}

void cl_conv_write_rows(FILE *fp, const cl_conv_result *r, bool header)
{
    if (header)
        fprintf(fp, "integrator,param,value,err_x,err_v,order,fitted,"
                    "fitted_v,steps,rhs_evals,cpu,fit_x,fit_v,status\n");
    for (int k = 0; k < r->nlev; k++) {
        const cl_conv_level *l = &r->lev[k];
        fprintf(fp, "%s,%s,%.9g,%.9g,%.9g,%.6g,%d,%d,%ld,%ld,%.6g,%.6g,"
                "%.6g,%s\n", r->label, r->fixed ? "dt" : "rtol", l->param,
                l->err_x, l->err_v, l->order, l->fitted, l->fitted_v,
                l->stats.steps,
                l->stats.rhs_evals, l->stats.cpu, r->slope_x, r->slope_v,
                l->rc ? cl_status_name(l->rc) : "ok");
    }
}
