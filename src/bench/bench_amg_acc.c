/* Workload 10 at the accuracy a step needs (bench/bench.h; the rest of
 * workload 10 is bench_amg.c): amg against the one-level solvers on hang
 * at dt = W10A_DT, every iterative solver at the loosest lin_tol of one
 * ladder whose state stays within a share of the step's own error.
 *
 * Why not at one lin_tol: the test bounds the residual, ||b - A x||_2 <=
 * lin_tol ||b||_2, and which modes of the error a solver still carries
 * when it passes depends on its preconditioner (an error in the softest
 * modes leaves a small residual).  At n = 256, lin_tol 1e-6, amg's largest
 * position error after 12 steps is 700 times pcg's (paper/findings.md,
 * "The same lin_tol is not the same error").  So here the accuracy is set
 * by the integration, the same for every solver, and each solver finds
 * its own tolerance for it:
 *
 *   reference   semi-bdf2 with cholmod, whose linear steps are exact to
 *               rounding, over W10A_STEPS steps; its time a step is
 *               cholmod's, which meets any accuracy;
 *   step error  the largest particle distance between that state and the
 *               one at dt/2 (amg at lin_tol W10A_FINE_TOL, its linear error
 *               under 1e-12 m); for a second-order method 3/4 of the dt
 *               run's own error;
 *   accuracy    W10A_SHARE of the step error: within it, a solver moves
 *               every error the integration reports by about 1 % at most;
 *   a solver    the loosest lin_tol of w10a_ladder whose largest particle
 *               distance from the reference is within the accuracy (the
 *               ladder is walked from its loose end, as a user would, and
 *               the errors need not fall with the tolerance); its CPU time
 *               a step over the steps after the first W10A_WARM, as in
 *               the rest of workload 10, the runs repeated up to the
 *               workload's CPU budget (cholmod's too), in W10A_ROUNDS
 *               such rounds that alternate between pcg and amg, the
 *               fastest kept.
 *
 * At every size of the plan (n = 64, 128, 256), rows: the reference and
 * the step error; pcg and amg at their lin_tol (the looser rungs tried,
 * and their errors, in the note).  Then amg against the faster of pcg and
 * cholmod at the largest n, goal >= 3x, and each solver's exponent of
 * time a step against unknowns, goal <= 1.15 for the fastest at the
 * largest n: the goals of the rest of workload 10, at one accuracy
 * instead of at one lin_tol. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench_impl.h"

#define W10A_DT 1e-2
#define W10A_WARM 2         /* untimed steps: semi-be start, first BDF2 */
#define W10A_STEPS 12       /* in all: t = 0.12 s at dt = 1e-2 */
#define W10A_SHARE 1e-2     /* the accuracy: this share of the step error */
#define W10A_FINE_TOL 1e-10 /* the dt/2 run's lin_tol */
/* Timed rounds of pcg and amg at their lin_tol, alternated (the ladder's
 * last run the first), the fastest kept: the two are compared at one n,
 * and a host whose speed drifts over minutes would otherwise decide. */
#define W10A_ROUNDS 3

static const double w10a_ladder[] = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5,
                                     1e-5, 3e-6, 1e-6, 1e-7, 1e-8, 1e-9,
                                     1e-10};
#define W10A_RUNGS (sizeof w10a_ladder / sizeof w10a_ladder[0])

/* A solver's figures at the accuracy (kept here, not as a row: rows move
 * as the table grows). */
typedef struct {
    bool ok;
    const char *linsol;
    double lin_tol;         /* 0 for a direct solver */
    double cpu, wall;       /* s a timed step: the fastest round */
    double cpu_max;         /* ... the slowest */
    int rounds;
    double error, rms;      /* m, distance from the reference */
    int tried;              /* looser rungs tried before, their errors: */
    double tried_tol[W10A_RUNGS], tried_err[W10A_RUNGS];
    char failed[160];       /* a run that failed, or "" */
} w10a_result;

typedef struct {
    cl_model *m;
    size_t n;               /* position unknowns, 3 a free particle */
    double *ref;            /* the reference positions at W10A_STEPS dt */
    double *x;              /* a run's positions there */
    double accuracy;        /* m */
} w10a_ctx;

/* Largest and rms particle distance between positions x and ref.  A NaN
 * in x makes the largest NaN. */
static void w10a_distance(const double *x, const double *ref, size_t n,
                          double *largest, double *rms)
{
    double big = 0.0, sum = 0.0;
    for (size_t p = 0; p + 2 < n; p += 3) {
        double dx = x[p] - ref[p], dy = x[p + 1] - ref[p + 1],
               dz = x[p + 2] - ref[p + 2], d2 = dx * dx + dy * dy + dz * dz;
        sum += d2;
        big = fmax(big, d2);
    }
    *largest = isnan(sum) ? NAN : sqrt(big);
    *rms = sqrt(sum / (double)(n / 3));
}

