/* The next stage of a sweep over dt (analysis/sweep_refine.c, `clothode
 * sweep refine`): steps inside the brackets of the collected stages, made
 * whole steps of T, and the stages read together by --from-sweep. */
#include <criterion/criterion.h>

#include <stdio.h>
#include <string.h>

#include "runcli.h"
#include "timelimit.h"

static char tmp[512];

static void setup(void)
{
    time_limit(120);
    tmp_mkdtemp(tmp, sizeof tmp, "sweepref");
}

static void teardown(void)
{
    tmp_rm_rf(tmp);
}

TestSuite(sweep_refine, .init = setup, .fini = teardown);

/* sweep refine DIR --table TABLE OPTION VALUE --out FINE succeeds and
 * says `want`. */
static void refine_plans(const char *dir, const char *table,
                         const char *option, const char *value,
                         const char *fine, const char *want)
{
    cli_result r;
    cli_run(&r, "sweep", "refine", dir, "--table", table, option, value,
            "--out", fine, NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, want), "%s", r.out);
    cli_result_free(&r);
}

/* The table `path` with one more row, a copy of its complete run at 8 ms
 * made another problem's (particle-flood.ini) and moved to 12.5 ms, into
 * out (in tmp). */
static void mixed_table(const char *path, char *out, size_t len)
{
    char text[65536], row[4096];
    tmp_slurp(path, text, sizeof text - sizeof row);
    const char *at = strstr(text, ",0.008,");
    cr_assert_not_null(at, "%s", text);
    const char *start = at;
    while (start > text && start[-1] != '\n')
        start--;
    size_t n = (size_t)(strchr(at, '\n') - start);
    snprintf(row, sizeof row, "x%.*s", (int)n - 1, start + 1);
    char *dt = strstr(row, ",0.008,"), *problem = strstr(row,
                                                         "particle-floor");
    cr_assert(dt && problem, "%s", row);
    memcpy(problem, "particle-flood", 14);
    memmove(dt + 7, dt + 6, strlen(dt + 6) + 1); /* ",0.008," -> ",0.0125," */
    memcpy(dt, ",0.0125,", 8);
    strcat(text, row);
    strcat(text, "\n");
    snprintf(out, len, "%s/mixed.csv", tmp);
    tmp_put(out, text);
}

/* A particle on a penalty floor, symplectic Euler over 0.2 s: the grid
 * 2, 4, 8, 16 ms brackets the limit between 8 and 16 ms; three points
 * 8 ms 2^(i/4) made 0.2/N: 0.2/21, 0.2/18, 0.2/15; with both stages the
 * bracket narrows to 9.52 .. 11.1 ms. */
