/* A collected sweep table (`clothode sweep collect`, analysis/sweep.h) read
 * back as the runs of a study: `stability`, `convergence` and
 * `workprecision --from-sweep TABLE` take their runs from it instead of
 * making them, so that a sweep run on a cluster feeds the same tables and
 * figures as a local study. */
#ifndef CL_SWEEP_TABLE_H
#define CL_SWEEP_TABLE_H

#include <stdbool.h>

#include "analysis/convergence.h"
#include "analysis/stability.h"
#include "core/error.h"
#include "io/config.h"

typedef struct {
    char *path;
    int ncol, nrow;
    char **head;  /* column names */
    char **cell;  /* nrow x ncol fields, row-major */
    int ncell;    /* fields read (ncell >= nrow x ncol) */
    bool *keep;   /* rows still selected */
} cl_sweep_table;

cl_status cl_sweep_table_read(const char *path, cl_sweep_table *t,
                              cl_error *err);
void cl_sweep_table_free(cl_sweep_table *t);

/* Keep the rows whose problem axes (the columns between integrator and
 * status other than the [run] keys of a method) hold the value cfg gives
 * that key, numbers compared as numbers; an axis cfg does not set must
 * have one value among the rows kept.  CL_EINVAL naming the axis and the
 * way to pick otherwise, or when no row is left. */
cl_status cl_sweep_table_select(cl_sweep_table *t, cl_config *cfg,
                                cl_error *err);

/* The stability result of the method `label` from its rows (role job):
 * complete runs are stable; failed runs that got going (a time reached)
 * are unstable, blown up or given up by their solver; failed runs that
 * never started and missing ones are left out.  dt_unstable is the
 * smallest unstable step, dt_stable the largest stable step below it (or
 * the largest of all when none was unstable). */
cl_status cl_stab_from_sweep(const cl_sweep_table *t, const char *label,
                             const cl_integrator_type *type,
                             cl_stab_result *r, cl_error *err);

/* The convergence levels of `label` from its rows: by dt for a fixed-step
 * method, by rtol otherwise, largest first; errors from the table (against
 * the sweep's reference run), every complete level with an error fitted. */
cl_status cl_conv_from_sweep(const cl_sweep_table *t, const char *label,
                             const cl_integrator_type *type,
                             cl_conv_result *r, cl_error *err);

#endif