/* semi-bdf2 with `linsol` at lin_tol (0: its default) and step dt, warm
 * untimed then timed steps; the final positions into a->x.  CPU seconds a
 * timed step into row->cpu_a; false, the failure noted, if it failed. */
static bool w10a_run(w10a_ctx *a, const char *linsol, double lin_tol,
                     double dt, long warm, long timed, cl_bench_row *row)
{
    cl_integrator_opts io = {.dt = dt, .linsol = linsol, .lin_tol = lin_tol};
    fixed_plan fp = {warm, 1, timed, 0.0, a->x};
    fixed_time ft;
    return cl_bench_semi_step(a->m, &io, &fp, row, &ft);
}

/* Time res's solver at its lin_tol over runs of the same steps until
 * their timed steps took the workload's budget of CPU (small n: one run
 * of 10 steps takes tenths of a second), the first run's figures already
 * in row; CPU and wall time a step over all of them into row. */
static void w10a_repeat(const cl_bctx *c, w10a_ctx *a, const w10a_result *res,
                       cl_bench_row *row)
{
    const long steps = W10A_STEPS - W10A_WARM;
    double cpu = row->cpu_a * steps, wall = row->wall_a * steps;
    int runs = 1;
    while (cpu < c->plan.w10_budget &&
           w10a_run(a, res->linsol, res->lin_tol, W10A_DT, W10A_WARM, steps,
                    row)) {
        cpu += row->cpu_a * steps;
        wall += row->wall_a * steps;
        runs++;
    }
    row->cpu_a = cpu / (double)(runs * steps);
    row->wall_a = wall / (double)(runs * steps);
}

/* The reference (cholmod) and the step error: the rows of both; cholmod's
 * time a step into *ref. */
static bool w10a_reference(cl_bctx *c, w10a_ctx *a, const char *kase,
                           w10a_result *ref)
{
    cl_bench_row *row = cl_bench_row_add(c, 10, kase);
    snprintf(row->side_a, sizeof row->side_a, "semi-bdf2 cholmod");
    cl_bench_log(c, "  semi-bdf2 cholmod, dt = %g (reference) ...", W10A_DT);
    bool ok = w10a_run(a, "cholmod", 0.0, W10A_DT, W10A_WARM,
                       W10A_STEPS - W10A_WARM, row);
    if (!ok) {
        cl_bench_log_row(c, row);
        return false;
    }
    double *swap = a->ref, rms;
    a->ref = a->x;
    a->x = swap;
    *ref = (w10a_result){.ok = true, .linsol = "cholmod", .rounds = 1};
    w10a_repeat(c, a, ref, row);
    ref->cpu = ref->cpu_max = row->cpu_a;
    ref->wall = row->wall_a;
    cl_bench_note(row, "the reference: exact linear steps to t = %g s",
                  W10A_STEPS * W10A_DT);
    cl_bench_log_row(c, row);
    row = cl_bench_row_add(c, 10, kase);
    snprintf(row->side_a, sizeof row->side_a, "semi-bdf2 amg dt=%g "
             "lin_tol=%g", W10A_DT / 2, W10A_FINE_TOL);
    cl_bench_log(c, "  semi-bdf2 amg, dt = %g (step error) ...",
                 W10A_DT / 2);
    ok = w10a_run(a, "amg", W10A_FINE_TOL, W10A_DT / 2, W10A_WARM,
                  2 * W10A_STEPS - W10A_WARM, row);
    if (ok) {
        double step_err;
        w10a_distance(a->x, a->ref, a->n, &step_err, &rms);
        a->accuracy = W10A_SHARE * step_err;
        row->error_a = step_err;
        ok = isfinite(step_err) && step_err > 0.0;
        cl_bench_note(row, "step error at t = %g s: the largest distance "
                      "from the dt = %g reference (rms %.2g m); accuracy "
                      "asked of the solvers below: %g of it, %.2g m",
                      W10A_STEPS * W10A_DT, W10A_DT, rms, W10A_SHARE,
                      a->accuracy);
    }
    cl_bench_log_row(c, row);
    return ok;
}

/* `linsol` down the ladder to the loosest rung within the accuracy, the
 * first round of its time; res->ok false, res->note saying why, if no
 * rung got there. */
