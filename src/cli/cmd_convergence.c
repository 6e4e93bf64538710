/* clothode convergence PROBLEM: observed orders of integrators against a
 * tight reference (analysis/convergence.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/convergence.h"
#include "analysis/sweep_table.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

/* The study: integrators with their options, levels, reference. */
typedef struct {
    cl_cli_args a;
    cl_cli_methods integrators;
    cl_cli_run run;
    long levels;
    cl_conv_opts co;
    cl_conv_ref ref;
    const cl_cli_study *study; /* convergence or workprecision */
    const char *from;          /* --from-sweep TABLE, or NULL */
    cl_sweep_table table;      /* its rows of this problem */
} conv_setup;

static const cl_cli_opt conv_rows[] = {
    {.name = "integrator", .arg = "LIST", .type = CL_CLI_METHODS,
     .sec = "run", .key = "integrator", .sdef = "cvode-bdf",
     .hi = CL_CLI_MAX_METHODS, .field = offsetof(conv_setup, integrators),
     .help = "integrators, comma-separated, each NAME or NAME:LINSOL "
             "(cvode-bdf:pcg)"},
    /* dt and rtol, atol: the first level of the fixed-step and of the
     * adaptive integrators */
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows,
     .unread = CL_CLI_RUN_OUTPUTS, .field = offsetof(conv_setup, run)},
    {.name = "levels", .arg = "K", .type = CL_CLI_LONG,
     .sec = "convergence", .key = "levels", .def = 5, .lo = 2,
     .hi = CL_CONV_MAX_LEVELS, .field = offsetof(conv_setup, levels),
     .help = "levels per integrator"},
    {.name = "ref-rtol", .arg = "R", .type = CL_CLI_DOUBLE,
     .sec = "convergence", .key = "ref_rtol", .def = 1e-11, .lo = 1e-15,
     .hi = 1e-4, .field = offsetof(conv_setup, co.ref_rtol),
     .help = "reference tolerance (atol R/100)"},
    {.name = "from-sweep", .arg = "TABLE", .type = CL_CLI_STRING,
     .field = offsetof(conv_setup, from),
     .help = "take the levels from a table of 'clothode sweep collect' "
             "(a sweep with a reference) instead of running them"},
    CL_CLI_TAIL(conv_setup, "no table on stdout"),
    {.type = CL_CLI_END}};

static const char conv_notes[] =
    "The first level of a fixed-step integrator is --dt, of an adaptive one\n"
    "--rtol and --atol; an adaptive one chooses its own initial step.  The\n"
    "reference's floors are its distances, in positions and velocities, to\n"
    "a run at 10x its rtol; levels within 3 floors in positions (too close\n"
    "to the reference's own error), and failed levels (as in run, a final\n"
    "stretch d/L beyond [run] max_stretch counts as a blow-up), are left out\n"
    "of the fits, levels within 3 floors in velocities out of the velocity\n"
    "fit.\n"
    "Problems that tear are refused.  With --from-sweep the levels are the\n"
    "sweep's runs of each integrator (its dt or rtol axis; the rows whose\n"
    "other axes match this problem's values) and their errors against the\n"
    "sweep's reference; every complete level is fitted.\n";

static const cl_cli_table conv_table = {
    .cmd = "convergence", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = conv_rows, .notes = conv_notes,
    .about =
    "Run each integrator at a sequence of levels to T and measure the final\n"
    "state against a tight cvode-bdf reference: fixed-step methods at dt,\n"
    "dt/2, dt/4, ..., adaptive ones at rtol, rtol/10, ... (atol alike).\n"
    "Prints the errors, the order between levels and the least-squares\n"
    "order; writes convergence.csv into the output directory.\n"};

static const cl_cli_table wp_table = {
    .cmd = "workprecision", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = conv_rows, .notes = conv_notes,
    .about =
    "The runs of clothode convergence (the same options), ranked by cost:\n"
    "each integrator, or integrator:linsol (cvode-bdf:pcg), at its levels\n"
    "with the error reached and its CPU time; then, for every decade of\n"
    "error, the integrator that reached it in the least CPU time and the\n"
    "others' times relative to it.  One run per level: repeat for timing\n"
    "noise.  Writes workprecision.csv (the columns of convergence.csv).\n"};

