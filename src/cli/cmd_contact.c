/* clothode contact PROBLEM: contact responses against the step
 * (analysis/contact_study.h), and the explicit limit against the penalty
 * stiffness beside the spectrum's prediction (analysis/contact_limit.h).
 *
 * Every response of --response and every stiffness of --k is a variant of
 * the problem: the same file and assignments with `response` (and `k`)
 * of every [obstacle.NAME] overridden, as `--set obstacle.NAME.response=R`
 * would, so any response the obstacle parser accepts is studied.  The
 * variants are built once before the study starts (a response or key
 * they refuse stops it there), on the command's configuration, so that a
 * key counts as used when any variant reads it; each is built again for
 * its runs, and the original values are put back in between. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/contact_limit.h"
#include "analysis/contact_study.h"
#include "analysis/sweep_table.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/study.h"

#define CT_MAX_RESP 8
#define CT_MAX_K 12
#define CT_MAX_OBS 16

typedef struct {
    char sec[96];
    char *response, *k; /* the values before any variant (NULL: absent) */
} ct_obstacle;

typedef struct {
    cl_cli_args a;
    cl_cli_methods integrators;
    cl_cli_run run;
    const char *responses, *dts, *ks;
    const char *state;    /* --k: the state of the prediction, "": initial */
    double t;             /* ... its time */
    long checks;
    double dt_max, dt_min, rel;
    cl_stab_opts so;
    int ndt, nresp, nk, nobs;
    double dt[CL_CSTUDY_MAX_DT], k[CT_MAX_K];
    char resp[CT_MAX_RESP][32];
    ct_obstacle obs[CT_MAX_OBS];
    cl_config *cfg;       /* the command's, where variants are applied */
    cl_model *variant;    /* the model of the variant being run */
    int variant_of;       /* ... its index, -1 none */
    double *x, *v;        /* --k: the free state of the prediction */
    const char *from;     /* --from-sweep TABLE, or NULL */
    cl_sweep_table table; /* its rows of the variant being run */
} ct_setup;

/* --k's search range, as stability's: dt_max (read first, while the
 * field is still 0) defaults to T/100 and is at most T/10; dt_min is at
 * most dt_max. */
static void search_bounds(const void *settings, double *def, double *hi)
{
    const ct_setup *s = settings;
    if (s->dt_max == 0.0) {
        *def = s->run.t_end / 100;
        *hi = s->run.t_end / 10;
    } else {
        *hi = s->dt_max;
    }
}

