/* Benchmark workload 8 (bench/bench.h): the contact share of a skirt
 * step.  problems/skirt.ini (a mesh cloth on a sphere mesh and a floor,
 * penalty contact) is run with its own integrator and step ([run]:
 * symplectic-euler-x, dt = 2e-4 s) to two states where the cloth touches:
 * t = 0.5 s, draped over the sphere (72 particles in contact; by t = 0.8 s
 * it has bounced off the soft penalty and only 6 touch), and t = 3 s, on
 * the floor (about 240).  From each state:
 *   step     W8_STEPS steps of the run, each time by a new integrator
 *            from the same state, W8_REPEATS times: the CPU time per step;
 *   tape     the same steps once more, through a system that records the
 *            arguments of every force and contact-hook call before passing
 *            it on;
 * then, in interleaved rounds until the plan's eval_budget CPU seconds
 * have passed, the recorded calls are replayed in their order, each on a
 * copy of its arguments in the same work arrays (hot in the cache, as the
 * run's arrays are when the integrator has just written them):
 *   copy     the copies alone;
 *   other    for a force call the model's force over every term but the
 *            contact term (the system's force_terms), for a hook call
 *            nothing;
 *   terms    for a force call the force over every term, as the step
 *            calls it, for a hook call nothing;
 *   contact  the terms for a force call, the contact hook (sys->contact)
 *            for a hook call.
 * The contact term is timed where the step runs it, between the other
 * terms of the same force call (their arrays, the scatter of the state),
 * not alone on hot data, so that it is measured the way the step is.
 * The contact layer's memos and caches follow the states of the replay as
 * they follow those of the run, so a replay does the run's contact work:
 * the contact term costs terms - other, the hook contact - terms, and
 * share = (contact - other) per step / step; goal <= 25 %. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bench/bench_impl.h"

#define W8_STEPS 500  /* steps timed and recorded from each state */
#define W8_REPEATS 5  /* times the steps are timed */
#define W8_FORCES 4   /* force calls per step recorded at most */
#define W8_ROUNDS 3   /* replay rounds at least */

/* The replays (header comment). */
enum { W8_COPY, W8_OTHER, W8_TERMS, W8_CONTACT, W8_PARTS };

/* The recorded calls in their order (the hook calls marked in is_hook),
 * their states as free arrays (n each). */
typedef struct {
    const cl_system *inner;  /* the model's system, called on */
    size_t n;
    size_t nforce, nhook;    /* recorded */
    size_t max_force, max_hook;
    unsigned char *is_hook;  /* nforce + nhook calls */
    double *force_t, *force_x, *force_v;
    double *hook_t, *hook_x, *hook_v;
    unsigned char *hook_what;   /* the hook calls' CL_CONTACT_* */
} w8_tape;

/* The model, its integrator, the state measured and the work arrays. */
typedef struct {
    cl_model *m;
    const cl_system *sys;
    const cl_integrator_type *type;
    cl_integrator_opts io;
    void *integ;           /* the run */
    double *x, *v;         /* its state (sys->n each) */
    double t0, t1;         /* the steps measured: from t0 to t1 */
    double *x0, *v0;       /* the state at t0 */
    double *xw, *vw, *fw;  /* work arrays: a call's state (n each) */
    uint64_t other;        /* the term mask without the contact term */
    w8_tape tape;
} w8_run;

static cl_status tape_force(void *data, double t, const double *x,
                            const double *v, double *f)
{
    w8_tape *tp = data;
    if (tp->nforce < tp->max_force && tp->nhook < tp->max_hook) {
        tp->is_hook[tp->nforce + tp->nhook] = false;
        size_t k = tp->nforce++;
        tp->force_t[k] = t;
        memcpy(tp->force_x + k * tp->n, x, tp->n * sizeof *x);
        memcpy(tp->force_v + k * tp->n, v, tp->n * sizeof *v);
    }
    return tp->inner->force(tp->inner->data, t, x, v, f);
}

static cl_status tape_contact(void *data, double t, double *x, double *v,
                              unsigned what)
{
    w8_tape *tp = data;
    if (tp->nforce < tp->max_force && tp->nhook < tp->max_hook) {
        tp->is_hook[tp->nforce + tp->nhook] = true;
        size_t k = tp->nhook++;
        tp->hook_t[k] = t;
        memcpy(tp->hook_x + k * tp->n, x, tp->n * sizeof *x);
        memcpy(tp->hook_v + k * tp->n, v, tp->n * sizeof *v);
        tp->hook_what[k] = (unsigned char)what;
    }
    return tp->inner->contact(tp->inner->data, t, x, v, what);
}