static cl_status check_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    conv_setup *s = ctx;
    /* the levels' own options, which a sweep's table does not use (the
     * rows of conv_table are wp_table's) */
    static const char *const runs[] = {"levels", "ref-rtol", NULL};
    cl_status rc = cl_cli_refuse_unless(cfg, &conv_table, runs, !s->from,
                                        "levels run here (not "
                                        "--from-sweep)", err);
    if (!rc)
        rc = cl_cli_methods_check(cfg, &s->integrators, &s->run.io,
                                  s->from ? CL_CLI_DT_NONE
                                          : CL_CLI_DT_FIXED, err);
    s->co.ref_linsol = "";
    s->co.max_stretch = s->run.max_stretch;
    if (!rc)
        rc = cl_cli_span(cfg, s->run.t_end, &s->co.t_end, err);
    for (int k = 0; !rc && !s->from && k < s->integrators.n; k++)
        rc = cl_conv_check(s->integrators.m[k].type, &s->integrators.m[k].io,
                           (int)s->levels, &s->co, err);
    if (!rc && s->from && !(rc = cl_sweep_table_read(s->from, &s->table,
                                                     err)))
        rc = cl_sweep_table_select(&s->table, cfg, "convergence", err);
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
               !l->fitted     ? "  (within 3 floors of the reference)"
               : !l->fitted_v ? "  (velocity within 3 floors)"
                              : "");
    }
    if (r->nfit < 2)
        printf("%-18s %s: no fit, fewer than 2 levels above 3 floors\n",
               "", r->label);
    else if (r->nfit_v == r->nfit)
        printf("%-18s %s: fitted order %.2f (positions), %.2f (velocities) "
               "over %d levels\n", "", r->label, r->slope_x,
               r->slope_v, r->nfit);
    else
        printf("%-18s %s: fitted order %.2f (positions, %d levels), %.2f "
               "(velocities, %d)\n", "", r->label, r->slope_x, r->nfit,
               r->slope_v, r->nfit_v);
}

/* The reference (which also checks that the model can be rerun), then
 * the header. */
static cl_status begin(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    conv_setup *s = ctx;
    const cl_cloth *c = cl_model_cloth(m);
    cl_status rc = cl_cli_methods_try(m, &s->integrators, err);
    if (rc || (!s->from && (rc = cl_conv_reference(m, &s->co, &s->ref,
                                                   err))) ||
        job->quiet)
        return rc;
    char shape[96];
    printf("problem    %s (%s, %zu free), T = %g s\n", job->problem,
           cl_cloth_shape(c, shape, sizeof shape), c->nfree, s->co.t_end);
    if (s->from)
        printf("runs       from the sweep table %s (errors against its "
               "reference)\n", s->from);
    else
        printf("reference  cvode-bdf rtol %g: %ld steps, floor %.2e m, "
               "%.2e m/s (distance to rtol %g)\n", s->co.ref_rtol,
               s->ref.stats.steps, s->ref.err_x, s->ref.err_v,
               10 * s->co.ref_rtol);
    return CL_OK;
}

static cl_status run_one(cl_model *m, void *ctx, int k, void *result,
                         cl_error *err)
{
    const conv_setup *s = ctx;
    cl_conv_result *r = result;
    const cl_cli_method *mk = &s->integrators.m[k];
    cl_status rc = s->from ? cl_conv_from_sweep(&s->table, mk->label,
                                                mk->type, r, err)
                           : cl_convergence(m, mk->type, &mk->io,
                                            (int)s->levels, &s->co, &s->ref,
                                            r, err);
    r->label = mk->label;
    return rc;
}

static void rows(FILE *fp, const void *result, bool header)
{
    cl_conv_write_rows(fp, result, header);
}

static void end(void *ctx)
{
    cl_conv_ref_free(&((conv_setup *)ctx)->ref);
    cl_sweep_table_free(&((conv_setup *)ctx)->table);
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
    int order[CL_CLI_MAX_METHODS], m = 0;
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
    .columns = "integrator          dt / rtol  err_x [m] err_v[m/s]   order"
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
    if (s->from && cl_sweep_table_same_inputs(&s->table, job->cfg, err))
        return err->code;
    return cl_cli_study_run(m, job, s->study, s->integrators.n, ctx, err);
}

/* The table is freed by end() once the study started, else here. */
static int conv_main(int argc, char **argv, const cl_cli_table *t,
                     conv_setup *s)
{
    int status = cl_cli_problem_main(argc, argv, t, s, check_setup, study);
    cl_sweep_table_free(&s->table);
    return status;
}

int cl_cmd_convergence(int argc, char **argv)
{
    conv_setup s = {.study = &conv_study};
    return conv_main(argc, argv, &conv_table, &s);
}

int cl_cmd_workprecision(int argc, char **argv)
{
    conv_setup s = {.study = &wp_study};
    return conv_main(argc, argv, &wp_table, &s);
}
