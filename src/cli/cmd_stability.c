/* clothode stability PROBLEM: the largest stable step of fixed-step
 * integrators (analysis/stability.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/contact_limit.h"
#include "analysis/stability.h"
#include "analysis/sweep.h"
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
    const char *axis;      /* --axis SECTION.KEY=VALUES, or "" */
    char key[128];         /* ... its key */
    char *original;        /* the problem's value of it (NULL: none) */
    cl_sweep_axis values;  /* ... and its values */
    cl_config *cfg;        /* the command's, where the values are set */
    cl_model *variant;     /* the model at the value being run ... */
    int variant_of;        /* ... its index, -1 none */
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
    /* [run] dt is not read: the search sets the step */
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows,
     .hide = "rtol atol max-order", .unread = "dt " CL_CLI_RUN_OUTPUTS,
     .field = offsetof(stab_setup, run)},
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
    {.name = "axis", .arg = "KEY=VALUES", .type = CL_CLI_STRING,
     .sec = "stability", .key = "axis", .field = offsetof(stab_setup, axis),
     .help = "the search at every value of a problem key (SECTION.KEY = a "
             "list, linspace(a, b, k) or logspace(a, b, k), as a sweep "
             "axis), beside the spectrum's prediction at the initial state; "
             "writes limits.csv"},
    CL_CLI_TAIL(stab_setup, "no table on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table stab_table = {
    .cmd = "stability", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = stab_rows,
    .about =
    "For each fixed-step integrator, the largest step dt = T/N with which a\n"
    "run to T stays bounded: N doubles from T/dt_max until a run and the\n"
    "run at twice its N are stable, then bisection brackets the limit.  A\n"
    "run is unstable when its state\n"
    "becomes non-finite, its stretch d/L exceeds [run] max_stretch at one of\n"
    "the checks, or its solver gives up.  d/L: the largest stretch the\n"
    "stable end's checks saw.  Writes every run to stability.csv in the\n"
    "output directory.\n",
    .notes =
    "The other [run] keys apply as in run; [run] dt is not used.  Stability\n"
    "need not be monotone in dt: the bracket is the one the search found.\n"
    "Bounded to T is the test, so the limit depends on T: just above a\n"
    "linear limit an instability grows slowly and may not reach\n"
    "max_stretch by T (a stable end's d/L well above the cloth's own says\n"
    "so); the limit is an upper bound of what a longer run keeps.\n"
    "Problems that tear are refused.  With --from-sweep the runs are the\n"
    "sweep's (its dt axis; the rows whose other axes match this problem's\n"
    "values): complete runs are stable, failed runs that got going are not;\n"
    "the bracket is the smallest unstable dt and the largest stable one\n"
    "below it.  With --axis KEY=VALUES (e.g. type1.ks=logspace(2, 7, 6))\n"
    "the search is made at every value of KEY (the sweep's rows of that\n"
    "value with --from-sweep), beside the spectrum's prediction at the\n"
    "initial state (as clothode spectrum), and the slope of log dt against\n"
    "log KEY is fitted for each method, measured (the geometric mean of\n"
    "each bracket) and predicted; writes limits.csv.\n"};

/* ---- --axis: the search at every value of a key ------------------------- */

/* The model at value v into s->variant, the table's rows of it selected
 * (the key set as --set would, then put back). */
static cl_status use_value(stab_setup *s, int v, cl_error *err)
{
    char a[512];
    if (s->variant_of == v)
        return CL_OK;
    cl_model_free(s->variant);
    s->variant = NULL;
    s->variant_of = -1;
    snprintf(a, sizeof a, "%s=%s", s->key, s->values.v[v]);
    cl_status rc = cl_config_set_as(s->cfg, a, "--axis", err);
    if (!rc && s->from)
        rc = cl_sweep_table_select(&s->table, s->cfg, "stability", err);
    if (!rc && !(rc = cl_cli_model_create(s->cfg, &s->variant, err)))
        s->variant_of = v;
    snprintf(a, sizeof a, "%s=%s", s->key, s->original ? s->original : "");
    if (s->original && !rc)
        rc = cl_config_set(s->cfg, a, err);
    return rc;
}

