/* The engines of `clothode sweep run` (cli/sweep_engine.h), end to end
 * through the command line: GNU parallel interrupted by SIGINT and
 * resumed; the same plan over ssh (an sshd started on loopback) and on a
 * single-node Slurm (scripts/slurm-local.sh), each giving the table of the
 * local run.  The ssh and Slurm tests say "skipped: REASON" when their
 * servers cannot be started. */
#include <criterion/criterion.h>

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "runcli.h"
#include "timelimit.h"

static char tmp[512];

static void setup(void)
{
    time_limit(600);
    tmp_mkdtemp(tmp, sizeof tmp, "sweepeng");
}

static void stop_servers(void);

static void teardown(void)
{
    stop_servers();
    tmp_rm_rf(tmp);
}

TestSuite(sweep_engine, .init = setup, .fini = teardown);

static const char *in_tmp(char *buf, const char *name)
{
    snprintf(buf, 1024, "%s/%s", tmp, name);
    return buf;
}

/* 2 integrators x 5 steps on hang to T = 0.1 s: jobs of 0.1 to 3 s. */
static const char *const spec =
    "[sweep]\nproblem = problems/hang.ini\n"
    "integrator = symplectic-euler, rk4\n"
    "dt = logspace(-5, -4, 5)\nt_end = 0.1\n";

static void plan(const char *dir, const char *text)
{
    char path[1024];
    tmp_put(in_tmp(path, "s.ini"), text);
    cli_result r;
    cli_run(&r, "sweep", "plan", path, "--out", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
}

/* collect DIR into DIR.csv; its summary line */
static void collect(const char *dir, char *summary, size_t len)
{
    char table[1100];
    snprintf(table, sizeof table, "%s.csv", dir);
    cli_result r;
    cli_run(&r, "sweep", "collect", dir, "--out", table, NULL);
    cli_assert_ok(&r);
    const char *s = strstr(r.out, " complete, ");
    cr_assert_not_null(s, "%s", r.out);
    while (s > r.out && s[-1] != '\n')
        s--;
    snprintf(summary, len, "%.*s", (int)strcspn(s, "\n"), s);
    cli_result_free(&r);
}

static size_t lines_of(const char *path)
{
    static char text[1 << 16];
    tmp_slurp(path, text, sizeof text);
    return cli_count_lines(text);
}

/* The table without its wall and cpu columns (they differ from run to
 * run): every other field is compared. */
static void table_without_times(const char *path, char *out, size_t len)
{
    static char text[1 << 16];
    tmp_slurp(path, text, sizeof text);
    size_t u = 0;
    int wall = -1, col = 0;
    for (const char *p = text; *p && u + 2 < len; p++) {
        if (wall < 0 && !strncmp(p, "wall,cpu,", 9))
            wall = col;
        bool skip = wall >= 0 && (col == wall || col == wall + 1);
        if (*p == ',')
            col++;
        if (*p == '\n')
            col = 0;
        if (!skip || *p == '\n')
            out[u++] = *p;
    }
    out[u] = '\0';
}

static void assert_same_table(const char *a, const char *b)
{
    static char ta[1 << 16], tb[1 << 16];
    table_without_times(a, ta, sizeof ta);
    table_without_times(b, tb, sizeof tb);
    cr_assert_str_eq(ta, tb, "%s and %s differ", a, b);
}

/* Failed jobs (their messages pass through on stderr) do not fail the
 * run: collect reports them. */
static void run_local(const char *dir)
{
    cli_result r;
    cli_run(&r, "sweep", "run", dir, "--jobs", "2", "--quiet", NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 0, "%s: exit status %d\n%s", r.cmd, r.status,
                 r.err);
    cli_result_free(&r);
}

static size_t joblog_entries(const char *dir)
{
    char path[1100], text[8192];
    snprintf(path, sizeof path, "%s/joblog", dir);
    FILE *fp = fopen(path, "r");
    if (!fp)
        return 0;
    fclose(fp);
    tmp_slurp(path, text, sizeof text);
    size_t n = cli_count_lines(text);
    return n ? n - 1 : 0;
}

/* The table's ten rows: distinct ids, every one complete at t = 0.1. */
static void assert_ten_distinct_complete(const char *table)
{
    /* every row a distinct id, every one complete */
    static char text[1 << 16];
    tmp_slurp(table, text, sizeof text);
    char ids[10][16];
    const char *p = strchr(text, '\n') + 1;
    for (int k = 0; k < 10; k++, p = strchr(p, '\n') + 1) {
        snprintf(ids[k], sizeof ids[k], "%.12s", p);
        cr_assert(strstr(p, ",complete,ok,0.1,") < strchr(p, '\n') &&
                      strstr(p, ",complete,ok,0.1,"), "%.200s", p);
        for (int j = 0; j < k; j++)
            cr_assert_str_neq(ids[j], ids[k]);
    }
}

/* `sweep run DIR --resume`: its first line must hold `want`. */
static void run_resume(const char *dir, const char *want)
{
    cli_result r;
    cli_run(&r, "sweep", "run", dir, "--jobs", "2", "--resume", NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, want), "%s", r.out);
    cli_result_free(&r);
}

/* The id of the first job of the sweep in dir (its sweep.json). */
static void first_id(const char *dir, char id[13])
{
    static char sweep_json[1 << 16];
    char path[1100];
    snprintf(path, sizeof path, "%s/sweep.json", dir);
    tmp_slurp(path, sweep_json, sizeof sweep_json);
    const char *at = strstr(sweep_json, "\"id\": \"");
    cr_assert_not_null(at);
    snprintf(id, 13, "%.12s", at + 7);
}