static const cl_cli_opt ct_rows[] = {
    {.name = "integrator", .arg = "LIST", .type = CL_CLI_METHODS,
     .sec = "run", .key = "integrator", .sdef = "symplectic-euler",
     .hi = CL_CLI_MAX_METHODS, .field = offsetof(ct_setup, integrators),
     .help = "fixed-step integrators, comma-separated, each NAME or "
             "NAME:LINSOL"},
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows,
     .hide = "rtol atol max-order", .unread = "dt " CL_CLI_RUN_OUTPUTS,
     .field = offsetof(ct_setup, run)},
    {.name = "response", .arg = "LIST", .type = CL_CLI_STRING,
     .sec = "contact", .key = "response", .field = offsetof(ct_setup, responses),
     .help = "responses, comma-separated, each given to every obstacle "
             "(default: the problem's own)"},
    {.name = "dt", .arg = "LIST", .type = CL_CLI_STRING, .sec = "contact",
     .key = "dt", .field = offsetof(ct_setup, dts),
     .help = "steps (s), comma-separated, or LO:HI:N for N steps spread "
             "evenly in log from LO to HI; each must divide T"},
    {.name = "checks", .arg = "K", .type = CL_CLI_LONG, .sec = "contact",
     .key = "checks", .def = 20, .lo = 1, .hi = 100000,
     .field = offsetof(ct_setup, checks), .help = "stretch tests per run"},
    {.name = "k", .arg = "LIST", .type = CL_CLI_STRING, .sec = "contact",
     .key = "k", .field = offsetof(ct_setup, ks),
     .help = "penalty stiffnesses (N/m), comma-separated: for each, every "
             "obstacle's response penalty with that k, the stability "
             "search's limit beside the spectrum's prediction at --state "
             "(default: none)"},
    {.name = "state", .arg = "FILE", .type = CL_CLI_STRING, .sec = "contact",
     .key = "state", .field = offsetof(ct_setup, state),
     .help = "--k: the state the prediction linearises at, as final.csv "
             "(default: the problem's initial state)"},
    {.name = "t", .arg = "T", .type = CL_CLI_DOUBLE, .sec = "contact",
     .key = "t", .lo = -INFINITY, .hi = INFINITY,
     .field = offsetof(ct_setup, t),
     .help = "--k: the time of that state (moving obstacles and pins; "
             "default [init] time, 0 unless given)"},
    {.name = "dt-max", .arg = "H", .type = CL_CLI_DOUBLE, .sec = "contact",
     .key = "dt_max", .lo = 1e-300, .bounds = search_bounds,
     .field = offsetof(ct_setup, dt_max),
     .help = "--k: largest step tried, at most T/10 (default T/100)"},
    {.name = "dt-min", .arg = "H", .type = CL_CLI_DOUBLE, .sec = "contact",
     .key = "dt_min", .def = 1e-7, .lo = 1e-300, .bounds = search_bounds,
     .field = offsetof(ct_setup, dt_min),
     .help = "--k: give up below this step, at most dt_max"},
    {.name = "rel", .arg = "R", .type = CL_CLI_DOUBLE, .sec = "contact",
     .key = "rel", .def = 0.02, .lo = 1e-6, .hi = 0.5,
     .field = offsetof(ct_setup, rel),
     .help = "--k: bracket width relative to the step"},
    {.name = "from-sweep", .arg = "TABLE", .type = CL_CLI_STRING,
     .field = offsetof(ct_setup, from),
     .help = "take the runs from a table of 'clothode sweep collect' (each "
             "job's series from jobs/ beside it): the step table over the "
             "sweep's dt, or with --k the search's bracket on them"},
    CL_CLI_TAIL(ct_setup, "no table on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table ct_table = {
    .cmd = "contact", .synopsis = "PROBLEM --dt LIST | --k LIST [options]",
    .npos = 1,
    .rows = ct_rows,
    .about =
    "For each response and fixed-step integrator, runs from the initial\n"
    "state to T at every step of --dt: whether the run stays stable (as in\n"
    "clothode stability: finite, stretch d/L within [run] max_stretch at\n"
    "the checks, the solver does not give up), the worst penetration into\n"
    "an obstacle (before any projection), the penetration and contacts at\n"
    "rest (the end state), the largest stretch, Newton iterations and CPU\n"
    "time; writes contact.csv.  With --k, for each penalty stiffness the\n"
    "largest stable step of each integrator (the stability search) beside\n"
    "the spectrum's prediction at --state (a state in contact includes\n"
    "the contact springs); writes contact-k.csv.\n",
    .notes =
    "A response is given to every [obstacle.NAME] of the problem, as --set\n"
    "obstacle.NAME.response=R would; its own keys come from the file or\n"
    "--set (e.g. --set obstacle.ball.k=1e4 for penalty), and a --set applies\n"
    "to every run (e.g. a continuous detection key of a response).  The\n"
    "other [run] keys apply as in run; [run] dt is not used.  Problems that\n"
    "tear are refused.  With --from-sweep TABLE the runs are the sweep's\n"
    "(its dt axis; for each response and k, the rows whose other axes hold\n"
    "the variant's values): --dt is not given; the worst penetration and\n"
    "the largest stretch are those of the run's series samples (sweep with\n"
    "[run] samples = T/dt and --checks T/dt for the study's figures), the\n"
    "rest state its last row; with --k the bracket is the sweep's smallest\n"
    "unstable dt and the largest stable one below it.\n"};

/* ---- the lists ---------------------------------------------------------- */

/* "a,b,c" into at most max finite numbers > 0; false if malformed. */
static bool read_numbers(const char *s, double *out, int max, int *n)
{
    *n = 0;
    while (*s) {
        char *end;
        double v = strtod(s, &end);
        if (end == s || !(v > 0 && isfinite(v)) || *n == max ||
            (*end && *end != ','))
            return false;
        out[(*n)++] = v;
        s = *end ? end + 1 : end;
    }
    return *n > 0;
}

