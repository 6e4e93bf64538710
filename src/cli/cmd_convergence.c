/* clothode convergence PROBLEM: observed orders of integrators against a
 * tight reference (analysis/convergence.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/convergence.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

#define CONV_MAX_METHODS 32

static const char conv_help[] =
    "usage: clothode convergence PROBLEM [options]\n"
    "Run each integrator at a sequence of levels to T and measure the final\n"
    "state against a tight cvode-bdf reference: fixed-step methods at dt,\n"
    "dt/2, dt/4, ..., adaptive ones at rtol, rtol/10, ... (atol alike).\n"
    "Prints the errors, the order between levels and the least-squares\n"
    "order; writes convergence.csv into the output directory.\n"
    "\n"
    "  --integrator LIST  integrators, comma-separated, each NAME or\n"
    "                     NAME:LINSOL (cvode-bdf:pcg); [run] integrator\n"
    "  --dt H             first step of the fixed-step integrators (s); the\n"
    "                     adaptive ones choose their own initial step\n"
    "  --rtol R --atol A  first tolerances of the adaptive integrators\n"
    "  --levels K         levels per integrator, 2 .. 20 (default 5)\n"
    "  --t-end T          final time (s); [run] t_end\n"
    "  --ref-rtol R       reference tolerance (default 1e-11; atol R/100)\n"
    "  --linsol NAME      linear solver of implicit integrators\n"
    "  --max-order K      highest order of CVODE / IDA\n"
    CL_CLI_HELP_OUT_SET
    "  --quiet            no table on stdout\n"
    "  --help             this text\n"
    "The reference's floor is its distance to a run at 10x its rtol; levels\n"
    "below the floor, and failed levels (as in run, a final stretch d/L\n"
    "beyond [run] max_stretch counts as a blow-up), are left out of the fit.\n"
    "Other [run] keys (newton_tol, lin_tol, ...) apply as in run.  Problems\n"
    "that tear are refused.\n";

static const struct option conv_opts[] = {
    {"integrator", required_argument, 0, 'i'},
    {"dt", required_argument, 0, 'd'},
    {"rtol", required_argument, 0, 'r'},
    {"atol", required_argument, 0, 'a'},
    {"levels", required_argument, 0, 'L'},
    {"t-end", required_argument, 0, 't'},
    {"ref-rtol", required_argument, 0, 'R'},
    {"linsol", required_argument, 0, 'l'},
    {"max-order", required_argument, 0, 'm'},
    CL_CLI_OPTS_TAIL};
static const char *const conv_key[128] = {
    ['i'] = "run.integrator", ['d'] = "run.dt", ['r'] = "run.rtol",
    ['a'] = "run.atol", ['L'] = "convergence.levels", ['t'] = "run.t_end",
    ['R'] = "convergence.ref_rtol", ['l'] = "run.linsol",
    ['m'] = "run.max_order"};
static const char *const conv_label[128] = {
    ['i'] = "--integrator", ['d'] = "--dt", ['r'] = "--rtol",
    ['a'] = "--atol", ['L'] = "--levels", ['t'] = "--t-end",
    ['R'] = "--ref-rtol", ['l'] = "--linsol", ['m'] = "--max-order"};
static const cl_cli_spec conv_spec = {"convergence", conv_help, conv_opts,
                                      conv_key, conv_label};

static const char wp_help[] =
    "usage: clothode workprecision PROBLEM [options]\n"
    "The runs of clothode convergence (the same options), ranked by cost:\n"
    "each integrator, or integrator:linsol (cvode-bdf:pcg), at its levels\n"
    "with the error reached and its CPU time; then, for every decade of\n"
    "error, the integrator that reached it in the least CPU time and the\n"
    "others' times relative to it.  One run per level: repeat for timing\n"
    "noise.  Writes workprecision.csv (the columns of convergence.csv).\n";
static const cl_cli_spec wp_spec = {"workprecision", wp_help, conv_opts,
                                    conv_key, conv_label};

/* The study: integrators with their options, levels, reference. */
typedef struct {
    int nm;
    cl_cli_method m[CONV_MAX_METHODS];
    long levels;
    cl_conv_opts co;
    cl_conv_ref ref;
    const cl_cli_study *study; /* convergence or workprecision */
} conv_setup;