/* Wait (at most a minute) until no process holds DIR/lock: after a
 * SIGINT the jobs GNU parallel was running may still be ending, and they
 * hold the lock they inherited, so that a --resume at once is refused
 * ("is running its jobs"), as it should be. */
static void wait_unlocked(const char *dir)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/lock", dir);
    int fd = open(path, O_RDWR);
    cr_assert_geq(fd, 0, "%s: %s", path, strerror(errno));
    int k = 0;
    while (flock(fd, LOCK_EX | LOCK_NB) != 0 && k++ < 600)
        nanosleep(&(struct timespec){0, 100000000}, NULL);
    cr_assert_lt(k, 600, "%s still locked after a minute", path);
    close(fd);
}

/* Interrupted by SIGINT once two jobs are done, resumed, collected:
 * every job once, none missing.  Then the results survive a plan with the
 * axes reordered, and a status left by another engine gives way to the
 * job's next run. */
Test(sweep_engine, local_interrupted_and_resumed)
{
    char dir[1024], table[1100], summary[256];
    plan(in_tmp(dir, "local"), spec);
    char *argv[] = {(char *)cli_binary(), "sweep", "run", dir, "--jobs", "2",
                    "--quiet", NULL};
    pid_t pid;
    cr_assert_eq(posix_spawnp(&pid, argv[0], NULL, NULL, argv, environ), 0);
    for (int k = 0; k < 6000 && joblog_entries(dir) < 2; k++)
        nanosleep(&(struct timespec){0, 10000000}, NULL);
    kill(pid, SIGINT);
    int ws;
    waitpid(pid, &ws, 0);
    wait_unlocked(dir);
    collect(dir, summary, sizeof summary);
    int done, failed, missing;
    cr_assert_eq(sscanf(summary, "%d complete, %d failed, %d missing", &done,
                        &failed, &missing), 3, "%s", summary);
    cr_assert(done >= 2 && done < 10 && done + failed + missing == 10,
              "after SIGINT: %s", summary);

    char want[64];
    snprintf(want, sizeof want, "resume     %d of 10 jobs", 10 - done);
    run_resume(dir, want);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "10 complete, 0 failed, 0 missing");
    snprintf(table, sizeof table, "%s.csv", dir);
    cr_assert_eq(lines_of(table), 11);
    assert_ten_distinct_complete(table);

    /* planned again with the axes in the other order: other command
     * lines, the same ids, the results kept */
    plan(dir, "[sweep]\nproblem = problems/hang.ini\nt_end = 0.1\n"
              "dt = logspace(-5, -4, 5)\n"
              "integrator = symplectic-euler, rk4\n");
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "10 complete, 0 failed, 0 missing");

    /* a status another engine recorded (a Slurm task killed: 137) is the
     * job's until the job runs again, here by --resume */
    char path[1100], id[13];
    first_id(dir, id);
    snprintf(path, sizeof path, "%s/jobs/%s/exit", dir, id);
    tmp_put(path, "137\n");
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "9 complete, 1 failed, 0 missing");
    run_resume(dir, "resume     1 of 10 jobs");
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "10 complete, 0 failed, 0 missing");
    /* nothing left to run: the counts still (before: nothing printed) */
    run_resume(dir, "resume     0 of 10 jobs failed or have no result\n"
                    "10 complete, 0 failed, 0 missing");
}


/* The field of column `name` in the table's row of job `id`. */
static void table_field(const char *table, const char *id, const char *name,
                        char *out, size_t len)
{
    static char text[1 << 16];
    tmp_slurp(table, text, sizeof text);
    int col = 0;
    for (const char *p = text; strncmp(p, name, strlen(name)) ||
                               (p[strlen(name)] != ',' &&
                                p[strlen(name)] != '\n');
         p++) {
        cr_assert(*p && *p != '\n', "no column %s in %s", name, table);
        col += *p == ',';
    }
    const char *row = strstr(text, id);
    cr_assert_not_null(row, "no row %s in %s", id, table);
    for (int c = 0; c < col; c++)
        row = strchr(row, ',') + 1;
    snprintf(out, len, "%.*s", (int)strcspn(row, ",\n"), row);
}

/* A sweep of `problem` (the rest of its [sweep] section in `rest`)
 * planned into tmp/name, its path into dir, and run. */
static void plan_and_run(char *dir, const char *name, const char *problem,
                         const char *rest)
{
    char text[1400];
    snprintf(text, sizeof text, "[sweep]\nproblem = %s\n%s", problem, rest);
    plan(in_tmp(dir, name), text);
    run_local(dir);
}

/* A run again after the problem changed: a job refused before its first
 * output (a bad value) leaves no earlier run's results behind it.  Before,
 * its row was "failed, input" with the previous run's time reached and
 * statistics, which stability --from-sweep took for a blow-up. */
Test(sweep_engine, a_refused_run_keeps_no_earlier_results)
{
    char dir[1024], prob[1024], table[1100], summary[256], f[64];
    static char text[1 << 16];
    tmp_slurp("problems/hang.ini", text, sizeof text);
    in_tmp(prob, "p.ini");
    tmp_put(prob, text);
    plan_and_run(dir, "refused", prob, "integrator = rk4\ncloth.n = 4\n"
                 "dt = 1e-3, 2e-3\nt_end = 0.02\n");
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "2 complete, 0 failed, 0 missing");
    /* the problem edited after the runs: a study refuses their table */
    char *ks = strstr(text, "ks = 200");
    cr_assert_not_null(ks);
    memcpy(ks, "ks = 300", 8);
    tmp_put(prob, text);
    char out[1100];
    snprintf(table, sizeof table, "%s.csv", dir);
    snprintf(out, sizeof out, "%s-stab", dir);
    cli_result r;
    cli_run(&r, "stability", prob, "--set", "cloth.n=4", "--t-end", "0.02",
            "--integrator", "rk4", "--from-sweep", table, "--out", out,
            NULL);
    cli_assert_error(&r, 0, "read a problem file of other bytes",
                     "the file changed after it ran", NULL);
    cli_result_free(&r);
    memcpy(ks, "ks = abc", 8);
    tmp_put(prob, text);
    run_local(dir);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "0 complete, 2 failed, 0 missing");
    snprintf(table, sizeof table, "%s.csv", dir);
    char id[13];
    first_id(dir, id);
    table_field(table, id, "exit", f, sizeof f);
    cr_assert_str_eq(f, "input");
    table_field(table, id, "t_reached", f, sizeof f);
    cr_assert_str_eq(f, "NA");
    table_field(table, id, "steps", f, sizeof f);
    cr_assert_str_eq(f, "NA");
}

