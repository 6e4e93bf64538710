/* run.json (manifest.h), written by jansson. */
#include "cli/manifest.h"

#include <dirent.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli/outdir.h"
#include "cli/version.h"
#include "core/clock.h"
#include "io/atomic.h"
#include "io/sha256.h"

/* "YYYY-MM-DDTHH:MM:SSZ", now. */
static json_t *utc_now(void)
{
    char buf[32];
    time_t t = time(NULL);
    struct tm tm;
    gmtime_r(&t, &tm);
    strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return json_string(buf);
}

static cl_status write_json(const cl_manifest *mf, cl_error *err)
{
    char path[4200];
    cl_afile af;
    snprintf(path, sizeof path, "%s/run.json", mf->dir);
    cl_status rc = cl_afile_open(&af, path, err);
    if (rc)
        return rc;
    if (json_dumpf(mf->root, af.fp, JSON_INDENT(2)) != 0 ||
        fputc('\n', af.fp) == EOF)
        return cl_afile_fail(&af, err);
    return cl_afile_commit(&af, err);
}

/* The configuration, {"sec": {"key": "value"}}, and the "sec.key" names
 * of those at their defaults. */
typedef struct {
    json_t *config, *defaults;
} resolved;

static void add_entry(void *ctx, const char *sec, const char *key,
                      const char *value, bool given)
{
    resolved *r = ctx;
    json_t *s = json_object_get(r->config, sec);
    if (!s) {
        s = json_object();
        json_object_set_new(r->config, sec, s);
    }
    json_object_set_new(s, key, json_string(value));
    if (!given)
        json_array_append_new(r->defaults, json_sprintf("%s.%s", sec, key));
}

static cl_status problem_json(const char *path, json_t **out, cl_error *err)
{
    char hex[CL_SHA256_HEX], real[PATH_MAX];
    cl_status rc = cl_sha256_file(path, hex, err);
    if (rc)
        return rc;
    *out = json_pack("{s:s, s:s, s:s}", "path", path, "realpath",
                     realpath(path, real) ? real : path, "sha256", hex);
    return CL_OK;
}

/* The input files the problem named (meshes), [{"key", "path",
 * "sha256"}]: a run's outputs depend on their bytes as on the problem
 * file's. */
typedef struct {
    json_t *list;
    cl_error *err;
    cl_status rc;
} input_list;

static void add_input(void *ctx, const char *sec, const char *key,
                      const char *path, bool given)
{
    (void)given;
    input_list *in = ctx;
    char hex[CL_SHA256_HEX];
    if (in->rc || (in->rc = cl_sha256_file(path, hex, in->err)))
        return;
    if (json_array_append_new(in->list, json_pack("{s:s++, s:s, s:s}", "key",
                                                  sec, ".", key, "path", path,
                                                  "sha256", hex)))
        in->rc = cl_error_set(in->err, CL_ENOMEM, "out of memory (run.json)");
}

static json_t *argv_json(int argc, char **argv)
{
    json_t *a = json_array();
    json_array_append_new(a, json_string("clothode"));
    for (int k = 0; k < argc; k++)
        json_array_append_new(a, json_string(argv[k]));
    return a;
}

void cl_manifest_clocks(cl_manifest *mf)
{
    mf->wall0 = cl_clock_wall();
    mf->cpu0 = cl_clock_cpu();
}

