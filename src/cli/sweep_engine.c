/* The engines of `clothode sweep run` (see sweep_engine.h). */
#include "cli/sweep_engine.h"

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/clock.h"
#include "core/exit.h"
#include "core/stop.h"
#include "io/atomic.h"
#include "io/input.h"

extern char **environ;

/* ---- GNU parallel ------------------------------------------------------- */

static volatile sig_atomic_t engine_pid, stopped_by;

/* SIGINT and SIGTERM go on to the program run (GNU parallel, which stops
 * its jobs; a pilot job; sbatch), and are noted. */
static void forward(int sig)
{
    stopped_by = sig;
    if (engine_pid > 0)
        kill((pid_t)engine_pid, sig);
}

/* While a child runs: SIGINT and SIGTERM forwarded to it (old: the
 * handlers before, for forwarding_end). */
typedef struct {
    struct sigaction old_int, old_term;
} forwarding;

static void forwarding_begin(forwarding *f, pid_t pid)
{
    struct sigaction sa = {.sa_handler = forward};
    sigemptyset(&sa.sa_mask);
    engine_pid = pid;
    sigaction(SIGINT, &sa, &f->old_int);
    sigaction(SIGTERM, &sa, &f->old_term);
}

static void forwarding_end(forwarding *f)
{
    engine_pid = 0;
    sigaction(SIGINT, &f->old_int, NULL);
    sigaction(SIGTERM, &f->old_term, NULL);
}

/* Whether a stop was asked for: a signal forwarded, or one the program's
 * own handler took (core/stop.h). */
static bool stop_asked(void)
{
    return stopped_by || cl_stop_requested();
}

/* Run argv, forwarding SIGINT and SIGTERM; its wait status, or -1. */
static int spawn_forwarding(const char *const *argv)
{
    forwarding f;
    pid_t pid;
    int status = -1;
    fflush(stdout);
    if (posix_spawnp(&pid, argv[0], NULL, NULL, (char *const *)argv,
                     environ) == 0) {
        forwarding_begin(&f, pid);
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
            ;
        forwarding_end(&f);
    }
    return status;
}

int cl_sweep_parallel(const cl_sweep *sw, const cl_sweep_run_args *r,
                      const char *list, bool append)
{
    char joblog[4200], jobs[32];
    const char *argv[16];
    int n = 0;
    snprintf(joblog, sizeof joblog, "%s%s/joblog", append ? "+" : "",
             sw->dir);
    argv[n++] = "parallel";
    argv[n++] = "--will-cite";
    if (r->jobs > 0) {
        snprintf(jobs, sizeof jobs, "%ld", r->jobs);
        argv[n++] = "--jobs";
        argv[n++] = jobs;
    }
    argv[n++] = "--joblog";
    argv[n++] = joblog;
    if (r->engine == CL_SWEEP_SSH) {
        argv[n++] = "--sshloginfile";
        argv[n++] = r->sshloginfile;
    }
    /* the progress bar on a terminal only, so that logs stay clean */
    if (isatty(STDERR_FILENO) && !r->a.quiet)
        argv[n++] = "--bar";
    argv[n++] = "-a";
    argv[n++] = list;
    argv[n] = NULL;
    /* the job lines are POSIX sh (analysis/sweep_plan.c); parallel would
     * run them in the caller's shell, which may be another (fish), here
     * and on ssh hosts alike */
    setenv("PARALLEL_SHELL", "/bin/sh", 1);
    int st = spawn_forwarding(argv);
    /* parallel's exit status counts the failed jobs, 101 for more than
     * 100; above that it was stopped or could not run */
    if (st >= 0 && WIFEXITED(st) && WEXITSTATUS(st) <= 101)
        return 0;
    if (st < 0 || (WIFEXITED(st) && WEXITSTATUS(st) == 127))
        fprintf(stderr, "clothode: sweep run: cannot run GNU parallel "
                        "(apt-get install parallel)\n");
    else
        fprintf(stderr, "clothode: sweep run: GNU parallel stopped before "
                        "the end (%s %d); 'sweep run --resume' runs the "
                        "rest\n", WIFEXITED(st) ? "exit status" : "signal",
                WIFEXITED(st) ? WEXITSTATUS(st) : WTERMSIG(st));
    return 1;
}

