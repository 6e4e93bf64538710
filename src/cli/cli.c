/* Shared pieces of the clothode subcommands. */
#include "cli/cli.h"

#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/outdir.h"
#include "core/meminfo.h"
#include "io/atomic.h"

int cl_cli_exit_status(cl_status code)
{
    switch (code) {
    case CL_OK: return CL_EXIT_OK;
    case CL_EINVAL:
    case CL_EPARSE:
    case CL_EUNSUPPORTED: return CL_EXIT_INPUT;
    case CL_ESOLVER:
    case CL_EINFEASIBLE: return CL_EXIT_SOLVER;
    case CL_EBLOWUP: return CL_EXIT_BLOWUP;
    case CL_EBUDGET: return CL_EXIT_BUDGET;
    case CL_EINTR: return CL_EXIT_INTERRUPTED;
    case CL_EIO: return CL_EXIT_IO;
    case CL_ENOMEM: break;
    }
    return CL_EXIT_OTHER;
}

int cl_cli_fail(const cl_error *err)
{
    fprintf(stderr, "clothode: %s\n", err->msg[0] ? err->msg
                                                  : cl_status_name(err->code));
    return cl_cli_exit_status(err->code);
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

cl_status cl_cli_model_create(cl_config *cfg, cl_model **m, cl_error *err)
{
    cl_mem_cap cap;
    cl_mem_cap_data(&cap);
    cl_status rc = cl_model_create(cfg, m, err);
    cl_mem_cap_release(&cap);
    if (rc == CL_ENOMEM && cap.limit) {
        cl_error inner = *err;
        cl_error_set(err, CL_ENOMEM, "%s: the model does not fit in the "
                     "%.3g GB available (%s); choose a smaller cloth",
                     inner.msg, cap.available / 1e9, cap.limit);
    }
    return rc;
}

cl_status cl_cli_problem_ready(cl_config *cfg, const cl_cli_table *t,
                               void *settings, cl_cli_check_fn check,
                               cl_model **m, cl_error *err)
{
    cl_status rc = cl_cli_read(cfg, t, settings, err);
    if (!rc && check)
        rc = check(cfg, settings, err);
    if (!rc)
        rc = cl_cli_model_create(cfg, m, err);
    return rc ? rc : cl_config_check_unused(cfg, err);
}

static int problem_job(const char *problem, const cl_cli_table *t,
                       void *settings, cl_cli_check_fn check,
                       cl_cli_work_fn work)
{
    const cl_cli_args *a = settings;
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    char outbuf[4096];
    cl_status rc = cfg ? CL_OK : cl_error_set(&err, CL_ENOMEM, "no memory");
    if (!rc && !(rc = cl_cli_load(cfg, problem, &a->sets, &err)) &&
        !(rc = cl_cli_problem_ready(cfg, t, settings, check, &m, &err))) {
        if (!a->out)
            cl_cli_default_out(problem, outbuf, sizeof outbuf);
        cl_cli_job job = {problem, cfg, a->out ? a->out : outbuf, a->quiet};
        rc = work(m, &job, settings, &err);
    }
    cl_model_free(m);
    cl_config_free(cfg);
    return rc ? cl_cli_fail(&err) : 0;
}

int cl_cli_problem_main(int argc, char **argv, const cl_cli_table *t,
                        void *settings, cl_cli_check_fn check,
                        cl_cli_work_fn work)
{
    int at = cl_cli_parse(argc, argv, t, settings);
    char buf[4096];
    int status = at == -2 ? 0
                 : at < 0 ? 2
                          : problem_job(cl_cli_problem_path(argv[at], buf,
                                                            sizeof buf),
                                        t, settings, check, work);
    cl_cli_sets_free(&((cl_cli_args *)settings)->sets);
    return status;
}

int cl_cli_args_main(int argc, char **argv, const cl_cli_table *t,
                     void *settings, int (*work)(void *settings))
{
    cl_cli_args *a = settings;
    int at = cl_cli_parse(argc, argv, t, settings), status = 2;
    cl_error err = {0};
    cl_config *cfg = at >= 0 ? cl_config_alloc() : NULL;
    a->arg = at >= 0 && at < argc ? argv[at] : NULL;
    if (at == -2)
        status = 0;
    else if (at >= 0 && !cfg)
        status = cl_cli_fail(&(cl_error){CL_ENOMEM, "out of memory"});
    else if (at >= 0 && cl_cli_apply(cfg, &a->sets, &err) == CL_OK &&
             cl_cli_read(cfg, t, settings, &err) == CL_OK)
        status = work(settings);
    else if (at >= 0)
        status = cl_cli_usage_error(t->cmd, "%s", err.msg);
    cl_config_free(cfg);
    cl_cli_sets_free(&a->sets);
    return status;
}

cl_status cl_cli_ignore_run(cl_config *cfg, const char *cmd, cl_error *err)
{
    const char *sec, *key;
    for (size_t k = 0; (key = cl_config_set_key_at(cfg, k, &sec)); k++)
        if (!strcmp(sec, "run"))
            return cl_cli_not_read(cfg, cmd, sec, key, err);
    cl_config_ignore_section(cfg, "run");
    return CL_OK;
}

cl_status cl_cli_check_output(const char *dir, const char *name,
                              cl_error *err)
{
    char path[4200];
    struct stat st;
    if (stat(dir, &st) == 0 && !S_ISDIR(st.st_mode))
        return cl_error_set(err, CL_EIO, "cannot use '%s' as the output "
                            "directory: it exists and is not a directory",
                            dir);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    /* made, and written to once (a temporary file, removed), so that a
     * directory that cannot be made or written fails before the work */
    cl_afile af;
    cl_status rc = cl_mkdir_p(dir, err);
    if (!rc && !(rc = cl_cli_outdir_hold(dir, err)) &&
        !(rc = cl_afile_open(&af, path, err)))
        cl_afile_abort(&af);
    return rc;
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

cl_status cl_cli_apply(cl_config *cfg, const cl_cli_sets *sets,
                       cl_error *err)
{
    cl_status rc = CL_OK;
    char label[64];
    for (int k = 0; rc == CL_OK && k < sets->n; k++) {
        if (sets->label[k])
            snprintf(label, sizeof label, "--%s", sets->label[k]);
        rc = cl_config_set_once(cfg, sets->v[k],
                                sets->label[k] ? label : NULL, err);
    }
    return rc;
}

cl_status cl_cli_load(cl_config *cfg, const char *problem,
                      const cl_cli_sets *sets, cl_error *err)
{
    cl_status rc = cl_config_load(cfg, problem, err);
    return rc ? rc : cl_cli_apply(cfg, sets, err);
}

/* Whether the file `path` lies in the problems directory. */
static bool in_problems_dir(const char *path)
{
    char *file = realpath(path, NULL);
    char *dir = realpath(cl_cli_problems_dir(), NULL);
    char *slash = file ? strrchr(file, '/') : NULL;
    bool in = slash && dir && (size_t)(slash - file) == strlen(dir) &&
              !strncmp(file, dir, strlen(dir));
    free(file);
    free(dir);
    return in;
}

/* 32-bit FNV-1a hash of a string (Fowler, Noll and Vo). */
static unsigned long fnv1a(const char *s)
{
    uint32_t h = 2166136261u;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 16777619u;
    return h;
}

void cl_cli_default_out(const char *problem, char *buf, size_t len)
{
    const char *base = strrchr(problem, '/');
    base = base ? base + 1 : problem;
    const char *dot = strrchr(base, '.');
    size_t n = dot && !strcmp(dot, ".ini") ? (size_t)(dot - base)
                                             : strlen(base);
    char *abs = in_problems_dir(problem) ? NULL : realpath(problem, NULL);
    if (abs)
        snprintf(buf, len, "out/%.*s-%08lx", (int)n, base, fnv1a(abs));
    else
        snprintf(buf, len, "out/%.*s", (int)n, base);
    free(abs);
}

cl_status cl_cli_span(cl_config *cfg, double t_end, double *span,
                      cl_error *err)
{
    double t0 = 0.0;
    cl_status rc = cl_model_config_start_time(cfg, &t0, err);
    if (rc)
        return rc;
    *span = t_end - t0;
    if (t0 == 0.0 || *span > 0)
        return CL_OK;
    return cl_error_set(err, CL_EINVAL, "t_end = %g is not after [init] "
                        "time = %g: the runs go from that time to t_end",
                        t_end, t0);
}

double cl_cli_dt_max(const cl_config *cfg, const char *sec, double given,
                     double span)
{
    return cl_config_peek(cfg, sec, "dt_max") ? given : span / 100;
}

double cl_cli_state_time(const cl_config *cfg, const char *sec,
                         const cl_model *m, double t)
{
    return cl_config_peek(cfg, sec, "t") ? t : cl_model_start_time(m);
}

cl_status cl_cli_free_state(cl_model *m, const char *path, double *x,
                            double *v, cl_error *err)
{
    return *path ? cl_model_read_state(m, path, x, v, err)
                 : cl_model_initial_state(m, x, v);
}
