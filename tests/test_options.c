/* The option table of the subcommands (cli/options.h), in-process: each
 * type parsed from a command line and read through a configuration, the
 * refusals (range, type, unknown names, usage), the values saved in a
 * written configuration read back to the same settings, and --help. */
#include <criterion/criterion.h>
#include <criterion/redirect.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/options.h"
#include "tmpdir.h"

/* ---- a table with a row of every type -------------------------------- */

typedef struct {
    double d;
    long l;
} grp_t;

typedef struct {
    cl_cli_args a;
    double x;
    long n;
    int k;
    const char *s;
    unsigned fmt;
    bool flag;
    grp_t g;
    double lim; /* its default and bound follow x */
    cl_cli_methods ms;
} opts_t;

static const char *const fmt_names[] = {"csv", "vtk", "obj", NULL};

static const cl_cli_opt grp_rows[] = {
    {.name = "gd", .arg = "D", .type = CL_CLI_DOUBLE, .sec = "g",
     .key = "d", .def = 0.5, .lo = 0, .hi = 1,
     .field = offsetof(grp_t, d), .help = "a number of the group"},
    {.name = "gl", .arg = "L", .type = CL_CLI_LONG, .sec = "g", .key = "l",
     .def = 7, .lo = 0, .hi = 9, .field = offsetof(grp_t, l),
     .help = "an integer of the group, not offered here"},
    {.type = CL_CLI_END}};

/* lim: x/2 by default, at most x */
static void lim_bounds(const void *settings, double *def, double *hi)
{
    const opts_t *o = settings;
    *def = o->x / 2;
    *hi = o->x;
}

static const cl_cli_opt rows[] = {
    {.name = "x", .arg = "X", .type = CL_CLI_DOUBLE, .sec = "t", .key = "x",
     .def = 2.5, .lo = 0, .hi = 10, .field = offsetof(opts_t, x),
     .help = "a number"},
    {.name = "n", .arg = "N", .type = CL_CLI_LONG, .sec = "t", .key = "n",
     .def = 3, .lo = 1, .hi = 100, .field = offsetof(opts_t, n),
     .help = "a count"},
    {.name = "k", .arg = "K", .type = CL_CLI_INT, .sec = "t", .key = "k",
     .def = -1, .lo = -5, .hi = 5, .field = offsetof(opts_t, k),
     .help = "a small integer"},
    {.name = "s", .arg = "TEXT", .type = CL_CLI_STRING, .sec = "t",
     .key = "s", .sdef = "none", .field = offsetof(opts_t, s),
     .help = "a text"},
    {.name = "format", .arg = "LIST", .type = CL_CLI_NAMES, .sec = "t",
     .key = "format", .sdef = "vtk", .names = fmt_names,
     .field = offsetof(opts_t, fmt), .help = "formats"},
    {.name = "flag", .type = CL_CLI_FLAG, .field = offsetof(opts_t, flag),
     .help = "a switch"},
    {.type = CL_CLI_GROUP, .group = grp_rows, .hide = "gl",
     .field = offsetof(opts_t, g)},
    {.name = "lim", .arg = "H", .type = CL_CLI_DOUBLE, .sec = "t",
     .key = "lim", .lo = 0, .bounds = lim_bounds,
     .field = offsetof(opts_t, lim), .help = "at most x (default x/2)"},
    {.name = "integrator", .arg = "LIST", .type = CL_CLI_METHODS,
     .sec = "run", .key = "integrator", .sdef = "cvode-bdf", .hi = 2,
     .field = offsetof(opts_t, ms), .help = "integrators"},
    CL_CLI_TAIL(opts_t, "say nothing"),
    {.type = CL_CLI_END}};

static const cl_cli_table table = {
    .cmd = "test", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = rows, .about = "A table of every type.\n",
    .notes = "Notes after the options.\n"};

/* ---- parsing and reading ---------------------------------------------- */

