/* Tests for cli/outdir: an earlier run's files are cleared, a directory
 * that is not a clothode output is refused with nothing removed; and, end
 * to end, a failed run into a reused directory leaves no file of the
 * earlier run, and a directory another clothode is writing into is
 * refused. */
#include "runcli.h"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include "cli/outdir.h"

static char dir[64];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "outdir");
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

TestSuite(outdir, .init = setup, .fini = teardown);

static void put(const char *name, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    tmp_put(path, text);
}

static int exists(const char *name)
{
    char path[256];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return lstat(path, &st) == 0;
}

Test(outdir, run_output_names)
{
    const char *yes[] = {"series.csv", "final.csv", "last-good.csv",
                         "stats.csv", "config.ini", "run.json",
                         "frame_00000.vtk",
                         "frame_12.obj", "obstacles_00003.obj",
                         "series.csv.tmp.Ab12Cd", NULL};
    const char *no[] = {"stability.csv", "notes.txt", "frame_.vtk",
                        "frame_0001.png", "series.csv.tmp.x", "final.csv~",
                        NULL};
    for (size_t k = 0; yes[k]; k++)
        cr_assert(cl_cli_run_output(yes[k]), "%s", yes[k]);
    for (size_t k = 0; no[k]; k++)
        cr_assert(!cl_cli_run_output(no[k]), "%s", no[k]);
}

