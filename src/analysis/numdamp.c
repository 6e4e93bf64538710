/* The numerical damping study (analysis/numdamp.h). */
#include "analysis/numdamp.h"

#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_fit.h>

#include "analysis/spectrum.h"
#include "analysis/trial.h"

/* E_k / E_0 below it is left out: an amplitude below 1e-8 of the start,
 * where the Newton tolerance (1e-10 of v_ref >= 1 m/s, kinsol_common.h)
 * and the round-off of x (1e-16 of a rest length) decide the energy. */
#define CL_NUMDAMP_FLOOR 1e-16

bool cl_numdamp_selects(const cl_integrator_type *type)
{
    return type->fixed_step && type->region &&
           type->region->kind == CL_REGION_SECTOR;
}

cl_status cl_numdamp_undamped(cl_model *m, cl_error *err)
{
    if (cl_model_contact(m))
        return cl_error_set(err, CL_EUNSUPPORTED, "damping: the problem has "
                            "obstacles, whose contact is not a linear "
                            "oscillator's force, so the theory would not "
                            "apply; the study is meant for spring2 or a "
                            "cloth without obstacles");
    /* the power of the forces at the initial positions moving with v = x,
     * a velocity under which every pair's length changes (a term without
     * force, such as pbd, dissipates nothing) */
    const cl_system *sys = cl_model_system(m);
    double *x = malloc(2 * sys->n * sizeof *x);
    cl_energy e = {0};
    cl_status rc = x ? cl_model_initial_state(m, x, x + sys->n)
                     : cl_error_set(err, CL_ENOMEM, "damping: out of memory");
    if (!rc && (rc = sys->energy(sys->data, cl_model_start_time(m), x, x,
                                 &e)))
        cl_error_set(err, rc, "damping: the energy at the initial state "
                     "failed");
    free(x);
    if (!rc && e.power_diss != 0.0)
        rc = cl_error_set(err, CL_EUNSUPPORTED, "damping: the problem has "
                          "damping forces (power %.3g W at a test "
                          "velocity), which the theory of an undamped "
                          "oscillator leaves out; set their coefficients to "
                          "0 (--set damping.kd=0, spring-damping.kd=0, ...)",
                          e.power_diss);
    return rc;
}

cl_status cl_numdamp_frequency(cl_model *m, double *w, cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    double *x = malloc(sys->n * sizeof *x), *v = malloc(sys->n * sizeof *v);
    cl_spectrum sp = {0};
    cl_status rc = cl_trial_repeatable(m, err);
    if (!rc)
        rc = cl_numdamp_undamped(m, err);
    if (!rc && !(x && v))
        rc = cl_error_set(err, CL_ENOMEM, "damping: out of memory");
    if (!rc && !(rc = cl_model_initial_state(m, x, v)))
        rc = cl_spectrum_compute(m, cl_model_start_time(m), x, v, &sp, err);
    *w = rc ? NAN : sp.w_max;
    if (!rc && !(*w > 0 && isfinite(*w)))
        rc = cl_error_set(err, CL_EINVAL, "damping: the problem has no "
                          "oscillating mode at its initial state (w_max = "
                          "%g)", *w);
    cl_spectrum_free(&sp);
    free(x);
    free(v);
    return rc;
}

/* The energies E_k of one run, gathered by the trial's hook. */
typedef struct {
    const cl_system *sys;
    double *e;
    long k;
} nd_log;

static cl_status nd_hook(void *ctx, double t, const double *x,
                         const double *v, cl_error *err)
{
    nd_log *l = ctx;
    cl_energy en;
    cl_status rc = l->sys->energy(l->sys->data, t, x, v, &en);
    if (rc)
        return cl_error_set(err, rc, "damping: energy at t = %g failed", t);
    l->e[l->k++] = en.total;
    return CL_OK;
}

/* exp(s/2), s the least-squares slope of ln e_k against k over the
 * energies e[first .. first + count - 1] (count >= 2; k, le: scratch). */
static double nd_ratio(const double *e, long first, long count, double *k,
                       double *le)
{
    double c0, s = NAN, c00, c01, c11, ss;
    for (long i = 0; i < count; i++) {
        k[i] = (double)(first + i);
        le[i] = log(e[first + i]);
    }
    gsl_fit_linear(k, 1, le, 1, (size_t)count, &c0, &s, &c00, &c01, &c11,
                   &ss);
    return exp(0.5 * s);
}