/* A mesh the problem names, edited after every run of a sweep: a study
 * that takes the table refuses it, where it took it before the edit
 * (before: the rows were compared with one another only, and the table
 * stood for today's cloth); edited between two runs: the table's rows
 * record different inputs_sha256, and a study refuses it (before: the
 * problem file's digest alone was compared, and the two cloths' runs
 * were read as one sweep). */
Test(sweep_engine, a_mesh_changed_between_runs)
{
    char dir[1024], prob[1024], table[1100], out[1100], path[1200], id[13],
        summary[256], a[80], b[80];
    in_tmp(prob, "mesh");
    char cmd[2200];
    snprintf(cmd, sizeof cmd, "mkdir -p %s && cp -r problems/skirt.ini "
             "problems/meshes %s", prob, prob);
    cr_assert_eq(system(cmd), 0, "%s", cmd);
    snprintf(path, sizeof path, "%s/skirt.ini", prob);
    plan_and_run(dir, "meshsweep", path, "integrator = symplectic-euler-x\n"
                 "dt = 1e-4, 2e-4\nt_end = 0.002\n");
    first_id(dir, id);
    collect(dir, summary, sizeof summary);
    snprintf(table, sizeof table, "%s.csv", dir);
    snprintf(out, sizeof out, "%s-stab", dir);
    char ini[1200];
    snprintf(ini, sizeof ini, "%s/skirt.ini", prob);
    cli_result r;
    cli_run(&r, "stability", ini, "--t-end", "0.002", "--integrator",
            "symplectic-euler-x", "--from-sweep", table, "--out", out,
            "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/meshes/sphere.obj", prob);
    tmp_write(path, "a", "# edited\n");
    cli_run(&r, "stability", ini, "--t-end", "0.002", "--integrator",
            "symplectic-euler-x", "--from-sweep", table, "--out", out,
            "--quiet", NULL);
    cli_assert_error(&r, 0, "its runs read other files than the problem "
                     "names now",
                     "a mesh or [init] state changed after the sweep ran",
                     NULL);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/jobs/%s/exit", dir, id);
    cr_assert_eq(unlink(path), 0, "%s", path);
    run_resume(dir, "resume     1 of 2 jobs");
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "2 complete, 0 failed, 0 missing");
    snprintf(table, sizeof table, "%s.csv", dir);
    static char text[1 << 16];
    tmp_slurp(table, text, sizeof text);
    const char *second = strchr(strchr(text, '\n') + 1, '\n') + 1;
    snprintf(a, sizeof a, "%.12s", strchr(text, '\n') + 1);
    snprintf(b, sizeof b, "%.12s", second);
    table_field(table, a, "inputs_sha256", a, sizeof a);
    table_field(table, b, "inputs_sha256", b, sizeof b);
    cr_assert(strlen(a) == 64 && strlen(b) == 64 && strcmp(a, b),
              "%s %s", a, b);
    cli_run(&r, "stability", ini, "--t-end", "0.002", "--integrator",
            "symplectic-euler-x", "--from-sweep", table, "--out", out, NULL);
    cli_assert_error(&r, 0, "read different files the problem names",
                     "a mesh or [init] state changed between the sweep's "
                     "runs", NULL);
    cli_result_free(&r);
}

/* More than 100 failed jobs (GNU parallel's exit status 101) are failed
 * jobs like any, not a stopped engine: before, sweep run reported
 * "GNU parallel stopped before the end" and exit 1. */
Test(sweep_engine, over_a_hundred_failed_jobs)
{
    char dir[1024], path[1024], summary[256];
    tmp_put(in_tmp(path, "many.ini"),
            "[sweep]\nproblem = problems/hang.ini\nintegrator = rk4\n"
            "cloth.n = 4\nt_end = 0.01\ndt = 1e-3\n"
            "type1.ks = linspace(-102, -1, 102)\n");
    cli_result r;
    cli_run(&r, "sweep", "plan", path, "--out", in_tmp(dir, "many"),
            "--no-check", "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cli_run(&r, "sweep", "run", dir, "--jobs", "2", NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert(strstr(r.out, "0 complete, 102 failed, 0 missing"), "%s",
              r.out);
    cli_result_free(&r);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "0 complete, 102 failed, 0 missing");
}

/* A sweep of two short jobs planned into DIR (tmp/name) and run: both
 * complete. */
static void two_complete(char *dir, const char *name)
{
    char summary[256];
    plan(in_tmp(dir, name), "[sweep]\nproblem = problems/hang.ini\n"
                            "integrator = rk4\ncloth.n = 4\n"
                            "t_end = 0.01\ndt = 1e-3, 2e-3\n");
    run_local(dir);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "2 complete, 0 failed, 0 missing");
}

/* Two runs of one sweep at once would run the same jobs into the same
 * files: while DIR/lock is held (by another 'sweep run', or by the GNU
 * parallel of a killed one), sweep run is refused and changes nothing. */
