/* A collected sweep table (`clothode sweep collect`, analysis/sweep.h) read
 * back as the runs of a study: `stability`, `convergence`,
 * `workprecision`, `energy` and `contact --from-sweep TABLE` take their
 * runs from it instead of making them, so that a sweep run on a cluster feeds the same tables and
 * figures as a local study. */
#ifndef CL_SWEEP_TABLE_H
#define CL_SWEEP_TABLE_H

#include <stdbool.h>

#include "analysis/contact_study.h"
#include "analysis/convergence.h"
#include "analysis/energy_balance.h"
#include "analysis/sweep.h"
#include "analysis/stability.h"
#include "core/decls.h"
#include "core/error.h"
#include "io/config.h"

CL_BEGIN_DECLS

#define CL_SWEEP_TABLE_MAX_ROWS 1024 /* rows of one method a study takes */

typedef struct {
    char *path;   /* as given: one table, or several separated by commas */
    int npath;
    char **paths; /* the tables */
    int *src;     /* the table of each row (index into paths) */
    int ncol, nrow;
    char **head;  /* column names */
    char **cell;  /* nrow x ncol fields, row-major */
    int ncell;    /* fields read (ncell >= nrow x ncol) */
    bool *keep;   /* rows still selected */
} cl_sweep_table;

/* The table at path, or the rows of several tables with the same columns
 * (the stages of one sweep, `sweep refine`) given as "A.csv,B.csv". */
cl_status cl_sweep_table_read(const char *path, cl_sweep_table *t,
                              cl_error *err);
void cl_sweep_table_free(cl_sweep_table *t);

/* The field of column `name` in `row` ("NA" without that column), and
 * its number (NaN when it is not one). */
const char *cl_sweep_table_text(const cl_sweep_table *t, int row,
                                const char *name);
double cl_sweep_table_value(const cl_sweep_table *t, int row,
                            const char *name);

/* Whether two fields hold the same value: numbers compared as numbers
 * (relative 1e-12), anything else as text. */
bool cl_sweep_same_value(const char *a, const char *b);

/* Keep the rows whose problem axes (the columns between integrator and
 * status other than the [run] keys of a method) hold the value cfg gives
 * that key, numbers compared as numbers; an axis cfg does not set must
 * have one value among the rows kept (every row is reconsidered, so a
 * table can be selected again for another configuration).  CL_EINVAL
 * naming the axis and the way to pick otherwise, or when no row is left;
 * also when the table's runs are of another problem than cfg's file
 * (cl_same_input), or a --set of cfg changes a model key that is no axis
 * of the table (the keys of [run] and of the command's own section `own`,
 * NULL for none, are no model's). */
cl_status cl_sweep_table_select(cl_sweep_table *t, cl_config *cfg,
                                const char *own, cl_error *err);

/* The table's runs read the files the model built from cfg named
 * (meshes) as they are now: CL_EINVAL when their recorded inputs_sha256
 * differs from the digest of today's files (a mesh edited after the
 * sweep ran); CL_OK when the table records none.  Called once the model
 * is built, since only then does cfg know its files. */
cl_status cl_sweep_table_same_inputs(const cl_sweep_table *t,
                                     const cl_config *cfg, cl_error *err);

/* Whether the table has a job row of `label` with a number in column
 * `param` ("run.dt": a petsc-* method the sweep gave fixed steps). */
bool cl_sweep_table_has_runs(const cl_sweep_table *t, const char *label,
                             const char *param);

/* Whether the table has a column `name` (an axis: "run.dt",
 * "obstacle.ball.k", ...). */
bool cl_sweep_table_has(const cl_sweep_table *t, const char *name);

/* A job row and its value of the method's parameter (dt, rtol). */
typedef struct {
    int row;
    double param;
} cl_sweep_row;

/* The kept job rows of `label` with a number in column `param` (a run.*
 * key), largest first; how many (1 .. max), or -1 with err set (no such
 * column, no such rows, more than max). */
