/* End-to-end tests of the clothode command line: the program ($CLOTHODE,
 * default build/clothode) is run as a separate process on the problems in
 * problems/, and its exit status, messages and output files are checked.
 * Run from the repository root. */
#include <criterion/criterion.h>
#include <criterion/logging.h>

#include <ctype.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "cli/cli.h"
#include "core/exit.h"
#include "io/config.h"
#include "io/mtx.h"
#include "io/state.h"
#include "system/model.h"
#include "runcli.h"
#include "timelimit.h"

/* ---- fixture: one scratch directory per test -------------------------- */

static char tmp[512];

static void setup(void)
{
    time_limit(900);
    tmp_mkdtemp(tmp, sizeof tmp, "cli");
}

static void teardown(void)
{
    tmp_rm_rf(tmp);
}

TestSuite(cli, .init = setup, .fini = teardown);

/* A path inside the scratch directory. */
static const char *in_tmp(char *buf, const char *name)
{
    snprintf(buf, 1024, "%s/%s", tmp, name);
    return buf;
}

/* ---- the model, built in-process, for rest positions and masses ------ */

static cl_config *model_cfg; /* the configuration of the loaded model */

/* problems/NAME.ini (or under $CLOTHODE_PROBLEMS) with assignments, as the
 * program builds it; free with free_model. */
static cl_model *load_model(const char *name, const char *const *sets)
{
    const char *dir = getenv("CLOTHODE_PROBLEMS");
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.ini", dir && *dir ? dir : "problems",
             name);
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cr_assert_not_null(cfg);
    cl_status rc = cl_config_load(cfg, path, &err);
    for (; !rc && sets && *sets; sets++)
        rc = cl_config_set(cfg, *sets, &err);
    cl_model *m = NULL;
    if (!rc)
        rc = cl_model_create(cfg, &m, &err);
    cr_assert_eq(rc, CL_OK, "%s: %s", path, err.msg);
    model_cfg = cfg;
    return m;
}

static void free_model(cl_model *m)
{
    cl_model_free(m);
    cl_config_free(model_cfg);
    model_cfg = NULL;
}

static void write_state(const char *path, size_t np, const double *x,
                        const double *v)
{
    cl_error err = {0};
    cr_assert_eq(cl_state_write(path, np, x, v, &err), CL_OK, "%s", err.msg);
}

/* Deterministic numbers in [0, 1). */
static double uniform(unsigned long long *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* Free particles moved by up to 0.1 h per coordinate and given velocities
 * up to 0.25 m/s per component; pinned ones at rest where they belong. */
static void perturbed_state(const cl_cloth *c, double *x, double *v)
{
    unsigned long long s = 12345;
    for (size_t p = 0; p < c->np; p++)
        for (int d = 0; d < 3; d++) {
            double ux = uniform(&s) - 0.5, uv = uniform(&s) - 0.5;
            bool pinned = c->dof[p] < 0;
            x[3 * p + d] = c->X0[3 * p + d] + (pinned ? 0 : 0.2 * c->hu * ux);
            v[3 * p + d] = pinned ? 0 : 0.5 * uv;
        }
}

/* ---- reading outputs -------------------------------------------------- */

/* energy.csv: the terms in order and their values. */
typedef struct {
    size_t n;
    char name[16][32];
    double value[16];
} energies;

static void read_energy(const char *path, energies *e)
{
    cli_lines L;
    cli_read_lines(path, &L);
    cr_assert(L.n >= 1, "%s is empty", path);
    cr_assert_str_eq(L.line[0], "term,value", "%s: header", path);
    e->n = 0;
    for (size_t k = 1; k < L.n; k++) {
        char *comma = strchr(L.line[k], ',');
        cr_assert(comma && e->n < 16, "%s: bad row \"%s\"", path, L.line[k]);
        snprintf(e->name[e->n], sizeof e->name[0], "%.*s",
                 (int)(comma - L.line[k]), L.line[k]);
        cli_parse_row(comma + 1, &e->value[e->n], 1, path);
        e->n++;
    }
    cli_lines_free(&L);
}

static double energy_of(const energies *e, const char *name)
{
    for (size_t k = 0; k < e->n; k++)
        if (!strcmp(e->name[k], name))
            return e->value[k];
    cr_assert_fail("energy.csv has no row \"%s\"", name);
    return NAN;
}

/* series.csv: header and rows of numbers. */
typedef struct {
    char header[1024];
    size_t ncol, nrow;
    double *v; /* nrow x ncol */
} series;

static void read_series(const char *path, series *s)
{
    cli_lines L;
    cli_read_lines(path, &L);
    cr_assert(L.n >= 1, "%s is empty", path);
    snprintf(s->header, sizeof s->header, "%s", L.line[0]);
    s->ncol = 1;
    for (const char *p = L.line[0]; *p; p++)
        s->ncol += *p == ',';
    s->nrow = L.n - 1;
    s->v = malloc((s->nrow ? s->nrow : 1) * s->ncol * sizeof *s->v);
    cr_assert_not_null(s->v);
    for (size_t k = 0; k < s->nrow; k++)
        cli_parse_row(L.line[k + 1], s->v + k * s->ncol, s->ncol, path);
    cli_lines_free(&L);
}

/* A "name,value" statistic of stats.csv. */
static double stat_of(const char *path, const char *name)
{
    cli_lines L;
    cli_read_lines(path, &L);
    size_t len = strlen(name);
    for (size_t k = 0; k < L.n; k++)
        if (!strncmp(L.line[k], name, len) && L.line[k][len] == ',') {
            double v;
            cli_parse_row(L.line[k] + len + 1, &v, 1, path);
            cli_lines_free(&L);
            return v;
        }
    cr_assert_fail("%s has no \"%s\" row", path, name);
    return NAN;
}

/* Field k (0-based) of a CSV line, up to the next comma, into buf. */
static const char *csv_field(const char *line, int k, char *buf, size_t len)
{
    for (; k > 0; k--) {
        line = strchr(line, ',');
        cr_assert_not_null(line, "no field %d", k);
        line++;
    }
    snprintf(buf, len, "%.*s", (int)strcspn(line, ","), line);
    return buf;
}

static double csv_number(const char *line, int k)
{
    char buf[64], *end;
    double v = strtod(csv_field(line, k, buf, sizeof buf), &end);
    cr_assert(end != buf && !*end, "field %d of \"%s\" is not a number", k,
              line);
    return v;
}

/* The index of column `name` in a CSV header. */
static int csv_column(const char *header, const char *name)
{
    size_t len = strlen(name);
    int k = 0;
    for (const char *h = header; h; k++) {
        if (!strncmp(h, name, len) && (h[len] == ',' || !h[len]))
            return k;
        h = strchr(h, ',');
        h = h ? h + 1 : NULL;
    }
    cr_assert_fail("no column %s in \"%s\"", name, header);
    return -1;
}

/* Names in dir that start with prefix; the first found into `first`. */
static int count_prefixed(const char *dir, const char *prefix, char *first,
                          size_t len)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d, "cannot open directory %s", dir);
    int n = 0;
    for (struct dirent *e; (e = readdir(d));)
        if (!strncmp(e->d_name, prefix, strlen(prefix))) {
            if (!n && first)
                snprintf(first, len, "%s", e->d_name);
            n++;
        }
    closedir(d);
    return n;
}

/* No temporary file of an unfinished atomic write is left in dir. */
static void assert_no_temporaries(const char *dir)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d, "cannot open directory %s", dir);
    for (struct dirent *e; (e = readdir(d));)
        cr_assert(!strstr(e->d_name, ".tmp"), "%s: leftover temporary %s",
                  dir, e->d_name);
    closedir(d);
}

/* The time a VTK frame carries (field data TIME). */
static double vtk_time(const char *path)
{
    cli_lines L;
    cli_read_lines(path, &L);
    for (size_t k = 0; k + 1 < L.n; k++)
        if (!strncmp(L.line[k], "TIME ", 5)) {
            double t;
            cli_parse_row(L.line[k + 1], &t, 1, path);
            cli_lines_free(&L);
            return t;
        }
    cr_assert_fail("%s: no TIME field", path);
    return NAN;
}

/* A Matrix Market file as a dense n x n matrix. */
static double *read_dense(const char *path, size_t n)
{
    cl_triplets t = {0};
    cl_error err = {0};
    cr_assert_eq(cl_mtx_read(path, &t, &err), CL_OK, "%s", err.msg);
    cr_assert(t.nrows == n && t.ncols == n, "%s: %zu x %zu, expected %zu^2",
              path, t.nrows, t.ncols, n);
    cr_assert(t.nnz > 0, "%s: no entries", path);
    double *a = calloc(n * n, sizeof *a);
    cr_assert_not_null(a);
    for (size_t k = 0; k < t.nnz; k++)
        a[t.row[k] * n + t.col[k]] += t.val[k];
    cl_triplets_free(&t);
    return a;
}

static double max_abs(const double *a, size_t n)
{
    double m = 0;
    for (size_t k = 0; k < n; k++)
        m = fmax(m, fabs(a[k]));
    return m;
}

/* ======================================================================
 * 1. Bad input: one message line "clothode...", non-zero exit, no crash.
 * ====================================================================== */

/* A NULL-terminated list of strings. */
#define LIST(...) ((const char *const[]){__VA_ARGS__, NULL})

/* `clothode ARGS --out <scratch>/o` is refused: cli_assert_error with
 * usage_lines and the strings of want. */
static void expect_refused(const char *const *args, int usage_lines,
                           const char *const *want)
{
    char out[1024];
    const char *argv[CLI_MAX_ARGS + 1];
    size_t n = 0;
    for (; args[n]; n++) {
        cr_assert(n + 2 < CLI_MAX_ARGS, "too many arguments");
        argv[n] = args[n];
    }
    argv[n++] = "--out";
    argv[n++] = in_tmp(out, "o");
    argv[n] = NULL;
    cli_result r;
    cli_runv(&r, argv);
    cli_assert_error_list(&r, usage_lines, want);
    cli_result_free(&r);
}

/* A [run] key given for a list (`set`): taken where kinsol-be of
 * kinsol-be,semi-be reads it, refused with `want` for rk4,fe, which
 * do not. */
static void list_key_served_or_refused(const char *set,
                                       const char *const *want)
{
    char out[1024];
    cli_result r;
    cli_run(&r, "convergence", "spring2", "--integrator", "kinsol-be,semi-be",
            "--set", set, "--dt", "1e-2", "--t-end", "1", "--levels", "2",
            "--out", in_tmp(out, "listkey"), "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    expect_refused(LIST("convergence", "spring2", "--integrator", "rk4,fe",
                        "--set", set, "--dt", "1e-2"), 0, want);
}

Test(cli, missing_problem_file)
{
    expect_refused(LIST("run", "problems/no-such-problem.ini"), 0,
                   LIST("no-such-problem.ini"));
}

Test(cli, missing_problem_by_name)
{
    expect_refused(LIST("run", "no-such-problem"), 0,
                   LIST("no-such-problem"));
}

/* A FIFO read as a problem, a state or an earlier run's run.json would
 * block in open until a writer comes: each is refused at once, saying
 * what it is (the test ends if one blocks). */
Test(cli, fifo_inputs_are_refused)
{
    char fifo[1024], dir[1024], manifest[1100];
    time_limit(60);
    cr_assert_eq(mkfifo(in_tmp(fifo, "fifo.ini"), 0600), 0);
    expect_refused(LIST("run", fifo), 0, LIST(fifo, "a FIFO"));
    expect_refused(LIST("eval", "hang", "--set", "cloth.n=4", "--state",
                        fifo), 0,
                   LIST(fifo, "a FIFO"));
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--t-end", "0.01",
            "--frames", "0", "--out", in_tmp(dir, "fifo-run"), "--quiet",
            NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(manifest, sizeof manifest, "%s/run.json", dir);
    cr_assert_eq(unlink(manifest), 0);
    cr_assert_eq(mkfifo(manifest, 0600), 0);
    cli_run(&r, "replay", dir, NULL);
    cli_assert_error(&r, 0, "run.json", "a FIFO", NULL);
    cli_result_free(&r);
}

Test(cli, malformed_ini_names_file_and_line)
{
    char ini[1024], out[1024], where[1100];
    tmp_put(in_tmp(ini, "broken.ini"),
            "; a problem with a broken line\n"
            "[cloth]\n"
            "n = 6\n"
            "this line is not an assignment\n"
            "size = 1.0\n");
    snprintf(where, sizeof where, "%s:4", ini);
    cli_result r;
    cli_run(&r, "run", ini, "--out", in_tmp(out, "o"), NULL);
    cli_assert_error(&r, 0, where, NULL);
    cli_result_free(&r);
}

Test(cli, unknown_key_is_named)
{
    expect_refused(LIST("run", "hang", "--set", "type1.kss=1"), 0,
                   LIST("--set: unknown key [type1] kss", "known keys in "
                        "[type1]: enabled, ks, compression, imex"));
}

Test(cli, unknown_key_in_file_is_named_with_line)
{
    char ini[1024], out[1024], where[1100];
    tmp_put(in_tmp(ini, "typo.ini"),
            "[cloth]\nn = 6\n[type1]\nks = 200\nkz = 3\n");
    snprintf(where, sizeof where, "%s:5", ini);
    cli_result r;
    cli_run(&r, "run", ini, "--out", in_tmp(out, "o"), NULL);
    cli_assert_error(&r, 0, where, "kz", NULL);
    cli_result_free(&r);
}

Test(cli, non_numeric_value)
{
    expect_refused(LIST("run", "hang", "--set", "type1.ks=abc"), 0,
                   LIST("--set: [type1] ks = \"abc\": expected a number in "
                        "[0, 1e+12]"));
}

Test(cli, nan_value)
{
    expect_refused(LIST("run", "hang", "--set", "type1.ks=nan"), 0,
                   LIST("[type1] ks = \"nan\": expected a number in [0, "
                        "1e+12]", "not a finite number"));
}

Test(cli, grid_too_small_for_type2)
{
    expect_refused(LIST("run", "hang", "--set", "cloth.n=2", "--set",
                        "type2.enabled=true"), 0,
                   LIST("2 x 2", "3"));
}

Test(cli, dt_zero)
{
    expect_refused(LIST("run", "hang", "--integrator", "symplectic-euler",
                        "--dt", "0", "--t-end", "0.01"), 0,
                   LIST("--dt: [run] dt = 0: integrator symplectic-euler "
                        "takes fixed steps and needs dt > 0"));
}

Test(cli, dt_negative)
{
    expect_refused(LIST("run", "hang", "--integrator", "symplectic-euler",
                        "--dt", "-1", "--t-end", "0.01"), 0,
                   LIST("dt", "-1"));
}

/* A study whose output directory cannot be made fails before its work
 * (exit 7, nothing of a table printed): before, stability computed its
 * limits, printed them and only then failed, and with --quiet nothing was
 * kept. */
Test(cli, study_output_directory_checked_before_the_work)
{
    cli_result r;
    cli_run(&r, "stability", "spring2", "--integrator", "rk4", "--t-end",
            "0.2", "--out", "/proc/no-such-dir", NULL);
    cli_assert_error(&r, 0, "cannot create directory '/proc/no-such-dir'",
                     NULL);
    cr_assert_eq(r.status, 7);
    cr_assert_str_eq(r.out, "");
    cli_result_free(&r);
}

