/* The obstacles of a problem as a force term (penalty) and a projection
 * (contact.h; docs/model.md, contact). */
#include "contact/contact.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "contact/barrier.h"
#include "contact/constraint.h"
#include "contact/penalty.h"
#include "contact/project.h"
#include "core/vec3.h"

#define PREFIX "obstacle."
#define ON_SURFACE CL_ON_SURFACE /* a projected particle counts as touching */

struct cl_contact {
    const cl_cloth *cloth;
    size_t nobs;
    cl_obstacle *obs;
    cl_pose *pose;           /* scratch: every obstacle's pose at a time */
    cl_contact_memo *memo;   /* np per obstacle: the last exact distances */
    unsigned char *cache;    /* the shapes' caches the memos point into */
    size_t *near;            /* scratch: the particles near one obstacle */
    cl_contact_point *hit;   /* scratch: their contact points */
    cl_contact_slim *slim;   /* ... without derivatives (no Jacobian) */
    bool barriers;           /* some obstacle has response = barrier */
    bool infeasible;         /* the last evaluation had a free particle at
                                d <= 0 of a barrier obstacle */
    double *lambda;          /* np per obstacle: the lagged normal force
                                of a barrier's friction (barrier.h) */
    double (*lag_n)[3];      /* ... and the lagged normal */
    bool penalizes, projects, constrains, sweeps;
    double *swept_x;         /* positions after the last projection (sweeps:
                              * some obstacle has ccd), at last_t */
    bool swept;              /* swept_x holds them */
    cl_constraint *cons;     /* np: each particle's constraint (constrains) */
    size_t *cons_obs;        /* np: the obstacle it is on */
    long passes;             /* projection passes */
    long *slot;              /* diagonal block of each particle, or -1 */
    double last_t;           /* time of the last projection */
    double last_dt;          /* ... and the time from the one before */
    double proj_force;       /* its impulses / last_dt */
    double proj_friction;    /* its friction energy / last_dt */
    /* The last accepted projection (cl_contact_project's trials): its
     * last_t, swept and swept_x, which a trial starts from; acc_live:
     * they are the live ones above (no trial since). */
    double acc_t;
    double *acc_swept_x;
    bool acc_swept, acc_live;
    double *eval_x;          /* positions of the last term evaluation */
    cl_pose *eval_pose;      /* ... every penalty obstacle's pose there */
    double *eval_worst;      /* ... each penalty obstacle's deepest
                                penetration of a free particle there */
    bool evaluated;          /* eval_* hold an evaluation */
};

bool cl_contact_projects(const cl_contact *c) { return c->projects; }

bool cl_contact_projects_friction(const cl_contact *c)
{
    for (size_t k = 0; k < c->nobs; k++) {
        const cl_response_params *r = &c->obs[k].resp;
        if (r->kind == CL_RESPONSE_PROJECT && (r->mu > 0 || r->zero_velocity))
            return true;
    }
    return false;
}

bool cl_contact_constrains(const cl_contact *c) { return c->constrains; }

size_t cl_contact_obstacles(const cl_contact *c) { return c->nobs; }

const cl_obstacle *cl_contact_obstacle(const cl_contact *c, size_t k)
{
    return &c->obs[k];
}

/* The memo of particle p and obstacle k. */
static cl_contact_memo *memo_of(cl_contact *c, size_t k, size_t p)
{
    return &c->memo[k * c->cloth->np + p];
}

/* ---- the term --------------------------------------------------------- */

static void contact_free(void *state)
{
    cl_contact *c = state;
    if (!c)
        return;
    for (size_t k = 0; k < c->nobs; k++)
        cl_obstacle_free(&c->obs[k]);
    free(c->obs);
    free(c->pose);
    free(c->memo);
    free(c->cache);
    free(c->near);
    free(c->hit);
    free(c->slim);
    free(c->slot);
    free(c->eval_x);
    free(c->eval_pose);
    free(c->eval_worst);
    free(c->lambda);
    free(c->lag_n);
    free(c->cons);
    free(c->cons_obs);
    free(c->swept_x);
    free(c->acc_swept_x);
    free(c);
}

/* The size of every shape cache together. */
static size_t caches_size(const cl_contact *c)
{
    size_t total = 0;
    for (size_t k = 0; k < c->nobs; k++)
        total += c->cloth->np * c->obs[k].type->cache_size;
    return total;
}

