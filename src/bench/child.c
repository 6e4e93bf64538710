/* Child processes for the benchmarks: posix_spawnp, wait4 for the usage of
 * one child alone (getrusage(RUSAGE_CHILDREN) would mix all of them, and
 * its ru_maxrss is the largest child's so far). */
#define _DEFAULT_SOURCE /* wait4 */
#include "bench/child.h"

#include "core/stop.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Redirect descriptor fd to path (truncated), or to /dev/null. */
static int redirect(posix_spawn_file_actions_t *fa, int fd, const char *path)
{
    return posix_spawn_file_actions_addopen(
        fa, fd, path ? path : "/dev/null",
        fd == STDIN_FILENO ? O_RDONLY : O_WRONLY | O_CREAT | O_TRUNC, 0666);
}

cl_status cl_child_start(cl_child *c, char *const argv[],
                         const char *out_path, const char *err_path,
                         cl_error *err)
{
    posix_spawn_file_actions_t fa;
    c->pid = 0;
    if (posix_spawn_file_actions_init(&fa))
        return cl_error_set(err, CL_ENOMEM, "out of memory (spawn)");
    int rc = redirect(&fa, STDIN_FILENO, NULL);
    if (!rc)
        rc = redirect(&fa, STDOUT_FILENO, out_path);
    if (!rc)
        rc = redirect(&fa, STDERR_FILENO, err_path);
    c->t0 = now();
    if (!rc)
        rc = posix_spawnp(&c->pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc) {
        c->pid = 0;
        return cl_error_set(err, CL_EIO, "cannot start %s: %s", argv[0],
                            strerror(rc));
    }
    return CL_OK;
}

static void fill_usage(int ws, const struct rusage *ru, double t0,
                       cl_child_usage *u)
{
    u->exited = WIFEXITED(ws);
    u->status = u->exited ? WEXITSTATUS(ws) : -1;
    u->signal = WIFSIGNALED(ws) ? WTERMSIG(ws) : 0;
    u->cpu = (double)ru->ru_utime.tv_sec + 1e-6 * ru->ru_utime.tv_usec +
             (double)ru->ru_stime.tv_sec + 1e-6 * ru->ru_stime.tv_usec;
    u->wall = now() - t0;
    u->maxrss_kb = ru->ru_maxrss;
}

/* Without blocking: true when the child was reaped, *u filled. */
static bool reap(cl_child *c, cl_child_usage *u)
{
    int ws = 0;
    struct rusage ru;
    pid_t w;
    do
        w = wait4(c->pid, &ws, WNOHANG, &ru);
    while (w < 0 && errno == EINTR);
    if (w == 0)
        return false;
    if (w < 0) { /* not our child any more: report a failure */
        memset(&ru, 0, sizeof ru);
        ws = 0xff00; /* exit status 255 */
    }
    fill_usage(ws, &ru, c->t0, u);
    c->pid = 0;
    return true;
}

bool cl_child_done(cl_child *c, cl_child_usage *u)
{
    return c->pid > 0 && reap(c, u);
}

/* Polled every 10 ms rather than blocked in wait4, so that a stop by
 * SIGINT or SIGTERM (core/stop.h) that comes at any moment of the wait is
 * seen and passed on to the child as SIGTERM, once: a bench stopped by a
 * signal sent to its process alone (kill PID, a batch system's time limit)
 * does not wait for a child's long run.  The end is seen up to 10 ms
 * late, in u->wall too. */
void cl_child_wait(cl_child *c, cl_child_usage *u)
{
    bool passed = false;
    while (c->pid > 0 && !reap(c, u)) {
        if (!passed && cl_stop_interrupted())
            passed = kill(c->pid, SIGTERM) == 0;
        nanosleep(&(struct timespec){0, 10000000}, NULL);
    }
}

cl_status cl_child_run(char *const argv[], const char *out_path,
                       const char *err_path, cl_child_usage *u,
                       cl_error *err)
{
    cl_child c;
    cl_status rc = cl_child_start(&c, argv, out_path, err_path, err);
    if (rc)
        return rc;
    cl_child_wait(&c, u);
    if (u->exited && u->status == 0)
        return CL_OK;
    if (u->exited)
        return cl_error_set(err, CL_EIO, "%s exited with status %d",
                            argv[0], u->status);
    return cl_error_set(err, CL_EIO, "%s was killed by signal %d (%s)",
                        argv[0], u->signal, strsignal(u->signal));
}

/* Does `python` import numpy and the scipy modules the peer uses? */
static bool has_scipy(const char *python)
{
    char *argv[] = {(char *)python, "-c",
                    "import numpy, scipy.sparse, scipy.integrate", NULL};
    cl_child_usage u;
    cl_error ignored;
    return cl_child_run(argv, NULL, NULL, &u, &ignored) == CL_OK;
}

cl_status cl_child_python(char *buf, size_t len, cl_error *err)
{
    const char *env = getenv("CLOTHODE_PYTHON");
    const char *cands[] = {"python3", "/usr/bin/python3"};
    if (env && *env) {
        snprintf(buf, len, "%s", env);
        if (has_scipy(env))
            return CL_OK;
        return cl_error_set(err, CL_EUNSUPPORTED,
                            "$CLOTHODE_PYTHON = %s cannot import numpy and "
                            "scipy", env);
    }
    for (size_t k = 0; k < 2; k++)
        if (has_scipy(cands[k])) {
            snprintf(buf, len, "%s", cands[k]);
            return CL_OK;
        }
    return cl_error_set(err, CL_EUNSUPPORTED,
                        "no Python with numpy and scipy (tried python3 on "
                        "PATH and /usr/bin/python3; install Debian's "
                        "python3-numpy python3-scipy, as "
                        "scripts/install-deps.sh does, or set "
                        "$CLOTHODE_PYTHON)");
}
