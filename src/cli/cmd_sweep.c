/* clothode sweep plan|run|collect|refine: parameter sweeps (analysis/sweep.h),
 * run by GNU parallel or Slurm (cli/sweep_engine.h). */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "analysis/sweep.h"
#include "analysis/sweep_table.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/sweep_engine.h"
#include "io/atomic.h"
#include "io/input.h"
#include "io/jsonfile.h"

/* ---- plan --------------------------------------------------------------- */

/* The rows of plan and collect: --out ARG, --quiet, --help. */
#define SWEEP_OUT_ROWS(arg_name, out_help)                                  \
    {{.name = "out", .arg = (arg_name), .type = CL_CLI_STRING,             \
      .field = offsetof(cl_cli_args, out), .help = (out_help)},            \
     {.name = "quiet", .type = CL_CLI_FLAG,                                \
      .field = offsetof(cl_cli_args, quiet), .help = "no summary on stdout"},\
     CL_CLI_HELP_ROW,                                                      \
     {.type = CL_CLI_END}}

typedef struct {
    cl_cli_args a;
    bool no_check; /* --no-check */
} plan_args;

static const cl_cli_opt plan_rows[] = {
    {.name = "out", .arg = "DIR", .type = CL_CLI_STRING,
     .field = offsetof(plan_args, a.out),
     .help = "sweep directory (default out/sweep-NAME for NAME.ini)"},
    {.name = "no-check", .type = CL_CLI_FLAG,
     .field = offsetof(plan_args, no_check),
     .help = "do not check the jobs as run would (the check builds the "
             "model of each new value here: about 1.8 GB at n = 1024)"},
    {.name = "quiet", .type = CL_CLI_FLAG,
     .field = offsetof(plan_args, a.quiet), .help = "no summary on stdout"},
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table plan_table = {
    .cmd = "sweep plan", .synopsis = "SWEEP.ini [--out DIR] [--no-check]",
    .npos = 1,
    .pos = "SWEEP.ini", .rows = plan_rows,
    .about =
    "Expand a sweep file ([sweep] problem, integrator, reference and the\n"
    "axes: lists, linspace(a, b, k), logspace(a, b, k) over dt, rtol, atol,\n"
    "t_end, n or any SECTION.KEY) into DIR/jobs.txt, one shell line per\n"
    "job that runs 'clothode run' into DIR/jobs/ID and records its exit\n"
    "status there, and the manifest DIR/sweep.json.  Ids hash each job's parameters: they stay when the\n"
    "plan is expanded again.  Each job that brings a new integrator or\n"
    "value is first checked as run checks its inputs (--no-check: not).\n"};

/* The problem: relative to the sweep file's directory if it is there,
 * else as `run` finds it (a path, or a name under problems/); absolute. */
static cl_status resolve_problem(cl_config *cfg, const char *spec,
                                 cl_sweep *sw, cl_error *err)
{
    char rel[4200], named[4200], *abs;
    struct stat st;
    const char *slash = strrchr(spec, '/');
    snprintf(rel, sizeof rel, "%.*s%s", slash ? (int)(slash - spec + 1) : 0,
             spec, sw->problem);
    const char *path = sw->problem[0] != '/' && stat(rel, &st) == 0
                           ? rel
                           : cl_cli_problem_path(sw->problem, named,
                                                 sizeof named);
    if (!(abs = realpath(path, NULL)))
        return cl_config_refuse(cfg, "sweep", "problem", CL_EINVAL,
                                "no such problem file", err);
    free(sw->problem);
    sw->problem = abs;
    return CL_OK;
}

/* The sweep directory, made (*made: it did not exist before), and the
 * binary, both absolute. */
static cl_status plan_dirs(const cl_cli_args *a, cl_sweep *sw, bool *made,
                           cl_error *err)
{
    char def[4200];
    struct stat st;
    const char *base = strrchr(a->arg, '/') ? strrchr(a->arg, '/') + 1
                                            : a->arg;
    snprintf(def, sizeof def, "out/sweep-%.*s", (int)strcspn(base, "."),
             base);
    const char *dir = a->out ? a->out : def;
    *made = stat(dir, &st) != 0;
    cl_status rc = cl_mkdir_p(dir, err);
    if (!rc && !(sw->dir = realpath(dir, NULL)))
        rc = cl_error_set(err, CL_EIO, "%s: cannot resolve", dir);
    if (!rc && !(sw->clothode = realpath("/proc/self/exe", NULL)))
        rc = cl_error_set(err, CL_EIO, "cannot find the clothode binary");
    /* jobs.txt has a job a line, and Slurm's script a path a line */
    const char *const paths[] = {sw->dir, sw->problem, sw->clothode};
    for (int k = 0; !rc && k < 3; k++) {
        char shown[4200];
        snprintf(shown, sizeof shown, "%s", paths[k]);
        bool control = false;
        for (char *c = shown; *c; c++)
            if ((unsigned char)*c < 0x20 || *c == 0x7f)
                *c = '?', control = true;
        if (control)
            rc = cl_error_set(err, CL_EINVAL, "%s: a control character (a "
                              "newline, ...; shown as ?) in the path; the "
                              "job lines cannot carry it", shown);
    }
    return rc;
}

/* A directory that already holds a sweep is planned again only for the
 * same problem (cl_same_input: the file, its bytes, or, planned on
 * another machine, its name): the ids hash the jobs' values alone, so the
 * results there would stand for another problem's jobs.  Its manifest is
 * read for the problem alone, so that a sweep of an earlier clothode can
 * still be planned again. */
static cl_status same_sweep(const cl_sweep *sw, cl_error *err)
{
    char path[4200];
    struct stat st;
    json_error_t je;
    const char *why;
    snprintf(path, sizeof path, "%s/sweep.json", sw->dir);
    if (stat(path, &st) != 0)
        return CL_OK;
    json_t *doc = cl_json_read(path, &je, &why);
    const char *old = json_string_value(json_object_get(doc, "problem"));
    cl_status rc = CL_OK;
    if (!doc)
        rc = cl_error_set(err, CL_EINVAL, "%s: not a sweep's manifest (%s); "
                          "the results in %s/jobs would stand for the new "
                          "jobs: remove the directory, or plan elsewhere",
                          path, why ? why : je.text, sw->dir);
    else if (old && !cl_same_input(old, sw->problem))
        rc = cl_error_set(err, CL_EINVAL, "%s: holds the sweep of %s, whose "
                          "results would stand for the jobs of %s with the "
                          "same values; plan into another directory (or "
                          "remove this one)", sw->dir, old, sw->problem);
    json_decref(doc);
    return rc;
}

/* Pointers met so far, in an open-addressed table of cap (a power of
 * two) slots: a sweep holds each value and integrator once, so a value is
 * its pointer. */
typedef struct {
    const void **slot;
    size_t cap;
} seen_set;

/* Add p; true if it was not there. */
static bool seen_add(seen_set *s, const void *p)
{
    size_t h = (size_t)(((uintptr_t)p >> 4) * 11400714819323198485ull) &
               (s->cap - 1);
    while (s->slot[h] && s->slot[h] != p)
        h = (h + 1) & (s->cap - 1);
    bool fresh = !s->slot[h];
    s->slot[h] = p;
    return fresh;
}

/* Job k as `run` would check it (cl_cmd_run_check) with the settings of
 * its command, the refusal prefixed with the job's assignments. */
static cl_status check_job(const cl_sweep *sw, int k, cl_error *err)
{
    const cl_sweep_job *j = &sw->job[k];
    char set[CL_SWEEP_MAX_AXES + 1][CL_SWEEP_SET_LEN], what[8192];
    const char *sets[CL_SWEEP_MAX_AXES + 1];
    int n = cl_sweep_job_sets(sw, j, set);
    for (int i = 0; i < n; i++)
        sets[i] = set[i];
    cl_error why = {0};
    cl_status rc = cl_cmd_run_check(sw->problem, j->integrator, sets, n, &why);
    if (rc)
        cl_sweep_describe(sw, j, what, sizeof what);
    return rc ? cl_error_set(err, rc, "sweep plan: the job %s would be "
                             "refused: %s", what, why.msg)
              : CL_OK;
}

/* Check, as `run` would before any work, every job that brings an
 * integrator or an axis value no job before it had: each integrator and
 * value is checked at least once, in a job of its own, so that a value
 * run refuses (an unknown key, a number out of its range) stops the plan
 * instead of failing job by job.  The references take cvode-bdf and the
 * problem's values, which the jobs check. */
static cl_status check_jobs(const cl_sweep *sw, cl_error *err)
{
    size_t values = (size_t)sw->nint;
    for (int a = 0; a < sw->naxis; a++)
        values += (size_t)sw->axis[a].n;
    seen_set s = {NULL, 16};
    while (s.cap < 2 * values + 2)
        s.cap *= 2;
    if (!(s.slot = calloc(s.cap, sizeof *s.slot)))
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    cl_status rc = CL_OK;
    for (int k = 0; !rc && k < sw->njob; k++) {
        const cl_sweep_job *j = &sw->job[k];
        if (j->reference)
            continue;
        bool fresh = seen_add(&s, j->integrator);
        for (int a = 0; a < sw->naxis; a++)
            if (j->value[a] && seen_add(&s, j->value[a]))
                fresh = true;
        if (fresh)
            rc = check_job(sw, k, err);
    }
    free(s.slot);
    return rc;
}

/* A refusal of the sweep file `path`'s jobs, named with the file: two
 * jobs that are one run, or a job run would refuse, come from its values
 * in combination, on no one line of it. */
static cl_status of_file(const char *path, cl_status rc, cl_error *err)
{
    if (rc == CL_EINVAL) {
        char why[sizeof err->msg];
        snprintf(why, sizeof why, "%s", err->msg);
        rc = cl_error_set(err, rc, "%s: %s", path, why);
    }
    return rc;
}

static int plan(void *settings)
{
    const plan_args *p = settings;
    const cl_cli_args *a = &p->a;
    bool made = false;
    cl_sweep sw = {0};
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_status rc = cfg ? cl_config_load(cfg, a->arg, &err) : CL_ENOMEM;
    if (!rc && !(rc = cl_sweep_read(cfg, &sw, &err)) &&
        !(rc = cl_config_check_unused(cfg, &err)) &&
        !(rc = resolve_problem(cfg, a->arg, &sw, &err)) &&
        !(rc = plan_dirs(a, &sw, &made, &err)) &&
        !(rc = same_sweep(&sw, &err)) &&
        !(rc = of_file(a->arg, cl_sweep_expand(&sw, &err), &err)) &&
        !(rc = p->no_check ? CL_OK
                           : of_file(a->arg, check_jobs(&sw, &err), &err)))
        rc = cl_sweep_write(&sw, &err);
    if (rc && made && sw.dir) /* a refused plan leaves no directory */
        rmdir(sw.dir);
    if (!rc && !a->quiet) {
        int refs = 0;
        for (int k = 0; k < sw.njob; k++)
            refs += sw.job[k].reference;
        printf("sweep      %s: %d jobs, %d references; %d integrators",
               sw.problem, sw.njob - refs, refs, sw.nint);
        for (int k = 0; k < sw.naxis; k++)
            printf(", %d %s", sw.axis[k].n, sw.axis[k].key);
        printf("\noutput     %s/jobs.txt, %s/sweep.json\n", sw.dir, sw.dir);
    }
    cl_sweep_free(&sw);
    cl_config_free(cfg);
    return rc ? cl_cli_fail(&err) : 0;
}

/* ---- run ---------------------------------------------------------------- */

static const char *const engines[] = {"local", "ssh", "slurm", NULL};

static const cl_cli_opt run_rows[] = {
    {.name = "engine", .arg = "NAME", .type = CL_CLI_NAMES, .sec = "sweep",
     .key = "engine", .sdef = "local", .names = engines,
     .field = offsetof(cl_sweep_run_args, engine),
     .help = "local (GNU parallel), ssh (GNU parallel --sshloginfile) or "
             "slurm (an sbatch --array job)"},
    {.name = "jobs", .arg = "N", .type = CL_CLI_LONG, .sec = "sweep",
     .key = "jobs", .lo = 0, .hi = 100000,
     .field = offsetof(cl_sweep_run_args, jobs),
     .help = "jobs at a time (per ssh login), 0 for one per core"},
    {.name = "resume", .type = CL_CLI_FLAG,
     .field = offsetof(cl_sweep_run_args, resume),
     .help = "run only the jobs that failed or have no result"},
    {.name = "sshloginfile", .arg = "FILE", .type = CL_CLI_STRING,
     .field = offsetof(cl_sweep_run_args, sshloginfile),
     .help = "ssh logins, one a line (GNU parallel's format); required "
             "with --engine ssh"},
    {.name = "chunk", .arg = "C", .type = CL_CLI_LONG, .sec = "sweep",
     .key = "chunk", .def = 1, .lo = 1, .hi = 100000,
     .field = offsetof(cl_sweep_run_args, chunk),
     .help = "slurm: jobs per array task"},
    {.name = "throttle", .arg = "K", .type = CL_CLI_LONG, .sec = "sweep",
     .key = "throttle", .lo = 0, .hi = 100000,
     .field = offsetof(cl_sweep_run_args, throttle),
     .help = "slurm: at most K array tasks at a time (--array=...%K), 0 for "
             "no limit"},
    {.name = "time", .arg = "MIN", .type = CL_CLI_LONG, .sec = "sweep",
     .key = "time", .lo = 0, .hi = 10000000,
     .field = offsetof(cl_sweep_run_args, time_min),
     .help = "slurm: minutes per array task, 0 to estimate from a pilot "
             "run"},
    {.name = "mem", .arg = "MB", .type = CL_CLI_LONG, .sec = "sweep",
     .key = "mem", .lo = 0, .hi = 100000000,
     .field = offsetof(cl_sweep_run_args, mem_mb),
     .help = "slurm: memory per array task, 0 to estimate from a pilot run"},
    {.name = "wait", .type = CL_CLI_FLAG,
     .field = offsetof(cl_sweep_run_args, wait),
     .help = "slurm: return when the array job has ended (sbatch --wait)"},
    {.name = "quiet", .type = CL_CLI_FLAG,
     .field = offsetof(cl_sweep_run_args, a.quiet),
     .help = "no progress bar and no summary"},
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table run_table = {
    .cmd = "sweep run", .synopsis = "DIR [options]", .npos = 1, .pos = "DIR",
    .rows = run_rows,
    .about =
    "Run the jobs of a planned sweep: --engine local runs DIR/jobs.txt with\n"
    "GNU parallel (joblog DIR/joblog, its --bar on a terminal), ssh the same\n"
    "over parallel --sshloginfile (the sweep directory and the binary at the\n"
    "same paths on every host), slurm submits an sbatch --array script\n"
    "(DIR/slurm/array.sh).  --resume runs only the jobs that failed or have\n"
    "no result, as 'sweep collect' finds them.\n"};

/* Job k's status and the place all_jobs sets it aside. */
static void status_paths(const cl_sweep *sw, int k, char *path,
                         char *earlier)
{
    snprintf(path, 4200, "%s/jobs/%s/exit", sw->dir, sw->job[k].id);
    snprintf(earlier, 4300, "%s.earlier", path);
}

/* After a Slurm submission: the earlier statuses all_jobs set aside are
 * dropped for the first `ran` jobs of todo (run as pilots, or queued) and
 * put back for the others, which never ran (sbatch refused the array, or
 * the submission was interrupted): a failed submission leaves the results
 * of the run before it standing.  A status that cannot be put back stays
 * set aside, and is named. */
static void put_back(const cl_sweep *sw, const int *todo, int n, int ran)
{
    char path[4200], earlier[4300];
    for (int k = 0; k < n; k++) {
        status_paths(sw, todo[k], path, earlier);
        bool gone = k < ran || link(earlier, path) == 0 || errno == EEXIST ||
                    errno == ENOENT;
        if (gone)
            (void)unlink(earlier);
        else if (rename(earlier, path) != 0)
            fprintf(stderr, "clothode: sweep run: cannot put back %s: %s; "
                            "the status stays in %s, which collect does not "
                            "read (rename it back by hand)\n", path,
                    strerror(errno), earlier);
    }
}

/* Without --resume: every job, each one's status of an earlier run
 * removed first so that it cannot stand for this one's while its job waits
 * (each job's command removes its own too when it starts); -1 with err set
 * when one cannot be removed (the job could not replace it either; those
 * set aside before it are put back).  With aside (Slurm, whose submission
 * can fail), each status is moved to exit.earlier instead, for put_back,
 * and an exit.earlier left by an interrupted submission is dropped. */
static int all_jobs(const cl_sweep *sw, int *todo, bool aside, cl_error *err)
{
    char path[4200], earlier[4300];
    for (int k = 0; k < sw->njob; k++) {
        status_paths(sw, k, path, earlier);
        const char *bad = NULL;
        if (aside && unlink(earlier) != 0 && errno != ENOENT)
            bad = earlier;
        else if (aside && rename(path, earlier) != 0 && errno != ENOENT)
            bad = path;
        else if (!aside && unlink(path) != 0 && errno != ENOENT)
            bad = path;
        if (bad) {
            cl_error_set(err, CL_EIO, "%s: cannot remove the status of an "
                         "earlier run: %s", bad, strerror(errno));
            if (aside)
                put_back(sw, todo, k, 0);
            return -1;
        }
        todo[k] = k;
    }
    return sw->njob;
}

/* Every job's outcome (allocated), or NULL with err set. */
static cl_sweep_outcome *outcomes_of(const cl_sweep *sw, cl_sweep_counts *c,
                                     cl_error *err)
{
    cl_sweep_outcome *out = calloc((size_t)sw->njob + 1, sizeof *out);
    if (out)
        cl_sweep_outcomes(sw, out, c);
    else
        cl_error_set(err, CL_ENOMEM, "out of memory");
    return out;
}

static int pending_jobs(const cl_sweep *sw, int *todo, cl_error *err)
{
    cl_sweep_counts c;
    cl_sweep_outcome *out = outcomes_of(sw, &c, err);
    int n = 0;
    for (int k = 0; out && k < sw->njob; k++)
        if (out[k].state != CL_SWEEP_COMPLETE)
            todo[n++] = k;
    free(out);
    return out ? n : -1;
}

/* DIR/pending.txt: the commands of todo, for GNU parallel. */
static cl_status write_pending(const cl_sweep *sw, const int *todo, int n,
                               char *path, size_t len, cl_error *err)
{
    cl_afile af;
    snprintf(path, len, "%s/pending.txt", sw->dir);
    cl_status rc = cl_afile_open(&af, path, err);
    for (int k = 0; !rc && k < n; k++)
        fprintf(af.fp, "%s\n", sw->job[todo[k]].command);
    return rc ? rc : cl_afile_commit(&af, err);
}

/* "N complete, M failed, K missing" once the engine is done (unless
 * quiet); exit status 1 when a job has no status though the engine ran
 * it (it could not record one: a full or read-only job directory). */
static int summary(const cl_sweep *sw, bool quiet, cl_error *err)
{
    cl_sweep_counts c;
    cl_sweep_outcome *out = outcomes_of(sw, &c, err);
    if (!out)
        return cl_cli_fail(err);
    if (!quiet)
        printf("%d complete, %d failed, %d missing (sweep collect %s)\n",
               c.complete, c.failed, c.missing, sw->dir);
    free(out);
    if (!c.missing)
        return 0;
    fprintf(stderr, "clothode: sweep run: the engine ended, yet %d %s no "
                    "status (see 'sweep collect' and the stderr of each); "
                    "'sweep run --resume' runs %s\n", c.missing,
            c.missing == 1 ? "job has" : "jobs have",
            c.missing == 1 ? "it" : "them");
    return 1;
}

/* Whether `program` is an executable file in $PATH. */
static bool in_path(const char *program)
{
    const char *path = getenv("PATH");
    char file[4200];
    for (const char *p = path ? path : ""; *p; p += *p == ':') {
        size_t n = strcspn(p, ":");
        snprintf(file, sizeof file, "%.*s/%s", (int)n, n ? p : ".", program);
        if (access(file, X_OK) == 0)
            return true;
        p += n;
    }
    return false;
}

/* DIR/lock, held (flock) by this run and the engine it starts, which
 * inherits it: a second 'sweep run' of the sweep, or a --resume while
 * the GNU parallel of a killed 'sweep run' still runs its jobs, would run
 * the same jobs into the same files.  The descriptor (left open until the
 * program ends), or -1 with err set. */
static int lock_sweep(const cl_sweep *sw, cl_error *err)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/lock", sw->dir);
    int fd = open(path, O_RDWR | O_CREAT | O_NOFOLLOW, 0644);
    if (fd < 0) {
        cl_error_set(err, CL_EIO, "%s: cannot open it: %s", path,
                     strerror(errno));
        return -1;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) == 0)
        return fd;
    int e = errno;
    close(fd);
    if (e == EWOULDBLOCK)
        cl_error_set(err, CL_EINVAL, "%s: another 'sweep run' of this sweep "
                     "(or the GNU parallel it started) is running its jobs; "
                     "wait for it or stop it first", sw->dir);
    else
        cl_error_set(err, CL_EIO, "%s: cannot lock it: %s", path,
                     strerror(e));
    return -1;
}