Test(cli, threads_out_of_range)
{
    expect_refused(LIST("run", "hang", "--threads", "0", "--t-end", "0.01"),
                   0, LIST("--threads: [run] threads = \"0\": expected an "
                           "integer in [1, 64]"));
    expect_refused(LIST("run", "hang", "--threads", "1000", "--t-end",
                        "0.01"), 0, LIST("threads = \"1000\"", "[1, 64]"));
}

Test(cli, max_order_only_for_cvode_and_ida)
{
    expect_refused(LIST("run", "hang", "--integrator", "semi-be", "--dt",
                        "1e-3", "--max-order", "2", "--t-end", "0.01"), 0,
                   LIST("max_order", "semi-be"));
    expect_refused(LIST("run", "hang", "--max-order", "13", "--t-end",
                        "0.01"), 0, LIST("max_order", "13"));
    /* above the method's own highest order: an input refused (exit 2),
     * not a solver failure (exit 3) */
    static const char *const bdf[] = {"cvode-bdf", "ida"};
    for (int k = 0; k < 2; k++)
        expect_refused(LIST("run", "spring2", "--integrator", bdf[k],
                            "--max-order", "6"), 0,
                       LIST(bdf[k], "max_order = 6", "above the method's "
                            "highest order (5 for BDF"));
}

Test(cli, substeps_and_iterations_only_for_xpbd_and_pd)
{
    expect_refused(LIST("run", "hang", "--integrator", "semi-be", "--dt",
                        "1e-3", "--substeps", "4", "--t-end", "0.01"), 0,
                   LIST("substeps", "semi-be", "xpbd and pd"));
    expect_refused(LIST("run", "hang", "--iterations", "3", "--t-end",
                        "0.01"), 0, LIST("iterations", "cvode-bdf"));
    expect_refused(LIST("run", "hang", "--integrator", "xpbd", "--dt",
                        "1e-3", "--t-end", "0.01"), 0,
                   LIST("xpbd needs distance constraints"));
}

/* A [run] key the command line gives that the integrator does not read
 * is refused, naming who reads it; the problem file's own keys (hang.ini
 * gives rtol and atol) serve whichever integrator runs. */
Test(cli, options_the_integrator_does_not_read)
{
    expect_refused(LIST("run", "hang", "--integrator", "semi-be", "--dt",
                        "1e-3", "--rtol", "1e-3", "--t-end", "0.01"), 0,
                   LIST("--rtol", "rtol", "semi-be", "adaptive"));
    expect_refused(LIST("run", "hang", "--integrator", "semi-be", "--dt",
                        "1e-3", "--max-newton", "3", "--t-end", "0.01"), 0,
                   LIST("newton_maxit", "semi-be", "kinsol-*"));
    expect_refused(LIST("run", "hang", "--integrator", "rk4", "--dt", "1e-3",
                        "--set", "run.verlet_damping=0.1", "--t-end",
                        "0.01"), 0,
                   LIST("verlet_damping", "rk4", "verlet-pbd"));
    expect_refused(LIST("run", "hang", "--integrator", "kinsol-be", "--dt",
                        "1e-3", "--rho-inf", "0.2", "--t-end", "0.01"), 0,
                   LIST("rho_inf", "kinsol-be", "kinsol-galpha"));
    expect_refused(LIST("run", "hang", "--integrator", "semi-be", "--dt",
                        "1e-3", "--set", "run.lin_tol=1e-6", "--t-end",
                        "0.01"), 0,
                   LIST("lin_tol", "semi-be", "klu (its default)"));
    expect_refused(LIST("run", "hang", "--integrator", "cvode-bdf:pcg",
                        "--set", "run.lin_tol=1e-6", "--t-end", "0.01"), 0,
                   LIST("lin_tol", "cvode-bdf", "pcg",
                        "tolerance themselves"));
    char out[1024];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--integrator",
            "semi-be:pcg", "--dt", "1e-3", "--set", "run.lin_tol=1e-6",
            "--t-end", "0.002", "--frames", "0", "--out",
            in_tmp(out, "lintol"), "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    /* cvode-bdf's default solver, auto, is iterative and reads lin_maxit;
     * klu does not */
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--integrator",
            "cvode-bdf", "--set", "run.lin_maxit=50", "--t-end", "0.002",
            "--frames", "0", "--out", in_tmp(out, "linmaxit"), "--quiet",
            NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    expect_refused(LIST("run", "hang", "--integrator", "cvode-bdf:klu",
                        "--set", "run.lin_maxit=50", "--t-end", "0.01"), 0,
                   LIST("lin_maxit", "linear solver klu"));
    list_key_served_or_refused("run.newton_tol=1e-12",
                               LIST("newton_tol",
                                    "no integrator of the list"));
}

Test(cli, fixed_step_without_dt)
{
    expect_refused(LIST("run", "hang", "--integrator", "symplectic-euler",
                        "--t-end", "0.01"), 0,
                   LIST("dt", "symplectic-euler"));
}

Test(cli, unknown_integrator_lists_the_allowed)
{
    expect_refused(LIST("run", "hang", "--integrator", "rk4-magic"), 0,
                   LIST("rk4-magic", "cvode-bdf", "symplectic-euler"));
}

Test(cli, unknown_subcommand)
{
    cli_result r;
    cli_run(&r, "frobnicate", "hang", NULL);
    cli_assert_error(&r, 1, "frobnicate", NULL);
    cli_result_free(&r);
}

Test(cli, unknown_option)
{
    expect_refused(LIST("run", "hang", "--frobnicate"), 1,
                   LIST("--frobnicate"));
    cli_result r;
    cli_run(&r, "eval", "hang", "--state", "x.csv", "--frobnicate", NULL);
    cli_assert_error(&r, 1, "--frobnicate", NULL);
    cli_result_free(&r);
    cli_run(&r, "counts", "--frobnicate", NULL);
    cli_assert_error(&r, 1, "--frobnicate", NULL);
    cli_result_free(&r);
}

Test(cli, option_without_its_value)
{
    cli_result r;
    cli_run(&r, "run", "hang", "--dt", NULL);
    cli_assert_error(&r, 1, "--dt", NULL);
    cli_result_free(&r);
}

Test(cli, t_end_not_a_multiple_of_dt)
{
    expect_refused(LIST("run", "hang", "--set", "cloth.n=6", "--integrator",
                        "symplectic-euler", "--dt", "3e-4", "--t-end",
                        "0.05"), 0,
                   LIST("t_end", "0.05", "dt"));
}

Test(cli, pin_outside_the_grid)
{
    expect_refused(LIST("run", "hang", "--set", "pins.at=0,99"), 0,
                   LIST("--set: [pins] at: pin (0, 99) lies outside the 16 x "
                        "16 grid (allowed: 0..15, 0..15"));
}

/* The files of `names` hold the same lines in directories a and b. */
static void assert_same_files(const char *a, const char *b,
                              const char *const *names)
{
    for (; *names; names++) {
        char pa[1300], pb[1300];
        cli_lines la, lb;
        snprintf(pa, sizeof pa, "%s/%s", a, *names);
        snprintf(pb, sizeof pb, "%s/%s", b, *names);
        cli_read_lines(pa, &la);
        cli_read_lines(pb, &lb);
        cr_assert_eq(la.n, lb.n, "%s: %zu and %zu lines", *names, la.n,
                     lb.n);
        for (size_t k = 0; k < la.n; k++)
            cr_assert_str_eq(la.line[k], lb.line[k], "%s line %zu differs",
                             *names, k + 1);
        cli_lines_free(&la);
        cli_lines_free(&lb);
    }
}

/* Run the config.ini a run wrote into `out` again, into `again`. */
static void rerun_config(const char *out, const char *again)
{
    char path[1200];
    cli_result r;
    snprintf(path, sizeof path, "%s/config.ini", out);
    cli_run(&r, "run", path, "--out", again, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
}

/* ---- strict inputs: each refused with file, line and key -------------- */

/* Run the problem `text` (written to the scratch directory as p.ini, each
 * '@' as a NUL byte) with the arguments `extra`; it must be refused with
 * one message naming p.ini:LINE and holding every string of want, and
 * write nothing. */
static void expect_file_refused(const char *text, int line,
                                const char *const *extra,
                                const char *const *want)
{
    char ini[1024], where[1100], out[1024];
    in_tmp(ini, "p.ini");
    FILE *f = fopen(ini, "wb");
    cr_assert_not_null(f);
    for (const char *c = text; *c; c++)
        fputc(*c == '@' ? '\0' : *c, f);
    cr_assert_eq(fclose(f), 0);
    const char *argv[CLI_MAX_ARGS + 1] = {"run", ini, "--out",
                                          in_tmp(out, "o")};
    size_t n = 4;
    for (; extra && *extra; extra++)
        argv[n++] = *extra;
    argv[n] = NULL;
    cli_result r;
    cli_runv(&r, argv);
    snprintf(where, sizeof where, "%s:%d: ", ini, line);
    cli_assert_error(&r, 0, where, NULL);
    cli_assert_error_list(&r, 0, want);
    cli_result_free(&r);
    cr_assert(!cli_exists(out), "%s: output written for a refused input",
              out);
}

Test(cli, duplicate_key_refused)
{
    expect_file_refused("[cloth]\nn = 6\nsize = 1\nn = 8\n", 4, NULL,
                        LIST("duplicate key [cloth] n (first on line 2)"));
}

Test(cli, duplicate_section_refused)
{
    expect_file_refused("[cloth]\nn = 6\n[type1]\nks = 200\n[cloth]\n"
                        "size = 1\n", 5, NULL,
                        LIST("duplicate section [cloth] (opened on line 1)"));
}

Test(cli, nul_byte_refused)
{
    expect_file_refused("[cloth]\nn = 6\n[type1]\nks = 2@00\n", 4, NULL,
                        LIST("NUL byte at column 7"));
}

Test(cli, empty_file_refused)
{
    expect_file_refused("", 1, NULL, LIST("no key = value line"));
    expect_file_refused("; only a comment\n[cloth]\n", 1, NULL,
                        LIST("no key = value line"));
}

Test(cli, pin_index_overflow_refused)
{
    expect_file_refused("[cloth]\nn = 6\n[pins]\nat = 0,0 4294967296,0\n",
                        4, NULL,
                        LIST("[pins] at: \"4294967296\": index beyond"
                             " the range of an int"));
}

Test(cli, integer_overflow_refused)
{
    expect_file_refused("[cloth]\nn = 99999999999999999999\n", 2, NULL,
                        LIST("[cloth] n = \"99999999999999999999\":"
                             " expected an integer in [2, 4096]"));
}

Test(cli, non_finite_and_absurd_values_refused)
{
    expect_file_refused("[cloth]\nn = 6\n[type1]\nks = inf\n", 4, NULL,
                        LIST("[type1] ks = \"inf\": expected a number in"
                             " [0, 1e+12] (this is not a finite number)"));
    expect_file_refused("[cloth]\nn = 6\n[type1]\nks = 1e300\n", 4, NULL,
                        LIST("[type1] ks = \"1e300\": expected a number in"
                             " [0, 1e+12]"));
    expect_file_refused("[cloth]\nn = 6\n[damping]\nkd = 1e-999\n", 4,
                        NULL, LIST("[damping] kd = \"1e-999\"",
                                   "rounds to a subnormal number or zero"));
}

Test(cli, over_long_line_refused)
{
    char text[512] = "[cloth]\nn = 6\n; ";
    memset(text + strlen(text), 'x', 300);
    strcat(text, "\n");
    expect_file_refused(text, 3, NULL,
                        LIST("line of 302 characters; the INI parser reads"
                             " lines of at most 197"));
}

Test(cli, key_set_twice_refused)
{
    expect_refused(LIST("run", "hang", "--set", "type1.ks=100", "--set",
                        "type1.ks=300"), 0,
                   LIST("[type1] ks is already set by an earlier --set"));
    expect_refused(LIST("run", "hang", "--rtol", "1e-5", "--set",
                        "run.rtol=1e-6"), 0,
                   LIST("--set \"run.rtol=1e-6\": [run] rtol is already set "
                        "by --rtol"));
    /* an option given twice names the option, not a --set */
    expect_refused(LIST("run", "hang", "--t-end", "0.1", "--t-end", "0.2"),
                   0, LIST("--t-end 0.2: [run] t_end is already set by "
                           "--t-end; give each key once"));
    /* an option of no key too, where the last would win silently */
    expect_refused(LIST("run", "hang", "--out", "a"), 1,
                   LIST("option --out given twice; give it once"));
}

/* A problem whose files are named relative to it reads back from the
 * config.ini its run wrote elsewhere: same series, same final state. */
Test(cli, config_ini_of_a_mesh_problem_reads_back)
{
    char out[1024], again[1024];
    cli_result r;
    cli_run(&r, "run", "skirt", "--t-end", "0.002", "--frames", "0",
            "--out", in_tmp(out, "first"), "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    rerun_config(out, in_tmp(again, "again"));
    assert_same_files(out, again,
                      LIST("series.csv", "final.csv", "config.ini"));
}

/* problems/NAME.ini goes to out/NAME, any other NAME.ini to
 * out/NAME-HASH: two problems of one name never share a directory. */
Test(cli, default_out_is_problem_specific)
{
    char a[1024], b[1024], buf[4096], first[4096];
    cl_cli_default_out("problems/hang.ini", buf, sizeof buf);
    cr_assert_str_eq(buf, "out/hang");
    tmp_put(in_tmp(a, "hang.ini"), "[cloth]\nn = 6\n");
    snprintf(b, sizeof b, "%s/sub", tmp);
    cr_assert_eq(mkdir(b, 0700), 0);
    tmp_put(in_tmp(b, "sub/hang.ini"), "[cloth]\nn = 6\n");
    cl_cli_default_out(a, first, sizeof first);
    cl_cli_default_out(b, buf, sizeof buf);
    cr_assert(!strncmp(first, "out/hang-", 9) && strlen(first) == 17,
              "%s", first);
    cr_assert(!strncmp(buf, "out/hang-", 9) && strlen(buf) == 17, "%s",
              buf);
    cr_assert_str_neq(first, buf);
    cl_cli_default_out("x/hang.coarse.ini", buf, sizeof buf);
    cr_assert(!strncmp(buf, "out/hang.coarse", 15), "%s", buf);
}

/* A run its integrator refuses (an unknown linear solver, a step that
 * does not divide t_end) leaves the earlier run in its directory as it
 * was. */
Test(cli, refused_run_keeps_the_earlier_one)
{
    char out[1024], path[1100], before[8192], after[8192];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--t-end", "0.02",
            "--out", in_tmp(out, "kept"), "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/run.json", out);
    tmp_slurp(path, before, sizeof before);
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--t-end", "0.02",
            "--linsol", "bogus", "--out", out, "--quiet", NULL);
    cli_assert_error(&r, 0, "unknown linear solver \"bogus\"", NULL);
    cli_result_free(&r);
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--t-end", "0.1",
            "--integrator", "rk4", "--dt", "0.03", "--out", out, "--quiet",
            NULL);
    cli_assert_error(&r, 0, "not a whole number of steps", NULL);
    cli_result_free(&r);
    tmp_slurp(path, after, sizeof after);
    cr_assert_str_eq(after, before, "run.json changed");
    snprintf(path, sizeof path, "%s/final.csv", out);
    cr_assert(cli_exists(path), "the earlier run's final.csv was removed");
}

/* ---- the memory guard --------------------------------------------------- */