/* The integrators of [run] integrator; an adaptive one picks its own
 * first step (dt is for the fixed-step ones). */
static cl_status read_methods(cl_config *cfg, conv_setup *s, cl_error *err)
{
    cl_status rc = cl_cli_methods(cfg, true, CONV_MAX_METHODS, s->m, &s->nm,
                                  err);
    for (int k = 0; !rc && k < s->nm; k++)
        if (!s->m[k].type->fixed_step)
            s->m[k].io.dt = 0.0;
    return rc;
}

static cl_status read_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    conv_setup *s = ctx;
    cl_status rc;
    s->co.ref_linsol = "";
    if ((rc = read_methods(cfg, s, err)) ||
        (rc = cl_config_double(cfg, "run", "t_end", 2.0, 1e-300, INFINITY,
                               &s->co.t_end, err)) ||
        (rc = cl_config_double(cfg, "run", "max_stretch", 10.0, 1.0,
                               INFINITY, &s->co.max_stretch, err)) ||
        (rc = cl_config_long(cfg, "convergence", "levels", 5, 2,
                             CL_CONV_MAX_LEVELS, &s->levels, err)) ||
        (rc = cl_config_double(cfg, "convergence", "ref_rtol", 1e-11, 1e-15,
                               1e-4, &s->co.ref_rtol, err)))
        return rc;
    for (int k = 0; !rc && k < s->nm; k++)
        rc = cl_conv_check(s->m[k].type, &s->m[k].io, (int)s->levels,
                           &s->co, err);
    return rc;
}

static void print_result(const void *result)
{
    const cl_conv_result *r = result;
    for (int k = 0; k < r->nlev; k++) {
        const cl_conv_level *l = &r->lev[k];
        printf("%-18s %10.3e", k ? "" : r->label, l->param);
        if (l->rc) {
            printf("   failed: %s\n", l->why.msg);
            continue;
        }
        printf(" %10.3e %10.3e", l->err_x, l->err_v);
        if (isnan(l->order))
            printf(" %7s", "-");
        else
            printf(" %7.2f", l->order);
        printf(" %9ld %9.3f%s\n", l->stats.steps, l->stats.cpu,
               l->fitted ? "" : "  (below the reference's floor)");
    }
    if (r->nfit >= 2)
        printf("%-18s %s: fitted order %.2f (positions), %.2f (velocities) "
               "over %d levels\n", "", r->label, r->slope_x,
               r->slope_v, r->nfit);
    else
        printf("%-18s %s: no fit, fewer than 2 levels above the floor\n", "",
               r->label);
}

/* The reference (which also checks that the model can be rerun), then
 * the header. */
static cl_status begin(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    conv_setup *s = ctx;
    const cl_cloth *c = cl_model_cloth(m);
    cl_status rc = cl_cli_methods_try(m, s->m, s->nm, err);
    if (rc || (rc = cl_conv_reference(m, &s->co, &s->ref, err)) ||
        job->quiet)
        return rc;
    char shape[96];
    printf("problem    %s (%s, %zu free), T = %g s\n", job->problem,
           cl_cloth_shape(c, shape, sizeof shape), c->nfree, s->co.t_end);
    printf("reference  cvode-bdf rtol %g: %ld steps, floor %.2e m "
           "(distance to rtol %g)\n", s->co.ref_rtol, s->ref.stats.steps,
           s->ref.err_x, 10 * s->co.ref_rtol);
    return CL_OK;
}

