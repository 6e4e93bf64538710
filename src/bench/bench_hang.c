/* Benchmark workloads on hang with cvode-bdf (bench/bench.h): the choice
 * of linear solver, 1 (against the scipy peer, run in the background), 2
 * (against klu-full; large n) and 6 (peak memory of a child run). */
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <time.h>
#include <unistd.h>

#include "bench/bench_impl.h"
#include "analysis/diagnostics.h"
#include "core/stop.h"
#include "io/state.h"
#include "linalg/linsol.h"

#define RTOL 1e-4
#define ATOL 1e-6
#define REF_RTOL 1e-8     /* the reference: 1e-10 costs 235 s at n = 16 */
#define REF_ATOL 1e-10
#define TIGHTEST 1e-8     /* rtol limit when matching the peer's error */
#define W2_ORDER 2        /* workload 2: BDF order cap beside CVODE's own */
#define RSS_T_END 0.02    /* workload 6: long enough for the first setups */

/* ---- the peers in the background ----------------------------------- */

/* The command line of peer p (its strings live in c and p). */
static void peer_argv(cl_bctx *c, cl_bpeer *p)
{
    snprintf(p->nset, sizeof p->nset, "cloth.n=%d", p->n);
    snprintf(p->tset, sizeof p->tset, "run.t_end=%.17g", p->t_end);
    char *argv[] = {c->python, (char *)c->o->peer, c->problem, "--set",
                    p->nset, "--set", p->tset, "--set", "run.rtol=1e-4",
                    "--set", "run.atol=1e-6", "--max-cpu", c->budget,
                    "--out", p->state, NULL};
    memcpy(p->argv, argv, sizeof argv);
}

/* SIGTERM in the peers' process: end the whole group, the Python peer
 * under way with it. */
static void end_peers(int sig)
{
    signal(sig, SIG_DFL);
    kill(0, sig);
}

/* In a forked process: each peer in turn (no gap between them, whatever
 * the bench is doing), a failure to start written to its error log.  The
 * peers are a process group of their own, which the bench ends if a
 * signal stops it (cl_bench_peers_stop), and which ends itself if the
 * bench dies (SIGTERM on the parent's death). */
_Noreturn static void run_peers(cl_bctx *c, pid_t bench)
{
    setpgid(0, 0);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, end_peers);
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != bench)
        _exit(0);
    for (int k = 0; k < c->plan.w1_cases; k++) {
        cl_bpeer *p = &c->peer[k];
        cl_child_usage u;
        cl_error err = {0};
        if (cl_child_run(p->argv, p->stats, p->errlog, &u, &err)) {
            FILE *fp = fopen(p->errlog, "a");
            if (fp) {
                fprintf(fp, "%s\n", err.msg);
                fclose(fp);
            }
        }
    }
    _exit(0);
}

void cl_bench_peers_start(cl_bctx *c)
{
    cl_error err = {0};
    if (cl_child_python(c->python, sizeof c->python, &err)) {
        cl_bench_copy(c->no_python, sizeof c->no_python, err.msg);
        return;
    }
    snprintf(c->problem, sizeof c->problem, "%s/hang.ini", c->o->problems);
    snprintf(c->budget, sizeof c->budget, "%g", c->plan.peer_budget);
    for (int k = 0; k < c->plan.w1_cases; k++) {
        cl_bpeer *p = &c->peer[k];
        p->n = c->plan.w1_n[k];
        p->t_end = c->plan.w1_t[k];
        const char *dir = c->o->scratch;
        snprintf(p->state, sizeof p->state, "%s/peer-%d.csv", dir, k);
        snprintf(p->stats, sizeof p->stats, "%s/peer-%d.out", dir, k);
        snprintf(p->errlog, sizeof p->errlog, "%s/peer-%d.err", dir, k);
        peer_argv(c, p);
    }
    if (c->o->log)
        fflush(c->o->log);
    fflush(stdout);
    pid_t bench = getpid(), pid = fork();
    if (pid == 0)
        run_peers(c, bench);
    if (pid < 0) {
        snprintf(c->no_python, sizeof c->no_python, "cannot fork: %s",
                 strerror(errno));
        return;
    }
    setpgid(pid, pid); /* also the child's own first step (run_peers) */
    c->peers = (cl_child){.pid = pid};
    cl_bench_log(c, "  scipy peers started in the background (%s)",
                 c->python);
}