/* KEY=VALUES read, and the model at every value built and checked. */
static cl_status read_axis(cl_config *cfg, stab_setup *s, cl_error *err)
{
    const char *eq = strchr(s->axis, '='), *dot;
    bool ok = eq && eq - s->axis < (long)sizeof s->key;
    if (ok) {
        snprintf(s->key, sizeof s->key, "%.*s", (int)(eq - s->axis),
                 s->axis);
        dot = strrchr(s->key, '.');
        ok = dot && dot > s->key && dot[1];
    }
    cl_status rc = ok ? cl_sweep_axis_values(&s->values, eq + 1, &ok)
                      : CL_OK;
    if (rc)
        return cl_error_set(err, rc, "out of memory");
    if (!ok)
        return cl_config_refuse(cfg, "stability", "axis", CL_EINVAL,
                                "expected SECTION.KEY=VALUES, the values a "
                                "list, linspace(a, b, k) or logspace(a, b, "
                                "k)", err);
    char sec[128], *end;
    snprintf(sec, sizeof sec, "%.*s", (int)(strrchr(s->key, '.') - s->key),
             s->key);
    if (!strcmp(sec, "run"))
        return cl_config_refuse(cfg, "stability", "axis", CL_EINVAL,
                                "a [run] key is the search's own setting "
                                "(its step is what it searches, its "
                                "integrators --integrator's); the axis is a "
                                "key of the model", err);
    for (int v = 0; v < s->values.n; v++) {
        (void)strtod(s->values.v[v], &end);
        if (end == s->values.v[v] || *end)
            return cl_config_refuse(cfg, "stability", "axis", CL_EINVAL,
                                    "every value must be a number (the "
                                    "limits are fitted against it)", err);
    }
    const char *was = cl_config_peek(cfg, sec, strrchr(s->key, '.') + 1);
    if (was && !(s->original = strdup(was)))
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    for (int v = 0; !rc && v < s->values.n; v++) {
        if (!(rc = use_value(s, v, err)) && v == 0)
            /* the model has read every key of the problem: a key it does
             * not know (a misspelt axis) is left unread */
            rc = cl_config_check_unused(cfg, err);
        if (!rc && !(rc = cl_cli_methods_try(s->variant, &s->integrators, err)))
            for (int k = 0; !rc && k < s->integrators.n; k++)
                rc = cl_stab_check(s->variant, s->integrators.m[k].type,
                                   &s->so, err);
    }
    return rc;
}

/* Least-squares slope of log y against log x over the pairs with both
 * finite and > 0; NaN with fewer than two. */
static double log_slope(const double *x, const double *y, int n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    for (int k = 0; k < n; k++) {
        if (!(x[k] > 0 && y[k] > 0 && isfinite(x[k]) && isfinite(y[k])))
            continue;
        double a = log(x[k]), b = log(y[k]);
        sx += a, sy += b, sxx += a * a, sxy += a * b, m++;
    }
    double d = m * sxx - sx * sx;
    return m >= 2 && d > 0 ? (m * sxy - sx * sy) / d : NAN;
}

static void print_axis_result(const void *result)
{
    cl_climit_print(stdout, result);
}

static cl_status begin_axis(cl_model *m, const cl_cli_job *job, void *ctx,
                            cl_error *err)
{
    const stab_setup *s = ctx;
    (void)m;
    (void)err;
    if (!job->quiet)
        printf("problem    %s, T = %g s, max_stretch %g, %ld checks per run; "
               "%d values of %s%s%s\n", job->problem, s->so.t_end,
               s->so.max_stretch, s->so.checks, s->values.n, s->key,
               s->from ? ", runs from the sweep table " : "",
               s->from ? s->from : "");
    return CL_OK;
}

static cl_status run_axis(cl_model *m, void *ctx, int k, void *result,
                          cl_error *err)
{
    stab_setup *s = ctx;
    cl_climit_result *r = result;
    const cl_cli_method *mk = &s->integrators.m[k % s->integrators.n];
    int v = k / s->integrators.n;
    (void)m;
    cl_status rc = use_value(s, v, err);
    size_t n = rc ? 0 : cl_model_system(s->variant)->n;
    double *x = rc ? NULL : malloc(2 * n * sizeof *x);
    if (!rc && !x)
        rc = cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!rc && cl_model_initial_state(s->variant, x, x + n))
        rc = cl_error_set(err, CL_EINVAL, "no initial state at %s = %s",
                          s->key, s->values.v[v]);
    if (!rc)
        rc = cl_climit_predict(s->variant, mk->type, 0.0, x, x + n, r, err);
    free(x);
    if (!rc)
        rc = cl_stab_limit(s->from ? &s->table : NULL, s->variant, mk->label,
                           mk->type, &mk->io, &s->so, &r->stab, err);
    r->label = mk->label;
    r->k = strtod(s->values.v[v], NULL);
    return rc;
}

/* For each method, the fitted slopes of log dt against log KEY. */
static void axis_summary(const void *results, int n)
{
    const cl_climit_result *r = results;
    printf("slope of log dt against log KEY   measured   predicted\n");
    for (int i = 0; i < n; i++) {
        double x[64], yo[64], yp[64];
        int m = 0;
        bool first = true;
        for (int j = 0; j < i && first; j++)
            first = strcmp(r[j].label, r[i].label) != 0;
        for (int j = i; first && j < n && m < 64; j++) {
            if (strcmp(r[j].label, r[i].label))
                continue;
            x[m] = r[j].k;
            yo[m] = sqrt(r[j].stab.dt_stable * r[j].stab.dt_unstable);
            yp[m++] = r[j].predicted;
        }
        if (first)
            printf("%-33s %9.3f %11.3f\n", r[i].label, log_slope(x, yo, m),
                   log_slope(x, yp, m));
    }
}

