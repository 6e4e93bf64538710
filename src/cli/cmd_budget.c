/* clothode budget PROBLEM: substeps against iterations at an equal budget
 * per step (analysis/budget.h). */
#include <math.h>
#include <stdlib.h>

#include "analysis/budget.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

typedef struct {
    cl_cli_args a;
    cl_cli_methods integrators;
    cl_cli_run run;
    cl_budget_opts bo;
    double ref_rtol;       /* 0: no reference */
    cl_conv_ref ref;
} budget_setup;

static const cl_cli_opt budget_rows[] = {
    {.name = "integrator", .arg = "LIST", .type = CL_CLI_METHODS,
     .sec = "run", .key = "integrator", .sdef = "xpbd",
     .hi = CL_CLI_MAX_METHODS, .field = offsetof(budget_setup, integrators),
     .help = "fixed-step integrators, comma-separated (xpbd,pd,kinsol-be)"},
    /* budget sets substeps, iterations and newton_maxit for every split */
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows,
     .unread = "substeps iterations max-newton " CL_CLI_RUN_OUTPUTS,
     .field = offsetof(budget_setup, run)},
    {.name = "budget", .arg = "B", .type = CL_CLI_LONG, .sec = "budget",
     .key = "budget", .def = 8, .lo = 1, .hi = 1000,
     .field = offsetof(budget_setup, bo.budget),
     .help = "iterations per step dt, split as S substeps x K = B / S "
             "iterations for every divisor S of B"},
    {.name = "ref-rtol", .arg = "R", .type = CL_CLI_DOUBLE, .sec = "budget",
     .key = "ref_rtol", .def = 1e-10, .lo = 0, .hi = 1e-4,
     .field = offsetof(budget_setup, ref_rtol),
     .help = "tolerance of the cvode-bdf reference (atol R/100); 0 for "
             "none (hard constraints)"},
    CL_CLI_TAIL(budget_setup, "no table on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table budget_table = {
    .cmd = "budget", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = budget_rows,
    .notes =
    "A constraint method (xpbd, pd) runs at --dt with --substeps S and\n"
    "--iterations K; a Newton method (kinsol-*) at dt / S with\n"
    "at most K Newton iterations per step (run.newton_maxit: kinsol-be\n"
    "and kinsol-bdf2 at K = 1 take one linearisation per step); any other\n"
    "fixed-step method (semi-*, explicit) at dt / S with K = 1, its one\n"
    "solve or force evaluation a step, so only S = B spends the budget\n"
    "(h: dt / S, the step or substep).  arkode-* are refused: they cap each\n"
    "stage's iterations, not the step's.  The splits set [run] substeps,\n"
    "iterations and newton_maxit themselves: no options here, and --set\n"
    "refuses them.  err_x is the\n"
    "final distance to the reference (cvode-bdf, which does not apply pbd\n"
    "constraints: the reference line says so), stretch the largest d/L - 1\n"
    "of the nearest neighbours at 100 checks, energy E(T) - E(0), beside\n"
    "the reference's.\n",
    .about =
    "Spend a budget of B iterations per step dt as S substeps of K = B / S\n"
    "iterations, for every divisor S of B (Macklin et al., \"Small steps in\n"
    "physics simulation\"): the error, constraint violation, energy change\n"
    "and CPU time of each split.  Writes budget.csv into the output\n"
    "directory.\n"};

static cl_status check_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    budget_setup *s = ctx;
    cl_status rc = cl_cli_methods_check(cfg, &s->integrators, &s->run.io,
                                        CL_CLI_DT_FIXED, err);
    s->bo.max_stretch = s->run.max_stretch;
    if (!rc)
        rc = cl_cli_span(cfg, s->run.t_end, &s->bo.t_end, err);
    if (!rc)
        rc = cl_cli_methods_fixed(cfg, &s->integrators, "budget", err);
    for (int k = 0; !rc && k < s->integrators.n; k++)
        rc = cl_budget_check(s->integrators.m[k].type,
                             &s->integrators.m[k].io, &s->bo, err);
    return rc;
}

static void print_result(const void *result)
{
    const cl_budget_result *r = result;
    for (int k = 0; k < r->n; k++) {
        const cl_budget_split *l = &r->s[k];
        printf("%-14s %5ld %5ld %10.3e", k ? "" : r->label, l->S, l->K, l->h);
        if (l->rc)
            printf("   failed: %s\n", l->why.msg);
        else
            printf(" %10.3e %10.3e %11.3e %9.3f\n", l->err_x, l->stretch,
                   l->energy, l->stats.cpu);
    }
    if (r->n && !cl_budget_takes_k(r->type))
        printf("%-14s %s takes no K (a step of dt / S costs the same "
               "whatever K): only S = %ld spends the budget\n", "", r->label,
               r->s[r->n - 1].S);
}

static cl_status begin(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    budget_setup *s = ctx;
    cl_conv_opts co = {.t_end = s->bo.t_end,
                       .max_stretch = s->bo.max_stretch,
                       .ref_rtol = s->ref_rtol, .ref_linsol = ""};
    cl_status rc = cl_cli_methods_try(m, &s->integrators, err);
    if (rc || (s->ref_rtol > 0 && (rc = cl_conv_reference(m, &co, &s->ref,
                                                          err))) ||
        job->quiet)
        return rc;
    char shape[96];
    const cl_cloth *c = cl_model_cloth(m);
    printf("problem    %s (%s, %zu free), T = %g s, budget %ld per step "
           "dt = %g s\n", job->problem, cl_cloth_shape(c, shape, sizeof shape),
           c->nfree, s->bo.t_end, s->bo.budget, s->run.io.dt);
    if (s->ref_rtol > 0)
        printf("reference  cvode-bdf rtol %g: %ld steps, floor %.2e m, "
               "E(T) - E(0) = %.3e J%s\n", s->ref_rtol, s->ref.stats.steps,
               s->ref.err_x, cl_budget_reference_energy(m, &s->ref,
                                                        s->bo.t_end),
               cl_model_system(m)->project
                   ? " (without the pbd constraints, which it does not "
                     "apply: err_x counts their effect)"
                   : "");
    else
        printf("reference  none (err_x not measured)\n");
    return CL_OK;
}

static cl_status run_one(cl_model *m, void *ctx, int k, void *result,
                         cl_error *err)
{
    const budget_setup *s = ctx;
    const cl_cli_method *mk = &s->integrators.m[k];
    cl_budget_result *r = result;
    cl_status rc = cl_budget(m, mk->type, &mk->io, &s->bo,
                             s->ref_rtol > 0 ? &s->ref : NULL, r, err);
    r->label = mk->label;
    return rc;
}

static void rows(FILE *fp, const void *result, bool header)
{
    cl_budget_write_rows(fp, result, header);
}

static void end(void *ctx) { cl_conv_ref_free(&((budget_setup *)ctx)->ref); }

static const cl_cli_study budget_study = {
    .csv = "budget.csv",
    .columns = "integrator         S     K          h  err_x [m]    stretch"
               "  energy [J]   cpu [s]",
    .size = sizeof(cl_budget_result),
    .begin = begin, .run = run_one, .print = print_result, .rows = rows,
    .end = end};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const budget_setup *s = ctx;
    return cl_cli_study_run(m, job, &budget_study, s->integrators.n, ctx,
                            err);
}

int cl_cmd_budget(int argc, char **argv)
{
    budget_setup s = {0};
    return cl_cli_problem_main(argc, argv, &budget_table, &s, check_setup,
                               study);
}