/* Every memo empty, pointing at its zeroed shape cache (if any). */
static void reset_memos(cl_contact *c)
{
    size_t np = c->cloth->np;
    unsigned char *at = c->cache;
    if (at)
        memset(at, 0, caches_size(c));
    for (size_t k = 0; k < c->nobs; k++) {
        size_t size = c->obs[k].type->cache_size;
        for (size_t p = 0; p < np; p++, at += size)
            *memo_of(c, k, p) = (cl_contact_memo){
                .d = -INFINITY, .cache = size ? at : NULL};
    }
}

static cl_status start_memos(cl_contact *c, cl_error *err)
{
    size_t total = caches_size(c);
    if (total && !(c->cache = malloc(total)))
        return cl_error_set(err, CL_ENOMEM, "out of memory (obstacles)");
    reset_memos(c);
    return CL_OK;
}

void cl_contact_restart(cl_contact *c, double t0)
{
    c->swept = false;
    for (size_t p = 0; c->constrains && p < c->cloth->np; p++)
        c->cons[p].mode = CL_CONSTRAINT_FREE;
    c->last_t = t0;
    c->last_dt = 0.0;
    c->proj_force = c->proj_friction = 0.0;
    c->acc_live = true;
    memset(c->lambda, 0, c->nobs * c->cloth->np * sizeof *c->lambda);
    reset_memos(c); /* an earlier run's distances are not this one's */
}

static cl_status contact_create(cl_config *cfg, const cl_cloth *cloth,
                                const cl_term_opts *opts, void **state,
                                cl_error *err)
{
    (void)opts;
    *state = NULL;
    size_t n = 0;
    while (cl_config_section_at(cfg, PREFIX, n))
        n++;
    if (n == 0)
        return CL_OK;
    cl_contact *c = calloc(1, sizeof *c);
    if (!c || !(c->obs = calloc(n, sizeof *c->obs)) ||
        !(c->pose = calloc(n, sizeof *c->pose)) ||
        !(c->memo = malloc(n * cloth->np * sizeof *c->memo)) ||
        !(c->near = malloc(cloth->np * sizeof *c->near)) ||
        !(c->hit = malloc(cloth->np * sizeof *c->hit)) ||
        !(c->slim = malloc(cloth->np * sizeof *c->slim)) ||
        !(c->slot = malloc(cloth->np * sizeof *c->slot)) ||
        !(c->eval_x = malloc(3 * cloth->np * sizeof *c->eval_x)) ||
        !(c->eval_pose = calloc(n, sizeof *c->eval_pose)) ||
        !(c->eval_worst = calloc(n, sizeof *c->eval_worst)) ||
        !(c->lambda = calloc(n * cloth->np, sizeof *c->lambda)) ||
        !(c->lag_n = calloc(n * cloth->np, sizeof *c->lag_n))) {
        contact_free(c);
        return cl_error_set(err, CL_ENOMEM, "out of memory (obstacles)");
    }
    c->cloth = cloth;
    for (; c->nobs < n; c->nobs++) {
        cl_obstacle *o = &c->obs[c->nobs];
        cl_status rc = cl_obstacle_create(
            cfg, cl_config_section_at(cfg, PREFIX, c->nobs), o, err);
        if (rc) {
            c->nobs++;
            contact_free(c);
            return rc;
        }
        c->penalizes |= o->resp.kind == CL_RESPONSE_PENALTY;
        c->projects |= o->resp.kind == CL_RESPONSE_PROJECT;
        c->barriers |= o->resp.kind == CL_RESPONSE_BARRIER;
        c->constrains |= o->resp.kind == CL_RESPONSE_CONSTRAINT;
        c->sweeps |= o->resp.kind == CL_RESPONSE_PROJECT && o->resp.ccd;
        if (o->resp.kind == CL_RESPONSE_PROJECT && o->resp.iterations >
                                                       c->passes)
            c->passes = o->resp.iterations;
    }
    cl_status rc = start_memos(c, err);
    if (!rc && c->constrains &&
        (!(c->cons = calloc(cloth->np, sizeof *c->cons)) ||
         !(c->cons_obs = calloc(cloth->np, sizeof *c->cons_obs))))
        rc = cl_error_set(err, CL_ENOMEM, "out of memory (obstacles)");
    if (!rc && c->sweeps &&
        (!(c->swept_x = malloc(3 * cloth->np * sizeof *c->swept_x)) ||
         !(c->acc_swept_x = malloc(3 * cloth->np * sizeof *c->swept_x))))
        rc = cl_error_set(err, CL_ENOMEM, "out of memory (obstacles)");
    if (rc) {
        contact_free(c);
        return rc;
    }
    *state = c;
    return CL_OK;
}

