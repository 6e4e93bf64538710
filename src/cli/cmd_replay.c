/* clothode replay DIR: rerun the run recorded in DIR/run.json into a
 * temporary directory (or --out) and compare every output it wrote, by
 * SHA-256, with the recorded ones, and those with DIR's files (README
 * "Provenance"). */
#include <errno.h>
#include <limits.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <jansson.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/outdir.h"
#include "io/input.h"
#include "io/jsonfile.h"
#include "io/sha256.h"

typedef struct {
    cl_cli_args a;
} replay_args;

static const cl_cli_opt replay_rows[] = {
    {.name = "out", .arg = "DIR", .type = CL_CLI_STRING,
     .field = offsetof(replay_args, a.out),
     .help = "keep the rerun in DIR (default: a temporary directory, "
             "removed afterwards)"},
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table replay_table = {
    .cmd = "replay", .synopsis = "DIR [--out DIR]", .npos = 1,
    .pos = "DIR", .rows = replay_rows,
    .about =
    "Rerun the run recorded in DIR/run.json (its command line, in its\n"
    "working directory) and report for every file it wrote whether the\n"
    "rerun wrote the same bytes, and whether DIR still holds them; the\n"
    "SHA-256 of the problem file and of the files it names (meshes) and\n"
    "the resolved configuration are compared too, and another build (its\n"
    "commit, compiler, flags, build ID, libraries) is named.  run.json\n"
    "itself is not compared (its times differ); a run that never finished\n"
    "is refused.\n",
    .notes =
    "exit status: 0 when every output is identical, 1 when one differs or\n"
    "is missing or when what the run read (problem, meshes, configuration)\n"
    "differs, else that of the failure (2 bad input, 7 I/O error, ...)\n"};

/* run.json of dir, checked to be a finished clothode run. */
static cl_status load_manifest(const char *dir, json_t **out, cl_error *err)
{
    char path[4200];
    json_error_t je;
    snprintf(path, sizeof path, "%s/run.json", dir);
    const char *why;
    json_t *root = cl_json_read(path, &je, &why);
    if (!root && why)
        return cl_error_set(err, CL_EIO, "%s: cannot read run.json: %s",
                            dir, why);
    if (!root)
        return cl_error_set(err, CL_EPARSE, "%s:%d: not JSON: %s", path,
                            je.line, je.text);
    const char *program = json_string_value(json_object_get(root, "program"));
    const char *cmd = json_string_value(json_object_get(root, "command"));
    json_t *argv = json_object_get(root, "argv"), *a;
    size_t k, strings = 0;
    json_array_foreach(argv, k, a)
        strings += json_is_string(a);
    *out = root;
    if (!program || strcmp(program, "clothode") || !cmd ||
        strcmp(cmd, "run") || !json_is_array(argv) ||
        json_array_size(argv) < 3 || json_array_size(argv) > 240 ||
        strings != json_array_size(argv) ||
        !json_is_string(json_object_get(root, "cwd")) ||
        !json_is_array(json_object_get(root, "files")))
        return cl_error_set(err, CL_EPARSE, "%s: not the run.json of a "
                            "`clothode run` (expected program \"clothode\", "
                            "command \"run\", argv of 3 to 240 strings, cwd "
                            "and files)", path);
    if (!json_is_integer(json_object_get(root, "exit_status")))
        return cl_error_set(err, CL_EINVAL, "%s: the run did not finish "
                            "(status %s, no exit status: killed?): it "
                            "recorded nothing to compare", path,
                            json_string_value(json_object_get(root,
                                                              "status")));
    return CL_OK;
}

/* The files the run recorded, as they are in dir now: one line for each
 * that is gone or was changed since the run (the rerun is compared with
 * the record, so a file edited since would go unnoticed); how many. */
static int check_recorded(const char *dir, json_t *was)
{
    json_t *files = json_object_get(was, "files"), *f;
    int bad = 0;
    size_t k;
    json_array_foreach(files, k, f) {
        const char *name = json_string_value(json_object_get(f, "name"));
        const char *sha = json_string_value(json_object_get(f, "sha256"));
        char path[4300], hex[CL_SHA256_HEX];
        cl_error err;
        snprintf(path, sizeof path, "%s/%s", dir, name ? name : "");
        bool gone = !name || cl_sha256_file(path, hex, &err) != CL_OK;
        if (gone || !sha || strcmp(sha, hex)) {
            printf("%-24s %s\n", name ? name : "?",
                   gone ? "gone from the run's directory"
                        : "changed in the run's directory since the run");
            bad++;
        }
    }
    return bad;
}

/* The entry of the array list whose string `field` is value, or NULL. */
static json_t *entry_with(json_t *list, const char *field, const char *value)
{
    size_t k;
    json_t *e;
    json_array_foreach(list, k, e) {
        const char *v = json_string_value(json_object_get(e, field));
        if (v && !strcmp(v, value))
            return e;
    }
    return NULL;
}

/* The keys of object a whose values differ in b (absent_only: that b
 * lacks) appended to what, ", "-separated, as far as they fit. */
static void keys_differing(json_t *a, json_t *b, bool absent_only,
                           char *what, size_t len)
{
    const char *key;
    json_t *v;
    json_object_foreach(a, key, v) {
        json_t *w = json_object_get(b, key);
        size_t u = strlen(what);
        if ((absent_only ? !w : !json_equal(v, w)) &&
            u + strlen(key) + 3 < len)
            snprintf(what + u, len - u, "%s%s", u ? ", " : "", key);
    }
}

/* The build that reran it (another commit, compiler or flags: outputs
 * may still agree), and the configuration it resolved, which must. */
static int compare_setup(json_t *was, json_t *now)
{
    json_t *ba = json_object_get(was, "build"), *bb = json_object_get(now,
                                                                      "build");
    if (!json_equal(ba, bb)) {
        char what[256] = "";
        keys_differing(bb, ba, false, what, sizeof what);
        keys_differing(ba, bb, true, what, sizeof what);
        printf("%-24s another (differs in: %s; commit %s, was %s; see "
               "run.json's build)\n", "build", what,
               json_string_value(json_object_get(bb, "commit")),
               json_string_value(json_object_get(ba, "commit")));
    }
    if (json_equal(json_object_get(was, "config"),
                   json_object_get(now, "config")))
        return 0;
    printf("%-24s differs (a value or a default resolved otherwise)\n",
           "configuration");
    return 1;
}

/* The entry of list whose "key" equals that of e, or NULL. */
static json_t *same_key(json_t *list, json_t *e)
{
    const char *key = json_string_value(json_object_get(e, "key"));
    return key ? entry_with(list, "key", key) : NULL;
}

static void input_line(json_t *e, const char *verdict)
{
    const char *key = json_string_value(json_object_get(e, "key"));
    const char *path = json_string_value(json_object_get(e, "path"));
    printf("%-24s %s: %s\n", key ? key : "input", path ? path : "?",
           verdict);
}

/* The input files the problem named (meshes): one line for each whose
 * bytes differ from those the run read, that the rerun did not read, or
 * that only the rerun read; their number. */
static int compare_inputs(json_t *was, json_t *now)
{
    json_t *ia = json_object_get(was, "inputs");
    json_t *ib = json_object_get(now, "inputs");
    int bad = 0;
    size_t k;
    json_t *a;
    json_array_foreach(ia, k, a) {
        json_t *b = same_key(ib, a);
        const char *verdict = !b ? "not read by the rerun"
                              : json_equal(json_object_get(a, "sha256"),
                                           json_object_get(b, "sha256"))
                                  ? NULL
                                  : "differs (the file changed since the run)";
        if (verdict) {
            input_line(a, verdict);
            bad++;
        }
    }
    json_array_foreach(ib, k, a)
        if (!same_key(ia, a)) {
            input_line(a, "read by the rerun only");
            bad++;
        }
    return bad;
}

/* Run `clothode run` with the recorded arguments, its --out replaced by
 * outdir, from the recorded working directory; its exit status. */
static int rerun(json_t *m, const char *outdir)
{
    json_t *argv = json_object_get(m, "argv");
    char *args[256], here[PATH_MAX];
    int n = 0;
    for (size_t k = 1; k < json_array_size(argv); k++) {
        /* strings all (load_manifest) */
        char *a = (char *)json_string_value(json_array_get(argv, k));
        /* --out, or the abbreviation of it getopt took (--ou), with its
         * value next or after '=' */
        size_t len = strcspn(a, "=");
        bool out = len >= 3 && len <= 5 && !strncmp(a, "--out", len);
        if (out && !a[len])
            k++;
        else if (!out)
            args[n++] = a;
    }
    args[n++] = "--out";
    args[n++] = (char *)outdir;
    args[n++] = "--quiet";
    args[n] = NULL;
    const char *cwd = json_string_value(json_object_get(m, "cwd"));
    if (!getcwd(here, sizeof here) || chdir(cwd) != 0) {
        fprintf(stderr, "clothode: cannot enter the run's directory '%s': "
                "%s\n", cwd, strerror(errno));
        return CL_EXIT_IO;
    }
    int status = cl_cmd_run(n, args);
    if (chdir(here) != 0) {
        fprintf(stderr, "clothode: cannot return to '%s': %s\n", here,
                strerror(errno));
        return CL_EXIT_IO;
    }
    return status;
}

static const char *sha_of(json_t *files, const char *name)
{
    return json_string_value(
        json_object_get(entry_with(files, "name", name), "sha256"));
}

/* One line per file of either run; the number that differ. */
static int compare(json_t *was, json_t *now)
{
    json_t *fa = json_object_get(was, "files"), *fb = json_object_get(now,
                                                                      "files");
    int bad = 0;
    size_t k;
    json_t *f;
    json_array_foreach(fa, k, f) {
        const char *name = json_string_value(json_object_get(f, "name"));
        const char *a = json_string_value(json_object_get(f, "sha256"));
        const char *b = name ? sha_of(fb, name) : NULL;
        const char *verdict = !b ? "missing in the rerun"
                              : a && !strcmp(a, b) ? "identical" : "differs";
        bad += strcmp(verdict, "identical") != 0;
        printf("%-24s %s\n", name ? name : "?", verdict);
    }
    json_array_foreach(fb, k, f) {
        const char *name = json_string_value(json_object_get(f, "name"));
        if (name && !sha_of(fa, name)) {
            printf("%-24s only in the rerun\n", name);
            bad++;
        }
    }
    return bad;
}

/* The rerun's outputs removed, then its directory. */
static void remove_rerun(const char *dir)
{
    cl_error ignored;
    if (cl_cli_outdir_prepare(dir, &ignored) == CL_OK && rmdir(dir) != 0)
        fprintf(stderr, "clothode: cannot remove '%s': %s\n", dir,
                strerror(errno));
}

/* The rerun into out and its verdict, the exit status. */
static int replay(const char *dir, json_t *was, const char *out)
{
    int status = rerun(was, out);
    cl_error err = {0};
    json_t *now = NULL;
    if (load_manifest(out, &now, &err)) {
        json_decref(now);
        return status ? status : cl_cli_fail(&err);
    }
    json_t *pa = json_object_get(json_object_get(was, "problem"), "sha256");
    json_t *pb = json_object_get(json_object_get(now, "problem"), "sha256");
    printf("replay of %s: %s\n", dir,
           json_string_value(json_object_get(was, "status")));
    if (!json_equal(pa, pb))
        printf("%-24s differs (the problem file changed since the run)\n",
               "problem");
    int bad = compare(was, now) + check_recorded(dir, was);
    int setup = !json_equal(pa, pb) + compare_inputs(was, now) +
                compare_setup(was, now);
    json_t *xa = json_object_get(was, "exit_status");
    json_t *xb = json_object_get(now, "exit_status");
    if (!json_equal(xa, xb)) {
        printf("%-24s %lld, was %lld\n", "exit status",
               (long long)json_integer_value(xb),
               (long long)json_integer_value(xa));
        bad++;
    }
    printf("replay: %zu files, %s\n",
           json_array_size(json_object_get(was, "files")),
           bad ? "outputs differ"
           : setup ? "every output identical, but what the run read differs"
                   : "every output identical");
    json_decref(now);
    return bad || setup ? CL_EXIT_OTHER : CL_EXIT_OK;
}

static int replay_dir(const char *dir, const char *keep)
{
    cl_error err = {0};
    json_t *was = NULL;
    char out[PATH_MAX], here[PATH_MAX];
    const char *tmp = getenv("TMPDIR");
    int status;
    if (keep && !*keep)
        cl_error_set(&err, CL_EINVAL, "--out: the output directory name is "
                     "empty");
    else if (!load_manifest(dir, &was, &err) && keep &&
             cl_same_file(dir, keep))
        cl_error_set(&err, CL_EINVAL, "--out %s: it is the recorded run's "
                     "own directory, which the rerun would replace; choose "
                     "another", keep);
    if (err.code) {
        json_decref(was);
        return cl_cli_fail(&err);
    }
    /* absolute: the rerun runs in the run's own working directory */
    int len = keep && (keep[0] == '/' || !getcwd(here, sizeof here))
                  ? snprintf(out, sizeof out, "%s", keep)
              : keep ? snprintf(out, sizeof out, "%s/%s", here, keep)
                     : snprintf(out, sizeof out, "%s/clothode-replay-XXXXXX",
                                tmp && *tmp == '/' ? tmp : "/tmp");
    if (len < 0 || (size_t)len >= sizeof out || (!keep && !mkdtemp(out))) {
        json_decref(was);
        return cl_cli_fail(&(cl_error){CL_EIO, "cannot create a temporary "
                                               "directory"});
    }
    status = replay(dir, was, out);
    if (!keep)
        remove_rerun(out);
    json_decref(was);
    return status;
}

int cl_cmd_replay(int argc, char **argv)
{
    replay_args a = {0};
    int at = cl_cli_parse(argc, argv, &replay_table, &a);
    int status = at == -2  ? CL_EXIT_OK
                 : at < 0 ? CL_EXIT_INPUT
                          : replay_dir(argv[at], a.a.out);
    cl_cli_sets_free(&a.a.sets);
    return status;
}