static bool tape_alloc(w8_tape *tp, const cl_system *sys)
{
    *tp = (w8_tape){.inner = sys, .n = sys->n,
                    .max_force = W8_FORCES * W8_STEPS,
                    .max_hook = W8_STEPS + 1};
    tp->is_hook = malloc(tp->max_force + tp->max_hook);
    tp->force_t = malloc(tp->max_force * sizeof *tp->force_t);
    tp->force_x = malloc(tp->max_force * tp->n * sizeof *tp->force_x);
    tp->force_v = malloc(tp->max_force * tp->n * sizeof *tp->force_v);
    tp->hook_t = malloc(tp->max_hook * sizeof *tp->hook_t);
    tp->hook_x = malloc(tp->max_hook * tp->n * sizeof *tp->hook_x);
    tp->hook_v = malloc(tp->max_hook * tp->n * sizeof *tp->hook_v);
    tp->hook_what = malloc(tp->max_hook * sizeof *tp->hook_what);
    return tp->is_hook && tp->force_t && tp->force_x && tp->force_v &&
           tp->hook_t && tp->hook_x && tp->hook_v && tp->hook_what;
}

static void tape_free(w8_tape *tp)
{
    free(tp->is_hook);
    free(tp->force_t);
    free(tp->force_x);
    free(tp->force_v);
    free(tp->hook_t);
    free(tp->hook_x);
    free(tp->hook_v);
    free(tp->hook_what);
}

/* The steps from (t0, x0, v0) to t1 by a new integrator on sys, in the
 * work arrays. */
static cl_status w8_steps(w8_run *r, const cl_system *sys, cl_error *err)
{
    void *integ = NULL;
    memcpy(r->xw, r->x0, r->sys->n * sizeof *r->xw);
    memcpy(r->vw, r->v0, r->sys->n * sizeof *r->vw);
    cl_status rc = r->type->create(sys, &r->io, r->t0, r->xw, r->vw, &integ,
                                   err);
    if (!rc)
        rc = r->type->advance(integ, r->t1, r->xw, r->vw, err);
    if (integ)
        r->type->free(integ);
    return rc;
}

/* The force at the state measured, untimed, before each timed pass over
 * the steps: the contact layer's memos and caches then hold what the
 * run's evaluation before the first step left (a symplectic Euler step
 * evaluates at its new positions, so the one before evaluated at x0), not
 * what the end of the previous pass left, 0.1 s of motion later, which the
 * run never sees. */
static cl_status w8_prime(w8_run *r)
{
    memcpy(r->xw, r->x0, r->sys->n * sizeof *r->xw);
    memcpy(r->vw, r->v0, r->sys->n * sizeof *r->vw);
    return r->sys->force(r->sys->data, r->t0, r->xw, r->vw, r->fw);
}

/* CPU and wall seconds per step, the mean of W8_REPEATS timings. */
static cl_status w8_time_steps(w8_run *r, double *cpu, double *wall,
                               cl_error *err)
{
    cl_status rc = CL_OK;
    *cpu = *wall = 0.0;
    for (int k = 0; k < W8_REPEATS && !rc; k++) {
        double c0, w0, c1, w1;
        if ((rc = w8_prime(r)))
            break;
        cl_bench_clock(&c0, &w0);
        rc = w8_steps(r, r->sys, err);
        cl_bench_clock(&c1, &w1);
        *cpu += (c1 - c0) / (W8_REPEATS * W8_STEPS);
        *wall += (w1 - w0) / (W8_REPEATS * W8_STEPS);
    }
    return rc;
}

/* The steps once more on the recording system. */
static cl_status w8_record(w8_run *r, cl_error *err)
{
    cl_system rec = *r->sys;
    rec.data = &r->tape;
    rec.force = tape_force;
    rec.contact = tape_contact;
    r->tape.nforce = r->tape.nhook = 0;
    cl_status rc = w8_steps(r, &rec, err);
    if (!rc && (r->tape.nforce >= r->tape.max_force ||
                r->tape.nhook != W8_STEPS))
        rc = cl_error_set(err, CL_EINVAL, "%zu force and %zu hook calls in "
                          "%d steps: not one hook call a step, or more "
                          "than %d force calls", r->tape.nforce,
                          r->tape.nhook, W8_STEPS, W8_FORCES);
    return rc;
}

