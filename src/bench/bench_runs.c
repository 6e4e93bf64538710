/* Benchmark plumbing (bench/bench_impl.h): problems, clocks, cached
 * cvode-bdf runs on hang, rows and progress lines. */
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench_impl.h"
#include "core/clock.h"
#include "core/stop.h"

cl_status cl_bench_model(const cl_bctx *c, const char *problem,
                         const char *const *sets, cl_bmodel *bm,
                         cl_error *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.ini", c->o->problems, problem);
    bm->m = NULL;
    bm->cfg = cl_config_alloc();
    cl_status rc = bm->cfg ? cl_config_load(bm->cfg, path, err)
                           : cl_error_set(err, CL_ENOMEM, "out of memory");
    for (; !rc && sets && *sets; sets++)
        rc = cl_config_set(bm->cfg, *sets, err);
    if (!rc)
        rc = cl_model_create(bm->cfg, &bm->m, err);
    if (rc)
        cl_bench_model_free(bm);
    return rc;
}

void cl_bench_model_free(cl_bmodel *bm)
{
    cl_model_free(bm->m);
    cl_config_free(bm->cfg);
    bm->m = NULL;
    bm->cfg = NULL;
}

cl_status cl_bench_fixed_opts(cl_config *cfg, double dt,
                              cl_integrator_opts *io, cl_error *err)
{
    cl_status rc = cl_config_double(cfg, "run", "dt", dt, 0.0, INFINITY,
                                    &io->dt, err);
    if (!rc && dt > 0)
        io->dt = dt;
    if (!rc)
        rc = cl_config_double(cfg, "run", "verlet_damping", 0.0, 0.0,
                              0.999999, &io->vdamp, err);
    return rc;
}

void cl_bench_clock(double *cpu, double *wall)
{
    *cpu = cl_clock_cpu();
    *wall = cl_clock_wall();
}

double cl_bench_uniform(unsigned long long *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return 2.0 * ((double)(*s >> 11) / 9007199254740992.0) - 1.0;
}

void cl_bench_side(char *buf, size_t len, const char *linsol, int max_order)
{
    int at = snprintf(buf, len, "cvode-bdf %s", *linsol ? linsol
                                                        : "(default)");
    if (max_order > 0 && at >= 0 && (size_t)at < len)
        snprintf(buf + at, len - (size_t)at, ", order <= %d", max_order);
}

/* Integrate: create, advance to t_end, statistics, free; times around
 * all of it. */
static cl_status timed_run(cl_model *m, cl_brun *r, cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    const cl_integrator_type *type =
        cl_integrator_find(*r->method ? r->method : "cvode-bdf");
    cl_integrator_opts io = {.rtol = r->rtol, .atol = r->atol,
                             .linsol = r->linsol,
                             .max_order = r->max_order, .petsc = r->petsc};
    double *v = malloc(sys->n * sizeof *v);
    r->x = malloc(sys->n * sizeof *r->x);
    r->nfree = sys->n / 3;
    if (!v || !r->x || !type) {
        free(v);
        return cl_error_set(err, CL_ENOMEM, "out of memory (bench)");
    }
    cl_status rc = cl_model_initial_state(m, r->x, v);
    double c0, w0, c1, w1;
    void *state = NULL;
    cl_stats st = {0};
    cl_bench_clock(&c0, &w0);
    /* a budget is kept by a CPU-time timer (core/stop.h): once it is
     * spent, the model's evaluations end the advance where it is */
    if (!rc && r->budget > 0)
        rc = cl_stop_after(CL_STOP_CPU, r->budget, err);
    if (!rc)
        rc = type->create(sys, &io, 0.0, r->x, v, &state, err);
    /* with a budget, in twentieths of t_end, so that the time reached is
     * known to a twentieth.  Not finer: a step that reaches an output
     * time ends on it, and PETSc's TSALPHA2 pays for that (hang n = 32
     * with hundredths reached t = 0.24 in 4185 steps, with twentieths
     * t = 0.5 in 5305). */
    int parts = r->budget > 0 ? 20 : 1;
    for (int k = 1; !rc && k <= parts; k++) {
        rc = type->advance(state, r->t_end * k / parts, r->x, v, err);
        r->t_reached = rc ? r->t_reached : r->t_end * k / parts;
    }
    if (rc == CL_EINTR && cl_stop_requested() == SIGPROF)
        rc = cl_error_set(err, CL_EBUDGET, "stopped by its budget of %g s "
                          "CPU after t = %g", r->budget, r->t_reached);
    if (r->budget > 0)
        cl_stop_clear();
    if (state) {
        type->stats(state, &st);
        type->free(state);
    }
    cl_bench_clock(&c1, &w1);
    r->cpu = c1 - c0;
    r->wall = w1 - w0;
    r->steps = st.steps;
    cl_bench_copy(r->used, sizeof r->used, st.linsol);
    free(v);
    return rc;
}

