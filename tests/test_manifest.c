/* Tests for cli/manifest (run.json) end to end: its content, and two
 * identical runs (also with --threads 2) that write identical bytes in
 * every file, run.json's times apart. */
#include "runcli.h"

#include <jansson.h>

#include "io/sha256.h"

static json_t *load_json(const char *dir)
{
    char path[300];
    json_error_t je;
    snprintf(path, sizeof path, "%s/run.json", dir);
    json_t *root = json_load_file(path, 0, &je);
    cr_assert_not_null(root, "%s:%d: %s", path, je.line, je.text);
    return root;
}

static const char *str_at(json_t *o, const char *a, const char *b)
{
    json_t *v = json_object_get(o, a);
    if (b)
        v = json_object_get(v, b);
    cr_assert(json_is_string(v), "run.json: %s%s%s is not a string", a,
              b ? "." : "", b ? b : "");
    return json_string_value(v);
}

static void small_run(const char *dir, const char *threads)
{
    cli_result r;
    cli_run(&r, "run", "hang", "--set", "cloth.n=8", "--t-end", "0.1",
            "--frames", "2", "--threads", threads, "--out", dir, "--quiet",
            NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
}

Test(manifest, run_json_records_the_run)
{
    char dir[64], path[300], hex[CL_SHA256_HEX];
    cl_error err = {0};
    tmp_mkdtemp(dir, sizeof dir, "manifest");
    small_run(dir, "1");
    json_t *m = load_json(dir);
    cr_assert_str_eq(str_at(m, "program", NULL), "clothode");
    cr_assert_str_eq(str_at(m, "status", NULL), "complete");
    cr_assert_eq(json_integer_value(json_object_get(m, "exit_status")), 0);
    cr_assert_str_eq(str_at(m, "command", NULL), "run");
    cr_assert_gt(strlen(str_at(m, "build", "commit")), 0);
    cr_assert(strstr(str_at(m, "build", "flags"), "-std=c11"));
    json_t *libs = json_object_get(json_object_get(m, "build"), "libraries");
    cr_assert(!strncmp(json_string_value(json_object_get(libs, "sundials")),
                       "6.", 2) ||
              !strncmp(json_string_value(json_object_get(libs, "sundials")),
                       "5.", 2));
    cr_assert(strstr(json_string_value(json_object_get(libs, "blas")),
                     "blas"));
    cr_assert_eq(json_integer_value(json_object_get(m, "threads")), 1);
    cr_assert_gt(strlen(str_at(m, "host", "cpu")), 0);
    /* the problem file's digest */
    cr_assert_eq(cl_sha256_file("problems/hang.ini", hex, &err), CL_OK);
    cr_assert_str_eq(str_at(m, "problem", "sha256"), hex);
    /* the configuration: the option given, the defaults made explicit */
    json_t *cfg = json_object_get(m, "config");
    cr_assert_str_eq(str_at(cfg, "cloth", "n"), "8");
    cr_assert_str_eq(str_at(cfg, "run", "t_end"), "0.1");
    cr_assert_str_eq(str_at(cfg, "run", "max_stretch"), "10");
    cr_assert_str_eq(str_at(cfg, "run", "samples"), "200");
    json_t *defaults = json_object_get(m, "defaults");
    size_t k;
    json_t *d;
    int seen = 0;
    json_array_foreach(defaults, k, d) {
        seen += !strcmp(json_string_value(d), "run.samples");
        cr_assert(strcmp(json_string_value(d), "cloth.n"));
    }
    cr_assert_eq(seen, 1);
    /* every file with its digest, run.json not among them */
    json_t *files = json_object_get(m, "files");
    cr_assert_eq(json_array_size(files), 10); /* 6 frames, 4 tables */
    json_array_foreach(files, k, d) {
        const char *name = str_at(d, "name", NULL);
        snprintf(path, sizeof path, "%s/%s", dir, name);
        cr_assert_eq(cl_sha256_file(path, hex, &err), CL_OK, "%s", err.msg);
        cr_assert_str_eq(str_at(d, "sha256", NULL), hex, "%s", name);
    }
    json_t *times = json_object_get(m, "times");
    cr_assert_geq(json_real_value(json_object_get(times, "wall")),
                  json_real_value(json_object_get(times, "integrator_wall")));
    json_decref(m);
    tmp_rm_rf(dir);
}

/* The GNU build ID of the ELF file `file`, as readelf prints it, into
 * line (256 bytes). */
static void readelf_build_id(const char *file, char *line)
{
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "readelf -n '%s' | sed -n 's/.*Build ID: //p'",
             file);
    FILE *fp = popen(cmd, "r");
    cr_assert_not_null(fp);
    cr_assert_not_null(fgets(line, 256, fp), "%s: no build ID", cmd);
    pclose(fp);
    line[strcspn(line, "\n")] = '\0';
    cr_assert_eq(strlen(line), 40, "%s", line);
}