static void w10a_ladder_walk(const cl_bctx *c, w10a_ctx *a,
                             const char *linsol, w10a_result *res)
{
    *res = (w10a_result){.linsol = linsol};
    for (size_t k = 0; k < W10A_RUNGS; k++) {
        cl_bench_row run = {0};
        double largest, rms;
        res->lin_tol = w10a_ladder[k];
        cl_bench_log(c, "  semi-bdf2 %s, lin_tol = %g ...", linsol,
                     res->lin_tol);
        if (!w10a_run(a, linsol, res->lin_tol, W10A_DT, W10A_WARM,
                      W10A_STEPS - W10A_WARM, &run)) {
            cl_bench_copy(res->failed, sizeof res->failed, run.note);
            return;
        }
        w10a_distance(a->x, a->ref, a->n, &largest, &rms);
        if (largest <= a->accuracy) {
            w10a_repeat(c, a, res, &run);
            res->ok = true;
            res->cpu = res->cpu_max = run.cpu_a;
            res->wall = run.wall_a;
            res->rounds = 1;
            res->error = largest;
            res->rms = rms;
            return;
        }
        res->tried_tol[res->tried] = res->lin_tol;
        res->tried_err[res->tried++] = largest;
    }
}

/* One more timed round of res's solver at its lin_tol. */
static void w10a_round(const cl_bctx *c, w10a_ctx *a, w10a_result *res)
{
    cl_bench_row run = {0};
    if (!res->ok || !w10a_run(a, res->linsol, res->lin_tol, W10A_DT,
                              W10A_WARM, W10A_STEPS - W10A_WARM, &run))
        return;
    w10a_repeat(c, a, res, &run);
    res->rounds++;
    if (cl_bench_round_fastest(&res->cpu, &res->cpu_max, run.cpu_a))
        res->wall = run.wall_a;
}

/* "; looser (lin_tol:m): TOL:ERR, ..." for the rungs tried before the one
 * taken, the tightest first, as many whole entries as fit in len. */
static void w10a_looser(const w10a_result *res, char *buf, size_t len)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int k = res->tried - 1; k >= 0; k--) {
        char item[40];
        int w = snprintf(item, sizeof item, "%s%g:%.3g",
                         used ? ", " : "; looser (lin_tol:m): ",
                         res->tried_tol[k], res->tried_err[k]);
        if (w < 0 || used + (size_t)w >= len)
            break;
        memcpy(buf + used, item, (size_t)w + 1);
        used += (size_t)w;
    }
}

/* "semi-bdf2 LINSOL lin_tol=TOL" (without the tolerance for a direct
 * solver) into a row's side. */
static void w10a_side(const w10a_result *res, char *side, size_t len)
{
    if (res->lin_tol > 0.0)
        snprintf(side, len, "semi-bdf2 %s lin_tol=%g", res->linsol,
                 res->lin_tol);
    else
        snprintf(side, len, "semi-bdf2 %s", res->linsol);
}

/* The row of a solver at its lin_tol. */
static void w10a_solver_row(cl_bctx *c, const w10a_ctx *a, const char *kase,
                            const w10a_result *res)
{
    cl_bench_row *row = cl_bench_row_add(c, 10, kase);
    char looser[120];
    w10a_looser(res, looser, sizeof looser);
    w10a_side(res, row->side_a, sizeof row->side_a);
    if (res->failed[0]) {
        cl_bench_note(row, "stopped at this lin_tol: %s", res->failed);
    } else if (!res->ok) {
        snprintf(row->side_a, sizeof row->side_a, "semi-bdf2 %s",
                 res->linsol);
        cl_bench_note(row, "no lin_tol down to %g within %.2g m%s",
                      res->lin_tol, a->accuracy, looser);
    } else {
        row->cpu_a = res->cpu;
        row->wall_a = res->wall;
        row->error_a = res->error;
        cl_bench_note(row, "loosest within %.2g m; rms %.2g m; best of %d "
                      "rounds (worst %.3g s)%s", a->accuracy, res->rms,
                      res->rounds, res->cpu_max, looser);
    }
    cl_bench_log_row(c, row);
}

/* The three solvers' figures at one size. */
typedef struct {
    double unknowns;
    w10a_result ref, pcg, amg;   /* ref: cholmod */
} w10a_size;

/* amg against the faster of pcg and cholmod at the largest size, each at
 * the accuracy. */