static int engine_run(cl_sweep *sw, cl_sweep_run_args *r, int *todo,
                      cl_error *err)
{
    char list[4300];
    bool slurm = r->engine == CL_SWEEP_SLURM;
    const char *engine = slurm ? "sbatch" : "parallel";
    if (!in_path(engine)) { /* before any status is removed */
        fprintf(stderr, "clothode: sweep run: %s is not in PATH (apt-get "
                        "install %s); no job's status was touched\n", engine,
                slurm ? "slurm-client" : "parallel");
        return 1;
    }
    if (slurm && strchr(sw->dir, '\\')) {
        fprintf(stderr, "clothode: sweep run: %s: a backslash in the "
                        "directory makes Slurm expand no file name pattern "
                        "(the tasks' output); plan the sweep elsewhere\n",
                sw->dir);
        return 2;
    }
    if (lock_sweep(sw, err) < 0)
        return cl_cli_fail(err);
    /* a submitted array's tasks may still run, outside the lock */
    if ((slurm || in_path("squeue")) && cl_sweep_slurm_idle(sw, err))
        return cl_cli_fail(err);
    int n = r->resume ? pending_jobs(sw, todo, err)
                      : all_jobs(sw, todo, slurm, err);
    if (n < 0)
        return cl_cli_fail(err);
    if (r->resume && !r->a.quiet)
        printf("resume     %d of %d jobs failed or have no result\n", n,
               sw->njob);
    if (n == 0) /* nothing to run: the counts as they stand */
        return summary(sw, r->a.quiet, err);
    if (slurm) {
        int ran = 0, status = cl_sweep_slurm(sw, r, todo, n, &ran);
        if (!r->resume)
            put_back(sw, todo, n, ran);
        /* with --wait, the counts once every job ran or was queued, also
         * when a task of the array failed */
        if (!r->wait || ran < n || status == CL_EXIT_INTERRUPTED)
            return status;
        int counted = summary(sw, r->a.quiet, err);
        return status ? status : counted;
    }
    snprintf(list, sizeof list, "%s/jobs.txt", sw->dir);
    if (r->resume && write_pending(sw, todo, n, list, sizeof list, err))
        return cl_cli_fail(err);
    int status = cl_sweep_parallel(sw, r, list, r->resume);
    return status ? status : summary(sw, r->a.quiet, err);
}