/* ---- Slurm -------------------------------------------------------------- */

/* DIR/slurm/NAME (its path in path) opened for an atomic write
 * (io/atomic.h): 0, or 1 with the reason printed. */
static int open_in(const cl_sweep *sw, const char *name, cl_afile *af,
                   char *path, size_t len)
{
    cl_error err;
    snprintf(path, len, "%s/slurm/%s", sw->dir, name);
    if (!cl_afile_open(af, path, &err))
        return 0;
    fprintf(stderr, "clothode: sweep run: %s\n", err.msg);
    return 1;
}

/* The file of open_in, written (af->fp's errors included) and renamed
 * onto its path: 0, or 1 with the reason printed. */
static int commit_in(cl_afile *af)
{
    cl_error err;
    if (!cl_afile_commit(af, &err))
        return 0;
    fprintf(stderr, "clothode: sweep run: %s\n", err.msg);
    return 1;
}

/* Run job k here, as the pilot (SIGINT and SIGTERM forwarded to it): its
 * wall time and peak memory. */
static int pilot(const cl_sweep *sw, int k, double *wall, long *rss_kb)
{
    struct rusage ru;
    const char *const argv[] = {"/bin/sh", "-c", sw->job[k].command, NULL};
    double t0 = cl_clock_wall();
    int status = spawn_forwarding(argv);
    /* the children's largest peak: this pilot's, or an earlier child's
     * (a pilot that failed, squeue), which can only raise --mem */
    if (status < 0 || getrusage(RUSAGE_CHILDREN, &ru))
        return -1;
    *wall = cl_clock_wall() - t0;
    *rss_kb = ru.ru_maxrss;
    /* the command has recorded its exit status in DIR/jobs/ID/exit */
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* Time (minutes) and memory (MB) of an array task: given, or three times
 * a pilot's wall time per job of a chunk plus a minute and twice its peak
 * memory plus 100 MB, the pilot's figures kept in DIR/slurm/estimate
 * ("job SECONDS KB", per job, so that a resubmission with another
 * --chunk scales them) for resubmissions.  The pilot is the first job of
 * todo that completes (of at most three tried); its result stands.  With
 * both given, no pilot runs. */
static int estimate(const cl_sweep *sw, const cl_sweep_run_args *r,
                    const int *todo, int n, long *minutes, long *mb,
                    int *piloted)
{
    char path[4200];
    *piloted = 0;
    if (r->time_min && r->mem_mb) {
        *minutes = r->time_min;
        *mb = r->mem_mb;
        return 0;
    }
    snprintf(path, sizeof path, "%s/slurm/estimate", sw->dir);
    const char *why;
    double wall = 0;
    long rss = 0;
    int code = -1;
    FILE *fp = cl_input_open(path, "r", &why);
    if (fp) {
        if (fscanf(fp, "job %lf %ld", &wall, &rss) == 2 && wall >= 0 &&
            rss > 0)
            code = 0; /* an earlier format, "MINUTES MB", is not read */
        fclose(fp);
    }
    while (code != 0 && *piloted < n && *piloted < 3 && !stop_asked())
        code = pilot(sw, todo[(*piloted)++], &wall, &rss);
    if (code == 0 && *piloted) {
        if (!r->a.quiet)
            printf("pilot      job %s: %.3g s, %ld MB peak\n",
                   sw->job[todo[*piloted - 1]].id, wall, rss / 1024);
        cl_afile af;
        if (!open_in(sw, "estimate", &af, path, sizeof path)) {
            fprintf(af.fp, "job %.17g %ld\n", wall, rss);
            commit_in(&af); /* without it, a resubmission pilots again */
        }
    }
    if (code == 0) {
        *minutes = (long)ceil((3 * wall * r->chunk + 60) / 60);
        *mb = (long)ceil(2 * rss / 1024.0) + 100;
    }
    *minutes = r->time_min ? r->time_min : *minutes;
    *mb = r->mem_mb ? r->mem_mb : *mb;
    if (*minutes && *mb)
        return 0;
    fprintf(stderr, "clothode: sweep run: no pilot job completed; give "
                    "--time MIN and --mem MB\n");
    return 1;
}

/* The job list of this submission, "ID LINE" (LINE in jobs.txt). */
static int write_ids(const cl_sweep *sw, const int *todo, int n, char *path,
                     size_t len)
{
    char name[64];
    struct stat st;
    int s = 1;
    do {
        snprintf(name, sizeof name, "ids-%d.txt", s++);
        snprintf(path, len, "%s/slurm/%s", sw->dir, name);
    } while (stat(path, &st) == 0);
    cl_afile af;
    if (open_in(sw, name, &af, path, len))
        return 1;
    for (int k = 0; k < n; k++)
        fprintf(af.fp, "%s %d\n", sw->job[todo[k]].id, todo[k] + 1);
    return commit_in(&af);
}

/* The array script: each task runs its chunk of the ids (each job's
 * command records its own exit status in DIR/jobs/ID/exit). */
static int write_script(const cl_sweep *sw, const cl_sweep_run_args *r,
                        const char *ids, int n, long minutes, long mb,
                        char *path, size_t len)
{
    char dir[4400], qids[4400], throttle[32] = "";
    cl_sweep_quote(sw->dir, dir, sizeof dir);
    cl_sweep_quote(ids, qids, sizeof qids);
    if (r->throttle > 0)
        snprintf(throttle, sizeof throttle, "%%%ld", r->throttle);
    cl_afile af;
    if (open_in(sw, "array.sh", &af, path, len))
        return 1;
    long tasks = (n + r->chunk - 1) / r->chunk;
    fprintf(af.fp,
            "#!/bin/bash\n"
            "#SBATCH --job-name=clothode-sweep\n"
            "#SBATCH --array=0-%ld%s\n"
            "#SBATCH --time=%ld\n"
            "#SBATCH --mem=%ldM\n"
            "# clothode sweep: %ld jobs a task, the jobs in %s\n"
            "dir=%s\n"
            "first=$((SLURM_ARRAY_TASK_ID * %ld + 1))\n"
            "sed -n \"${first},$((first + %ld - 1))p\" %s |\n"
            "while read -r id line; do\n"
            "    cmd=$(sed -n \"${line}p\" \"$dir/jobs.txt\")\n"
            "    bash -c \"$cmd\" < /dev/null\n"
            "done\n"
            "exit 0\n",
            tasks - 1, throttle, minutes, mb, r->chunk, ids, dir, r->chunk,
            r->chunk, qids);
    return commit_in(&af);
}

/* Lines of a child's standard output as they come: the part read of the
 * current one, handed to line(ctx, text) at each newline. */
typedef struct {
    char text[1024];
    size_t u;
    void (*line)(void *ctx, const char *text);
    void *ctx;
} line_reader;

static void take(line_reader *lr, const char *buf, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        bool end = buf[k] == '\n';
        if (!end && lr->u + 1 < sizeof lr->text)
            lr->text[lr->u++] = buf[k];
        if (end) {
            lr->text[lr->u] = '\0';
            lr->line(lr->ctx, lr->text);
            lr->u = 0;
        }
    }
}