/* "LO:HI:N": N >= 2 steps evenly in log from LO to HI, or a list. */
static bool read_steps(const char *s, double *dt, int *n)
{
    double lo, hi;
    int count, used = 0;
    if (sscanf(s, "%lf:%lf:%d%n", &lo, &hi, &count, &used) == 3 &&
        !s[used]) {
        if (!(lo > 0 && hi > lo && isfinite(hi)) || count < 2 ||
            count > CL_CSTUDY_MAX_DT)
            return false;
        for (int k = 0; k < count; k++)
            dt[k] = lo * pow(hi / lo, (double)k / (count - 1));
        *n = count;
        return true;
    }
    return read_numbers(s, dt, CL_CSTUDY_MAX_DT, n);
}

/* "a,b" into names of 1..31 characters. */
static bool read_names(const char *s, char (*out)[32], int max, int *n)
{
    *n = 0;
    while (*s) {
        size_t len = strcspn(s, ",");
        if (len == 0 || len >= 32 || *n == max)
            return false;
        memcpy(out[*n], s, len);
        out[(*n)++][len] = '\0';
        s += len + (s[len] == ',');
    }
    return true;
}

static cl_status read_lists(cl_config *cfg, ct_setup *s, cl_error *err)
{
    char why[160];
    if (!*s->dts && !*s->ks && !s->from)
        return cl_error_set(err, CL_EINVAL, "contact needs steps to run "
                            "(--dt LIST) or stiffnesses to search (--k "
                            "LIST)");
    if (*s->dts && s->from)
        return cl_config_refuse(cfg, "contact", "dt", CL_EINVAL, "with "
                                "--from-sweep the steps are the sweep's",
                                err);
    if (*s->dts && !read_steps(s->dts, s->dt, &s->ndt)) {
        snprintf(why, sizeof why, "expected steps > 0 separated by commas "
                 "(at most %d) or LO:HI:N with 0 < LO < HI and 2 <= N <= %d",
                 CL_CSTUDY_MAX_DT, CL_CSTUDY_MAX_DT);
        return cl_config_refuse(cfg, "contact", "dt", CL_EINVAL, why, err);
    }
    if (!read_names(s->responses, s->resp, CT_MAX_RESP, &s->nresp)) {
        snprintf(why, sizeof why, "expected at most %d response names of 1 "
                 "to 31 characters, separated by commas", CT_MAX_RESP);
        return cl_config_refuse(cfg, "contact", "response", CL_EINVAL, why,
                                err);
    }
    if (*s->ks && !read_numbers(s->ks, s->k, CT_MAX_K, &s->nk)) {
        snprintf(why, sizeof why, "expected at most %d stiffnesses > 0 "
                 "(N/m) separated by commas", CT_MAX_K);
        return cl_config_refuse(cfg, "contact", "k", CL_EINVAL, why, err);
    }
    return CL_OK;
}

/* ---- variants ----------------------------------------------------------- */

static char *copy_of(const char *v)
{
    return v ? strdup(v) : NULL;
}

/* The obstacles and their response and k as the problem gives them. */
static cl_status save_obstacles(cl_config *cfg, ct_setup *s, cl_error *err)
{
    const char *sec;
    for (s->nobs = 0; (sec = cl_config_section_at(cfg, "obstacle.",
                                                  (size_t)s->nobs));
         s->nobs++) {
        ct_obstacle *o = &s->obs[s->nobs];
        if (s->nobs == CT_MAX_OBS || strlen(sec) >= sizeof o->sec)
            return cl_error_set(err, CL_EINVAL, "[%s]: contact studies at "
                                "most %d obstacles with names shorter than "
                                "%zu characters", sec, CT_MAX_OBS,
                                sizeof o->sec - 9);
        strcpy(o->sec, sec);
        o->response = copy_of(cl_config_string(cfg, sec, "response", NULL));
        o->k = copy_of(cl_config_string(cfg, sec, "k", NULL));
    }
    if (s->nobs == 0)
        return cl_error_set(err, CL_EINVAL, "the problem has no obstacle "
                            "([obstacle.NAME] sections): nothing to study");
    return CL_OK;
}

static void free_obstacles(ct_setup *s)
{
    for (int k = 0; k < s->nobs; k++) {
        free(s->obs[k].response);
        free(s->obs[k].k);
    }
}

/* key = value on every obstacle (value NULL: left as it is), reported as
 * the option `label`. */