/* A command line "test ..." (NULL-terminated) and its argument count. */
#define ARGV(...) ((char *[]){"test", __VA_ARGS__, NULL})

static int argc_of(char **argv)
{
    int n = 0;
    while (argv[n])
        n++;
    return n;
}

/* Parse argv into o (expecting PROBLEM last), apply the assignments to
 * cfg and read the table: the status of the read, err its message. */
static cl_status parse_read(char **argv, opts_t *o, cl_config *cfg,
                            cl_error *err)
{
    int argc = argc_of(argv);
    memset(o, 0, sizeof *o);
    int at = cl_cli_parse(argc, argv, &table, o);
    cr_assert_eq(at, argc - 1, "parse gave %d", at);
    cl_status rc = cl_cli_apply(cfg, &o->a.sets, err);
    if (!rc)
        rc = cl_cli_read(cfg, &table, o, err);
    cl_cli_sets_free(&o->a.sets);
    return rc;
}

/* The same on a fresh configuration, which the caller frees. */
static cl_config *read_args(char **argv, opts_t *o, cl_status want,
                            cl_error *err)
{
    cl_config *cfg = cl_config_alloc();
    cr_assert_not_null(cfg);
    cl_status rc = parse_read(argv, o, cfg, err);
    cr_assert_eq(rc, want, "status %d (%s), expected %d", rc, err->msg,
                 want);
    return cfg;
}

Test(options, defaults_when_nothing_is_given)
{
    opts_t o;
    cl_error err = {0};
    cl_config *cfg = read_args(ARGV("P"), &o, CL_OK, &err);
    cr_assert_eq(o.x, 2.5);
    cr_assert_eq(o.n, 3);
    cr_assert_eq(o.k, -1);
    cr_assert_str_eq(o.s, "none");
    cr_assert_eq(o.fmt, 2u, "vtk is bit 1: %u", o.fmt);
    cr_assert(!o.flag);
    cr_assert_eq(o.g.d, 0.5);
    cr_assert_eq(o.g.l, 7);
    cr_assert_eq(o.lim, 1.25, "x/2: %g", o.lim);
    cr_assert_eq(o.ms.n, 1);
    cr_assert_str_eq(o.ms.m[0].type->name, "cvode-bdf");
    cr_assert_null(o.a.out);
    cr_assert(!o.a.quiet);
    cl_config_free(cfg);
}

Test(options, every_type_parses)
{
    char **v = ARGV("--x", "7.25", "--n", "42", "--k=-4", "--s", "hello",
                    "--format", "obj, csv", "--flag", "--gd", "0.125",
                    "--lim", "3", "--integrator", "rk4,semi-bdf2:pcg",
                    "--set", "g.l=2", "--out", "dir", "--quiet", "P");
    opts_t o;
    cl_error err = {0};
    cl_config *cfg = read_args(v, &o, CL_OK, &err);
    cr_assert_eq(o.x, 7.25);
    cr_assert_eq(o.n, 42);
    cr_assert_eq(o.k, -4);
    cr_assert_str_eq(o.s, "hello");
    cr_assert_eq(o.fmt, 5u, "csv (bit 0) and obj (bit 2): %u", o.fmt);
    cr_assert(o.flag);
    cr_assert_eq(o.g.d, 0.125);
    cr_assert_eq(o.g.l, 2, "a hidden option's key is still read");
    cr_assert_eq(o.lim, 3.0);
    cr_assert_eq(o.ms.n, 2);
    cr_assert_str_eq(o.ms.m[0].type->name, "rk4");
    cr_assert_str_eq(o.ms.m[0].linsol, "");
    cr_assert_str_eq(o.ms.m[1].type->name, "semi-bdf2");
    cr_assert_str_eq(o.ms.m[1].linsol, "pcg");
    cr_assert_str_eq(o.ms.m[1].label, "semi-bdf2:pcg");
    cr_assert_str_eq(o.a.out, "dir");
    cr_assert(o.a.quiet);
    /* the options are keys of the configuration, set from their option */
    cr_assert_str_eq(cl_config_string(cfg, "t", "x", ""), "7.25");
    char where[64];
    cr_assert_str_eq(cl_config_origin(cfg, "t", "x", where, sizeof where),
                     "--x");
    cr_assert_str_eq(cl_config_origin(cfg, "g", "l", where, sizeof where),
                     "--set");
    cl_config_free(cfg);
}