/* Wait for the peers to end (at once if they have), ending them (their
 * process group) once a signal has stopped the bench, before or during
 * the wait. */
void cl_bench_peers_stop(cl_bctx *c)
{
    cl_child_usage u;
    bool ended = false;
    while (c->peers.pid > 0 && !cl_child_done(&c->peers, &u)) {
        if (!ended && cl_stop_interrupted())
            ended = kill(-c->peers.pid, SIGTERM) == 0;
        nanosleep(&(struct timespec){0, 20000000}, NULL);
    }
}

/* The peer's "name,value" statistics. */
typedef struct {
    double cpu, wall, t;
    long steps;
    bool finished;
} peer_stats;

static bool read_peer_stats(const char *path, peer_stats *s)
{
    FILE *fp = fopen(path, "r");
    char line[256], status[64] = "";
    int got = 0;
    *s = (peer_stats){NAN, NAN, NAN, 0, false};
    if (!fp)
        return false;
    while (fgets(line, sizeof line, fp)) {
        got += sscanf(line, "cpu,%lf", &s->cpu) == 1;
        got += sscanf(line, "wall,%lf", &s->wall) == 1;
        got += sscanf(line, "t,%lf", &s->t) == 1;
        got += sscanf(line, "steps,%ld", &s->steps) == 1;
        got += sscanf(line, "status,%63s", status) == 1;
    }
    fclose(fp);
    s->finished = !strcmp(status, "finished");
    return got == 5;
}

/* The last line of a file (the peer's message), into buf. */
static void last_line(const char *path, char *buf, size_t len)
{
    FILE *fp = fopen(path, "r");
    char line[512];
    snprintf(buf, len, "no message");
    while (fp && fgets(line, sizeof line, fp))
        if (line[strspn(line, " \n")]) {
            line[strcspn(line, "\n")] = '\0';
            snprintf(buf, len, "%s", line);
        }
    if (fp)
        fclose(fp);
}

/* Free positions of the peer's final state (3 nfree), or NULL. */
static double *peer_positions(cl_bctx *c, const cl_bpeer *p, size_t nfree)
{
    char nset[32];
    snprintf(nset, sizeof nset, "cloth.n=%d", p->n);
    const char *sets[] = {nset, NULL};
    cl_bmodel bm;
    cl_error err = {0};
    if (cl_bench_model(c, "hang", sets, &bm, &err))
        return NULL;
    const cl_cloth *cl = cl_model_cloth(bm.m);
    double *x = malloc(3 * cl->np * sizeof *x);
    double *v = malloc(3 * cl->np * sizeof *v);
    double *xf = malloc(3 * nfree * sizeof *xf);
    bool ok = x && v && xf && cl->nfree == nfree &&
              cl_state_read(p->state, cl->np, x, v, &err) == CL_OK;
    if (ok)
        cl_cloth_gather(cl, x, xf);
    free(x);
    free(v);
    cl_bench_model_free(&bm);
    if (!ok) {
        free(xf);
        return NULL;
    }
    return xf;
}

/* ---- the best solver ------------------------------------------------- */

static void choose_row(cl_bctx *c, const char *kase, const cl_brun *r)
{
    cl_bench_row *row = cl_bench_row_add(c, 0, kase);
    cl_bench_side(row->side_a, sizeof row->side_a, r->linsol, 0);
    if (r->rc) {
        cl_bench_note(row, "failed: %s", r->msg);
        return;
    }
    row->cpu_a = r->cpu;
    row->wall_a = r->wall;
    cl_bench_note(row, "%ld steps", r->steps);
    if (*r->used && strcmp(r->used, r->linsol))
        cl_bench_note(row, "solver used: %s", r->used);
}

