/* The claims table (scripts/claims.sh, README "Reports"): every row's
 * command is run here at a reduced size (a shorter horizon, a coarser
 * bracket, fewer points) and must exit 0 and write the quantity the row
 * reads, parsed as the script parses it.  Rows whose quantity has a known
 * answer (the connection counts, an order) are checked against it; the
 * others against the value measured at the reduced size (deterministic
 * runs: a stability limit to 5 %, so that one bisection decision taken
 * otherwise (10 %) shows; an error or a penetration to 5-10 %, a count of
 * wrinkles to 2), so that a change of what a row measures shows here
 * before the report.  A limit at the top of its search (the default
 * dt_max, t_end / 100, or --dt-max) means stable over the whole bracket.  The list
 * of rows is the script's ROWS; a test checks that both lists agree. */
#include <criterion/criterion.h>

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "runcli.h"
#include "timelimit.h"

static char tmp[512];

static void setup(void)
{
    time_limit(600);
    tmp_mkdtemp(tmp, sizeof tmp, "claims");
}

static void teardown(void)
{
    tmp_rm_rf(tmp);
}

TestSuite(claims, .init = setup, .fini = teardown);

/* Jiao's 10 x 10 cloth (problems/jiao.ini, spacing 1 m). */
#define J10 "--set cloth.n=10 --set cloth.size=9 "

/* The rows with a command, each run by one test below; the rows "not
 * testable here" have none. */
static const char *const rows_run[] = {
    "jiao-limit-fe", "jiao-limit-symplectic-euler", "jiao-bdf2-bounded",
    "jiao-bdf2-accurate", "jiao-explicit-wrinkles", "jiao-stiffness",
    "jiao-more-wrinkles", "jiao-counts-ck", "jiao-counts-bw",
    "jiao-counts-slower", "jiao-asinc", "jiao-asinc-used",
    "jiao-sphere-inside", "jiao-sphere-unstable", "jiao-sphere-small",
    "jiao-sphere-fig13", "jiao-sphere-fig14", "verlet-small-sphere",
    "skirt-limit", "skirt-penalty", "skirt-penalty-file", "verlet-order",
    "verlet-pbd-60", "verlet-pbd-30", "verlet-spring-k150", "verlet-spring-k15",
    "verlet-friction", "verlet-friction-30", "verlet-map", NULL};
static const char *const rows_untestable[] = {"verlet-fps", "verlet-look",
                                              "zca-ratio", NULL};

/* Run clothode with the space-separated arguments `args` (and, unless
 * `plain`, --out TMP/ID); it must exit 0.  The result is the caller's to
 * free; the output directory's name goes into dir. */
static cli_result row_run(const char *id, const char *args, int plain,
                          char *dir, size_t len)
{
    static char buf[2048];
    const char *argv[CLI_MAX_ARGS + 1];
    size_t n = 0;
    snprintf(dir, len, "%s/%s", tmp, id);
    cr_assert_lt(strlen(args), sizeof buf);
    strcpy(buf, args);
    for (char *tok = strtok(buf, " "); tok; tok = strtok(NULL, " ")) {
        cr_assert_lt(n, CLI_MAX_ARGS - 2);
        argv[n++] = tok;
    }
    if (!plain) {
        argv[n++] = "--out";
        argv[n++] = dir;
    }
    argv[n] = NULL;
    cli_result r;
    cli_runv(&r, argv);
    cli_assert_ok(&r);
    return r;
}

static double parse_number(const char *s, const char *what)
{
    char *end;
    double v = strtod(s, &end);
    cr_assert(end != s, "%s: \"%.40s\" is not a number", what, s);
    cr_assert(isfinite(v), "%s: %g is not finite", what, v);
    return v;
}

static void expect_in(double v, double lo, double hi, const char *what)
{
    cr_assert(isfinite(v) && v >= lo && v <= hi,
              "%s = %g, expected in [%g, %g]", what, v, lo, hi);
}

/* v within rel (relative) of the value measured at the reduced size. */
static void expect_near(double v, double measured, double rel,
                        const char *what)
{
    cr_assert(isfinite(v) && fabs(v - measured) <= rel * fabs(measured),
              "%s = %g, measured %g (to %g %%)", what, v, measured,
              100 * rel);
}

/* The k-th (0-based) comma-separated field of a line (no quoted commas
 * before it), as a number. */
static double field(const char *line, int k, const char *what)
{
    const char *p = line;
    for (int i = 0; i < k; i++) {
        p = strchr(p, ',');
        cr_assert_not_null(p, "%s: \"%s\" has no field %d", what, line, k);
        p++;
    }
    return parse_number(p, what);
}

