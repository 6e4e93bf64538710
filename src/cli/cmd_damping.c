/* clothode damping PROBLEM: the numerical damping of the implicit
 * fixed-step integrators against w h (analysis/numdamp.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/numdamp.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

typedef struct {
    cl_cli_args a;
    cl_cli_methods integrators;
    cl_cli_run run;
    const char *range;   /* --wh LO:HI:N */
    long steps;
    double modes_t, modes_dt, speed; /* the cloth study (modes_t > 0) */
    bool equilibrium;    /* ... from the static equilibrium */
    double wh[CL_NUMDAMP_MAX_WH];
    int nwh;
    double w;
    cl_numdamp_modes basis;
} nd_setup;

/* The registry's implicit fixed-step integrators, the default of
 * --integrator (filled by cl_cmd_damping). */
static char nd_default[1024];

static cl_cli_opt nd_rows[] = {
    {.name = "integrator", .arg = "LIST", .type = CL_CLI_METHODS,
     .sec = "damping", .key = "integrator", .sdef = nd_default,
     .hi = CL_CLI_MAX_METHODS, .field = offsetof(nd_setup, integrators),
     .help = "fixed-step integrators, comma-separated, each NAME or "
             "NAME:LINSOL (default: every implicit fixed-step one)"},
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows,
     .hide = "rtol atol max-order", .unread = "dt t-end " CL_CLI_RUN_OUTPUTS,
     .field = offsetof(nd_setup, run)},
    {.name = "wh", .arg = "LO:HI:N", .type = CL_CLI_STRING, .sec = "damping",
     .key = "wh", .sdef = "0.1:100:13", .field = offsetof(nd_setup, range),
     .help = "values of w h, N >= 2 spread evenly in log from LO to HI"},
    {.name = "steps", .arg = "N", .type = CL_CLI_LONG, .sec = "damping",
     .key = "steps", .def = 200, .lo = 4, .hi = 10000000,
     .field = offsetof(nd_setup, steps), .help = "steps of each run"},
    {.name = "modes", .arg = "T", .type = CL_CLI_DOUBLE, .sec = "damping",
     .key = "modes_t", .def = 0, .lo = 0, .hi = INFINITY,
     .field = offsetof(nd_setup, modes_t),
     .help = "the cloth study instead: energy per eigenmode after T s, 0 "
             "for the oscillator study"},
    {.name = "modes-dt", .arg = "H", .type = CL_CLI_DOUBLE, .sec = "damping",
     .key = "modes_dt", .def = 1e-2, .lo = 1e-300, .hi = INFINITY,
     .field = offsetof(nd_setup, modes_dt),
     .help = "--modes: the step (s), dividing T"},
    {.name = "speed", .arg = "V", .type = CL_CLI_DOUBLE, .sec = "damping",
     .key = "speed", .def = 1e-3, .lo = 1e-300, .hi = INFINITY,
     .field = offsetof(nd_setup, speed),
     .help = "--modes: the largest initial particle speed (m/s)"},
    {.name = "equilibrium", .type = CL_CLI_FLAG,
     .field = offsetof(nd_setup, equilibrium),
     .help = "--modes: from the static equilibrium of the problem (e.g. "
             "the hanging cloth under gravity) instead of its initial "
             "state"},
    CL_CLI_TAIL(nd_setup, "no table on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table nd_table = {
    .cmd = "damping", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = nd_rows,
    .about =
    "For each integrator and each w h (w the problem's fastest mode at its\n"
    "initial state, h = (w h)/w), runs the given steps from the initial\n"
    "state and fits the amplitude ratio per step from the energy after\n"
    "every step; prints it beside the theory (the integrator's\n"
    "amplification on the undamped oscillator: backward Euler\n"
    "1/sqrt(1 + (w h)^2), the midpoint rule 1, BDF2, generalized-alpha at\n"
    "[run] rho_inf; -- where there is no formula, as for the arkode-*\n"
    "methods, whose amplification depends on --table; nan in the file) and\n"
    "the loss per period, 1 - r^(2 pi/(w h)).  Writes damping.csv.  Meant\n"
    "for an undamped linear oscillator: spring2.\n"
    "With --modes T, on a cloth at rest instead: every oscillating mode of\n"
    "the linearised cloth gets the same energy, each integrator runs to T\n"
    "in steps of --modes-dt, and the energy left in each mode, beside the\n"
    "theory amplification(w dt)^(2 T/dt), goes to damping-modes.csv.\n"
    "With --equilibrium the modes are those of the static equilibrium\n"
    "(the hanging cloth: tension gives the out-of-plane, wrinkle modes a\n"
    "stiffness), each classed in-plane or out-of-plane by its normal\n"
    "fraction (column normal).\n",
    .notes =
    "The default integrators are every implicit fixed-step one of the\n"
    "registry (clothode list), found by its table; the problem's [run]\n"
    "integrator, t_end and dt are not used.  Problems that tear, and\n"
    "problems with obstacles or damping forces (whose motion the theory of\n"
    "an undamped oscillator does not describe), are refused.  A row is\n"
    "marked \"not settled\" when the ratios fitted over the two halves of\n"
    "its steps are more than 5 % apart (a second root nearly as large as\n"
    "the first, and few steps above the floor): the fit is not yet the\n"
    "step's spectral radius, and the table gives it to two digits.\n"};