/* Time one candidate; keep it if it is the fastest so far. */
static void choose_one(cl_bctx *c, const char *kase, const char *name,
                       double *best_cpu)
{
    int k = c->plan.select;
    const cl_brun *r = cl_bench_hang(c, c->plan.w1_n[k], c->plan.w1_t[k],
                                     name, 0, RTOL, ATOL);
    if (!r)
        return;
    choose_row(c, kase, r);
    if (!r->rc && r->cpu < *best_cpu) {
        *best_cpu = r->cpu;
        cl_bench_copy(c->best, sizeof c->best, name);
    }
}

void cl_bench_choose(cl_bctx *c)
{
    int k = c->plan.select;
    double best_cpu = INFINITY;
    char kase[48], side[48];
    snprintf(kase, sizeof kase, "choice n=%d T=%g", c->plan.w1_n[k],
             c->plan.w1_t[k]);
    c->linsol_ok = cl_integrator_find("cvode-bdf")->takes_linsol;
    if (!c->linsol_ok) {
        cl_bench_row *row = cl_bench_row_add(c, 0, kase);
        cl_bench_side(row->side_a, sizeof row->side_a, "", 0);
        cl_bench_note(row, "cvode-bdf takes no --linsol: its default "
                           "solver is used throughout");
        return;
    }
    size_t first = c->t->n;
    choose_one(c, kase, "klu-full", &best_cpu);
    for (int j = 0; cl_linsol_registry[j]; j++)
        choose_one(c, kase, cl_linsol_registry[j]->name, &best_cpu);
    cl_bench_side(side, sizeof side, c->best, 0);
    for (size_t j = first; j < c->t->n; j++) {
        cl_bench_row *row = &c->t->row[j];
        cl_bench_judge(row, row->cpu_a / best_cpu, "x best", "", NAN);
        if (!strcmp(row->side_a, side))
            cl_bench_note(row, "best");
        cl_bench_log_row(c, row);
    }
}

/* ---- workload 1 ------------------------------------------------------- */

/* Peer figures into the row (the peers have ended); its final positions
 * (NULL if it did not finish, or failed). */
static double *w1_peer(cl_bctx *c, const cl_bpeer *p, cl_bench_row *row,
                       size_t nfree)
{
    peer_stats ps;
    char msg[512];
    if (*c->no_python) {
        cl_bench_note(row, "no peer: %s", c->no_python);
        return NULL;
    }
    if (!read_peer_stats(p->stats, &ps)) {
        last_line(p->errlog, msg, sizeof msg);
        cl_bench_note(row, "peer failed: %s", msg);
        return NULL;
    }
    row->cpu_b = ps.cpu;
    row->wall_b = ps.wall;
    cl_bench_note(row, "peer %ld steps", ps.steps);
    if (!ps.finished) {
        cl_bench_note(row, "peer stopped by its %g s budget at t = %.3g s: "
                      "its time and the ratio are lower bounds, errors not "
                      "compared", c->plan.peer_budget, ps.t);
        return NULL;
    }
    double *x = peer_positions(c, p, nfree);
    if (!x)
        cl_bench_note(row, "cannot read the peer's state %s", p->state);
    return x;
}

/* clothode at rtol, tightened until its error is not above err_b. */
const cl_brun *cl_bench_match(cl_bctx *c, int n, double T, int max_order,
                              const cl_brun *ref, double err_b,
                              double *err_a)
{
    double rtol = RTOL;
    const cl_brun *a = cl_bench_hang(c, n, T, c->best, max_order, rtol,
                                     ATOL);
    while (a && !a->rc) {
        *err_a = cl_max_distance(a->x, ref->x, a->nfree);
        if (!(*err_a > err_b) || rtol <= TIGHTEST * 1.01)
            break;
        rtol *= 0.1;
        a = cl_bench_hang(c, n, T, c->best, max_order, rtol,
                          ATOL * rtol / RTOL);
    }
    return a;
}