static const cl_brun *find_run(const cl_bctx *c, const cl_brun *want)
{
    for (size_t k = 0; k < c->nrun; k++) {
        const cl_brun *r = c->runs[k];
        if (r->n == want->n && r->t_end == want->t_end &&
            r->rtol == want->rtol && r->max_order == want->max_order &&
            !strcmp(r->linsol, want->linsol) &&
            !strcmp(r->method, want->method) &&
            !strcmp(r->petsc, want->petsc))
            return r;
    }
    return NULL;
}

static void run_hang(cl_bctx *c, cl_brun *r)
{
    char nset[32];
    snprintf(nset, sizeof nset, "cloth.n=%d", r->n);
    const char *sets[] = {nset, NULL};
    cl_bmodel bm;
    cl_error err = {0};
    char side[224];
    if (*r->method)
        snprintf(side, sizeof side, "%s %s", r->method, r->petsc);
    else
        cl_bench_side(side, sizeof side, r->linsol, r->max_order);
    cl_bench_log(c, "  %s on hang n = %d, T = %g, rtol %g ...", side, r->n,
                 r->t_end, r->rtol);
    r->rc = cl_bench_model(c, "hang", sets, &bm, &err);
    if (!r->rc) {
        r->rc = timed_run(bm.m, r, &err);
        cl_bench_model_free(&bm);
    }
    if (r->rc)
        cl_bench_copy(r->msg, sizeof r->msg, err.msg);
    cl_bench_log(c, "    %s: %.3g s CPU, %ld steps%s%s", r->rc ? "failed" :
                 "done", r->cpu, r->steps, r->rc ? ": " : "", r->msg);
}

/* The run `want` (n, t_end, tolerances, solver, method), from the cache
 * or made. */
static const cl_brun *cached_run(cl_bctx *c, const cl_brun *want)
{
    const cl_brun *have = find_run(c, want);
    if (have)
        return have;
    cl_brun **grown = realloc(c->runs, (c->nrun + 1) * sizeof *grown);
    cl_brun *r = calloc(1, sizeof *r);
    if (grown)
        c->runs = grown;
    if (!grown || !r) {
        free(r);
        c->nomem = true;
        return NULL;
    }
    *r = *want;
    c->runs[c->nrun++] = r;
    run_hang(c, r);
    return r;
}

const cl_brun *cl_bench_hang(cl_bctx *c, int n, double t_end,
                             const char *linsol, int max_order, double rtol,
                             double atol)
{
    cl_brun want = {.n = n, .t_end = t_end, .rtol = rtol, .atol = atol,
                    .max_order = max_order};
    cl_bench_copy(want.linsol, sizeof want.linsol, linsol);
    return cached_run(c, &want);
}

const cl_brun *cl_bench_hang_petsc(cl_bctx *c, int n, double t_end,
                                   const char *method, const char *petsc,
                                   double rtol, double atol, double budget)
{
    cl_brun want = {.n = n, .t_end = t_end, .rtol = rtol, .atol = atol,
                    .budget = budget};
    cl_bench_copy(want.method, sizeof want.method, method);
    cl_bench_copy(want.petsc, sizeof want.petsc, petsc);
    return cached_run(c, &want);
}

