/* Child processes for the benchmarks (`clothode-bench`): start a program
 * with posix_spawnp, its stdout and stderr into files, and collect its exit
 * status with its own resource usage (wait4: user + system CPU time and
 * peak resident set size of that child alone), without blocking if asked.
 *
 *   cl_child c;
 *   if (cl_child_start(&c, argv, "out.txt", NULL, err)) return err->code;
 *   ...                               (other work; cl_child_done polls)
 *   cl_child_usage u;
 *   cl_child_wait(&c, &u);
 *
 * Also finds a Python interpreter for the scipy peer
 * (scripts/peers/hang_scipy.py). */
#ifndef CL_CHILD_H
#define CL_CHILD_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

#include "core/error.h"

typedef struct {
    pid_t pid;       /* 0: not running */
    double t0;       /* start (monotonic clock, s) */
} cl_child;

typedef struct {
    bool exited;     /* ended by exit (status valid), else by a signal */
    int status;      /* exit status */
    int signal;      /* the signal that ended it, 0 if none */
    double cpu;      /* user + system CPU seconds of the child */
    double wall;     /* seconds from start to the end being seen */
    long maxrss_kb;  /* peak resident set size (KiB) */
} cl_child_usage;

/* Start argv[0] (looked up in PATH when it has no '/') with argv, stdin
 * from /dev/null, stdout into out_path and stderr into err_path (each
 * truncated; NULL for /dev/null).  CL_EIO naming the program or file. */
cl_status cl_child_start(cl_child *c, char *const argv[],
                         const char *out_path, const char *err_path,
                         cl_error *err);

/* Non-blocking: true once the child has ended, with *u filled and c->pid
 * reset; false while it runs. */
bool cl_child_done(cl_child *c, cl_child_usage *u);

/* Wait until the child ends (polled every 10 ms); *u as for
 * cl_child_done.  Once SIGINT or SIGTERM has asked this process to stop
 * (cl_stop_interrupted), the child gets SIGTERM. */
void cl_child_wait(cl_child *c, cl_child_usage *u);

/* Start, wait, and report success: exit status 0 (else CL_EIO with the
 * status or signal, naming argv[0]). */
cl_status cl_child_run(char *const argv[], const char *out_path,
                       const char *err_path, cl_child_usage *u,
                       cl_error *err);

/* A Python 3 that imports numpy and scipy: $CLOTHODE_PYTHON if set (and
 * then only it), else the first of python3 on PATH and /usr/bin/python3
 * that does (a Python of one's own earlier on PATH may lack Debian's
 * python3-scipy).  Its name goes into buf; if there is none,
 * CL_EUNSUPPORTED naming what was tried and the packages to install. */
cl_status cl_child_python(char *buf, size_t len, cl_error *err);

#endif