/* Read the child's stdout (fd[0]) into lr and its stderr (fd[1], -1 for
 * none) into err until both end, through poll so that neither pipe fills
 * while the other is read. */
static void read_both(int fd[2], line_reader *lr, char *err, size_t errlen)
{
    size_t eu = 0;
    char buf[4096];
    struct pollfd p[2] = {{.fd = fd[0], .events = POLLIN},
                          {.fd = fd[1], .events = POLLIN}};
    while (p[0].fd >= 0 || p[1].fd >= 0) {
        if (poll(p, 2, -1) < 0) {
            if (errno == EINTR)
                continue;
            break;
        }
        for (int i = 0; i < 2; i++) {
            if (p[i].fd < 0 || !p[i].revents)
                continue;
            ssize_t k = read(p[i].fd, buf, sizeof buf);
            if (k <= 0 && !(k < 0 && errno == EINTR)) {
                close(p[i].fd);
                p[i].fd = -1;
            } else if (k > 0 && i == 0) {
                take(lr, buf, (size_t)k);
            } else if (k > 0) { /* stderr: kept up to errlen - 1 */
                size_t room = errlen - 1 - eu, m = (size_t)k;
                memcpy(err + eu, buf, m < room ? m : room);
                eu += m < room ? m : room;
            }
        }
    }
    if (lr->u)
        take(lr, "\n", 1);
    if (err)
        err[eu] = '\0';
}