/* "LO:HI:N" into s->wh. */
static cl_status read_range(cl_config *cfg, nd_setup *s, cl_error *err)
{
    double lo, hi;
    int n, used = 0;
    char why[128];
    if (sscanf(s->range, "%lf:%lf:%d%n", &lo, &hi, &n, &used) != 3 ||
        s->range[used] || !(lo > 0 && hi > lo && hi <= 1e6) || n < 2 ||
        n > CL_NUMDAMP_MAX_WH) {
        snprintf(why, sizeof why, "expected LO:HI:N with 0 < LO < HI <= 1e6 "
                 "and 2 <= N <= %d", CL_NUMDAMP_MAX_WH);
        return cl_config_refuse(cfg, "damping", "wh", CL_EINVAL, why, err);
    }
    for (int k = 0; k < n; k++)
        s->wh[k] = lo * pow(hi / lo, (double)k / (n - 1));
    s->nwh = n;
    return CL_OK;
}

static cl_status check_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    nd_setup *s = ctx;
    /* options of the cloth study only (--equilibrium, a flag, has no key) */
    static const char *const modes_only[] = {"modes-dt", "speed", NULL};
    const char *with = "--modes T (the cloth study)";
    if (s->equilibrium && !(s->modes_t > 0))
        return cl_error_set(err, CL_EINVAL, "--equilibrium goes with %s; "
                            "without it, it would be ignored", with);
    cl_status rc0 = cl_cli_refuse_unless(cfg, &nd_table, modes_only,
                                         s->modes_t > 0, with, err);
    if (rc0)
        return rc0;
    /* the problem's own [run] integrator is not this study's */
    cl_status rc = cl_cli_not_read(cfg, "damping", "run", "integrator", err);
    if (!rc)
        rc = cl_cli_methods_check(cfg, &s->integrators, &s->run.io,
                                        CL_CLI_DT_NONE, err);
    if (!rc)
        rc = cl_cli_methods_fixed(cfg, &s->integrators, "damping", err);
    return rc ? rc : read_range(cfg, s, err);
}

/* A spread of the two halves' ratios above it is marked: the fit is not
 * yet the spectral radius (analysis/numdamp.h). */
#define UNSETTLED 0.05

/* A not settled ratio to two digits (the halves differ in the second or
 * first); a theory the method has no formula for (region.h), "--". */
static void print_result(const void *result)
{
    const cl_numdamp_result *r = result;
    for (int i = 0; i < r->n; i++) {
        const cl_numdamp_point *p = &r->p[i];
        bool settled = !(p->spread > UNSETTLED);
        printf("%-18s %9.4g %11.4e %12.*g", i ? "" : r->label, p->wh, p->h,
               settled ? 6 : 2, p->measured);
        if (isnan(p->theory))
            printf(" %12s", "--");
        else
            printf(" %12.6g", p->theory);
        printf(" %11.4e", p->loss_period);
        if (p->rc)
            printf("  failed: %s", p->why.msg);
        else if (p->spread > UNSETTLED)
            printf("  (not settled: %ld steps, halves %.0f %% apart)",
                   p->fitted, 100 * p->spread);
        putchar('\n');
    }
}

static cl_status begin(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    nd_setup *s = ctx;
    cl_status rc = cl_cli_methods_try(m, &s->integrators, err);
    if (!rc)
        rc = cl_numdamp_frequency(m, &s->w, err);
    if (rc || job->quiet)
        return rc;
    printf("problem    %s, w = %.6g rad/s, %ld steps per run\n",
           job->problem, s->w, s->steps);
    return CL_OK;
}

static cl_status run_one(cl_model *m, void *ctx, int k, void *result,
                         cl_error *err)
{
    const nd_setup *s = ctx;
    cl_numdamp_result *r = result;
    const cl_cli_method *mk = &s->integrators.m[k];
    cl_status rc = cl_numdamp_run(m, mk->type, &mk->io, s->w, s->wh, s->nwh,
                                  s->steps, r, err);
    r->label = mk->label;
    return rc;
}

static void rows(FILE *fp, const void *result, bool header)
{
    cl_numdamp_write_rows(fp, result, header);
}

static const cl_cli_study nd_study = {
    .csv = "damping.csv",
    .columns = "integrator              w h       h [s]  measured |R|  "
               "theory |R|  loss/period",
    .size = sizeof(cl_numdamp_result), .begin = begin, .run = run_one,
    .print = print_result, .rows = rows};