Test(sweep_engine, a_running_sweep_is_not_run_twice)
{
    char dir[1024], path[1100], summary[256];
    two_complete(dir, "locked");
    snprintf(path, sizeof path, "%s/lock", dir);
    int fd = open(path, O_RDWR);
    cr_assert_geq(fd, 0, "%s: %s", path, strerror(errno));
    cr_assert_eq(flock(fd, LOCK_EX | LOCK_NB), 0);
    cli_result r;
    cli_run(&r, "sweep", "run", dir, "--resume", NULL);
    cli_assert_error(&r, 0, "another 'sweep run' of this sweep", NULL);
    cli_result_free(&r);
    cli_run(&r, "sweep", "run", dir, NULL);
    cli_assert_error(&r, 0, "is running its jobs", NULL);
    cli_result_free(&r);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "2 complete, 0 failed, 0 missing");
    close(fd);
    run_local(dir);
}

/* r, a sweep run of dir, refused with exit status `status` and `text` on
 * stderr; dir's two jobs still complete. */
static void assert_refused_keeping_two(cli_result *r, const char *dir,
                                       int status, const char *text)
{
    char summary[256];
    cli_assert_no_crash(r);
    cr_assert_eq(r->status, status, "%s", r->err);
    cr_assert(strstr(r->err, text), "%s", r->err);
    cli_result_free(r);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "2 complete, 0 failed, 0 missing");
}

/* A job that cannot record its status (here its exit.tmp is a directory)
 * is missing once the engine has ended, and sweep run says so with exit
 * status 1 (before: exit 0).  Without GNU parallel in PATH, sweep run
 * stops before it touches any job's status (before: every status was
 * removed first, so the complete jobs became missing). */
Test(sweep_engine, missing_statuses_and_no_engine)
{
    char dir[1024], path[1100];
    two_complete(dir, "nostatus");
    char *save = strdup(getenv("PATH"));
    setenv("PATH", "/nonexistent", 1);
    cli_result r;
    cli_run(&r, "sweep", "run", dir, NULL);
    setenv("PATH", save, 1);
    free(save);
    assert_refused_keeping_two(&r, dir, 1, "parallel is not in PATH");
    char id[13];
    first_id(dir, id);
    snprintf(path, sizeof path, "%s/jobs/%s/exit.tmp", dir, id);
    cr_assert_eq(mkdir(path, 0755), 0);
    cli_run(&r, "sweep", "run", dir, "--jobs", "2", NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 1, "%s", r.err);
    cr_assert(strstr(r.out, "1 complete, 0 failed, 1 missing"), "%s", r.out);
    cr_assert(strstr(r.err, "yet 1 job has no status"), "%s", r.err);
    cli_result_free(&r);
}

/* A program `name` in tmp/fakebin that prints `out` on stdout (or, with
 * to_err, stderr) and exits with `status`: Slurm's commands as a test
 * needs them to answer. */
static void fake_script(const char *name, const char *body)
{
    char bin[1024], path[1100], text[2048];
    in_tmp(bin, "fakebin");
    mkdir(bin, 0755);
    snprintf(path, sizeof path, "%s/%s", bin, name);
    /* its arguments into tmp/fakebin/NAME.args */
    snprintf(text, sizeof text, "#!/bin/sh\necho \"$@\" > '%s.args'\n%s",
             path, body);
    tmp_put(path, text);
    cr_assert_eq(chmod(path, 0755), 0);
}

static void fake_program(const char *name, const char *out, bool to_err,
                         int status)
{
    char body[1024];
    snprintf(body, sizeof body, "echo '%s'%s\nexit %d\n", out,
             to_err ? " >&2" : "", status);
    fake_script(name, body);
}

/* `sweep run ARGS...` with tmp/fakebin first in PATH. */
static void run_faked(cli_result *r, const char *dir, const char *engine,
                      bool limits)
{
    char bin[1024], path[8192], *save = strdup(getenv("PATH"));
    snprintf(path, sizeof path, "%s:%s", in_tmp(bin, "fakebin"), save);
    setenv("PATH", path, 1);
    if (engine && limits)
        cli_run(r, "sweep", "run", dir, "--engine", engine, "--time", "5",
                "--mem", "300", NULL);
    else if (engine) /* a pilot run first */
        cli_run(r, "sweep", "run", dir, "--engine", engine, NULL);
    else
        cli_run(r, "sweep", "run", dir, "--quiet", NULL);
    setenv("PATH", save, 1);
    free(save);
    cli_assert_no_crash(r);
}

/* A Slurm submission that sbatch refuses leaves the earlier results
 * standing, the pilot's new one included (before: every status was
 * removed first, and the complete jobs became missing), also when sbatch
 * printed a line that is not a job id; one it queues is recorded
 * (DIR/slurm/job), and while squeue lists that array's tasks no 'sweep
 * run' of the sweep starts (before: a --resume ran the queued jobs a
 * second time into the same files).  An array Slurm has forgotten
 * ("Invalid job id") is over, and so is one squeue lists no task of, even
 * with a warning on stderr; a squeue that cannot answer stops the run. */
