/* Internals shared by the benchmark files (bench/bench*.c): the run
 * context, the size plan of a full or quick run, cached timed runs of
 * cvode-bdf on hang, rows, clocks.  Not part of the library's interface. */
#ifndef CL_BENCH_IMPL_H
#define CL_BENCH_IMPL_H

#include "bench/bench.h"
#include "bench/child.h"
#include "integrators/integrator.h"
#include "io/config.h"
#include "system/model.h"

/* Sizes and budgets of a run (full or --quick). */
typedef struct {
    int w1_cases;            /* workload 1: (n, T) cases */
    int w1_n[2];
    double w1_t[2];
    int select;              /* the case of workload 1 that picks the solver */
    double peer_budget;      /* CPU seconds per peer run */
    int w2_n;                /* workload 2: best vs klu-full at n, T */
    double w2_t;
    bool w2_large;           /* n = 64 and 128 as well */
    double w2_cap;           /* skip n = 128 when predicted above (s) */
    int w3_nn;               /* workload 3: sizes */
    int w3_n[4];
    double w3_budget;        /* CPU seconds per (solver, n, dt) */
    double eval_budget;      /* workloads 4, 5, 7, 8: seconds per case */
    int w6_n;
    int w10_nn;              /* workload 10: sizes */
    int w10_n[3];
    double w10_budget;       /* CPU seconds per (solver, n, dt) */
    int w12_n;               /* workload 12: n, T */
    double w12_t;
    int w11_nn;              /* workload 11: sizes, T */
    int w11_n[3];
    double w11_t;
    int w13_n;               /* workload 13: the cloth size */
} cl_bplan;

/* A timed cvode-bdf run on hang, kept for the whole bench run. */
typedef struct {
    int n;
    double t_end, rtol, atol;
    char linsol[32];         /* as asked ("" for the default) */
    int max_order;           /* CVODE's highest BDF order (0: its 5) */
    char method[32];         /* "" for cvode-bdf, else a petsc-* method */
    char petsc[160];         /* its PETSc options */
    double budget;           /* CPU seconds, 0 for none (CL_EBUDGET) */
    double t_reached;        /* the last output time reached */
    cl_status rc;
    char msg[240];           /* the failure, if rc */
    double cpu, wall;        /* create + advance + free */
    long steps;
    char used[32];           /* the solver(s) that worked (cl_stats) */
    size_t nfree;
    double *x;               /* free positions at t_end, 3 nfree */
} cl_brun;

/* A peer run: its case, its files, its command line. */
typedef struct {
    int n;
    double t_end;
    char state[4096], stats[4096], errlog[4096];
    char nset[32], tset[48];
    char *argv[16];
} cl_bpeer;

typedef struct {
    const cl_bench_opts *o;
    cl_bplan plan;
    cl_bench_table *t;
    cl_bench_row spare;      /* written when the table cannot grow */
    bool nomem;
    int stopped_in;          /* the workload a signal interrupted (0: the
                              * choice of solver), or -1 */
    cl_brun **runs;
    size_t nrun;
    bool linsol_ok;          /* cvode-bdf takes --linsol */
    char best[32];           /* "" for cvode-bdf's default */
    int best_order;          /* max_order for n >= 128 (workload 2) */
    cl_child peers;          /* runs the peers one after the other */
    char problem[4096];      /* the peers' problem file */
    char budget[32];
    char python[512];
    char no_python[400];     /* why there is no peer, or "" */
    cl_bpeer peer[2];
} cl_bctx;

/* A problem with assignments, and its configuration (kept alive). */
typedef struct {
    cl_config *cfg;
    cl_model *m;
} cl_bmodel;

/* ---- bench_runs.c --------------------------------------------------- */

cl_status cl_bench_model(const cl_bctx *c, const char *problem,
                         const char *const *sets, cl_bmodel *bm,
                         cl_error *err);
void cl_bench_model_free(cl_bmodel *bm);

/* [run] dt and verlet_damping of a problem's configuration into io (dt
 * > 0 given: that one instead of [run] dt). */
cl_status cl_bench_fixed_opts(cl_config *cfg, double dt,
                              cl_integrator_opts *io, cl_error *err);

/* A timed stretch of fixed steps. */
typedef struct {
    cl_status rc;
    char msg[200];
    double cpu, wall;      /* of the timed steps */
    long steps;
    cl_stats stats;        /* the integrator's, over all steps */
} fixed_time;

typedef struct {
    long warm, chunk, min_steps;
    double budget;         /* stop once the timed steps took this (s) */
    double *x_final;       /* sys->n: the final positions, or NULL */
} fixed_plan;

/* Create the integrator on the model's initial state, take fp->warm
 * untimed steps, then time steps (fp->chunk per advance) until at least
 * fp->min_steps and fp->budget CPU seconds; the positions then into
 * fp->x_final if not NULL (bench_cost.c). */
void cl_bench_time_fixed(cl_model *m, const cl_integrator_type *type,
                         const cl_integrator_opts *io, const fixed_plan *fp,
                         fixed_time *ft);

/* cl_bench_time_fixed of semi-bdf2: CPU and wall time per step into
 * row->cpu_a, wall_a; false, the failure noted in row, if it failed. */
bool cl_bench_semi_step(cl_model *m, const cl_integrator_opts *io,
                        const fixed_plan *fp, cl_bench_row *row,
                        fixed_time *ft);

/* Least-squares slope of log(value) against log(unknowns) over the nn
 * sizes with a finite value (their count into *used unless used is NULL;
 * NaN under two). */