static size_t contact_couplings(const void *state, const int (**pairs)[2])
{
    (void)state;
    *pairs = NULL; /* diagonal blocks only: always in the pattern */
    return 0;
}

static cl_status contact_bind(void *state, const cl_bpattern *pat,
                              const int *dof, cl_error *err)
{
    cl_contact *c = state;
    (void)err;
    for (size_t p = 0; p < c->cloth->np; p++)
        c->slot[p] = cl_bpattern_find(pat, dof[p], dof[p]);
    return CL_OK;
}

static void add_block(double *vals, long slot, const double b[9])
{
    for (int k = 0; k < 9; k++)
        vals[9 * slot + k] += b[k];
}

/* The particles with a block (the free particles; all of them for the
 * full Jacobian of `clothode eval`) that obstacle k's screen at pose P
 * does not show beyond its reach dmax, into c->near; their number. */
static size_t screened(cl_contact *c, size_t k, const cl_pose *P,
                       const cl_eval *ev, double dmax)
{
    size_t n = cl_obstacle_screen(&c->obs[k], P, ev->x, c->cloth->np, dmax,
                                  memo_of(c, k, 0), c->near), m = 0;
    for (size_t i = 0; i < n; i++)
        if (c->slot[c->near[i]] >= 0)
            c->near[m++] = c->near[i];
    return m;
}

/* Particle p at signed distance d from obstacle k: eval_worst[k] raised
 * to its penetration depth -d if p is free and deeper than those before. */
static void deepen(cl_contact *c, size_t k, size_t p, double d)
{
    if (c->cloth->dof[p] >= 0 && -d > c->eval_worst[k])
        c->eval_worst[k] = -d;
}

/* The particles with a block within obstacle k's reach dmax at pose P:
 * their indices into c->near and contact points into c->hit, and their
 * number.  The deepest penetration of a free particle there is kept in
 * eval_worst[k] (every particle inside, d < 0 <= dmax, is within the
 * reach, so it is among those queried here).  The points are all queried
 * first and the laws applied after (by the caller), so that the laws
 * (square roots and divisions, independent of one another) overlap in the
 * processor instead of each waiting for its own query. */
static size_t gather(cl_contact *c, size_t k, const cl_pose *P,
                     const cl_eval *ev, double dmax)
{
    const cl_obstacle *o = &c->obs[k];
    size_t nnear = screened(c, k, P, ev, dmax), nhit = 0;
    c->eval_worst[k] = 0.0;
    for (size_t i = 0; i < nnear; i++) {
        size_t p = c->near[i];
        cl_contact_point *q = &c->hit[nhit];
        if (!cl_obstacle_near(o, P, ev->x + 3 * p, dmax, memo_of(c, k, p), q))
            continue;
        deepen(c, k, p, q->d); /* q.d < dmax: a number */
        c->near[nhit++] = p;
    }
    return nhit;
}

/* gather() without derivatives, the points into c->slim: what a force
 * without its Jacobian reads. */
static size_t gather_slim(cl_contact *c, size_t k, const cl_pose *P,
                          const cl_eval *ev, double dmax)
{
    size_t nhit = cl_obstacle_near_slim(&c->obs[k], P, ev->x, dmax,
                                        memo_of(c, k, 0), c->near,
                                        screened(c, k, P, ev, dmax), c->slim);
    c->eval_worst[k] = 0.0;
    for (size_t i = 0; i < nhit; i++)
        deepen(c, k, c->near[i], c->slim[i].d);
    return nhit;
}

/* The penalty forces of obstacle k (at pose P) without Jacobians, their
 * energy and power added to *energy and *power. */