/* 200 x 200 particles: the dense Newton matrix alone is 2 (2n)^2 8 bytes
 * = 922 GB, refused before anything is allocated or written. */
Test(cli, memory_guard_refuses_a_dense_solver_on_a_large_cloth)
{
    char out[1024];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=200", "--integrator",
            "cvode-bdf-dense", "--out", in_tmp(out, "o"), NULL);
    cli_assert_error(&r, 0, "cvode-bdf-dense: the Jacobian and the factors"
                     " of the Newton matrix need about 922 GB (119994"
                     " unknowns), more than the", "--force", NULL);
    cli_result_free(&r);
    cr_assert(!cli_exists(out), "output directory made for a refused run");
    /* --force passes the guard: the dense solver's own limit speaks */
    cli_run(&r, "run", "hang", "--set", "cloth.n=200", "--integrator",
            "cvode-bdf-dense", "--force", "--out", out, NULL);
    cli_assert_error(&r, 0, "the dense solver is limited to", NULL);
    cli_result_free(&r);
}

/* ---- solver failures name the option to change --------------------------- */

Test(cli, solver_failure_names_the_option)
{
    expect_refused(LIST("run", "hang", "--set", "cloth.n=6", "--set",
                        "run.max_steps=2", "--t-end", "0.5", "--quiet"), 0,
                   LIST("CV_TOO_MUCH_WORK", "to change: raise the steps"
                        " allowed per output interval (--set"
                        " run.max_steps=N"));
}

/* eval's state is required, as --state or as the key [eval] state, which
 * a --set (or the problem file) may give (before: refused unless given as
 * --state, though its help names the key). */
Test(cli, eval_without_state)
{
    expect_refused(LIST("eval", "hang"), 0,
                   LIST("--state FILE ([eval] state) is required"));
    char out[1024], state[1100], set[1200];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--t-end", "0.01",
            "--frames", "0", "--quiet", "--out", in_tmp(out, "st"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(state, sizeof state, "%s/final.csv", out);
    snprintf(set, sizeof set, "eval.state=%s", state);
    cli_run(&r, "eval", "hang", "--set", "cloth.n=4", "--set", set, "--out",
            in_tmp(out, "ev"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
}

/* The whole content of the file at `path`. */
static char *file_text(const char *path)
{
    FILE *fp = fopen(path, "r");
    cr_assert_not_null(fp, "cannot open %s", path);
    char *text = cli_slurp_fp(fp);
    fclose(fp);
    return text;
}

/* A valid rest state of hang at n = 6 as CSV text, for corrupting. */
static char *rest_state_text(void)
{
    const char *sets[] = {"cloth.n=6", NULL};
    cl_model *m = load_model("hang", sets);
    const cl_cloth *c = cl_model_cloth(m);
    char path[1024];
    double *v = calloc(3 * c->np, sizeof *v);
    write_state(in_tmp(path, "rest.csv"), c->np, c->X0, v);
    free(v);
    free_model(m);
    return file_text(path);
}

/* Run eval of hang (n = 6) on a state file written from `text`. */
static void eval_text(cli_result *r, const char *text, char *state)
{
    char out[1024];
    tmp_put(in_tmp(state, "state.csv"), text);
    cli_run(r, "eval", "hang", "--set", "cloth.n=6", "--state", state,
            "--out", in_tmp(out, "eval"), NULL);
}

Test(cli, eval_state_wrong_header)
{
    char *text = rest_state_text(), state[1024], where[1100];
    char *body = strchr(text, '\n');
    char *bad = malloc(strlen(text) + 32);
    sprintf(bad, "p,x,y,z,vx,vy%s", body);
    cli_result r;
    eval_text(&r, bad, state);
    snprintf(where, sizeof where, "%s:1", state);
    cli_assert_error(&r, 0, where, "expected header \"p,x,y,z,vx,vy,vz\", "
                     "found \"p,x,y,z,vx,vy\"", NULL);
    cli_result_free(&r);
    free(bad);
    free(text);
}

Test(cli, eval_state_missing_particle)
{
    char *text = rest_state_text(), state[1024];
    /* drop the row of particle 7 (line 9) */
    char *row = strstr(text, "\n7,");
    cr_assert_not_null(row);
    char *next = strchr(row + 1, '\n');
    memmove(row, next, strlen(next) + 1);
    cli_result r;
    eval_text(&r, text, state);
    cli_assert_error(&r, 0, state, "particle 7", NULL);
    cli_result_free(&r);
    free(text);
}

Test(cli, eval_state_non_numeric)
{
    char *text = rest_state_text(), state[1024], where[1100];
    /* particle 9 is on line 11; its x becomes "abc" */
    char *row = strstr(text, "\n9,");
    cr_assert_not_null(row);
    char *x = row + 3, *end = strchr(x, ',');
    cr_assert_not_null(end);
    char *bad = malloc(strlen(text) + 8);
    sprintf(bad, "%.*sabc%s", (int)(x - text), text, end);
    cli_result r;
    eval_text(&r, bad, state);
    free(bad);
    snprintf(where, sizeof where, "%s:11", state);
    cli_assert_error(&r, 0, where, "abc", NULL);
    cli_result_free(&r);
    free(text);
}

Test(cli, eval_state_missing_file)
{
    char state[1024], out[1024];
    cli_result r;
    cli_run(&r, "eval", "hang", "--state", in_tmp(state, "none.csv"),
            "--out", in_tmp(out, "eval"), NULL);
    cli_assert_error(&r, 0, "none.csv", NULL);
    cli_result_free(&r);
}

/* Two outputs of one eval in one file are refused before any work,
 * however the path is spelt: a Jacobian over forces.csv, or both Jacobians
 * in one file; so are an empty name for a Jacobian and an output over an
 * input. */
Test(cli, eval_outputs_in_one_file_are_refused)
{
    char out[1024], state[1024], jac[1100], other[1100];
    tmp_put(in_tmp(state, "s.csv"), "p,x,y,z,vx,vy,vz\n");
    in_tmp(out, "same");
    snprintf(jac, sizeof jac, "%s/forces.csv", out);
    cli_result r;
    cli_run(&r, "eval", "hang", "--state", state, "--jacobian", jac, "--out",
            out, NULL);
    cli_assert_error(&r, 0, "the same file as forces.csv in --out", NULL);
    cli_result_free(&r);
    snprintf(jac, sizeof jac, "%s/J.mtx", tmp);
    snprintf(other, sizeof other, "%s/../%s/J.mtx", tmp, strrchr(tmp, '/') + 1);
    cli_run(&r, "eval", "hang", "--state", state, "--jacobian", jac,
            "--jacobian-v", other, "--out", out, NULL);
    cli_assert_error(&r, 0, "the same file as --jacobian", NULL);
    cli_result_free(&r);
    /* an empty name, which would read as no Jacobian */
    cli_run(&r, "eval", "hang", "--state", state, "--jacobian-v", "",
            "--out", out, NULL);
    cli_assert_error(&r, 0, "[eval] jacobian_v = \"\": an empty file name",
                     NULL);
    cli_result_free(&r);
    /* an input as an output: the state (before, overwritten by the
     * Jacobian), the problem file */
    cli_run(&r, "eval", "hang", "--state", state, "--jacobian", state,
            "--out", out, NULL);
    cli_assert_error(&r, 0, "the same file as --state", NULL);
    cli_result_free(&r);
    static char text[64];
    tmp_slurp(state, text, sizeof text);
    cr_assert_str_eq(text, "p,x,y,z,vx,vy,vz\n");
    cli_run(&r, "eval", "problems/hang.ini", "--state", state,
            "--jacobian-v", "problems/../problems/hang.ini", "--out", out,
            NULL);
    cli_assert_error(&r, 0, "the same file as the problem", NULL);
    cli_result_free(&r);
}

/* Options of one mode of a study given in the other, where they would
 * be ignored, are refused: damping's --equilibrium without --modes,
 * contact's --dt-max without --k. */
Test(cli, options_of_another_mode_are_refused)
{
    expect_refused(LIST("damping", "spring2", "--integrator", "semi-be",
                        "--equilibrium"), 0,
                   LIST("--equilibrium goes with --modes T"));
    expect_refused(LIST("contact", "particle-floor", "--integrator",
                        "symplectic-euler", "--dt", "1e-3", "--dt-max",
                        "1e-3"), 0,
                   LIST("--dt-max ([contact] dt_max) goes with --k LIST"));
}

/* ======================================================================
 * 2. A small run and its outputs.
 * ====================================================================== */

#define RUN_N 6
#define RUN_NP (RUN_N * RUN_N)

Test(cli, run_writes_its_outputs)
{
    char out[1024], path[1200];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--t-end", "0.05",
            "--integrator", "symplectic-euler", "--dt", "1e-4", "--frames",
            "2", "--out", in_tmp(out, "run"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);

    /* config.ini: the problem with the options as [run] keys, as given;
     * keys left to their defaults are not written */
    snprintf(path, sizeof path, "%s/config.ini", out);
    cl_config *cfg = cl_config_alloc();
    cl_error err = {0};
    cr_assert_eq(cl_config_load(cfg, path, &err), CL_OK, "%s", err.msg);
    static const char *const saved[][3] = {
        {"cloth", "n", "6"}, {"run", "t_end", "0.05"},
        {"run", "integrator", "symplectic-euler"}, {"run", "dt", "1e-4"},
        {"run", "frames", "2"}, {"type1", "ks", "200"}};
    for (size_t k = 0; k < sizeof saved / sizeof *saved; k++)
        cr_assert_str_eq(cl_config_string(cfg, saved[k][0], saved[k][1], ""),
                         saved[k][2], "[%s] %s", saved[k][0], saved[k][1]);
    cr_assert_null(cl_config_string(cfg, "run", "samples", NULL));
    cl_config_free(cfg);

    /* series.csv: t = 0 and 200 samples (the default), 0 .. t_end */
    series s;
    snprintf(path, sizeof path, "%s/series.csv", out);
    read_series(path, &s);
    cr_assert(!strncmp(s.header, "t,kinetic", 9), "header \"%s\"", s.header);
    cr_assert_eq(s.nrow, 201, "series.csv has %zu rows, expected 201",
                 s.nrow);
    cr_assert_eq(s.v[0], 0.0);
    cr_assert(fabs(s.v[(s.nrow - 1) * s.ncol] - 0.05) < 1e-12,
              "last sample at t = %g", s.v[(s.nrow - 1) * s.ncol]);
    for (size_t k = 1; k < s.nrow; k++)
        cr_assert_gt(s.v[k * s.ncol], s.v[(k - 1) * s.ncol],
                     "series.csv: t not increasing at row %zu", k + 1);
    free(s.v);

    /* final.csv: every particle; the pinned ones where they were put */
    const char *sets[] = {"cloth.n=6", NULL};
    cl_model *m = load_model("hang", sets);
    const cl_cloth *c = cl_model_cloth(m);
    cr_assert_eq(c->np, RUN_NP);
    double x[3 * RUN_NP], v[3 * RUN_NP];
    snprintf(path, sizeof path, "%s/final.csv", out);
    cli_read_state(path, RUN_NP, x, v);
    size_t npinned = 0;
    double fall = 0;
    for (size_t p = 0; p < RUN_NP; p++) {
        if (c->dof[p] >= 0) {
            fall = fmax(fall, -x[3 * p + 1]);
            continue;
        }
        npinned++;
        for (int d = 0; d < 3; d++) {
            cr_assert_eq(x[3 * p + d], c->X0[3 * p + d],
                         "pinned particle %zu moved: x[%d] = %.17g, rest "
                         "%.17g", p, d, x[3 * p + d], c->X0[3 * p + d]);
            cr_assert_eq(v[3 * p + d], 0.0, "pinned particle %zu moves", p);
        }
    }
    cr_assert_eq(npinned, 2);
    cr_assert(fall > 1e-3, "the cloth did not fall (max drop %g m)", fall);
    free_model(m);

    /* stats.csv: 0.05 / 1e-4 steps */
    snprintf(path, sizeof path, "%s/stats.csv", out);
    cr_assert_eq(stat_of(path, "steps"), 500.0);

    /* frames 0, 1, 2 in both formats, no more */
    for (int k = 0; k <= 2; k++)
        for (int f = 0; f < 2; f++) {
            snprintf(path, sizeof path, "%s/frame_%05d.%s", out, k,
                     f ? "obj" : "vtk");
            cr_assert(cli_exists(path), "missing or empty %s", path);
        }
    cr_assert_eq(count_prefixed(out, "frame_", NULL, 0), 6);
    for (int k = 0; k <= 2; k++) {
        snprintf(path, sizeof path, "%s/frame_%05d.vtk", out, k);
        double t = vtk_time(path);
        cr_assert(fabs(t - 0.025 * k) < 1e-12, "frame %d at t = %g", k, t);
    }
    snprintf(path, sizeof path, "%s/config.ini", out);
    cr_assert(cli_exists(path), "missing or empty %s", path);
    assert_no_temporaries(out);
}

/* config.ini is the problem as run: running it again gives the same
 * series and final state, bit for bit. */
Test(cli, run_config_ini_reproduces_the_run)
{
    char out[1024], again[1024];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--t-end", "0.01",
            "--integrator", "symplectic-euler", "--dt", "1e-4", "--frames",
            "0", "--set", "type1.ks=150", "--out", in_tmp(out, "first"),
            "--quiet", NULL);
    cli_assert_ok(&r);
    cr_assert_str_empty(r.out, "--quiet printed:\n%s", r.out);
    cli_result_free(&r);
    rerun_config(out, in_tmp(again, "again"));

    /* the same series (samples, formats: the defaults again) and state */
    assert_same_files(out, again, LIST("series.csv", "final.csv"));
}

/* The file `name` of two run directories, as lines. */
static void read_pair(const char *a, const char *b, const char *name,
                      cli_lines *la, cli_lines *lb)
{
    char pa[1300], pb[1300];
    snprintf(pa, sizeof pa, "%s/%s", a, name);
    snprintf(pb, sizeof pb, "%s/%s", b, name);
    cli_read_lines(pa, la);
    cli_read_lines(pb, lb);
}

/* A run from a state ([init] state = the final.csv of a run to T) of a
 * problem whose pins and forces do not change with time continues that
 * run: with a one-step method of fixed steps, run to T and then from its
 * state for T more, it ends bit for bit where one run to 2T ends, and its
 * series is the second half of that run's (t counted from the state).
 * The state in the output directory itself is refused. */
Test(cli, run_from_a_state_continues_the_run)
{
    char whole[1024], first[1024], second[1024], state[1100], set[1200];
    const char *common[] = {"run", "hang", "--set", "cloth.n=6",
                            "--integrator", "semi-be", "--dt", "1e-3",
                            "--frames", "0", "--quiet", "--t-end"};
    enum { NC = sizeof common / sizeof *common };
    const char *args[NC + 8];
    memcpy(args, common, sizeof common);
    const char *tail1[] = {"0.02", "--samples", "4", "--out",
                           in_tmp(whole, "whole"), NULL};
    memcpy(args + NC, tail1, sizeof tail1);
    cli_run_ok(args);
    const char *tail2[] = {"0.01", "--samples", "2", "--out",
                           in_tmp(first, "first"), NULL};
    memcpy(args + NC, tail2, sizeof tail2);
    cli_run_ok(args);
    snprintf(state, sizeof state, "%s/final.csv", first);
    snprintf(set, sizeof set, "init.state=%s", state);
    const char *tail3[] = {"0.01", "--samples", "2", "--set", set, "--out",
                           in_tmp(second, "second"), NULL};
    memcpy(args + NC, tail3, sizeof tail3);
    cli_run_ok(args);
    assert_same_files(whole, second, LIST("final.csv"));

    cli_lines la, lb;
    read_pair(whole, second, "series.csv", &la, &lb);
    cr_assert_eq(la.n, 6, "header and 5 rows, %zu lines", la.n);
    cr_assert_eq(lb.n, 4, "header and 3 rows, %zu lines", lb.n);
    cr_assert_str_eq(la.line[0], lb.line[0]);
    for (size_t k = 1; k < lb.n; k++) /* all but t */
        cr_assert_str_eq(strchr(la.line[k + 2], ','), strchr(lb.line[k], ','),
                         "row %zu of the second half differs", k);
    cli_lines_free(&la);
    cli_lines_free(&lb);

    /* continued into its own directory: refused before anything goes
     * (before: the earlier run's files, final.csv among them, were
     * removed, then the state could not be read) */
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--set", set, "--out",
            first, NULL);
    cli_assert_error(&r, 0, "in the output directory", NULL);
    cli_result_free(&r);
    cr_assert(cli_exists(state), "%s was removed", state);
}

/* The command `common` (NULL-ended, without --t-end and --out) run to
 * t_end into DIR/<tag>whole, to t_half into <tag>first, and from that
 * run's final.csv at its time to t_end into <tag>second (1024 bytes
 * each). */
static void run_in_two(const char *const *common, const char *t_half,
                       const char *t_end, const char *tag, char *whole,
                       char *first, char *second)
{
    char name[64], state[1200], when[80];
    char *dir[3] = {whole, first, second};
    static const char *const part[3] = {"whole", "first", "second"};
    const char *args[CLI_MAX_ARGS + 1];
    size_t n = 0;
    for (; common[n]; n++)
        args[n] = common[n];
    cr_assert_lt(n + 9, CLI_MAX_ARGS);
    for (int k = 0; k < 3; k++) {
        size_t at = n;
        snprintf(name, sizeof name, "%s%s", tag, part[k]);
        args[at++] = "--t-end";
        args[at++] = k == 1 ? t_half : t_end;
        args[at++] = "--out";
        args[at++] = in_tmp(dir[k], name);
        if (k == 2) {
            snprintf(state, sizeof state, "init.state=%s/final.csv", first);
            snprintf(when, sizeof when, "init.time=%s", t_half);
            args[at++] = "--set";
            args[at++] = state;
            args[at++] = "--set";
            args[at++] = when;
        }
        args[at] = NULL;
        cli_run_ok(args);
    }
}

/* Moving pins: compress's ends pushed in at 0.1 m/s.  Continued from its
 * state at t = 0.1 with [init] time = 0.1 to 0.2, a run ends where one
 * run to 0.2 ends, to round-off (the pins' times t0 + k dt against
 * k dt), its series starting at t = 0.1; spectrum linearises there as
 * at --state FILE --t 0.1; a study to a t_end not after it is refused,
 * and a time the state was not saved at is refused by the pins. */
Test(cli, run_from_a_state_at_its_time)
{
    char whole[1024], first[1024], second[1024], state[1100], set[1200];
    const char *common[] = {"run", "compress", "--set", "cloth.nu=11",
                            "--integrator", "semi-be", "--dt", "1e-3",
                            "--frames", "0", "--quiet", "--samples", "2",
                            NULL};
    run_in_two(common, "0.1", "0.2", "c", whole, first, second);
    snprintf(state, sizeof state, "%s/final.csv", first);
    snprintf(set, sizeof set, "init.state=%s", state);
    cli_lines la, lb;
    read_pair(whole, second, "final.csv", &la, &lb);
    cr_assert_eq(la.n, lb.n);
    double worst = 0.0;
    for (size_t k = 1; k < la.n; k++) {
        double a[7], b[7];
        cli_parse_row(la.line[k], a, 7, "final.csv");
        cli_parse_row(lb.line[k], b, 7, "final.csv");
        for (int i = 1; i < 7; i++)
            worst = fmax(worst, fabs(a[i] - b[i]));
    }
    cr_assert_lt(worst, 1e-12, "continued run %g from the whole run",
                 worst);
    cli_lines_free(&la);
    cli_lines_free(&lb);
    read_pair(whole, second, "series.csv", &la, &lb);
    cr_assert(!strncmp(lb.line[1], "0.1,", 4), "first row %s", lb.line[1]);
    cli_lines_free(&la);
    cli_lines_free(&lb);

    /* spectrum linearises at [init] time unless --t says otherwise */
    char sa[1024], sb[1024];
    cli_run_ok(LIST("spectrum", "compress", "--set", "cloth.nu=11",
                    "--state", state, "--t", "0.1", "--quiet", "--out",
                    in_tmp(sa, "cspa")));
    cli_run_ok(LIST("spectrum", "compress", "--set", "cloth.nu=11", "--set",
                    set, "--set", "init.time=0.1", "--quiet", "--out",
                    in_tmp(sb, "cspb")));
    assert_same_files(sa, sb, LIST("spectrum.csv"));

    cli_result r;
    cli_run(&r, "stability", "compress", "--set", "cloth.nu=11",
            "--integrator", "semi-be", "--t-end", "0.1", "--set", set,
            "--set", "init.time=0.1", "--out", in_tmp(second, "cstab"), NULL);
    cli_assert_error(&r, 0, "t_end = 0.1 is not after [init] time = 0.1",
                     NULL);
    cli_result_free(&r);
    cli_run(&r, "run", "compress", "--set", "cloth.nu=11", "--set", set,
            "--set", "init.time=0.05", "--out", in_tmp(second, "cbad"),
            NULL);
    cli_assert_error(&r, 0, "pinned particle", "[init] time = 0.05", NULL);
    cli_result_free(&r);
}

/* The studies run from [init] time to t_end: on hang, whose forces and
 * pins do not change with time, a state's stability and energy balance
 * from t = 0.2 to 0.5 are those from t = 0 to 0.3, but for the times
 * they name (and CPU times); before, the studies refused the start. */
Test(cli, studies_from_a_state_at_its_time)
{
    char run[1024], a[1024], b[1024], set[1100];
    cli_run_ok(LIST("run", "hang", "--set", "cloth.n=8", "--integrator",
                    "semi-be", "--dt", "1e-3", "--t-end", "0.2", "--frames",
                    "0", "--quiet", "--out", in_tmp(run, "srun")));
    snprintf(set, sizeof set, "init.state=%s/final.csv", run);
    cli_run_ok(LIST("stability", "hang", "--set", "cloth.n=8", "--set", set,
                    "--integrator", "symplectic-euler", "--t-end", "0.3",
                    "--quiet", "--out", in_tmp(a, "sstab0")));
    cli_run_ok(LIST("stability", "hang", "--set", "cloth.n=8", "--set", set,
                    "--set", "init.time=0.2", "--integrator",
                    "symplectic-euler", "--t-end", "0.5", "--quiet", "--out",
                    in_tmp(b, "sstab2")));
    cli_lines la, lb;
    read_pair(a, b, "stability.csv", &la, &lb);
    cr_assert_eq(la.n, lb.n);
    cr_assert_geq(la.n, 3, "at least two trials");
    for (size_t k = 1; k < la.n; k++) { /* dt, steps, stable, status */
        const char *ea = la.line[k], *eb = lb.line[k];
        for (int f = 0; f < 5; f++) {
            const char *na = strchr(ea, ','), *nb = strchr(eb, ',');
            cr_assert(na && nb && na - ea == nb - eb &&
                          !strncmp(ea, eb, (size_t)(na - ea)),
                      "row %zu field %d: %s | %s", k, f, la.line[k],
                      lb.line[k]);
            ea = na + 1;
            eb = nb + 1;
        }
    }
    cli_lines_free(&la);
    cli_lines_free(&lb);
    cli_run_ok(LIST("energy", "hang", "--set", "cloth.n=8", "--set", set,
                    "--integrator", "semi-be", "--dt", "1e-3", "--t-end",
                    "0.1", "--samples", "4", "--quiet", "--out",
                    in_tmp(a, "sen0")));
    cli_run_ok(LIST("energy", "hang", "--set", "cloth.n=8", "--set", set,
                    "--set", "init.time=0.2", "--integrator", "semi-be",
                    "--dt", "1e-3", "--t-end", "0.3", "--samples", "4",
                    "--quiet", "--out", in_tmp(b, "sen2")));
    read_pair(a, b, "energy.csv", &la, &lb);
    cr_assert_eq(la.n, 6, "header and 5 samples: %zu lines", la.n);
    cr_assert_eq(la.n, lb.n);
    for (size_t k = 1; k < la.n; k++) { /* all but t, t shifted by 0.2 */
        double ta = strtod(strchr(la.line[k], ',') + 1, NULL);
        double tb = strtod(strchr(lb.line[k], ',') + 1, NULL);
        cr_assert_float_eq(tb, ta + 0.2, 1e-12, "row %zu", k);
        cr_assert_str_eq(strchr(strchr(la.line[k], ',') + 1, ','),
                         strchr(strchr(lb.line[k], ',') + 1, ','),
                         "row %zu", k);
    }
    cli_lines_free(&la);
    cli_lines_free(&lb);
}

/* Barriers with friction carry a lag, the normal forces after the last
 * step: a run continued from a saved state starts with that state's, as
 * the run it continues had, so drape-sphere-barrier (8 x 8, kinsol-be,
 * in contact by t = 0.3 s) continued at t = 1 ends bit for bit where
 * one run ends (before: with no lag, 1.7 mm away on the full cloth). */
Test(cli, run_from_a_state_keeps_the_friction_lag)
{
    char whole[1024], first[1024], second[1024];
    run_in_two(LIST("run", "drape-sphere-barrier", "--set", "cloth.n=8",
                    "--integrator", "kinsol-be", "--dt", "0.01", "--frames",
                    "0", "--quiet", "--samples", "4"),
               "1", "1.2", "b", whole, first, second);
    assert_same_files(whole, second, LIST("final.csv"));
}

/* csv alone: the series without frames, and says so; --frames K asked
 * for with it would change nothing and is refused, as is an empty list */
Test(cli, run_format_csv_writes_no_frames)
{
    char out[1024], path[1200], first[256] = "";
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--t-end", "0.01",
            "--integrator", "symplectic-euler", "--dt", "1e-4", "--format",
            "csv", "--out", in_tmp(out, "csv"), NULL);
    cli_assert_ok(&r);
    cr_assert_not_null(strstr(r.out, "(series.csv, 0 frames,"), "%s", r.out);
    cli_result_free(&r);
    cr_assert_eq(count_prefixed(out, "frame_", first, sizeof first), 0,
                 "--format csv wrote %s", first);
    const char *want[] = {"series.csv", "final.csv", "stats.csv"};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/%s", out, want[k]);
        cr_assert(cli_exists(path), "missing or empty %s", path);
    }
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--frames", "2",
            "--format", "csv", "--out", in_tmp(out, "csv2"), NULL);
    cli_assert_error(&r, 0, "[run] frames = \"2\"", "no frame format",
                     NULL);
    cli_result_free(&r);
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--format", "",
            "--out", in_tmp(out, "csv3"), NULL);
    cli_assert_error(&r, 0, "[run] format = \"\"", "an empty list", NULL);
    cli_result_free(&r);
    /* both in one problem file: refused too (before: its frames dropped
     * without a word); a file's frames under --format csv are the file's
     * default, which the command line's format overrides */
    char ini[1200];
    static char text[1 << 14];
    tmp_slurp("problems/hang.ini", text, sizeof text);
    char *run = strstr(text, "[run]\n");
    cr_assert_not_null(run);
    snprintf(ini, sizeof ini, "%s/csvframes.ini", tmp);
    FILE *fp = fopen(ini, "w");
    cr_assert_not_null(fp);
    fprintf(fp, "%.*s[run]\nformat = csv\nframes = 5\n%s",
            (int)(run - text), text, run + 6);
    fclose(fp);
    cli_run(&r, "run", ini, "--set", "cloth.n=6", "--t-end", "0.01",
            "--out", in_tmp(out, "csv4"), NULL);
    cli_assert_error(&r, 0, "csvframes.ini:", "[run] frames = \"5\"",
                     "no frame format", NULL);
    cli_result_free(&r);
}