/* The column named `name` of a CSV header, 0-based. */
static int column(const char *header, const char *name)
{
    size_t len = strlen(name);
    int k = 0;
    for (const char *p = header;; k++) {
        if (!strncmp(p, name, len) && (p[len] == ',' || p[len] == '\0'))
            return k;
        p = strchr(p, ',');
        cr_assert_not_null(p, "no column %s in \"%s\"", name, header);
        p++;
    }
}

/* The largest stable step of `method` in DIR/stability.csv. */
static double stable_dt(const char *dir, const char *method)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/stability.csv", dir);
    cli_lines L;
    cli_read_lines(path, &L);
    cr_assert_str_eq(L.line[0], "integrator,dt,steps,stable,status,cpu,"
                                "stretch,reason");
    double best = -1.0;
    size_t len = strlen(method);
    for (size_t k = 1; k < L.n; k++)
        if (!strncmp(L.line[k], method, len) && L.line[k][len] == ',' &&
            field(L.line[k], 3, path) == 1.0)
            best = fmax(best, field(L.line[k], 1, path));
    cli_lines_free(&L);
    cr_assert_gt(best, 0.0, "%s: no stable run of %s", path, method);
    return best;
}

/* The largest (or, with last, the final) value of a series.csv column. */
static double series(const char *dir, const char *name, int last)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/series.csv", dir);
    cli_lines L;
    cli_read_lines(path, &L);
    cr_assert_gt(L.n, 1, "%s has no rows", path);
    int c = column(L.line[0], name);
    double v = -INFINITY;
    for (size_t k = 1; k < L.n; k++) {
        double x = field(L.line[k], c, path);
        v = last ? x : fmax(v, x);
    }
    cli_lines_free(&L);
    return v;
}

/* A field of the first row of `method` in DIR/convergence.csv. */
static double convergence(const char *dir, const char *method,
                          const char *name)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/convergence.csv", dir);
    cli_lines L;
    cli_read_lines(path, &L);
    int c = column(L.line[0], name);
    size_t len = strlen(method);
    for (size_t k = 1; k < L.n; k++)
        if (!strncmp(L.line[k], method, len) && L.line[k][len] == ',') {
            double v = field(L.line[k], c, path);
            cli_lines_free(&L);
            return v;
        }
    cr_assert_fail("%s: no row of %s", path, method);
    return NAN;
}

/* The column `name` of row k (1-based, after the header) of
 * DIR/contact.csv, whose header and row count are checked. */
static double contact(const char *dir, size_t k, size_t rows,
                      const char *name)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/contact.csv", dir);
    cli_lines L;
    cli_read_lines(path, &L);
    cr_assert_str_eq(L.line[0], "integrator,response,dt,steps,stable,status,"
                                "worst_penetration,worst_t,rest_penetration,"
                                "rest_contacts,max_stretch,newton_iters,cpu,"
                                "reason");
    cr_assert_eq(L.n, rows + 1, "%s: %zu lines", path, L.n);
    double v = field(L.line[k], column(L.line[0], name), path);
    cli_lines_free(&L);
    return v;
}

/* The worst penetration a run's summary prints (m). */
static double penetration(const cli_result *r)
{
    const char *p = strstr(r->out, "worst penetration ");
    cr_assert_not_null(p, "%s: no worst penetration in\n%s", r->cmd, r->out);
    return parse_number(p + strlen("worst penetration "), r->cmd);
}

static void free_result(cli_result r)
{
    cli_result_free(&r);
}

/* ---- the rows --------------------------------------------------------- */

Test(claims, rows_match_the_script)
{
    FILE *fp = fopen("scripts/claims.sh", "r");
    cr_assert_not_null(fp, "scripts/claims.sh (run from the repository root)");
    char *s = cli_slurp_fp(fp);
    fclose(fp);
    char *p = strstr(s, "\nROWS=(");
    cr_assert_not_null(p, "no ROWS=( in scripts/claims.sh");
    p += strlen("\nROWS=(");
    char *end = strchr(p, ')');
    cr_assert_not_null(end);
    *end = '\0';
    size_t n = 0, nrun = 0, nun = 0;
    for (char *tok = strtok(p, " \n"); tok; tok = strtok(NULL, " \n"), n++) {
        int found = 0;
        for (size_t k = 0; rows_run[k]; k++)
            found += !strcmp(tok, rows_run[k]);
        for (size_t k = 0; rows_untestable[k]; k++)
            found += !strcmp(tok, rows_untestable[k]);
        cr_assert_eq(found, 1, "row %s of scripts/claims.sh: %d tests", tok,
                     found);
    }
    while (rows_run[nrun])
        nrun++;
    while (rows_untestable[nun])
        nun++;
    cr_assert_eq(n, nrun + nun, "the script has %zu rows, the test %zu", n,
                 nrun + nun);
    free(s);
}

