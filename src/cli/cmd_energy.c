/* clothode energy PROBLEM: energy balance of integrators
 * (analysis/energy_balance.h). */
#include <math.h>
#include <stdlib.h>

#include "analysis/energy_balance.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

#define EB_MAX_METHODS 32

static const char eb_help[] =
    "usage: clothode energy PROBLEM [options]\n"
    "Run each integrator to T and follow its energy at evenly spread\n"
    "samples: E = kinetic + potential, W = the work of the damping\n"
    "(trapezoidal rule between samples) and the balance B = E - E(0) - W,\n"
    "the energy the integrator made (> 0) or destroyed (< 0).  Prints E(0),\n"
    "E(T), W(T), B(T) and max |B| (also relative to the run's energy\n"
    "scale); writes every sample to energy.csv in the output directory.\n"
    "\n"
    "  --integrator LIST  integrators, comma-separated; [run] integrator\n"
    "  --dt H             step of the fixed-step integrators (s)\n"
    "  --rtol R --atol A  tolerances of the adaptive integrators\n"
    "  --t-end T          final time (s); [run] t_end\n"
    "  --samples S        samples after t = 0 (default 1000; a fixed-step\n"
    "                     method is sampled at most at every step)\n"
    "  --linsol NAME      linear solver of implicit integrators\n"
    CL_CLI_HELP_OUT_SET
    "  --quiet            no table on stdout\n"
    "  --help             this text\n"
    "W's quadrature error falls with the square of the sample spacing:\n"
    "sample densely when the damping is strong.  Moving pins do work that\n"
    "shows in B.  A run that blows up (as in run) is reported with the\n"
    "samples before it.  Problems that tear are refused.\n";

static const struct option eb_opts[] = {
    {"integrator", required_argument, 0, 'i'},
    {"dt", required_argument, 0, 'd'},
    {"rtol", required_argument, 0, 'r'},
    {"atol", required_argument, 0, 'a'},
    {"t-end", required_argument, 0, 't'},
    {"samples", required_argument, 0, 'S'},
    {"linsol", required_argument, 0, 'l'},
    CL_CLI_OPTS_TAIL};
static const char *const eb_key[128] = {
    ['i'] = "run.integrator", ['d'] = "run.dt", ['r'] = "run.rtol",
    ['a'] = "run.atol", ['t'] = "run.t_end", ['S'] = "energy.samples",
    ['l'] = "run.linsol"};
static const char *const eb_label[128] = {
    ['i'] = "--integrator", ['d'] = "--dt", ['r'] = "--rtol",
    ['a'] = "--atol", ['t'] = "--t-end", ['S'] = "--samples",
    ['l'] = "--linsol"};
static const cl_cli_spec eb_spec = {"energy", eb_help, eb_opts, eb_key,
                                    eb_label};

typedef struct {
    int nm;
    cl_cli_method m[EB_MAX_METHODS];
    double t_end, max_stretch;
    long samples;
} eb_setup;

static cl_status read_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    eb_setup *s = ctx;
    cl_status rc;
    if ((rc = cl_cli_methods(cfg, true, EB_MAX_METHODS, s->m, &s->nm,
                             err)) ||
        (rc = cl_config_double(cfg, "run", "t_end", 2.0, 1e-300, INFINITY,
                               &s->t_end, err)) ||
        (rc = cl_config_double(cfg, "run", "max_stretch", 10.0, 1.0,
                               INFINITY, &s->max_stretch, err)))
        return rc;
    for (int k = 0; k < s->nm; k++)
        if (!s->m[k].type->fixed_step)
            s->m[k].io.dt = 0.0; /* not CVODE's first step: its own */
    return cl_config_long(cfg, "energy", "samples", 1000, 1, 100000000,
                          &s->samples, err);
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
    cl_status rc = cl_cli_methods_try(m, s->m, s->nm, err);
    for (int k = 0; !rc && k < s->nm; k++)
        rc = cl_ebal_check(m, s->m[k].type, &s->m[k].io, s->t_end,
                           s->samples, err);
    if (rc || job->quiet)
        return rc;
    printf("problem    %s, T = %g s, %ld samples\n", job->problem, s->t_end,
           s->samples);
    return CL_OK;
}

static cl_status run_one(cl_model *m, void *ctx, int k, void *result,
                         cl_error *err)
{
    const eb_setup *s = ctx;
    cl_ebal_result *r = result;
    cl_status rc = cl_ebal_run(m, s->m[k].type, &s->m[k].io, s->t_end,
                               s->samples, s->max_stretch, r, err);
    r->label = s->m[k].label;
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

static const cl_cli_study eb_study = {
    .csv = "energy.csv",
    .columns = "integrator            E(0) [J]        E(T)        W(T)       "
               " B(T)     max |B|  max|B|/S    steps  cpu [s]",
    .size = sizeof(cl_ebal_result), .begin = begin,
    .run = run_one, .print = print_result, .rows = rows,
    .release = release};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const eb_setup *s = ctx;
    return cl_cli_study_run(m, job, &eb_study, s->nm, ctx, err);
}

int cl_cmd_energy(int argc, char **argv)
{
    eb_setup s = {0};
    return cl_cli_problem_main(argc, argv, &eb_spec, read_setup, study, &s);
}