Test(sweep_engine, slurm_refused_or_still_queued)
{
    char dir[1024], path[1100], summary[256], text[256];
    two_complete(dir, "fakeslurm");
    fake_program("sbatch", "sbatch: error: Batch job submission failed: "
                 "Requested time limit is invalid", true, 1);
    cli_result r;
    run_faked(&r, dir, "slurm", false);
    cr_assert(strstr(r.out, "pilot      job "), "%s", r.out);
    assert_refused_keeping_two(&r, dir, 1, "Requested time limit is invalid");
    char id[13];
    first_id(dir, id);
    snprintf(path, sizeof path, "%s/jobs/%s/exit.earlier", dir, id);
    cr_assert(!cli_exists(path), "%s left behind", path);
    fake_program("sbatch", "Your project has 1234 core-hours left", false, 1);
    run_faked(&r, dir, "slurm", true);
    cr_assert(strstr(r.out, "Your project has 1234 core-hours left\n") &&
                  !strstr(r.out, "submitted"), "%s", r.out);
    cr_assert_eq(r.status, 1, "%s", r.err);
    cli_result_free(&r);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "2 complete, 0 failed, 0 missing");
    snprintf(path, sizeof path, "%s/slurm/job", dir);
    cr_assert(!cli_exists(path), "%s written", path);

    fake_program("sbatch", "4242;cluster", false, 0);
    fake_program("squeue", "4242_[0-1] PENDING", false, 0);
    run_faked(&r, dir, "slurm", true);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "slurm      submitted array job 4242\n"), "%s",
              r.out);
    cli_result_free(&r);
    tmp_slurp(path, text, sizeof text);
    cr_assert_str_eq(text, "4242;cluster\n");
    collect(dir, summary, sizeof summary); /* queued, not run (fake) */
    cr_assert_str_eq(summary, "0 complete, 0 failed, 2 missing");
    run_faked(&r, dir, NULL, false);
    cli_assert_error(&r, 0, "the Slurm array job 4242;cluster that an "
                     "earlier 'sweep run' submitted still has tasks queued "
                     "or running (squeue: 4242_[0-1] PENDING)", NULL);
    cr_assert_eq(r.status, 2);
    cli_result_free(&r);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "0 complete, 0 failed, 2 missing");

    fake_program("squeue", "slurm_load_jobs error: Unable to contact slurm "
                 "controller", true, 1);
    run_faked(&r, dir, NULL, false);
    cr_assert_eq(r.status, 7, "%s", r.err);
    cr_assert(strstr(r.err, "cannot ask Slurm whether the array job 4242"),
              "%s", r.err);
    cli_result_free(&r);
    fake_program("squeue", "slurm_load_jobs error: Invalid job id "
                 "specified", true, 1);
    run_faked(&r, dir, NULL, false);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cli_result_free(&r);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "2 complete, 0 failed, 0 missing");
    fake_program("squeue", "squeue: error: a warning from the site", true, 0);
    run_faked(&r, dir, NULL, false);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cli_result_free(&r);
    /* squeue is asked about the recorded cluster, in the states of tasks
     * still to run, and a header line is no task */
    fake_program("squeue", "CLUSTER: cluster", false, 0);
    run_faked(&r, dir, NULL, false);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cli_result_free(&r);
    char args[1100];
    in_tmp(args, "fakebin/squeue.args");
    tmp_slurp(args, text, sizeof text);
    cr_assert(strstr(text, "--jobs=4242 --clusters=cluster") &&
                  strstr(text, "--states=PENDING,RUNNING,"), "%s", text);
}

/* sbatch that queues without printing an id: the earlier statuses go
 * (the jobs will run), with a warning; sbatch --wait that ends with a
 * failed task: the counts all the same, exit 1, the message; SIGTERM to
 * sweep run alone while sbatch --wait waits reaches sbatch, and the run
 * ends at once with exit 6, naming the array. */
Test(sweep_engine, slurm_without_id_failed_task_and_stopped)
{
    char dir[1024], summary[256];
    two_complete(dir, "fakeslurm2");
    fake_program("squeue", "", false, 0);
    fake_script("sbatch", "exit 0\n");
    cli_result r;
    run_faked(&r, dir, "slurm", true);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 0, "%s", r.err);
    cr_assert(strstr(r.err, "sbatch printed no job id"), "%s", r.err);
    cli_result_free(&r);
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "0 complete, 0 failed, 2 missing");

    fake_script("sbatch", "echo 901\nexit 1\n");
    char bin[1024], path[8192], *save = strdup(getenv("PATH"));
    snprintf(path, sizeof path, "%s:%s", in_tmp(bin, "fakebin"), save);
    setenv("PATH", path, 1);
    cli_run(&r, "sweep", "run", dir, "--engine", "slurm", "--time", "5",
            "--mem", "300", "--wait", NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 1, "%s", r.err);
    cr_assert(strstr(r.out, "0 complete, 0 failed, 2 missing") &&
                  strstr(r.err, "the array job 901 ended with a task that "
                                "failed or was killed"),
              "%s%s", r.out, r.err);
    cli_result_free(&r);

    fake_script("sbatch", "echo 902\nexec sleep 120\n");
    char *argv[] = {(char *)cli_binary(), "sweep", "run", dir, "--engine",
                    "slurm", "--time", "5", "--mem", "300", "--wait",
                    "--quiet", NULL};
    pid_t pid;
    cr_assert_eq(posix_spawnp(&pid, argv[0], NULL, NULL, argv, environ), 0);
    char job[1100];
    snprintf(job, sizeof job, "%s/slurm/job", dir);
    static char text[256];
    for (int k = 0; k < 2000; k++) {
        if (cli_exists(job)) {
            tmp_slurp(job, text, sizeof text);
            if (!strcmp(text, "902\n"))
                break;
        }
        nanosleep(&(struct timespec){0, 10000000}, NULL);
    }
    kill(pid, SIGTERM);
    int ws = 0, k = 0;
    while (waitpid(pid, &ws, WNOHANG) == 0 && k++ < 3000)
        nanosleep(&(struct timespec){0, 10000000}, NULL);
    if (k > 3000) /* sbatch still waiting: the signal did not reach it */
        kill(pid, SIGKILL);
    setenv("PATH", save, 1);
    free(save);
    cr_assert(k <= 3000, "sweep run still waiting 30 s after SIGTERM");
    cr_assert(WIFEXITED(ws) && WEXITSTATUS(ws) == 6, "status %d", ws);
}