/* Run argv, each line of its standard output handed to line(ctx, text)
 * as it comes; with err, its standard error kept there (errlen bytes at
 * most, NUL-terminated), else passed through.  SIGINT and SIGTERM are
 * forwarded to it.  Its wait status, or -1 when it cannot be started. */
static int run_reading(const char *const *argv,
                       void (*line)(void *ctx, const char *text), void *ctx,
                       char *err, size_t errlen)
{
    int out[2], ep[2] = {-1, -1};
    if (pipe(out) != 0)
        return -1;
    if (err && pipe(ep) != 0) {
        close(out[0]);
        close(out[1]);
        return -1;
    }
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        dup2(out[1], STDOUT_FILENO);
        if (err)
            dup2(ep[1], STDERR_FILENO);
        close(out[0]);
        close(out[1]);
        if (err) {
            close(ep[0]);
            close(ep[1]);
        }
        execvp(argv[0], (char *const *)argv);
        fprintf(stderr, "clothode: cannot run %s: %s (apt-get install "
                        "slurm-client; SLURM_CONF)\n", argv[0],
                strerror(errno));
        _exit(127);
    }
    close(out[1]);
    if (err)
        close(ep[1]);
    int fd[2] = {out[0], err ? ep[0] : -1}, status = -1;
    line_reader lr = {.u = 0, .line = line, .ctx = ctx};
    if (pid < 0) {
        close(fd[0]);
        if (fd[1] >= 0)
            close(fd[1]);
        return -1;
    }
    forwarding f;
    forwarding_begin(&f, pid);
    read_both(fd, &lr, err, errlen);
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    forwarding_end(&f);
    return status;
}

/* Whether text is a Slurm job id as sbatch --parsable prints it, "ID" or
 * "ID;CLUSTER" (digits; a cluster name without blanks); its digits into
 * id and the cluster (or "") into cluster, 64 bytes each. */
static bool job_id(const char *text, char *id, char *cluster)
{
    size_t d = strspn(text, "0123456789");
    const char *c = text + d + (text[d] == ';');
    if (d == 0 || d >= 64 || (text[d] && text[d] != ';') ||
        (text[d] == ';' && !*c) || strcspn(c, " \t") != strlen(c) ||
        strlen(c) >= 64)
        return false;
    snprintf(id, 64, "%.*s", (int)d, text);
    snprintf(cluster, 64, "%s", c);
    return true;
}

/* The array job submitted: its id (sbatch --parsable prints "ID" or
 * "ID;CLUSTER" as soon as the job is queued, before --wait waits) kept in
 * DIR/slurm/job, so that a later 'sweep run' can see the array still
 * queued or running (cl_sweep_slurm_idle).  Any other line sbatch prints
 * (a site's notice) is passed on, not taken for the id. */
typedef struct {
    const cl_sweep *sw;
    char id[64], cluster[64];
} submission;

static void on_sbatch_line(void *ctx, const char *text)
{
    submission *s = ctx;
    if (*s->id || !job_id(text, s->id, s->cluster)) {
        printf("%s\n", text);
        return;
    }
    char path[4200];
    cl_error err;
    cl_afile af;
    snprintf(path, sizeof path, "%s/slurm/job", s->sw->dir);
    cl_status rc = cl_afile_open(&af, path, &err);
    if (!rc && fprintf(af.fp, "%s\n", text) < 0)
        rc = cl_afile_fail(&af, &err);
    if (!rc)
        rc = cl_afile_commit(&af, &err);
    if (rc)
        fprintf(stderr, "clothode: sweep run: cannot record the array job's "
                        "id %s: %s\n", text, err.msg);
    printf("slurm      submitted array job %s\n", s->id);
    fflush(stdout);
}

