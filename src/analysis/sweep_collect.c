/* A sweep's collected table (analysis/sweep.h): every job's outcome, one
 * row each, the missing and failed ones included. */
#include "analysis/sweep.h"

#include <math.h>
#include <string.h>

void cl_sweep_outcomes(const cl_sweep *sw, cl_sweep_outcome *out,
                       cl_sweep_counts *c)
{
    *c = (cl_sweep_counts){0};
    for (int k = 0; k < sw->njob; k++) {
        cl_sweep_outcome_read(sw, k, &out[k]);
        c->complete += out[k].state == CL_SWEEP_COMPLETE;
        c->failed += out[k].state == CL_SWEEP_FAILED;
        c->missing += out[k].state == CL_SWEEP_MISSING;
    }
    for (int k = 0; k < sw->njob; k++) {
        int r = sw->job[k].ref;
        if (r >= 0 && out[r].state == CL_SWEEP_COMPLETE)
            cl_sweep_outcome_error(sw, k, &out[k]);
    }
}

static void number(FILE *fp, double v)
{
    if (isnan(v))
        fprintf(fp, ",NA");
    else
        fprintf(fp, ",%.10g", v);
}

static const char *state_name(cl_sweep_state s)
{
    return s == CL_SWEEP_COMPLETE ? "complete"
           : s == CL_SWEEP_FAILED ? "failed"
                                  : "missing";
}

/* A value as a CSV field: quoted when it holds a comma or a quote. */
static void field(FILE *fp, const char *v)
{
    if (!v) {
        fprintf(fp, ",NA");
        return;
    }
    if (!strpbrk(v, ",\"\n")) {
        fprintf(fp, ",%s", v);
        return;
    }
    fprintf(fp, ",\"");
    for (; *v; v++)
        fprintf(fp, *v == '"' ? "\"\"" : "%c", *v);
    fputc('"', fp);
}

void cl_sweep_write_table(FILE *fp, const cl_sweep *sw,
                          const cl_sweep_outcome *out)
{
    fprintf(fp, "id,role,integrator");
    for (int a = 0; a < sw->naxis; a++)
        fprintf(fp, ",%s", sw->axis[a].key);
    fprintf(fp, ",status,exit,t_reached");
    for (int s = 0; s < CL_SWEEP_NSTAT; s++)
        fprintf(fp, ",%s", cl_sweep_stat_names[s]);
    fprintf(fp, ",err_x,err_v,message,problem,problem_sha256,"
                "inputs_sha256\n");
    for (int k = 0; k < sw->njob; k++) {
        const cl_sweep_job *j = &sw->job[k];
        const cl_sweep_outcome *o = &out[k];
        fprintf(fp, "%s,%s", j->id, j->reference ? "reference" : "job");
        field(fp, j->integrator);
        for (int a = 0; a < sw->naxis; a++)
            field(fp, j->value[a]);
        fprintf(fp, ",%s,%s", state_name(o->state), o->exit_class);
        number(fp, o->t_reached);
        for (int s = 0; s < CL_SWEEP_NSTAT; s++)
            number(fp, o->stat[s]);
        number(fp, o->err_x);
        number(fp, o->err_v);
        field(fp, o->message);
        /* the studies' --from-sweep check these */
        field(fp, sw->problem);
        field(fp, o->problem_sha256[0] ? o->problem_sha256 : "NA");
        field(fp, o->inputs_sha256[0] ? o->inputs_sha256 : "NA");
        fputc('\n', fp);
    }
}