static void w1_case(cl_bctx *c, int k)
{
    int n = c->plan.w1_n[k];
    double T = c->plan.w1_t[k], err_a = NAN;
    char kase[48];
    snprintf(kase, sizeof kase, "hang n=%d T=%g", n, T);
    cl_bench_row *row = cl_bench_row_add(c, 1, kase);
    snprintf(row->side_b, sizeof row->side_b, "scipy BDF rtol 1e-4");
    const cl_brun *ref = cl_bench_hang(c, n, T, c->best, 0, REF_RTOL,
                                       REF_ATOL);
    if (!ref || ref->rc) {
        cl_bench_note(row, "reference failed: %s", ref ? ref->msg : "");
        return;
    }
    double *xb = w1_peer(c, &c->peer[k], row, ref->nfree);
    if (xb)
        row->error_b = cl_max_distance(xb, ref->x, ref->nfree);
    free(xb);
    const cl_brun *a = cl_bench_match(c, n, T, 0, ref, row->error_b,
                                      &err_a);
    if (!a || a->rc) {
        cl_bench_note(row, "clothode failed: %s", a ? a->msg : "");
        return;
    }
    snprintf(row->side_a, sizeof row->side_a, "cvode-bdf %s rtol %g",
             *c->best ? c->best : "(default)", a->rtol);
    cl_bench_judge_matched(row, a, err_a, 100.0, "the peer's");
    if (*a->used && strcmp(a->used, a->linsol))
        cl_bench_note(row, "solver used: %s", a->used);
}

void cl_bench_w1(cl_bctx *c)
{
    for (int k = 0; k < c->plan.w1_cases; k++) {
        int n = c->plan.w1_n[k];
        double T = c->plan.w1_t[k];
        cl_bench_hang(c, n, T, c->best, 0, REF_RTOL, REF_ATOL);
        cl_bench_hang(c, n, T, c->best, 0, RTOL, ATOL);
    }
    cl_bench_log(c, "  waiting for the scipy peers ...");
    cl_bench_peers_stop(c);
    for (int k = 0; k < c->plan.w1_cases; k++) {
        w1_case(c, k);
        cl_bench_log_row(c, &c->t->row[c->t->n - 1]);
    }
}

/* ---- workload 2 ------------------------------------------------------- */

/* The best solver alone at n with max_order: CPU seconds against cap. */
static const cl_brun *w2_alone(cl_bctx *c, int n, double T, int max_order,
                               double cap)
{
    char kase[48];
    snprintf(kase, sizeof kase, "hang n=%d T=%g", n, T);
    cl_bench_row *row = cl_bench_row_add(c, 2, kase);
    cl_bench_side(row->side_a, sizeof row->side_a, c->best, max_order);
    const cl_brun *a = cl_bench_hang(c, n, T, c->best, max_order, RTOL,
                                     ATOL);
    if (a && !a->rc) {
        row->cpu_a = a->cpu;
        row->wall_a = a->wall;
        cl_bench_judge(row, a->cpu, "s", "<=", cap);
        cl_bench_note(row, "%ld steps", a->steps);
    } else {
        cl_bench_note(row, "failed: %s", a ? a->msg : "");
    }
    cl_bench_log_row(c, row);
    return a && !a->rc ? a : NULL;
}

