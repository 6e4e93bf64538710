/* The benchmark harness (bench/bench.h, bench/child.h, the program
 * clothode-bench): its options, its CSV, the child-process helpers.  No
 * timing is asserted; short workloads (--quick) run for real. */
#include <criterion/criterion.h>

#include <ctype.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench/bench.h"
#include "bench/child.h"
#include "core/stop.h"
#include "runcli.h"
#include "timelimit.h"

static char tmp[512];

static void setup(void)
{
    time_limit(300);
    tmp_mkdtemp(tmp, sizeof tmp, "bench");
}

static void teardown(void)
{
    tmp_rm_rf(tmp);
}

TestSuite(bench, .init = setup, .fini = teardown);

/* The program: $CLOTHODE_BENCH, else build/clothode-bench. */
static char *bench_program(void)
{
    const char *b = getenv("CLOTHODE_BENCH");
    return (char *)(b && *b ? b : "build/clothode-bench");
}

/* Run clothode-bench with the NULL-terminated arguments. */
static void bench_run(cli_result *r, ...)
{
    char *argv[CLI_MAX_ARGS + 2];
    size_t n = 0;
    argv[n++] = bench_program();
    va_list ap;
    va_start(ap, r);
    for (char *a; (a = va_arg(ap, char *));) {
        cr_assert(n < CLI_MAX_ARGS, "too many arguments");
        argv[n++] = a;
    }
    va_end(ap);
    argv[n] = NULL;
    cli_spawn(r, argv);
}

static const char *in_tmp(char *buf, const char *name)
{
    snprintf(buf, 1024, "%s/%s", tmp, name);
    return buf;
}

Test(bench, help_and_bad_options)
{
    cli_result r;
    bench_run(&r, "--help", NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "usage: clothode-bench"), "%s", r.out);
    cli_result_free(&r);
    bench_run(&r, "--only", "14", NULL);
    cli_assert_error(&r, 1, "--only \"14\": expected workload numbers 1..13 "
                     "separated by commas", NULL);
    cli_result_free(&r);
    bench_run(&r, "--only", "1,x", NULL);
    cli_assert_error(&r, 1, "--only \"1,x\": expected workload numbers", NULL);
    cli_result_free(&r);
    bench_run(&r, "--frobnicate", NULL);
    cli_assert_error(&r, 1, "unknown or incomplete option '--frobnicate'",
                     NULL);
    cli_result_free(&r);
    bench_run(&r, "extra", NULL);
    cli_assert_error(&r, 1, "unexpected argument 'extra'", NULL);
    cli_result_free(&r);
    bench_run(&r, "--peak-memory", "2:klu", NULL);
    cli_assert_error(&r, 1, "--peak-memory \"2:klu\": expected N:LINSOL "
                     "with N >= 3", NULL);
    cli_result_free(&r);
    bench_run(&r, "--peak-memory", "6:no-such-solver", NULL);
    cli_assert_error(&r, 0, "no-such-solver", NULL);
    cli_result_free(&r);
}

/* Workload 6's child mode: one line, a positive peak in KiB. */
Test(bench, peak_memory_child_prints_its_peak)
{
    cli_result r;
    bench_run(&r, "--peak-memory", "6:", NULL);
    cli_assert_ok(&r);
    long kb = -1;
    cr_assert_eq(sscanf(r.out, "peak_kb,%ld\n", &kb), 1, "%s", r.out);
    cr_assert_gt(kb, 0);
    cr_assert_eq(cli_count_lines(r.out), 1, "%s", r.out);
    cli_result_free(&r);
}

/* Process `pid`'s state letter and CPU clock ticks (user + system) from
 * /proc/PID/stat, the fields after the command's closing parenthesis;
 * false if it is gone. */
