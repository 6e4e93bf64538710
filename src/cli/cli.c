/* Shared pieces of the clothode subcommands. */
#include "cli/cli.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/atomic.h"

int cl_cli_fail(const cl_error *err)
{
    fprintf(stderr, "clothode: %s\n", err->msg[0] ? err->msg
                                                  : cl_status_name(err->code));
    return 1;
}

int cl_cli_usage_error(const char *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "clothode %s: ", cmd);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(see 'clothode %s --help')\n", cmd);
    return 2;
}

const char *cl_cli_problems_dir(void)
{
    static char installed[4096];
    struct stat st;
    const char *dir = getenv("CLOTHODE_PROBLEMS");
    if (dir && *dir)
        return dir;
    if (stat("problems", &st) == 0 && S_ISDIR(st.st_mode))
        return "problems";
    /* an installed clothode: PREFIX/bin/clothode, PREFIX/share/clothode */
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    char *slash = n > 0 ? (exe[n] = '\0', strrchr(exe, '/')) : NULL;
    if (slash) {
        *slash = '\0';
        int k = snprintf(installed, sizeof installed,
                         "%s/../share/clothode/problems", exe);
        if (k > 0 && (size_t)k < sizeof installed &&
            stat(installed, &st) == 0 && S_ISDIR(st.st_mode))
            return installed;
    }
    return "problems";
}

const char *cl_cli_problem_path(const char *arg, char *buf, size_t len)
{
    struct stat st;
    if (strchr(arg, '/') || strstr(arg, ".ini") || stat(arg, &st) == 0)
        return arg;
    snprintf(buf, len, "%s/%s.ini", cl_cli_problems_dir(), arg);
    return buf;
}

int cl_cli_sets_add(cl_cli_sets *s, const char *key, const char *val,
                    const char *label)
{
    size_t len = (key ? strlen(key) : 0) + strlen(val) + 2;
    char *a = malloc(len);
    char **grown = realloc(s->v, (size_t)(s->n + 1) * sizeof *grown);
    if (grown)
        s->v = grown;
    const char **lgrown = realloc(s->label, (size_t)(s->n + 1) *
                                                sizeof *lgrown);
    if (lgrown)
        s->label = lgrown;
    if (!a || !grown || !lgrown) {
        free(a);
        return -1;
    }
    snprintf(a, len, "%s%s%s", key ? key : "", key ? "=" : "", val);
    s->label[s->n] = key ? label : NULL;
    s->v[s->n++] = a;
    return 0;
}

void cl_cli_sets_free(cl_cli_sets *s)
{
    for (int k = 0; k < s->n; k++)
        free(s->v[k]);
    free(s->v);
    free(s->label);
    s->v = NULL;
    s->label = NULL;
    s->n = 0;
}

int cl_cli_parse(int argc, char **argv, const cl_cli_spec *spec,
                 cl_cli_args *a)
{
    int c, rc = 0;
    optind = 1;
    opterr = 0;
    while (rc == 0 &&
           (c = getopt_long(argc, argv, "", spec->opts, NULL)) != -1) {
        if (c == 'h') {
            fputs(spec->help, stdout);
            return -2;
        } else if (c == 'o') {
            a->out = optarg;
        } else if (c == 'q') {
            a->quiet = true;
        } else if (c == 's') {
            rc = cl_cli_sets_add(&a->sets, NULL, optarg, NULL);
        } else if (c > 0 && c < 128 && spec->key[c]) {
            rc = cl_cli_sets_add(&a->sets, spec->key[c], optarg,
                                 spec->label[c]);
        } else {
            cl_cli_usage_error(spec->cmd, "unknown or incomplete option "
                               "'%s'", argv[optind - 1]);
            return -1;
        }
    }
    if (rc)
        return -1;
    if (optind != argc - 1) {
        cl_cli_usage_error(spec->cmd, "expected exactly one PROBLEM, got %d",
                           argc - optind);
        return -1;
    }
    return optind;
}

static int problem_job(const char *problem, const cl_cli_args *a,
                       cl_cli_setup_fn setup, cl_cli_work_fn work, void *ctx)
{
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    char outbuf[4096];
    cl_status rc = cfg ? CL_OK : cl_error_set(&err, CL_ENOMEM, "no memory");
    if (!rc && !(rc = cl_cli_load(cfg, problem, &a->sets, &err)) &&
        !(rc = setup(cfg, ctx, &err)) &&
        !(rc = cl_model_create(cfg, &m, &err)) &&
        !(rc = cl_config_check_unused(cfg, &err))) {
        if (!a->out)
            cl_cli_default_out(problem, outbuf, sizeof outbuf);
        cl_cli_job job = {problem, cfg, a->out ? a->out : outbuf, a->quiet};
        rc = work(m, &job, ctx, &err);
    }
    cl_model_free(m);
    cl_config_free(cfg);
    return rc ? cl_cli_fail(&err) : 0;
}

int cl_cli_problem_main(int argc, char **argv, const cl_cli_spec *spec,
                        cl_cli_setup_fn setup, cl_cli_work_fn work,
                        void *ctx)
{
    cl_cli_args a = {0};
    int at = cl_cli_parse(argc, argv, spec, &a);
    char buf[4096];
    int status = at == -2 ? 0
                 : at < 0 ? 2
                          : problem_job(cl_cli_problem_path(argv[at], buf,
                                                            sizeof buf),
                                        &a, setup, work, ctx);
    cl_cli_sets_free(&a.sets);
    return status;
}

cl_status cl_cli_write_csv(const char *dir, const char *name,
                           cl_cli_rows_fn write, const void *ctx, int n,
                           cl_error *err)
{
    char path[4200];
    cl_afile af;
    cl_status rc = cl_mkdir_p(dir, err);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (rc || (rc = cl_afile_open(&af, path, err)))
        return rc;
    write(af.fp, ctx, n);
    return cl_afile_commit(&af, err);
}

cl_status cl_cli_load(cl_config *cfg, const char *problem,
                      const cl_cli_sets *sets, cl_error *err)
{
    cl_status rc = cl_config_load(cfg, problem, err);
    for (int k = 0; rc == CL_OK && k < sets->n; k++)
        rc = cl_config_set_as(cfg, sets->v[k], sets->label[k], err);
    return rc;
}

void cl_cli_default_out(const char *problem, char *buf, size_t len)
{
    const char *base = strrchr(problem, '/');
    base = base ? base + 1 : problem;
    size_t n = strcspn(base, ".");
    snprintf(buf, len, "out/%.*s", (int)n, base);
}

void cl_cli_progress(void *ctx, double fraction)
{
    (void)ctx;
    if (!isatty(STDERR_FILENO))
        return;
    int width = 40, done = (int)(fraction * width + 0.5);
    fprintf(stderr, "\r[%.*s%*s] %3.0f%%", done,
            "########################################", width - done, "",
            100.0 * fraction);
    if (fraction >= 1.0)
        fputc('\n', stderr);
    fflush(stderr);
}