static cl_status set_all(ct_setup *s, const char *key, const char *value,
                         const char *label, cl_error *err)
{
    char a[256];
    cl_status rc = CL_OK;
    for (int k = 0; !rc && value && k < s->nobs; k++) {
        snprintf(a, sizeof a, "%s.%s=%s", s->obs[k].sec, key, value);
        rc = cl_config_set_as(s->cfg, a, label, err);
    }
    return rc;
}

/* The values the problem gave (a key it did not give stays as the last
 * variant set it: only the variants that set it read it). */
static cl_status restore(ct_setup *s, cl_error *err)
{
    char a[512];
    cl_status rc = CL_OK;
    for (int k = 0; !rc && k < s->nobs; k++) {
        const ct_obstacle *o = &s->obs[k];
        if (o->response) {
            snprintf(a, sizeof a, "%s.response=%s", o->sec, o->response);
            rc = cl_config_set_as(s->cfg, a, "the problem file", err);
        }
        if (!rc && o->k) {
            snprintf(a, sizeof a, "%s.k=%s", o->sec, o->k);
            rc = cl_config_set_as(s->cfg, a, "the problem file", err);
        }
    }
    return rc;
}

/* Whether the step table is made: --dt, or a sweep's steps without --k. */
static bool step_table(const ct_setup *s)
{
    return s->ndt > 0 || (s->from && s->nk == 0);
}

/* Variants 0 .. nresp-1 (or one, the problem as it is, without
 * --response) are the responses, none without the step table, then one
 * per k. */
static int dt_variants(const ct_setup *s)
{
    return !step_table(s) ? 0 : s->nresp > 0 ? s->nresp : 1;
}

static const char *variant_response(const ct_setup *s, int v)
{
    return v < dt_variants(s) ? (s->nresp ? s->resp[v] : NULL) : "penalty";
}

/* The model of variant v into s->variant (the previous one freed). */
static cl_status build(ct_setup *s, int v, cl_error *err)
{
    char k[32];
    cl_model_free(s->variant);
    s->variant = NULL;
    s->variant_of = -1;
    cl_status rc = restore(s, err);
    if (!rc)
        rc = set_all(s, "response", variant_response(s, v), "--response",
                     err);
    if (!rc && v >= dt_variants(s)) {
        snprintf(k, sizeof k, "%.17g", s->k[v - dt_variants(s)]);
        rc = set_all(s, "k", k, "--k", err);
    }
    if (!rc && s->from) /* the sweep's rows of this variant, and their
                         * start time */
        rc = cl_sweep_table_select(&s->table, s->cfg, "contact", err);
    if (!rc && s->from)
        rc = cl_cli_span(s->cfg, s->run.t_end, &s->so.t_end, err);
    if (!rc && !(rc = cl_cli_model_create(s->cfg, &s->variant, err)))
        s->variant_of = v;
    return rc;
}

/* The model of variant v in s->variant, built unless it is there. */
static cl_status use_variant(ct_setup *s, int v, cl_error *err)
{
    return s->variant_of == v ? CL_OK : build(s, v, err);
}

/* The integrator of the study's k-th result (variants by integrators). */
static const cl_cli_method *method_of(const ct_setup *s, int k)
{
    return &s->integrators.m[k % s->integrators.n];
}

/* With --from-sweep, the obstacles' `key`, which the variants set
 * (--response, --k), must be an axis of the sweep, unless the runs' value
 * (the problem file's, `given`: NULL for any) is the one the variants
 * set, `set`: otherwise they would take the rows of other runs. */
static cl_status swept(const ct_setup *s, const char *key, const char *set,
                       const char *option, cl_error *err)
{
    char name[256];
    for (int k = 0; k < s->nobs; k++) {
        const char *given = !strcmp(key, "k") ? s->obs[k].k
                                              : s->obs[k].response;
        snprintf(name, sizeof name, "%s.%s", s->obs[k].sec, key);
        if (!cl_sweep_table_has(&s->table, name) &&
            (!set || !given || strcmp(given, set)))
            return cl_error_set(err, CL_EINVAL, "--from-sweep %s: %s, yet "
                                "%s is no axis of the sweep, whose runs "
                                "had the problem file's value%s%s; give %s "
                                "only with a sweep over it", s->from, option,
                                name, given ? ", " : "", given ? given : "",
                                option);
    }
    return CL_OK;
}

/* Every variant built, each integrator created on it and checked for its
 * study, then the problem's own values put back. */