double cl_bench_exponent(const double *unknowns, const double *value,
                         int nn, int *used);

/* A new row of `workload`, case kase: the exponent p of semi-bdf2
 * `solver`'s time per step ~ unknowns^p, the least-squares slope of
 * log(per_step) against log(unknowns) over the nn sizes with a finite time
 * (NaN under two), judged by `goal` against target ("" for no goal); the
 * note says over how many sizes, and "fastest at the largest n" if
 * `fastest`.  Not logged yet: the caller may add to the note. */
cl_bench_row *cl_bench_fit_row(cl_bctx *c, int workload, const char *kase,
                               const char *solver, const double *unknowns,
                               const double *per_step, int nn,
                               const char *goal, double target,
                               bool fastest);

/* Process CPU and monotonic wall clocks (s). */
void cl_bench_clock(double *cpu, double *wall);

/* A round's CPU seconds per unit s into the range [*lo, *hi] of the
 * rounds so far; true if it is the fastest yet (the workloads that keep
 * the fastest of alternated rounds: 4, 5, 10). */
bool cl_bench_round_fastest(double *lo, double *hi, double s);

/* cvode-bdf on hang at n, t_end (linsol "" for the default, max_order 0
 * for CVODE's), cached; NULL only when out of memory (c->nomem set).  A
 * failed run has rc set. */
const cl_brun *cl_bench_hang(cl_bctx *c, int n, double t_end,
                             const char *linsol, int max_order, double rtol,
                             double atol);

/* The petsc-* integrator `method` with PETSc options `petsc` on hang,
 * cached as cl_bench_hang's runs; stopped with rc = CL_EBUDGET once it
 * has used `budget` CPU seconds (inside an advance: core/stop.h's
 * cl_stop_after), t_reached the last twentieth of t_end reached. */
const cl_brun *cl_bench_hang_petsc(cl_bctx *c, int n, double t_end,
                                   const char *method, const char *petsc,
                                   double rtol, double atol, double budget);

/* cvode-bdf with the best solver (max_order) on hang at n, T from rtol
 * 1e-4, tightened 10x at a time (down to 1e-8) until its distance to the
 * reference ref, *err_a, is not above err_b. */
const cl_brun *cl_bench_match(cl_bctx *c, int n, double T, int max_order,
                              const cl_brun *ref, double err_b,
                              double *err_a);

/* Free the cached runs. */
void cl_bench_runs_free(cl_bctx *c);

/* A new row (NaN figures, no goal), or c->spare if the table is full. */
cl_bench_row *cl_bench_row_add(cl_bctx *c, int workload, const char *kase);

/* Set the figure, its unit and goal, and whether it is met. */
void cl_bench_judge(cl_bench_row *r, double ratio, const char *unit,
                    const char *goal, double target);

/* Side a's run `a` at error err_a into the row (side b's CPU time and
 * error set): the speed-up cpu_b / cpu_a judged against >= target, not
 * met when err_a is above side b's error (`other`, "the peer's"). */
void cl_bench_judge_matched(cl_bench_row *r, const cl_brun *a, double err_a,
                            double target, const char *other);

/* Copy src into dst[len], cut if need be. */
void cl_bench_copy(char *dst, size_t len, const char *src);

/* Append "; "-separated text to the row's note. */
void cl_bench_note(cl_bench_row *r, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Progress: a line on the log. */
void cl_bench_log(const cl_bctx *c, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
void cl_bench_log_row(const cl_bctx *c, const cl_bench_row *r);

/* Deterministic numbers in [-1, 1) from the state *s (a linear
 * congruential generator, Knuth's MMIX constants). */
double cl_bench_uniform(unsigned long long *s);

/* "cvode-bdf LINSOL" or "cvode-bdf (default)", and ", order <= K" for a
 * max_order K > 0. */
void cl_bench_side(char *buf, size_t len, const char *linsol, int max_order);

/* ---- bench_hang.c: workloads 1, 2, 6 and the choice of solver -------- */

void cl_bench_peers_start(cl_bctx *c);
void cl_bench_choose(cl_bctx *c);
void cl_bench_w1(cl_bctx *c);
void cl_bench_w2(cl_bctx *c);
void cl_bench_w6(cl_bctx *c);
void cl_bench_peers_stop(cl_bctx *c);

/* ---- bench_cost.c: workloads 3, 4, 5, 13 ---------------------------- */

void cl_bench_w3(cl_bctx *c);
void cl_bench_w4(cl_bctx *c);
void cl_bench_w5(cl_bctx *c);
void cl_bench_w13(cl_bctx *c);

/* ---- bench_mesh.c: workload 7 --------------------------------------- */

void cl_bench_w7(cl_bctx *c);

/* ---- bench_contact.c: workload 8 ------------------------------------ */

void cl_bench_w8(cl_bctx *c);

/* ---- bench_selfcontact.c: workload 9 --------------------------------- */

void cl_bench_w9(cl_bctx *c);

/* ---- bench_amg.c: workloads 10 and 12 -------------------------------- */

void cl_bench_w10(cl_bctx *c);
void cl_bench_w12(cl_bctx *c);

/* ---- bench_amg_acc.c: workload 10 at the accuracy a step needs ------ */

void cl_bench_w10_accuracy(cl_bctx *c);
/* ---- bench_petscts.c: workload 11 ------------------------------------ */

void cl_bench_w11(cl_bctx *c);

#endif