static const cl_brun *w2_ratio(cl_bctx *c, int n, double T)
{
    char kase[48];
    snprintf(kase, sizeof kase, "hang n=%d T=%g", n, T);
    cl_bench_row *row = cl_bench_row_add(c, 2, kase);
    cl_bench_side(row->side_a, sizeof row->side_a, c->best, 0);
    cl_bench_side(row->side_b, sizeof row->side_b, "klu-full", 0);
    const cl_brun *a = cl_bench_hang(c, n, T, c->best, 0, RTOL, ATOL);
    const cl_brun *b = c->linsol_ok ? cl_bench_hang(c, n, T, "klu-full", 0,
                                                    RTOL, ATOL) : NULL;
    if (!a || !b || a->rc || b->rc) {
        cl_bench_note(row, "%s", !c->linsol_ok ? "cvode-bdf takes no "
                      "--linsol: no klu-full to compare with" :
                      a && a->rc ? a->msg : b && b->rc ? b->msg : "");
        cl_bench_log_row(c, row);
        return a && !a->rc ? a : NULL;
    }
    row->cpu_a = a->cpu;
    row->cpu_b = b->cpu;
    row->wall_a = a->wall;
    row->wall_b = b->wall;
    cl_bench_judge(row, b->cpu / a->cpu, "x", ">=", 20.0);
    cl_bench_note(row, "%ld vs %ld steps, final positions %.2g m apart",
                  a->steps, b->steps,
                  cl_max_distance(a->x, b->x, a->nfree));
    cl_bench_log_row(c, row);
    return a;
}

/* The ratio at w2_n compares linear solvers at CVODE's own orders.  At
 * 2 w2_n both CVODE's orders (up to 5) and BDF2 at most are timed: the
 * cloth's fast, lightly damped modes lie near the imaginary axis, where
 * BDF3-5 are not stable, and as n grows (higher frequencies) capping the
 * order takes fewer steps (n = 128, T = 0.3: 1779 steps against 5096).
 * The faster of the two runs 4 w2_n. */
void cl_bench_w2(cl_bctx *c)
{
    double T = c->plan.w2_t;
    const cl_brun *a32 = w2_ratio(c, c->plan.w2_n, T);
    if (!c->plan.w2_large)
        return;
    const cl_brun *d64 = w2_alone(c, 2 * c->plan.w2_n, T, 0, 60.0);
    const cl_brun *o64 = w2_alone(c, 2 * c->plan.w2_n, T, W2_ORDER, 60.0);
    const cl_brun *a64 = !o64 || (d64 && d64->cpu <= o64->cpu) ? d64 : o64;
    c->best_order = a64 == o64 ? W2_ORDER : 0;
    double predicted = a32 && a64 ? a64->cpu * (a64->cpu / a32->cpu) : NAN;
    if (predicted <= c->plan.w2_cap) {
        w2_alone(c, 4 * c->plan.w2_n, T, c->best_order, 300.0);
        return;
    }
    char kase[48];
    snprintf(kase, sizeof kase, "hang n=%d T=%g", 4 * c->plan.w2_n, T);
    cl_bench_row *row = cl_bench_row_add(c, 2, kase);
    cl_bench_side(row->side_a, sizeof row->side_a, c->best, c->best_order);
    cl_bench_judge(row, NAN, "s", "<=", 300.0);
    cl_bench_note(row, "skipped: n = %d -> %d growth predicts %.0f s CPU "
                  "(cap %.0f s)", c->plan.w2_n, 2 * c->plan.w2_n, predicted,
                  c->plan.w2_cap);
    cl_bench_log_row(c, row);
}

/* ---- workload 6 ------------------------------------------------------- */

/* The peak resident memory of this process (VmHWM of /proc/self/status:
 * the high-water mark of its own address space). */
static cl_status read_vmhwm(long *kb, cl_error *err)
{
    FILE *fp = fopen("/proc/self/status", "r");
    char line[256];
    *kb = -1;
    while (fp && fgets(line, sizeof line, fp) &&
           sscanf(line, "VmHWM: %ld", kb) != 1)
        ;
    if (fp)
        fclose(fp);
    return *kb >= 0 ? CL_OK
                    : cl_error_set(err, CL_EUNSUPPORTED, "no VmHWM in "
                                   "/proc/self/status");
}