/* One option value refused: the message names the option, the key, the
 * value and what is allowed. */
static void refused(const char *opt, const char *val, const char *allowed)
{
    char *v[] = {"test", (char *)opt, (char *)val, "P", NULL};
    opts_t o;
    cl_error err = {0};
    cl_config *cfg = read_args(v, &o, CL_EINVAL, &err);
    char want[128];
    snprintf(want, sizeof want, "%s: ", opt);
    cr_assert(!strncmp(err.msg, want, strlen(want)), "%s", err.msg);
    snprintf(want, sizeof want, "\"%s\"", val);
    cr_assert(strstr(err.msg, want), "no %s in: %s", want, err.msg);
    cr_assert(strstr(err.msg, allowed), "no \"%s\" in: %s", allowed,
              err.msg);
    cl_config_free(cfg);
}

Test(options, out_of_range_and_malformed_values_are_refused)
{
    refused("--x", "10.5", "in [0, 10]");
    refused("--x", "-1", "in [0, 10]");
    refused("--x", "abc", "[t] x");
    refused("--x", "nan", "[t] x");
    refused("--n", "0", "an integer in [1, 100]");
    refused("--n", "101", "an integer in [1, 100]");
    refused("--n", "2.5", "an integer in [1, 100]");
    refused("--k", "6", "an integer in [-5, 5]");
    refused("--gd", "2", "in [0, 1]");
    refused("--lim", "2.6", "in [0, 2.5]"); /* at most x = 2.5 */
    refused("--format", "vtk,png", "expected a list of csv, vtk, obj");
    refused("--format", ",", "an empty list; expected at least one of csv, "
                             "vtk, obj");
    refused("--format", "vtk,obj,vtk", "vtk is listed twice");
    refused("--integrator", "rk5", "unknown integrator \"rk5\"");
    refused("--integrator", "rk5", "rk4");
    refused("--integrator", "rk4,fe,rk4", "more than 2 entries");
    refused("--integrator", ":klu", "NAME:LINSOL");
}

/* cl_cli_parse on argv is a usage error: -1, and on stderr the message
 * `want` with the pointer to --help. */
static void usage_error(char **argv, const char *want)
{
    opts_t o = {0};
    char msg[256];
    int at = cl_cli_parse(argc_of(argv), argv, &table, &o);
    cl_cli_sets_free(&o.a.sets);
    fflush(stderr);
    cr_assert_eq(at, -1, "parse gave %d", at);
    snprintf(msg, sizeof msg, "clothode test: %s\n(see 'clothode test "
             "--help')\n", want);
    cr_assert_stderr_eq_str(msg);
}

Test(options, unknown_option, .init = cr_redirect_stderr)
{
    usage_error(ARGV("--y", "1", "P"), "unknown or ambiguous option '--y'");
}

Test(options, hidden_option_of_a_group, .init = cr_redirect_stderr)
{
    usage_error(ARGV("--gl", "1", "P"), "unknown or ambiguous option '--gl'");
}

Test(options, missing_value, .init = cr_redirect_stderr)
{
    usage_error(ARGV("P", "--x"), "option '--x' needs a value (--x X)");
}

Test(options, value_to_a_flag, .init = cr_redirect_stderr)
{
    usage_error(ARGV("--flag=1", "P"), "option '--flag=1' takes no value");
}

Test(options, problem_count, .init = cr_redirect_stderr)
{
    usage_error(ARGV("P", "Q"), "expected exactly one PROBLEM, got 2");
}