/* One replay of the recorded calls, in order. */
static cl_status w8_replay(w8_run *r, int part)
{
    w8_tape *tp = &r->tape;
    const cl_system *sys = r->sys;
    cl_status rc = CL_OK;
    size_t kf = 0, kh = 0;
    for (size_t k = 0; k < tp->nforce + tp->nhook && !rc; k++) {
        bool hook = tp->is_hook[k];
        size_t at = (hook ? kh : kf) * tp->n;
        memcpy(r->xw, (hook ? tp->hook_x : tp->force_x) + at,
               tp->n * sizeof *r->xw);
        memcpy(r->vw, (hook ? tp->hook_v : tp->force_v) + at,
               tp->n * sizeof *r->vw);
        if (hook && part == W8_CONTACT)
            rc = sys->contact(sys->data, tp->hook_t[kh], r->xw, r->vw,
                              tp->hook_what[kh]);
        if (!hook && part != W8_COPY)
            rc = sys->force_terms(sys->data,
                                  part == W8_OTHER ? r->other : UINT64_MAX,
                                  tp->force_t[kf], r->xw, r->vw, r->fw);
        kh += hook;
        kf += !hook;
    }
    return rc;
}

/* CPU and wall seconds per recorded step of each replay, the replays
 * interleaved; the rounds made into *rounds. */
static cl_status w8_time_replays(w8_run *r, double budget,
                                 double cpu[W8_PARTS], double wall[W8_PARTS],
                                 long *rounds)
{
    double spent = 0.0;
    cl_status rc = CL_OK;
    long k = 0;
    for (int p = 0; p < W8_PARTS; p++)
        cpu[p] = wall[p] = 0.0;
    for (; !rc && (k < W8_ROUNDS || spent < budget); k++)
        for (int p = 0; p < W8_PARTS && !rc; p++) {
            double c0, w0, c1, w1;
            if ((rc = w8_prime(r)))
                break;
            cl_bench_clock(&c0, &w0);
            rc = w8_replay(r, p);
            cl_bench_clock(&c1, &w1);
            cpu[p] += c1 - c0;
            wall[p] += w1 - w0;
            spent += c1 - c0;
        }
    *rounds = k;
    for (int p = 0; p < W8_PARTS; p++) {
        cpu[p] /= (double)k * W8_STEPS;
        wall[p] /= (double)k * W8_STEPS;
    }
    return rc;
}

/* The row of the state at t: the figure, and a note of its parts. */
static void w8_judge(cl_bctx *c, w8_run *r, cl_bench_row *row,
                     size_t contacts, const double cpu[W8_PARTS],
                     const double wall[W8_PARTS], long rounds)
{
    size_t np = cl_model_cloth(r->m)->np;
    double contact = cpu[W8_TERMS] - cpu[W8_OTHER];
    double hook = cpu[W8_CONTACT] - cpu[W8_TERMS];
    double other = cpu[W8_OTHER] - cpu[W8_COPY];
    row->cpu_a = cpu[W8_CONTACT] - cpu[W8_OTHER];
    row->wall_a = wall[W8_CONTACT] - wall[W8_OTHER];
    cl_bench_judge(row, 100.0 * row->cpu_a / row->cpu_b, "%", "<=", 25.0);
    cl_bench_note(row, "%zu particles, %zu in contact at t; per step: "
                  "contact term %.3g us, hook %.3g us (%.1f ns a "
                  "particle), the other terms %.3g us, the step %.3g us; "
                  "%d steps, their %zu force calls replayed %ld times",
                  np, contacts, 1e6 * contact, 1e6 * hook,
                  1e9 * row->cpu_a / (double)np, 1e6 * other,
                  1e6 * row->cpu_b, W8_STEPS, r->tape.nforce, rounds);
    cl_bench_log_row(c, row);
}

