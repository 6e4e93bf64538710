/* The next stage of a sweep over dt (sweep_table.h, `clothode sweep
 * refine`): within each bracket of the collected stages, points evenly
 * spread in log, so that a grid's answer narrows to a bisection's. */
#include "analysis/sweep_table.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/input.h"

static int axis_of(const cl_sweep *sw, const char *key)
{
    for (int a = 0; a < sw->naxis; a++)
        if (!strcmp(sw->axis[a].key, key))
            return a;
    return -1;
}

/* Whether table row r is a job of j's line: a run of sw's problem
 * (ours[r]), its integrator and every axis but dt (NA where j has no
 * value). */
static bool same_line(const cl_sweep_table *t, const bool *ours, int r,
                      const cl_sweep *sw, const cl_sweep_job *j, int adt)
{
    if (!ours[r] || strcmp(cl_sweep_table_text(t, r, "role"), "job") ||
        strcmp(cl_sweep_table_text(t, r, "integrator"), j->integrator))
        return false;
    for (int a = 0; a < sw->naxis; a++)
        if (a != adt &&
            !cl_sweep_same_value(cl_sweep_table_text(t, r, sw->axis[a].key),
                                 j->value[a] ? j->value[a] : "NA"))
            return false;
    return true;
}

/* The bracket of j's line over every stage's rows: the smallest unstable
 * dt and the largest stable one below it (NaN: none). */
static void line_bracket(const cl_sweep_table *t, const bool *ours,
                         const cl_sweep *sw, const cl_sweep_job *j, int adt,
                         double *lo, double *hi)
{
    cl_stab_trial tr;
    *lo = *hi = NAN;
    for (int r = 0; r < t->nrow; r++) {
        cl_sweep_row row = {r, cl_sweep_table_value(t, r, "run.dt")};
        if (same_line(t, ours, r, sw, j, adt) && cl_sweep_table_trial(t, row, &tr)
            && tr.rc && !(tr.dt >= *hi))
            *hi = tr.dt;
    }
    for (int r = 0; r < t->nrow; r++) {
        cl_sweep_row row = {r, cl_sweep_table_value(t, r, "run.dt")};
        if (same_line(t, ours, r, sw, j, adt) && cl_sweep_table_trial(t, row, &tr)
            && !tr.rc && !(tr.dt >= *hi) && !(tr.dt <= *lo))
            *lo = tr.dt;
    }
}

/* Whether an earlier job of sw is on job k's line. */
static bool line_seen(const cl_sweep *sw, int k, int adt)
{
    for (int i = 0; i < k; i++) {
        const cl_sweep_job *a = &sw->job[i], *b = &sw->job[k];
        bool same = !a->reference && !strcmp(a->integrator, b->integrator);
        for (int x = 0; same && x < sw->naxis; x++)
            same = x == adt || (a->value[x] && b->value[x]
                                    ? !strcmp(a->value[x], b->value[x])
                                    : a->value[x] == b->value[x]);
        if (same)
            return true;
    }
    return false;
}

/* The points of one bracket (lo, hi) as jobs of next: k points
 * lo (hi/lo)^(i/(k+1)), each made T/N with the line's T when it has one
 * (a whole number of steps, as the plan makes them). */
static cl_status refine_line(cl_sweep *next, const cl_sweep *sw,
                             const cl_sweep_job *j, int adt, double lo,
                             double hi, int k, int *added, cl_error *err)
{
    int at = axis_of(sw, "run.t_end");
    double T = at >= 0 && j->value[at] ? strtod(j->value[at], NULL) : NAN;
    const char *value[CL_SWEEP_MAX_AXES + 1];
    char dt[32];
    double last = lo;
    memcpy(value, j->value, (size_t)sw->naxis * sizeof *value);
    for (int i = 1; i <= k; i++) {
        double h = lo * pow(hi / lo, (double)i / (k + 1));
        if (T > 0)
            h = T / nearbyint(T / h);
        if (!(h > last * (1 + 1e-12) && h < hi * (1 - 1e-12)))
            continue; /* a step already there, at T/N */
        last = h;
        cl_sweep_exact(h, dt, sizeof dt);
        value[adt] = dt;
        cl_status rc = cl_sweep_add_job(next, j->integrator, value, err);
        if (rc)
            return rc;
        ++*added;
    }
    return CL_OK;
}