cl_status cl_manifest_begin(cl_manifest *mf, const cl_cli_job *job, int argc,
                            char **argv, long threads, cl_error *err)
{
    char cwd[PATH_MAX];
    json_t *problem = NULL;
    resolved r = {json_object(), json_array()};
    mf->dir = job->outdir;
    mf->root = NULL;
    input_list in = {json_array(), err, CL_OK};
    cl_status rc = problem_json(job->problem, &problem, err);
    if (!rc)
        cl_config_input_files(job->cfg, add_input, &in);
    if (rc || (rc = in.rc)) {
        json_decref(problem);
        json_decref(in.list);
        json_decref(r.config);
        json_decref(r.defaults);
        return rc;
    }
    cl_config_resolved(job->cfg, add_entry, &r);
    mf->root = json_pack(
        "{s:s, s:i, s:o, s:s, s:o, s:s, s:o, s:o, s:o, s:o, s:I, s:o, s:o, "
        "s:s, s:[]}",
        "program", "clothode", "schema", 1, "build", cl_cli_build_json(),
        "command", argv[0], "argv", argv_json(argc, argv), "cwd",
        getcwd(cwd, sizeof cwd) ? cwd : "unknown", "problem", problem,
        "inputs", in.list, "config", r.config, "defaults", r.defaults,
        "threads", (json_int_t)threads, "host", cl_cli_host_json(), "start",
        utc_now(), "status", "running", "files");
    if (!mf->root)
        return cl_error_set(err, CL_ENOMEM, "out of memory (run.json)");
    rc = write_json(mf, err);
    if (rc) {
        json_decref(mf->root);
        mf->root = NULL;
    }
    return rc;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The run's files in the directory, sorted, as {"name", "bytes",
 * "sha256"}; run.json itself is not among them. */
static cl_status files_json(const char *dir, json_t *files, cl_error *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return cl_error_set(err, CL_EIO, "cannot read directory '%s'", dir);
    char **names = NULL, path[4200], hex[CL_SHA256_HEX];
    size_t n = 0, cap = 0;
    cl_status rc = CL_OK;
    for (struct dirent *e; !rc && (e = readdir(d));) {
        if (!cl_cli_run_output(e->d_name) || !strcmp(e->d_name, "run.json"))
            continue;
        if (n == cap) {
            cap = cap ? 2 * cap : 64;
            char **grown = realloc(names, cap * sizeof *names);
            if (!grown)
                rc = cl_error_set(err, CL_ENOMEM, "out of memory");
            else
                names = grown;
        }
        if (!rc && !(names[n++] = strdup(e->d_name)))
            rc = cl_error_set(err, CL_ENOMEM, "out of memory");
    }
    closedir(d);
    if (names)
        qsort(names, n, sizeof *names, by_name);
    for (size_t k = 0; k < n; k++) {
        struct stat st;
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        if (!rc && !(rc = cl_sha256_file(path, hex, err)) &&
            stat(path, &st) == 0)
            json_array_append_new(files, json_pack(
                "{s:s, s:I, s:s}", "name", names[k], "bytes",
                (json_int_t)st.st_size, "sha256", hex));
        free(names[k]);
    }
    free(names);
    return rc;
}

static json_t *status_json(cl_status rc, const cl_error *why)
{
    switch (rc) {
    case CL_OK: return json_string("complete");
    case CL_EINTR: return json_string("interrupted");
    case CL_EBUDGET: return json_string("budget");
    default: return json_sprintf("failed: %s", why->msg);
    }
}

cl_status cl_manifest_end(cl_manifest *mf, cl_status rc, const cl_error *why,
                          const cl_stats *st, cl_error *err)
{
    json_t *o = mf->root;
    json_object_set_new(o, "status", status_json(rc, why));
    if (rc)
        json_object_set_new(o, "message", json_string(why->msg));
    json_object_set_new(o, "exit_status",
                        json_integer(cl_cli_exit_status(rc)));
    json_object_set_new(o, "end", utc_now());
    /* the plug-ins the run loaded, known only now */
    json_object_set_new(json_object_get(o, "build"), "plugins",
                        cl_cli_plugins_json());
    json_object_set_new(o, "times", json_pack(
        "{s:f, s:f, s:f, s:f}", "wall", cl_clock_wall() - mf->wall0, "cpu",
        cl_clock_cpu() - mf->cpu0, "integrator_wall", st->wall,
        "integrator_cpu", st->cpu));
    cl_status rc2 = files_json(mf->dir, json_object_get(o, "files"), err);
    if (!rc2)
        rc2 = write_json(mf, err);
    json_decref(o);
    mf->root = NULL;
    return rc2;
}
