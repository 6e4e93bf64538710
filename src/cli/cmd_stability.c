/* clothode stability PROBLEM: the largest stable step of fixed-step
 * integrators (analysis/stability.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/stability.h"
#include "analysis/sweep_table.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

typedef struct {
    cl_cli_args a;
    cl_cli_methods integrators;
    cl_cli_run run;
    cl_stab_opts so;
    const char *from;      /* --from-sweep TABLE, or NULL */
    cl_sweep_table table;  /* its rows of this problem */
} stab_setup;

/* dt_max: T/100 by default, at most T/10 (a run of a few steps has no room
 * to blow up); dt_min at most dt_max. */
static void dt_max_bounds(const void *settings, double *def, double *hi)
{
    const stab_setup *s = settings;
    *def = s->run.t_end / 100;
    *hi = s->run.t_end / 10;
}

static void dt_min_bounds(const void *settings, double *def, double *hi)
{
    (void)def;
    *hi = ((const stab_setup *)settings)->so.dt_max;
}

static const cl_cli_opt stab_rows[] = {
    {.name = "integrator", .arg = "LIST", .type = CL_CLI_METHODS,
     .sec = "run", .key = "integrator", .sdef = "cvode-bdf",
     .hi = CL_CLI_MAX_METHODS, .field = offsetof(stab_setup, integrators),
     .help = "fixed-step integrators, comma-separated, each NAME or "
             "NAME:LINSOL"},
    /* [run] dt is read but not used: the search sets the step */
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows,
     .hide = "dt rtol atol max-order " CL_CLI_RUN_OUTPUTS, .field = offsetof(stab_setup, run)},
    {.name = "dt-max", .arg = "H", .type = CL_CLI_DOUBLE,
     .sec = "stability", .key = "dt_max", .lo = 1e-300,
     .bounds = dt_max_bounds, .field = offsetof(stab_setup, so.dt_max),
     .help = "largest step tried, at most T/10 (default T/100): a run of a "
             "few steps has no room to blow up"},
    {.name = "dt-min", .arg = "H", .type = CL_CLI_DOUBLE,
     .sec = "stability", .key = "dt_min", .def = 1e-7, .lo = 1e-300,
     .bounds = dt_min_bounds, .field = offsetof(stab_setup, so.dt_min),
     .help = "give up below this step, at most dt_max"},
    {.name = "rel", .arg = "R", .type = CL_CLI_DOUBLE, .sec = "stability",
     .key = "rel", .def = 0.02, .lo = 1e-6, .hi = 0.5,
     .field = offsetof(stab_setup, so.rel),
     .help = "bracket width relative to the step"},
    {.name = "checks", .arg = "K", .type = CL_CLI_LONG, .sec = "stability",
     .key = "checks", .def = 20, .lo = 1, .hi = 100000,
     .field = offsetof(stab_setup, so.checks),
     .help = "stretch tests per run"},
    {.name = "from-sweep", .arg = "TABLE", .type = CL_CLI_STRING,
     .field = offsetof(stab_setup, from),
     .help = "take the runs from a table of 'clothode sweep collect' "
             "instead of searching"},
    CL_CLI_TAIL(stab_setup, "no table on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table stab_table = {
    .cmd = "stability", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = stab_rows,
    .about =
    "For each fixed-step integrator, the largest step dt = T/N with which a\n"
    "run to T stays bounded: N doubles from T/dt_max until a run is stable,\n"
    "then bisection brackets the limit.  A run is unstable when its state\n"
    "becomes non-finite, its stretch d/L exceeds [run] max_stretch at one of\n"
    "the checks, or its solver gives up.  Writes every run to stability.csv\n"
    "in the output directory.\n",
    .notes =
    "The other [run] keys apply as in run; [run] dt is not used.  Stability\n"
    "need not be monotone in dt: the bracket is the one the search found.\n"
    "Problems that tear are refused.  With --from-sweep the runs are the\n"
    "sweep's (its dt axis; the rows whose other axes match this problem's\n"
    "values): complete runs are stable, failed runs that got going are not;\n"
    "the bracket is the smallest unstable dt and the largest stable one\n"
    "below it.\n"};

/* Only fixed-step integrators have a step to limit. */
static cl_status check_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    stab_setup *s = ctx;
    cl_status rc = cl_cli_methods_check(cfg, &s->integrators, &s->run.io,
                                        CL_CLI_DT_NONE, err);
    if (!rc)
        rc = cl_cli_methods_fixed(cfg, &s->integrators, "stability", err);
    if (rc)
        return rc;
    s->so.t_end = s->run.t_end;
    s->so.max_stretch = s->run.max_stretch;
    if (s->from && !(rc = cl_sweep_table_read(s->from, &s->table, err)))
        rc = cl_sweep_table_select(&s->table, cfg, err);
    return rc;
}

static void print_result(const void *result)
{
    const cl_stab_result *r = result;
    printf("%-18s ", r->label);
    if (isnan(r->dt_unstable))
        printf("stable at dt_max = %.4g (%d run)\n", r->dt_stable,
               r->ntrial);
    else if (isnan(r->dt_stable))
        printf("%11s %11.4g %5d  %s\n", "none", r->dt_unstable, r->ntrial,
               r->trial[r->failed].why.msg);
    else
        printf("%11.4g %11.4g %5d  %s\n", r->dt_stable, r->dt_unstable,
               r->ntrial, r->trial[r->failed].why.msg);
}

/* Every request checked, then the header. */
static cl_status begin(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const stab_setup *s = ctx;
    const cl_cloth *c = cl_model_cloth(m);
    cl_status rc = cl_cli_methods_try(m, &s->integrators, err);
    for (int k = 0; !rc && k < s->integrators.n; k++)
        rc = cl_stab_check(m, s->integrators.m[k].type, &s->so, err);
    if (rc || job->quiet)
        return rc;
    char shape[96];
    printf("problem    %s (%s, %zu free), T = %g s, max_stretch %g, %ld "
           "checks per run\n", job->problem,
           cl_cloth_shape(c, shape, sizeof shape), c->nfree, s->so.t_end,
           s->so.max_stretch, s->so.checks);
    if (s->from)
        printf("runs       from the sweep table %s\n", s->from);
    return CL_OK;
}

static cl_status run_one(cl_model *m, void *ctx, int k, void *result,
                         cl_error *err)
{
    const stab_setup *s = ctx;
    cl_stab_result *r = result;
    const cl_cli_method *mk = &s->integrators.m[k];
    cl_status rc = s->from ? cl_stab_from_sweep(&s->table, mk->label,
                                                mk->type, r, err)
                           : cl_stability(m, mk->type, &mk->io, &s->so, r,
                                          err);
    r->label = mk->label;
    return rc;
}

static void rows(FILE *fp, const void *result, bool header)
{
    cl_stab_write_rows(fp, result, header);
}

static void end(void *ctx)
{
    cl_sweep_table_free(&((stab_setup *)ctx)->table);
}

static const cl_cli_study stab_study = {
    .csv = "stability.csv",
    .columns = "integrator           stable dt unstable dt  runs  why the "
               "unstable run failed",
    .size = sizeof(cl_stab_result), .begin = begin,
    .run = run_one, .print = print_result, .rows = rows, .end = end};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const stab_setup *s = ctx;
    return cl_cli_study_run(m, job, &stab_study, s->integrators.n, ctx,
                            err);
}

int cl_cmd_stability(int argc, char **argv)
{
    stab_setup s = {0};
    int status = cl_cli_problem_main(argc, argv, &stab_table, &s,
                                     check_setup, study);
    cl_sweep_table_free(&s.table); /* when the study did not start */
    return status;
}