void cl_bench_runs_free(cl_bctx *c)
{
    for (size_t k = 0; k < c->nrun; k++) {
        free(c->runs[k]->x);
        free(c->runs[k]);
    }
    free(c->runs);
    c->runs = NULL;
    c->nrun = 0;
}

cl_bench_row *cl_bench_row_add(cl_bctx *c, int workload, const char *kase)
{
    cl_bench_table *t = c->t;
    cl_bench_row *r = &c->spare;
    if (t->n == t->cap) {
        size_t cap = t->cap ? 2 * t->cap : 64;
        cl_bench_row *grown = realloc(t->row, cap * sizeof *grown);
        if (grown) {
            t->row = grown;
            t->cap = cap;
        }
    }
    if (t->n < t->cap)
        r = &t->row[t->n++];
    else
        c->nomem = true;
    *r = (cl_bench_row){.workload = workload, .met = -1};
    cl_bench_copy(r->kase, sizeof r->kase, kase);
    r->cpu_a = r->cpu_b = r->wall_a = r->wall_b = NAN;
    r->error_a = r->error_b = r->ratio = r->target = NAN;
    return r;
}

void cl_bench_judge(cl_bench_row *r, double ratio, const char *unit,
                    const char *goal, double target)
{
    r->ratio = ratio;
    snprintf(r->unit, sizeof r->unit, "%s", unit);
    snprintf(r->goal, sizeof r->goal, "%s", goal);
    r->target = *goal ? target : NAN;
    if (!*goal || !isfinite(ratio))
        r->met = -1;
    else
        r->met = goal[0] == '>' ? ratio >= target : ratio <= target;
}

void cl_bench_judge_matched(cl_bench_row *r, const cl_brun *a, double err_a,
                            double target, const char *other)
{
    r->cpu_a = a->cpu;
    r->wall_a = a->wall;
    r->error_a = err_a;
    cl_bench_judge(r, r->cpu_b / r->cpu_a, "x", ">=", target);
    if (r->error_a > r->error_b) {
        r->met = 0;
        cl_bench_note(r, "error above %s at rtol %g", other, a->rtol);
    }
}

void cl_bench_copy(char *dst, size_t len, const char *src)
{
    size_t n = strlen(src);
    n = n < len ? n : len - 1;
    memcpy(dst, src, n);
    dst[n] = '\0';
}

void cl_bench_note(cl_bench_row *r, const char *fmt, ...)
{
    size_t len = strlen(r->note);
    if (len && len + 2 < sizeof r->note) {
        strcpy(r->note + len, "; ");
        len += 2;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->note + len, sizeof r->note - len, fmt, ap);
    va_end(ap);
}

bool cl_bench_round_fastest(double *lo, double *hi, double s)
{
    bool fastest = !(s >= *lo);
    *lo = fmin(*lo, s);
    *hi = fmax(*hi, s);
    return fastest;
}

void cl_bench_log(const cl_bctx *c, const char *fmt, ...)
{
    if (!c->o->log)
        return;
    va_list ap;
    va_start(ap, fmt);
    vfprintf(c->o->log, fmt, ap);
    va_end(ap);
    fputc('\n', c->o->log);
    fflush(c->o->log);
}

void cl_bench_log_row(const cl_bctx *c, const cl_bench_row *r)
{
    double figure = isfinite(r->ratio) ? r->ratio : r->cpu_a;
    char shown[48] = "n/a";
    if (isfinite(figure))
        snprintf(shown, sizeof shown, "%.4g %s", figure,
                 isfinite(r->ratio) ? r->unit : "s CPU");
    cl_bench_log(c, "[%d] %s: %s%s%s -> %s%s%s%s", r->workload, r->kase,
                 r->side_a, *r->side_b ? " vs " : "", r->side_b, shown,
                 r->met == 1 ? " (met)" : r->met == 0 ? " (not met)" : "",
                 *r->note ? "; " : "", r->note);
}