static void penalty_forces(cl_contact *c, size_t k, const cl_pose *P,
                           cl_eval *ev, double *energy, double *power)
{
    const cl_obstacle *o = &c->obs[k];
    size_t nhit = gather_slim(c, k, P, ev, o->resp.eps);
    cl_penalty_forces(&o->resp, c->slim, c->near, nhit, ev->v, ev->f, energy,
                      power);
}

/* Add one particle's force and Jacobian blocks. */
static void add_particle(cl_contact *c, cl_eval *ev, size_t p,
                         const double f[3], const double dfdx[9],
                         const double dfdv[9])
{
    if (ev->f)
        cl_v3_add(ev->f + 3 * p, f, ev->f + 3 * p);
    if (ev->dfdx)
        add_block(ev->dfdx, c->slot[p], dfdx);
    if (ev->dfdv)
        add_block(ev->dfdv, c->slot[p], dfdv);
}

/* The barrier forces of obstacle k (at pose P) on its nhit gathered
 * particles, then the lagged friction of every particle with a block and
 * a lagged normal force; a free particle at d <= 0 makes the state
 * infeasible (energy +infinity). */
static void barrier_eval(cl_contact *c, size_t k, const cl_pose *P,
                         size_t nhit, cl_eval *ev, bool jac, double *energy,
                         double *power)
{
    const cl_obstacle *o = &c->obs[k];
    const double *lambda = c->lambda + k * c->cloth->np;
    cl_barrier_out out;
    for (size_t i = 0; i < nhit; i++) {
        size_t p = c->near[i];
        if (!(c->hit[i].d > 0.0) && c->cloth->dof[p] >= 0) {
            c->infeasible = true;
            *energy = INFINITY;
        }
        if (!cl_barrier_eval(&o->resp, &c->hit[i], jac, &out))
            continue;
        add_particle(c, ev, p, out.f, out.dfdx, out.dfdv);
        *energy += out.energy;
    }
    for (size_t p = 0; o->resp.mu > 0.0 && p < c->cloth->np; p++) {
        double u[3];
        if (!(lambda[p] > 0.0) || c->slot[p] < 0)
            continue;
        cl_obstacle_velocity(o, P, ev->x + 3 * p, u);
        cl_barrier_friction(&o->resp, c->lag_n[k * c->cloth->np + p],
                            lambda[p], u, P->W, ev->v + 3 * p, jac, &out);
        add_particle(c, ev, p, out.f, out.dfdx, out.dfdv);
        *power += out.power;
    }
}

/* Penalty and barrier forces of every particle that has a block.  The
 * deepest penetration of a free particle into each penalty obstacle is
 * kept with the positions and the obstacles' poses (gather): the contact
 * hook of a step that ends at the very state evaluated last (a symplectic
 * Euler step evaluates its forces at its new positions) reads it from
 * there instead of screening the particles again. */
static void contact_eval(void *state, cl_eval *ev)
{
    cl_contact *c = state;
    bool jac = ev->dfdx || ev->dfdv;
    double energy = 0.0, power = 0.0;
    c->infeasible = false;
    for (size_t k = 0; k < c->nobs && (c->penalizes || c->barriers); k++) {
        const cl_obstacle *o = &c->obs[k];
        cl_pose *P = &c->eval_pose[k];
        if (o->resp.kind == CL_RESPONSE_PROJECT)
            continue;
        cl_obstacle_pose(o, ev->t, P);
        if (o->resp.kind == CL_RESPONSE_PENALTY && !jac) {
            penalty_forces(c, k, P, ev, &energy, &power);
            continue;
        }
        bool barrier = o->resp.kind == CL_RESPONSE_BARRIER;
        size_t nhit = gather(c, k, P, ev,
                             barrier ? o->resp.dhat : o->resp.eps);
        if (barrier) {
            barrier_eval(c, k, P, nhit, ev, jac, &energy, &power);
            continue;
        }
        for (size_t i = 0; i < nhit; i++) {
            size_t p = c->near[i];
            cl_penalty_out out;
            if (!cl_penalty_eval(&o->resp, &c->hit[i], ev->v + 3 * p, jac,
                                 &out))
                continue;
            add_particle(c, ev, p, out.f, out.dfdx, out.dfdv);
            energy += out.energy;
            power += out.power;
        }
    }
    if (ev->want_energy) {
        ev->energy = energy;
        ev->power = power;
    }
    if (c->penalizes) {
        memcpy(c->eval_x, ev->x, 3 * c->cloth->np * sizeof *c->eval_x);
        c->evaluated = true;
    }
}