/* sbatch the script, each task's output into DIR/slurm/task-A_a.out:
 * given as an argument, not an #SBATCH line, so that a directory with
 * spaces or quotes reaches sbatch as it is, with its '%' doubled (a
 * literal '%' in Slurm's file name patterns).  Its wait status, and the
 * array's id once sbatch has queued it ("" if not). */
static int sbatch(const cl_sweep *sw, const char *script, bool wait,
                  submission *s)
{
    char output[8500];
    size_t u = (size_t)snprintf(output, sizeof output, "--output=");
    for (const char *c = sw->dir; *c && u + 2 < sizeof output; c++) {
        if (*c == '%')
            output[u++] = '%';
        output[u++] = *c;
    }
    snprintf(output + u, sizeof output - u, "/slurm/task-%%A_%%a.out");
    const char *argv[] = {"sbatch", "--parsable", output, script, NULL, NULL};
    if (wait) {
        argv[3] = "--wait";
        argv[4] = script;
    }
    *s = (submission){.sw = sw};
    int status = run_reading(argv, on_sbatch_line, s, NULL, 0);
    if (status < 0)
        fprintf(stderr, "clothode: cannot run sbatch: %s\n", strerror(errno));
    return status;
}

/* squeue's lines of the array's tasks still queued or running ("ID" or
 * "ID_..."), and the first of them. */
typedef struct {
    const char *id;
    int tasks;
    char first[256];
} queue_answer;

static void on_squeue_line(void *ctx, const char *text)
{
    queue_answer *q = ctx;
    size_t n = strlen(q->id);
    if (strncmp(text, q->id, n) || (text[n] && text[n] != '_' &&
                                    text[n] != ' '))
        return; /* a header, "CLUSTER: name" */
    if (!q->tasks++)
        snprintf(q->first, sizeof q->first, "%s", text);
}

cl_status cl_sweep_slurm_idle(const cl_sweep *sw, cl_error *err)
{
    char path[4200], text[256] = "", id[64], cluster[64], jobs[80],
        clusters[80], said[1024] = "";
    const char *why;
    snprintf(path, sizeof path, "%s/slurm/job", sw->dir);
    FILE *fp = cl_input_open(path, "r", &why);
    if (!fp)
        return CL_OK; /* no array was submitted */
    if (!fgets(text, sizeof text, fp))
        *text = '\0';
    fclose(fp);
    text[strcspn(text, "\n")] = '\0';
    if (!job_id(text, id, cluster))
        return cl_error_set(err, CL_EINVAL, "%s: \"%s\" is not a Slurm job "
                            "id (ID or ID;CLUSTER); remove the file if no "
                            "array of this sweep is queued", path, text);
    snprintf(jobs, sizeof jobs, "--jobs=%s", id);
    snprintf(clusters, sizeof clusters, "--clusters=%s", cluster);
    /* the states of a task still to run or running, whatever the user's
     * SQUEUE_STATES says */
    const char *argv[] = {"squeue", "--noheader", "--format=%i",
                          "--states=PENDING,RUNNING,SUSPENDED,COMPLETING,"
                          "CONFIGURING,REQUEUED,RESIZING,SIGNALING,"
                          "STAGE_OUT,STOPPED", jobs,
                          *cluster ? clusters : NULL, NULL};
    queue_answer q = {.id = id};
    int st = run_reading(argv, on_squeue_line, &q, said, sizeof said);
    if (stop_asked())
        return cl_error_set(err, CL_EINTR, "interrupted while squeue was "
                            "asked about the array job %s", text);
    bool ok = st >= 0 && WIFEXITED(st) && WEXITSTATUS(st) == 0;
    /* an array long ended is forgotten by Slurm: "Invalid job id" */
    if ((ok && !q.tasks) || (!ok && strstr(said, "Invalid job id")))
        return CL_OK;
    if (ok)
        return cl_error_set(err, CL_EINVAL, "%s: the Slurm array job %s "
                            "that an earlier 'sweep run' submitted still has "
                            "tasks queued or running (squeue: %s%s), and "
                            "they write this sweep's jobs: wait for them, or "
                            "'scancel %s', then run again", sw->dir, text,
                            q.first, q.tasks > 1 ? ", ..." : "", id);
    said[strcspn(said, "\n")] = '\0';
    return cl_error_set(err, CL_EIO, "%s: cannot ask Slurm whether the array "
                        "job %s that an earlier 'sweep run' submitted still "
                        "runs (squeue%s%s); its tasks would write this "
                        "sweep's jobs: ask again once squeue answers, or "
                        "remove %s if that array is known to be over",
                        sw->dir, text, *said ? ": " : "", said, path);
}