/* The ssh engine's host file (NULL: none), readable before GNU parallel
 * is started on it. */
static cl_status hosts_readable(const char *file, cl_error *err)
{
    const char *why;
    FILE *fp = file ? cl_input_open(file, "r", &why) : NULL;
    if (file && !fp)
        return cl_error_set(err, CL_EIO, "--sshloginfile %s: cannot read "
                            "it: %s", file, why);
    if (fp)
        (void)fclose(fp);
    return CL_OK;
}

static int run(void *settings)
{
    cl_sweep_run_args *r = settings;
    cl_sweep sw = {0};
    cl_error err = {0};
    if (r->engine != CL_SWEEP_LOCAL && r->engine != CL_SWEEP_SSH &&
        r->engine != CL_SWEEP_SLURM)
        return cl_cli_usage_error(run_table.cmd, "--engine: one of local, "
                                  "ssh, slurm");
    if ((r->engine == CL_SWEEP_SSH) != (r->sshloginfile != NULL))
        return cl_cli_usage_error(run_table.cmd, "--sshloginfile FILE goes "
                                  "with --engine ssh, and only with it");
    if (r->engine != CL_SWEEP_SLURM &&
        (r->chunk != 1 || r->throttle || r->time_min || r->mem_mb || r->wait))
        return cl_cli_usage_error(run_table.cmd, "--chunk, --throttle, "
                                  "--time, --mem and --wait go with --engine "
                                  "slurm, and only with it");
    if (!hosts_readable(r->sshloginfile, &err) &&
        !cl_sweep_load(r->a.arg, &sw, &err) && !cl_same_file(r->a.arg, sw.dir))
        /* the jobs' command lines name the planned directory: run there
         * only (a copy is collected where it is) */
        cl_error_set(&err, CL_EINVAL, "%s/sweep.json: planned for %s, where "
                     "its jobs write; plan it again here to run it here "
                     "('clothode sweep plan SWEEP.ini --out %s', the ids "
                     "stay)", r->a.arg, sw.dir, r->a.arg);
    if (err.code) {
        cl_sweep_free(&sw);
        return cl_cli_fail(&err);
    }
    int *todo = malloc(((size_t)sw.njob + 1) * sizeof *todo);
    int status = todo ? engine_run(&sw, r, todo, &err)
                      : cl_cli_fail(&(cl_error){CL_ENOMEM, "out of memory"});
    free(todo);
    cl_sweep_free(&sw);
    return status;
}