Test(outdir, missing_directory_is_created)
{
    char sub[128];
    cl_error err = {0};
    snprintf(sub, sizeof sub, "%s/a/b", dir);
    cr_assert_eq(cl_cli_outdir_prepare(sub, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(tmp_list_dir(sub, NULL, 0), 0);
}

/* An older run without run.json: its files go, a study's table stays. */
Test(outdir, earlier_run_is_cleared_study_tables_stay)
{
    cl_error err = {0};
    put("series.csv", "t\n0\n");
    put("frame_00004.vtk", "x");
    put("final.csv.tmp.AbCdEf", "x");
    put("stability.csv", "integrator\n");
    cr_assert_eq(cl_cli_outdir_prepare(dir, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 1);
    cr_assert(exists("stability.csv"));
}

/* Every table a command writes into its output directory (a study's
 * `.csv = "NAME"`, or a "NAME.csv" given to cl_cli_check_output or
 * cl_cli_write_csv in src/cli) is known as clothode's, so that a study
 * into out/PROBLEM does not make the run's own directory "not a clothode
 * output" (before: damping.csv, budget.csv, limits.csv, contact.csv and
 * others were not known, and `run` after such a study was refused). */
Test(outdir, every_table_of_the_commands_is_clothode_s)
{
    FILE *fp = popen("grep -h -o -E '(\\.csv = |cl_cli_(check_output|"
                     "write_csv)\\([^\"]*)\"[a-z0-9_.-]+\\.csv\"' "
                     "src/cli/*.c | sed -E 's/.*\"([^\"]+)\"/\\1/' | "
                     "sort -u", "r");
    cr_assert_not_null(fp);
    char name[128];
    int n = 0;
    while (fgets(name, sizeof name, fp)) {
        name[strcspn(name, "\n")] = '\0';
        cr_assert(cl_cli_clothode_output(name), "%s is not known", name);
        n++;
    }
    pclose(fp);
    cr_assert_geq(n, 12, "found %d tables in src/cli (run from the "
                  "repository root)", n);
    cr_assert(!cl_cli_clothode_output("thesis.csv"));
}

/* End to end: a study's table in the directory, then a run there: the
 * run is accepted and the table stays. */
Test(outdir, run_after_a_study_in_its_directory)
{
    cli_result r;
    cli_run(&r, "damping", "spring2", "--out", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cli_run(&r, "run", "spring2", "--out", dir, "--frames", "0", "--quiet",
            NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cr_assert(exists("damping.csv") && exists("series.csv"));
}

Test(outdir, foreign_directory_is_refused_untouched)
{
    cl_error err = {0};
    put("series.csv", "t\n0\n");
    put("thesis.tex", "x");
    cr_assert_eq(cl_cli_outdir_prepare(dir, &err), CL_EIO);
    cr_assert(strstr(err.msg, "thesis.tex") && strstr(err.msg, dir),
              "%s", err.msg);
    cr_assert(exists("series.csv") && exists("thesis.tex"));
}

/* run.json of clothode's marks the directory: the files it lists go
 * (whatever their names), the user's notes beside them stay. */
Test(outdir, listed_files_go_with_run_json)
{
    cl_error err = {0};
    put("run.json", "{\"program\": \"clothode\", \"files\": "
                    "[{\"name\": \"extra.dat\"}]}");
    put("extra.dat", "x");
    put("final.csv", "x");
    put("notes.txt", "keep");
    cr_assert_eq(cl_cli_outdir_prepare(dir, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 1);
    cr_assert(exists("notes.txt"));
}

Test(outdir, special_file_under_an_output_name_is_refused)
{
    char path[256];
    cl_error err = {0};
    snprintf(path, sizeof path, "%s/final.csv", dir);
    cr_assert_eq(mkfifo(path, 0600), 0);
    put("series.csv", "t\n");
    cr_assert_eq(cl_cli_outdir_prepare(dir, &err), CL_EIO);
    cr_assert(strstr(err.msg, "FIFO"), "%s", err.msg);
    cr_assert(exists("final.csv") && exists("series.csv"));
}

Test(outdir, file_in_place_of_the_directory_is_refused)
{
    char path[256];
    cl_error err = {0};
    snprintf(path, sizeof path, "%s/f", dir);
    tmp_put(path, "x");
    cr_assert_eq(cl_cli_outdir_prepare(path, &err), CL_EIO);
    cr_assert(strstr(err.msg, "not a directory"), "%s", err.msg);
}

/* End to end: a run with frames, then a run into the same directory that
 * blows up at once: nothing of the first is left (its frames, final.csv
 * and config.ini would otherwise sit beside the new series); then a
 * finished run, which leaves nothing of the failed one. */
Test(outdir, failed_run_into_reused_directory_leaves_nothing_old)
{
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator",
            "symplectic-euler", "--dt", "1e-3", "--t-end", "0.02",
            "--frames", "4", "--out", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cr_assert(exists("frame_00004.vtk") && exists("final.csv"));
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator", "fe",
            "--dt", "0.05", "--frames", "1", "--out", dir, "--quiet", NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 4, "%s: status %d\n%s", r.cmd, r.status, r.err);
    cli_result_free(&r);
    /* every file there is the failed run's: listed in its run.json */
    char names[32][256], path[256], json[65536], want[300];
    size_t n = tmp_list_dir(dir, names, 32);
    snprintf(path, sizeof path, "%s/run.json", dir);
    tmp_slurp(path, json, sizeof json);
    cr_assert(strstr(json, "\"status\": \"failed: blow-up"), "%s", json);
    cr_assert(!exists("frame_00004.vtk") && !exists("final.csv"));
    cr_assert(exists("last-good.csv"));
    cr_assert(n < 32);
    for (size_t k = 0; k < n; k++) {
        snprintf(want, sizeof want, "\"name\": \"%s\"", names[k]);
        cr_assert(!strcmp(names[k], "run.json") || strstr(json, want),
                  "%s is not the failed run's", names[k]);
    }
    /* and a finished run after it leaves no last-good.csv */
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator",
            "symplectic-euler", "--dt", "1e-3", "--t-end", "0.01",
            "--out", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cr_assert(exists("final.csv") && !exists("last-good.csv"));
}

/* A run or a study into a directory a running clothode writes into is
 * refused (exit 7), and the running one ends with its outputs (before:
 * the second run cleared the first's temporaries and frames, the first
 * failed to rename its series (exit 7), and the directory mixed the two
 * runs); once it has ended, the directory is free. */
Test(outdir, a_directory_in_use_is_refused)
{
    char *argv[] = {(char *)cli_binary(), "run", "hang", "--set",
                    "cloth.n=12", "--t-end", "100", "--integrator", "rk4",
                    "--dt", "1e-5", "--max-wall", "60", "--quiet", "--out",
                    dir, NULL};
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, "/dev/null",
                                     O_WRONLY, 0);
    pid_t pid;
    cr_assert_eq(posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ), 0);
    posix_spawn_file_actions_destroy(&fa);
    for (int k = 0; k < 3000 && !exists("run.json"); k++)
        nanosleep(&(struct timespec){0, 10000000}, NULL);
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--t-end", "0.01",
            "--quiet", "--out", dir, NULL);
    cli_assert_error(&r, 0, "is in use by another clothode writing there",
                     NULL);
    cr_assert_eq(r.status, 7);
    cli_result_free(&r);
    cli_run(&r, "stability", "spring2", "--integrator", "rk4", "--t-end",
            "0.1", "--quiet", "--out", dir, NULL);
    cr_assert_eq(r.status, 7, "%s", r.err);
    cli_result_free(&r);
    kill(pid, SIGTERM);
    int ws;
    cr_assert_eq(waitpid(pid, &ws, 0), pid);
    cr_assert(WIFEXITED(ws) && WEXITSTATUS(ws) == 6, "status %d", ws);
    cr_assert(exists("series.csv") && exists("final.csv"));
    cli_run(&r, "run", "hang", "--set", "cloth.n=4", "--t-end", "0.01",
            "--frames", "0", "--quiet", "--out", dir, NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
}