const cl_term_type cl_contact_term = {
    .name = "contact",
    .doc = "obstacles [obstacle.NAME]: penalty and barrier forces; "
           "projection after the steps; constraints in semi-be/semi-bdf2",
    .conservative = true,
    .create = contact_create,
    .couplings = contact_couplings,
    .bind = contact_bind,
    .eval = contact_eval,
    .free = contact_free,
};

/* ---- figures and projection ------------------------------------------ */

/* The distance within which a particle counts as touching. */
static double reach(const cl_response_params *r)
{
    return r->kind == CL_RESPONSE_PENALTY   ? r->eps
           : r->kind == CL_RESPONSE_BARRIER ? r->dhat
                                            : r->offset + ON_SURFACE;
}

/* Every obstacle's pose at t into c->pose. */
static void place(cl_contact *c, double t)
{
    for (size_t k = 0; k < c->nobs; k++)
        cl_obstacle_pose(&c->obs[k], t, &c->pose[k]);
}

/* A barrier's force on particle p (added to fp) and its friction's power
 * (to f). */
static void barrier_force(const cl_contact *c, size_t k, size_t p,
                          const cl_contact_point *q, const double v[3],
                          double fp[3], cl_contact_figures *f)
{
    const cl_obstacle *o = &c->obs[k];
    size_t at = k * c->cloth->np + p;
    cl_barrier_out out;
    if (cl_barrier_eval(&o->resp, q, false, &out))
        for (int i = 0; i < 3; i++)
            fp[i] += out.f[i];
    if (o->resp.mu == 0.0 || !(c->lambda[at] > 0.0))
        return;
    cl_barrier_friction(&o->resp, c->lag_n[at], c->lambda[at], q->u, q->W,
                        v, false, &out);
    for (int i = 0; i < 3; i++)
        fp[i] += out.f[i];
    f->friction_power += out.power;
}

void cl_contact_measure(cl_contact *c, double t, const double *x,
                        const double *v, cl_contact_figures *f)
{
    const cl_cloth *cl = c->cloth;
    memset(f, 0, sizeof *f);
    place(c, t);
    for (size_t p = 0; p < cl->np; p++) {
        double fp[3] = {0.0, 0.0, 0.0};
        bool in = false;
        if (cl->dof[p] < 0)
            continue;
        for (size_t k = 0; k < c->nobs; k++) {
            const cl_obstacle *o = &c->obs[k];
            cl_contact_point q;
            cl_penalty_out out;
            if (!cl_obstacle_near(o, &c->pose[k], x + 3 * p, reach(&o->resp),
                                  memo_of(c, k, p), &q))
                continue;
            f->max_penetration = fmax(f->max_penetration, -q.d);
            in = true; /* near() answered d < reach */
            if (o->resp.kind == CL_RESPONSE_BARRIER) {
                barrier_force(c, k, p, &q, v + 3 * p, fp, f);
                continue;
            }
            if (o->resp.kind != CL_RESPONSE_PENALTY ||
                !cl_penalty_eval(&o->resp, &q, v + 3 * p, false, &out))
                continue;
            for (int i = 0; i < 3; i++)
                fp[i] += out.f[i];
            f->friction_power += out.friction_power;
        }
        f->contacts += in;
        f->force += sqrt(fp[0] * fp[0] + fp[1] * fp[1] + fp[2] * fp[2]);
    }
    if (c->projects) {
        f->force += c->proj_force;
        f->friction_power += c->proj_friction;
    }
    f->min_distance = c->barriers ? cl_contact_min_distance(c, t, x)
                                  : INFINITY;
}

/* Whether obstacle k stands at pose P where the last evaluation saw it:
 * the same displacement and rotation (its velocity does not move a
 * particle), so that a time that differs from the evaluation's in the
 * last bits (t0 + (k + 1) h against t0 + k h + h) still finds a static
 * obstacle in its place. */
static bool placed_as_evaluated(const cl_contact *c, size_t k,
                                const cl_pose *P)
{
    const cl_pose *E = &c->eval_pose[k];
    return P->rotates == E->rotates && !memcmp(P->s, E->s, sizeof P->s) &&
           (!P->rotates || !memcmp(P->R, E->R, sizeof P->R));
}