/* ---- collect ------------------------------------------------------------ */

static const cl_cli_opt collect_rows[] = SWEEP_OUT_ROWS(
    "TABLE", "the CSV table (default DIR/collected.csv)");

static const cl_cli_table collect_table = {
    .cmd = "sweep collect", .synopsis = "DIR [--out TABLE.csv]", .npos = 1,
    .pos = "DIR", .rows = collect_rows,
    .about =
    "One CSV row per job of the sweep in DIR: id, role (job or reference),\n"
    "integrator, every axis, status (complete, failed, missing), exit\n"
    "class, the time reached, the statistics of stats.csv and the errors\n"
    "err_x, err_v against the reference's final state; then the failed and\n"
    "missing jobs by id and 'N complete, M failed, K missing'.\n"};

static void list_unfinished(const cl_sweep *sw, const cl_sweep_outcome *out)
{
    for (int k = 0; k < sw->njob; k++) {
        if (out[k].state == CL_SWEEP_COMPLETE)
            continue;
        printf("%-10s %s %s", out[k].state == CL_SWEEP_FAILED ? "failed"
                                                              : "missing",
               sw->job[k].id, sw->job[k].integrator);
        for (int a = 0; a < sw->naxis; a++)
            if (sw->job[k].value[a])
                printf(" %s=%s", sw->axis[a].key, sw->job[k].value[a]);
        if (out[k].state == CL_SWEEP_FAILED)
            printf(" (%s)%s%s", out[k].exit_class, *out[k].message ? ": " : "",
                   out[k].message);
        putchar('\n');
    }
}