/* One state's row; false if the run or a measurement failed. */
static bool w8_state(cl_bctx *c, w8_run *r, double t, const char *where)
{
    char kase[48];
    snprintf(kase, sizeof kase, "skirt t=%g s (%s)", t, where);
    cl_bench_row *row = cl_bench_row_add(c, 8, kase);
    snprintf(row->side_a, sizeof row->side_a, "contact term + hook");
    snprintf(row->side_b, sizeof row->side_b, "a step");
    cl_bench_log(c, "  skirt to t = %g s (%s) ...", t, where);
    double cpu[W8_PARTS], wall[W8_PARTS];
    long rounds = 0;
    cl_contact_figures fig = {0};
    cl_error err = {0};
    size_t n = r->sys->n;
    cl_status rc = r->type->advance(r->integ, t, r->x, r->v, &err);
    if (!rc)
        rc = cl_model_contact_figures(r->m, t, r->x, r->v, &fig);
    r->t0 = t;
    r->t1 = t + W8_STEPS * r->io.dt;
    memcpy(r->x0, r->x, n * sizeof *r->x);
    memcpy(r->v0, r->v, n * sizeof *r->v);
    if (!rc)
        rc = w8_time_steps(r, &row->cpu_b, &row->wall_b, &err);
    if (!rc)
        rc = w8_record(r, &err);
    if (!rc)
        rc = w8_time_replays(r, c->plan.eval_budget, cpu, wall, &rounds);
    if (rc) {
        cl_bench_note(row, "failed: %s", *err.msg ? err.msg
                                                  : cl_status_name(rc));
        cl_bench_log_row(c, row);
        return false;
    }
    w8_judge(c, r, row, fig.contacts, cpu, wall, rounds);
    return true;
}

/* Integrator, step and arrays of the run; a note row when it cannot. */
static bool w8_start(cl_bctx *c, cl_bmodel *bm, w8_run *r)
{
    cl_error err = {0};
    const char *name = cl_config_string(bm->cfg, "run", "integrator", "");
    r->m = bm->m;
    r->sys = cl_model_system(bm->m);
    r->type = cl_integrator_find(name);
    size_t n = r->sys->n;
    double **arrays[] = {&r->x, &r->v, &r->x0, &r->v0, &r->xw, &r->vw,
                         &r->fw};
    bool ok = tape_alloc(&r->tape, r->sys);
    for (size_t k = 0; k < sizeof arrays / sizeof *arrays; k++)
        ok &= (*arrays[k] = malloc(n * sizeof **arrays[k])) != NULL;
    if (!ok || cl_model_initial_state(bm->m, r->x, r->v)) {
        c->nomem = true;
        return false;
    }
    cl_status rc = CL_OK;
    const char *const *terms;
    size_t nterm = cl_model_terms(r->m, &terms), kc = 0;
    while (kc < nterm && strcmp(terms[kc], cl_contact_term.name))
        kc++;
    r->other = UINT64_MAX & ~(kc < nterm ? UINT64_C(1) << kc : 0);
    if (!r->type || !r->type->fixed_step || !r->sys->contact ||
        !r->sys->force_terms || kc == nterm)
        rc = cl_error_set(&err, CL_EINVAL, "skirt: [run] integrator \"%s\" "
                          "is not a registered fixed-step method, or no "
                          "obstacle", name);
    if (!rc)
        rc = cl_bench_fixed_opts(bm->cfg, 0.0, &r->io, &err);
    if (!rc)
        rc = r->type->create(r->sys, &r->io, 0.0, r->x, r->v, &r->integ,
                             &err);
    if (rc)
        cl_bench_note(cl_bench_row_add(c, 8, "skirt"), "%s", err.msg);
    return !rc;
}

static void w8_free(w8_run *r)
{
    if (r->integ)
        r->type->free(r->integ);
    double *arrays[] = {r->x, r->v, r->x0, r->v0, r->xw, r->vw, r->fw};
    for (size_t k = 0; k < sizeof arrays / sizeof *arrays; k++)
        free(arrays[k]);
    tape_free(&r->tape);
}

void cl_bench_w8(cl_bctx *c)
{
    static const struct {
        double t;
        const char *where;
    } states[] = {{0.5, "sphere"}, {3.0, "floor"}};
    cl_bmodel bm;
    cl_error err = {0};
    if (cl_bench_model(c, "skirt", NULL, &bm, &err)) {
        cl_bench_note(cl_bench_row_add(c, 8, "skirt"), "%s", err.msg);
        return;
    }
    cl_model_contact_start(bm.m, 0.0, false); /* penalty: no sweep */
    w8_run r = {0};
    bool ok = w8_start(c, &bm, &r);
    for (size_t k = 0; ok && k < sizeof states / sizeof *states; k++)
        ok = w8_state(c, &r, states[k].t, states[k].where);
    w8_free(&r);
    cl_bench_model_free(&bm);
}
