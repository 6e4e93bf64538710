/* The studies that read a sweep job's series (analysis/sweep_series.c):
 * `energy` and `contact --from-sweep` print the same table as the study
 * made here, on a small instance run through `clothode sweep`. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "runcli.h"
#include "timelimit.h"

static char tmp[512];

static void setup(void)
{
    time_limit(180);
    tmp_mkdtemp(tmp, sizeof tmp, "sweepser");
}

static void teardown(void)
{
    tmp_rm_rf(tmp);
}

TestSuite(sweep_series, .init = setup, .fini = teardown);

/* The sweep `text` planned, run and collected into tmp/NAME; the table's
 * path into table. */
static void sweep(const char *name, const char *text, char *table,
                  size_t size)
{
    char ini[1024], dir[900];
    snprintf(ini, sizeof ini, "%s/%s.ini", tmp, name);
    snprintf(dir, sizeof dir, "%s/%s", tmp, name);
    snprintf(table, size, "%s/collected.csv", dir);
    tmp_put(ini, text);
    cli_result r;
    cli_run(&r, "sweep", "plan", ini, "--out", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cli_run(&r, "sweep", "run", dir, "--jobs", "2", "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cli_run(&r, "sweep", "collect", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
}

/* The study's table: the lines from the column header to "output", each
 * without its last field (the CPU time, which differs from run to run). */
static void table_of(const char *out, char *text, size_t size)
{
    const char *p = strstr(out, "integrator ");
    cr_assert(p, "%s", out);
    size_t used = 0;
    while (*p && strncmp(p, "output", 6)) {
        size_t len = strcspn(p, "\n");
        size_t keep = len;
        while (keep > 0 && p[keep - 1] != ' ')
            keep--; /* drop the last field */
        used += (size_t)snprintf(text + used, size - used, "%.*s\n",
                                 (int)keep, p);
        cr_assert_lt(used, size);
        p += len + (p[len] == '\n');
    }
}

/* The two study outputs' tables are the same. */
static void assert_same_table(const cli_result *here, const cli_result *swept)
{
    static char a[8192], b[8192];
    table_of(here->out, a, sizeof a);
    table_of(swept->out, b, sizeof b);
    cr_assert_str_eq(a, b, "made here:\n%s\nfrom the sweep:\n%s", a, b);
}

/* hang at n = 6, two explicit methods, 100 steps sampled 20 times:
 * E(0), E(T), W(T), B(T), max |B| and the steps agree to the printed
 * digits (the series keeps 10 digits). */
Test(sweep_series, energy_from_sweep_equals_the_study)
{
    char table[1024], out[1024];
    sweep("energy", "[sweep]\nproblem = problems/hang.ini\n"
          "integrator = symplectic-euler, rk4\ndt = 0.001\nt_end = 0.1\n"
          "n = 6, 8\nrun.samples = 20\n", table, sizeof table);
    const char *common[] = {"energy", "hang", "--set", "cloth.n=6",
                            "--integrator", "symplectic-euler,rk4", "--dt",
                            "1e-3", "--t-end", "0.1", "--out", out};
    cli_result here, swept;
    snprintf(out, sizeof out, "%s/here", tmp);
    cli_runv(&here, (const char *const[]){
        common[0], common[1], common[2], common[3], common[4], common[5],
        common[6], common[7], common[8], common[9], common[10], common[11],
        "--samples", "20", NULL});
    cli_assert_ok(&here);
    snprintf(out, sizeof out, "%s/swept", tmp);
    cli_runv(&swept, (const char *const[]){
        common[0], common[1], common[2], common[3], common[4], common[5],
        common[6], common[7], common[8], common[9], common[10], common[11],
        "--from-sweep", table, NULL});
    cli_assert_ok(&swept);
    assert_same_table(&here, &swept);
    cr_assert(strstr(swept.out, "rk4                 0.0000e+00"), "%s",
              swept.out);
    cli_result_free(&here);
    cli_result_free(&swept);
    /* energy.csv: every sample, the same to the series' 10 digits
     * (each field within 1e-9 of the largest of its row) */
    char csv[1100];
    cli_lines A, B;
    snprintf(csv, sizeof csv, "%s/here/energy.csv", tmp);
    cli_read_lines(csv, &A);
    snprintf(csv, sizeof csv, "%s/swept/energy.csv", tmp);
    cli_read_lines(csv, &B);
    cr_assert_eq(B.n, 1 + 2 * 21);
    cr_assert_eq(A.n, B.n);
    cr_assert_str_eq(A.line[0], B.line[0]);
    for (size_t k = 1; k < A.n; k++) {
        const char *a = strchr(A.line[k], ','), *b = strchr(B.line[k], ',');
        cr_assert(a && b && a - A.line[k] == b - B.line[k] &&
                  !strncmp(A.line[k], B.line[k], (size_t)(a - A.line[k])),
                  "%s\n%s", A.line[k], B.line[k]);
        double x[16], y[16], big = 0.0;
        int n = 0;
        for (char *ea, *eb; *a == ',' && *b == ',' && n < 16; a = ea, b = eb) {
            x[n] = strtod(a + 1, &ea);
            y[n] = strtod(b + 1, &eb);
            big = fmax(big, fmax(fabs(x[n]), fabs(y[n])));
            n++;
        }
        cr_assert(*a == '\0' && *b == '\0' && n > 5, "%s\n%s", A.line[k],
                  B.line[k]);
        for (int c = 0; c < n; c++)
            cr_assert_leq(fabs(x[c] - y[c]), 1e-9 * big, "row %zu field %d: "
                          "%.12g against %.12g", k, c + 1, x[c], y[c]);
    }
    cli_lines_free(&A);
    cli_lines_free(&B);
}

/* A particle on a penalty floor: symplectic Euler stable at 2e-3 and
 * 5e-3 and not at 1e-2 (the limit 2 sqrt(m/k) = 6.3e-3), semi-be stable
 * throughout; sampled at every step of the finest dt, so that the
 * series sees the worst penetration the contact hook sees. */
Test(sweep_series, contact_from_sweep_equals_the_study)
{
    char table[1024], out[1024];
    sweep("contact", "[sweep]\nproblem = problems/particle-floor.ini\n"
          "integrator = symplectic-euler, semi-be\n"
          "obstacle.floor.k = 1e4, 4e4\ndt = 0.002, 0.005, 0.01\n"
          "t_end = 0.2\nrun.samples = 100\n", table, sizeof table);
    cli_result here, swept;
    snprintf(out, sizeof out, "%s/here", tmp);
    cli_run(&here, "contact", "particle-floor", "--integrator",
            "symplectic-euler,semi-be", "--t-end", "0.2", "--checks", "100",
            "--dt", "0.002,0.005,0.01", "--out", out, NULL);
    cli_assert_ok(&here);
    snprintf(out, sizeof out, "%s/swept", tmp);
    cli_run(&swept, "contact", "particle-floor", "--integrator",
            "symplectic-euler,semi-be", "--t-end", "0.2", "--checks", "100",
            "--from-sweep", table, "--out", out, NULL);
    cli_assert_ok(&swept);
    assert_same_table(&here, &swept);
    cr_assert(strstr(swept.out, "unstable from dt = 0.01, stable at 0.005"),
              "%s", swept.out);
    cli_result_free(&here);
    cli_result_free(&swept);
    /* --k: the bracket of each stiffness on the sweep's grid, beside the
     * prediction 2 sqrt(m/k) */
    cli_run(&swept, "contact", "particle-floor", "--integrator",
            "symplectic-euler", "--t-end", "0.2", "--k", "1e4,4e4",
            "--from-sweep", table, "--out", out, NULL);
    cli_assert_ok(&swept);
    cr_assert(strstr(swept.out, "symplectic-euler        1e+04       0.005 "
                                "       0.01    0.006325"), "%s",
              swept.out);
    cr_assert(strstr(swept.out, "symplectic-euler        4e+04       0.002 "
                                "      0.005    0.003162"), "%s",
              swept.out);
    cli_result_free(&swept);
    /* --response of a sweep with no response axis: its runs are all of the
     * file's penalty floor (before: the project rows were the penalty
     * runs, reported as the projection's) */
    cli_run(&swept, "contact", "particle-floor", "--integrator",
            "symplectic-euler", "--t-end", "0.2", "--response",
            "penalty,project", "--from-sweep", table, "--out", out, NULL);
    cli_assert_error(&swept, 0, "--response, yet obstacle.floor.response is "
                     "no axis of the sweep", "give --response only with a "
                     "sweep over it", NULL);
    cr_assert_eq(swept.status, 2);
    cli_result_free(&swept);
}

Test(sweep_series, series_must_be_beside_the_table)
{
    char table[1024], moved[1100], text[65536], out[1024];
    sweep("e", "[sweep]\nproblem = problems/hang.ini\n"
          "integrator = rk4\ndt = 0.001\nt_end = 0.01\nn = 6\n", table,
          sizeof table);
    snprintf(moved, sizeof moved, "%s/t.csv", tmp);
    tmp_slurp(table, text, sizeof text);
    tmp_put(moved, text);
    snprintf(out, sizeof out, "%s/o", tmp);
    cli_result r;
    cli_run(&r, "energy", "hang", "--set", "cloth.n=6", "--integrator",
            "rk4", "--dt", "1e-3", "--t-end", "0.01", "--from-sweep", moved,
            "--out", out, NULL);
    cr_assert_neq(r.status, 0);
    cr_assert(strstr(r.err, "jobs/") && strstr(r.err, "collect into the "
                                                     "sweep directory"),
              "%s", r.err);
    cli_result_free(&r);
}