Test(claims, jiao_limits)
{
    char dir[1024];
    free_result(row_run("jiao-limit-fe",
                        "stability jiao " J10 "--integrator fe --t-end 0.1 "
                        "--rel 0.1 --quiet",
                        0, dir, sizeof dir));
    expect_near(stable_dt(dir, "fe"), 4.717e-4, 0.05, "fe limit");
    free_result(row_run("jiao-limit-symplectic-euler",
                        "stability jiao " J10 "--integrator symplectic-euler "
                        "--t-end 0.1 --rel 0.1 --quiet",
                        0, dir, sizeof dir));
    /* the top of the search, t_end / 100 */
    expect_near(stable_dt(dir, "symplectic-euler"), 1e-3, 0.05,
                "symplectic Euler limit");
}

Test(claims, jiao_bdf2)
{
    char dir[1024];
    free_result(row_run("jiao-bdf2-bounded",
                        "stability jiao " J10 "--integrator semi-bdf2 "
                        "--t-end 0.2 --dt-max 0.02 --rel 0.1 --quiet",
                        0, dir, sizeof dir));
    /* stable over the whole bracket */
    expect_near(stable_dt(dir, "semi-bdf2"), 0.02, 1e-12, "semi-bdf2 limit");
    free_result(row_run("jiao-bdf2-accurate",
                        "convergence jiao " J10 "--integrator semi-bdf2 "
                        "--dt 0.02 --levels 2 --t-end 0.1 --ref-rtol 1e-5",
                        0, dir, sizeof dir));
    expect_near(convergence(dir, "semi-bdf2", "err_x"), 0.7318, 0.05,
                "semi-bdf2 error");
}

Test(claims, jiao_wrinkles)
{
    char dir[1024];
    free_result(row_run("jiao-explicit-wrinkles",
                        "run compress --integrator symplectic-euler --dt 1e-4 "
                        "--t-end 0.05 --frames 0 --samples 10 --quiet",
                        0, dir, sizeof dir));
    expect_in(series(dir, "wrinkles", 0), 11.0, 15.0, "wrinkles (13)");
    expect_near(series(dir, "max_offplane", 1), 8.451e-3, 0.05, "amplitude");
    free_result(row_run("jiao-stiffness",
                        "stability compress --set type1.ks=2000 "
                        "--set type2.cb=2000 --integrator "
                        "symplectic-euler,semi-be --t-end 0.01 --rel 0.1 "
                        "--quiet",
                        0, dir, sizeof dir));
    expect_near(stable_dt(dir, "symplectic-euler"), 5e-5, 0.05, "explicit");
    expect_near(stable_dt(dir, "semi-be"), 1e-4, 0.05,
                "semi-be (the top of the search)");
    const char *more[] = {"run compress --integrator semi-be --dt 1e-3 "
                          "--set type1.ks=2000 --set type2.cb=2000 "
                          "--t-end 0.05 --frames 0 --samples 10 --quiet",
                          "run compress --integrator semi-be --dt 1e-3 "
                          "--t-end 0.05 --frames 0 --samples 10 --quiet"};
    const double most[] = {15, 13};
    for (int k = 0; k < 2; k++) {
        free_result(row_run("jiao-more-wrinkles", more[k], 0, dir,
                            sizeof dir));
        expect_in(series(dir, "wrinkles", 0), most[k] - 2, most[k] + 2,
                  more[k]);
    }
}

/* Known answers: Choi-Ko counts equal Jiao's formulas; Jiao's bending
 * count exceeds the interior edges by 4(N-1) = 36 at N = 10; CK exceeds
 * the counted BW. */