cl_status cl_bench_peak_memory(const cl_bench_opts *o, int n,
                               const char *linsol, long *peak_kb,
                               cl_error *err)
{
    cl_bench_opts quiet = *o;
    quiet.log = NULL;
    cl_bctx c = {.o = &quiet};
    const cl_brun *r = cl_bench_hang(&c, n, RSS_T_END, linsol, 0, RTOL,
                                     ATOL);
    cl_status rc = !r ? cl_error_set(err, CL_ENOMEM, "out of memory")
                   : r->rc ? cl_error_set(err, r->rc, "%s", r->msg)
                           : read_vmhwm(peak_kb, err);
    cl_bench_runs_free(&c);
    return rc;
}

/* Peak memory (KiB) of `clothode-bench --peak-memory N:LINSOL` in a child
 * process, and its CPU time; false with the message in err if it failed.
 * (The child reads its own VmHWM: the ru_maxrss of a posix_spawn child
 * also counts its parent's peak, whose address space it shares until
 * exec.) */
static bool w6_child(cl_bctx *c, int n, const char *linsol, long *kb,
                     cl_child_usage *u, cl_error *err)
{
    char arg[64], out[4096], line[128];
    snprintf(arg, sizeof arg, "%d:%s", n, linsol);
    snprintf(out, sizeof out, "%s/peak-%d.out", c->o->scratch, n);
    char *argv[] = {(char *)c->o->self, "--peak-memory", arg, NULL};
    cl_bench_log(c, "  cvode-bdf %s, n = %d: child run for its peak "
                 "memory ...", *linsol ? linsol : "(default)", n);
    *kb = -1;
    if (cl_child_run(argv, out, NULL, u, err))
        return false;
    FILE *fp = fopen(out, "r");
    while (fp && fgets(line, sizeof line, fp))
        sscanf(line, "peak_kb,%ld", kb);
    if (fp)
        fclose(fp);
    if (*kb < 0)
        cl_error_set(err, CL_EIO, "%s %s %s: no peak_kb line", argv[0],
                     argv[1], argv[2]);
    return *kb >= 0;
}

/* Free particles of hang at n (0 if the model cannot be built). */
static size_t w6_free(cl_bctx *c, int n)
{
    char nset[32];
    snprintf(nset, sizeof nset, "cloth.n=%d", n);
    const char *sets[] = {nset, NULL};
    cl_bmodel bm;
    cl_error err = {0};
    if (cl_bench_model(c, "hang", sets, &bm, &err))
        return 0;
    size_t nfree = cl_model_cloth(bm.m)->nfree;
    cl_bench_model_free(&bm);
    return nfree;
}

static void w6_one(cl_bctx *c, const char *linsol)
{
    int n = c->plan.w6_n;
    char kase[48];
    snprintf(kase, sizeof kase, "hang n=%d T=%g", n, RSS_T_END);
    cl_bench_row *row = cl_bench_row_add(c, 6, kase);
    cl_bench_side(row->side_a, sizeof row->side_a, linsol, 0);
    double unknowns = 6.0 * (double)w6_free(c, n);
    double base_unknowns = 6.0 * (double)w6_free(c, 8);
    long kb, base_kb;
    cl_child_usage u, base;
    cl_error err = {0};
    if (!w6_child(c, n, linsol, &kb, &u, &err) ||
        !w6_child(c, 8, linsol, &base_kb, &base, &err) || !(unknowns > 0)) {
        cl_bench_note(row, "%s", *err.msg ? err.msg : "no model");
        cl_bench_log_row(c, row);
        return;
    }
    row->cpu_a = u.cpu;
    row->wall_a = u.wall;
    cl_bench_judge(row, 1024.0 * (double)kb / unknowns, "B/unknown", "",
                   NAN);
    cl_bench_note(row, "peak RSS %.1f MiB for %.0f unknowns; %.0f B per "
                  "unknown above the n = 8 run (%.1f MiB)", kb / 1024.0,
                  unknowns, 1024.0 * (double)(kb - base_kb) /
                                (unknowns - base_unknowns),
                  base_kb / 1024.0);
    cl_bench_log_row(c, row);
}

/* The best solver only: klu-full at n = 128 needs minutes for its first
 * factorisations. */
void cl_bench_w6(cl_bctx *c)
{
    w6_one(c, c->best);
}