static cl_status run_one(cl_model *m, void *ctx, int k, void *result,
                         cl_error *err)
{
    const conv_setup *s = ctx;
    cl_conv_result *r = result;
    cl_status rc = cl_convergence(m, s->m[k].type, &s->m[k].io,
                                  (int)s->levels, &s->co, &s->ref, r, err);
    r->label = s->m[k].label;
    return rc;
}

static void rows(FILE *fp, const void *result, bool header)
{
    cl_conv_write_rows(fp, result, header);
}

static void end(void *ctx)
{
    cl_conv_ref_free(&((conv_setup *)ctx)->ref);
}

/* ---- workprecision: the same runs, ranked by CPU time per accuracy ---- */

static void print_wp(const void *result)
{
    const cl_conv_result *r = result;
    for (int k = 0; k < r->nlev; k++) {
        const cl_conv_level *l = &r->lev[k];
        printf("%-18s %10.3e", k ? "" : r->label, l->param);
        if (l->rc)
            printf("   failed: %s\n", l->why.msg);
        else
            printf(" %10.3e %9.3f %9ld %9ld\n", l->err_x, l->stats.cpu,
                   l->stats.steps, l->stats.rhs_evals);
    }
}

/* One row per decade of error reached: the cheapest method and the
 * others' CPU time relative to it. */
static void print_ranking(const cl_conv_result *res, int n, double target)
{
    int order[CONV_MAX_METHODS], m = 0;
    for (int k = 0; k < n; k++)
        if (!isnan(cl_conv_cheapest(&res[k], target)))
            order[m++] = k;
    for (int i = 1; i < m; i++) /* insertion sort by CPU time */
        for (int j = i; j > 0 && cl_conv_cheapest(&res[order[j]], target) <
                                     cl_conv_cheapest(&res[order[j - 1]],
                                                      target); j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    double best = cl_conv_cheapest(&res[order[0]], target);
    printf("<= %-8.0e %-18s %8.3f s", target, res[order[0]].label, best);
    for (int i = 1; i < m; i++)
        printf("%s %s %.3gx", i == 1 ? "  then" : ",", res[order[i]].label,
               cl_conv_cheapest(&res[order[i]], target) / best);
    printf("\n");
}

static void summary_wp(const void *results, int n)
{
    const cl_conv_result *res = results;
    double lo = INFINITY, hi = 0.0;
    for (int k = 0; k < n; k++)
        for (int l = 0; l < res[k].nlev; l++)
            if (res[k].lev[l].fitted) {
                lo = fmin(lo, res[k].lev[l].err_x);
                hi = fmax(hi, res[k].lev[l].err_x);
            }
    if (!(lo <= hi))
        return;
    printf("%-11s %-18s %10s\n", "error [m]", "fastest", "cpu");
    for (double t = pow(10, ceil(log10(lo))); t <= 10 * hi; t *= 10)
        print_ranking(res, n, t);
}

static const cl_cli_study conv_study = {
    .csv = "convergence.csv",
    .columns = "integrator          dt / rtol  err_x [m]      err_v   order"
               "     steps   cpu [s]",
    .size = sizeof(cl_conv_result),
    .begin = begin, .run = run_one, .print = print_result, .rows = rows,
    .end = end};

static const cl_cli_study wp_study = {
    .csv = "workprecision.csv",
    .columns = "integrator          dt / rtol  err_x [m]   cpu [s]     steps"
               "       rhs",
    .size = sizeof(cl_conv_result),
    .begin = begin, .run = run_one, .print = print_wp,
    .summary = summary_wp, .rows = rows, .end = end};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const conv_setup *s = ctx;
    return cl_cli_study_run(m, job, s->study, s->nm, ctx, err);
}

int cl_cmd_convergence(int argc, char **argv)
{
    conv_setup s = {.study = &conv_study};
    return cl_cli_problem_main(argc, argv, &conv_spec, read_setup, study, &s);
}

int cl_cmd_workprecision(int argc, char **argv)
{
    conv_setup s = {.study = &wp_study};
    return cl_cli_problem_main(argc, argv, &wp_spec, read_setup, study, &s);
}