/* ---- saved and read back ----------------------------------------------- */

static void assert_same(const opts_t *a, const opts_t *b)
{
    cr_assert_eq(a->x, b->x);
    cr_assert_eq(a->n, b->n);
    cr_assert_eq(a->k, b->k);
    cr_assert_str_eq(a->s, b->s);
    cr_assert_eq(a->fmt, b->fmt);
    cr_assert_eq(a->g.d, b->g.d);
    cr_assert_eq(a->g.l, b->g.l);
    cr_assert_eq(a->lim, b->lim);
    cr_assert_eq(a->ms.n, b->ms.n);
    for (int k = 0; k < a->ms.n; k++)
        cr_assert_str_eq(a->ms.m[k].label, b->ms.m[k].label);
}

/* The configuration with the command line's values written as INI (as run
 * saves config.ini) and loaded again gives the same settings: the given
 * values from their keys, the others from the same defaults. */
static void round_trip(char **argv)
{
    char dir[512], path[600];
    tmp_mkdtemp(dir, sizeof dir, "options");
    snprintf(path, sizeof path, "%s/config.ini", dir);
    opts_t a, b;
    cl_error err = {0};
    cl_config *cfg = read_args(argv, &a, CL_OK, &err);
    cr_assert_eq(cl_config_write(cfg, path, &err), CL_OK, "%s", err.msg);
    cl_config *again = cl_config_alloc();
    cr_assert_eq(cl_config_load(again, path, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(parse_read(ARGV("P"), &b, again, &err), CL_OK, "%s",
                 err.msg);
    assert_same(&a, &b);
    cl_config_free(again);
    cl_config_free(cfg);
    tmp_rm_rf(dir);
}

Test(options, saved_values_read_back_to_the_same_settings)
{
    round_trip(ARGV("--x", "9", "--n", "17", "--format", "csv,obj",
                        "--lim", "4.5", "--integrator", "fe,rk4:klu",
                        "--set", "g.l=0", "P"));
}

Test(options, defaults_read_back_to_the_same_settings)
{
    /* one key given, so that the file is not empty; the rest defaults,
     * among them lim, which follows x */
    round_trip(ARGV("--s", "text", "P"));
}

/* ---- the integrators' options ------------------------------------------ */

/* Read `integrator` with [run] keys `sets` and check it as run does. */
static cl_status check(const char *integrator, const char *const *sets,
                       cl_cli_methods *ms, cl_error *err)
{
    static const cl_cli_opt row = {.type = CL_CLI_METHODS, .sec = "run",
                                   .key = "integrator", .sdef = "cvode-bdf",
                                   .hi = CL_CLI_MAX_METHODS};
    char a[128];
    cl_cli_run run = {0};
    cl_config *cfg = cl_config_alloc();
    snprintf(a, sizeof a, "run.integrator=%s", integrator);
    cl_status rc = cl_config_set_as(cfg, a, "--integrator", err);
    for (; !rc && *sets; sets++)
        rc = cl_config_set(cfg, *sets, err);
    static const cl_cli_opt group[] = {
        {.type = CL_CLI_GROUP, .group = cl_cli_run_rows},
        {.type = CL_CLI_END}};
    const cl_cli_table t = {.cmd = "check", .rows = group};
    if (!rc && !(rc = cl_cli_read(cfg, &t, &run, err)) &&
        !(rc = cl_cli_methods_read(cfg, &row, ms, err)))
        rc = cl_cli_methods_check(cfg, ms, &run.io, CL_CLI_DT_ALL, err);
    cl_config_free(cfg);
    return rc;
}

#define SETS(...) ((const char *const[]){__VA_ARGS__, NULL})

Test(options, integrator_options_are_checked_against_the_integrator)
{
    cl_cli_methods ms;
    cl_error err = {0};
    cr_assert_eq(check("cvode-bdf", SETS("run.dt=0.01", "run.rtol=1e-3"),
                       &ms, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(ms.m[0].io.dt, 0.01, "the first step");
    cr_assert_eq(ms.m[0].io.rtol, 1e-3);
    cr_assert_eq(ms.m[0].io.atol, 1e-8, "the default");
    cr_assert_eq(check("rk4", SETS("run.dt=0.01", "run.rtol=1e-3"), &ms,
                       &err), CL_EINVAL, "a fixed step reads no rtol");
    cr_assert(strstr(err.msg, "[run] rtol = \"1e-3\": integrator rk4 reads "
                              "no rtol"), "%s", err.msg);
    cr_assert_eq(check("cvode-bdf:pcg", SETS("run.linsol=klu"), &ms, &err),
                 CL_OK, "%s", err.msg);
    cr_assert_str_eq(ms.m[0].io.linsol, "pcg", "the entry's solver wins");
    cr_assert_eq(check("rk4", SETS("run.dt=0.01", "run.linsol=klu"), &ms,
                       &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "[run] linsol = \"klu\": integrator rk4 has "
                              "no choice"), "%s", err.msg);
    cr_assert_eq(check("rk4:klu", SETS("run.dt=0.01"), &ms, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "--integrator: [run] integrator = "
                              "\"rk4:klu\""), "%s", err.msg);
    cr_assert_eq(check("cvode-bdf:", SETS("run.dt=0.01"), &ms, &err),
                 CL_EINVAL, "an empty linear solver");
    cr_assert(strstr(err.msg, "bad entry \"cvode-bdf:\""), "%s", err.msg);
    cr_assert_eq(check("semi-be", SETS("run.dt=0.01", "run.max_order=2"),
                       &ms, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "max_order = 2: integrator semi-be"), "%s",
              err.msg);
    cr_assert_eq(check("rk4", SETS("run.rtol=1e-3"), &ms, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "dt = 0: integrator rk4 takes fixed steps"),
              "%s", err.msg);
}

/* ---- --help ------------------------------------------------------------ */

Test(options, help_comes_from_the_table)
{
    char *text = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&text, &len);
    cr_assert_not_null(fp);
    cl_cli_help(&table, fp);
    fclose(fp);
    const char head[] = "usage: clothode test PROBLEM [options]\n"
                        "A table of every type.\n\n";
    cr_assert(!strncmp(text, head, strlen(head)), "%s", text);
    cr_assert(strstr(text, "\n  --x X              a number; [t] x, "
                           "default 2.5\n"), "%s", text);
    cr_assert(strstr(text, "\n  --n N              a count; [t] n, 1 .. "
                           "100, default 3\n"), "%s", text);
    cr_assert(strstr(text, "\n  --s TEXT           a text; [t] s, default "
                           "none\n"), "%s", text);
    cr_assert(strstr(text, "\n  --flag             a switch\n"), "%s", text);
    cr_assert(strstr(text, "\n  --lim H            at most x (default x/2); "
                           "[t] lim\n"), "%s", text);
    cr_assert(!strstr(text, "--gl"), "a hidden option is offered:\n%s",
              text);
    cr_assert(strstr(text, "Keys without an option (problem file or --set "
                           "SEC.KEY=VAL):\n  [g] l              an integer "
                           "of the group, not offered here; 0 .. 9,\n"
                           "                     default 7\n"), "%s", text);
    cr_assert(strstr(text, "\n  --quiet            say nothing\n"), "%s",
              text);
    size_t n = strlen(text);
    cr_assert(n > 25 && !strcmp(text + n - 25, "Notes after the options.\n"),
              "%s", text);
    for (char *p = text; *p;) {
        size_t w = strcspn(p, "\n");
        cr_assert(w <= 78, "a line of %zu columns: %.*s", w, (int)w, p);
        p += w + (p[w] == '\n');
    }
    free(text);
}