static bool process_stat(pid_t pid, char *state, unsigned long *ticks)
{
    char path[64], line[1024];
    snprintf(path, sizeof path, "/proc/%d/stat", (int)pid);
    FILE *fp = fopen(path, "r");
    if (!fp)
        return false;
    char *got = fgets(line, sizeof line, fp);
    fclose(fp);
    char *paren = got ? strrchr(line, ')') : NULL;
    unsigned long ut = 0, st = 0;
    if (!paren || sscanf(paren + 1, " %c %*d %*d %*d %*d %*d %*u %*u %*u "
                         "%*u %*u %lu %lu", state, &ut, &st) != 3)
        return false;
    *ticks = ut + st;
    return true;
}

/* Has process `pid` ended: gone, or a zombie its new parent has not
 * reaped? */
static bool process_ended(pid_t pid)
{
    char state;
    unsigned long ticks;
    return !process_stat(pid, &state, &ticks) || state == 'Z' ||
           state == 'X';
}

/* Wait (up to 20 s) until process `pid` has used 0.5 s of CPU. */
static void await_cpu(pid_t pid)
{
    long hz = sysconf(_SC_CLK_TCK);
    char state;
    unsigned long ticks = 0;
    for (int k = 0; k < 200 && process_stat(pid, &state, &ticks) &&
                    (long)ticks < hz / 2;
         k++)
        nanosleep(&(struct timespec){0, 100000000}, NULL);
}

/* Workload 6's child ends when its parent dies.  A process of the test
 * starts `--peak-memory 64:klu` (about 12 s of CPU), hands the child's
 * pid over a pipe and waits; killed outright (SIGKILL) once the child has
 * used 0.5 s of CPU (past its set-up), it leaves its child to end by
 * SIGTERM (PR_SET_PDEATHSIG) within 3 s, where before the child ran to its
 * end. */
Test(bench, peak_memory_child_ends_with_its_parent)
{
    int fd[2];
    cr_assert_eq(pipe(fd), 0);
    pid_t parent = fork();
    cr_assert_geq(parent, 0);
    if (parent == 0) {
        close(fd[0]);
        char *argv[] = {bench_program(), "--peak-memory", "64:klu", NULL};
        cl_child c;
        cl_error err;
        if (cl_child_start(&c, argv, NULL, NULL, &err) ||
            write(fd[1], &c.pid, sizeof c.pid) != sizeof c.pid)
            _exit(1);
        for (;;)
            pause();
    }
    close(fd[1]);
    pid_t child = 0;
    ssize_t got = read(fd[0], &child, sizeof child);
    close(fd[0]);
    if (got == (ssize_t)sizeof child)
        await_cpu(child);
    kill(parent, SIGKILL);
    waitpid(parent, NULL, 0);
    cr_assert_eq(got, (ssize_t)sizeof child, "the parent did not start "
                 "its child");
    bool ended = false;
    for (int k = 0; k < 30 && !(ended = process_ended(child)); k++)
        nanosleep(&(struct timespec){0, 100000000}, NULL);
    if (!ended)
        kill(child, SIGKILL);
    cr_assert(ended, "the child %d ran on after its parent's death",
              (int)child);
}

/* The figure of a CSV row: the number before ",UNIT," (NaN if absent). */
static double row_figure(const char *line, const char *unit)
{
    const char *p = strstr(line, unit);
    if (!p)
        return NAN;
    while (p > line && p[-1] != ',')
        p--;
    return strtod(p, NULL);
}

/* `bench --quick --only W` writing its CSV into tmp/name (created): the
 * table on stdout must hold `unit`; the CSV's lines into L. */
static void quick_workload(const char *w, const char *name, const char *unit,
                           cli_lines *L)
{
    char csv[1024];
    cli_result r;
    bench_run(&r, "--quick", "--only", w, "--out", in_tmp(csv, name),
            NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 0, "%s: status %d\n%s", r.cmd, r.status, r.err);
    cr_assert(strstr(r.out, unit), "table:\n%s", r.out);
    cli_result_free(&r);
    cli_read_lines(csv, L);
}

/* Workload 4 in its quick form: a table on stdout, the CSV with its header
 * and a force row whose figure is a positive time per pair. */
