/* Benchmarks (`clothode-bench`, README "Benchmarks"): cost of the
 * integrators and linear solvers on the default problem, against goals.
 * Workloads:
 *
 *   1  hang, cvode-bdf with the best linear solver against the scipy peer
 *      (scripts/peers/hang_scipy.py: solve_ivp BDF, analytic sparse
 *      Jacobian) at rtol 1e-4, at equal or better error: n = 16, T = 2 s
 *      and n = 32, T = 0.5 s; goal >= 100x.  If clothode's error is larger
 *      than the peer's, its rtol is tightened (10x at a time) until it is
 *      not.  The peer runs in a child process, started first so that it
 *      works on the second core while the rest runs (CPU times are
 *      compared, not wall); it is stopped after a CPU budget, and then its
 *      time is a lower bound.
 *   2  hang, T = 2 s: the best solver against klu-full (KLU on the
 *      first-order system, the plain design) at n = 32, goal >= 20x; the
 *      best solver alone at n = 64 (goal <= 60 s CPU) and n = 128 (<= 300
 *      s; skipped with a note when the n = 32 -> 64 growth predicts more
 *      than the cap).
 *   3  semi-bdf2, dt = 1e-3 and 1e-2, n = 16, 32, 64, 128: CPU time per
 *      step for every registered linear solver (after two untimed steps),
 *      the fitted exponent of time against unknowns (goal <= 1.2 for the
 *      fastest solver at the largest n), and that solver against klu at
 *      n = 64 (goal >= 30x).
 *   4  force evaluations of hang at n = 64 on a perturbed state (Type2
 *      buckling branch active), ns per pair (Type1 + Type2, damping and
 *      gravity included): goal <= 10; the Jacobian's cost beside it.
 *   5  explicit steps on a 30 x 30 cloth (the size of the Verlet-and-PBD
 *      report's cloth): symplectic-euler and verlet on
 *      problems/ms-hang.ini (springs; springs + axial spring damping),
 *      verlet-pbd on problems/verlet-scene1.ini (constraint level 2, 10
 *      iterations): steps per CPU second, goal >= 25,000.
 *   6  peak resident memory per unknown (6 per free particle) of
 *      cvode-bdf with the best solver on hang at n = 128, T = 0.02 s (past
 *      the first factorisations), run in a child process (`clothode
 *      bench --peak-memory`, which reports its own VmHWM); the note gives
 *      the bytes per unknown above a run at n = 8 (program, libraries and
 *      fixed buffers taken out).
 *   7  the contact layer's nearest-triangle query (contact/bvh.h): CPU
 *      time per point of the bounding-volume tree against trying every
 *      triangle, on an icosphere of 20480 triangles and 10^4 points
 *      around it; goal >= 50x.
 *   8  the contact share of a skirt step (problems/skirt.ini, its
 *      symplectic-euler-x at dt = 2e-4 s) over 500 steps from t = 0.5 s
 *      (over the sphere) and from t = 3 s (on the floor): CPU time of the
 *      contact term plus the contact hook, replayed on the recorded
 *      calls of those steps, over that of a step; goal <= 25 %.
 *   9  self-contact in a step of problems/fold.ini (semi-be, dt = 1e-3
 *      s) at t = 2.5 s, the cloth folded onto itself: CPU time of the
 *      self-contact term's evaluations of a step (spatial hash, close
 *      pairs, forces, lumped Jacobian) over that of the step; goal <=
 *      10 %.
 *  10  algebraic multigrid: semi-bdf2 on hang, dt = 1e-3 and 1e-2, n = 64,
 *      128, 256: time per step of amg and amg-hypre beside pcg, cholmod
 *      and klu, exponents against unknowns (goal <= 1.15 for the fastest
 *      at dt = 1e-2), amg against the fastest one-level solver at n = 256
 *      (goals >= 3x at dt = 1e-2, >= 1.5x at dt = 1e-3; the two timed
 *      at every n in three alternated rounds, the fastest kept)
 *      (bench_amg.c);
 *      then at dt = 1e-2 and n = 64, 128, 256, at one accuracy: pcg and
 *      amg each at the loosest lin_tol whose state stays within 1 % of
 *      the step's error of the exact linear steps (cholmod's), amg
 *      against the faster of pcg and cholmod at n = 256 (goal >= 3x) and
 *      the exponents (goal <= 1.15 for the fastest) (bench_amg_acc.c).
 *  11  hang, T = 2 s, n = 32, 64, 128: cvode-bdf with the best solver
 *      against the best petsc-ts configuration (bench_petscts.c) at equal
 *      or better error (clothode's rtol tightened from 1e-4 as in
 *      workload 1); goal: clothode >= 3x faster.  PETSc's CPU budget is 4
 *      times clothode's at rtol 1e-4: stopped there, the goal is met.
 *  12  hang n = 256, T = 2 s by semi-bdf2 --linsol amg at dt = 1e-2, lin_tol
 *      1e-6 (bench_amg.c): CPU seconds, goal <= 600; run only when named
 *      (--only 12).
 *  13  semi-bdf2 with pcg on hang at n = 128 (--quick: 64): wall time
 *      per step with one thread over that with --threads 2 (forces,
 *      Jacobians, the solver's products; system/model.h); goal >= 1.6x.
 *
 * The best solver for cvode-bdf is picked once per run: every name of the
 * linear-solver registry plus klu-full, timed on the first case of
 * workload 1 (rows of workload 0), the least CPU time wins (if cvode-bdf
 * takes no --linsol, its default is used and a note says so).  Errors are
 * the largest distance between final particle positions and those of a
 * reference run (cvode-bdf, best solver, rtol 1e-8, atol 1e-10, same n
 * and T; 1e-10 would take minutes), computed once per run.  Times are
 * process CPU time (clock_gettime(CLOCK_PROCESS_CPUTIME_ID)) of the timed
 * work beside its wall time; children are measured by wait4.  --quick
 * runs a reduced set (smaller n and T) in about two minutes. */
