/* Contact at a list of steps (see contact_study.h). */
#include "analysis/contact_study.h"

#include <math.h>
#include <string.h>

#include "io/csv.h"

cl_status cl_cstudy_check(cl_model *m, const cl_integrator_type *type,
                          const cl_stab_opts *o, const double *dt, int ndt,
                          cl_error *err)
{
    if (!type->fixed_step)
        return cl_error_set(err, CL_EINVAL, "%s chooses its own steps by "
                            "error control: the contact study takes "
                            "fixed-step integrators", type->name);
    if (!cl_model_contact(m))
        return cl_error_set(err, CL_EINVAL, "the problem has no obstacle "
                            "([obstacle.NAME] sections): nothing to study");
    if (ndt < 1 || ndt > CL_CSTUDY_MAX_DT)
        return cl_error_set(err, CL_EINVAL, "%d steps: expected 1 to %d",
                            ndt, CL_CSTUDY_MAX_DT);
    if (!(o->t_end > 0 && isfinite(o->t_end)) || o->checks < 1)
        return cl_error_set(err, CL_EINVAL, "t_end = %g, checks = %ld: "
                            "expected t_end > 0 and checks >= 1", o->t_end,
                            o->checks);
    cl_status rc = CL_OK;
    for (int k = 0; !rc && k < ndt; k++)
        rc = cl_trial_whole_steps(type, dt[k], o->t_end, err);
    return rc ? rc : cl_trial_repeatable(m, err);
}

/* The contact figures of the run that just ended on t into row. */
static void measure(cl_trial *t, const cl_stab_opts *o, cl_cstudy_row *row)
{
    cl_contact_figures cf;
    row->stretch_max = t->stretch_seen;
    row->rest_pen = NAN;
    row->rest_contacts = -1;
    if (row->run.rc == CL_OK &&
        cl_model_contact_figures(t->m, o->t_end, t->x, t->v, &cf) == CL_OK) {
        row->rest_pen = cf.max_penetration;
        row->rest_contacts = (long)cf.contacts;
    }
    /* after the figures, which count the end state too */
    cl_model_contact_worst(t->m, &row->worst_pen, &row->worst_t);
}

void cl_cstudy_bracket(cl_cstudy_result *r)
{
    r->dt_unstable = r->dt_stable = NAN;
    for (int k = 0; k < r->n; k++)
        if (r->row[k].run.rc != CL_OK && !(r->row[k].run.dt >= r->dt_unstable))
            r->dt_unstable = r->row[k].run.dt;
    for (int k = 0; k < r->n; k++) {
        double dt = r->row[k].run.dt;
        if (r->row[k].run.rc == CL_OK && !(dt >= r->dt_unstable) &&
            !(dt <= r->dt_stable))
            r->dt_stable = dt;
    }
}

cl_status cl_cstudy_run(cl_model *m, const cl_integrator_type *type,
                        const cl_integrator_opts *io, const cl_stab_opts *o,
                        const double *dt, int ndt, cl_cstudy_result *r,
                        cl_error *err)
{
    cl_trial t = {0};
    memset(r, 0, sizeof *r);
    r->label = r->response = "";
    cl_status rc = cl_cstudy_check(m, type, o, dt, ndt, err);
    if (rc || (rc = cl_trial_init(&t, m, err))) {
        cl_trial_free(&t);
        return rc;
    }
    for (int k = 0; k < ndt; k++) {
        cl_cstudy_row *row = &r->row[k];
        long nsteps = lround(o->t_end / dt[k]);
        if (cl_stab_try(&t, type, io, o, nsteps, &row->run, err) < 0) {
            rc = err->code;
            break;
        }
        measure(&t, o, row);
        r->n = k + 1;
    }
    cl_trial_free(&t);
    cl_cstudy_bracket(r);
    return rc;
}

void cl_cstudy_write_rows(FILE *fp, const cl_cstudy_result *r, bool header)
{
    if (header)
        fputs("integrator,response,dt,steps,stable,status,"
              "worst_penetration,worst_t,rest_penetration,rest_contacts,"
              "max_stretch,newton_iters,cpu,reason\n", fp);
    for (int k = 0; k < r->n; k++) {
        const cl_cstudy_row *w = &r->row[k];
        const cl_stab_trial *t = &w->run;
        fprintf(fp, "%s,%s,%.9g,%ld,%d,%s,%.6g,%.6g,%.6g,%ld,%.6g,%ld,%.6g,",
                r->label, r->response, t->dt, t->nsteps, t->rc == CL_OK,
                t->rc ? cl_status_name(t->rc) : "ok", w->worst_pen,
                w->worst_t, w->rest_pen, w->rest_contacts, w->stretch_max,
                t->stats.nonlin_iters, t->stats.cpu);
        cl_csv_quoted(fp, t->rc ? t->why.msg : "");
        fputc('\n', fp);
    }
}
