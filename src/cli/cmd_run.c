/* clothode run PROBLEM: integrate one problem and write its outputs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/simulate.h"
#include "cli/cli.h"
#include "cli/commands.h"

static const char run_help[] =
    "usage: clothode run PROBLEM [options]\n"
    "Integrate PROBLEM (a .ini file, or a name under problems/) and write\n"
    "series.csv, frames, final.csv and stats.csv into the output directory.\n"
    "\n"
    "  --integrator NAME  integrator (clothode list); [run] integrator\n"
    "  --dt H             fixed step for fixed-step integrators (s)\n"
    "  --rtol R --atol A  tolerances for adaptive integrators\n"
    "  --linsol NAME      linear solver of implicit integrators (klu, pcg, ...)\n"
    "  --max-order K      highest order of CVODE / IDA (default 5 for BDF, 12\n"
    "                     for Adams; BDF beyond 2 is not A-stable)\n"
    "  --threads N        threads for the pair forces of every right-hand side\n"
    "                     (default 1; results equal the serial ones to\n"
    "                     round-off)\n"
    "  --t-end T          final time (s); [run] t_end\n"
    "  --samples S        time-series rows after t = 0 (default 200)\n"
    "  --frames K         frames after t = 0 (default 10, 0 for none)\n"
    "  --format LIST      frame formats among csv,vtk,obj (default vtk,obj;\n"
    "                     csv: the time series only)\n"
    CL_CLI_HELP_OUT_SET
    "  --quiet            no summary on stdout\n"
    "  --help             this text\n"
    "Every option is also a key of the [run] section (t_end, dt, rtol, atol,\n"
    "linsol, max_order, threads, samples, frames, format, integrator,\n"
    "max_stretch);\n"
    "[run] also takes newton_tol, newton_maxit (fixed-step implicit methods),\n"
    "lin_tol, lin_maxit (iterative linear solvers) and verlet_damping\n"
    "(the Verlet-and-PBD report).\n";

static const struct option run_opts[] = {
    {"integrator", required_argument, 0, 'i'},
    {"dt", required_argument, 0, 'd'},
    {"rtol", required_argument, 0, 'r'},
    {"atol", required_argument, 0, 'a'},
    {"linsol", required_argument, 0, 'l'},
    {"threads", required_argument, 0, 'T'},
    {"max-order", required_argument, 0, 'm'},
    {"t-end", required_argument, 0, 't'},
    {"samples", required_argument, 0, 'S'},
    {"frames", required_argument, 0, 'f'},
    {"format", required_argument, 0, 'F'},
    CL_CLI_OPTS_TAIL};
static const char *const run_key[128] = {
    ['i'] = "run.integrator", ['d'] = "run.dt", ['r'] = "run.rtol",
    ['a'] = "run.atol", ['l'] = "run.linsol", ['T'] = "run.threads",
    ['m'] = "run.max_order", ['t'] = "run.t_end", ['S'] = "run.samples",
    ['f'] = "run.frames", ['F'] = "run.format"};
static const char *const run_label[128] = {
    ['i'] = "--integrator", ['d'] = "--dt", ['r'] = "--rtol",
    ['a'] = "--atol", ['l'] = "--linsol", ['T'] = "--threads",
    ['m'] = "--max-order", ['t'] = "--t-end", ['S'] = "--samples",
    ['f'] = "--frames", ['F'] = "--format"};
static const cl_cli_spec run_spec = {"run", run_help, run_opts, run_key,
                                     run_label};

typedef struct {
    const cl_integrator_type *type;
    cl_integrator_opts io;
    cl_sim_opts so;
    long threads;
} run_setup;

static cl_status read_formats(cl_config *cfg, cl_sim_opts *so, cl_error *err)
{
    const char *fmt = cl_config_string(cfg, "run", "format", "vtk,obj");
    char where[256];
    so->vtk = so->obj = false;
    for (const char *p = fmt; *p;) {
        size_t n = strcspn(p, ", ");
        if (n == 3 && !strncmp(p, "vtk", 3))
            so->vtk = true;
        else if (n == 3 && !strncmp(p, "obj", 3))
            so->obj = true;
        else if (n && !(n == 3 && !strncmp(p, "csv", 3)))
            return cl_error_set(err, CL_EINVAL,
                                "%s: [run] format = \"%s\": expected a list "
                                "of csv, vtk, obj",
                                cl_config_origin(cfg, "run", "format", where,
                                                 sizeof where), fmt);
        p += n;
        p += strspn(p, ", ");
    }
    return CL_OK;
}

static cl_status read_integrator(cl_config *cfg, run_setup *r, cl_error *err)
{
    const char *names[64];
    int n = 0, k;
    for (; cl_integrator_registry[n] && n < 63; n++)
        names[n] = cl_integrator_registry[n]->name;
    names[n] = NULL;
    cl_status rc = cl_config_choice(cfg, "run", "integrator", names, 0, &k,
                                    err);
    if (rc)
        return rc;
    r->type = cl_integrator_registry[k];
    return cl_cli_integrator_opts(cfg, r->type, true, &r->io, err);
}

static cl_status read_run(cl_config *cfg, void *ctx, cl_error *err)
{
    run_setup *r = ctx;
    cl_status rc;
    if ((rc = read_integrator(cfg, r, err)) ||
        (rc = cl_config_double(cfg, "run", "t_end", 2.0, 1e-300, INFINITY,
                               &r->so.t_end, err)) ||
        (rc = cl_config_long(cfg, "run", "samples", 200, 1, 100000000,
                             &r->so.samples, err)) ||
        (rc = cl_config_long(cfg, "run", "frames", 10, 0, 1000000,
                             &r->so.frames, err)) ||
        (rc = cl_config_long(cfg, "run", "threads", 1, 1,
                             CL_MODEL_MAX_THREADS, &r->threads, err)) ||
        (rc = cl_config_double(cfg, "run", "max_stretch", 10.0, 1.0,
                               INFINITY, &r->so.max_stretch, err)))
        return rc;
    return read_formats(cfg, &r->so, err);
}

static void print_summary(const char *problem, const run_setup *r,
                          const cl_model *m, const cl_sim_result *res)
{
    const cl_cloth *c = cl_model_cloth(m);
    char shape[96];
    printf("problem      %s (%s, %zu free)\n", problem,
           cl_cloth_shape(c, shape, sizeof shape), c->nfree);
    printf("integrator   %s", r->type->name);
    if (r->type->fixed_step)
        printf(" (dt = %g)\n", r->io.dt);
    else
        printf(" (rtol = %g, atol = %g)\n", r->io.rtol, r->io.atol);
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
    cl_status rc = cl_model_set_threads(m, (int)r->threads, err);
    r->so.outdir = job->outdir;
    r->so.progress = cl_cli_progress;
    if (!rc)
        rc = cl_simulate(m, r->type, &r->io, &r->so, &res, err);
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
    return cl_cli_problem_main(argc, argv, &run_spec, read_run, run_work,
                               &r);
}