static void axis_rows(FILE *fp, const void *result, bool header)
{
    const cl_climit_result *r = result;
    if (header)
        fputs("integrator,value,dt_stable,dt_unstable,predicted,w_max,"
              "runs\n", fp);
    fprintf(fp, "%s,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n", r->label, r->k,
            r->stab.dt_stable, r->stab.dt_unstable, r->predicted, r->w_max,
            r->stab.ntrial);
}

static void end_axis(void *ctx)
{
    stab_setup *s = ctx;
    cl_model_free(s->variant);
    s->variant = NULL;
    s->variant_of = -1;
    cl_sweep_table_free(&s->table);
}

static const cl_cli_study axis_study = {
    .csv = "limits.csv",
    .columns = "integrator              value   stable dt unstable dt "
               "predicted dt w_max [1/s]  runs",
    .size = sizeof(cl_climit_result), .begin = begin_axis,
    .run = run_axis, .print = print_axis_result, .summary = axis_summary,
    .rows = axis_rows, .end = end_axis};

/* ---- the command -------------------------------------------------------- */

/* Only fixed-step integrators have a step to limit. */
static cl_status check_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    stab_setup *s = ctx;
    /* the search's own options, which a sweep's table does not use */
    static const char *const search[] = {"dt-max", "dt-min", "rel", NULL};
    cl_status rc = cl_cli_refuse_unless(cfg, &stab_table, search, !s->from,
                                        "a search of its own (not "
                                        "--from-sweep)", err);
    if (!rc)
        rc = cl_cli_methods_check(cfg, &s->integrators, &s->run.io,
                                  CL_CLI_DT_NONE, err);
    if (!rc)
        rc = cl_cli_methods_fixed(cfg, &s->integrators, "stability", err);
    if (rc)
        return rc;
    s->so.max_stretch = s->run.max_stretch;
    s->cfg = cfg;
    s->variant_of = -1;
    if (s->from && !(rc = cl_sweep_table_read(s->from, &s->table, err)) &&
        !*s->axis)
        rc = cl_sweep_table_select(&s->table, cfg, "stability", err);
    /* from [init] time (the sweep's, once selected) to t_end */
    if (!rc && !(rc = cl_cli_span(cfg, s->run.t_end, &s->so.t_end, err)))
        s->so.dt_max = cl_cli_dt_max(cfg, "stability", s->so.dt_max,
                                     s->so.t_end);
    if (!rc && *s->axis)
        rc = read_axis(cfg, s, err);
    return rc;
}

static void print_result(const void *result)
{
    const cl_stab_result *r = result;
    /* the stable end's stretch: "-" when not known (a sweep's runs) */
    double held = r->held >= 0 ? r->trial[r->held].stretch : NAN;
    char dl[16] = "-";
    if (!isnan(held))
        snprintf(dl, sizeof dl, "%.3g", held);
    printf("%-18s ", r->label);
    if (isnan(r->dt_unstable))
        printf("stable at dt_max = %.4g (%d %s, d/L %s%s)\n", r->dt_stable,
               r->ntrial, r->ntrial == 1 ? "run" : "runs", dl,
               r->ntrial == 1 && !isnan(held) /* the search's, not a sweep's */
                   ? "; dt_max / 2 is below --dt-min: unconfirmed"
                   : "");
    else if (isnan(r->dt_stable))
        printf("%11s %6s %11.4g %5d  %s\n", "none", "-", r->dt_unstable,
               r->ntrial, r->trial[r->failed].why.msg);
    else
        printf("%11.4g %6s %11.4g %5d  %s\n", r->dt_stable, dl,
               r->dt_unstable, r->ntrial, r->trial[r->failed].why.msg);
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
    cl_status rc = cl_stab_limit(s->from ? &s->table : NULL, m, mk->label,
                                 mk->type, &mk->io, &s->so, r, err);
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
    .columns = "integrator           stable dt    d/L unstable dt  runs  why "
               "the unstable run failed",
    .size = sizeof(cl_stab_result), .begin = begin,
    .run = run_one, .print = print_result, .rows = rows, .end = end};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    const stab_setup *s = ctx;
    if (s->from && cl_sweep_table_same_inputs(&s->table, job->cfg, err))
        return err->code;
    if (*s->axis)
        return cl_cli_study_run(m, job, &axis_study,
                                s->values.n * s->integrators.n, ctx, err);
    return cl_cli_study_run(m, job, &stab_study, s->integrators.n, ctx,
                            err);
}

int cl_cmd_stability(int argc, char **argv)
{
    stab_setup s = {0};
    int status = cl_cli_problem_main(argc, argv, &stab_table, &s,
                                     check_setup, study);
    cl_sweep_table_free(&s.table); /* when the study did not start */
    cl_model_free(s.variant);
    cl_sweep_strings_free(s.values.v, s.values.n);
    free(s.original);
    return status;
}
