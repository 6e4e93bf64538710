/* clothode run PROBLEM: integrate one problem and write its outputs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/simulate.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/progress.h"

typedef struct {
    cl_cli_args a;
    cl_cli_methods integrator; /* one */
    cl_cli_run run;
    cl_sim_opts so;
} run_setup;

static const cl_cli_opt run_rows[] = {
    {.name = "integrator", .arg = "NAME", .type = CL_CLI_METHODS,
     .sec = "run", .key = "integrator", .sdef = "cvode-bdf", .hi = 1,
     .field = offsetof(run_setup, integrator),
     .help = "integrator, or NAME:LINSOL (clothode list)"},
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows,
     .field = offsetof(run_setup, run)},
    CL_CLI_TAIL(run_setup, "no summary on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table run_table = {
    .cmd = "run", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = run_rows,
    .about =
    "Integrate PROBLEM (a .ini file, or a name under problems/) and write\n"
    "series.csv, frames, final.csv and stats.csv into the output\n"
    "directory.\n"};

static cl_status check_run(cl_config *cfg, void *ctx, cl_error *err)
{
    run_setup *r = ctx;
    r->so.t_end = r->run.t_end;
    r->so.max_stretch = r->run.max_stretch;
    r->so.samples = r->run.samples;
    r->so.frames = r->run.frames;
    r->so.vtk = r->run.format & CL_CLI_FMT_VTK;
    r->so.obj = r->run.format & CL_CLI_FMT_OBJ;
    return cl_cli_methods_check(cfg, &r->integrator, &r->run.io,
                                CL_CLI_DT_ALL, err);
}

static void print_summary(const char *problem, const run_setup *r,
                          const cl_model *m, const cl_sim_result *res)
{
    const cl_cloth *c = cl_model_cloth(m);
    const cl_cli_method *im = &r->integrator.m[0];
    char shape[96];
    printf("problem      %s (%s, %zu free)\n", problem,
           cl_cloth_shape(c, shape, sizeof shape), c->nfree);
    printf("integrator   %s", im->type->name);
    if (im->type->fixed_step)
        printf(" (dt = %g)\n", im->io.dt);
    else
        printf(" (rtol = %g, atol = %g)\n", im->io.rtol, im->io.atol);
    printf("time         %g of %g s\n", res->t_reached, r->so.t_end);
    printf("energy       %.10g -> %.10g J (kinetic %.6g)\n", res->e0.total,
           res->e1.total, res->e1.kinetic);
    for (size_t k = 0; k < res->e1.nterm; k++)
        printf("  %-10s %.10g J\n", res->e1.name[k], res->e1.value[k]);
    printf("shape        max stretch d/L = %.6f, ", res->max_stretch);
    if (isnan(res->max_offplane))
        printf("max out-of-plane n/a (the rest mesh is not horizontal)\n");
    else
        printf("max out-of-plane %.6g m\n", res->max_offplane);
    if (cl_model_contact(m))
        printf("contact      worst penetration %.6g m at t = %.6g s\n",
               res->worst_penetration, res->worst_t);
    cl_stats_print(&res->stats, stdout, true);
    printf("output       %s (series.csv, %ld frames, final.csv, stats.csv)\n",
           r->so.outdir, res->frames);
}

static cl_status run_work(cl_model *m, const cl_cli_job *job, void *ctx,
                          cl_error *err)
{
    run_setup *r = ctx;
    cl_sim_result res = {0};
    cl_cli_progress_line line;
    cl_status rc = cl_model_set_threads(m, (int)r->run.threads, err);
    cl_cli_progress_start(&line, job->quiet, "t =", "s", r->so.t_end);
    r->so.outdir = job->outdir;
    r->so.progress = cl_cli_progress;
    r->so.progress_ctx = &line;
    if (!rc)
        rc = cl_simulate(m, r->integrator.m[0].type, &r->integrator.m[0].io,
                         &r->so, &res, err);
    cl_cli_progress_clear(&line);
    if (!job->quiet && res.rows > 0)
        print_summary(job->problem, r, m, &res);
    if (res.rows > 0) {
        char path[4200];
        cl_error ignored;
        snprintf(path, sizeof path, "%s/config.ini", job->outdir);
        cl_config_write(job->cfg, path, &ignored);
    }
    free(res.xfinal);
    return rc;
}

int cl_cmd_run(int argc, char **argv)
{
    run_setup r = {0};
    return cl_cli_problem_main(argc, argv, &run_table, &r, check_run,
                               run_work);
}