static cl_status try_variants(ct_setup *s, cl_error *err)
{
    cl_status rc = CL_OK;
    for (int v = 0; !rc && v < dt_variants(s) + s->nk; v++) {
        if ((rc = build(s, v, err)) ||
            (rc = cl_cli_methods_try(s->variant, &s->integrators, err)))
            break;
        for (int i = 0; !rc && i < s->integrators.n; i++)
            rc = s->from && v < dt_variants(s) ? CL_OK /* the sweep's */
                 : v < dt_variants(s)
                     ? cl_cstudy_check(s->variant, s->integrators.m[i].type,
                                       &s->so, s->dt, s->ndt, err)
                     : cl_stab_check(s->variant, s->integrators.m[i].type,
                                     &s->so, err);
    }
    cl_model_free(s->variant);
    s->variant = NULL;
    s->variant_of = -1;
    return rc ? rc : restore(s, err);
}

static cl_status check_setup(cl_config *cfg, void *ctx, cl_error *err)
{
    ct_setup *s = ctx;
    s->cfg = cfg;
    s->variant_of = -1;
    /* options of the stiffness table only */
    static const char *const k_only[] = {"state", "t", "dt-max", "dt-min",
                                         "rel", NULL};
    cl_status rc = cl_cli_refuse_unless(cfg, &ct_table, k_only,
                                        s->ks && *s->ks,
                                        "--k LIST (the stiffness table)",
                                        err);
    if (!rc)
        rc = cl_cli_methods_check(cfg, &s->integrators, &s->run.io,
                                  CL_CLI_DT_NONE, err);
    if (!rc)
        rc = cl_cli_methods_fixed(cfg, &s->integrators, "contact", err);
    if (rc)
        return rc;
    s->so = (cl_stab_opts){.checks = s->checks,
                           .max_stretch = s->run.max_stretch, .rel = s->rel,
                           .dt_min = s->dt_min};
    if ((rc = cl_cli_span(cfg, s->run.t_end, &s->so.t_end, err)))
        return rc;
    s->so.dt_max = cl_cli_dt_max(cfg, "contact", s->dt_max, s->so.t_end);
    if (s->from)
        rc = cl_sweep_table_read(s->from, &s->table, err);
    if (!rc && !(rc = read_lists(cfg, s, err)) &&
        !(rc = save_obstacles(cfg, s, err)) && s->from && s->nresp > 0)
        rc = swept(s, "response", NULL, "--response", err);
    if (!rc && s->from && s->nk > 0 &&
        !(rc = swept(s, "response", "penalty", "--k (response = penalty)",
                     err)))
        rc = swept(s, "k", NULL, "--k", err);
    if (!rc)
        rc = try_variants(s, err);
    return rc;
}

/* ---- the step table ----------------------------------------------------- */

static void print_step_result(const void *result)
{
    const cl_cstudy_result *r = result;
    for (int k = 0; k < r->n; k++) {
        const cl_cstudy_row *w = &r->row[k];
        printf("%-18s %-9s %9.3g %-8s %10.3g %10.3g %7ld %8.3g %8ld %8.3f\n",
               k ? "" : r->label, k ? "" : r->response, w->run.dt,
               w->run.rc ? "UNSTABLE" : "stable", w->worst_pen, w->rest_pen,
               w->rest_contacts, w->stretch_max, w->run.stats.nonlin_iters,
               w->run.stats.cpu);
    }
    if (isnan(r->dt_unstable))
        return;
    printf("%-18s %-9s unstable from dt = %.4g", "", "", r->dt_unstable);
    if (!isnan(r->dt_stable))
        printf(", stable at %.4g", r->dt_stable);
    putchar('\n');
}

static cl_status begin_steps(cl_model *m, const cl_cli_job *job, void *ctx,
                             cl_error *err)
{
    const ct_setup *s = ctx;
    (void)m;
    (void)err;
    if (job->quiet)
        return CL_OK;
    printf("problem    %s, T = %g s, max_stretch %g, %ld checks per run, ",
           job->problem, s->so.t_end, s->so.max_stretch, s->so.checks);
    if (s->from)
        printf("the steps of the sweep table %s\n", s->from);
    else
        printf("%d steps\n", s->ndt);
    return CL_OK;
}