/* Under a data limit (ulimit -d 250 MB): a model larger than it (hang at
 * n = 512 takes about 620 MB) is refused as out of memory, exit 1, naming
 * what was available and which limit, not ended by the kernel's OOM kill;
 * a model that fits, whose Newton factors do not, is refused by the memory
 * guard against the room left.  Not under AddressSanitizer, which reserves
 * its shadow memory as data. */
#if !defined(__SANITIZE_ADDRESS__)
Test(cli, run_beyond_the_data_limit_is_refused)
{
    char out[1024];
    cli_result r;
    char *big[] = {"prlimit", "--data=250000000", (char *)cli_binary(),
                   "run", "hang", "--set", "cloth.n=512", "--frames", "0",
                   "--out", (char *)in_tmp(out, "big"), NULL};
    cli_spawn(&r, big);
    cr_assert_eq(r.status, 1, "%s", r.err);
    cli_assert_error(&r, 0, "out of memory", "the model does not fit in the",
                     "GB available (ulimit -d)", NULL);
    cli_result_free(&r);
    char *factors[] = {"prlimit", "--data=250000000", (char *)cli_binary(),
                       "run", "hang", "--set", "cloth.n=200", "--integrator",
                       "cvode-bdf:klu", "--frames", "0", "--out",
                       (char *)in_tmp(out, "klu"), NULL};
    cli_spawn(&r, factors);
    cr_assert_eq(r.status, 1, "%s", r.err);
    cli_assert_error(&r, 0, "cvode-bdf: the Jacobian and the factors",
                     "GB available (ulimit -d)", NULL);
    cli_result_free(&r);
}
#endif

Test(cli, run_bad_format)
{
    char out[1024];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--format", "vtk,png",
            "--out", in_tmp(out, "o"), NULL);
    cli_assert_error(&r, 0, "--format: [run] format = \"vtk,png\": expected "
                     "a list of csv, vtk, obj", NULL);
    cli_result_free(&r);
}

/* ======================================================================
 * 3. A blow-up: reported with its time, the rows before it published.
 * ====================================================================== */