double cl_contact_penetration(cl_contact *c, double t, const double *x)
{
    double worst = 0.0;
    bool evaluated = c->evaluated &&
                     !memcmp(x, c->eval_x,
                             3 * c->cloth->np * sizeof *c->eval_x);
    place(c, t);
    for (size_t k = 0; k < c->nobs; k++) {
        if (evaluated && c->obs[k].resp.kind == CL_RESPONSE_PENALTY &&
            placed_as_evaluated(c, k, &c->pose[k])) {
            worst = fmax(worst, c->eval_worst[k]); /* contact_eval */
            continue;
        }
        size_t nnear = cl_obstacle_screen(&c->obs[k], &c->pose[k], x,
                                          c->cloth->np, 0.0,
                                          memo_of(c, k, 0), c->near);
        for (size_t i = 0; i < nnear; i++) {
            size_t p = c->near[i];
            double d;
            if (c->cloth->dof[p] >= 0 &&
                cl_obstacle_depth(&c->obs[k], &c->pose[k], x + 3 * p, 0.0,
                                  memo_of(c, k, p), &d))
                worst = fmax(worst, -d);
        }
    }
    return worst;
}

/* Continuous detection (docs/model.md, eq. C14): every free particle's
 * path from its position after the last projection (at last_t) to x,
 * against every obstacle with ccd; the first hit over them stops it
 * there, with projection's velocity response.  The first projection of
 * a run has no earlier one: its paths run back from x along v over the
 * step (from the position before the step for the methods whose step
 * ends x_{n+1} = x_n + h v_{n+1}: symplectic Euler, semi-be). */
static void sweep(cl_contact *c, double t, double *x, double *v,
                  cl_project_tally *tally)
{
    const cl_cloth *cl = c->cloth;
    if (!c->swept)
        for (size_t i = 0; i < 3 * cl->np; i++)
            c->swept_x[i] = x[i] - (t - c->last_t) * v[i];
    for (size_t p = 0; p < cl->np; p++) {
        double first = INFINITY, s, at[3], hit[3];
        size_t k_hit = 0;
        for (size_t k = 0; k < c->nobs && cl->dof[p] >= 0; k++) {
            const cl_obstacle *o = &c->obs[k];
            cl_pose P0;
            if (o->resp.kind != CL_RESPONSE_PROJECT || !o->resp.ccd)
                continue;
            cl_obstacle_pose(o, c->last_t, &P0);
            if (cl_obstacle_sweep(o, &P0, c->swept_x + 3 * p, &c->pose[k],
                                  x + 3 * p, o->resp.offset, &s, at) &&
                s < first) {
                first = s;
                k_hit = k;
                memcpy(hit, at, sizeof hit);
            }
        }
        if (first > 1.0)
            continue;
        const cl_obstacle *o = &c->obs[k_hit];
        cl_contact_point q;
        memcpy(x + 3 * p, hit, sizeof hit);
        cl_obstacle_near(o, &c->pose[k_hit], x + 3 * p, INFINITY,
                         memo_of(c, k_hit, p), &q);
        cl_project_hit(&o->resp, &q, cl->mass[p], x + 3 * p, v + 3 * p,
                       tally);
    }
}

/* A trial starts from the last accepted projection: the first trial since
 * keeps it (the live bookkeeping), a later one restores it. */
static void trial_start(cl_contact *c)
{
    size_t len = 3 * c->cloth->np * sizeof *c->swept_x;
    if (c->acc_live) {
        c->acc_t = c->last_t;
        c->acc_swept = c->swept;
        if (c->sweeps && c->swept)
            memcpy(c->acc_swept_x, c->swept_x, len);
    } else {
        c->last_t = c->acc_t;
        c->swept = c->acc_swept;
        if (c->sweeps && c->swept)
            memcpy(c->swept_x, c->acc_swept_x, len);
    }
    c->acc_live = false;
}

/* The figures of a projection at t: its impulses and friction energy over
 * the time since the last one; a second projection at the same time (an
 * output at the end of a step projected already) adds its own to the
 * first's over that step. */