Test(claims, jiao_counts)
{
    char dir[1024];
    cli_result r = row_run("jiao-counts-ck", "counts --csv --n-max 10", 1,
                           dir, sizeof dir);
    double ck10 = NAN;
    const char *line = strchr(r.out, '\n');
    cr_assert_not_null(line);
    cr_assert(!strncmp(r.out, "n,type1,type1_formula,type2,type2_formula,ck,"
                              "ck_formula\n",
                       (size_t)(line - r.out) + 1),
              "counts --csv header");
    for (line++; *line; line = strchr(line, '\n') + 1) {
        for (int k = 1; k <= 5; k += 2)
            cr_assert_eq(field(line, k, "counts"), field(line, k + 1, "counts"),
                         "counts: %.40s", line);
        if (field(line, 0, "counts") == 10.0)
            ck10 = field(line, 5, "counts");
    }
    free_result(r);
    r = row_run("jiao-counts-bw", "counts --n-max 10", 1, dir, sizeof dir);
    double v[10];
    int found = 0;
    /* the Baraff-Witkin rows: n tris f hinges f edges f BW f Jiao's BW */
    for (const char *p = r.out; !found && p; p = strchr(p, '\n')) {
        p += *p == '\n';
        found = sscanf(p, "%lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", v, v + 1,
                       v + 2, v + 3, v + 4, v + 5, v + 6, v + 7, v + 8,
                       v + 9) == 10 &&
                v[0] == 10.0;
    }
    cr_assert(found, "counts: no Baraff-Witkin row for n = 10\n%s", r.out);
    cr_assert_eq(v[9] - v[7], 36.0, "Jiao's BW minus the count at n = 10");
    cr_assert_gt(ck10 / v[7], 1.0, "jiao-counts-slower: CK over BW");
    free_result(r);
}

Test(claims, jiao_asinc)
{
    char dir[1024];
    cli_result r = row_run("jiao-asinc", "asinc --points 50 --csv", 1, dir,
                           sizeof dir);
    double e_pi = 0.0, e = 0.0;
    const char *line = strchr(r.out, '\n');
    cr_assert_not_null(line);
    for (line++; *line; line = strchr(line, '\n') + 1) {
        double p = field(line, 3, "asinc");
        e_pi = fmax(e_pi, fabs(p - field(line, 2, "asinc")));
        e = fmax(e, fabs(p - field(line, 1, "asinc")));
    }
    expect_near(e_pi, 0.0565, 0.05, "|p - asinc/pi|");
    /* p is asinc/pi's fit: at x = 0, p = 1 where asinc = pi */
    expect_near(e, M_PI - 1, 1e-6, "jiao-asinc-used: |p - asinc|");
    free_result(r);
}

Test(claims, jiao_sphere)
{
    char dir[1024];
    cli_result r = row_run("jiao-sphere-inside",
                           "run jiao-sphere --integrator semi-bdf2 --dt 0.02 "
                           "--t-end 0.2 --frames 0",
                           0, dir, sizeof dir);
    expect_near(penetration(&r), 2.326, 0.05, "penetration at 0.02 s");
    free_result(r);
    const char *stab[] = {"stability jiao-sphere --integrator semi-bdf2 "
                          "--t-end 0.2 --dt-max 0.02 --rel 0.1 --quiet",
                          "stability jiao --integrator semi-bdf2 "
                          "--t-end 0.2 --dt-max 0.02 --rel 0.1 --quiet"};
    for (int k = 0; k < 2; k++) {
        free_result(row_run("jiao-sphere-unstable", stab[k], 0, dir,
                            sizeof dir));
        expect_near(stable_dt(dir, "semi-bdf2"), 0.02, 1e-12, "semi-bdf2");
    }
    r = row_run("jiao-sphere-small", "run jiao-sphere --t-end 0.1 --frames 0",
                0, dir, sizeof dir);
    expect_near(penetration(&r), 2.755e-2, 0.1, "penetration at 5e-4 s");
    free_result(r);
}

/* The contact study's rows at T = 0.2 s: the projection's runs on
 * jiao-sphere and the instability test on jiao alone; scene 1 of the
 * Verlet-and-PBD report up to the sphere's passage (t = 2.3 s), where a
 * sphere of radius 0.05 m, below half the 0.15 m quad's diagonal, touches
 * no particle and one of 0.2 m does. */