Test(bench, quick_force_workload_writes_its_rows)
{
    cli_lines L;
    quick_workload("4", "sub/bench.csv", "ns/pair", &L);
    cr_assert_str_eq(L.line[0], "workload,case,side_a,side_b,cpu_a,cpu_b,"
                     "wall_a,wall_b,error_a,error_b,ratio,unit,goal,"
                     "target,met,note");
    cr_assert_eq(L.n, 3, "%zu rows", L.n - 1);
    cr_assert(!strncmp(L.line[1], "4,hang n=64,force,,", 19), "%s",
              L.line[1]);
    cr_assert(strstr(L.line[1], ",ns/pair,<=,10,"), "%s", L.line[1]);
    double ns = row_figure(L.line[1], ",ns/pair,");
    cr_assert(ns > 0 && isfinite(ns), "figure %g ns per pair", ns);
    cli_lines_free(&L);
}

/* SIGINT once workload 10 has logged a row (workload 4 finished before):
 * exit status 6 with the message naming workload 10, and the CSV holds
 * workload 4's two rows and none of workload 10, whose cases after the
 * signal failed or were cut short. */
Test(bench, interrupted_keeps_the_finished_workloads)
{
    const char *b = getenv("CLOTHODE_BENCH");
    char csv[1024], errlog[1024];
    char *argv[] = {(char *)(b && *b ? b : "build/clothode-bench"),
                    "--quick", "--only", "4,10", "--out",
                    (char *)in_tmp(csv, "bench.csv"), NULL};
    in_tmp(errlog, "bench.err");
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null",
                                     O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, errlog,
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid;
    cr_assert_eq(posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    static char text[1 << 16];
    bool seen = false;
    for (int k = 0; k < 24000 && !seen; k++) {
        nanosleep(&(struct timespec){0, 10000000}, NULL);
        tmp_slurp(errlog, text, sizeof text);
        seen = strstr(text, "\n[10] ") != NULL;
    }
    cr_assert_eq(kill(pid, seen ? SIGINT : SIGKILL), 0);
    int ws = 0;
    pid_t got = 0;
    for (int k = 0; k < 6000 && !got; k++) {
        nanosleep(&(struct timespec){0, 10000000}, NULL);
        got = waitpid(pid, &ws, WNOHANG);
    }
    if (!got) {
        kill(pid, SIGKILL);
        waitpid(pid, &ws, 0);
    }
    tmp_slurp(errlog, text, sizeof text);
    cr_assert(seen, "workload 10 logged no row:\n%s", text);
    cr_assert(got == pid, "not ended 60 s after SIGINT:\n%s", text);
    cr_assert(WIFEXITED(ws) && WEXITSTATUS(ws) == 6, "status %d\n%s", ws,
              text);
    cr_assert(strstr(text, "interrupted by SIGINT in workload 10"), "%s",
              text);
    cli_lines L;
    cli_read_lines(csv, &L);
    cr_assert_eq(L.n, 3, "%zu rows", L.n - 1);
    cr_assert(!strncmp(L.line[1], "4,", 2) && !strncmp(L.line[2], "4,", 2),
              "%s\n%s", L.line[1], L.line[2]);
    cli_lines_free(&L);
}

/* Workload 7 in its quick form: the band row with its goal, the cube row
 * without, positive speed-ups, the tree's distances those of brute
 * force. */
Test(bench, quick_mesh_workload_writes_its_rows)
{
    cli_lines L;
    quick_workload("7", "mesh.csv", "every triangle", &L);
    cr_assert_eq(L.n, 3, "%zu rows", L.n - 1);
    static const char band[] = "7,band 0.9..1.1 R,bvh nearest triangle,"
                               "every triangle,";
    cr_assert(!strncmp(L.line[1], band, sizeof band - 1), "%s", L.line[1]);
    cr_assert(strstr(L.line[1], ",x,>=,50,"), "%s", L.line[1]);
    cr_assert(!strncmp(L.line[2], "7,cube 1.5 R,", 13), "%s", L.line[2]);
    cr_assert(strstr(L.line[2], ",x,,,,"), "%s", L.line[2]);
    for (size_t k = 1; k < 3; k++) {
        double x = row_figure(L.line[k], ",x,");
        cr_assert(x > 0 && isfinite(x), "figure %g", x);
        cr_assert(strstr(L.line[k], "; 0 of "), "%s", L.line[k]);
    }
    cli_lines_free(&L);
}

/* The number after `key` in a line (NaN if absent). */
static double number_after(const char *line, const char *key)
{
    const char *p = strstr(line, key);
    return p ? strtod(p + strlen(key), NULL) : NAN;
}

/* Workload 8 in its quick form: one row per state of the skirt, the share
 * a percentage strictly between 0 and 100 with its goal, and particles in
 * contact at both states. */
Test(bench, quick_contact_workload_writes_its_rows)
{
    cli_lines L;
    quick_workload("8", "contact.csv", "<= 25 %", &L);
    cr_assert_eq(L.n, 3, "%zu rows", L.n - 1);
    static const char *const kase[] = {"8,skirt t=0.5 s (sphere),",
                                       "8,skirt t=3 s (floor),"};
    for (size_t k = 1; k < 3; k++) {
        const char *line = L.line[k];
        cr_assert(!strncmp(line, kase[k - 1], strlen(kase[k - 1])), "%s",
                  line);
        cr_assert(strstr(line, ",contact term + hook,a step,"), "%s",
                  line);
        cr_assert(strstr(line, ",%,<=,25,"), "%s", line);
        double share = row_figure(line, ",%,");
        cr_assert(share > 0 && share < 100, "share %g %% (%s)", share, line);
        double in = number_after(line, " particles, ");
        cr_assert(strstr(line, " force calls replayed "), "%s", line);
        cr_assert(in > 0 && isfinite(in), "no particle in contact: %s", line);
    }
    cli_lines_free(&L);
}

/* Field k (from 0) of a CSV row as a number: the fields before the note
 * hold no comma (NaN if empty or absent). */
static double csv_number(const char *line, int k)
{
    for (; k > 0 && line; k--) {
        line = strchr(line, ',');
        line = line ? line + 1 : NULL;
    }
    return line && *line && *line != ',' ? strtod(line, NULL) : NAN;
}

/* The first row of a CSV that begins with `prefix` and holds `part`
 * (NULL: any), or NULL. */
static const char *row_with(const cli_lines *L, const char *prefix,
                            const char *part)
{
    for (size_t k = 1; k < L->n; k++)
        if (!strncmp(L->line[k], prefix, strlen(prefix)) &&
            (!part || strstr(L->line[k], part)))
            return L->line[k];
    return NULL;
}

/* Every "TOL:ERR" after "looser (lin_tol:m): " in a note: each rung tried
 * before the one taken left an error above the accuracy (printed to three
 * digits, hence the 0.5 % allowance). */
static void assert_looser_above(const char *line, double accuracy)
{
    static const char key[] = "looser (lin_tol:m): ";
    const char *p = strstr(line, key);
    for (p = p ? p + sizeof key - 1 : NULL; p && *p && *p != '"';) {
        const char *colon = strchr(p, ':');
        cr_assert(colon, "no TOL:ERR entry at '%s'", p);
        double e = strtod(colon + 1, NULL);
        cr_assert(e > accuracy * (1 - 5e-3), "a looser rung within %g m: "
                  "%s", accuracy, line);
        p = strstr(colon, ", ");
        p = p ? p + 2 : NULL;
    }
}

/* Workload 10 at `dt`, n = 32: the rows of amg and of the one-level
 * solver the speed-up row names say they ran in 3 alternated rounds, their
 * times lie within the rounds' range (the slowest printed to three
 * digits), and the speed-up row is built from those two rows' times. */
static void assert_rounds(const cli_lines *L, const char *dt)
{
    char prefix[96], one[32] = "";
    snprintf(prefix, sizeof prefix, "10,dt=%s n=32,semi-bdf2 amg,semi-bdf2 ",
             dt);
    const char *ratio = row_with(L, prefix, ",x,>=,");
    cr_assert(ratio, "no speed-up row at dt = %s", dt);
    cr_assert_eq(sscanf(ratio + strlen(prefix), "%31[^,]", one), 1);
    const char *const name[2] = {"amg", one};
    static const char key[] = "fastest of 3 alternated rounds (slowest ";
    for (int q = 0; q < 2; q++) {
        snprintf(prefix, sizeof prefix, "10,dt=%s n=32,semi-bdf2 %s,,", dt,
                 name[q]);
        const char *line = row_with(L, prefix, NULL);
        cr_assert(line, "no row %s", prefix);
        const char *at = strstr(line, key);
        cr_assert(at, "no rounds in %s", line);
        double cpu = csv_number(line, 4);
        double slowest = strtod(at + sizeof key - 1, NULL);
        cr_assert(cpu > 0 && cpu <= slowest * (1 + 5e-3), "%s", line);
        cr_assert_float_eq(csv_number(ratio, 4 + q), cpu, 1e-9 * cpu,
                           "%s against %s", ratio, line);
    }
    double cpu_a = csv_number(ratio, 4), cpu_b = csv_number(ratio, 5);
    cr_assert_float_eq(csv_number(ratio, 10), cpu_b / cpu_a,
                       1e-4 * cpu_b / cpu_a, "%s", ratio);
}

/* A number of a row's note: the one before `unit` ("unknowns",
 * "iterations per solve"). */
static double note_number(const char *line, const char *unit)
{
    const char *at = line ? strstr(line, unit) : NULL;
    cr_assert(at && at > line, "no %s in %s", unit, line);
    while (at > line && at[-1] == ' ')
        at--;
    while (at > line && (isdigit((unsigned char)at[-1]) || at[-1] == '.'))
        at--;
    return strtod(at, NULL);
}

/* The fixed-dt fit row of pcg and amg at dt = 1e-2 gives the exponent of
 * their CG iterations a solve, the slope between the two sizes' rows
 * (iterations printed to a tenth). */
static void assert_iteration_exponents(const cli_lines *L)
{
    static const char *const solver[] = {"pcg", "amg"};
    for (int j = 0; j < 2; j++) {
        char prefix[96];
        double u[2], it[2];
        for (int i = 0; i < 2; i++) {
            snprintf(prefix, sizeof prefix, "10,dt=0.01 n=%d,semi-bdf2 %s,,",
                     16 << i, solver[j]);
            const char *line = row_with(L, prefix, NULL);
            u[i] = note_number(line, " unknowns");
            it[i] = note_number(line, " iterations per solve");
        }
        snprintf(prefix, sizeof prefix, "10,dt=0.01 fit,semi-bdf2 %s,",
                 solver[j]);
        const char *fit = row_with(L, prefix, NULL);
        static const char key[] = "CG iterations a solve ~ unknowns^";
        const char *at = fit ? strstr(fit, key) : NULL;
        cr_assert(at, "no iteration exponent in %s", fit);
        double q = log(it[1] / it[0]) / log(u[1] / u[0]);
        double dq = (0.05 / it[0] + 0.05 / it[1]) / log(u[1] / u[0]);
        cr_assert(fabs(strtod(at + sizeof key - 1, NULL) - q) <= dq + 1e-3,
                  "%s: %g iterations at %g unknowns, %g at %g", fit, it[0],
                  u[0], it[1], u[1]);
    }
    const char *direct = row_with(L, "10,dt=0.01 fit,semi-bdf2 cholmod,",
                                  NULL);
    cr_assert(direct && !strstr(direct, "iterations"), "%s", direct);
}

/* Workload 10's rows, quick form (n = 16, 32).  At lin_tol 1e-10: the
 * speed-ups at dt = 1e-3 and 1e-2 from alternated rounds (assert_rounds),
 * and pcg's and amg's exponents of their iterations.
 * At one accuracy: the step error of semi-bdf2 at dt = 1e-2 (its distance
 * from dt/2 at t = 0.12 s, about 1.4e-3 m at n = 32); pcg and amg each at
 * a lin_tol of the ladder whose error is within 1 % of it, every looser
 * rung above; the speed-up row their time ratio, with its goal; amg's
 * exponent a number. */
Test(bench, quick_amg_rows_follow_their_rules)
{
    cli_lines L;
    quick_workload("10", "amg.csv", "accuracy", &L);
    assert_rounds(&L, "0.001");
    assert_rounds(&L, "0.01");
    assert_iteration_exponents(&L);
    const char *step = row_with(&L, "10,dt=0.01 n=32 accuracy,semi-bdf2 amg "
                                "dt=0.005 lin_tol=1e-10,", NULL);
    cr_assert(step, "no step-error row");
    double step_err = csv_number(step, 8), accuracy = 1e-2 * step_err;
    cr_assert(step_err > 1.2e-3 && step_err < 1.6e-3, "step error %g m",
              step_err);
    static const char *const solver[] = {"pcg", "amg"};
    for (int j = 0; j < 2; j++) {
        char prefix[96];
        snprintf(prefix, sizeof prefix, "10,dt=0.01 n=32 accuracy,"
                 "semi-bdf2 %s lin_tol=", solver[j]);
        const char *line = row_with(&L, prefix, NULL);
        cr_assert(line, "no %s row", solver[j]);
        double tol = strtod(line + strlen(prefix), NULL);
        double rung = tol / pow(10.0, floor(log10(tol) + 1e-9));
        cr_assert(fabs(rung - 1.0) < 1e-9 || fabs(rung - 3.0) < 1e-9,
                  "lin_tol %g not on the ladder", tol);
        double err = csv_number(line, 8);
        cr_assert(err >= 0.0 && err <= accuracy, "%s: error %g m, accuracy "
                  "%g m", solver[j], err, accuracy);
        assert_looser_above(line, accuracy);
        cr_assert(csv_number(line, 4) > 0.0, "%s", line);
    }
    const char *ratio = row_with(&L, "10,dt=0.01 n=32 accuracy,semi-bdf2 "
                                 "amg lin_tol=", ",x,>=,3,");
    cr_assert(ratio, "no speed-up row");
    double cpu_a = csv_number(ratio, 4), cpu_b = csv_number(ratio, 5);
    cr_assert_float_eq(csv_number(ratio, 10), cpu_b / cpu_a,
                       1e-4 * cpu_b / cpu_a, "%s", ratio);
    const char *fit = row_with(&L, "10,dt=0.01 accuracy fit,semi-bdf2 amg,",
                               NULL);
    cr_assert(fit && strstr(fit, ",exponent,"), "no exponent of amg");
    cr_assert(isfinite(csv_number(fit, 10)), "%s", fit);
    cli_lines_free(&L);
}

Test(bench, csv_quotes_text_and_leaves_missing_figures_empty)
{
    cl_bench_row row = {.workload = 2, .met = 0, .ratio = 3.5,
                        .cpu_a = 1.25, .cpu_b = NAN, .wall_a = NAN,
                        .wall_b = NAN, .error_a = NAN, .error_b = NAN,
                        .target = 20};
    strcpy(row.kase, "hang n=32");
    strcpy(row.side_a, "a, b");
    strcpy(row.unit, "x");
    strcpy(row.goal, ">=");
    strcpy(row.note, "said \"so\"");
    cl_bench_table t = {&row, 1, 1};
    char path[1024];
    cl_error err = {0};
    cr_assert_eq(cl_bench_write_csv(in_tmp(path, "t.csv"), &t, &err), CL_OK,
                 "%s", err.msg);
    cli_lines L;
    cli_read_lines(path, &L);
    cr_assert_eq(L.n, 2);
    cr_assert_str_eq(L.line[1], "2,hang n=32,\"a, b\",,1.25,,,,,,3.5,x,>=,"
                                "20,no,\"said \"\"so\"\"\"");
    cli_lines_free(&L);
}

Test(bench, child_status_usage_and_output)
{
    char out[1024];
    cl_child_usage u;
    cl_error err = {0};
    char *yes[] = {"sh", "-c", "echo hello; exit 0", NULL};
    cr_assert_eq(cl_child_run(yes, in_tmp(out, "o.txt"), NULL, &u, &err),
                 CL_OK, "%s", err.msg);
    cr_assert(u.exited && u.status == 0 && u.maxrss_kb > 0);
    cr_assert(u.cpu >= 0 && u.wall >= 0);
    char text[64];
    tmp_slurp(out, text, sizeof text);
    cr_assert_str_eq(text, "hello\n");
    char *no[] = {"sh", "-c", "exit 3", NULL};
    cr_assert_eq(cl_child_run(no, NULL, NULL, &u, &err), CL_EIO);
    cr_assert_eq(u.status, 3);
    cr_assert(strstr(err.msg, "status 3"), "%s", err.msg);
    char *missing[] = {"clothode-no-such-program", NULL};
    cr_assert_eq(cl_child_run(missing, NULL, NULL, &u, &err), CL_EIO);
    cr_assert(strstr(err.msg, "clothode-no-such-program"), "%s", err.msg);
}

/* A stop asked of the waiting process reaches its child.  The test installs
 * the stop handler (core/stop.h), starts `sleep 5` and a second process
 * that sends the test SIGTERM after 0.1 s: the wait passes SIGTERM on, so
 * the sleep ends by that signal, not by its own exit after 5 s. */
Test(bench, child_wait_passes_a_stop_on)
{
    cl_stop_install();
    cl_child c;
    cl_child_usage u;
    cl_error err = {0};
    char *sleeper[] = {"sleep", "5", NULL};
    cr_assert_eq(cl_child_start(&c, sleeper, NULL, NULL, &err), CL_OK, "%s",
                 err.msg);
    pid_t test = getpid(), stopper = fork();
    cr_assert_geq(stopper, 0);
    if (stopper == 0) {
        nanosleep(&(struct timespec){0, 100000000}, NULL);
        kill(test, SIGTERM);
        _exit(0);
    }
    cl_child_wait(&c, &u);
    waitpid(stopper, NULL, 0);
    cr_assert(cl_stop_interrupted(), "the test's SIGTERM did not arrive");
    cr_assert(!u.exited && u.signal == SIGTERM, "exited %d (status %d), "
              "signal %d", u.exited, u.status, u.signal);
}

/* A child that blocks reading a FIFO until the test writes to it: polled
 * before, it cannot have ended; it then exits with the status it read.
 * The test alone holds the FIFO open for reading and writing (Linux: never
 * blocks; close-on-exec, so the child does not inherit it): the child's
 * open returns at once and, should the test die, the child reads
 * end-of-file and ends too. */
Test(bench, child_poll_then_wait)
{
    cl_child c;
    cl_child_usage u;
    cl_error err = {0};
    char fifo[1024];
    cr_assert_eq(mkfifo(in_tmp(fifo, "gate"), 0600), 0, "mkfifo %s", fifo);
    int fd = open(fifo, O_RDWR | O_CLOEXEC);
    cr_assert_geq(fd, 0, "open %s", fifo);
    char *gated[] = {"sh", "-c", "read s < \"$0\"; exit \"$s\"", fifo,
                     NULL};
    cr_assert_eq(cl_child_start(&c, gated, NULL, NULL, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_not(cl_child_done(&c, &u), "a child waiting for its FIFO "
                  "ended");
    cr_assert_eq(write(fd, "7\n", 2), 2);
    cl_child_wait(&c, &u);
    close(fd);
    cr_assert(u.exited && u.status == 7, "exited %d, status %d", u.exited,
              u.status);
    cr_assert_eq(c.pid, 0);
    cr_assert_not(cl_child_done(&c, &u), "a reaped child polled again");
}
