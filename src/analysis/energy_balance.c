/* Energy balance of one run (see energy_balance.h). */
#include "analysis/energy_balance.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/trial.h"

typedef struct {
    cl_model *m;
    cl_ebal_result *r;
    size_t cap;
    double trapz;   /* int P dt so far, by the trapezoidal rule */
} ebal_ctx;

cl_status cl_ebal_add(cl_ebal_result *r, size_t cap, double *trapz,
                      double t, const cl_energy *e)
{
    if (r->n == cap)
        return CL_EINVAL;
    cl_ebal_sample *s = &r->s[r->n], *p = r->n ? s - 1 : NULL;
    s->t = t;
    s->kinetic = e->kinetic;
    s->potential = e->potential;
    s->total = e->total;
    s->power = e->power_diss;
    if (p)
        *trapz += 0.5 * (t - p->t) * (p->power + s->power);
    s->dissipated = *trapz + e->contact_work;
    s->balance = p ? s->total - r->s[0].total - s->dissipated : 0.0;
    r->scale = fmax(r->scale, fmax(s->kinetic, fabs(s->dissipated)));
    r->scale = fmax(r->scale, fabs(s->potential - r->s[0].potential));
    r->balance_max = fmax(r->balance_max, fabs(s->balance));
    r->n++;
    return CL_OK;
}

/* One sample: energies at (t, x, v). */
static cl_status sample(void *vctx, double t, const double *x,
                        const double *v, cl_error *err)
{
    ebal_ctx *c = vctx;
    const cl_system *sys = cl_model_system(c->m);
    cl_energy e;
    cl_status rc = sys->energy(sys->data, t, x, v, &e);
    if (rc)
        return cl_error_set(err, rc, "energy at t = %g failed", t);
    if (cl_ebal_add(c->r, c->cap, &c->trapz, t, &e))
        return cl_error_set(err, CL_EINVAL, "more samples than planned");
    return CL_OK;
}

cl_status cl_ebal_check(cl_model *m, const cl_integrator_type *type,
                        const cl_integrator_opts *io, double T, long samples,
                        cl_error *err)
{
    if (samples < 1 || !(T > 0))
        return cl_error_set(err, CL_EINVAL, "samples = %ld, T = %g: expected "
                            ">= 1 and > 0", samples, T);
    cl_status rc = cl_trial_whole_steps(type, io->dt, T, err);
    if (!rc && !type->fixed_step && cl_model_system(m)->projects)
        return cl_error_set(err, CL_EUNSUPPORTED, "%s: the energy balance "
                            "cannot separate the work of contact "
                            "projections made inside an adaptive method's "
                            "steps; use a fixed-step method or penalty "
                            "contact", type->name);
    return rc ? rc : cl_trial_repeatable(m, err);
}

cl_status cl_ebal_run(cl_model *m, const cl_integrator_type *type,
                      const cl_integrator_opts *io, double T, long samples,
                      double max_stretch, cl_ebal_result *r, cl_error *err)
{
    cl_trial t = {0};
    memset(r, 0, sizeof *r);
    r->type = type;
    r->label = type->name;
    cl_status rc = cl_ebal_check(m, type, io, T, samples, err);
    if (rc)
        return rc;
    /* a fixed-step method is sampled at most at every one of its steps */
    double steps = cl_integrator_fixed(type, io->dt) ? round(T / io->dt)
                                                     : INFINITY;
    long taken = (double)samples < steps ? samples : (long)steps;
    ebal_ctx c = {m, r, (size_t)taken + 1, 0.0};
    r->s = malloc(c.cap * sizeof *r->s);
    if (!r->s)
        return cl_error_set(err, CL_ENOMEM, "out of memory (%ld samples)",
                            taken);
    if (!(rc = cl_trial_init(&t, m, err))) {
        t.hook = sample;
        t.hook_ctx = &c;
        t.contact_work = true;
        r->rc = cl_trial_run(&t, type, io, T, samples, max_stretch,
                             &r->stats, &r->why);
        if (r->rc == CL_EINTR) /* a stopped study keeps no part-row */
            rc = cl_error_set(err, CL_EINTR, "%s", r->why.msg);
    }
    cl_trial_free(&t);
    return rc;
}

void cl_ebal_free(cl_ebal_result *r)
{
    free(r->s);
    memset(r, 0, sizeof *r);
}

void cl_ebal_write_rows(FILE *fp, const cl_ebal_result *r, bool header)
{
    if (header)
        fprintf(fp, "integrator,t,kinetic,potential,total,dissipated,"
                    "balance\n");
    for (size_t k = 0; k < r->n; k++) {
        const cl_ebal_sample *s = &r->s[k];
        fprintf(fp, "%s,%.9g,%.12g,%.12g,%.12g,%.12g,%.12g\n", r->label,
                s->t, s->kinetic, s->potential, s->total, s->dissipated,
                s->balance);
    }
}