static void w10a_speedup(cl_bctx *c, const char *kase, const w10a_size *z)
{
    const w10a_result *one = z->pcg.ok && z->pcg.cpu < z->ref.cpu ? &z->pcg
                                                                  : &z->ref;
    cl_bench_row *row = cl_bench_row_add(c, 10, kase);
    w10a_side(&z->amg, row->side_a, sizeof row->side_a);
    w10a_side(one, row->side_b, sizeof row->side_b);
    row->cpu_a = z->amg.cpu;
    row->cpu_b = one->cpu;
    row->wall_a = z->amg.wall;
    row->wall_b = one->wall;
    row->error_a = z->amg.error;
    row->error_b = one->error;
    cl_bench_judge(row, row->cpu_b / row->cpu_a, "x", ">=", 3.0);
    cl_bench_note(row, "per step, each within %g of the step error of the "
                  "exact linear steps; against the faster of pcg and "
                  "cholmod there", W10A_SHARE);
    cl_bench_log_row(c, row);
}

/* Exponents of time a step against unknowns at the accuracy, the goal
 * (<= 1.15) on the fastest at the largest size. */
static void w10a_fits(cl_bctx *c, const w10a_size *z, int nn)
{
    static const char *const name[3] = {"cholmod", "pcg", "amg"};
    double unknowns[3], t[3][3];
    int best = -1;
    char kase[48];
    snprintf(kase, sizeof kase, "dt=%g accuracy fit", W10A_DT);
    for (int i = 0; i < nn; i++) {
        const w10a_result *r[3] = {&z[i].ref, &z[i].pcg, &z[i].amg};
        unknowns[i] = z[i].unknowns;
        for (int j = 0; j < 3; j++)
            t[j][i] = r[j]->ok ? r[j]->cpu : NAN;
    }
    for (int j = 0; j < 3; j++)
        if (isfinite(t[j][nn - 1]) &&
            (best < 0 || t[j][nn - 1] < t[best][nn - 1]))
            best = j;
    for (int j = 0; j < 3; j++) {
        cl_bench_row *row = cl_bench_fit_row(c, 10, kase, name[j], unknowns,
                                             t[j], nn, j == best ? "<=" : "",
                                             1.15, j == best);
        if (isfinite(row->ratio))
            cl_bench_note(row, "each size at the loosest lin_tol within %g "
                          "of the step error", W10A_SHARE);
        cl_bench_log_row(c, row);
    }
}

/* Reference, step error and both solvers' rungs at size n. */
static void w10a_size_run(cl_bctx *c, int n, w10a_size *z)
{
    char nset[32], kase[48];
    snprintf(nset, sizeof nset, "cloth.n=%d", n);
    snprintf(kase, sizeof kase, "dt=%g n=%d accuracy", W10A_DT, n);
    const char *sets[] = {nset, NULL};
    cl_bmodel bm;
    cl_error err = {0};
    if (cl_bench_model(c, "hang", sets, &bm, &err)) {
        cl_bench_note(cl_bench_row_add(c, 10, kase), "%s", err.msg);
        return;
    }
    w10a_ctx a = {.m = bm.m, .n = cl_model_system(bm.m)->n};
    z->unknowns = (double)a.n;
    a.ref = malloc(a.n * sizeof *a.ref);
    a.x = malloc(a.n * sizeof *a.x);
    if (!a.ref || !a.x) {
        c->nomem = true;
    } else if (w10a_reference(c, &a, kase, &z->ref)) {
        w10a_ladder_walk(c, &a, "pcg", &z->pcg);
        w10a_ladder_walk(c, &a, "amg", &z->amg);
        for (int r = 1; r < W10A_ROUNDS; r++) {
            w10a_round(c, &a, &z->pcg);
            w10a_round(c, &a, &z->amg);
        }
        w10a_solver_row(c, &a, kase, &z->pcg);
        w10a_solver_row(c, &a, kase, &z->amg);
    }
    free(a.ref);
    free(a.x);
    cl_bench_model_free(&bm);
}

void cl_bench_w10_accuracy(cl_bctx *c)
{
    int nn = c->plan.w10_nn;
    w10a_size z[3] = {{0}};
    for (int i = 0; i < nn; i++)
        w10a_size_run(c, c->plan.w10_n[i], &z[i]);
    char kase[48];
    snprintf(kase, sizeof kase, "dt=%g n=%d accuracy", W10A_DT,
             c->plan.w10_n[nn - 1]);
    if (z[nn - 1].amg.ok) {
        w10a_speedup(c, kase, &z[nn - 1]);
    } else {
        cl_bench_row *row = cl_bench_row_add(c, 10, kase);
        snprintf(row->side_a, sizeof row->side_a, "semi-bdf2 amg");
        cl_bench_note(row, "not measured: amg not within the accuracy at "
                      "this n");
        cl_bench_log_row(c, row);
    }
    w10a_fits(c, z, nn);
}
