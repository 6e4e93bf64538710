/* Benchmark workload 9 (bench/bench.h): the cost of self-contact in a
 * step of problems/fold.ini (its semi-be, dt = 1e-3 s), at t = 2.5 s,
 * when the upper half of the folded cloth lies on the lower half.  From
 * that state:
 *   step  W9_STEPS steps of the run: CPU time per step, and the force and
 *         Jacobian evaluations they make (the integrator's counters);
 *   term  the self-contact term alone (forces/selfcontact.h: the spatial
 *         hash rebuilt, its close pairs, forces, and the lumped blocks for
 *         a Jacobian evaluation), on the state reached, as many times per
 *         step as the steps evaluated it, repeated until the plan's
 *         eval_budget CPU seconds have passed;
 * share = term / step; goal <= 10 %. */
#include <stdlib.h>
#include <string.h>

#include "bench/bench_impl.h"
#include "core/stop.h"
#include "forces/selfcontact.h"

#define W9_T 2.5      /* the state measured (s) */
#define W9_STEPS 200  /* steps timed from it */

typedef struct {
    cl_model *m;
    const cl_system *sys;
    const cl_integrator_type *type;
    cl_integrator_opts io;
    void *integ;
    double *x, *v;          /* the run's free state */
    double *xf, *vf, *f;    /* full-particle state and forces (3 np) */
    double *dfdx;           /* pattern values */
    void *term;             /* a self-contact term of its own */
} w9_run;

static cl_status w9_start(cl_bmodel *bm, w9_run *r, cl_error *err)
{
    const char *name = cl_config_string(bm->cfg, "run", "integrator", "");
    const cl_cloth *c = cl_model_cloth(bm->m);
    cl_term_opts opts = {0};
    r->m = bm->m;
    r->sys = cl_model_system(bm->m);
    r->type = cl_integrator_find(name);
    r->x = malloc((r->sys->n + 1) * sizeof *r->x);
    r->v = malloc((r->sys->n + 1) * sizeof *r->v);
    r->xf = malloc(3 * c->np * sizeof *r->xf);
    r->vf = malloc(3 * c->np * sizeof *r->vf);
    r->f = malloc(3 * c->np * sizeof *r->f);
    r->dfdx = malloc((9 * r->sys->pattern->nnzb + 1) * sizeof *r->dfdx);
    if (!r->x || !r->v || !r->xf || !r->vf || !r->f || !r->dfdx ||
        cl_model_initial_state(bm->m, r->x, r->v))
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!r->type || !r->type->fixed_step)
        return cl_error_set(err, CL_EINVAL, "fold: [run] integrator \"%s\" "
                            "is not a registered fixed-step method", name);
    cl_status rc;
    if ((rc = cl_term_selfcontact.create(bm->cfg, c, &opts, &r->term,
                                         err)) ||
        (rc = !r->term ? cl_error_set(err, CL_EINVAL, "fold: [selfcontact] "
                                      "is not enabled")
                       : CL_OK) ||
        (rc = cl_term_selfcontact.bind(r->term, r->sys->pattern,
                                       c->dof, err)) ||
        (rc = cl_bench_fixed_opts(bm->cfg, 0.0, &r->io, err)))
        return rc;
    return r->type->create(r->sys, &r->io, 0.0, r->x, r->v, &r->integ, err);
}

static void w9_free(w9_run *r)
{
    if (r->integ)
        r->type->free(r->integ);
    if (r->term)
        cl_term_selfcontact.free(r->term);
    double *arrays[] = {r->x, r->v, r->xf, r->vf, r->f, r->dfdx};
    for (size_t k = 0; k < sizeof arrays / sizeof *arrays; k++)
        free(arrays[k]);
}

/* CPU seconds of one round of the term's evaluations of a step: nf force
 * evaluations and nj Jacobian evaluations (forces and blocks). */
static void w9_round(w9_run *r, double nf, double nj)
{
    size_t nval = 9 * r->sys->pattern->nnzb;
    for (long k = 0; k < (long)(nf + nj + 0.5); k++) {
        bool jac = k < (long)(nj + 0.5);
        memset(r->f, 0, 3 * cl_model_cloth(r->m)->np * sizeof *r->f);
        if (jac)
            memset(r->dfdx, 0, nval * sizeof *r->dfdx);
        cl_eval ev = {.x = r->xf, .v = r->vf, .f = r->f,
                      .dfdx = jac ? r->dfdx : NULL};
        cl_term_selfcontact.eval(r->term, &ev);
    }
}

static void w9_measure(cl_bctx *c, w9_run *r, cl_bench_row *row)
{
    cl_stats s0 = {0}, s1 = {0};
    cl_error err = {0};
    cl_status rc = r->type->advance(r->integ, W9_T, r->x, r->v, &err);
    double c0, w0, c1, w1;
    r->type->stats(r->integ, &s0);
    cl_bench_clock(&c0, &w0);
    if (!rc)
        rc = r->type->advance(r->integ, W9_T + W9_STEPS * r->io.dt, r->x,
                              r->v, &err);
    cl_bench_clock(&c1, &w1);
    r->type->stats(r->integ, &s1);
    if (rc) {
        cl_bench_note(row, "failed: %s", err.msg);
        return;
    }
    row->cpu_b = (c1 - c0) / W9_STEPS;
    row->wall_b = (w1 - w0) / W9_STEPS;
    double nf = (double)(s1.rhs_evals - s0.rhs_evals) / W9_STEPS;
    double nj = (double)(s1.jac_evals - s0.jac_evals) / W9_STEPS;
    cl_cloth_scatter(cl_model_cloth(r->m), W9_T, r->x, r->v, r->xf, r->vf);
    double closest = cl_selfcontact_closest(r->term, r->xf);
    long rounds = 0;
    cl_bench_clock(&c0, &w0);
    /* a signal stops the bench here too (its rows are dropped) */
    for (c1 = c0; (c1 - c0 < c->plan.eval_budget || rounds < 3) &&
                  !cl_stop_interrupted();
         rounds++) {
        w9_round(r, nf, nj);
        cl_bench_clock(&c1, &w1);
    }
    row->cpu_a = rounds ? (c1 - c0) / (double)rounds : NAN;
    row->wall_a = rounds ? (w1 - w0) / (double)rounds : NAN;
    cl_bench_judge(row, 100.0 * row->cpu_a / row->cpu_b, "%", "<=", 10.0);
    cl_bench_note(row, "%zu particles; closest non-neighbours %.3g m; per "
                  "step %.3g force and %.3g Jacobian evaluations: the term "
                  "%.3g us, the step %.3g us; %ld rounds",
                  cl_model_cloth(r->m)->np, closest, nf, nj,
                  1e6 * row->cpu_a, 1e6 * row->cpu_b, rounds);
}

void cl_bench_w9(cl_bctx *c)
{
    cl_bmodel bm;
    cl_error err = {0};
    cl_bench_row *row = cl_bench_row_add(c, 9, "fold t=2.5 s");
    snprintf(row->side_a, sizeof row->side_a, "self-contact term");
    snprintf(row->side_b, sizeof row->side_b, "a step");
    cl_bench_log(c, "  fold to t = %g s ...", W9_T);
    if (cl_bench_model(c, "fold", NULL, &bm, &err)) {
        cl_bench_note(row, "%s", err.msg);
        cl_bench_log_row(c, row);
        return;
    }
    w9_run r = {0};
    if (w9_start(&bm, &r, &err))
        cl_bench_note(row, "%s", err.msg);
    else
        w9_measure(c, &r, row);
    cl_bench_log_row(c, row);
    w9_free(&r);
    cl_bench_model_free(&bm);
}
