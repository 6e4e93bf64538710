/* clothode energy PROBLEM: energy balance of integrators
 * (analysis/energy_balance.h). */
#include <math.h>
#include <stdlib.h>

#include "analysis/energy_balance.h"
#include "analysis/sweep_table.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

typedef struct {
    cl_cli_args a;
    cl_cli_methods integrators;
    cl_cli_run run;
    long samples;
    const char *from;      /* --from-sweep TABLE, or NULL */
    cl_sweep_table table;  /* its rows of this problem */
} eb_setup;

static const cl_cli_opt eb_rows[] = {
    {.name = "integrator", .arg = "LIST", .type = CL_CLI_METHODS,
     .sec = "run", .key = "integrator", .sdef = "cvode-bdf",
     .hi = CL_CLI_MAX_METHODS, .field = offsetof(eb_setup, integrators),
     .help = "integrators, comma-separated, each NAME or NAME:LINSOL"},
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows, .hide = "max-order",
     .unread = CL_CLI_RUN_OUTPUTS, .field = offsetof(eb_setup, run)},
    {.name = "samples", .arg = "S", .type = CL_CLI_LONG, .sec = "energy",
     .key = "samples", .def = 1000, .lo = 1, .hi = 100000000,
     .field = offsetof(eb_setup, samples),
     .help = "samples after t = 0 (a fixed-step method is sampled at most "
             "at every step)"},
    {.name = "from-sweep", .arg = "TABLE", .type = CL_CLI_STRING,
     .field = offsetof(eb_setup, from),
     .help = "take the runs from a table of 'clothode sweep collect' (each "
             "job's series from jobs/ beside it) instead of making them"},
    CL_CLI_TAIL(eb_setup, "no table on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table eb_table = {
    .cmd = "energy", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = eb_rows,
    .about =
    "Run each integrator to T and follow its energy at evenly spread\n"
    "samples: E = kinetic + potential, W = the work of the damping\n"
    "(trapezoidal rule between samples) and the balance B = E - E(0) - W,\n"
    "the energy the integrator made (> 0) or destroyed (< 0).  Prints E(0),\n"
    "E(T), W(T), B(T) and max |B|, also over S, the energy that moved (the\n"
    "largest kinetic energy, |potential - potential(0)| and |W| of the\n"
    "samples); writes every sample to energy.csv in the output directory\n"
    "(its column dissipated is W, negative where energy is removed).\n",
    .notes =
    "W's quadrature error falls with the square of the sample spacing:\n"
    "sample densely when the damping is strong.  An adaptive method's B is\n"
    "at the level of its tolerances and moves with its steps, which the\n"
    "sample times change.  Moving pins do work that shows in B.  A run\n"
    "that blows up (as in run) is reported with the samples before it.\n"
    "Problems that tear are refused.  With --from-sweep\n"
    "each integrator's run is the sweep's at its dt (fixed step) or rtol\n"
    "(the rows whose other axes match this problem's values), its samples\n"
    "the rows of the run's series.csv (the sweep's [run] samples; --samples\n"
    "is not used), read from TABLE's directory (collect's default output);\n"
    "contact projections are refused (their work is not in the series).\n"};

/* The step of the fixed-step methods of the list and the tolerances of
 * the adaptive ones, as the runs use them. */
static void print_steps(const cl_cli_methods *ms, const cl_integrator_opts *io)
{
    bool fixed = false, adaptive = false;
    for (int k = 0; k < ms->n; k++)
        *(cl_integrator_fixed(ms->m[k].type, ms->m[k].io.dt) ? &fixed
                                                             : &adaptive) =
            true;
    if (fixed)
        printf("fixed      dt = %g s\n", io->dt);
    if (adaptive)
        printf("adaptive   rtol %g, atol %g\n", io->rtol, io->atol);
}