int cl_sweep_table_rows(const cl_sweep_table *t, const char *label,
                        const char *param, cl_sweep_row *out, int max,
                        cl_error *err);

/* The stability trial of a row (dt = row.param): complete runs are
 * stable; failed runs that got going (a time reached) are unstable
 * (CL_EBLOWUP, why "failed at t = T s (EXIT)"); false for failed runs that
 * never started and missing ones.  The statistics are the table's. */
bool cl_sweep_table_trial(const cl_sweep_table *t, cl_sweep_row row,
                          cl_stab_trial *tr);

/* The stability result of the method `label` from its rows (role job):
 * complete runs are stable; failed runs that got going (a time reached)
 * are unstable, blown up or given up by their solver; failed runs that
 * never started and missing ones are left out.  dt_unstable is the
 * smallest unstable step, dt_stable the largest stable step below it (or
 * the largest of all when none was unstable). */
cl_status cl_stab_from_sweep(const cl_sweep_table *t, const char *label,
                             const cl_integrator_type *type,
                             cl_stab_result *r, cl_error *err);

/* The step limit of `type` (labelled `label`) on model m: from the sweep's
 * rows when t is not NULL (cl_stab_from_sweep), else by the search
 * (cl_stability with io and o). */
cl_status cl_stab_limit(const cl_sweep_table *t, cl_model *m,
                        const char *label, const cl_integrator_type *type,
                        const cl_integrator_opts *io, const cl_stab_opts *o,
                        cl_stab_result *r, cl_error *err);

/* The convergence levels of `label` from its rows: by dt for a fixed-step
 * method (and a petsc-* one whose rows have a dt), by rtol otherwise,
 * largest first; errors from the table (against
 * the sweep's reference run), every complete level with an error fitted. */
cl_status cl_conv_from_sweep(const cl_sweep_table *t, const char *label,
                             const cl_integrator_type *type,
                             cl_conv_result *r, cl_error *err);

/* The next stage of the sweep sw over dt into next (its dir, problem
 * and binary set): for every line of sw (an integrator and the values of
 * the other axes) whose rows in t bracket a limit (cl_stab_from_sweep's
 * smallest unstable dt and largest stable one below it, lo and hi) with
 * hi > lo (1 + rel), `points` steps lo (hi/lo)^(i/(points+1)), each made
 * T/N when the line has a t_end T.  next gets sw's axes, in sw's order
 * (so that its collected table has the same columns), and no references;
 * *brackets counts the lines refined.  CL_EINVAL without a dt axis. */
cl_status cl_sweep_refine(const cl_sweep *sw, const cl_sweep_table *t,
                          int points, double rel, cl_sweep *next,
                          int *brackets, cl_error *err);

/* The studies that need a run's time series read it from
 * DIR/jobs/ID/run/series.csv, DIR the directory of the row's table
 * (collect's default output, DIR/collected.csv): CL_EIO naming the file when it is not
 * there. */

/* The energy balance of `label` from its one row at the method's level
 * (`param` = "run.dt" or "run.rtol" equal to `level`), its samples the
 * rows of the run's series (analysis/energy_balance.h: the same
 * trapezoidal W from the series' power_diss).  A failed run keeps the
 * samples it wrote (r->rc CL_EBLOWUP).  CL_EINVAL when no row or several
 * rows match. */
cl_status cl_ebal_from_sweep(const cl_sweep_table *t, const char *label,
                             const cl_integrator_type *type,
                             const char *param, double level,
                             cl_ebal_result *r, cl_error *err);

/* The contact rows of `label`, one per step of the sweep, smallest first:
 * stable and unstable as cl_stab_from_sweep; worst penetration and the
 * largest stretch the largest of the series' samples (max_penetration,
 * max_stretch), penetration and contacts at rest its last row when the
 * run reached T (o->t_end); Newton iterations and CPU time the table's. */
cl_status cl_cstudy_from_sweep(const cl_sweep_table *t, const char *label,
                               const cl_stab_opts *o, cl_cstudy_result *r,
                               cl_error *err);

CL_END_DECLS

#endif