#ifndef CL_BENCH_H
#define CL_BENCH_H

#include <stdbool.h>
#include <stdio.h>

#include "core/error.h"

#define CL_BENCH_WORKLOADS 13

typedef struct {
    bool quick;
    unsigned only;          /* bit w (1..13) selects workload w; 0: all
                             * but 12 */
    const char *problems;   /* directory of the problem files */
    const char *peer;       /* the peer script */
    const char *self;       /* the clothode-bench program, for child runs */
    const char *scratch;    /* directory for child outputs (must exist) */
    FILE *log;              /* progress lines, or NULL */
} cl_bench_opts;

/* One result line.  cpu_*, wall_* are seconds of the timed unit (a whole
 * run; one step in workload 3; one evaluation in workload 4; one point in
 * workload 7; one step's share in workloads 8 and 9); ratio is the measured
 * figure in `unit` (x for a speed-up, s, ns/pair, steps/s, B/unknown, %,
 * or empty for an exponent), compared
 * with target by goal (">=" or "<="; "" when there is none).  NaN where
 * not measured. */
typedef struct {
    int workload;
    char kase[48];
    char side_a[64], side_b[64];
    double cpu_a, cpu_b, wall_a, wall_b;
    double error_a, error_b;   /* m, against the reference */
    double ratio;
    char unit[12];
    char goal[3];
    double target;
    int met;                   /* 1 met, 0 not, -1 no goal or no figure */
    char note[200];
} cl_bench_row;

typedef struct {
    cl_bench_row *row;
    size_t n, cap;
} cl_bench_table;

/* Run the selected workloads, appending rows to t (rows of a workload
 * that cannot run carry a note instead of figures).  Fails only for
 * CL_ENOMEM, bad options, and CL_EINTR once SIGINT or SIGTERM has asked
 * to stop (core/stop.h, its handler installed by the caller): then t holds
 * the rows of the workloads finished before the signal, and the scipy
 * peers are ended. */
cl_status cl_bench_run(const cl_bench_opts *o, cl_bench_table *t,
                       cl_error *err);

/* The table as CSV (header workload,case,side_a,side_b,cpu_a,cpu_b,wall_a,
 * wall_b,error_a,error_b,ratio,unit,goal,target,met,note), atomically. */
cl_status cl_bench_write_csv(const char *path, const cl_bench_table *t,
                             cl_error *err);

/* The table for people: one line per row, notes below. */
void cl_bench_print(const cl_bench_table *t, FILE *fp);

void cl_bench_table_free(cl_bench_table *t);

/* Workload 6's child: cvode-bdf on hang at n with linsol ("" for the
 * default) to T = 0.02 s in this process, then its peak resident memory
 * (VmHWM, KiB). */
cl_status cl_bench_peak_memory(const cl_bench_opts *o, int n,
                               const char *linsol, long *peak_kb,
                               cl_error *err);

#endif
