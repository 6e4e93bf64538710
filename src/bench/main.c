/* clothode-bench: the benchmark workloads (bench/bench.h), a table on
 * stdout, progress on stderr, results/bench.csv.  A program of its own
 * on libclothode: the library holds the numerics, not the harness. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <ftw.h>
#include <getopt.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <time.h>
#include <unistd.h>

#include "bench/bench.h"
#include "cli/cli.h"
#include "core/stop.h"
#include "io/atomic.h"

static const char bench_help[] =
    "usage: clothode-bench [options]\n"
    "Time the workloads and compare them with their goals; print a table\n"
    "and write it as CSV.  Run from the repository root (problems/, the\n"
    "scipy peer scripts/peers/hang_scipy.py).  CPU time is reported.\n"
    "\n"
    "  0  the best linear solver for cvode-bdf on hang n = 16, T = 2 s\n"
    "  1  hang: cvode-bdf (best linear solver) vs the scipy peer, >= 100x\n"
    "  2  hang T = 2 s: best vs klu-full at n = 32, >= 20x; n = 64 <= 60 s,\n"
    "     n = 128 <= 300 s\n"
    "  3  semi-bdf2 per step for every linear solver, n = 16..128: size\n"
    "     exponent <= 1.2, best vs klu at n = 64 >= 30x\n"
    "  4  force evaluation at n = 64: <= 10 ns per pair\n"
    "  5  explicit mass-spring steps (symplectic-euler, verlet) on a\n"
    "     30 x 30 cloth: >= 25,000 steps/s; verlet-pbd beside them\n"
    "  6  peak memory per unknown of cvode-bdf at n = 128\n"
    "  7  nearest triangle among 20480: bounding-volume tree vs trying all,\n"
    "     >= 50x for points near the surface\n"
    "  8  skirt step (over the sphere, on the floor): contact term + hook\n"
    "     <= 25 % of a step\n"
    "  9  fold step: self-contact term <= 10 % of a step\n"
    " 10  semi-bdf2 n = 64..256: amg vs the one-level solvers, exponent\n"
    "     <= 1.15, amg >= 3x (dt 1e-2) and >= 1.5x (dt 1e-3) at n = 256;\n"
    "     then pcg and amg at dt = 1e-2 x 64/n (the same Courant number)\n"
    " 11  hang n = 32..128: cvode-bdf vs the best petsc-ts, >= 3x\n"
    " 12  hang n = 256, T = 2 s by semi-bdf2 amg: <= 600 s CPU (long: runs\n"
    "     only when named in --only)\n"
    " 13  semi-bdf2 pcg at n = 128: wall time with --threads 2, >= 1.6x\n"
    "\n"
    "  --quick        a reduced set (smaller n and T), about two minutes\n"
    "  --only LIST    only these workloads, e.g. --only 3,4\n"
    "  --out FILE     CSV file (default results/bench.csv)\n"
    "  --peer FILE    the peer script (default scripts/peers/hang_scipy.py)\n"
    "  --peak-memory N:LINSOL\n"
    "                 workload 6's child: cvode-bdf (LINSOL, empty for the\n"
    "                 default) on hang at n = N to T = 0.02 s; prints\n"
    "                 peak_kb,VALUE (its VmHWM) and nothing else\n"
    "  --help         this text\n"
    "The peer runs with $CLOTHODE_PYTHON, else the first of python3 on PATH\n"
    "and /usr/bin/python3 that has numpy and scipy.\n"
    "SIGINT (Ctrl-C) or SIGTERM stops the bench within the run under way;\n"
    "the rows of the workloads it finished are printed and written (exit\n"
    "status 6).\n";

/* A usage error: one message and the pointer to --help; exit status 2. */
static int usage_error(const char *fmt, ...)
    __attribute__((format(printf, 1, 2)));
static int usage_error(const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "clothode-bench: ");
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(see 'clothode-bench --help')\n");
    return 2;
}

typedef struct {
    cl_bench_opts o;
    const char *out;
    const char *peak;   /* --peak-memory N:LINSOL, or NULL */
} bench_args;

/* "1,3" -> bits 1 and 3; -1 if malformed. */
static int parse_only(const char *s, unsigned *bits)
{
    *bits = 0;
    for (const char *p = s; *p;) {
        char *end;
        long w = strtol(p, &end, 10);
        if (end == p || w < 1 || w > CL_BENCH_WORKLOADS ||
            (*end && *end != ','))
            return -1;
        *bits |= 1u << w;
        p = *end ? end + 1 : end;
    }
    return *bits ? 0 : -1;
}