static void project_figures(cl_contact *c, double t,
                            const cl_project_tally *tally)
{
    double dt = t - c->last_t;
    if (dt > 0.0) {
        c->last_dt = dt;
        c->proj_force = tally->impulse / dt;
        c->proj_friction = tally->friction_energy / dt;
    } else if (dt == 0.0 && c->last_dt > 0.0) {
        c->proj_force += tally->impulse / c->last_dt;
        c->proj_friction += tally->friction_energy / c->last_dt;
    } else if (dt < 0.0) {
        c->proj_force = c->proj_friction = 0.0;
    }
}

size_t cl_contact_project(cl_contact *c, double t, double *x, double *v,
                          bool trial)
{
    const cl_cloth *cl = c->cloth;
    cl_project_tally tally = {0, 0.0, 0.0};
    if (trial)
        trial_start(c);
    place(c, t);
    if (c->sweeps && c->last_t < t)
        sweep(c, t, x, v, &tally);
    for (long pass = 0; pass < c->passes; pass++)
        for (size_t k = 0; k < c->nobs; k++) {
            const cl_obstacle *o = &c->obs[k];
            if (o->resp.kind != CL_RESPONSE_PROJECT ||
                pass >= o->resp.iterations)
                continue;
            size_t nnear = cl_obstacle_screen(o, &c->pose[k], x, cl->np,
                                              o->resp.offset,
                                              memo_of(c, k, 0), c->near);
            for (size_t i = 0; i < nnear; i++) {
                size_t p = c->near[i];
                cl_contact_point q;
                if (cl->dof[p] >= 0 &&
                    cl_obstacle_near(o, &c->pose[k], x + 3 * p,
                                     o->resp.offset, memo_of(c, k, p), &q))
                    cl_project_particle(&o->resp, &q, cl->mass[p], x + 3 * p,
                                        v + 3 * p, &tally);
            }
        }
    project_figures(c, t, &tally);
    c->last_t = t;
    if (c->sweeps) {
        memcpy(c->swept_x, x, 3 * cl->np * sizeof *x);
        c->swept = true;
    }
    c->acc_live = !trial;
    return tally.moved;
}

void cl_contact_accept(cl_contact *c, double t)
{
    if (!c->acc_live)
        c->last_t = t;
    c->acc_live = true;
}

/* ---- barriers ---------------------------------------------------------- */

bool cl_contact_barriers(const cl_contact *c) { return c->barriers; }

bool cl_contact_infeasible(const cl_contact *c) { return c->infeasible; }

bool cl_contact_lags(const cl_contact *c)
{
    for (size_t k = 0; k < c->nobs; k++)
        if (c->obs[k].resp.kind == CL_RESPONSE_BARRIER && c->obs[k].resp.mu > 0)
            return true;
    return false;
}

void cl_contact_lag(cl_contact *c, double t, const double *x)
{
    const cl_cloth *cl = c->cloth;
    place(c, t);
    for (size_t k = 0; k < c->nobs; k++) {
        const cl_obstacle *o = &c->obs[k];
        double *lambda = c->lambda + k * cl->np;
        if (o->resp.kind != CL_RESPONSE_BARRIER || o->resp.mu == 0.0)
            continue;
        memset(lambda, 0, cl->np * sizeof *lambda);
        size_t nnear = cl_obstacle_screen(o, &c->pose[k], x, cl->np,
                                          o->resp.dhat, memo_of(c, k, 0),
                                          c->near);
        for (size_t i = 0; i < nnear; i++) {
            size_t p = c->near[i];
            cl_contact_point q;
            if (cl->dof[p] < 0 ||
                !cl_obstacle_near(o, &c->pose[k], x + 3 * p, o->resp.dhat,
                                  memo_of(c, k, p), &q))
                continue;
            lambda[p] = cl_barrier_lambda(&o->resp, q.d);
            memcpy(c->lag_n[k * cl->np + p], q.n, sizeof q.n);
        }
    }
}

double cl_contact_min_distance(cl_contact *c, double t, const double *x)
{
    const cl_cloth *cl = c->cloth;
    double best = INFINITY;
    place(c, t);
    for (size_t k = 0; k < c->nobs; k++) {
        const cl_obstacle *o = &c->obs[k];
        if (o->resp.kind != CL_RESPONSE_BARRIER)
            continue;
        for (size_t p = 0; p < cl->np; p++) {
            double d;
            if (cl->dof[p] >= 0 &&
                cl_obstacle_depth(o, &c->pose[k], x + 3 * p, best,
                                  memo_of(c, k, p), &d))
                best = d;
        }
    }
    return best;
}