/* sweep collect --out naming one of the sweep's own files (the manifest,
 * the job list) is refused, and the file kept (before: the table replaced
 * sweep.json, and the sweep could not be read again). */
Test(sweep_engine, collect_out_over_the_sweep_s_own_files)
{
    char dir[1024], path[1100], before[4096], after[4096];
    two_complete(dir, "collectout");
    snprintf(path, sizeof path, "%s/sweep.json", dir);
    tmp_slurp(path, before, sizeof before);
    cli_result r;
    cli_run(&r, "sweep", "collect", dir, "--out", path, NULL);
    cli_assert_error(&r, 0, "the sweep's own", "which the table would "
                     "replace", NULL);
    cr_assert_eq(r.status, 2);
    cli_result_free(&r);
    tmp_slurp(path, after, sizeof after);
    cr_assert_str_eq(after, before);
    /* jobs.txt by another spelling of its path: named, left as it was */
    snprintf(path, sizeof path, "%s/jobs.txt", dir);
    tmp_slurp(path, before, sizeof before);
    snprintf(path, sizeof path, "%s/../%s/jobs.txt", dir,
             strrchr(dir, '/') + 1);
    cli_run(&r, "sweep", "collect", dir, "--out", path, NULL);
    cr_assert_eq(r.status, 2, "%s", r.err);
    cli_assert_error(&r, 0, "jobs.txt: the sweep's own", "jobs.txt, which the "
                     "table would replace; write it elsewhere", NULL);
    cli_result_free(&r);
    tmp_slurp(path, after, sizeof after);
    cr_assert_str_eq(after, before);
}

/* The Slurm submission's files are written atomically, onto regular files
 * only: a symbolic link at DIR/slurm/array.sh is refused, naming it, and
 * its target stays as it was (before: fopen wrote the script through the
 * link); the earlier results stand, since nothing was submitted. */
Test(sweep_engine, slurm_files_replace_regular_files_only)
{
    char dir[1024], path[1100], target[1100], summary[256], text[64];
    two_complete(dir, "fakeslurm3");
    fake_program("sbatch", "4343", false, 0);
    snprintf(path, sizeof path, "%s/slurm", dir);
    cr_assert_eq(mkdir(path, 0755), 0);
    in_tmp(target, "not-a-script");
    tmp_put(target, "keep\n");
    snprintf(path, sizeof path, "%s/slurm/array.sh", dir);
    cr_assert_eq(symlink(target, path), 0);
    cli_result r;
    run_faked(&r, dir, "slurm", true);
    cr_assert_eq(r.status, 1, "%s", r.err);
    cr_assert(strstr(r.err, "array.sh") && strstr(r.err, "symbolic link"),
              "%s", r.err);
    cli_result_free(&r);
    tmp_slurp(target, text, sizeof text);
    cr_assert_str_eq(text, "keep\n");
    collect(dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "2 complete, 0 failed, 0 missing");
}

/* The sweep files under problems/sweeps plan from any directory (their
 * problem relative to them); a directory holding another problem's sweep,
 * or a manifest that is not one, is not planned over (its results would
 * stand for the new jobs), while the same sweep plans there again. */
Test(sweep_engine, sweep_files_and_planning_over_a_sweep)
{
    static const char *const files[] = {"hang-dt", "map", "workprecision"};
    char bin[4096], here[4096], spec[4200], dir[1024], path[1100];
    cr_assert_not_null(realpath(cli_binary(), bin));
    cr_assert_not_null(getcwd(here, sizeof here));
    cr_assert_eq(chdir(tmp), 0);
    cli_result r;
    for (int k = 0; k < 3; k++) {
        snprintf(spec, sizeof spec, "%s/problems/sweeps/%s.ini", here,
                 files[k]);
        snprintf(dir, sizeof dir, "%s/files-%s", tmp, files[k]);
        char *argv[] = {bin, "sweep", "plan", spec, "--out", dir,
                        "--no-check", "--quiet", NULL};
        cli_spawn(&r, argv);
        cli_assert_ok(&r);
        cli_result_free(&r);
    }
    cr_assert_eq(chdir(here), 0);
    snprintf(dir, sizeof dir, "%s/files-hang-dt", tmp);
    plan(dir, "[sweep]\nproblem = problems/hang.ini\nintegrator = rk4\n"
              "dt = 1e-3\nt_end = 0.01\n");
    tmp_put(in_tmp(path, "s2.ini"), "[sweep]\nproblem = problems/spring2.ini"
                                    "\nintegrator = rk4\ndt = 1e-3\n"
                                    "t_end = 0.01\n");
    cli_run(&r, "sweep", "plan", path, "--out", dir, NULL);
    cli_assert_error(&r, 0, "holds the sweep of", "hang.ini", NULL);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/sweep.json", dir);
    tmp_put(path, "{ not json");
    cli_run(&r, "sweep", "plan", in_tmp(spec, "s2.ini"), "--out", dir, NULL);
    cli_assert_error(&r, 0, "not a sweep's manifest", NULL);
    cli_result_free(&r);
}

/* ---- ssh ------------------------------------------------------------- */