/* r from the energies e[0..steps] (numdamp.h) into p: the ratio, the
 * points fitted and the spread of the ratios of the fit's two halves. */
static void nd_fit(const double *e, long steps, cl_numdamp_point *p)
{
    long last = 0;
    while (last < steps && e[last + 1] > CL_NUMDAMP_FLOOR * e[0])
        last++;
    long first = last >= 4 ? last / 4 : 0, n = last - first + 1;
    p->fitted = n;
    if (n < 2) {
        p->measured = 0.0; /* gone below the floor in one step */
        return;
    }
    double *k = malloc((size_t)n * sizeof *k);
    double *le = malloc((size_t)n * sizeof *le);
    if (k && le) {
        p->measured = nd_ratio(e, first, n, k, le);
        if (n >= 4)
            p->spread = fabs(nd_ratio(e, first + n - n / 2, n / 2, k, le) -
                             nd_ratio(e, first, n / 2, k, le)) /
                        p->measured;
    }
    free(k);
    free(le);
}

static void nd_point(cl_trial *t, nd_log *l, const cl_integrator_type *type,
                     const cl_integrator_opts *io, double w, double wh,
                     long steps, cl_numdamp_point *p)
{
    cl_integrator_opts o = *io;
    cl_stats st;
    *p = (cl_numdamp_point){.wh = wh, .h = wh / w, .measured = NAN,
                            .loss_period = NAN, .spread = NAN};
    p->theory = type->region->amplification
                    ? type->region->amplification(wh, io->rho_inf) : NAN;
    o.dt = p->h;
    l->k = 0;
    p->rc = cl_trial_run(t, type, &o, (double)steps * p->h, steps, INFINITY,
                         &st, &p->why);
    if (p->rc || l->k != steps + 1 || !(l->e[0] > 0))
        return;
    nd_fit(l->e, steps, p);
    p->loss_period = 1.0 - pow(p->measured, 2.0 * M_PI / wh);
}

cl_status cl_numdamp_run(cl_model *m, const cl_integrator_type *type,
                         const cl_integrator_opts *io, double w,
                         const double *wh, int n, long steps,
                         cl_numdamp_result *r, cl_error *err)
{
    *r = (cl_numdamp_result){.type = type, .label = type->name, .w = w};
    if (n < 1 || n > CL_NUMDAMP_MAX_WH || steps < 4 || !(w > 0))
        return cl_error_set(err, CL_EINVAL, "damping: %d values of w h "
                            "(1 to %d), %ld steps (>= 4), w = %g (> 0)", n,
                            CL_NUMDAMP_MAX_WH, steps, w);
    if (!type->fixed_step)
        return cl_error_set(err, CL_EINVAL, "damping: %s chooses its own "
                            "steps; the study takes fixed-step integrators",
                            type->name);
    nd_log l = {.sys = cl_model_system(m),
                .e = malloc((size_t)(steps + 1) * sizeof(double))};
    cl_trial t = {0};
    cl_status rc = l.e ? cl_trial_init(&t, m, err)
                       : cl_error_set(err, CL_ENOMEM, "damping: out of "
                                      "memory");
    t.hook = nd_hook;
    t.hook_ctx = &l;
    for (int i = 0; !rc && i < n; i++, r->n++)
        nd_point(&t, &l, type, io, w, wh[i], steps, &r->p[i]);
    cl_trial_free(&t);
    free(l.e);
    return rc;
}

void cl_numdamp_write_rows(FILE *fp, const cl_numdamp_result *r,
                           bool header)
{
    if (header)
        fprintf(fp, "integrator,wh,h,measured,theory,loss_period,fitted,"
                    "spread,status\n");
    for (int i = 0; i < r->n; i++) {
        const cl_numdamp_point *p = &r->p[i];
        fprintf(fp, "%s,%.9g,%.9g,%.9g,%.9g,%.9g,%ld,%.3g,%s\n", r->label,
                p->wh, p->h, p->measured, p->theory, p->loss_period,
                p->fitted, p->spread, p->rc ? cl_status_name(p->rc) : "ok");
    }
}