static void table_rows(FILE *fp, const void *ctx, int n)
{
    const void *const *p = ctx;
    (void)n;
    cl_sweep_write_table(fp, p[0], p[1]);
}

/* A table given by --out that is one of the sweep's own files (its
 * manifest, job list, ...), which it would replace: CL_EINVAL. */
static cl_status not_a_sweep_file(const char *dir, const char *out,
                                  cl_error *err)
{
    static const char *const own[] = {"sweep.json", "jobs.txt", "joblog",
                                      "pending.txt", "lock", "slurm/job"};
    char path[4200];
    for (size_t k = 0; out && k < sizeof own / sizeof *own; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, own[k]);
        if (cl_same_file(out, path))
            return cl_error_set(err, CL_EINVAL, "--out %s: the sweep's own "
                                "%s, which the table would replace; write "
                                "it elsewhere", out, path);
    }
    return CL_OK;
}

static int collect(void *settings)
{
    cl_cli_args *a = settings;
    cl_sweep sw = {0};
    cl_error err = {0};
    cl_sweep_counts c;
    cl_sweep_outcome *out = NULL;
    char table[4200], dir[4200];
    cl_status rc = not_a_sweep_file(a->arg, a->out, &err);
    if (!rc)
        rc = cl_sweep_load(a->arg, &sw, &err);
    /* the jobs' outputs where the sweep is now (copied from a cluster) */
    free(sw.dir);
    sw.dir = strdup(a->arg);
    if (!rc && !sw.dir)
        rc = cl_error_set(&err, CL_ENOMEM, "out of memory");
    if (!rc && !(out = outcomes_of(&sw, &c, &err)))
        rc = err.code;
    snprintf(table, sizeof table, "%s", a->out ? a->out : "collected.csv");
    snprintf(dir, sizeof dir, "%s", a->out ? "." : a->arg);
    char *slash = a->out ? strrchr(table, '/') : NULL;
    if (slash) /* TABLE as DIR/NAME for the atomic writer */
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - table), table),
            memmove(table, slash + 1, strlen(slash));
    const void *ctx[2] = {&sw, out};
    if (!rc)
        rc = cl_cli_write_csv(dir, table, table_rows, ctx, 1, &err);
    if (!rc && !a->quiet) {
        list_unfinished(&sw, out);
        printf("%d complete, %d failed, %d missing\noutput     %s/%s\n",
               c.complete, c.failed, c.missing, dir, table);
    }
    free(out);
    cl_sweep_free(&sw);
    return rc ? cl_cli_fail(&err) : 0;
}

