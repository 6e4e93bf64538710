/* Benchmark workload 8 (bench/bench.h): the contact share of a skirt
 * step.  problems/skirt.ini (a mesh cloth on a sphere mesh and a floor,
 * penalty contact) is run with its own integrator and step ([run]:
 * symplectic-euler-x, dt = 2e-4 s) to two states where the cloth touches:
 * t = 0.5 s, draped over the sphere (72 particles in contact when written,
 * none on the floor; by t = 0.8 s it has bounced off the soft penalty and
 * only 6 touch), and t = 3 s, on the floor (233).  At each state, in
 * interleaved rounds until the plan's eval_budget CPU seconds have
 * passed:
 *   contact  the contact term alone (cl_contact_term.eval on the
 *            full-particle arrays, as the model's force calls it);
 *   hook     the contact hook the fixed-step methods call after every step
 *            (sys->contact with record: the penetration, the projections);
 *   force    the model's whole force (every term, the contact term
 *            included; scatter and gather).
 * share = (contact + hook) / (force + hook), the contact part of a step
 * whose cost is its force evaluation and its hook; goal <= 25 %.  The
 * integrator's own work (a few vector updates) is left out of the
 * denominator; the note gives, beside it, the CPU time per step of the
 * next W8_STEPS steps of the run itself. */
#include <math.h>
#include <stdlib.h>

#include "bench/bench_impl.h"

#define W8_CHUNK 8    /* calls per clock reading */
#define W8_ROUNDS 10  /* rounds at least */
#define W8_STEPS 500  /* steps of the run timed after each state */

enum { W8_CONTACT, W8_HOOK, W8_FORCE, W8_PARTS };

/* The model, its integrator and the state being measured. */
typedef struct {
    cl_model *m;
    const cl_system *sys;
    const cl_integrator_type *type;
    void *integ;
    double dt, t;
    double *x, *v, *f;     /* free state and forces (sys->n each) */
    double *xf, *vf, *ff;  /* full-particle arrays (3 np each) */
    cl_eval ev;            /* the contact term's evaluation on xf, vf */
} w8_run;

static cl_status w8_call(w8_run *r, int part)
{
    const cl_system *sys = r->sys;
    if (part == W8_CONTACT) {
        cl_contact_term.eval(cl_model_contact_state(r->m), &r->ev);
        return CL_OK;
    }
    if (part == W8_HOOK)
        return sys->contact(sys->data, r->t, r->x, r->v, true);
    return sys->force(sys->data, r->t, r->x, r->v, r->f);
}

/* CPU and wall seconds per call of each part, interleaved in rounds of
 * W8_CHUNK calls each; the calls made of each part into *calls. */
static cl_status w8_time(w8_run *r, double budget, double cpu[W8_PARTS],
                         double wall[W8_PARTS], long *calls)
{
    double spent = 0.0;
    cl_status rc = CL_OK;
    long rounds = 0;
    for (int p = 0; p < W8_PARTS; p++)
        cpu[p] = wall[p] = 0.0;
    for (; !rc && (rounds < W8_ROUNDS || spent < budget); rounds++)
        for (int p = 0; p < W8_PARTS && !rc; p++) {
            double c0, w0, c1, w1;
            cl_bench_clock(&c0, &w0);
            for (int k = 0; k < W8_CHUNK && !rc; k++)
                rc = w8_call(r, p);
            cl_bench_clock(&c1, &w1);
            cpu[p] += c1 - c0;
            wall[p] += w1 - w0;
            spent += c1 - c0;
        }
    *calls = rounds * W8_CHUNK;
    for (int p = 0; p < W8_PARTS; p++) {
        cpu[p] /= (double)*calls;
        wall[p] /= (double)*calls;
    }
    return rc;
}

/* The run to t (from wherever it is), and the full arrays of that state. */
static cl_status w8_advance(w8_run *r, double t, cl_error *err)
{
    cl_status rc = r->type->advance(r->integ, t, r->x, r->v, err);
    r->t = t;
    cl_cloth_scatter(cl_model_cloth(r->m), t, r->x, r->v, r->xf, r->vf);
    r->ev = (cl_eval){.t = t, .x = r->xf, .v = r->vf, .f = r->ff};
    return rc;
}

/* CPU seconds per step of the next W8_STEPS steps of the run. */
static cl_status w8_steps(w8_run *r, double *per_step, cl_error *err)
{
    double c0, w0, c1, w1;
    cl_bench_clock(&c0, &w0);
    cl_status rc = r->type->advance(r->integ, r->t + W8_STEPS * r->dt, r->x,
                                    r->v, err);
    cl_bench_clock(&c1, &w1);
    *per_step = (c1 - c0) / W8_STEPS;
    return rc;
}