/* The files the problem names (the skirt's cloth and obstacle meshes)
 * with their digests, and the GNU build IDs of the program and of the
 * plug-ins a run loaded, as readelf reads them from the files (before:
 * none was recorded, and a mesh edited after the run, or a binary rebuilt
 * from an edited tree, left no trace). */
Test(manifest, input_files_and_build_id)
{
    char dir[64], hex[CL_SHA256_HEX], line[256];
    cl_error err = {0};
    tmp_mkdtemp(dir, sizeof dir, "manifest");
    cli_result r;
    cli_run(&r, "run", "problems/skirt.ini", "--t-end", "0.001", "--frames",
            "0", "--out", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    json_t *m = load_json(dir);
    json_t *inputs = json_object_get(m, "inputs");
    static const char *const keys[] = {"cloth.mesh", "obstacle.sphere.file"};
    static const char *const files[] = {"problems/meshes/skirt.obj",
                                        "problems/meshes/sphere.obj"};
    cr_assert_eq(json_array_size(inputs), 2);
    for (size_t k = 0; k < 2; k++) {
        json_t *in = json_array_get(inputs, k);
        char *real = realpath(files[k], NULL);
        cr_assert_str_eq(str_at(in, "key", NULL), keys[k]);
        cr_assert_str_eq(str_at(in, "path", NULL), real);
        cr_assert_eq(cl_sha256_file(files[k], hex, &err), CL_OK);
        cr_assert_str_eq(str_at(in, "sha256", NULL), hex);
        free(real);
    }
    readelf_build_id(cli_binary(), line);
    cr_assert_str_eq(str_at(m, "build", "build_id"), line);
    json_decref(m);
    small_run(dir, "1"); /* a grid cloth names no file, loads no plug-in */
    m = load_json(dir);
    cr_assert_eq(json_array_size(json_object_get(m, "inputs")), 0);
    json_t *plugins = json_object_get(json_object_get(m, "build"), "plugins");
    cr_assert(json_is_array(plugins) && json_array_size(plugins) == 0);
    json_decref(m);
    /* an amg run records the PETSc plug-in it loaded */
    cli_run(&r, "run", "hang", "--set", "cloth.n=6", "--integrator",
            "semi-bdf2", "--linsol", "amg", "--dt", "1e-2", "--t-end",
            "0.02", "--frames", "0", "--out", dir, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    m = load_json(dir);
    plugins = json_object_get(json_object_get(m, "build"), "plugins");
    cr_assert_eq(json_array_size(plugins), 1);
    const char *path = str_at(json_array_get(plugins, 0), "path", NULL);
    cr_assert(strstr(path, "/clothode-petsc.so"), "%s", path);
    readelf_build_id(path, line);
    cr_assert_str_eq(str_at(json_array_get(plugins, 0), "build_id", NULL),
                     line);
    json_decref(m);
    tmp_rm_rf(dir);
}

/* Every file of two runs byte for byte, and their run.json without what
 * differs by design: the times and the output directory in argv. */
static void assert_runs_identical(const char *a, const char *b)
{
    json_t *ma = load_json(a), *mb = load_json(b);
    const char *drop[] = {"start", "end", "times", "argv"};
    for (size_t k = 0; k < 4; k++) {
        json_object_del(ma, drop[k]);
        json_object_del(mb, drop[k]);
    }
    cr_assert(json_equal(ma, mb), "run.json of %s and %s differ", a, b);
    size_t k;
    json_t *f;
    json_array_foreach(json_object_get(ma, "files"), k, f) {
        char pa[300], pb[300];
        const char *name = str_at(f, "name", NULL);
        snprintf(pa, sizeof pa, "%s/%s", a, name);
        snprintf(pb, sizeof pb, "%s/%s", b, name);
        FILE *fa = fopen(pa, "rb"), *fb = fopen(pb, "rb");
        cr_assert(fa && fb, "%s", name);
        char *sa = cli_slurp_fp(fa), *sb = cli_slurp_fp(fb);
        cr_assert_str_eq(sa, sb, "%s differs", name);
        free(sa);
        free(sb);
        fclose(fa);
        fclose(fb);
    }
    json_decref(ma);
    json_decref(mb);
}

Test(manifest, identical_runs_write_identical_bytes)
{
    const char *threads[] = {"1", "2"};
    for (size_t t = 0; t < 2; t++) {
        char a[64], b[64];
        tmp_mkdtemp(a, sizeof a, "same");
        tmp_mkdtemp(b, sizeof b, "same");
        small_run(a, threads[t]);
        small_run(b, threads[t]);
        assert_runs_identical(a, b);
        tmp_rm_rf(a);
        tmp_rm_rf(b);
    }
}