/* A stop (SIGINT, SIGTERM) during the submission: exit status 6 with what
 * became of the array. */
static int interrupted(const submission *s)
{
    if (*s->id)
        fprintf(stderr, "clothode: sweep run: interrupted; the array job %s "
                        "was submitted and runs on (squeue; 'scancel %s' "
                        "stops it)\n", s->id, s->id);
    else
        fprintf(stderr, "clothode: sweep run: interrupted before the array "
                        "was submitted\n");
    return CL_EXIT_INTERRUPTED;
}

int cl_sweep_slurm(const cl_sweep *sw, const cl_sweep_run_args *r,
                   const int *todo, int n, int *ran)
{
    char dir[4200], ids[4300], script[4300];
    long minutes = 0, mb = 0;
    int piloted;
    cl_error err;
    submission s = {.sw = sw};
    *ran = 0;
    snprintf(dir, sizeof dir, "%s/slurm", sw->dir);
    if (cl_mkdir_p(dir, &err))
        return fprintf(stderr, "clothode: %s\n", err.msg), 1;
    int status = estimate(sw, r, todo, n, &minutes, &mb, &piloted);
    *ran = piloted;
    if (stop_asked())
        return interrupted(&s);
    if (status)
        return 1;
    todo += piloted;
    n -= piloted;
    if (n == 0) {
        if (!r->a.quiet)
            printf("slurm      nothing left to submit\n");
        return 0;
    }
    if (write_ids(sw, todo, n, ids, sizeof ids) ||
        write_script(sw, r, ids, n, minutes, mb, script, sizeof script))
        return 1; /* the reason printed */
    if (!r->a.quiet)
        printf("slurm      %d jobs in %ld array tasks of %ld, %ld min and "
               "%ld MB each: %s\n", n, (n + r->chunk - 1) / r->chunk,
               r->chunk, minutes, mb, script);
    status = sbatch(sw, script, r->wait, &s);
    bool done = status >= 0 && WIFEXITED(status) && !WEXITSTATUS(status);
    /* queued: an id printed, or a success without one (no check of
     * the queue can be made then) */
    *ran += *s.id || done ? n : 0;
    if (done && !*s.id)
        fprintf(stderr, "clothode: sweep run: sbatch printed no job id; a "
                        "later 'sweep run' cannot see whether this array "
                        "still runs\n");
    if (stop_asked())
        return interrupted(&s);
    if (status >= 0 && WIFSIGNALED(status))
        fprintf(stderr, "clothode: sweep run: sbatch was killed (signal "
                        "%d)%s%s%s\n", WTERMSIG(status),
                *s.id ? "; the array job " : "", s.id,
                *s.id ? " was submitted (squeue)" : "");
    else if (!done && *s.id && r->wait)
        fprintf(stderr, "clothode: sweep run: the array job %s ended with a "
                        "task that failed or was killed (sbatch --wait: exit "
                        "status %d; a time or memory limit? see %s/slurm/"
                        "task-*.out); 'sweep run --resume' runs the jobs "
                        "without a result\n", s.id,
                status >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1,
                sw->dir);
    return done ? 0 : 1;
}