static cl_status run_steps(cl_model *m, void *ctx, int k, void *result,
                           cl_error *err)
{
    ct_setup *s = ctx;
    cl_cstudy_result *r = result;
    int v = k / s->integrators.n;
    const cl_cli_method *mk = method_of(s, k);
    cl_status rc = use_variant(s, v, err);
    (void)m;
    if (!rc)
        rc = s->from ? cl_cstudy_from_sweep(&s->table, mk->label, &s->so, r,
                                            err)
                     : cl_cstudy_run(s->variant, mk->type, &mk->io, &s->so,
                                     s->dt, s->ndt, r, err);
    r->label = mk->label;
    r->response = s->nresp ? s->resp[v] : "problem";
    return rc;
}

static void step_rows(FILE *fp, const void *result, bool header)
{
    cl_cstudy_write_rows(fp, result, header);
}

static const cl_cli_study step_study = {
    .csv = "contact.csv",
    .columns = "integrator         response         dt status   worst pen. "
               " rest pen. contacts  stretch   Newton  cpu [s]",
    .size = sizeof(cl_cstudy_result), .begin = begin_steps,
    .run = run_steps, .print = print_step_result, .rows = step_rows};

/* ---- the stiffness table ------------------------------------------------ */

static void print_k_result(const void *result)
{
    cl_climit_print(stdout, result);
}

static cl_status begin_k(cl_model *m, const cl_cli_job *job, void *ctx,
                         cl_error *err)
{
    ct_setup *s = ctx;
    size_t n = cl_model_system(m)->n;
    s->x = malloc(n * sizeof *s->x);
    s->v = malloc(n * sizeof *s->v);
    cl_status rc = s->x && s->v ? cl_cli_free_state(m, s->state, s->x, s->v,
                                                    err)
                                : cl_error_set(err, CL_ENOMEM,
                                               "out of memory");
    if (rc)
        return rc;
    s->t = cl_cli_state_time(job->cfg, "contact", m, s->t);
    if (!job->quiet)
        printf("\nexplicit limit against the penalty stiffness k (every "
               "obstacle penalty), predicted at %s\n",
               *s->state ? s->state : "the initial state");
    return CL_OK;
}

static cl_status run_k(cl_model *m, void *ctx, int k, void *result,
                       cl_error *err)
{
    ct_setup *s = ctx;
    cl_climit_result *r = result;
    int v = dt_variants(s) + k / s->integrators.n;
    const cl_cli_method *mk = method_of(s, k);
    cl_status rc = use_variant(s, v, err);
    (void)m;
    if (!rc)
        rc = cl_climit_predict(s->variant, mk->type, s->t, s->x, s->v, r,
                               err);
    if (!rc)
        rc = cl_stab_limit(s->from ? &s->table : NULL, s->variant, mk->label,
                           mk->type, &mk->io, &s->so, &r->stab, err);
    r->label = mk->label;
    r->k = s->k[v - dt_variants(s)];
    return rc;
}

static void k_rows(FILE *fp, const void *result, bool header)
{
    cl_climit_write_row(fp, result, header);
}

static void end_k(void *ctx)
{
    ct_setup *s = ctx;
    cl_model_free(s->variant);
    s->variant = NULL;
    s->variant_of = -1;
}

static const cl_cli_study k_study = {
    .csv = "contact-k.csv",
    .columns = "integrator                  k   stable dt unstable dt "
               "predicted dt  w_max [1/s]  runs",
    .size = sizeof(cl_climit_result), .begin = begin_k,
    .run = run_k, .print = print_k_result, .rows = k_rows, .end = end_k};

static cl_status study(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    ct_setup *s = ctx;
    if (s->from && cl_sweep_table_same_inputs(&s->table, job->cfg, err))
        return err->code;
    cl_status rc = !step_table(s) ? CL_OK
                   : cl_cli_study_run(m, job, &step_study,
                                      dt_variants(s) * s->integrators.n, ctx,
                                      err);
    if (!rc && s->nk > 0)
        rc = cl_cli_study_run(m, job, &k_study, s->nk * s->integrators.n,
                              ctx, err);
    end_k(s);
    return rc;
}

int cl_cmd_contact(int argc, char **argv)
{
    ct_setup s = {0};
    int status = cl_cli_problem_main(argc, argv, &ct_table, &s, check_setup,
                                     study);
    cl_model_free(s.variant);
    free_obstacles(&s);
    free(s.x);
    free(s.v);
    cl_sweep_table_free(&s.table);
    return status;
}