Test(cli, blow_up_is_reported_and_the_series_kept)
{
    const double dt = 0.01, t_end = 1.0;
    char out[1024], path[1200];
    cli_result r;
    /* one sample per step, so every computed step has its row */
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator",
            "symplectic-euler", "--dt", "0.01", "--t-end", "1", "--samples",
            "100", "--frames", "0", "--out", in_tmp(out, "blow"), NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 4, "a blow-up exits 4: %d", r.status);
    cr_assert_eq(cli_count_lines(r.err), 1, "stderr:\n%s", r.err);
    cr_assert(!strncmp(r.err, "clothode", 8), "stderr:\n%s", r.err);
    const char *at = strstr(r.err, "blow-up at t = ");
    cr_assert_not_null(at, "no \"blow-up at t = \" in\n%s", r.err);
    double tb = strtod(at + strlen("blow-up at t = "), NULL);
    /* at the sixth step (dt = 0.01, far beyond symplectic Euler's limit
     * on this cloth), by the stretch test */
    cr_assert(fabs(tb - 0.06) < 1e-12 && tb < t_end, "blow-up time %g", tb);
    cr_assert(strstr(r.err, "runaway stretch (max stretch d/L = ") &&
              strstr(r.err, ", limit 10)"), "stderr:\n%s", r.err);
    /* the summary names the files written: last-good.csv, no final.csv */
    const char *o = strstr(r.out, "\noutput ");
    cr_assert_not_null(o, "no output line in\n%s", r.out);
    cr_assert(strstr(o, "last-good.csv, stats.csv") && !strstr(o, "final"),
              "%s", o);
    cli_result_free(&r);

    series s;
    snprintf(path, sizeof path, "%s/series.csv", out);
    read_series(path, &s);
    cr_assert(!strncmp(s.header, "t,kinetic", 9), "header \"%s\"", s.header);
    cr_assert(s.nrow >= 2, "series.csv has %zu rows", s.nrow);
    double last = s.v[(s.nrow - 1) * s.ncol];
    cr_assert(fabs(last - (tb - dt)) < 1e-9,
              "last row at t = %g, the blow-up at t = %g", last, tb);
    cr_assert_eq(s.nrow, (size_t)llround(tb / dt),
                 "%zu rows for a blow-up at t = %g with dt = %g", s.nrow, tb,
                 dt);
    for (size_t k = 0; k < s.nrow * s.ncol; k++)
        cr_assert(isfinite(s.v[k]), "series.csv: non-finite value");
    for (size_t k = 1; k < s.nrow; k++)
        cr_assert_gt(s.v[k * s.ncol], s.v[(k - 1) * s.ncol]);
    free(s.v);
    snprintf(path, sizeof path, "%s/stats.csv", out);
    cr_assert(cli_exists(path), "missing %s", path);
    snprintf(path, sizeof path, "%s/final.csv", out);
    cr_assert(!cli_exists(path), "a failed run wrote %s", path);
    assert_no_temporaries(out);

    /* last-good.csv is the state of the last row: the final.csv of the
     * same run ending there, byte for byte */
    char again[1024], tl[32], rows[32], *good, *fin;
    snprintf(tl, sizeof tl, "%.17g", last);
    snprintf(rows, sizeof rows, "%ld", lround(last / dt));
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator",
            "symplectic-euler", "--dt", "0.01", "--t-end", tl, "--samples",
            rows, "--frames", "0", "--quiet", "--out",
            in_tmp(again, "blow-again"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/last-good.csv", out);
    good = file_text(path);
    snprintf(path, sizeof path, "%s/final.csv", again);
    fin = file_text(path);
    cr_assert(!strcmp(good, fin),
              "last-good.csv differs from the final.csv of a run to t = %s",
              tl);
    free(good);
    free(fin);
}

/* A solver failure inside the first advance: last-good.csv is the state of
 * the only row, hang's rest state at t = 0. */
Test(cli, solver_failure_keeps_the_state_of_the_last_row)
{
    char out[1024], path[1200];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--set",
            "run.max_steps=1", "--out", in_tmp(out, "mxstep"), NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 3, "%s: status %d\n%s", r.cmd, r.status, r.err);
    cr_assert(strstr(r.out, "last-good.csv, stats.csv"), "%s", r.out);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/last-good.csv", out);
    char *good = file_text(path), *rest = rest_state_text();
    cr_assert(!strcmp(good, rest), "last-good.csv is not the rest state:\n%s",
              good);
    free(good);
    free(rest);
    snprintf(path, sizeof path, "%s/final.csv", out);
    cr_assert(!cli_exists(path), "a failed run wrote %s", path);
}

/* More samples requested than there are fixed steps: every step is one row
 * at most; time must not repeat. */
Test(cli, series_time_never_repeats)
{
    char out[1024], path[1200];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator",
            "symplectic-euler", "--dt", "1e-3", "--t-end", "0.05",
            "--samples", "200", "--frames", "0", "--out", in_tmp(out, "s"),
            "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    series s;
    snprintf(path, sizeof path, "%s/series.csv", out);
    read_series(path, &s);
    cr_assert_eq(s.nrow, 51, "one row a step and t = 0: %zu", s.nrow);
    for (size_t k = 1; k < s.nrow; k++)
        cr_assert_gt(s.v[k * s.ncol], s.v[(k - 1) * s.ncol],
                     "series.csv data rows %zu and %zu at t = %g and %g",
                     k, k + 1, s.v[(k - 1) * s.ncol], s.v[k * s.ncol]);
    cr_assert(fabs(s.v[(s.nrow - 1) * s.ncol] - 0.05) < 1e-12);
    free(s.v);
}

/* The same for frames: more frames requested than there are steps. */
Test(cli, frame_time_never_repeats)
{
    char out[1024], path[1200];
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=3", "--integrator",
            "symplectic-euler", "--dt", "1e-3", "--t-end", "0.005",
            "--samples", "5", "--frames", "10", "--format", "vtk", "--out",
            in_tmp(out, "f"), "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    int n = count_prefixed(out, "frame_", NULL, 0);
    cr_assert_eq(n, 6, "one frame a step and t = 0: %d frames", n);
    double prev = -1;
    for (int k = 0; k < n; k++) {
        snprintf(path, sizeof path, "%s/frame_%05d.vtk", out, k);
        double t = vtk_time(path);
        cr_assert_gt(t, prev, "frame %d at t = %g, frame %d at t = %g", k - 1,
                     prev, k, t);
        prev = t;
    }
    cr_assert(fabs(prev - 0.005) < 1e-12, "last frame at t = %g", prev);
}

/* ======================================================================
 * 4. eval: forces, energies, Jacobians.
 * ====================================================================== */

/* eval of hang at n = 6 (extra assignments in `set`, or NULL) at the state
 * x, v; outputs under tmp/eval, Jacobians tmp/J.mtx and tmp/V.mtx. */
static void run_eval(const cl_cloth *c, const double *x, const double *v,
                     const char *set)
{
    char state[1024], out[1024], jx[1024], jv[1024];
    write_state(in_tmp(state, "state.csv"), c->np, x, v);
    cli_result r;
    const char *args[] = {"eval", "hang", "--set", "cloth.n=6", "--state",
                          state, "--out", in_tmp(out, "eval"), "--jacobian",
                          in_tmp(jx, "J.mtx"), "--jacobian-v",
                          in_tmp(jv, "V.mtx"), set ? "--set" : NULL, set,
                          NULL};
    cli_runv(&r, args);
    cli_assert_ok(&r);
    cli_result_free(&r);
}

Test(cli, eval_forces_and_energies)
{
    const char *sets[] = {"cloth.n=6", NULL};
    cl_model *m = load_model("hang", sets);
    const cl_cloth *c = cl_model_cloth(m);
    double x[3 * RUN_NP], v[3 * RUN_NP], f[3 * RUN_NP];
    perturbed_state(c, x, v);
    run_eval(c, x, v, NULL);

    char path[1024];
    cli_read_forces(in_tmp(path, "eval/forces.csv"), c->np, f);
    for (size_t k = 0; k < 3 * c->np; k++)
        cr_assert(isfinite(f[k]));
    energies e;
    read_energy(in_tmp(path, "eval/energy.csv"), &e);
    const char *names[] = {"kinetic", "type1", "type2", "gravity", "total"};
    cr_assert_eq(e.n, 5, "energy.csv has %zu rows", e.n);
    for (int k = 0; k < 5; k++)
        cr_assert_str_eq(e.name[k], names[k]);
    double sum = 0, scale = 0;
    for (int k = 0; k < 4; k++) {
        sum += e.value[k];
        scale += fabs(e.value[k]);
    }
    double total = energy_of(&e, "total");
    cr_assert(fabs(total - sum) <= 1e-12 * scale,
              "total %.17g != kinetic + potentials %.17g", total, sum);

    /* kinetic 1/2 m v^2 and gravity energy m g y (g = -9.81 along y),
     * from the state itself */
    double kin = 0, grav = 0;
    for (size_t p = 0; p < c->np; p++) {
        for (int d = 0; d < 3; d++)
            kin += 0.5 * c->mass[p] * v[3 * p + d] * v[3 * p + d];
        grav += c->mass[p] * 9.81 * x[3 * p + 1];
    }
    double ek = energy_of(&e, "kinetic"), eg = energy_of(&e, "gravity");
    cr_assert(fabs(ek - kin) <= 1e-12 * kin, "kinetic %.17g, expected %.17g",
              ek, kin);
    cr_assert(fabs(eg - grav) <= 1e-12 * c->np * fabs(grav) + 1e-300,
              "gravity energy %.17g, expected %.17g", eg, grav);
    cr_assert_gt(energy_of(&e, "type1"), 0.0, "a stretched cloth");
    free_model(m);
}

Test(cli, eval_rest_state_without_gravity_has_no_force)
{
    const char *sets[] = {"cloth.n=6", NULL};
    cl_model *m = load_model("hang", sets);
    const cl_cloth *c = cl_model_cloth(m);
    double v[3 * RUN_NP] = {0}, f[3 * RUN_NP];
    run_eval(c, c->X0, v, "gravity.g=0,0,0");
    char path[1024];
    cli_read_forces(in_tmp(path, "eval/forces.csv"), c->np, f);
    for (size_t k = 0; k < 3 * c->np; k++)
        cr_assert_eq(f[k], 0.0, "force on particle %zu [%zu] = %.17g at rest",
                     k / 3, k % 3, f[k]);
    energies e;
    read_energy(in_tmp(path, "eval/energy.csv"), &e);
    for (size_t k = 0; k < e.n; k++)
        cr_assert_eq(e.value[k], 0.0, "energy %s = %.17g at rest",
                     e.name[k], e.value[k]);
    free_model(m);
}

Test(cli, eval_internal_forces_sum_to_zero)
{
    const char *sets[] = {"cloth.n=6", NULL};
    cl_model *m = load_model("hang", sets);
    const cl_cloth *c = cl_model_cloth(m);
    double x[3 * RUN_NP], v[3 * RUN_NP], f[3 * RUN_NP];
    perturbed_state(c, x, v);
    run_eval(c, x, v, "gravity.g=0,0,0");
    char path[1024];
    cli_read_forces(in_tmp(path, "eval/forces.csv"), c->np, f);
    double fmax = max_abs(f, 3 * c->np);
    cr_assert_gt(fmax, 0.0);
    for (int d = 0; d < 3; d++) {
        double s = 0;
        for (size_t p = 0; p < c->np; p++)
            s += f[3 * p + d];
        cr_assert(fabs(s) <= 1e-12 * fmax,
                  "sum of forces [%d] = %.3g, max force %.3g", d, s, fmax);
    }
    free_model(m);
}

Test(cli, eval_jacobians)
{
    const char *sets[] = {"cloth.n=6", NULL};
    cl_model *m = load_model("hang", sets);
    const cl_cloth *c = cl_model_cloth(m);
    double x[3 * RUN_NP], v[3 * RUN_NP];
    perturbed_state(c, x, v);
    run_eval(c, x, v, NULL);
    const size_t n = 3 * c->np;
    char path[1024];
    double *J = read_dense(in_tmp(path, "J.mtx"), n);
    double *V = read_dense(in_tmp(path, "V.mtx"), n);
    double jmax = max_abs(J, n * n), vmax = max_abs(V, n * n);
    cr_assert(jmax > 0 && vmax > 0, "zero Jacobian");
    /* conservative pair forces: df/dx is a Hessian, symmetric; linear pair
     * damping: df/dv symmetric too */
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < i; j++) {
            cr_assert(fabs(J[i * n + j] - J[j * n + i]) <= 1e-12 * jmax,
                      "df/dx(%zu,%zu) = %.17g but (%zu,%zu) = %.17g", i, j,
                      J[i * n + j], j, i, J[j * n + i]);
            cr_assert(fabs(V[i * n + j] - V[j * n + i]) <= 1e-12 * vmax,
                      "df/dv(%zu,%zu) = %.17g but (%zu,%zu) = %.17g", i, j,
                      V[i * n + j], j, i, V[j * n + i]);
        }
    /* forces depend on differences only: moving (or speeding up) every
     * particle alike changes nothing, so each row sums to 0 per component */
    for (size_t i = 0; i < n; i++)
        for (size_t b = 0; b < 3; b++) {
            double sj = 0, sv = 0;
            for (size_t p = 0; p < c->np; p++) {
                sj += J[i * n + 3 * p + b];
                sv += V[i * n + 3 * p + b];
            }
            cr_assert(fabs(sj) <= 1e-12 * jmax,
                      "df/dx row %zu, component %zu sums to %.3g", i, b, sj);
            cr_assert(fabs(sv) <= 1e-12 * vmax,
                      "df/dv row %zu, component %zu sums to %.3g", i, b, sv);
        }
    free(J);
    free(V);
    free_model(m);
}

/* ======================================================================
 * 5. The two integrators agree.
 * ====================================================================== */