double cl_contact_step_fraction(cl_contact *c, double t0, const double *x0,
                                double t1, const double *x1)
{
    const cl_cloth *cl = c->cloth;
    double toi = INFINITY;
    for (size_t k = 0; k < c->nobs; k++) {
        const cl_obstacle *o = &c->obs[k];
        cl_pose P0, P1;
        if (o->resp.kind != CL_RESPONSE_BARRIER)
            continue;
        cl_obstacle_pose(o, t0, &P0);
        cl_obstacle_pose(o, t1, &P1);
        for (size_t i = 0; i < cl->nfree; i++)
            toi = fmin(toi, cl_obstacle_toi(o, &P0, x0 + 3 * i, &P1,
                                            x1 + 3 * i, 0.0));
    }
    return toi <= 1.0 ? CL_BARRIER_SAFETY * toi : 1.0;
}

/* ---- Baraff-Witkin constraints ---------------------------------------- */

/* The constraint obstacle particle p (at x, velocity v) is closest to
 * relative to its offset, among those it touches (d <= offset + 1e-9 m,
 * or, when it was constrained to that obstacle through the last step,
 * d <= offset + 1e-9 m + h |v - u|: a particle sliding on a curved surface
 * drifts off it by O(h^2 |v|^2 / radius) a step and stays constrained
 * until its constraint pulls); SIZE_MAX if none. */
static size_t constraint_obstacle(cl_contact *c, size_t p, double h,
                                  const double *x, const double *v,
                                  cl_contact_point *best)
{
    size_t pick = SIZE_MAX;
    bool held = c->cons[p].mode != CL_CONSTRAINT_FREE;
    for (size_t k = 0; k < c->nobs; k++) {
        const cl_obstacle *o = &c->obs[k];
        cl_contact_point q;
        bool mine = held && c->cons_obs[p] == k;
        if (o->resp.kind != CL_RESPONSE_CONSTRAINT ||
            !cl_obstacle_near(o, &c->pose[k], x, mine ? INFINITY : reach(
                              &o->resp), memo_of(c, k, p), &q))
            continue;
        double w2 = 0.0;
        for (int i = 0; i < 3; i++)
            w2 += (v[i] - q.u[i]) * (v[i] - q.u[i]);
        double gap = q.d - o->resp.offset;
        if (gap > ON_SURFACE + (mine ? h * sqrt(w2) : 0.0) ||
            (pick != SIZE_MAX && gap >= best->d - c->obs[pick].resp.offset))
            continue;
        pick = k;
        *best = q;
    }
    return pick;
}

void cl_contact_constrain(cl_contact *c, double t, double h, const double *x,
                          const double *v, double *S, double *z, double *y,
                          double *g)
{
    const cl_cloth *cl = c->cloth;
    place(c, t);
    for (size_t p = 0; p < cl->np; p++) {
        int i = cl->dof[p];
        if (i < 0)
            continue;
        cl_contact_point q;
        size_t k = constraint_obstacle(c, p, h, x + 3 * p, v + 3 * p, &q);
        if (k == SIZE_MAX) {
            c->cons[p].mode = CL_CONSTRAINT_FREE;
            cl_constraint_none(S + 9 * i, z + 3 * i, y + 3 * i, g + 3 * i);
            continue;
        }
        c->cons_obs[p] = k;
        cl_constraint_start(&c->obs[k].resp, &q, v + 3 * p, &c->cons[p],
                            S + 9 * i, z + 3 * i, y + 3 * i, g + 3 * i);
    }
}

bool cl_contact_release(cl_contact *c, const double *impulse, double *S,
                        double *z, double *y, double *g)
{
    const cl_cloth *cl = c->cloth;
    bool changed = false;
    for (size_t p = 0; p < cl->np; p++) {
        int i = cl->dof[p];
        if (i >= 0 && c->cons[p].mode != CL_CONSTRAINT_FREE)
            changed |= cl_constraint_release(
                c->obs[c->cons_obs[p]].resp.mu, impulse + 3 * i, &c->cons[p],
                S + 9 * i, z + 3 * i, y + 3 * i, g + 3 * i);
    }
    return changed;
}