/* One state's row; false if the run or a measurement failed. */
static bool w8_state(cl_bctx *c, w8_run *r, double t, const char *where)
{
    char kase[48];
    snprintf(kase, sizeof kase, "skirt t=%g s (%s)", t, where);
    cl_bench_row *row = cl_bench_row_add(c, 8, kase);
    snprintf(row->side_a, sizeof row->side_a, "contact term + hook");
    snprintf(row->side_b, sizeof row->side_b, "force + hook");
    cl_bench_log(c, "  skirt to t = %g s (%s) ...", t, where);
    double cpu[W8_PARTS], wall[W8_PARTS], step = NAN;
    long calls = 0;
    cl_contact_figures fig = {0};
    cl_error err = {0};
    cl_status rc = w8_advance(r, t, &err);
    if (!rc)
        rc = cl_model_contact_figures(r->m, t, r->x, r->v, &fig);
    if (!rc)
        rc = w8_time(r, c->plan.eval_budget, cpu, wall, &calls);
    if (!rc)
        rc = w8_steps(r, &step, &err);
    if (rc) {
        cl_bench_note(row, "failed: %s", *err.msg ? err.msg
                                                  : cl_status_name(rc));
        cl_bench_log_row(c, row);
        return false;
    }
    size_t np = cl_model_cloth(r->m)->np;
    row->cpu_a = cpu[W8_CONTACT] + cpu[W8_HOOK];
    row->cpu_b = cpu[W8_FORCE] + cpu[W8_HOOK];
    row->wall_a = wall[W8_CONTACT] + wall[W8_HOOK];
    row->wall_b = wall[W8_FORCE] + wall[W8_HOOK];
    cl_bench_judge(row, 100.0 * row->cpu_a / row->cpu_b, "%", "<=", 25.0);
    cl_bench_note(row, "%zu particles, %zu in contact; contact %.1f ns/"
                  "particle (term %.3g us, hook %.3g us), force %.3g us; "
                  "%ld calls each; a step of the run %.3g us",
                  np, fig.contacts, 1e9 * row->cpu_a / (double)np,
                  1e6 * cpu[W8_CONTACT], 1e6 * cpu[W8_HOOK],
                  1e6 * cpu[W8_FORCE], calls, 1e6 * step);
    cl_bench_log_row(c, row);
    return true;
}

/* Integrator, step and arrays of the run; a note row when it cannot. */
static bool w8_start(cl_bctx *c, cl_bmodel *bm, w8_run *r)
{
    cl_error err = {0};
    cl_integrator_opts io = {0};
    const char *name = cl_config_string(bm->cfg, "run", "integrator", "");
    r->m = bm->m;
    r->sys = cl_model_system(bm->m);
    r->type = cl_integrator_find(name);
    size_t n = r->sys->n, n3 = 3 * cl_model_cloth(bm->m)->np;
    r->x = malloc(n * sizeof *r->x);
    r->v = malloc(n * sizeof *r->v);
    r->f = malloc(n * sizeof *r->f);
    r->xf = malloc(n3 * sizeof *r->xf);
    r->vf = malloc(n3 * sizeof *r->vf);
    r->ff = calloc(n3, sizeof *r->ff);
    cl_status rc = r->x && r->v && r->f && r->xf && r->vf && r->ff
                       ? cl_model_initial_state(bm->m, r->x, r->v)
                       : CL_ENOMEM;
    if (rc) {
        c->nomem = true;
        return false;
    }
    if (!r->type || !r->type->fixed_step || !r->sys->contact)
        rc = cl_error_set(&err, CL_EINVAL, "skirt: [run] integrator \"%s\" "
                          "is not a registered fixed-step method, or no "
                          "obstacle", name);
    if (!rc)
        rc = cl_bench_fixed_opts(bm->cfg, 0.0, &io, &err);
    if (!rc)
        rc = r->type->create(r->sys, &io, 0.0, r->x, r->v, &r->integ, &err);
    r->dt = io.dt;
    if (rc)
        cl_bench_note(cl_bench_row_add(c, 8, "skirt"), "%s", err.msg);
    return !rc;
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
    cl_model_contact_start(bm.m, false);
    w8_run r = {0};
    bool ok = w8_start(c, &bm, &r);
    for (size_t k = 0; ok && k < sizeof states / sizeof *states; k++)
        ok = w8_state(c, &r, states[k].t, states[k].where);
    if (r.integ)
        r.type->free(r.integ);
    free(r.x);
    free(r.v);
    free(r.f);
    free(r.xf);
    free(r.vf);
    free(r.ff);
    cl_bench_model_free(&bm);
}
