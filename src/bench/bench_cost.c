/* Benchmark workloads of cost per unit (bench/bench.h): 3 (semi-bdf2
 * per step, per linear solver, against size), 4 (force and Jacobian
 * evaluations per pair) and 5 (explicit steps per second). */
#define _DEFAULT_SOURCE /* getloadavg */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench_impl.h"
#include "analysis/counts.h"
#include "forces/pairkern.h"
#include "linalg/linsol.h"

#define W3_DTS 2
#define W3_MAX_SOLVERS 16
#define W3_WARM 2          /* untimed steps: semi-be start, first BDF2 */
#define W3_MIN_STEPS 3
#define W3_CASE_CAP 20.0   /* skip a case predicted to take longer (s) */
#define W4_ROUNDS 3        /* timed stretches per evaluation, fastest kept */
#define W5_CHUNK 100       /* explicit steps per advance call */
#define W5_GOAL 25000.0    /* steps/s of the explicit mass-spring steps */
#define W5_ROUNDS 3        /* timed stretches per case, the fastest kept */

static cl_status timed_steps(void *state, const cl_integrator_type *type,
                             double dt, const fixed_plan *fp, double *x,
                             double *v, fixed_time *ft, cl_error *err)
{
    double c0, w0, c1, w1;
    long k = fp->warm;
    cl_status rc = k ? type->advance(state, k * dt, x, v, err) : CL_OK;
    cl_bench_clock(&c0, &w0);
    c1 = c0;
    w1 = w0;
    while (!rc && (k - fp->warm < fp->min_steps || c1 - c0 < fp->budget)) {
        k += fp->chunk;
        rc = type->advance(state, k * dt, x, v, err);
        cl_bench_clock(&c1, &w1);
    }
    ft->cpu = c1 - c0;
    ft->wall = w1 - w0;
    ft->steps = k - fp->warm;
    return rc;
}

void cl_bench_time_fixed(cl_model *m, const cl_integrator_type *type,
                         const cl_integrator_opts *io, const fixed_plan *fp,
                         fixed_time *ft)
{
    const cl_system *sys = cl_model_system(m);
    double *x = malloc(sys->n * sizeof *x), *v = malloc(sys->n * sizeof *v);
    void *state = NULL;
    cl_error err = {0};
    *ft = (fixed_time){.cpu = NAN, .wall = NAN};
    cl_status rc = x && v ? cl_model_initial_state(m, x, v)
                          : cl_error_set(&err, CL_ENOMEM, "out of memory");
    if (!rc && !(rc = type->create(sys, io, 0.0, x, v, &state, &err)))
        rc = timed_steps(state, type, io->dt, fp, x, v, ft, &err);
    if (!rc && fp->x_final)
        memcpy(fp->x_final, x, sys->n * sizeof *x);
    if (state) {
        type->stats(state, &ft->stats);
        type->free(state);
    }
    ft->rc = rc;
    if (rc)
        cl_bench_copy(ft->msg, sizeof ft->msg, err.msg);
    free(x);
    free(v);
}

bool cl_bench_semi_step(cl_model *m, const cl_integrator_opts *io,
                        const fixed_plan *fp, cl_bench_row *row,
                        fixed_time *ft)
{
    cl_bench_time_fixed(m, cl_integrator_find("semi-bdf2"), io, fp, ft);
    if (ft->rc) {
        cl_bench_note(row, "failed: %s", ft->msg);
        return false;
    }
    row->cpu_a = ft->cpu / (double)ft->steps;
    row->wall_a = ft->wall / (double)ft->steps;
    return true;
}

/* ---- workload 3 ------------------------------------------------------- */

typedef struct {
    int nsolver;
    const char *name[W3_MAX_SOLVERS];
    double per_step[W3_MAX_SOLVERS][4];  /* NaN: not measured */
    double unknowns[4];
    bool stop[W3_MAX_SOLVERS];           /* failed or too slow: skip larger n */
} w3_sweep;