/* ---- the cloth study (--modes) ------------------------------------------ */

/* The mean energy ratio over the slowest, middle or fastest third (third
 * 0, 1, 2) of the in-plane (out = false) or out-of-plane modes. */
static double third_mean(const cl_numdamp_modal *r, bool out, int third)
{
    size_t m = 0, j = 0, cnt = 0;
    double sum = 0.0;
    for (size_t k = 0; k < r->nosc; k++)
        m += (r->normal[k] > 0.5) == out;
    for (size_t k = 0; k < r->nosc; k++) {
        if ((r->normal[k] > 0.5) != out)
            continue;
        if (j >= m * (size_t)third / 3 && j < m * (size_t)(third + 1) / 3) {
            sum += r->ratio[k];
            cnt++;
        }
        j++;
    }
    return cnt ? sum / (double)cnt : NAN;
}

static void print_modal(const void *result)
{
    const cl_numdamp_modal *r = result;
    printf("%-18s", r->label);
    for (int g = 0; g < 6; g++)
        printf(" %9.3g", third_mean(r, g >= 3, g % 3));
    printf("%s%s\n", r->rc ? "  failed: " : "", r->rc ? r->why.msg : "");
}

static cl_status begin_modal(cl_model *m, const cl_cli_job *job, void *ctx,
                             cl_error *err)
{
    nd_setup *s = ctx;
    cl_status rc = cl_cli_methods_try(m, &s->integrators, err);
    if (!rc)
        rc = cl_numdamp_modes_init(m, s->speed, s->equilibrium, &s->basis,
                                   err);
    if (rc || job->quiet)
        return rc;
    size_t nout = 0, first = s->basis.n - s->basis.nosc;
    for (size_t k = first; k < s->basis.n; k++)
        nout += s->basis.normal[k] > 0.5;
    if (s->equilibrium)
        printf("equilibrium after %d steps, max |M^-1 f| = %.3g m/s^2; %zu "
               "buckling modes (mu < 0) left out\n", s->basis.eq.steps,
               s->basis.eq.residual, s->basis.nneg);
    printf("problem    %s, %zu oscillating modes (%zu in-plane, %zu "
           "out-of-plane), w %.4g .. %.4g rad/s, T = %g s, dt = %g s\n",
           job->problem, s->basis.nosc, s->basis.nosc - nout, nout,
           sqrt(s->basis.mu[s->basis.n - s->basis.nosc]),
           sqrt(s->basis.mu[s->basis.n - 1]), s->modes_t, s->modes_dt);
    printf("energy left E(T)/E(0), mean over the slowest, middle and fastest "
           "third of the in-plane and of the out-of-plane modes\n");
    return CL_OK;
}

static cl_status run_modal(cl_model *m, void *ctx, int k, void *result,
                           cl_error *err)
{
    nd_setup *s = ctx;
    cl_numdamp_modal *r = result;
    const cl_cli_method *mk = &s->integrators.m[k];
    cl_status rc = cl_numdamp_modal_run(m, &s->basis, mk->type, &mk->io,
                                        s->modes_dt, s->modes_t, r, err);
    r->label = mk->label;
    return rc;
}

static void rows_modal(FILE *fp, const void *result, bool header)
{
    cl_numdamp_modal_rows(fp, result, header);
}

static void release_modal(void *result)
{
    cl_numdamp_modal_free(result);
}

static void end_modal(void *ctx)
{
    nd_setup *s = ctx;
    cl_numdamp_modes_free(&s->basis);
}

static const cl_cli_study nd_modal_study = {
    .csv = "damping-modes.csv",
    .columns = "integrator           in slow    in mid   in fast  out slow   "
               "out mid  out fast",
    .size = sizeof(cl_numdamp_modal), .begin = begin_modal, .run = run_modal,
    .print = print_modal, .rows = rows_modal, .release = release_modal,
    .end = end_modal};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const nd_setup *s = ctx;
    return cl_cli_study_run(m, job, s->modes_t > 0 ? &nd_modal_study
                                                   : &nd_study,
                            s->integrators.n, ctx, err);
}

/* nd_default: the names of the integrators cl_numdamp_selects. */
static void default_list(void)
{
    size_t at = 0;
    nd_default[0] = '\0';
    for (size_t i = 0; cl_integrator_registry[i]; i++) {
        const cl_integrator_type *t = cl_integrator_registry[i];
        if (cl_numdamp_selects(t) && at < sizeof nd_default)
            at += (size_t)snprintf(nd_default + at, sizeof nd_default - at,
                                   "%s%s", at ? "," : "", t->name);
    }
}

int cl_cmd_damping(int argc, char **argv)
{
    nd_setup s = {0};
    default_list();
    return cl_cli_problem_main(argc, argv, &nd_table, &s, check_setup,
                               study);
}