static int parse_args(int argc, char **argv, bench_args *a)
{
    static const struct option opts[] = {
        {"quick", no_argument, 0, 'q'}, {"only", required_argument, 0, 'w'},
        {"out", required_argument, 0, 'o'},
        {"peer", required_argument, 0, 'p'},
        {"peak-memory", required_argument, 0, 'm'},
        {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0}};
    int c;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        if (c == 'h') {
            fputs(bench_help, stdout);
            return -2;
        } else if (c == 'q') {
            a->o.quick = true;
        } else if (c == 'o') {
            a->out = optarg;
        } else if (c == 'p') {
            a->o.peer = optarg;
        } else if (c == 'm') {
            a->peak = optarg;
        } else if (c == 'w' && parse_only(optarg, &a->o.only)) {
            return usage_error("--only \"%s\": expected workload numbers "
                               "1..%d separated by commas", optarg,
                               CL_BENCH_WORKLOADS),
                   -1;
        } else if (c != 'w') {
            return usage_error("unknown or incomplete option '%s'",
                               argv[optind - 1]),
                   -1;
        }
    }
    if (optind != argc)
        return usage_error("unexpected argument '%s'", argv[optind]), -1;
    return 0;
}

static int rm_entry(const char *path, const struct stat *st, int flag,
                    struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    remove(path);
    return 0;
}

/* The directory part of path made to exist. */
static cl_status make_parent(const char *path, cl_error *err)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (!slash || slash == dir)
        return CL_OK;
    *slash = '\0';
    return cl_mkdir_p(dir, err);
}

static void summary(const cl_bench_table *t, double cpu, double wall)
{
    int met = 0, goals = 0;
    for (size_t k = 0; k < t->n; k++) {
        goals += t->row[k].met >= 0;
        met += t->row[k].met == 1;
    }
    printf("%d of %d goals met; the bench took %.0f s CPU, %.0f s wall\n",
           met, goals, cpu, wall);
}

static int bench(bench_args *a)
{
    char self[4096], scratch[4096];
    const char *tmp = getenv("TMPDIR");
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    snprintf(scratch, sizeof scratch, "%s/clothode-bench-XXXXXX",
             tmp && *tmp ? tmp : "/tmp");
    cl_error err = {0};
    if (n <= 0 || !mkdtemp(scratch))
        return cl_cli_fail(&(cl_error){CL_EIO, "bench: cannot find the "
                                       "program or make a scratch directory"});
    self[n] = '\0';
    a->o.self = self;
    a->o.scratch = scratch;
    struct timespec c0, w0, c1, w1;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
    clock_gettime(CLOCK_MONOTONIC, &w0);
    cl_bench_table t = {0};
    cl_stop_install();
    cl_status rc = cl_bench_run(&a->o, &t, &err);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
    clock_gettime(CLOCK_MONOTONIC, &w1);
    nftw(scratch, rm_entry, 16, FTW_DEPTH | FTW_PHYS);
    /* a bench a signal interrupted writes the rows of the workloads it
     * finished, if any */
    bool write = !rc || (rc == CL_EINTR && t.n > 0);
    cl_error werr = {0};
    cl_status wrc = write ? make_parent(a->out, &werr) : CL_OK;
    if (write && !wrc)
        wrc = cl_bench_write_csv(a->out, &t, &werr);
    if (wrc && rc)
        cl_cli_fail(&werr);
    else if (wrc) {
        rc = wrc;
        err = werr;
    }
    if (t.n) {
        cl_bench_print(&t, stdout);
        summary(&t, (double)(c1.tv_sec - c0.tv_sec) +
                        1e-9 * (double)(c1.tv_nsec - c0.tv_nsec),
                (double)(w1.tv_sec - w0.tv_sec) +
                    1e-9 * (double)(w1.tv_nsec - w0.tv_nsec));
        if (write && !wrc)
            printf("results in %s\n", a->out);
    }
    cl_bench_table_free(&t);
    return rc ? cl_cli_fail(&err) : 0;
}

/* --peak-memory N:LINSOL, the child of workload 6: it ends (SIGTERM)
 * when its parent does, so that a bench killed outright (SIGKILL) leaves
 * no run behind (a parent that dies in the milliseconds before the prctl
 * is not seen). */
static int peak_memory(bench_args *a)
{
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    char *end;
    long n = strtol(a->peak, &end, 10);
    if (end == a->peak || *end != ':' || n < 3 || n > 4096)
        return usage_error("--peak-memory \"%s\": expected N:LINSOL "
                           "with N >= 3", a->peak);
    long kb;
    cl_error err = {0};
    if (cl_bench_peak_memory(&a->o, (int)n, end + 1, &kb, &err))
        return cl_cli_fail(&err);
    printf("peak_kb,%ld\n", kb);
    return 0;
}

int main(int argc, char **argv)
{
    bench_args a = {.o = {.problems = cl_cli_problems_dir(),
                          .peer = "scripts/peers/hang_scipy.py",
                          .log = stderr},
                    .out = "results/bench.csv"};
    int rc = parse_args(argc, argv, &a);
    return rc == -2 ? 0 : rc < 0 ? 2 : a.peak ? peak_memory(&a) : bench(&a);
}
