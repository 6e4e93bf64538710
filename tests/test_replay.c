/* Tests for clothode replay (cli/cmd_replay.c): a finished run replays to
 * identical outputs; a recorded digest that does not match is reported. */
#include "runcli.h"

/* A run into dir, the directory given by `out_option` (--out, or an
 * abbreviation of it, which replay replaces as it does --out). */
static void run_into(const char *dir, const char *out_option)
{
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator",
            "semi-bdf2", "--dt", "1e-2", "--t-end", "0.2", "--frames", "1",
            out_option, dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
}

/* A run into a fresh directory dir (64 bytes), its run.json's path into
 * path (300 bytes) and its text into json (64 KiB), to be edited. */
static void run_and_read(char *dir, char *path, char *json)
{
    tmp_mkdtemp(dir, 64, "replay");
    run_into(dir, "--out");
    snprintf(path, 300, "%s/run.json", dir);
    tmp_slurp(path, json, 1 << 16);
}

Test(replay, finished_run_replays_identically)
{
    char dir[64];
    cli_result r;
    tmp_mkdtemp(dir, sizeof dir, "replay");
    run_into(dir, "--ou");
    cli_run(&r, "replay", dir, NULL);
    cli_assert_ok(&r);
    const char *files[] = {"series.csv", "final.csv", "stats.csv",
                           "config.ini", "frame_00001.vtk",
                           "frame_00001.obj"};
    for (size_t k = 0; k < 6; k++) {
        char want[64];
        snprintf(want, sizeof want, "%-24s identical\n", files[k]);
        cr_assert(strstr(r.out, want), "no \"%s\" in\n%s", want, r.out);
    }
    cr_assert(strstr(r.out, "replay: 8 files, every output identical"),
              "%s", r.out);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}

/* A recorded digest changed: that file differs, exit status 1, and the
 * kept rerun (--out) holds the true outputs. */
Test(replay, changed_digest_is_reported)
{
    char dir[64], keep[64], path[300], json[1 << 16];
    cli_result r;
    tmp_mkdtemp(keep, sizeof keep, "rerun");
    run_and_read(dir, path, json);
    char *at = strstr(json, "\"name\": \"final.csv\"");
    cr_assert_not_null(at);
    at = strstr(at, "\"sha256\": \"") + 11;
    *at = *at == '0' ? '1' : '0';
    tmp_put(path, json);
    cli_run(&r, "replay", dir, "--out", keep, NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 1, "status %d\n%s%s", r.status, r.out, r.err);
    cr_assert(strstr(r.out, "final.csv                differs"), "%s", r.out);
    cr_assert(strstr(r.out, "series.csv               identical"), "%s",
              r.out);
    cr_assert(strstr(r.out, "outputs differ"), "%s", r.out);
    /* the kept rerun's final.csv is the run's own, byte for byte */
    static char kept[1 << 16], orig[1 << 16];
    snprintf(path, sizeof path, "%s/final.csv", keep);
    tmp_slurp(path, kept, sizeof kept);
    snprintf(path, sizeof path, "%s/final.csv", dir);
    tmp_slurp(path, orig, sizeof orig);
    cr_assert_gt(strlen(orig), 100);
    cr_assert_str_eq(kept, orig);
    cli_result_free(&r);
    tmp_rm_rf(dir);
    tmp_rm_rf(keep);
}

/* The record is checked against the directory too: an output edited or
 * removed since the run is reported, though the rerun still matches the
 * record (before: "every output identical"). */
Test(replay, outputs_changed_since_the_run)
{
    char dir[64], path[300];
    cli_result r;
    tmp_mkdtemp(dir, sizeof dir, "replay");
    run_into(dir, "--out");
    snprintf(path, sizeof path, "%s/final.csv", dir);
    FILE *fp = fopen(path, "a");
    cr_assert_not_null(fp);
    fputs("0,0,0,0,0,0,0\n", fp);
    fclose(fp);
    snprintf(path, sizeof path, "%s/frame_00001.vtk", dir);
    cr_assert_eq(unlink(path), 0);
    cli_run(&r, "replay", dir, NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 1, "%s%s", r.out, r.err);
    cr_assert(strstr(r.out, "final.csv                changed in the run's "
                            "directory since the run") &&
                  strstr(r.out, "frame_00001.vtk          gone from the "
                                "run's directory") &&
                  strstr(r.out, "outputs differ"),
              "%s", r.out);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}

/* Another build is named (its outputs may still agree); a configuration
 * resolved otherwise is a difference; a run that never finished (killed:
 * no exit status) has nothing to compare and is refused. */
