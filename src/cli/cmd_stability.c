/* clothode stability PROBLEM: the largest stable step of fixed-step
 * integrators (analysis/stability.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/stability.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

#define STAB_MAX_METHODS 32

static const char stab_help[] =
    "usage: clothode stability PROBLEM [options]\n"
    "For each fixed-step integrator, the largest step dt = T/N with which a\n"
    "run to T stays bounded: N doubles from T/dt_max until a run is stable,\n"
    "then bisection brackets the limit.  A run is unstable when its state\n"
    "becomes non-finite, its stretch d/L exceeds [run] max_stretch at one of\n"
    "the checks, or its solver gives up.  Writes every run to stability.csv\n"
    "in the output directory.\n"
    "\n"
    "  --integrator LIST  fixed-step integrators, comma-separated\n"
    "  --t-end T          horizon every run must survive (s); [run] t_end\n"
    "  --dt-max H         largest step tried, at most T/10 (default T/100):\n"
    "                     a run of a few steps has no room to blow up\n"
    "  --dt-min H         give up below this step (default 1e-7)\n"
    "  --rel R            bracket width relative to the step (default 0.02)\n"
    "  --checks K         stretch tests per run (default 20)\n"
    "  --linsol NAME      linear solver of implicit integrators\n"
    CL_CLI_HELP_OUT_SET
    "  --quiet            no table on stdout\n"
    "  --help             this text\n"
    "Other [run] keys (newton_tol, newton_maxit, verlet_damping, ...) apply\n"
    "as in run; [run] dt is not used.  Stability need not be monotone in\n"
    "dt: the bracket is the one the search found.  Problems that tear are\n"
    "refused.\n";

static const struct option stab_opts[] = {
    {"integrator", required_argument, 0, 'i'},
    {"t-end", required_argument, 0, 't'},
    {"dt-max", required_argument, 0, 'H'},
    {"dt-min", required_argument, 0, 'M'},
    {"rel", required_argument, 0, 'r'},
    {"checks", required_argument, 0, 'c'},
    {"linsol", required_argument, 0, 'l'},
    CL_CLI_OPTS_TAIL};
static const char *const stab_key[128] = {
    ['i'] = "run.integrator", ['t'] = "run.t_end",
    ['H'] = "stability.dt_max", ['M'] = "stability.dt_min",
    ['r'] = "stability.rel", ['c'] = "stability.checks",
    ['l'] = "run.linsol"};
static const char *const stab_label[128] = {
    ['i'] = "--integrator", ['t'] = "--t-end", ['H'] = "--dt-max",
    ['M'] = "--dt-min", ['r'] = "--rel", ['c'] = "--checks",
    ['l'] = "--linsol"};
static const cl_cli_spec stab_spec = {"stability", stab_help, stab_opts,
                                      stab_key, stab_label};

typedef struct {
    int nm;
    cl_cli_method m[STAB_MAX_METHODS];
    cl_stab_opts so;
} stab_setup;

/* Only fixed-step integrators have a step to limit. */
static cl_status check_fixed(cl_config *cfg, const stab_setup *s,
                             cl_error *err)
{
    char where[256];
    for (int k = 0; k < s->nm; k++)
        if (!s->m[k].type->fixed_step)
            return cl_error_set(err, CL_EINVAL, "%s: [run] integrator: %s "
                                "chooses its own steps by error control; "
                                "stability takes fixed-step integrators",
                                cl_config_origin(cfg, "run", "integrator",
                                                 where, sizeof where),
                                s->m[k].type->name);
    return CL_OK;
}

static cl_status read_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    stab_setup *s = ctx;
    cl_stab_opts *o = &s->so;
    cl_status rc;
    if ((rc = cl_cli_methods(cfg, false, STAB_MAX_METHODS, s->m, &s->nm,
                             err)) ||
        (rc = check_fixed(cfg, s, err)) ||
        (rc = cl_config_double(cfg, "run", "t_end", 2.0, 1e-300, INFINITY,
                               &o->t_end, err)) ||
        (rc = cl_config_double(cfg, "run", "max_stretch", 10.0, 1.0,
                               INFINITY, &o->max_stretch, err)) ||
        (rc = cl_config_double(cfg, "stability", "dt_max", o->t_end / 100,
                               1e-300, o->t_end / 10, &o->dt_max, err)) ||
        (rc = cl_config_double(cfg, "stability", "dt_min", 1e-7, 1e-300,
                               o->dt_max, &o->dt_min, err)) ||
        (rc = cl_config_double(cfg, "stability", "rel", 0.02, 1e-6, 0.5,
                               &o->rel, err)))
        return rc;
    return cl_config_long(cfg, "stability", "checks", 20, 1, 100000,
                          &o->checks, err);
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
    cl_status rc = cl_cli_methods_try(m, s->m, s->nm, err);
    for (int k = 0; !rc && k < s->nm; k++)
        rc = cl_stab_check(m, s->m[k].type, &s->so, err);
    if (rc || job->quiet)
        return rc;
    char shape[96];
    printf("problem    %s (%s, %zu free), T = %g s, max_stretch %g, %ld "
           "checks per run\n", job->problem,
           cl_cloth_shape(c, shape, sizeof shape), c->nfree, s->so.t_end,
           s->so.max_stretch, s->so.checks);
    return CL_OK;
}

static cl_status run_one(cl_model *m, void *ctx, int k, void *result,
                         cl_error *err)
{
    const stab_setup *s = ctx;
    cl_stab_result *r = result;
    cl_status rc = cl_stability(m, s->m[k].type, &s->m[k].io, &s->so, r,
                                err);
    r->label = s->m[k].label;
    return rc;
}

static void rows(FILE *fp, const void *result, bool header)
{
    cl_stab_write_rows(fp, result, header);
}

static const cl_cli_study stab_study = {
    .csv = "stability.csv",
    .columns = "integrator           stable dt unstable dt  runs  why the "
               "unstable run failed",
    .size = sizeof(cl_stab_result), .begin = begin,
    .run = run_one, .print = print_result, .rows = rows};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const stab_setup *s = ctx;
    return cl_cli_study_run(m, job, &stab_study, s->nm, ctx, err);
}

int cl_cmd_stability(int argc, char **argv)
{
    stab_setup s = {0};
    return cl_cli_problem_main(argc, argv, &stab_spec, read_setup, study, &s);
}