/* The jobs of next: sw's axes, then the points of every line whose
 * bracket is wider than 1 + rel. */
static cl_status refine_stages(const cl_sweep *sw, const cl_sweep_table *t,
                               const bool *ours, int adt, int points,
                               double rel, cl_sweep *next, int *brackets,
                               cl_error *err)
{
    for (int a = 0; a < sw->naxis; a++) { /* the same columns */
        next->axis[a] = (cl_sweep_axis){.key = strdup(sw->axis[a].key),
                                        .from = -1};
        if (!next->axis[a].key)
            return cl_error_set(err, CL_ENOMEM, "out of memory");
        next->naxis = a + 1;
    }
    cl_status rc = CL_OK;
    for (int k = 0; !rc && k < sw->njob; k++) {
        const cl_sweep_job *j = &sw->job[k];
        double lo, hi;
        int added = 0;
        if (j->reference || !j->value[adt] || line_seen(sw, k, adt))
            continue;
        line_bracket(t, ours, sw, j, adt, &lo, &hi);
        if (!(hi > lo * (1 + rel)))
            continue; /* no bracket, or narrow enough */
        rc = refine_line(next, sw, j, adt, lo, hi, points, &added, err);
        *brackets += added > 0;
    }
    return rc;
}

/* Whether each row of t is a run of sw's problem (every row of a table
 * without a problem column), into ours; rows naming one file are
 * compared once. */
static void rows_of_problem(const cl_sweep_table *t, const cl_sweep *sw,
                            bool *ours)
{
    bool has = cl_sweep_table_has(t, "problem"), same = true;
    const char *last = NULL;
    for (int r = 0; r < t->nrow; r++) {
        const char *p = cl_sweep_table_text(t, r, "problem");
        if (has && (!last || strcmp(p, last)))
            same = cl_same_input(p, sw->problem);
        last = p;
        ours[r] = same;
    }
}

/* CL_EINVAL unless t has sw's axes as columns and a job row on one of
 * sw's lines: a table of another sweep would plan nothing. */
static cl_status table_of_sweep(const cl_sweep *sw, const cl_sweep_table *t,
                                const bool *ours, int adt, cl_error *err)
{
    for (int a = 0; a < sw->naxis; a++)
        if (!cl_sweep_table_has(t, sw->axis[a].key))
            return cl_error_set(err, CL_EINVAL, "sweep refine: %s has no "
                                "column %s, an axis of the sweep in %s: "
                                "give the tables of this sweep's stages",
                                t->path, sw->axis[a].key, sw->dir);
    for (int k = 0; k < sw->njob; k++)
        for (int r = 0; !sw->job[k].reference && r < t->nrow; r++)
            if (same_line(t, ours, r, sw, &sw->job[k], adt))
                return CL_OK;
    return cl_error_set(err, CL_EINVAL, "sweep refine: no run of %s is "
                        "one of the sweep in %s (its problem %s, its "
                        "integrators and the values of its axes): give "
                        "the tables of this sweep's stages", t->path,
                        sw->dir, sw->problem);
}

cl_status cl_sweep_refine(const cl_sweep *sw, const cl_sweep_table *t,
                          int points, double rel, cl_sweep *next,
                          int *brackets, cl_error *err)
{
    int adt = axis_of(sw, "run.dt");
    *brackets = 0;
    if (adt < 0)
        return cl_error_set(err, CL_EINVAL, "sweep refine: the sweep in %s "
                            "has no dt axis", sw->dir);
    bool *ours = calloc((size_t)t->nrow + 1, sizeof *ours);
    if (!ours)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    rows_of_problem(t, sw, ours);
    cl_status rc = table_of_sweep(sw, t, ours, adt, err);
    if (!rc)
        rc = refine_stages(sw, t, ours, adt, points, rel, next, brackets,
                           err);
    free(ours);
    return rc;
}