static void w3_case(cl_bctx *c, w3_sweep *s, double dt, int i, int j,
                    cl_model *m)
{
    int n = c->plan.w3_n[i];
    char kase[48];
    snprintf(kase, sizeof kase, "dt=%g n=%d", dt, n);
    cl_bench_row *row = cl_bench_row_add(c, 3, kase);
    snprintf(row->side_a, sizeof row->side_a, "semi-bdf2 %s", s->name[j]);
    if (s->stop[j]) {
        cl_bench_note(row, "skipped (failed or too slow at a smaller n)");
        return;
    }
    cl_integrator_opts io = {.dt = dt, .linsol = s->name[j]};
    fixed_plan fp = {W3_WARM, 1, W3_MIN_STEPS, c->plan.w3_budget, NULL};
    fixed_time ft;
    cl_bench_log(c, "  semi-bdf2 %s, dt = %g, n = %d ...", s->name[j], dt, n);
    if (!cl_bench_semi_step(m, &io, &fp, row, &ft)) {
        s->stop[j] = true;
        cl_bench_log_row(c, row);
        return;
    }
    s->per_step[j][i] = row->cpu_a;
    cl_bench_note(row, "%ld timed steps; %.0f unknowns", ft.steps,
                  s->unknowns[i]);
    /* the next size has 4x the unknowns: 8x the time would be too slow */
    s->stop[j] = 8.0 * row->cpu_a * (W3_WARM + W3_MIN_STEPS) > W3_CASE_CAP;
    cl_bench_log_row(c, row);
}