Test(replay, build_configuration_and_unfinished_runs)
{
    char dir[64], path[300], json[1 << 16];
    cli_result r;
    run_and_read(dir, path, json);
    char *commit = strstr(json, "\"commit\": \"");
    cr_assert_not_null(commit);
    memcpy(commit + 11, "0000000", 7);
    char *n = strstr(json, "\"n\": \"6\"");
    cr_assert_not_null(n);
    n[6] = '7';
    tmp_put(path, json);
    cli_run(&r, "replay", dir, NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 1, "%s%s", r.out, r.err);
    cr_assert(strstr(r.out, "build                    another (differs "
                            "in: commit; commit ") &&
                  strstr(r.out, "configuration            differs"),
              "%s", r.out);
    cli_result_free(&r);
    char *x = strstr(json, "\"exit_status\"");
    cr_assert_not_null(x);
    memcpy(x, "\"exit_statuz\"", 13);
    tmp_put(path, json);
    cli_run(&r, "replay", dir, NULL);
    cli_assert_error(&r, 0, "the run did not finish", NULL);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}

/* A mesh the problem names, edited since the run, is named and is a
 * difference, though every output is the same (before: not seen, the
 * mesh's bytes were not recorded). */
Test(replay, an_input_file_changed_since_the_run)
{
    char dir[64], prob[64], path[300];
    cli_result r;
    tmp_mkdtemp(dir, sizeof dir, "replay");
    tmp_mkdtemp(prob, sizeof prob, "problem");
    char cmd[200];
    snprintf(cmd, sizeof cmd, "cp -r problems/skirt.ini problems/meshes %s",
             prob);
    cr_assert_eq(system(cmd), 0, "%s", cmd);
    snprintf(path, sizeof path, "%s/skirt.ini", prob);
    cli_run(&r, "run", path, "--t-end", "0.001", "--frames", "0", "--out",
            dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/meshes/sphere.obj", prob);
    tmp_write(path, "a", "# edited\n");
    cli_run(&r, "replay", dir, NULL);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 1, "%s%s", r.out, r.err);
    cr_assert(strstr(r.out, "final.csv                identical") &&
                  strstr(r.out, "obstacle.sphere.file     ") &&
                  strstr(r.out, "meshes/sphere.obj: differs (the file "
                                "changed since the run)") &&
                  strstr(r.out, "every output identical, but what the run "
                                "read differs") &&
                  !strstr(r.out, "cloth.mesh"),
              "%s", r.out);
    cli_result_free(&r);
    tmp_rm_rf(dir);
    tmp_rm_rf(prob);
}

Test(replay, directory_without_run_json_is_refused)
{
    char dir[64];
    cli_result r;
    tmp_mkdtemp(dir, sizeof dir, "replay");
    cli_run(&r, "replay", dir, NULL);
    cli_assert_error(&r, 0, "run.json", NULL);
    cr_assert_eq(r.status, 7);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}

/* The rerun into the recorded run's own directory would replace the
 * record it is compared with: refused (by another name too), the record
 * untouched; a run.json whose argv holds a non-string is refused with a
 * message. */
Test(replay, own_directory_and_bad_argv_are_refused)
{
    char dir[64], path[300], other[400], json[1 << 16], after[1 << 16];
    cli_result r;
    tmp_mkdtemp(dir, sizeof dir, "replay");
    run_into(dir, "--out");
    snprintf(path, sizeof path, "%s/run.json", dir);
    tmp_slurp(path, json, sizeof json);
    snprintf(other, sizeof other, "%s/../%s", dir, strrchr(dir, '/') + 1);
    const char *outs[] = {dir, other};
    for (int k = 0; k < 2; k++) {
        cli_run(&r, "replay", dir, "--out", outs[k], NULL);
        cli_assert_error(&r, 0, "own directory", NULL);
        cr_assert_eq(r.status, 2);
        cli_result_free(&r);
    }
    cli_run(&r, "replay", dir, "--out", "", NULL);
    cli_assert_error(&r, 0, "--out: the output directory name is empty",
                     NULL);
    cli_result_free(&r);
    tmp_slurp(path, after, sizeof after);
    cr_assert_str_eq(after, json, "the record changed");
    char *at = strstr(json, "\"argv\": [");
    cr_assert_not_null(at);
    at += strlen("\"argv\": [");
    size_t first = strcspn(at, ","); /* the first entry replaced by 7 */
    memmove(at + 1, at + first, strlen(at + first) + 1);
    at[0] = '7';
    tmp_put(path, json);
    cli_run(&r, "replay", dir, NULL);
    cli_assert_error(&r, 0, "argv of 3 to 240 strings", NULL);
    cli_result_free(&r);
    tmp_rm_rf(dir);
}
