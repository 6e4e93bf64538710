/* The studies that read a sweep job's time series (sweep_table.h): the
 * energy balance and the contact figures of `clothode energy` and
 * `clothode contact --from-sweep`. */
#include "analysis/sweep_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The series.csv of the job of table row `row`, read as a table. */
static cl_status read_series(const cl_sweep_table *t, int row,
                             cl_sweep_table *s, cl_error *err)
{
    char path[4096];
    const char *table = t->paths[t->src[row]], *slash = strrchr(table, '/');
    int dirlen = slash ? (int)(slash - table) : 1;
    snprintf(path, sizeof path, "%.*s/jobs/%s/run/series.csv", dirlen,
             slash ? table : ".", cl_sweep_table_text(t, row, "id"));
    cl_status rc = cl_sweep_table_read(path, s, err);
    if (rc == CL_EIO)
        rc = cl_error_set(err, CL_EIO, "--from-sweep %s: no series %s (the "
                          "jobs are read from jobs/ beside the table: "
                          "collect into the sweep directory)", table, path);
    else if (!rc && s->nrow == 0)
        rc = cl_error_set(err, CL_EPARSE, "%s: no rows", path);
    return rc;
}

/* The one kept job row of `label` at `param` = level. */
static int level_row(const cl_sweep_table *t, const char *label,
                     const char *param, double level, cl_error *err)
{
    cl_sweep_row rows[CL_SWEEP_TABLE_MAX_ROWS];
    int n = cl_sweep_table_rows(t, label, param, rows,
                                CL_SWEEP_TABLE_MAX_ROWS, err), found = -1;
    for (int k = 0; k < n; k++) {
        if (fabs(rows[k].param - level) > 1e-12 * fabs(level))
            continue;
        if (found >= 0)
            return cl_error_set(err, CL_EINVAL, "--from-sweep %s: several "
                                "runs of %s at %s = %g: give the other "
                                "axes' values with --set", t->path, label,
                                param, level), -1;
        found = rows[k].row;
    }
    if (n > 0 && found < 0)
        cl_error_set(err, CL_EINVAL, "--from-sweep %s: no run of %s at %s = "
                     "%g (give the sweep's value with --%s)", t->path, label,
                     param, level, param + 4);
    return found;
}

static cl_status ebal_samples(const cl_sweep_table *s, cl_ebal_result *r,
                              cl_error *err)
{
    const char *need[] = {"t", "kinetic", "potential", "total",
                          "power_diss"};
    for (size_t k = 0; k < sizeof need / sizeof *need; k++)
        if (isnan(cl_sweep_table_value(s, 0, need[k])))
            return cl_error_set(err, CL_EPARSE, "%s: no %s column",
                                s->path, need[k]);
    r->s = malloc((size_t)s->nrow * sizeof *r->s);
    if (!r->s)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    double trapz = 0.0;
    for (int k = 0; k < s->nrow; k++) {
        cl_energy e = {
            .kinetic = cl_sweep_table_value(s, k, "kinetic"),
            .potential = cl_sweep_table_value(s, k, "potential"),
            .total = cl_sweep_table_value(s, k, "total"),
            .power_diss = cl_sweep_table_value(s, k, "power_diss")};
        cl_ebal_add(r, (size_t)s->nrow, &trapz,
                    cl_sweep_table_value(s, k, "t"), &e);
    }
    return CL_OK;
}

cl_status cl_ebal_from_sweep(const cl_sweep_table *t, const char *label,
                             const cl_integrator_type *type,
                             const char *param, double level,
                             cl_ebal_result *r, cl_error *err)
{
    memset(r, 0, sizeof *r);
    r->type = type;
    r->label = label;
    int row = level_row(t, label, param, level, err);
    if (row < 0)
        return err->code;
    cl_sweep_row at = {row, level};
    cl_stab_trial tr;
    if (!cl_sweep_table_trial(t, at, &tr))
        return cl_error_set(err, CL_EINVAL, "--from-sweep %s: the run of %s "
                            "at %s = %g did not start (%s)", t->path, label,
                            param, level,
                            cl_sweep_table_text(t, row, "exit"));
    r->rc = tr.rc;
    r->why = tr.why;
    r->stats = tr.stats;
    cl_sweep_table s;
    cl_status rc = read_series(t, row, &s, err);
    if (!rc)
        rc = ebal_samples(&s, r, err);
    cl_sweep_table_free(&s);
    return rc;
}

/* The figures of one contact row from its run's series. */
static void contact_figures(const cl_sweep_table *s, double t_end,
                            cl_cstudy_row *w)
{
    w->worst_pen = w->worst_t = 0.0;
    w->stretch_max = 0.0;
    for (int k = 0; k < s->nrow; k++) {
        double pen = cl_sweep_table_value(s, k, "max_penetration");
        if (k > 0 && pen > w->worst_pen) { /* after steps, as the hook */
            w->worst_pen = pen;
            w->worst_t = cl_sweep_table_value(s, k, "t");
        }
        w->stretch_max = fmax(w->stretch_max,
                              cl_sweep_table_value(s, k, "max_stretch"));
    }
    int last = s->nrow - 1;
    double reached = cl_sweep_table_value(s, last, "t");
    bool rest = w->run.rc == CL_OK &&
                fabs(reached - t_end) <= 1e-9 * t_end;
    w->rest_pen = rest ? cl_sweep_table_value(s, last, "max_penetration")
                       : NAN;
    w->rest_contacts = rest ? lround(cl_sweep_table_value(s, last,
                                                          "contacts"))
                            : -1;
}

cl_status cl_cstudy_from_sweep(const cl_sweep_table *t, const char *label,
                               const cl_stab_opts *o, cl_cstudy_result *r,
                               cl_error *err)
{
    cl_sweep_row rows[CL_CSTUDY_MAX_DT];
    memset(r, 0, sizeof *r);
    r->label = label;
    r->response = "";
    int n = cl_sweep_table_rows(t, label, "run.dt", rows, CL_CSTUDY_MAX_DT,
                                err);
    cl_status rc = n < 0 ? err->code : CL_OK;
    for (int k = n - 1; !rc && k >= 0; k--) { /* smallest dt first */
        cl_cstudy_row *w = &r->row[r->n];
        cl_sweep_table s;
        if (!cl_sweep_table_trial(t, rows[k], &w->run))
            continue; /* never ran, or refused its input */
        w->run.nsteps = lround(o->t_end / w->run.dt); /* as planned */
        if (!(rc = read_series(t, rows[k].row, &s, err))) {
            contact_figures(&s, o->t_end, w);
            r->n++;
        }
        cl_sweep_table_free(&s);
    }
    cl_cstudy_bracket(r);
    return rc;
}