Test(cli, cvode_and_symplectic_euler_agree)
{
    enum { N = 8, NP = N * N };
    char a[1024], b[1024], path[1200];
    double t0 = cli_now();
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=8", "--t-end", "0.2",
            "--integrator", "cvode-bdf", "--rtol", "1e-8", "--atol", "1e-10",
            "--samples", "10", "--frames", "0", "--quiet", "--out",
            in_tmp(a, "cvode"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    double t1 = cli_now();
    cli_run(&r, "run", "hang", "--set", "cloth.n=8", "--t-end", "0.2",
            "--integrator", "symplectic-euler", "--dt", "2e-5", "--samples",
            "10", "--frames", "0", "--quiet", "--out", in_tmp(b, "symp"),
            NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    double t2 = cli_now();

    static double xa[3 * NP], va[3 * NP], xb[3 * NP], vb[3 * NP];
    snprintf(path, sizeof path, "%s/final.csv", a);
    cli_read_state(path, NP, xa, va);
    snprintf(path, sizeof path, "%s/final.csv", b);
    cli_read_state(path, NP, xb, vb);
    double diff = 0, fall = 0;
    for (size_t p = 0; p < NP; p++) {
        double d2 = 0;
        for (int d = 0; d < 3; d++)
            d2 += (xa[3 * p + d] - xb[3 * p + d]) *
                  (xa[3 * p + d] - xb[3 * p + d]);
        diff = fmax(diff, sqrt(d2));
        fall = fmax(fall, -xa[3 * p + 1]);
    }
    cr_log_info("cvode-bdf vs symplectic-euler, hang n = 8 to t = 0.2 s: "
                "max position difference %.3g m (max drop %.3g m; %.1f s + "
                "%.1f s)", diff, fall, t1 - t0, t2 - t1);
    cr_assert(fall > 0.05, "the cloth barely moved (max drop %g m)", fall);
    /* measured 2.16e-5 m: symplectic Euler's first-order error at
     * dt = 2e-5 (cvode-bdf at rtol 1e-8 is far closer to the solution);
     * the bound leaves a factor 2.3 */
    cr_assert_lt(diff, 5e-5, "final positions differ by %g m", diff);
}

/* ======================================================================
 * 6. counts, list, help.
 * ====================================================================== */

Test(cli, counts_match_their_formulas)
{
    cli_result r;
    cli_run(&r, "counts", "--csv", "--n-max", "40", NULL);
    cli_assert_ok(&r);
    char *save, *line = strtok_r(r.out, "\n", &save);
    cr_assert_not_null(line);
    cr_assert_str_eq(line,
                     "n,type1,type1_formula,type2,type2_formula,ck,ck_formula");
    long expect_n = 3;
    while ((line = strtok_r(NULL, "\n", &save))) {
        double k[7];
        cli_parse_row(line, k, 7, "counts --csv");
        long n = (long)k[0];
        cr_assert_eq(n, expect_n, "row for n = %ld, expected %ld", n,
                     expect_n);
        double t1 = 2.0 * (n - 1) * (2 * n - 1), t2 = 4.0 * (n - 1) * (n - 2);
        double ck = 8.0 * n * n - 18.0 * n + 10;
        cr_assert_eq(k[2], t1, "n = %ld: type1 formula %g", n, k[2]);
        cr_assert_eq(k[4], t2, "n = %ld: type2 formula %g", n, k[4]);
        cr_assert_eq(k[6], ck, "n = %ld: CK formula %g", n, k[6]);
        cr_assert_eq(k[1], t1, "n = %ld: %g Type1 pairs, formula %g", n,
                     k[1], t1);
        cr_assert_eq(k[3], t2, "n = %ld: %g Type2 pairs, formula %g", n,
                     k[3], t2);
        cr_assert_eq(k[5], ck, "n = %ld: CK count %g, formula %g", n, k[5],
                     ck);
        expect_n++;
    }
    cr_assert_eq(expect_n, 41, "rows for n = 3..%ld only", expect_n - 1);
    cli_result_free(&r);
}

/* Run args (a LIST whose --out is dir), which must succeed, and read
 * dir/convergence.csv into L. */
static void convergence_csv(const char *const *args, const char *dir,
                            cli_lines *L)
{
    char path[1100];
    cli_result r;
    cli_runv(&r, args);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/convergence.csv", dir);
    cli_read_lines(path, L);
}

/* convergence: one CSV row per level, the fitted order of rk4 near 4 on
 * every row of rk4. */
Test(cli, convergence_table_and_csv)
{
    char out[1024];
    cli_lines L;
    convergence_csv(LIST("convergence", "spring2", "--integrator",
                         "rk4,cvode-bdf", "--dt", "1e-2", "--rtol", "1e-4",
                         "--atol", "1e-6", "--t-end", "1", "--levels", "3",
                         "--out", in_tmp(out, "conv")),
                    out, &L);
    cr_assert_eq(L.n, 7, "header and 2 x 3 levels, got %zu lines", L.n);
    cr_assert_str_eq(L.line[0], "integrator,param,value,err_x,err_v,order,"
                                "fitted,fitted_v,steps,rhs_evals,cpu,fit_x,"
                                "fit_v,status");
    static const char *const method[] = {"rk4", "rk4", "rk4", "cvode-bdf",
                                         "cvode-bdf", "cvode-bdf"};
    static const double first[] = {0.01, 1e-4};
    char f[64];
    for (size_t k = 1; k < L.n; k++) {
        const char *row = L.line[k];
        bool rk4 = k <= 3;
        cr_assert_str_eq(csv_field(row, 0, f, sizeof f), method[k - 1]);
        cr_assert_str_eq(csv_field(row, 1, f, sizeof f), rk4 ? "dt" : "rtol");
        /* dt halves, rtol falls by 10, from --dt and --rtol */
        double level = first[!rk4] / pow(rk4 ? 2 : 10, (double)((k - 1) % 3));
        cr_assert_float_eq(csv_number(row, 2), level, 1e-12 * level, "%s",
                           row);
        cr_assert_str_eq(csv_field(row, 13, f, sizeof f), "ok");
        if (rk4)
            cr_assert(fabs(csv_number(row, 11) - 4) < 0.2, "rk4: %s", row);
    }
    /* rk4 from dt = 0.01: 100, 200, 400 steps to T = 1 */
    cr_assert_eq(csv_number(L.line[3], 8), 400.0, "%s", L.line[3]);
    cli_lines_free(&L);
}

/* An option of [run] serves the integrators of the list that take it:
 * arkode-dirk-fixed gets --table beside rk4 (SDIRK_2_1_2, second order),
 * semi-be gets --linsol beside rk4; alone, rk4 refuses either. */
Test(cli, list_options_serve_the_methods_that_take_them)
{
    char out[1024], f[64];
    cli_lines L;
    convergence_csv(LIST("convergence", "spring2", "--integrator",
                         "rk4,arkode-dirk-fixed,semi-be", "--table",
                         "SDIRK_2_1_2", "--linsol", "klu", "--dt", "1e-2",
                         "--t-end", "1", "--levels", "3", "--out",
                         in_tmp(out, "listopts")),
                    out, &L);
    cr_assert_eq(L.n, 10, "header and 3 x 3 levels, got %zu", L.n);
    const char *dirk = L.line[4];
    cr_assert_str_eq(csv_field(dirk, 0, f, sizeof f), "arkode-dirk-fixed");
    cr_assert(fabs(csv_number(dirk, 11) - 2) < 0.2, "%s", dirk);
    cli_lines_free(&L);
    expect_refused(LIST("convergence", "spring2", "--integrator", "rk4,fe",
                        "--table", "SDIRK_2_1_2", "--dt", "1e-2"), 0,
                   LIST("--table", "rk4", "no choice of table"));
    /* Rayleigh damping: kinsol-be takes it, semi-be leaves it */
    list_key_served_or_refused("run.rayleigh_alpha=0.5",
                               LIST("rayleigh_alpha", "no Rayleigh damping"));
}

Test(cli, convergence_refusals)
{
    expect_refused(LIST("convergence", "spring2", "--integrator",
                        "rk4,no-such", "--dt", "1e-2"), 0,
                   LIST("--integrator", "no-such", "cvode-bdf", "semi-bdf2"));
    expect_refused(LIST("convergence", "spring2", "--integrator", "rk4",
                        "--dt", "1e-2", "--levels", "1"), 0,
                   LIST("--levels: [convergence] levels = \"1\": expected an "
                        "integer in [2, 20]"));
    expect_refused(LIST("convergence", "spring2", "--integrator", "rk4"), 0,
                   LIST("[run] dt = 0: integrator rk4 takes fixed steps and "
                        "needs dt > 0 (--dt H)"));
    expect_refused(LIST("convergence", "spring2", "--integrator", "rk4",
                        "--dt", "0.3", "--t-end", "1"), 0,
                   LIST("whole number", "0.3"));
    expect_refused(LIST("convergence", "spring2", "--ref-rtol", "1e-2"), 0,
                   LIST("--ref-rtol: [convergence] ref_rtol = \"1e-2\": "
                        "expected a number in [1e-15, 0.0001]"));
}

/* A problem file written for run serves the studies: run's output keys
 * ([run] frames, samples, format, threads, budget_steps) are ignored
 * there, while the same keys given by --set, where they would change
 * nothing, are refused, and a misspelt key is still refused. */
Test(cli, studies_take_run_output_keys)
{
    char out[1024], path[1100], text[4096];
    cli_result r;
    tmp_slurp("problems/spring2.ini", text, sizeof text - 200);
    strcat(text, "frames = 3\nsamples = 7\nformat = csv\nthreads = 2\n"
                 "budget_steps = 5\n");
    tmp_put(in_tmp(path, "spring2-run.ini"), text);
    cli_run(&r, "stability", path, "--integrator", "symplectic-euler",
            "--t-end", "1", "--dt-max", "0.05", "--rel", "0.1", "--out",
            in_tmp(out, "stab-keys"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cli_lines L;
    snprintf(path, sizeof path, "%s/stability.csv", out);
    cli_read_lines(path, &L);
    /* stable at dt_max, and at half of it (the search's check) */
    cr_assert_eq(L.n, 3);
    cr_assert(!strncmp(L.line[1], "symplectic-euler,0.05,20,1,ok,", 30) &&
              !strncmp(L.line[2], "symplectic-euler,0.025,40,1,ok,", 31),
              "%s\n%s", L.line[1], L.line[2]);
    cli_lines_free(&L);
    static const char *const given[] = {
        "run.frames=3", "run.samples=7", "run.format=csv", "run.threads=2",
        "run.budget_wall=9", "run.budget_steps=5", "run.dt=0.01"};
    for (size_t k = 0; k < sizeof given / sizeof *given; k++) {
        cli_run(&r, "stability", "spring2", "--set", given[k], NULL);
        cli_assert_error(&r, 0, "clothode stability does not read it",
                         NULL);
        cli_result_free(&r);
    }
    cli_run(&r, "damping", "spring2", "--set", "run.t_end=3", NULL);
    cli_assert_error(&r, 0, "[run] t_end", "clothode damping does not read",
                     NULL);
    cli_result_free(&r);
    cli_run(&r, "damping", "spring2", "--set", "run.integrator=rk4", NULL);
    cli_assert_error(&r, 0, "[run] integrator",
                     "clothode damping does not read", NULL);
    cli_result_free(&r);
    /* spectrum and eval read no [run] key, misspelt or not */
    static const char *const other[][2] = {{"spectrum", "run.samples=7"},
                                           {"spectrum", "run.framez=3"},
                                           {"eval", "run.rtol=1e-3"}};
    for (int k = 0; k < 3; k++) {
        char want[64];
        snprintf(want, sizeof want, "clothode %s does not read it",
                 other[k][0]);
        cli_run(&r, other[k][0], "spring2", "--set", other[k][1], "--out",
                in_tmp(out, "not-read"), "--state", "none.csv", NULL);
        cli_assert_error(&r, 0, want, NULL);
        cli_result_free(&r);
    }
    cli_run(&r, "convergence", "spring2", "--set", "run.framez=3", NULL);
    cli_assert_error(&r, 0, "framez", "frames", NULL);
    cli_result_free(&r);
}

/* stability on the stiffened spring (w = 100): symplectic Euler's limit
 * 2/w = 0.02 bracketed to --rel 0.01, backward Euler stable at dt_max
 * and dt_max/2;
 * every run in the CSV. */
Test(cli, stability_table_and_csv)
{
    char out[1024], path[1100], f[64];
    cli_result r;
    cli_run(&r, "stability", "spring2", "--set", "type1.ks=1e4", "--set",
            "run.max_stretch=1.5", "--checks", "100000", "--integrator",
            "symplectic-euler,semi-be", "--t-end", "4", "--dt-max", "0.1",
            "--rel", "0.01", "--out", in_tmp(out, "stab"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cli_lines L;
    snprintf(path, sizeof path, "%s/stability.csv", out);
    cli_read_lines(path, &L);
    cr_assert_str_eq(L.line[0], "integrator,dt,steps,stable,status,cpu,"
                                "stretch,reason");
    double stable = 0, unstable = INFINITY;
    for (size_t k = 1; k + 2 < L.n; k++) {
        const char *row = L.line[k];
        cr_assert_str_eq(csv_field(row, 0, f, sizeof f), "symplectic-euler");
        double dt = csv_number(row, 1);
        cr_assert_eq(csv_number(row, 2), (double)llround(4 / dt), "%s", row);
        /* a stable run's checks stayed within max_stretch = 1.5 */
        cr_assert(csv_number(row, 3) == 0 || csv_number(row, 6) <= 1.5, "%s",
                  row);
        if (csv_number(row, 3) == 1)
            stable = fmax(stable, dt);
        else
            unstable = fmin(unstable, dt);
    }
    /* at dt = 2/w itself the method is marginal, its error grows */
    cr_assert(stable < 0.02 && unstable >= 0.02 && unstable <= 1.011 * stable,
              "bracket (%g, %g]", stable, unstable);
    /* semi-be: dt_max and its half, both stable */
    for (int k = 0; k < 2; k++) {
        const char *row = L.line[L.n - 2 + (size_t)k];
        cr_assert_str_eq(csv_field(row, 0, f, sizeof f), "semi-be");
        cr_assert_eq(csv_number(row, 1), k ? 0.05 : 0.1);
        cr_assert_eq(csv_number(row, 3), 1.0, "%s", row);
        cr_assert_str_eq(csv_field(row, 4, f, sizeof f), "ok");
        /* amplitude v0 / w = 0.01 m on L = 1 m, damped by backward Euler */
        cr_assert(csv_number(row, 6) >= 1.0 && csv_number(row, 6) <= 1.0101,
                  "%s", row);
    }
    cli_lines_free(&L);
}

Test(cli, stability_refusals)
{
    expect_refused(LIST("stability", "spring2", "--integrator",
                        "rk4,cvode-bdf"), 0,
                   LIST("cvode-bdf", "error control"));
    expect_refused(LIST("stability", "spring2", "--integrator", "rk4",
                        "--t-end", "4", "--dt-max", "1"), 0,
                   LIST("--dt-max: [stability] dt_max = \"1\": expected a "
                        "number in [1e-300, 0.4]"));
    expect_refused(LIST("stability", "verlet-scene3", "--integrator",
                        "verlet", "--t-end", "1"), 0,
                   LIST("tear"));
}

/* contact on particle-floor (a 0.1 kg particle 1e-4 m deep in a floor,
 * g = 9.81): penalty k = 1e4 rests at m g / k under semi-be; projection
 * sinks 1e-4 + g dt^2 in its first step; symplectic Euler's limit on the
 * contact spring is 2 sqrt(m/k) = 6.325e-3 s (dt = 1e-2 unstable). */
Test(cli, contact_table_and_csv)
{
    char out[1024], path[1100], f[64];
    cli_result r;
    cli_run(&r, "contact", "particle-floor", "--integrator",
            "semi-be,symplectic-euler", "--response", "penalty,project",
            "--dt", "1e-2,1e-3", "--k", "1e4", "--dt-max", "0.02",
            "--out", in_tmp(out, "contact"), NULL);
    cli_assert_ok(&r);
    cr_assert_not_null(strstr(r.out, "unstable from dt = 0.01"), "%s", r.out);
    cli_result_free(&r);
    cli_lines L;
    snprintf(path, sizeof path, "%s/contact.csv", out);
    cli_read_lines(path, &L);
    cr_assert_str_eq(L.line[0], "integrator,response,dt,steps,stable,status,"
                                "worst_penetration,worst_t,rest_penetration,"
                                "rest_contacts,max_stretch,newton_iters,cpu,"
                                "reason");
    cr_assert_eq(L.n, 9, "%zu lines", L.n); /* 2 responses x 2 x 2 dt */
    const char *order[] = {"semi-be", "symplectic-euler"};
    for (size_t k = 1; k < L.n; k++) {
        const char *row = L.line[k];
        int project = k > 4;
        double dt = k % 2 ? 1e-2 : 1e-3;
        cr_assert_str_eq(csv_field(row, 0, f, sizeof f), order[(k - 1) / 2 % 2]);
        cr_assert_str_eq(csv_field(row, 1, f, sizeof f),
                         project ? "project" : "penalty");
        cr_assert_eq(csv_number(row, 2), dt, "%s", row);
        cr_assert_eq(csv_number(row, 3), (double)llround(2 / dt), "%s", row);
        if (project)
            cr_assert_float_eq(csv_number(row, 6), 1e-4 + 9.81 * dt * dt,
                               1e-12, "%s", row);
    }
    cr_assert_float_eq(csv_number(L.line[1], 8), 0.1 * 9.81 / 1e4, 1e-12,
                       "%s", L.line[1]);
    cr_assert_eq(csv_number(L.line[3], 4), 0.0, "%s", L.line[3]);
    cr_assert_str_eq(csv_field(L.line[3], 5, f, sizeof f), "blow-up");
    cli_lines_free(&L);
    snprintf(path, sizeof path, "%s/contact-k.csv", out);
    cli_read_lines(path, &L);
    cr_assert_str_eq(L.line[0], "integrator,k,dt_stable,dt_unstable,"
                                "predicted,w_max,runs");
    cr_assert_eq(L.n, 3, "%zu lines", L.n);
    cr_assert_float_eq(csv_number(L.line[2], 4), 2 * sqrt(0.1 / 1e4), 1e-12,
                       "%s", L.line[2]);
    cli_lines_free(&L);
}

/* A particle dropped 0.1 m onto a barrier plane: symplectic Euler at
 * 1e-2 s steps into it, a blow-up that says so (it read "energy is not
 * finite"); started inside, the run is refused before its first step. */
Test(cli, barrier_crossed_or_started_inside_says_so)
{
    char ini[1024], out[1024];
    const char *text =
        "[cloth]\nnu = 1\nnv = 2\nsize = 0.1\nparticle_mass = 0.1\n"
        "[pins]\nat =\n[type1]\nenabled = false\n[type2]\n"
        "enabled = false\n[damping]\nkd = 0\n[gravity]\ng = 0, -9.81, 0\n"
        "[obstacle.floor]\nshape = plane\nnormal = 0, 1, 0\n"
        "point = 0, %s, 0\nresponse = barrier\nkappa = 10\ndhat = 0.01\n";
    char body[1024];
    snprintf(body, sizeof body, text, "-0.1");
    tmp_put(in_tmp(ini, "drop.ini"), body);
    cli_result r;
    cli_run(&r, "run", ini, "--integrator", "symplectic-euler", "--dt",
            "1e-2", "--t-end", "0.5", "--out", in_tmp(out, "drop"), NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, CL_EXIT_BLOWUP, "%s", r.err);
    cr_assert_not_null(strstr(r.err, "d <= 0 of a barrier obstacle"), "%s",
                       r.err);
    cli_result_free(&r);
    snprintf(body, sizeof body, text, "1e-4");
    tmp_put(ini, body);
    cli_run(&r, "run", ini, "--integrator", "symplectic-euler", "--dt",
            "1e-2", "--t-end", "0.5", "--out", in_tmp(out, "inside"), NULL);
    cli_assert_error(&r, 0, "initial state", "barrier obstacle", NULL);
    cr_assert_eq(r.status, CL_EXIT_INPUT, "%s", r.err);
    cli_result_free(&r);
}

/* With no stable step the summary names the unstable one alone. */
Test(cli, contact_summary_without_a_stable_step)
{
    char out[1024];
    cli_result r;
    cli_run(&r, "contact", "particle-floor", "--integrator",
            "symplectic-euler", "--response", "penalty", "--dt", "1e-2",
            "--out", in_tmp(out, "contact-unstable"), NULL);
    cli_assert_ok(&r);
    cr_assert_not_null(strstr(r.out, "unstable from dt = 0.01\n"), "%s",
                       r.out);
    cli_result_free(&r);
}

Test(cli, contact_refusals)
{
    expect_refused(LIST("contact", "particle-floor"), 0,
                   LIST("--dt LIST", "--k LIST"));
    expect_refused(LIST("contact", "particle-floor", "--dt", "1e-2,x"), 0,
                   LIST("--dt", "1e-2,x", "expected steps"));
    expect_refused(LIST("contact", "particle-floor", "--dt", "1e-2",
                        "--integrator", "cvode-bdf"), 0,
                   LIST("cvode-bdf", "error control"));
    expect_refused(LIST("contact", "particle-floor", "--dt", "1e-2",
                        "--response", "penalty,bogus"), 0,
                   LIST("--response", "bogus", "penalty, project"));
    expect_refused(LIST("contact", "spring2", "--dt", "1e-2",
                        "--integrator", "semi-be"), 0,
                   LIST("no obstacle"));
    expect_refused(LIST("contact", "particle-floor", "--dt", "3e-2"), 0,
                   LIST("whole number", "0.03"));
    expect_refused(LIST("contact", "jiao-sphere", "--dt", "1e-2",
                        "--response", "penalty"), 0,
                   LIST("problems/jiao-sphere.ini:", "[obstacle.sphere] k: "
                        "required (response = penalty's stiffness"));
    expect_refused(LIST("contact", "particle-floor", "--k", "1e4,-1"), 0,
                   LIST("--k", "stiffnesses > 0"));
}

/* spectrum of the stiffened spring at rest (ks = 1e4 on unit mass and
 * length): mu = w^2 = 0, 0, 1e4 and lambda = 0 (4 times) and +-100 i. */
Test(cli, spectrum_summary_and_csv)
{
    char out[1024], path[1100], f[64];
    cli_result r;
    cli_run(&r, "spectrum", "spring2", "--set", "type1.ks=1e4", "--out",
            in_tmp(out, "spec"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cli_lines L;
    snprintf(path, sizeof path, "%s/spectrum.csv", out);
    cli_read_lines(path, &L);
    cr_assert_eq(L.n, 10, "%zu lines", L.n);
    cr_assert_str_eq(L.line[0], "kind,index,re,im");
    double mu_max = 0, im_max = 0, re_max = 0;
    for (size_t k = 1; k < L.n; k++) {
        bool mu = k <= 3;
        cr_assert_str_eq(csv_field(L.line[k], 0, f, sizeof f),
                         mu ? "mu" : "lambda");
        cr_assert_eq(csv_number(L.line[k], 1), (double)(mu ? k - 1 : k - 4));
        if (mu)
            mu_max = fmax(mu_max, csv_number(L.line[k], 2));
        else
            im_max = fmax(im_max, fabs(csv_number(L.line[k], 3)));
        if (!mu)
            re_max = fmax(re_max, fabs(csv_number(L.line[k], 2)));
    }
    cr_assert_float_eq(mu_max, 1e4, 1e-9, "%.17g", mu_max);
    cr_assert_float_eq(im_max, 100, 1e-11, "%.17g", im_max);
    cr_assert(re_max <= 1e-9, "an undamped spring: |Re lambda| = %g",
              re_max);
    cli_lines_free(&L);
}

Test(cli, spectrum_refusals)
{
    char path[1024];
    expect_refused(LIST("spectrum", "hang", "--set", "cloth.n=26"), 0,
                   LIST("24 x 24"));
    expect_refused(LIST("spectrum", "spring2", "--state",
                        in_tmp(path, "no-such-state.csv")),
                   0, LIST("no-such-state.csv"));
}

/* energy on spring2 (a linear oscillator, w = 10, starting at rest length
 * with E = 0.5 J, no damping) at dt = 0.01: backward Euler multiplies the
 * energy by 1/(1 + (h w)^2) per step, so E(1) = 0.5 * 1.01^-100; velocity
 * Verlet conserves E - q w^2 x^2 / 2 with q = (h w)^2 / 4 exactly, so its
 * balance stays in [0, 0.5 q / (1 - q)] = [0, 1.2531e-3] J.  One CSV row
 * per sample and integrator. */
Test(cli, energy_table_and_csv)
{
    char out[1024], path[1100], f[64];
    cli_result r;
    cli_run(&r, "energy", "spring2", "--integrator",
            "semi-be,velocity-verlet", "--dt", "1e-2", "--t-end", "1",
            "--samples", "10", "--out", in_tmp(out, "energy"), NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "\nfixed      dt = 0.01 s\n") &&
                  !strstr(r.out, "adaptive"),
              "the step the runs used, no tolerance: %s", r.out);
    cli_result_free(&r);
    cli_lines L;
    snprintf(path, sizeof path, "%s/energy.csv", out);
    cli_read_lines(path, &L);
    cr_assert_eq(L.n, 23, "header and 2 x 11 samples, got %zu", L.n);
    cr_assert_str_eq(L.line[0], "integrator,t,kinetic,potential,total,"
                                "dissipated,balance");
    double vv_min = 0, vv_max = 0;
    for (size_t k = 1; k < L.n; k++) {
        const char *row = L.line[k];
        bool be = k <= 11;
        cr_assert_str_eq(csv_field(row, 0, f, sizeof f),
                         be ? "semi-be" : "velocity-verlet");
        cr_assert_float_eq(csv_number(row, 1), 0.1 * (double)((k - 1) % 11),
                           1e-12, "%s", row);
        cr_assert_eq(csv_number(row, 5), 0.0, "no damping: %s", row);
        if (!be) {
            vv_min = fmin(vv_min, csv_number(row, 6));
            vv_max = fmax(vv_max, csv_number(row, 6));
        }
    }
    cr_assert_float_eq(csv_number(L.line[1], 4), 0.5, 1e-12);
    double e1 = 0.5 * pow(1.01, -100);
    cr_assert_float_eq(csv_number(L.line[11], 4), e1, 1e-9 * e1, "%s",
                       L.line[11]);
    cr_assert_float_eq(csv_number(L.line[11], 6), e1 - 0.5, 1e-9, "%s",
                       L.line[11]);
    cr_assert(vv_min > -1e-12 && vv_max > 0 && vv_max <= 1.2532e-3,
              "velocity-verlet B in [%g, %g]", vv_min, vv_max);
    cli_lines_free(&L);
}

Test(cli, energy_refusals)
{
    expect_refused(LIST("energy", "spring2", "--integrator", "rk4", "--dt",
                        "0.3", "--t-end", "1"), 0,
                   LIST("whole number", "0.3"));
    expect_refused(LIST("energy", "spring2", "--samples", "0"), 0,
                   LIST("--samples: [energy] samples = \"0\": expected an "
                        "integer in [1, 100000000]"));
}

/* workprecision: integrator:linsol entries label the CSV; a ranking line
 * for every decade of error the fitted levels reach. */
Test(cli, workprecision_ranking_and_csv)
{
    char out[1024], path[1100], f[64];
    cli_result r;
    cli_run(&r, "workprecision", "spring2", "--integrator",
            "rk4,semi-bdf2:pcg", "--dt", "1e-2", "--t-end", "1", "--levels",
            "3", "--out", in_tmp(out, "wp"), NULL);
    cli_assert_ok(&r);
    cli_lines L;
    snprintf(path, sizeof path, "%s/workprecision.csv", out);
    cli_read_lines(path, &L);
    cr_assert_eq(L.n, 7, "%zu lines", L.n);
    double lo = INFINITY, hi = 0;
    for (size_t k = 1; k < L.n; k++) {
        cr_assert_str_eq(csv_field(L.line[k], 0, f, sizeof f),
                         k <= 3 ? "rk4" : "semi-bdf2:pcg");
        if (csv_number(L.line[k], 6) == 1) {
            lo = fmin(lo, csv_number(L.line[k], 3));
            hi = fmax(hi, csv_number(L.line[k], 3));
        }
    }
    cli_lines_free(&L);
    /* the decades 10^ceil(log10 lo) .. 10 hi, each a line "<= 1e-0K" */
    int rows = 0;
    for (double t = pow(10, ceil(log10(lo))); t <= 10 * hi; t *= 10, rows++) {
        char want[32];
        snprintf(want, sizeof want, "\n<= %.0e ", t);
        cr_assert(strstr(r.out, want), "no ranking for %g:\n%s", t, r.out);
    }
    cr_assert_geq(rows, 2, "errors %g .. %g", lo, hi);
    cli_result_free(&r);
    expect_refused(LIST("workprecision", "spring2", "--integrator",
                        "rk4:klu", "--dt", "1e-2"), 0,
                   LIST("rk4", "no choice of linear solver"));
    expect_refused(LIST("workprecision", "spring2", "--integrator",
                        "semi-bdf2:nosuch", "--dt", "1e-2"), 0,
                   LIST("semi-bdf2:nosuch", "nosuch"));
}

/* asinc --csv: the inverse sinc solves 1 - sinc(t) = 1 - y to round-off
 * (README: at most 2.2e-16) and Jiao's polynomial fits t/pi to 0.057
 * (0.055 .. 0.058 on 10000 intervals). */
Test(cli, asinc_table_and_csv)
{
    cli_result r;
    cli_run(&r, "asinc", "--points", "10000", "--csv", NULL);
    cli_assert_ok(&r);
    char *save, *line = strtok_r(r.out, "\n", &save);
    cr_assert_str_eq(line, "y,asinc,asinc_over_pi,seed_poly,residual");
    size_t n = 0;
    double fit = 0, resid = 0;
    while ((line = strtok_r(NULL, "\n", &save))) {
        double v[5];
        cli_parse_row(line, v, 5, "asinc --csv");
        cr_assert_float_eq(v[0], (double)n / 10000, 1e-15, "%s", line);
        cr_assert_float_eq(v[2], v[1] / M_PI, 1e-15, "%s", line);
        if (n == 0)
            cr_assert_float_eq(v[1], M_PI, 1e-15, "asinc(0) = pi: %s", line);
        fit = fmax(fit, fabs(v[3] - v[2]));
        resid = fmax(resid, v[4]);
        n++;
    }
    cr_assert_eq(n, 10001);
    cr_assert(fit > 0.055 && fit < 0.058, "max |p - asinc/pi| = %g", fit);
    cr_assert(resid <= 2.3e-16, "residual %g", resid);
    cli_result_free(&r);
    cli_run(&r, "asinc", "--points", "0", NULL);
    cli_assert_error(&r, 1, "--points", "\"0\"", "[1, 10000000]", NULL);
    cli_result_free(&r);
}

Test(cli, list_names_problems_integrators_terms)
{
    cli_result r;
    cli_run(&r, "list", NULL);
    cli_assert_ok(&r);
    const char *names[] = {"hang", "hang-smooth", "jiao", "cvode-bdf",
                           "symplectic-euler", "type1", "type2"};
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        char want[64];
        snprintf(want, sizeof want, "\n  %s ", names[k]);
        cr_assert(strstr(r.out, want), "list does not name %s:\n%s",
                  names[k], r.out);
    }
    cli_result_free(&r);
}

/* Entries of the problems folder that are not regular files (a FIFO,
 * which would block, a link to an endless device) are named, not read. */
Test(cli, list_names_odd_entries_without_reading_them)
{
    char dir[1100], path[1200];
    in_tmp(dir, "problems");
    cr_assert_eq(mkdir(dir, 0700), 0);
    snprintf(path, sizeof path, "%s/fifo.ini", dir);
    cr_assert_eq(mkfifo(path, 0600), 0);
    snprintf(path, sizeof path, "%s/zero.ini", dir);
    cr_assert_eq(symlink("/dev/zero", path), 0);
    snprintf(path, sizeof path, "%s/plain.ini", dir);
    tmp_put(path, "; a plain problem\n[cloth]\nn = 4\n");
    setenv("CLOTHODE_PROBLEMS", dir, 1);
    cli_result r;
    cli_run(&r, "list", NULL);
    unsetenv("CLOTHODE_PROBLEMS");
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "\n  fifo                 (it is a FIFO, not a "
                            "regular file)\n")
                  && strstr(r.out, "\n  zero                 (it is a device, "
                                   "not a regular file)\n")
                  && strstr(r.out, "\n  plain                a plain "
                                   "problem\n"), "%s", r.out);
    cli_result_free(&r);
}

Test(cli, help_on_every_subcommand)
{
    const char *cmds[] = {"run",       "eval",     "counts",
                          "list",      "convergence", "workprecision",
                          "stability", "spectrum", "energy",
                          "asinc"};
    enum { NCMD = sizeof cmds / sizeof cmds[0] };
    cli_result r;
    for (size_t k = 0; k < NCMD; k++) {
        cli_run(&r, cmds[k], "--help", NULL);
        cli_assert_ok(&r);
        cr_assert(strstr(r.out, "usage"), "%s --help:\n%s", cmds[k], r.out);
        cli_result_free(&r);
    }
    /* run's table: every [run] key, with or without an option, its range
     * and default (the text with its lines joined) */
    cli_run(&r, "run", "--help", NULL);
    char *w = r.out;
    for (const char *p = r.out; *p; p++)
        if (!isspace((unsigned char)*p) || (w > r.out && w[-1] != ' '))
            *w++ = isspace((unsigned char)*p) ? ' ' : *p;
    *w = '\0';
    static const char *const keys[] = {
        "--t-end T final time (s); [run] t_end, default 2",
        "--max-order K", "[run] max_order, 0 .. 12, default 0",
        "[run] newton_tol", "[run] verlet_damping",
        "[run] max_stretch a stretch d/L beyond this counts as a blow-up; "
        "default 10",
        "--samples S time-series rows after t = 0; with fixed steps on the "
        "nearest steps, so at most one a step; [run] samples, 1 .. "
        "100000000, default 200"};
    for (size_t k = 0; k < sizeof keys / sizeof *keys; k++)
        cr_assert(strstr(r.out, keys[k]), "run --help lacks %s:\n%s",
                  keys[k], r.out);
    cli_result_free(&r);
    cli_run(&r, "--help", NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "usage"), "--help:\n%s", r.out);
    for (size_t k = 0; k < NCMD; k++)
        cr_assert(strstr(r.out, cmds[k]), "--help does not list %s",
                  cmds[k]);
    cli_result_free(&r);
}

Test(cli, no_command_is_a_usage_error)
{
    cli_result r;
    cli_run(&r, NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 2);
    cr_assert(strstr(r.err, "usage: clothode COMMAND [options]"), "stderr:\n%s",
              r.err);
    cli_result_free(&r);
}

/* ---- obstacles: bad parameters, malformed meshes, unsupported pairs ---- */

Test(cli, bad_obstacle_parameters_are_refused)
{
    static const struct {
        const char *problem, *set, *want[6];
    } bad[] = {
        {"drape-sphere", "obstacle.ball.radius=0",
         {"--set: [obstacle.ball] radius = \"0\": expected a number > 0"}},
        {"drape-sphere", "obstacle.ball.radius=-1",
         {"radius = \"-1\": expected a number > 0"}},
        {"drape-sphere", "obstacle.floor.normal=0, 0, 0",
         {"[obstacle.floor] normal", "nonzero"}},
        {"drape-sphere", "obstacle.ball.shape=cone",
         {"shape", "cone", "sphere", "plane", "box", "mesh"}},
        {"drape-sphere", "obstacle.ball.response=bounce",
         {"response", "bounce", "penalty", "project", "barrier"}},
        {"drape-sphere", "obstacle.ball.path=0: 1, 2",
         {"[obstacle.ball] path", "keyframes"}},
        {"drape-sphere", "obstacle.ball.path=1: 0, 0, 0; 1: 1, 0, 0",
         {"path", "increasing"}},
        {"drape-sphere", "obstacle.ball.k=0",
         {"[obstacle.ball] k = \"0\": expected a number in [1e-300, 1e+12]"}},
        {"drape-box", "obstacle.table.size=1, 0, 1",
         {"[obstacle.table] size = \"1, 0, 1\": expected three side lengths "
          "> 0"}},
        {"drape-sphere-barrier", "obstacle.ball.kappa=0",
         {"[obstacle.ball] kappa = \"0\": expected a number in [1e-300, "
          "1e+12]"}},
        {"drape-box-barrier", "obstacle.table.dhat=-1",
         {"[obstacle.table] dhat = \"-1\": expected a number in [1e-300, "
          "1e+12]"}},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        const char *const *w = bad[k].want;
        expect_refused(LIST("run", bad[k].problem, "--set", bad[k].set), 0,
                       LIST(w[0], w[1], w[2] ? w[2] : w[1],
                            w[3] ? w[3] : w[1], w[4] ? w[4] : w[1],
                            w[5] ? w[5] : w[1]));
    }
}

Test(cli, projection_refused_by_an_integrator_that_cannot_apply_it)
{
    expect_refused(LIST("run", "jiao-sphere", "--integrator", "ida"), 0,
                   LIST("ida", "response = project", "penalty"));
    expect_refused(LIST("run", "jiao-sphere", "--integrator", "gsl-rk8pd"),
                   0, LIST("gsl-rk8pd", "response = project"));
    expect_refused(LIST("run", "jiao-sphere", "--integrator", "cvode-bdf"),
                   0, LIST("cvode-bdf", "friction", "zero_velocity"));
    expect_refused(LIST("energy", "verlet-scene1", "--integrator",
                        "cvode-bdf", "--t-end", "0.1"),
                   0, LIST("energy balance", "projections"));
}

/* A problem whose obstacle is the mesh FILE: every malformed OBJ stops the
 * run with one message naming the file and its line (or why the file as a
 * whole is refused) and a non-zero exit. */
Test(cli, malformed_obstacle_meshes_are_refused)
{
    static const struct {
        const char *name, *text, *want, *why;
    } bad[] = {
        {"empty.obj", "", "empty.obj:1", "empty file"},
        {"nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "nofaces.obj:3",
         "end of file without faces"},
        {"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "zero.obj:4",
         "vertex index 0 (indices start at 1"},
        {"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "range.obj:4",
         "vertex index 7 out of range (3 vertices"},
        {"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "nan.obj:2",
         "\"nan\" is not a finite number"},
        {"inf.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nf 1 2 3\n", "inf.obj:3",
         "\"inf\" is not a finite number"},
        {"degenerate.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
         "degenerate.obj:4", "zero area"},
        {"repeated.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n",
         "repeated.obj:4", "repeats a vertex"},
        {"token.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n", "token.obj:2",
         "\"zero\" is not a number"},
    };
    char ini[1100], obj[1100], text[1400];
    for (size_t k = 0; k < sizeof bad / sizeof *bad; k++) {
        tmp_put(in_tmp(obj, bad[k].name), bad[k].text);
        in_tmp(ini, "mesh.ini");
        snprintf(text, sizeof text,
                 "[cloth]\nn = 4\n[obstacle.rock]\nshape = mesh\nfile = %s\n"
                 "response = penalty\nk = 10\n", bad[k].name);
        tmp_put(ini, text);
        expect_refused(LIST("run", ini, "--t-end", "0.01"), 0,
                       LIST("mesh.ini:5: [obstacle.rock] file: ", bad[k].want,
                            bad[k].why));
    }
    /* a 10 MB line */
    char *big = malloc(10u << 20);
    cr_assert_not_null(big);
    memset(big, '1', (10u << 20) - 1);
    memcpy(big, "v 0 0 ", 6);
    big[(10u << 20) - 1] = '\0';
    tmp_put(in_tmp(obj, "long.obj"), big);
    free(big);
    snprintf(text, sizeof text, "[cloth]\nn = 4\n[obstacle.rock]\nshape = mesh"
             "\nfile = long.obj\nresponse = penalty\nk = 10\n");
    tmp_put(ini, text);
    expect_refused(LIST("run", ini, "--t-end", "0.01"), 0,
                   LIST("long.obj:1", "long"));
}

/* drape-sphere with one method of every family, through the first
 * contact (t = 0.4 s): each finishes, and the deepest penetration of its
 * samples (series.csv) stays within a few bands (eps = 5 mm) of the
 * surface. */
Test(cli, drape_sphere_runs_with_every_family)
{
    static const char *const runs[][4] = {
        {"cvode-bdf", NULL, NULL, NULL},
        {"semi-bdf2", "--dt", "0.01", NULL},
        {"semi-be", "--dt", "0.01", NULL},
        {"kinsol-bdf2", "--dt", "0.01", NULL},
        {"symplectic-euler", "--dt", "1e-4", NULL},
    };
    char out[1024], path[1100];
    for (size_t k = 0; k < sizeof runs / sizeof *runs; k++) {
        cli_result r;
        cli_run(&r, "run", "drape-sphere", "--t-end", "0.4", "--frames",
                "0", "--out", in_tmp(out, runs[k][0]), "--quiet",
                "--integrator", runs[k][0], runs[k][1], runs[k][2], NULL);
        cli_assert_ok(&r);
        cli_result_free(&r);
        series s;
        snprintf(path, sizeof path, "%s/series.csv", out);
        read_series(path, &s);
        int col = csv_column(s.header, "max_penetration");
        double pen = 0;
        for (size_t i = 0; i < s.nrow; i++)
            pen = fmax(pen, s.v[i * s.ncol + (size_t)col]);
        cr_assert_float_eq(s.v[(s.nrow - 1) * s.ncol], 0.4, 1e-12);
        cr_expect(pen >= 0.0 && pen < 0.02, "%s: deepest penetration %g m",
                  runs[k][0], pen);
        free(s.v);
    }
}

/* ---- exit status per class of failure --------------------------------- */

static void assert_status(const char *const *args, int want, const char *msg)
{
    cli_result r;
    cli_runv(&r, args);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, want, "%s: status %d, expected %d\n%s", r.cmd,
                 r.status, want, r.err);
    cr_assert(strstr(r.err, msg), "%s: no \"%s\" in\n%s", r.cmd, msg, r.err);
    cli_result_free(&r);
}

Test(cli, each_failure_class_has_its_exit_status)
{
    char out[64];
    tmp_mkdtemp(out, sizeof out, "exit");
    const char *bad[] = {"run", "hang", "--set", "cloth.n=1", "--out", out,
                         NULL};
    assert_status(bad, 2, "--set: [cloth] n = \"1\": expected an integer in "
                          "[2, 4096]");
    const char *usage[] = {"run", "hang", "--no-such-option", NULL};
    assert_status(usage, 2, "no-such-option");
    const char *blowup[] = {"run", "hang", "--integrator", "fe", "--dt",
                            "0.05", "--out", out, "--quiet", NULL};
    assert_status(blowup, 4, "blow-up");
    const char *solver[] = {"run", "hang", "--set", "cloth.n=8", "--set",
                            "run.max_steps=1", "--out", out, "--quiet",
                            NULL};
    assert_status(solver, 3, "mxstep");
    const char *budget[] = {"run", "hang", "--set", "cloth.n=8",
                            "--max-steps", "10", "--out", out, "--quiet",
                            NULL};
    assert_status(budget, 5, "--max-steps 10");
    char path[300], json[1 << 16];
    snprintf(path, sizeof path, "%s/run.json", out);
    tmp_slurp(path, json, sizeof json);
    cr_assert(strstr(json, "\"status\": \"budget\""), "%s", json);
    snprintf(path, sizeof path, "%s/final.csv", out);
    cr_assert(cli_exists(path), "a budget run writes final.csv");
    tmp_rm_rf(out);
}

/* `clothode ARGS` with stdout on /dev/full: exit status 7 and one message
 * saying so. */
static void stdout_full(char *const argv[])
{
    FILE *err = tmpfile();
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/full",
                                     O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&fa, fileno(err), STDERR_FILENO);
    pid_t pid;
    int ws;
    cr_assert_eq(posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    cr_assert_eq(waitpid(pid, &ws, 0), pid);
    char *msg = cli_slurp_fp(err);
    fclose(err);
    cr_assert(WIFEXITED(ws) && WEXITSTATUS(ws) == 7, "status %d: %s",
              WEXITSTATUS(ws), msg);
    cr_assert(strstr(msg, "cannot write standard output"), "%s", msg);
    cr_assert_eq(cli_count_lines(msg), 1, "%s", msg);
    free(msg);
}

/* The lost output is an I/O error; a run's run.json says the run failed
 * so (before: "complete", with the program's exit status 7). */
Test(cli, stdout_write_error_is_an_io_error)
{
    char *list[] = {(char *)cli_binary(), "list", NULL};
    stdout_full(list);
    char out[1024], path[1100], json[1 << 14];
    char *run[] = {(char *)cli_binary(), "run", "hang", "--set",
                   "cloth.n=4", "--t-end", "0.01", "--frames", "0", "--out",
                   (char *)in_tmp(out, "full"), NULL};
    stdout_full(run);
    snprintf(path, sizeof path, "%s/run.json", out);
    tmp_slurp(path, json, sizeof json);
    cr_assert(strstr(json, "\"status\": \"failed: cannot write standard "
                           "output"), "%s", json);
}

/* A write past the file-size limit (ulimit -f) is an I/O error with its
 * message, not death by SIGXFSZ with a temporary file behind. */
Test(cli, file_size_limit_is_an_io_error)
{
    char out[1024];
    char *argv[] = {"sh", "-c", "ulimit -f 20 && exec \"$0\" \"$@\"",
                    (char *)cli_binary(), "run", "hang", "--set",
                    "cloth.n=8", "--t-end", "0.1", "--quiet", "--out",
                    (char *)in_tmp(out, "fsize"), NULL};
    cli_result r;
    cli_spawn(&r, argv);
    cr_assert_eq(r.status, 7, "status %d: %s", r.status, r.err);
    cr_assert(strstr(r.err, "File too large"), "%s", r.err);
    cli_result_free(&r);
    DIR *d = opendir(out);
    cr_assert_not_null(d);
    for (struct dirent *e; (e = readdir(d));)
        cr_assert_null(strstr(e->d_name, ".tmp"), "%s left behind",
                       e->d_name);
    closedir(d);
}

/* Output paths that are not regular files are refused before any work,
 * and the special file is left as it was (as root, the rename of an
 * atomic write would replace a device node). */
Test(cli, special_output_paths_are_refused_untouched)
{
    char dir[64], fifo[128], out[128], state[300], null[128];
    struct stat before[3], after[3];
    tmp_mkdtemp(dir, sizeof dir, "special");
    snprintf(fifo, sizeof fifo, "%s/pipe", dir);
    snprintf(out, sizeof out, "%s/out", dir);
    snprintf(state, sizeof state, "%s/final.csv", out);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    /* a null device of the test's own as root (nothing else on the
     * machine touches it), /dev/null otherwise */
    snprintf(null, sizeof null, "%s/null", dir);
    const char *dev = mknod(null, S_IFCHR | 0666, makedev(1, 3)) == 0
                          ? null : "/dev/null";
    const char *nodes[] = {fifo, dev, "/dev/full"};
    for (size_t k = 0; k < 3; k++)
        cr_assert_eq(lstat(nodes[k], &before[k]), 0);
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--t-end", "0.01",
            "--out", out, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    const char *jac[] = {fifo, "/dev/full"};
    for (size_t k = 0; k < 2; k++) {
        cli_run(&r, "eval", "hang", "--set", "cloth.n=4", "--state", state,
                "--jacobian", jac[k], "--out", out, NULL);
        cli_assert_error(&r, 0, jac[k], "regular file", NULL);
        cr_assert_eq(r.status, 7);
        cli_result_free(&r);
    }
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--out", dev, NULL);
    cli_assert_error(&r, 0, dev, "not a directory", NULL);
    cr_assert_eq(r.status, 7);
    cli_result_free(&r);
    for (size_t k = 0; k < 3; k++) {
        cr_assert_eq(lstat(nodes[k], &after[k]), 0);
        cr_assert(before[k].st_mode == after[k].st_mode &&
                      before[k].st_ino == after[k].st_ino &&
                      before[k].st_rdev == after[k].st_rdev,
                  "%s was replaced", nodes[k]);
    }
    tmp_rm_rf(dir);
}