double cl_bench_exponent(const double *unknowns, const double *value,
                         int nn, int *used)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int k = 0;
    for (int i = 0; i < nn; i++)
        if (isfinite(value[i])) {
            double lx = log(unknowns[i]), ly = log(value[i]);
            sx += lx;
            sy += ly;
            sxx += lx * lx;
            sxy += lx * ly;
            k++;
        }
    if (used)
        *used = k;
    return k < 2 ? NAN : (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

cl_bench_row *cl_bench_fit_row(cl_bctx *c, int workload, const char *kase,
                               const char *solver, const double *unknowns,
                               const double *per_step, int nn,
                               const char *goal, double target, bool fastest)
{
    int used;
    double e = cl_bench_exponent(unknowns, per_step, nn, &used);
    cl_bench_row *row = cl_bench_row_add(c, workload, kase);
    snprintf(row->side_a, sizeof row->side_a, "semi-bdf2 %s", solver);
    cl_bench_judge(row, e, "exponent", goal, target);
    if (used < 2)
        cl_bench_note(row, "not fitted: measured at %d size%s", used,
                      used == 1 ? "" : "s");
    else
        cl_bench_note(row, "time per step ~ unknowns^p over %d sizes%s",
                      used, fastest ? "; fastest at the largest n" : "");
    return row;
}

/* The fastest solver at the largest size any solver reached, or -1. */
static int w3_best(const w3_sweep *s, int nn, int *at)
{
    for (int i = nn - 1; i >= 0; i--) {
        int best = -1;
        for (int j = 0; j < s->nsolver; j++)
            if (isfinite(s->per_step[j][i]) &&
                (best < 0 || s->per_step[j][i] < s->per_step[best][i]))
                best = j;
        if (best >= 0) {
            *at = i;
            return best;
        }
    }
    return -1;
}

static void w3_fits(cl_bctx *c, const w3_sweep *s, double dt, int best)
{
    char kase[48];
    snprintf(kase, sizeof kase, "dt=%g fit", dt);
    for (int j = 0; j < s->nsolver; j++)
        cl_bench_log_row(c, cl_bench_fit_row(c, 3, kase, s->name[j],
                                             s->unknowns, s->per_step[j],
                                             c->plan.w3_nn,
                                             j == best ? "<=" : "", 1.2,
                                             j == best));
}

static int find_solver(const w3_sweep *s, const char *name)
{
    for (int j = 0; j < s->nsolver; j++)
        if (!strcmp(s->name[j], name))
            return j;
    return -1;
}

/* The fastest solver against klu at n = 64 (or the largest n with both). */
static void w3_versus_klu(cl_bctx *c, const w3_sweep *s, double dt, int best)
{
    int klu = find_solver(s, "klu"), i = c->plan.w3_nn - 1;
    while (i > 0 && (c->plan.w3_n[i] > 64 || klu < 0 ||
                     !isfinite(s->per_step[klu][i]) ||
                     !isfinite(s->per_step[best][i])))
        i--;
    char kase[48];
    snprintf(kase, sizeof kase, "dt=%g n=%d", dt, c->plan.w3_n[i]);
    cl_bench_row *row = cl_bench_row_add(c, 3, kase);
    snprintf(row->side_a, sizeof row->side_a, "semi-bdf2 %s", s->name[best]);
    snprintf(row->side_b, sizeof row->side_b, "semi-bdf2 klu");
    if (klu < 0) {
        cl_bench_note(row, "no klu solver registered");
        return;
    }
    row->cpu_a = s->per_step[best][i];
    row->cpu_b = s->per_step[klu][i];
    bool at64 = c->plan.w3_n[i] == 64;
    cl_bench_judge(row, row->cpu_b / row->cpu_a, "x", at64 ? ">=" : "",
                   30.0);
    cl_bench_note(row, "per step%s", at64 ? "" : "; goal is at n = 64");
    cl_bench_log_row(c, row);
}

static void w3_dt(cl_bctx *c, double dt)
{
    w3_sweep s = {0};
    for (int j = 0; cl_linsol_registry[j] && j < W3_MAX_SOLVERS; j++)
        s.name[s.nsolver++] = cl_linsol_registry[j]->name;
    for (int i = 0; i < c->plan.w3_nn; i++) {
        char nset[32];
        snprintf(nset, sizeof nset, "cloth.n=%d", c->plan.w3_n[i]);
        const char *sets[] = {nset, NULL};
        cl_bmodel bm;
        cl_error err = {0};
        for (int j = 0; j < s.nsolver; j++)
            s.per_step[j][i] = NAN;
        if (cl_bench_model(c, "hang", sets, &bm, &err)) {
            cl_bench_note(cl_bench_row_add(c, 3, nset), "%s", err.msg);
            continue;
        }
        s.unknowns[i] = (double)cl_model_system(bm.m)->n;
        for (int j = 0; j < s.nsolver; j++) {
            w3_case(c, &s, dt, i, j, bm.m);
        }
        cl_bench_model_free(&bm);
    }
    int at, best = w3_best(&s, c->plan.w3_nn, &at);
    if (best < 0)
        return;
    w3_fits(c, &s, dt, best);
    w3_versus_klu(c, &s, dt, best);
}

void cl_bench_w3(cl_bctx *c)
{
    static const double dts[W3_DTS] = {1e-3, 1e-2};
    if (!cl_integrator_find("semi-bdf2")) {
        cl_bench_note(cl_bench_row_add(c, 3, "semi-bdf2"),
                      "semi-bdf2 is not registered");
        return;
    }
    for (int k = 0; k < W3_DTS; k++)
        w3_dt(c, dts[k]);
}

/* ---- workload 4 ------------------------------------------------------- */

/* Rest positions moved by up to 5 % of a spacing per coordinate (many
 * Type2 pairs on the buckling branch), velocities up to 0.1 m/s. */
static void perturb(const cl_model *m, double *x, double *v, size_t n)
{
    double h = cl_model_cloth(m)->hu;
    unsigned long long s = 2024;
    for (size_t k = 0; k < n; k++) {
        x[k] += 0.05 * h * cl_bench_uniform(&s);
        v[k] = 0.1 * cl_bench_uniform(&s);
    }
}

/* Seconds (CPU, wall) per call of force (jac = false) or jacobian. */
static cl_status time_eval(const cl_system *sys, bool jac, const double *x,
                           const double *v, double budget, double *cpu,
                           double *wall, long *calls)
{
    size_t nval = 9 * sys->pattern->nnzb;
    double *f = malloc(sys->n * sizeof *f);
    double *jx = jac ? malloc(nval * sizeof *jx) : NULL;
    double *jv = jac ? malloc(nval * sizeof *jv) : NULL;
    double c0, w0, c1, w1;
    cl_status rc = f && (!jac || (jx && jv)) ? CL_OK : CL_ENOMEM;
    long k = 0;
    cl_bench_clock(&c0, &w0);
    for (c1 = c0; !rc && (k < 10 || c1 - c0 < budget);) {
        for (int r = 0; r < 8 && !rc; r++, k++)
            rc = jac ? sys->jacobian(sys->data, 0.0, x, v, f, jx, jv)
                     : sys->force(sys->data, 0.0, x, v, f);
        cl_bench_clock(&c1, &w1);
    }
    *cpu = (c1 - c0) / (double)k;
    *wall = (w1 - w0) / (double)k;
    *calls = k;
    free(f);
    free(jx);
    free(jv);
    return rc;
}

/* An evaluation's fastest round: seconds (CPU, wall) per call, its calls,
 * and the fastest and slowest rounds' CPU seconds per call. */
typedef struct {
    cl_status rc;
    double cpu, wall, lo, hi;
    long calls;
} w4_time;

static void w4_round(const cl_system *sys, bool jac, const double *x,
                     const double *v, double budget, w4_time *t)
{
    double cpu, wall;
    long calls;
    if (t->rc || (t->rc = time_eval(sys, jac, x, v, budget, &cpu, &wall,
                                    &calls)))
        return;
    if (cl_bench_round_fastest(&t->lo, &t->hi, cpu)) {
        t->cpu = cpu;
        t->wall = wall;
        t->calls = calls;
    }
}

static void w4_row(cl_bctx *c, const cl_system *sys, bool jac,
                   const w4_time *t, long pairs)
{
    cl_bench_row *row = cl_bench_row_add(c, 4, "hang n=64");
    snprintf(row->side_a, sizeof row->side_a, "%s",
             jac ? "jacobian (df/dx, df/dv)" : "force");
    if (t->rc) {
        cl_bench_note(row, "failed: %s", cl_status_name(t->rc));
    } else {
        row->cpu_a = t->cpu;
        row->wall_a = t->wall;
        double per = 1e9 / (double)pairs;
        cl_bench_judge(row, per * t->cpu, "ns/pair", jac ? "" : "<=", 10.0);
        /* The Jacobian's values (two arrays of 3x3 blocks) outgrow a
         * core's cache: its time depends on what else runs. */
        char vals[48] = "";
        if (jac)
            snprintf(vals, sizeof vals, ", values %.3g MB",
                     2.0 * 72.0 * (double)sys->pattern->nnzb / 1e6);
        cl_bench_note(row, "%ld pairs, %ld calls, %s kernels%s; the fastest "
                      "of %d alternating rounds (%.4g-%.4g ns/pair)", pairs,
                      t->calls, cl_pairkern_isa(), vals, W4_ROUNDS,
                      per * t->lo, per * t->hi);
    }
    cl_bench_log_row(c, row);
}

void cl_bench_w4(cl_bctx *c)
{
    const char *sets[] = {"cloth.n=64", NULL};
    cl_bmodel bm;
    cl_counts counts;
    cl_error err = {0};
    if (cl_bench_model(c, "hang", sets, &bm, &err) ||
        cl_counts_measure(64, &counts, &err)) {
        cl_bench_note(cl_bench_row_add(c, 4, "hang n=64"), "%s", err.msg);
        return;
    }
    const cl_system *sys = cl_model_system(bm.m);
    double *x = malloc(sys->n * sizeof *x), *v = malloc(sys->n * sizeof *v);
    if (x && v && !cl_model_initial_state(bm.m, x, v)) {
        perturb(bm.m, x, v, sys->n);
        w4_time t[2] = {{.lo = INFINITY}, {.lo = INFINITY}};
        /* force and Jacobian alternate, so that a stretch the host slows
         * does not fall on every round of one */
        for (int r = 0; r < W4_ROUNDS; r++)
            for (int jac = 0; jac < 2; jac++)
                w4_round(sys, jac, x, v, c->plan.eval_budget, &t[jac]);
        for (int jac = 0; jac < 2; jac++)
            w4_row(c, sys, jac, &t[jac], counts.type1 + counts.type2);
    } else {
        c->nomem = true;
    }
    free(x);
    free(v);
    cl_bench_model_free(&bm);
}

/* ---- workload 5 ------------------------------------------------------- */

typedef struct {
    const char *integrator, *problem, *what;
    const char *sets[4];   /* NULL-terminated */
    double dt;             /* 0: the problem's [run] dt */
    bool goal;             /* judged against W5_GOAL (the mass-spring
                            * rows); else reported without a goal */
} w5_case;

/* A case's fastest round and the range of its rounds' CPU seconds per
 * step. */
typedef struct {
    fixed_time best;       /* the fastest round's timing */
    double dt, lo, hi;     /* step; fastest and slowest seconds per step */
    char msg[240];         /* why it failed; "" */
} w5_result;

/* One timed stretch of case wc (its steps/s into res): a fresh
 * integrator on the model's initial state, as every round. */
static void w5_round(cl_bctx *c, const w5_case *wc, w5_result *res)
{
    const cl_integrator_type *type = cl_integrator_find(wc->integrator);
    cl_bmodel bm;
    cl_error err = {0};
    cl_integrator_opts io = {0};
    if (!type) {
        snprintf(res->msg, sizeof res->msg, "%s is not registered",
                 wc->integrator);
        return;
    }
    if (cl_bench_model(c, wc->problem, wc->sets, &bm, &err)) {
        cl_bench_copy(res->msg, sizeof res->msg, err.msg);
        return;
    }
    fixed_plan fp = {10, W5_CHUNK, W5_CHUNK, c->plan.eval_budget, NULL};
    fixed_time ft = {.rc = cl_bench_fixed_opts(bm.cfg, wc->dt, &io, &err)};
    if (!ft.rc)
        cl_bench_time_fixed(bm.m, type, &io, &fp, &ft);
    cl_bench_model_free(&bm);
    if (ft.rc) {
        snprintf(res->msg, sizeof res->msg, "failed: %.200s",
                 *ft.msg ? ft.msg : err.msg);
        return;
    }
    if (cl_bench_round_fastest(&res->lo, &res->hi, ft.cpu / (double)ft.steps))
        res->best = ft;
    res->dt = io.dt;
}

static void w5_row(cl_bctx *c, const w5_case *wc, const w5_result *res)
{
    cl_bench_row *row = cl_bench_row_add(c, 5, "30x30 cloth");
    snprintf(row->side_a, sizeof row->side_a, "%s", wc->integrator);
    snprintf(row->side_b, sizeof row->side_b, "%s", wc->what);
    if (*res->msg) {
        cl_bench_note(row, "%s", res->msg);
    } else {
        row->cpu_a = res->best.cpu;
        row->wall_a = res->best.wall;
        cl_bench_judge(row, 1.0 / res->lo, "steps/s", wc->goal ? ">=" : "",
                       W5_GOAL);
        cl_bench_note(row, "%ld steps of %g s (%s), the fastest of %d "
                      "alternating rounds (%.4g-%.4g steps/s); %s",
                      res->best.steps, res->dt, wc->problem, W5_ROUNDS,
                      1.0 / res->hi, 1.0 / res->lo,
                      wc->goal ? "the goal is the mass-spring step's "
                                 "(symplectic-euler, verlet)"
                               : "no goal (the 25,000 steps/s are the "
                                 "mass-spring step's)");
    }
    cl_bench_log_row(c, row);
}

void cl_bench_w5(cl_bctx *c)
{
    static const w5_case cases[] = {
        {"symplectic-euler", "ms-hang", "springs",
         {"cloth.n=30", "spring-damping.kd=0", "pbd.enabled=false"}, 2e-4,
         true},
        {"verlet", "ms-hang", "springs",
         {"cloth.n=30", "spring-damping.kd=0", "pbd.enabled=false"}, 2e-4,
         true},
        {"symplectic-euler", "ms-hang", "springs + axial damping",
         {"cloth.n=30", "pbd.enabled=false", NULL}, 2e-4, true},
        {"verlet", "ms-hang", "springs + axial damping",
         {"cloth.n=30", "pbd.enabled=false", NULL}, 2e-4, true},
        /* Position-based dynamics: no goal of its own, for the record. */
        {"verlet-pbd", "verlet-scene1", "PBD level 2, 10 iterations",
         {"cloth.n=30", "pbd.levels=2", "pbd.iterations=10"}, 0.0, false},
    };
    enum { NC = sizeof cases / sizeof *cases };
    w5_result res[NC];
    for (size_t k = 0; k < NC; k++)
        res[k] = (w5_result){.lo = INFINITY};
    /* rounds alternate over the cases, so that a stretch the host slows
     * does not fall on one case's every round */
    for (int r = 0; r < W5_ROUNDS; r++)
        for (size_t k = 0; k < NC; k++)
            if (!*res[k].msg)
                w5_round(c, &cases[k], &res[k]);
    for (size_t k = 0; k < NC; k++)
        w5_row(c, &cases[k], &res[k]);
}

/* ---- workload 13 ------------------------------------------------------ */

#define W13_DT 1e-3
#define W13_STEPS 10   /* timed steps per run, after W3_WARM untimed ones */
#define W13_ROUNDS 3   /* runs per thread count, alternating 1 and 2 */

/* The size of a team OpenMP forms when asked for `want` threads (fewer
 * under omp_set_dynamic or a thread limit). */
static int w13_team(int want)
{
    int got = 0;
#pragma omp parallel num_threads(want)
#pragma omp single
    got = omp_get_num_threads();
    return got;
}

/* Wall (and CPU) seconds per semi-bdf2 (pcg) step of model m on `threads`
 * threads, or NaN (a note on row). */
static double w13_per_step(cl_model *m, int threads, double *cpu,
                           cl_bench_row *row)
{
    cl_error err = {0};
    cl_integrator_opts io = {.dt = W13_DT, .linsol = "pcg"};
    fixed_plan fp = {W3_WARM, 1, W13_STEPS, 0.0, NULL};
    fixed_time ft;
    if (cl_model_set_threads(m, threads, &err)) {
        cl_bench_note(row, "%s", err.msg);
        return NAN;
    }
    cl_bench_time_fixed(m, cl_integrator_find("semi-bdf2"), &io, &fp, &ft);
    if (ft.rc) {
        cl_bench_note(row, "failed: %s", ft.msg);
        return NAN;
    }
    *cpu = ft.cpu / (double)ft.steps;
    return ft.wall / (double)ft.steps;
}

/* W13_ROUNDS rounds of one run on 1 thread and one on 2: each count's
 * fastest run into row (side b: 1 thread, side a: 2), the ratios of the
 * rounds into lo, hi.  False if a run failed. */
static bool w13_rounds(cl_model *m, cl_bench_row *row, double *lo,
                       double *hi)
{
    row->wall_a = row->wall_b = INFINITY;
    *lo = INFINITY;
    *hi = 0.0;
    for (int r = 0; r < W13_ROUNDS; r++) {
        double c1 = NAN, c2 = NAN;
        double w1 = w13_per_step(m, 1, &c1, row);
        double w2 = isfinite(w1) ? w13_per_step(m, 2, &c2, row) : NAN;
        if (!isfinite(w2))
            return false;
        if (w1 < row->wall_b) {
            row->wall_b = w1;
            row->cpu_b = c1;
        }
        if (w2 < row->wall_a) {
            row->wall_a = w2;
            row->cpu_a = c2;
        }
        *lo = fmin(*lo, w1 / w2);
        *hi = fmax(*hi, w1 / w2);
    }
    return true;
}

void cl_bench_w13(cl_bctx *c)
{
    char nset[32], kase[48];
    snprintf(nset, sizeof nset, "cloth.n=%d", c->plan.w13_n);
    snprintf(kase, sizeof kase, "hang n=%d", c->plan.w13_n);
    const char *sets[] = {nset, NULL};
    cl_bench_row *row = cl_bench_row_add(c, 13, kase);
    snprintf(row->side_a, sizeof row->side_a, "semi-bdf2 pcg --threads 2");
    snprintf(row->side_b, sizeof row->side_b, "semi-bdf2 pcg --threads 1");
    cl_bmodel bm;
    cl_error err = {0};
    if (cl_bench_model(c, "hang", sets, &bm, &err)) {
        cl_bench_note(row, "%s", err.msg);
        return;
    }
    cl_bench_log(c, "  semi-bdf2 pcg, n = %d, 1 and 2 threads, %d rounds "
                 "...", c->plan.w13_n, W13_ROUNDS);
    double load[2] = {NAN, NAN}, lo, hi;
    int team = w13_team(2);
    getloadavg(&load[0], 1);
    if (w13_rounds(bm.m, row, &lo, &hi)) {
        getloadavg(&load[1], 1);
        cl_bench_judge(row, row->wall_b / row->wall_a, "x", ">=", 1.6);
        cl_bench_note(row, "wall per step (dt = %g), 1 over 2 threads, "
                      "fastest of %d alternating runs of %d steps (rounds "
                      "%.2f-%.2fx); team of %d; load %.1f, %.1f", W13_DT,
                      W13_ROUNDS, W13_STEPS, lo, hi, team, load[0],
                      load[1]);
    }
    cl_bench_model_free(&bm);
    cl_bench_log_row(c, row);
}