static int sh(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static int sh(const char *fmt, ...)
{
    char cmd[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    int st = system(cmd);
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

static void skip(const char *what, const char *why)
{
    fprintf(stderr, "sweep_engine::%s: skipped: %s\n", what, why);
    cr_skip_test("skipped: %s", why);
}

/* Why ssh failed: the last line of D/NAME. */
static const char *last_line(const char *d, const char *name)
{
    static char why[600];
    char path[1100], line[512] = "no message";
    snprintf(path, sizeof path, "%s/%s", d, name);
    FILE *fp = fopen(path, "r");
    while (fp && fgets(line, sizeof line, fp))
        ;
    if (fp)
        fclose(fp);
    snprintf(why, sizeof why, "ssh to the test's sshd failed (%s): %.*s", name,
             (int)strcspn(line, "\n"), line);
    return why;
}

/* An sshd of its own on 127.0.0.1:PORT with a generated host key and an
 * authorized key, and a login file naming this machine twice; 0, or why
 * not. */
static const char *start_sshd(const char *d, int port)
{
    if (geteuid() != 0)
        return "not root: cannot start an sshd of its own";
    if (access("/usr/sbin/sshd", X_OK) || sh("command -v ssh-keygen ssh "
                                             ">/dev/null"))
        return "openssh-server or openssh-client is not installed";
    if (sh("mkdir -p /run/sshd && cd %s && ssh-keygen -q -t ed25519 -N '' "
           "-f host && ssh-keygen -q -t ed25519 -N '' -f key && "
           "cp key.pub authorized_keys && chmod 600 authorized_keys", d))
        return "ssh-keygen failed";
    FILE *fp = fopen(strcat(strcpy((char[1100]){0}, d), "/sshd_config"), "w");
    if (!fp)
        return "cannot write sshd_config";
    fprintf(fp, "Port %d\nListenAddress 127.0.0.1\nHostKey %s/host\n"
                "AuthorizedKeysFile %s/authorized_keys\nPidFile none\n"
                "PasswordAuthentication no\nKbdInteractiveAuthentication no\n"
                "PermitRootLogin prohibit-password\nStrictModes no\n"
                "UsePAM no\n", port, d, d);
    fclose(fp);
    /* in the foreground (-D) of a background shell job: daemon() can
     * fail under the test runner */
    if (sh("/usr/sbin/sshd -D -f %s/sshd_config -E %s/sshd.log "
           "</dev/null >/dev/null 2>&1 & echo $! > %s/sshd.pid", d, d, d))
        return "sshd did not start";
    const char *ssh = "ssh -p %d -i %s/key -o StrictHostKeyChecking=no "
                      "-o UserKnownHostsFile=/dev/null -o BatchMode=yes "
                      "-o LogLevel=ERROR";
    char login[1400];
    snprintf(login, sizeof login, ssh, port, d);
    /* up to 30 s: a loaded machine starts sshd slowly */
    for (double t0 = cli_now();
         sh("%s -o ConnectTimeout=10 root@127.0.0.1 true 2>>%s/ssh.log",
            login, d);) {
        if (cli_now() - t0 > 30)
            return last_line(d, "sshd.log");
        nanosleep(&(struct timespec){0, 200000000}, NULL);
    }
    fp = fopen(strcat(strcpy((char[1100]){0}, d), "/logins"), "w");
    if (!fp)
        return "cannot write the login file";
    fprintf(fp, "1/%s root@127.0.0.1\n1/%s root@localhost\n", login, login);
    fclose(fp);
    return NULL;
}

static void stop_sshd(const char *d)
{
    sh("test -f %s/sshd.pid && kill $(cat %s/sshd.pid)", d, d);
}

/* The daemons a test started, also after a failed assertion. */
static void stop_servers(void)
{
    char d[1100];
    stop_sshd(in_tmp(d, "sshd"));
    if (!access(in_tmp(d, "slurm-state/slurm.conf"), F_OK))
        sh("scripts/slurm-local.sh stop %s/slurm-state", tmp);
}

Test(sweep_engine, ssh_gives_the_local_table)
{
    char dir[1024], ssh_dir[1024], local[1100], remote[1100], logins[1100];
    char summary[256];
    in_tmp(dir, "sshd");
    mkdir(dir, 0700);
    /* ports apart from the Slurm test's (30000 .. 31999) */
    const char *why = start_sshd(dir, 40000 + (int)(getpid() % 10000));
    if (why) {
        skip("ssh_gives_the_local_table", why);
        return;
    }
    plan(in_tmp(local, "local"), spec);
    plan(in_tmp(ssh_dir, "ssh"), spec);
    run_local(local);
    snprintf(logins, sizeof logins, "%s/logins", dir);
    cli_result r;
    cli_run(&r, "sweep", "run", ssh_dir, "--engine", "ssh", "--sshloginfile",
            logins, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    collect(local, summary, sizeof summary);
    collect(ssh_dir, summary, sizeof summary);
    cr_assert_str_eq(summary, "10 complete, 0 failed, 0 missing");
    /* both hosts took jobs */
    char log[1100], text[1 << 14];
    snprintf(log, sizeof log, "%s/joblog", ssh_dir);
    tmp_slurp(log, text, sizeof text);
    cr_assert(strstr(text, "root@127.0.0.1\t") && strstr(text,
                                                          "root@localhost\t"),
              "%s", text);
    snprintf(local + strlen(local), 8, ".csv");
    snprintf(remote, sizeof remote, "%s.csv", ssh_dir);
    assert_same_table(local, remote);
}

/* A value `run` would refuse stops the plan, naming the sweep file, the
 * job and the refusal, and leaves no sweep directory. */
Test(sweep_engine, plan_refuses_what_run_would)
{
    char dir[1024], path[1100];
    tmp_put(in_tmp(path, "bad.ini"), "[sweep]\nproblem = problems/hang.ini\n"
            "integrator = rk4\ndt = 1e-4, -1\nt_end = 0.05\n");
    cli_result r;
    cli_run(&r, "sweep", "plan", path, "--out", in_tmp(dir, "bad"), NULL);
    cli_assert_error(&r, 0, "bad.ini: sweep plan: the job integrator=rk4 "
                     "run.dt=-1 run.t_end=0.05 would be refused: --set: [run] "
                     "dt = \"-1\": expected a number in [0, 1e+12]", NULL);
    cli_result_free(&r);
    cr_assert(!cli_exists(dir), "a refused plan left its directory");

    /* a file an axis names by a relative path: each job would look for it
     * where 'sweep run' starts (before: planned, then every job failed) */
    tmp_put(in_tmp(path, "rel.ini"), "[sweep]\nproblem = problems/skirt.ini\n"
            "integrator = rk4\ndt = 1e-4\nt_end = 0.05\n"
            "obstacle.sphere.file = problems/meshes/sphere.obj\n");
    cli_run(&r, "sweep", "plan", path, "--out", in_tmp(dir, "rel"), NULL);
    cli_assert_error(&r, 0, "would be refused", "obstacle.sphere.file = "
                     "problems/meshes/sphere.obj: a relative file name",
                     NULL);
    cli_result_free(&r);

    /* two jobs that are one run: the sweep file and the values named */
    tmp_put(in_tmp(path, "twin.ini"), "[sweep]\nproblem = problems/hang.ini\n"
            "integrator = rk4\ndt = 1e-4, 0.0001\nt_end = 0.05\n");
    cli_run(&r, "sweep", "plan", path, "--out", in_tmp(dir, "twin"), NULL);
    cli_assert_error(&r, 0, "twin.ini: sweep: two jobs are the same run, "
                     "integrator=rk4 run.dt=0.0001", NULL);
    cli_result_free(&r);
    cr_assert(!cli_exists(dir), "a refused plan left its directory");
}

/* ---- Slurm ----------------------------------------------------------- */

Test(sweep_engine, slurm_array_failed_job_and_resume)
{
    char state[1024], conf[1100], local[1100], sl[1024], summary[256];
    in_tmp(state, "slurm-state");
    if (geteuid() != 0) {
        skip("slurm_array_failed_job_and_resume", "not root: cannot start "
             "slurmctld and slurmd");
        return;
    }
    if (sh("SLURM_LOCAL_PORT=%d scripts/slurm-local.sh start %s > %s.log "
           "2>&1", 30000 + (int)(getpid() % 1000) * 2, state, state)) {
        skip("slurm_array_failed_job_and_resume", "scripts/slurm-local.sh "
             "could not start Slurm (see its log)");
        return;
    }
    snprintf(conf, sizeof conf, "%s/slurm.conf", state);
    setenv("SLURM_CONF", conf, 1);
    /* dt = 1e-2 is past both methods' stable steps: its jobs blow up,
     * the others complete */
    const char *failing = "[sweep]\nproblem = problems/hang.ini\n"
                          "integrator = symplectic-euler, rk4\n"
                          "dt = 1e-4, 2e-4, 1e-2\nt_end = 0.05\n";
    plan(in_tmp(local, "local"), failing);
    /* a directory with a space, a quote and a '%' (a file name pattern
     * to Slurm): its tasks' output is still written there */
    plan(in_tmp(sl, "slurm %x 'dir"), failing);
    run_local(local);
    cli_result r;
    cli_run(&r, "sweep", "run", sl, "--engine", "slurm", "--chunk", "2",
            "--throttle", "2", "--wait", NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "pilot      job "), "%s", r.out);
    cli_result_free(&r);
    collect(sl, summary, sizeof summary);
    cr_assert_str_eq(summary, "4 complete, 2 failed, 0 missing");
    char listing[1024];
    cli_run(&r, "sweep", "collect", sl, "--out", in_tmp(listing, "l.csv"),
            NULL);
    cr_assert(strstr(r.out, "run.dt=0.01 run.t_end=0.05 (blow-up): "
                            "clothode: blow-up at t = "), "%s", r.out);
    cli_result_free(&r);
    collect(local, summary, sizeof summary);
    snprintf(local + strlen(local), 8, ".csv");
    char sl_csv[1100];
    snprintf(sl_csv, sizeof sl_csv, "%s.csv", sl);
    assert_same_table(local, sl_csv);

    /* --resume submits the two failed jobs, and only them */
    cli_run(&r, "sweep", "run", sl, "--engine", "slurm", "--resume",
            "--wait", NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "resume     2 of 6 jobs failed or have no "
                            "result\nslurm      2 jobs in 2 array tasks"),
              "%s", r.out);
    cli_result_free(&r);
    char ids[1100], text[1024];
    snprintf(ids, sizeof ids, "%s/slurm/ids-2.txt", sl);
    tmp_slurp(ids, text, sizeof text);
    cr_assert_eq(cli_count_lines(text), 2, "%s", text);
    collect(sl, summary, sizeof summary);
    cr_assert_str_eq(summary, "4 complete, 2 failed, 0 missing");

    /* the limits given: every job again, no pilot (and none for want of
     * the earlier estimate, removed) */
    char estimate[1100];
    snprintf(estimate, sizeof estimate, "%s/slurm/estimate", sl);
    cr_assert_eq(unlink(estimate), 0, "%s", estimate);
    cli_run(&r, "sweep", "run", sl, "--engine", "slurm", "--time", "5",
            "--mem", "300", "--wait", NULL);
    cli_assert_ok(&r);
    cr_assert(!strstr(r.out, "pilot") &&
                  strstr(r.out, "slurm      6 jobs in 6 array tasks of 1, 5 "
                                "min and 300 MB each"), "%s", r.out);
    cli_result_free(&r);
    collect(sl, summary, sizeof summary);
    cr_assert_str_eq(summary, "4 complete, 2 failed, 0 missing");
}