static cl_status check_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    eb_setup *s = ctx;
    cl_status rc = cl_cli_methods_check(cfg, &s->integrators, &s->run.io,
                                        CL_CLI_DT_FIXED, err);
    if (!rc && s->from && !(rc = cl_sweep_table_read(s->from, &s->table,
                                                      err)))
        rc = cl_sweep_table_select(&s->table, cfg, "energy", err);
    /* the span, from [init] time (the sweep's, once selected) to t_end */
    if (!rc)
        rc = cl_cli_span(cfg, s->run.t_end, &s->run.t_end, err);
    /* a petsc-* method the sweep ran at fixed steps: its run is picked by
     * --dt, as a fixed-step method's */
    for (int k = 0; !rc && s->from && k < s->integrators.n; k++) {
        const cl_cli_method *mk = &s->integrators.m[k];
        if (!cl_integrator_fixed(mk->type, mk->io.dt) &&
            mk->type->dt_fixes_step &&
            cl_sweep_table_has_runs(&s->table, mk->label, "run.dt"))
            rc = cl_error_set(err, CL_EINVAL, "--from-sweep %s: the sweep "
                              "ran %s at fixed steps (run.dt): give --dt to "
                              "pick its run", s->from, mk->label);
    }
    return rc;
}

static void print_result(const void *result)
{
    const cl_ebal_result *r = result;
    if (r->n == 0) { /* failed before the first sample */
        printf("%-18s failed: %s\n", r->label, r->why.msg);
        return;
    }
    const cl_ebal_sample *a = &r->s[0], *b = &r->s[r->n - 1];
    printf("%-18s %11.4e %11.4e %11.4e %11.4e %11.4e %9.2e %8ld %8.3f%s%s\n",
           r->label, a->total, b->total, b->dissipated, b->balance,
           r->balance_max, r->scale > 0 ? r->balance_max / r->scale : NAN,
           r->stats.steps, r->stats.cpu, r->rc ? "  failed: " : "",
           r->rc ? r->why.msg : "");
}

/* Every request checked, then the header. */
static cl_status begin(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const eb_setup *s = ctx;
    cl_status rc = cl_cli_methods_try(m, &s->integrators, err);
    for (int k = 0; !rc && k < s->integrators.n; k++)
        rc = cl_ebal_check(m, s->integrators.m[k].type,
                           &s->integrators.m[k].io, s->run.t_end, s->samples,
                           err);
    if (!rc && s->from && cl_model_system(m)->projects)
        rc = cl_error_set(err, CL_EUNSUPPORTED, "--from-sweep: the work of "
                          "the contact projections is not in a run's "
                          "series; run the study here");
    if (rc || job->quiet)
        return rc;
    if (s->from)
        printf("problem    %s, T = %g s, samples of the sweep table %s\n",
               job->problem, s->run.t_end, s->from);
    else
        printf("problem    %s, T = %g s, %ld samples\n", job->problem,
               s->run.t_end, s->samples);
    print_steps(&s->integrators, &s->run.io);
    return CL_OK;
}

static cl_status run_one(cl_model *m, void *ctx, int k, void *result,
                         cl_error *err)
{
    const eb_setup *s = ctx;
    cl_ebal_result *r = result;
    const cl_cli_method *mk = &s->integrators.m[k];
    bool fixed = cl_integrator_fixed(mk->type, mk->io.dt);
    cl_status rc = s->from
        ? cl_ebal_from_sweep(&s->table, mk->label, mk->type,
                             fixed ? "run.dt" : "run.rtol",
                             fixed ? mk->io.dt : mk->io.rtol, r, err)
        : cl_ebal_run(m, mk->type, &mk->io, s->run.t_end, s->samples,
                      s->run.max_stretch, r, err);
    r->label = mk->label;
    return rc;
}

static void rows(FILE *fp, const void *result, bool header)
{
    cl_ebal_write_rows(fp, result, header);
}

static void release(void *result)
{
    cl_ebal_free(result);
}

static void end(void *ctx)
{
    cl_sweep_table_free(&((eb_setup *)ctx)->table);
}

static const cl_cli_study eb_study = {
    .csv = "energy.csv",
    .columns = "integrator            E(0) [J]        E(T)        W(T)       "
               " B(T)     max |B|  max|B|/S    steps  cpu [s]",
    .size = sizeof(cl_ebal_result), .begin = begin,
    .run = run_one, .print = print_result, .rows = rows,
    .release = release, .end = end};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const eb_setup *s = ctx;
    if (s->from && cl_sweep_table_same_inputs(&s->table, job->cfg, err))
        return err->code;
    return cl_cli_study_run(m, job, &eb_study, s->integrators.n, ctx, err);
}

int cl_cmd_energy(int argc, char **argv)
{
    eb_setup s = {0};
    int status = cl_cli_problem_main(argc, argv, &eb_table, &s, check_setup,
                                     study);
    cl_sweep_table_free(&s.table); /* when the study did not start */
    return status;
}