/* ---- refine ------------------------------------------------------------- */

typedef struct {
    cl_cli_args a;
    const char *tables;   /* --table LIST, default DIR/collected.csv */
    long points;
    double rel;
} refine_args;

static const cl_cli_opt refine_rows[] = {
    {.name = "table", .arg = "LIST", .type = CL_CLI_STRING,
     .field = offsetof(refine_args, tables),
     .help = "the collected tables of the stages so far, comma-separated "
             "(default DIR/collected.csv)"},
    {.name = "points", .arg = "K", .type = CL_CLI_LONG, .sec = "sweep",
     .key = "points", .def = 8, .lo = 1, .hi = 1000,
     .field = offsetof(refine_args, points),
     .help = "steps planned inside each bracket"},
    {.name = "rel", .arg = "R", .type = CL_CLI_DOUBLE, .sec = "sweep",
     .key = "rel", .def = 0.02, .lo = 1e-9, .hi = 100,
     .field = offsetof(refine_args, rel),
     .help = "leave brackets narrower than 1 + R (the stability search's "
             "--rel)"},
    {.name = "out", .arg = "DIR2", .type = CL_CLI_STRING,
     .field = offsetof(refine_args, a.out),
     .help = "the next stage's sweep directory (default DIR-refine)"},
    {.name = "quiet", .type = CL_CLI_FLAG,
     .field = offsetof(refine_args, a.quiet), .help = "no summary on stdout"},
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table refine_table = {
    .cmd = "sweep refine",
    .synopsis = "DIR [--table LIST] [--points K] [--rel R] [--out DIR2]",
    .npos = 1, .pos = "DIR", .rows = refine_rows,
    .about =
    "Plan the next stage of a sweep over dt: for every line of the sweep in\n"
    "DIR (an integrator and the values of the other axes) whose collected\n"
    "runs bracket a stability limit (the smallest unstable dt, the largest\n"
    "stable one below it, as 'stability --from-sweep' reads them) wider than\n"
    "1 + R, K steps evenly spread in log inside the bracket (each made T/N\n"
    "when the sweep gives one t_end).  DIR2 is a sweep of its own (same\n"
    "problem, binary and axes, no references): run and collect it, then give\n"
    "the studies both tables, --from-sweep A.csv,B.csv; refine again with\n"
    "--table A.csv,B.csv.\n"};

/* The rows of the tables without a result, which bound no bracket, on
 * stderr (also with --quiet: a stage planned without them is not the
 * whole refinement). */
static void name_missing(const cl_sweep_table *t)
{
    int missing = 0;
    for (int row = 0; row < t->nrow; row++)
        if (!strcmp(cl_sweep_table_text(t, row, "status"), "missing") &&
            missing++ < 8)
            fprintf(stderr, "%s %s", missing > 1 ? "," : "clothode: sweep "
                    "refine: rows without a result, left out of the "
                    "brackets:", cl_sweep_table_text(t, row, "id"));
    if (missing)
        fprintf(stderr, "%s (%d in all); run them ('sweep run --resume'), "
                        "collect, and refine again\n",
                missing > 8 ? ", ..." : "", missing);
}

static int refine(void *settings)
{
    refine_args *r = settings;
    cl_sweep sw = {0}, next = {0};
    cl_sweep_table t = {0};
    cl_error err = {0};
    char table[4200], out[4200];
    int brackets = 0;
    snprintf(table, sizeof table, "%s/collected.csv", r->a.arg);
    snprintf(out, sizeof out, "%s-refine", r->a.arg);
    r->a.out = r->a.out ? r->a.out : out;
    cl_status rc = cl_sweep_load(r->a.arg, &sw, &err);
    if (!rc && cl_same_file(r->a.arg, r->a.out))
        rc = cl_error_set(&err, CL_EINVAL, "--out %s: it is the sweep being "
                          "refined, whose manifest the next stage would "
                          "replace; the next stage is a sweep directory of "
                          "its own", r->a.out);
    if (!rc)
        rc = cl_sweep_table_read(r->tables ? r->tables : table, &t, &err);
    if (!rc && !(rc = cl_mkdir_p(r->a.out, &err)) &&
        (!(next.dir = realpath(r->a.out, NULL)) ||
         !(next.problem = strdup(sw.problem)) ||
         !(next.clothode = strdup(sw.clothode))))
        rc = cl_error_set(&err, CL_ENOMEM, "%s: cannot resolve", r->a.out);
    if (!rc)
        rc = cl_sweep_refine(&sw, &t, (int)r->points, r->rel, &next,
                             &brackets, &err);
    if (!rc)
        rc = cl_sweep_write(&next, &err);
    if (!rc && !r->a.quiet)
        printf("refine     %d jobs inside %d brackets wider than 1 + %g\n"
               "output     %s/jobs.txt, %s/sweep.json\n", next.njob,
               brackets, r->rel, next.dir, next.dir);
    if (!rc)
        name_missing(&t);
    cl_sweep_table_free(&t);
    cl_sweep_free(&next);
    cl_sweep_free(&sw);
    return rc ? cl_cli_fail(&err) : 0;
}

/* ---- dispatch ----------------------------------------------------------- */

int cl_cmd_sweep(int argc, char **argv)
{
    const char *what = argc > 1 ? argv[1] : "";
    if (!strcmp(what, "plan")) {
        plan_args p = {0};
        return cl_cli_args_main(argc - 1, argv + 1, &plan_table, &p, plan);
    }
    if (!strcmp(what, "run")) {
        cl_sweep_run_args r = {0};
        return cl_cli_args_main(argc - 1, argv + 1, &run_table, &r, run);
    }
    if (!strcmp(what, "collect")) {
        cl_cli_args a = {0};
        return cl_cli_args_main(argc - 1, argv + 1, &collect_table, &a,
                                collect);
    }
    if (!strcmp(what, "refine")) {
        refine_args r = {0};
        return cl_cli_args_main(argc - 1, argv + 1, &refine_table, &r,
                                refine);
    }
    FILE *fp = strcmp(what, "--help") ? stderr : stdout;
    if (fp == stderr && *what)
        fprintf(stderr, "clothode: sweep: unknown subcommand '%s' (plan, "
                "run, collect or refine)\n", what);
    else if (fp == stderr)
        fprintf(stderr, "clothode: sweep: a subcommand is needed (plan, "
                "run, collect or refine)\n");
    fprintf(fp, "usage: clothode sweep plan SWEEP.ini [--out DIR] "
                "[--no-check]\n"
                "       clothode sweep run DIR [--engine local|ssh|slurm] "
                "[--jobs N] [--resume] ...\n"
                "       clothode sweep collect DIR [--out TABLE.csv]\n"
                "       clothode sweep refine DIR [--table LIST] [--points K] "
                "[--rel R] [--out DIR2]\n"
                "(clothode sweep plan|run|collect|refine --help for more)\n");
    return fp == stdout ? 0 : 2;
}