Test(claims, contact_study)
{
    char dir[1024];
    free_result(row_run("jiao-sphere-fig13",
                        "contact jiao-sphere --integrator semi-bdf2 "
                        "--response project --dt 1e-2,2e-2 --t-end 0.2 "
                        "--checks 20 --set run.max_stretch=3 --quiet",
                        0, dir, sizeof dir));
    const double worst[] = {0.8890, 1.894}; /* at dt = 1e-2, 2e-2 */
    for (size_t k = 1; k <= 2; k++) {
        double stable = contact(dir, k, 2, "stable");
        cr_assert(stable == 0.0 || stable == 1.0);
        expect_near(contact(dir, k, 2, "worst_penetration"), worst[k - 1],
                    0.05, "jiao-sphere penetration");
    }
    free_result(row_run("jiao-sphere-fig13",
                        "stability jiao --integrator semi-bdf2 --t-end 0.2 "
                        "--checks 20 --set run.max_stretch=3 --dt-max 0.02 "
                        "--rel 0.1 --quiet",
                        0, dir, sizeof dir));
    expect_near(stable_dt(dir, "semi-bdf2"), 0.02, 1e-12, "jiao alone");
    const char *scene1 = "contact verlet-scene1 --integrator verlet-pbd "
                         "--dt 0.016666666666666666 --t-end 2.5 --quiet "
                         "--set obstacle.ball.radius=";
    char args[256];
    snprintf(args, sizeof args, "%s0.05", scene1);
    free_result(row_run("verlet-small-sphere", args, 0, dir, sizeof dir));
    cr_assert_eq(contact(dir, 1, 1, "worst_penetration"), 0.0);
    snprintf(args, sizeof args, "%s0.2", scene1);
    free_result(row_run("verlet-small-sphere", args, 0, dir, sizeof dir));
    expect_near(contact(dir, 1, 1, "worst_penetration"), 0.1087, 0.05,
                "radius 0.2 m");
}

Test(claims, skirt)
{
    char dir[1024];
    free_result(row_run("skirt-limit",
                        "run skirt --integrator symplectic-euler-x --dt 4e-4 "
                        "--t-end 0.04 --frames 0 --quiet",
                        0, dir, sizeof dir));
    /* the rest shape's 1: the skirt has not yet stretched at 0.04 s */
    expect_near(series(dir, "max_stretch", 0), 1.0, 0.01, "skirt stretch");
    cli_result r = row_run("skirt-penalty",
                           "run skirt --integrator symplectic-euler-x "
                           "--dt 8e-4 --t-end 0.4 "
                           "--set obstacle.floor.point=0,-50,0 --frames 0",
                           0, dir, sizeof dir);
    expect_near(penetration(&r), 4.217e-3, 0.1, "skirt penetration");
    free_result(r);
    r = row_run("skirt-penalty-file",
                "run skirt --t-end 0.4 --set obstacle.floor.point=0,-50,0 "
                "--frames 0",
                0, dir, sizeof dir);
    expect_near(penetration(&r), 4.22e-3, 0.1,
                "skirt penetration at 2e-4 s");
    free_result(r);
}

Test(claims, verlet)
{
    char dir[1024];
    free_result(row_run("verlet-order",
                        "convergence spring2 --integrator verlet --dt 1e-2 "
                        "--levels 2 --t-end 0.2 --set gravity.g=-10,0,0 "
                        "--set init.velocity=0,0,0 --quiet",
                        0, dir, sizeof dir));
    expect_near(convergence(dir, "verlet", "fit_x"), 2.0, 0.025,
                "verlet order");
    const char *pbd[][2] = {
        {"verlet-pbd-60", "run verlet-scene1 --dt 0.016666666666666666 "
                          "--t-end 0.5 --frames 0 --quiet"},
        {"verlet-pbd-30", "run verlet-scene1 --dt 0.033333333333333333 "
                          "--t-end 0.5 --frames 0 --quiet"},
        {"verlet-friction", "run verlet-drop --t-end 0.5 --frames 0 --quiet"},
        {"verlet-friction-30", "run verlet-drop --dt 0.033333333333333333 "
                               "--t-end 0.2 --frames 0 --quiet"},
        {"verlet-map", "run verlet-drop --set springs.k_structural=50 "
                       "--set spring-damping.kd=0.5 --t-end 0.5 --frames 0 "
                       "--samples 20 --quiet"}};
    const double stretch[] = {1.2677, 1.7149, 1.1951, 1.5543, 1.1951};
    for (size_t k = 0; k < sizeof pbd / sizeof *pbd; k++) {
        free_result(row_run(pbd[k][0], pbd[k][1], 0, dir, sizeof dir));
        expect_near(series(dir, "max_stretch", 0), stretch[k], 0.02,
                    pbd[k][0]);
    }
    const char *spring[][2] = {
        {"verlet-spring-k150", "run verlet-drop --set spring-damping.kd=0 "
                               "--set springs.k_structural=150 --t-end 0.1 "
                               "--frames 0 --quiet"},
        {"verlet-spring-k15", "run verlet-drop --set spring-damping.kd=0 "
                              "--set springs.k_structural=15 --t-end 0.1 "
                              "--frames 0 --quiet"}};
    for (size_t k = 0; k < 2; k++) {
        free_result(row_run(spring[k][0], spring[k][1], 0, dir, sizeof dir));
        cr_assert_float_eq(series(dir, "t", 1), 0.1, 1e-12, "%s",
                           spring[k][0]);
    }
}