Test(sweep_refine, steps_inside_the_bracket)
{
    char dir[700], fine[700], t1[700], t2[700], both[1500], out[700],
        text[65536];
    cli_sweep_through(tmp, "[sweep]\nproblem = problems/particle-floor.ini\n"
                           "integrator = symplectic-euler\n"
                           "dt = 0.002, 0.004, 0.008, 0.016\nt_end = 0.2\n",
                      dir, t1, sizeof t1);
    snprintf(fine, sizeof fine, "%s/s-refine", tmp);
    cli_result r;
    /* into the refined sweep's own directory: refused, its manifest kept */
    char manifest[800], before[65536];
    snprintf(manifest, sizeof manifest, "%s/sweep.json", dir);
    tmp_slurp(manifest, before, sizeof before);
    cli_run(&r, "sweep", "refine", dir, "--table", t1, "--out", dir, NULL);
    cli_assert_error(&r, 0, "it is the sweep being refined", NULL);
    cli_result_free(&r);
    tmp_slurp(manifest, text, sizeof text);
    cr_assert_str_eq(text, before);
    cli_run(&r, "sweep", "refine", dir, "--table", t1, "--points", "3",
            NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "refine     3 jobs inside 1 brackets wider than "
                            "1 + 0.02\n"), "%s", r.out);
    cli_result_free(&r);
    snprintf(manifest, sizeof manifest, "%s/sweep.json", fine);
    tmp_slurp(manifest, text, sizeof text);
    /* T / N to the last digit, the stability search's steps */
    cr_assert(strstr(text, "\"run.dt\": \"0.009523809523809525\"") &&
              strstr(text, "\"run.dt\": \"0.011111111111111112\"") &&
              strstr(text, "\"run.dt\": \"0.013333333333333334\""), "%s",
              text);
    snprintf(t2, sizeof t2, "%s/fine.csv", tmp);
    cli_run_ok((const char *const[]){"sweep", "run", fine, "--jobs", "2",
                                     "--quiet", NULL});
    cli_run_ok((const char *const[]){"sweep", "collect", fine, "--out", t2,
                                     "--quiet", NULL});
    snprintf(both, sizeof both, "%s,%s", t1, t2);
    snprintf(out, sizeof out, "%s/st", tmp);
    cli_run(&r, "stability", "particle-floor", "--t-end", "0.2",
            "--integrator", "symplectic-euler", "--from-sweep", both,
            "--out", out, NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "symplectic-euler      0.009524      -     0.01111"
                            "     7  failed at t = 0.1 s (blow-up)\n"), "%s",
              r.out);
    cli_result_free(&r);
    /* narrow enough: nothing left to plan */
    refine_plans(dir, both, "--rel", "0.2", fine,
                 "refine     0 jobs inside 0 brackets");
    /* a row of another problem in the table, stable at 12.5 ms inside the
     * bracket, is left out of it: the same three points as before */
    mixed_table(t1, out, sizeof out);
    refine_plans(dir, out, "--points", "3", fine,
                 "refine     3 jobs inside 1 brackets");
    snprintf(manifest, sizeof manifest, "%s/sweep.json", fine);
    tmp_slurp(manifest, text, sizeof text);
    cr_assert(strstr(text, "\"run.dt\": \"0.009523809523809525\""), "%s",
              text);
    /* a table of another sweep (another problem, or other integrators)
     * would plan an empty stage: refused, naming the sweep */
    static const char *const other[][2] = {
        {"particle-floor.ini", "particle-flood.ini"},
        {"symplectic-euler", "symplectic-eulex"}};
    for (int k = 0; k < 2; k++) {
        tmp_slurp(t1, text, sizeof text);
        for (char *p = text; (p = strstr(p, other[k][0])); p++)
            memcpy(p, other[k][1], strlen(other[k][1]));
        snprintf(out, sizeof out, "%s/other.csv", tmp);
        tmp_put(out, text);
        cli_run(&r, "sweep", "refine", dir, "--table", out, "--out", fine,
                NULL);
        cli_assert_error(&r, 0, "sweep refine: no run of", "is one of the "
                         "sweep in", "give the tables of this sweep's "
                         "stages", NULL);
        cli_result_free(&r);
    }
    /* a row without a result is named, not silently left out */
    tmp_slurp(t1, text, sizeof text);
    char *row = strstr(text, "complete,ok");
    cr_assert_not_null(row, "%s", text);
    memcpy(row, "missing,mis", 11);
    memmove(row + 15, row + 11, strlen(row + 11) + 1);
    memcpy(row + 11, "sing", 4);
    tmp_put(t1, text);
    cli_run(&r, "sweep", "refine", dir, "--table", t1, "--out", fine,
            "--quiet", NULL);
    cr_assert(r.exited && r.status == 0, "%s", r.err);
    cr_assert(strstr(r.err, "rows without a result, left out of the "
                            "brackets: ") && strstr(r.err, " (1 in all)"),
              "%s", r.err);
    cli_result_free(&r);
}

Test(sweep_refine, stages_must_have_the_same_columns)
{
    char a[600], b[600], both[1300], out[600];
    snprintf(a, sizeof a, "%s/a.csv", tmp);
    snprintf(b, sizeof b, "%s/b.csv", tmp);
    tmp_put(a, "id,role,integrator,run.dt,status\n");
    tmp_put(b, "id,role,integrator,cloth.n,run.dt,status\n");
    snprintf(both, sizeof both, "%s,%s", a, b);
    snprintf(out, sizeof out, "%s/st", tmp);
    cli_result r;
    cli_run(&r, "stability", "particle-floor", "--integrator",
            "symplectic-euler", "--from-sweep", both, "--out", out, NULL);
    cr_assert_neq(r.status, 0);
    cr_assert(strstr(r.err, "its columns are not those of"), "%s", r.err);
    cli_result_free(&r);
}
