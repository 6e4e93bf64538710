/* A cloth problem as a cl_system: scatter the free state to full-particle
 * arrays (pins prescribed), let every force term add its share, gather. */
#include "system/model.h"

#include "contact/contact.h"
#include "forces/selfcontact.h"
#include "model/cloth_read.h"
#include "model/pins.h"
#include "system/distances.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_rng.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "core/stop.h"
#include "io/state.h"

struct cl_model {
    cl_cloth cloth;
    double v0[3];         /* initial velocity of the free particles */
    double *xs, *vs;      /* [init] state: the free state at t0 (3 nfree
                           * each), or NULL */
    double t0;            /* [init] time: the time of the initial state */
    double perturb;       /* amplitude of the initial out-of-plane noise */
    long seed;            /* its random seed */
    cl_term_opts opts;
    size_t nterm;         /* force terms, at most one per registry row and
                           * the obstacles' */
    const cl_term_type **type;
    void **state;
    const char **term_name; /* nterm (cl_model_terms) */
    size_t npot;          /* conservative terms (cl_energy.nterm) */
    const char **pot_name; /* their names, and their energies at the */
    double *pot_value;    /* last energy evaluation (cl_energy) */
    cl_bpattern pattern;  /* blocks over free particles */
    double *mass3;        /* 3 * nfree */
    double *xf, *vf, *ff; /* full-particle work arrays, 3 * np */
    int (*torn)[2];       /* distinct connections torn so far, sorted */
    size_t ntorn;
    cl_contact *contact;  /* the obstacles (also a term), or NULL */
    double worst_pen;     /* deepest penetration seen by the contact hook */
    double worst_t;       /* ... and when */
    bool tears;           /* [tear] cut > 0 and a term that tears */
    bool lags;            /* a barrier with friction (its lag) */
    double min_dist;      /* least distance to a barrier obstacle seen by
                           * the contact hook */
    double min_dist_t;    /* ... and when */
    uint64_t implicit;    /* terms with imex = implicit (cl_system) */
    bool track_work;      /* account the projections' energy change */
    double contact_work;  /* their sum so far (J) */
    double *xw, *vw;      /* the state before a projection (track_work) */
    cl_distance_set dist; /* distance constraints (system.h) */
    cl_system sys;
};

/* ---- configuration ---------------------------------------------------- */

static cl_status read_init(cl_config *cfg, cl_model *m, cl_error *err)
{
    cl_status rc;
    if ((rc = cl_config_vector(cfg, "init", "velocity", 3, m->v0, err)) ||
        (rc = cl_config_double(cfg, "init", "perturb", 0.0, 0.0, INFINITY,
                               &m->perturb, err)) ||
        (rc = cl_config_long(cfg, "init", "seed", 1, 0, LONG_MAX, &m->seed,
                             err)))
        return rc;
    return CL_OK;
}

/* The largest distance, over the pinned particles, between a state's
 * position xs (3 np) and where the pin holds the particle at t0; the pin
 * with it in *worst. */
static double pin_mismatch(const cl_cloth *c, double t0, const double *xs,
                           size_t *worst)
{
    double far = 0.0;
    for (size_t k = 0; k < c->npin; k++) {
        double at[3];
        cl_cloth_pin_position(c, k, t0, at);
        const double *x = xs + 3 * (size_t)c->pins[k].p;
        double d = hypot(hypot(x[0] - at[0], x[1] - at[1]), x[2] - at[2]);
        if (!(d <= far)) {
            far = d;
            *worst = k;
        }
    }
    return far;
}

/* The side of the rest shape's bounding box, for a tolerance in metres. */
static double rest_extent(const cl_cloth *c)
{
    double ext = 0.0;
    for (int a = 0; a < 3; a++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t p = 0; p < c->np; p++) {
            lo = fmin(lo, c->X0[3 * p + a]);
            hi = fmax(hi, c->X0[3 * p + a]);
        }
        ext = fmax(ext, hi - lo);
    }
    return ext;
}

/* A state file's pinned rows must be where the pins hold those particles
 * at [init] time: a state saved at another time of a problem whose pins
 * move would otherwise start with its pins jumping.  The reason into
 * why (len bytes) when they are not. */
static bool state_pins_agree(const cl_cloth *c, double t0, const double *xs,
                             char *why, size_t len)
{
    size_t k = 0;
    double far = pin_mismatch(c, t0, xs, &k);
    if (far <= 1e-9 * rest_extent(c))
        return true;
    double at[3];
    const double *x = xs + 3 * (size_t)c->pins[k].p;
    cl_cloth_pin_position(c, k, t0, at);
    const double *w = c->pins[k].w;
    bool moves = (w[0] != 0.0 || w[1] != 0.0 || w[2] != 0.0) &&
                 c->pins[k].t_stop > 0.0;
    snprintf(why, len, "pinned particle %d is at (%.9g, %.9g, %.9g), "
             "%.3g m from where its pin holds it at [init] time = %g s, "
             "(%.9g, %.9g, %.9g): %s", c->pins[k].p, x[0], x[1], x[2], far,
             t0, at[0], at[1], at[2],
             moves ? "give the time the state was saved at as [init] time"
                   : "that pin does not move, so the state is of another "
                     "problem or pinning");
    return false;
}

/* The free part of a state file into x, v (3 nfree each); with t0 not
 * NaN, its pinned rows checked first (state_pins_agree: CL_EINVAL). */
static cl_status free_state_of(const cl_cloth *c, const char *path,
                               double t0, double *x, double *v,
                               cl_error *err)
{
    double *xf = malloc(3 * c->np * sizeof *xf);
    double *vf = malloc(3 * c->np * sizeof *vf);
    char why[512];
    cl_status rc = xf && vf ? cl_state_read(path, c->np, xf, vf, err)
                            : cl_error_set(err, CL_ENOMEM, "out of memory "
                                           "(a state)");
    if (!rc && !isnan(t0) && !state_pins_agree(c, t0, xf, why, sizeof why))
        rc = cl_error_set(err, CL_EINVAL, "%s", why);
    if (!rc) {
        cl_cloth_gather(c, xf, x);
        cl_cloth_gather(c, vf, v);
    }
    free(xf);
    free(vf);
    return rc;
}

cl_status cl_model_read_state(const cl_model *m, const char *path, double *x,
                              double *v, cl_error *err)
{
    return free_state_of(&m->cloth, path, NAN, x, v, err);
}

cl_status cl_model_config_start_time(cl_config *cfg, double *t0,
                                     cl_error *err)
{
    return cl_config_double(cfg, "init", "time", 0.0, 0.0, 1e12, t0, err);
}

/* [init] state: a state file (final.csv) whose free particles' positions
 * and velocities are the state at [init] time (README "[init]"). */
static cl_status read_state(cl_config *cfg, cl_model *m, cl_error *err)
{
    cl_status rc = cl_model_config_start_time(cfg, &m->t0, err);
    if (rc)
        return rc;
    if (!*cl_config_string(cfg, "init", "state", ""))
        return m->t0 == 0.0
                   ? CL_OK
                   : cl_config_refuse(cfg, "init", "time", CL_EINVAL,
                                      "the time of [init] state, which is "
                                      "not given (the problem's own "
                                      "initial state is at t = 0)", err);
    const cl_cloth *c = &m->cloth;
    char path[4096];
    if ((rc = cl_config_path_of(cfg, "init", "state", path, sizeof path,
                                err)))
        return rc;
    /* the state replaces the problem's own initial state, its velocity
     * and perturbation (a run continued from its state is not perturbed
     * again); asked for beside it on the command line, they are refused */
    if (cl_config_set_by_command(cfg, "init", "velocity"))
        return cl_config_refuse(cfg, "init", "velocity", CL_EINVAL,
                                "given with [init] state, whose file gives "
                                "the velocities", err);
    if (cl_config_set_by_command(cfg, "init", "perturb") && m->perturb > 0)
        return cl_config_refuse(cfg, "init", "perturb", CL_EINVAL,
                                "given with [init] state, whose file gives "
                                "the positions", err);
    m->xs = malloc((3 * c->nfree + 1) * sizeof *m->xs);
    m->vs = malloc((3 * c->nfree + 1) * sizeof *m->vs);
    if (!m->xs || !m->vs)
        return cl_error_set(err, CL_ENOMEM, "out of memory ([init] state)");
    if ((rc = free_state_of(c, path, m->t0, m->xs, m->vs, err))) {
        char why[sizeof err->msg];
        snprintf(why, sizeof why, "%s", err->msg);
        rc = cl_config_refuse(cfg, "init", "state", rc, why, err);
    }
    return rc;
}

static cl_status read_opts(cl_config *cfg, cl_term_opts *o, cl_error *err)
{
    static const char *const transverse[] = {"full", "clamp", NULL};
    int k;
    cl_status rc = cl_config_choice(cfg, "jacobian", "transverse", transverse,
                                    0, &k, err);
    o->clamp_transverse = k == 1;
    if (rc)
        return rc;
    rc = cl_config_double(cfg, "tear", "cut", 0.0, 0.0, INFINITY,
                          &o->tear_cut, err);
    char where[256];
    if (rc == CL_OK && o->tear_cut != 0.0 && o->tear_cut <= 1.0)
        return cl_error_set(err, CL_EINVAL,
                            "%s: [tear] cut = %g: expected 0 (no tearing) or "
                            "a number > 1 (a connection breaks when d > cut L)",
                            cl_config_origin(cfg, "tear", "cut", where,
                                             sizeof where), o->tear_cut);
    return rc;
}

/* ---- terms and pattern ------------------------------------------------ */

/* The obstacles, a force term after the registry's (contact/contact.h). */
static cl_status create_contact(cl_config *cfg, cl_model *m, cl_error *err)
{
    void *st = NULL;
    cl_status rc = cl_contact_term.create(cfg, &m->cloth, &m->opts, &st,
                                          err);
    if (rc || !st)
        return rc;
    m->type[m->nterm] = &cl_contact_term;
    m->state[m->nterm++] = st;
    m->contact = st;
    return CL_OK;
}

/* The registry's terms that the configuration enables, then the obstacles':
 * at most one per registry row and one more. */
static cl_status create_terms(cl_config *cfg, cl_model *m, cl_error *err)
{
    size_t rows = 0;
    while (cl_term_registry[rows])
        rows++;
    m->type = malloc((rows + 1) * sizeof *m->type);
    m->state = malloc((rows + 1) * sizeof *m->state);
    if (!m->type || !m->state)
        return cl_error_set(err, CL_ENOMEM, "out of memory (force terms)");
    for (size_t k = 0; cl_term_registry[k]; k++) {
        void *st = NULL;
        cl_status rc = cl_term_registry[k]->create(cfg, &m->cloth, &m->opts,
                                                   &st, err);
        if (rc)
            return rc;
        if (!st)
            continue;
        m->type[m->nterm] = cl_term_registry[k];
        m->state[m->nterm++] = st;
    }
    return create_contact(cfg, m, err);
}

/* The names of the terms, and of the conservative ones with room for their
 * energies (cl_energy). */
static cl_status name_terms(cl_model *m, cl_error *err)
{
    m->term_name = malloc((m->nterm + 1) * sizeof *m->term_name);
    m->pot_name = malloc((m->nterm + 1) * sizeof *m->pot_name);
    m->pot_value = calloc(m->nterm + 1, sizeof *m->pot_value);
    if (!m->term_name || !m->pot_name || !m->pot_value)
        return cl_error_set(err, CL_ENOMEM, "out of memory (term names)");
    for (size_t k = 0; k < m->nterm; k++) {
        m->term_name[k] = m->type[k]->name;
        if (m->type[k]->conservative)
            m->pot_name[m->npot++] = m->type[k]->name;
    }
    return CL_OK;
}

/* The implicit part of an IMEX split (cl_system implicit_terms): each
 * term's `imex` key in its own section, implicit by default unless the
 * term is soft (cl_term_type.soft: gravity, Type2 bending). */
static cl_status read_imex(cl_config *cfg, cl_model *m, cl_error *err)
{
    static const char *const parts[] = {"implicit", "explicit", NULL};
    if (m->nterm > 64)
        return cl_error_set(err, CL_EINVAL, "%zu force terms: a term mask "
                            "holds at most 64", m->nterm);
    for (size_t k = 0; k < m->nterm; k++) {
        int part;
        cl_status rc = cl_config_choice(cfg, m->type[k]->name, "imex", parts,
                                        m->type[k]->soft ? 1 : 0, &part,
                                        err);
        if (rc)
            return rc;
        if (part == 0)
            m->implicit |= UINT64_C(1) << k;
    }
    return CL_OK;
}

/* Pattern over the particles with dof[p] >= 0, bound to every term. */
static cl_status build_pattern(cl_model *m, const int *dof, size_t nb,
                               cl_bpattern *pat, cl_error *err)
{
    size_t total = 0;
    for (size_t k = 0; k < m->nterm; k++) {
        const int(*pairs)[2];
        total += m->type[k]->couplings(m->state[k], &pairs);
    }
    int(*all)[2] = malloc((total + 1) * sizeof *all);
    if (!all)
        return cl_error_set(err, CL_ENOMEM, "out of memory (couplings)");
    size_t at = 0;
    for (size_t k = 0; k < m->nterm; k++) {
        const int(*pairs)[2];
        size_t n = m->type[k]->couplings(m->state[k], &pairs);
        if (n)
            memcpy(all + at, pairs, n * sizeof *pairs);
        at += n;
    }
    cl_status rc = cl_bpattern_build(m->cloth.np, dof, nb, total,
                                     (const int(*)[2])all, pat, err);
    free(all);
    for (size_t k = 0; rc == CL_OK && k < m->nterm; k++)
        rc = m->type[k]->bind(m->state[k], pat, dof, err);
    return rc;
}

/* ---- evaluation ------------------------------------------------------- */

/* How many of the terms after k (all in mask, no energies) term k
 * evaluated with it: their forces in one pass (forces/term.h, fuse), then
 * their Jacobian blocks, if asked for, term by term; so that a Jacobian's
 * forces are bitwise those of the force evaluation. */
static size_t fused_with_next(cl_model *m, uint64_t mask, size_t k,
                              const cl_eval *ev)
{
    const cl_term_type *t = m->type[k];
    size_t nnext = 0;
    if (!ev->f || ev->want_energy || !t->fuse)
        return 0;
    while (k + 1 + nnext < m->nterm && (mask >> (k + 1 + nnext) & 1))
        nnext++;
    if (!nnext)
        return 0;
    cl_eval forces = *ev, blocks = *ev;
    forces.dfdx = forces.dfdv = NULL;
    size_t done = t->fuse(m->state[k], m->type + k + 1, m->state + k + 1,
                          nnext, &forces);
    blocks.f = NULL;
    if (done && (blocks.dfdx || blocks.dfdv))
        for (size_t j = 0; j <= done; j++)
            m->type[k + j]->eval(m->state[k + j], &blocks);
    return done;
}

/* Run the terms of mask (bit k: the k-th term) on the full arrays m->xf,
 * m->vf. */
static void eval_terms(cl_model *m, uint64_t mask, double t, double *f,
                       double *dfdx, double *dfdv, cl_energy *e)
{
    if (f)
        memset(f, 0, 3 * m->cloth.np * sizeof *f);
    if (e)
        *e = (cl_energy){.name = m->pot_name, .value = m->pot_value};
    for (size_t k = 0; k < m->nterm; k++) {
        if (!(mask >> k & 1))
            continue;
        cl_eval ev = {.t = t, .x = m->xf, .v = m->vf, .f = f,
                      .dfdx = dfdx, .dfdv = dfdv, .want_energy = e != NULL};
        size_t fused = fused_with_next(m, mask, k, &ev);
        if (fused) {
            k += fused;
            continue;
        }
        m->type[k]->eval(m->state[k], &ev);
        if (!e)
            continue;
        if (m->type[k]->conservative) {
            m->pot_value[e->nterm++] = ev.energy;
            e->potential += ev.energy;
        }
        e->power_diss += ev.power; /* 0 but for damping, friction */
    }
    if (e)
        e->contact_work = m->contact_work;
}

/* The status of an evaluation whose results are `finite`: CL_EINFEASIBLE
 * when it found a particle at d <= 0 of a barrier obstacle (system.h),
 * else CL_OK or CL_EBLOWUP. */
static cl_status eval_status(const cl_model *m, bool finite)
{
    if (m->contact && cl_contact_infeasible(m->contact))
        return CL_EINFEASIBLE;
    return finite ? CL_OK : CL_EBLOWUP;
}

/* The state into the model's full arrays, after the stop check that
 * makes every force and Jacobian evaluation return CL_EINTR once a stop is requested
 * (core/stop.h). */
static cl_status model_scatter(cl_model *m, double t, const double *x,
                               const double *v)
{
    if (cl_stop_requested())
        return CL_EINTR;
    cl_cloth_scatter(&m->cloth, t, x, v, m->xf, m->vf);
    return CL_OK;
}

static cl_status sys_force_terms(void *data, uint64_t mask, double t,
                                 const double *x, const double *v, double *f)
{
    cl_model *m = data;
    cl_status st = model_scatter(m, t, x, v);
    if (st)
        return st;
    eval_terms(m, mask, t, m->ff, NULL, NULL, NULL);
    cl_cloth_gather(&m->cloth, m->ff, f);
    return eval_status(m, cl_all_finite(f, 3 * m->cloth.nfree));
}

static cl_status sys_force(void *data, double t, const double *x,
                           const double *v, double *f)
{
    return sys_force_terms(data, UINT64_MAX, t, x, v, f);
}

/* a[0 .. n) = 0 on `threads` threads over equal ranges (the Jacobians'
 * values: megabytes at n = 128). */
static void zero_threads(double *a, size_t n, int threads)
{
    if (threads <= 1) {
        memset(a, 0, n * sizeof *a);
        return;
    }
    size_t nt = (size_t)threads;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (size_t t = 0; t < nt; t++)
        memset(a + n * t / nt, 0, (n * (t + 1) / nt - n * t / nt) * sizeof *a);
}

static cl_status sys_jacobian_terms(void *data, uint64_t mask, double t,
                                    const double *x, const double *v,
                                    double *f, double *dfdx, double *dfdv)
{
    cl_model *m = data;
    cl_status st = model_scatter(m, t, x, v);
    if (st)
        return st;
    size_t nval = 9 * m->pattern.nnzb;
    int nt = m->sys.threads;
    zero_threads(dfdx, nval, nt);
    zero_threads(dfdv, nval, nt);
    eval_terms(m, mask, t, f ? m->ff : NULL, dfdx, dfdv, NULL);
    if (f)
        cl_cloth_gather(&m->cloth, m->ff, f);
    return eval_status(m, cl_all_finite_threads(dfdx, nval, nt) &&
                              cl_all_finite_threads(dfdv, nval, nt));
}

static cl_status sys_jacobian(void *data, double t, const double *x,
                              const double *v, double *f, double *dfdx,
                              double *dfdv)
{
    return sys_jacobian_terms(data, UINT64_MAX, t, x, v, f, dfdx, dfdv);
}

static double sys_step_fraction(void *data, double t0, const double *x0,
                                double t1, const double *x1)
{
    cl_model *m = data;
    return cl_contact_step_fraction(m->contact, t0, x0, t1, x1);
}

static double kinetic_free(const cl_cloth *c, const double *vfull)
{
    double ke = 0.0;
    for (size_t k = 0; k < c->nfree; k++) {
        const double *v = vfull + 3 * (size_t)c->free_p[k];
        ke += 0.5 * c->mass[c->free_p[k]] * (v[0] * v[0] + v[1] * v[1] +
                                             v[2] * v[2]);
    }
    return ke;
}

static cl_status sys_energy(void *data, double t, const double *x,
                            const double *v, cl_energy *e)
{
    cl_model *m = data;
    cl_cloth_scatter(&m->cloth, t, x, v, m->xf, m->vf);
    eval_terms(m, UINT64_MAX, t, NULL, NULL, NULL, e);
    e->kinetic = kinetic_free(&m->cloth, m->vf);
    e->total = e->kinetic + e->potential;
    return eval_status(m, isfinite(e->total));
}

/* f without the terms that the distance constraints stand for. */
static cl_status sys_force_other(void *data, double t, const double *x,
                                 const double *v, double *f)
{
    cl_model *m = data;
    cl_status st = model_scatter(m, t, x, v);
    if (st)
        return st;
    memset(m->ff, 0, 3 * m->cloth.np * sizeof *m->ff);
    for (size_t k = 0; k < m->nterm; k++) {
        cl_eval ev = {.t = t, .x = m->xf, .v = m->vf, .f = m->ff};
        if (!m->type[k]->distances)
            m->type[k]->eval(m->state[k], &ev);
    }
    cl_cloth_gather(&m->cloth, m->ff, f);
    return eval_status(m, cl_all_finite(f, 3 * m->cloth.nfree));
}

static void sys_anchors(void *data, double t, double *xa)
{
    const cl_model *m = data;
    for (size_t k = 0; k < m->cloth.npin; k++)
        cl_cloth_pin_position(&m->cloth, k, t, xa + 3 * k);
}

/* Position-based constraints of every term that has them. */
static cl_status sys_project(void *data, double t, double *x)
{
    cl_model *m = data;
    cl_cloth_scatter(&m->cloth, t, x, NULL, m->xf, NULL);
    for (size_t k = 0; k < m->nterm; k++)
        if (m->type[k]->project)
            m->type[k]->project(m->state[k], m->xf, m->cloth.dof);
    cl_cloth_gather(&m->cloth, m->xf, x);
    return cl_all_finite(x, 3 * m->cloth.nfree) ? CL_OK : CL_EBLOWUP;
}

static int (*broken_pairs(const cl_model *m, size_t *n))[2];

/* m->torn = the distinct pairs of all terms' broken lists. */
static cl_status update_torn(cl_model *m)
{
    size_t n = 0, kept = 0;
    int(*all)[2] = broken_pairs(m, &n);
    if (!all)
        return CL_ENOMEM;
    for (size_t i = 0; i < n; i++)
        if (kept == 0 || memcmp(all[i], all[kept - 1], sizeof all[i]))
            memmove(all[kept++], all[i], sizeof all[i]);
    free(m->torn);
    m->torn = all;
    m->ntorn = kept;
    return CL_OK;
}

/* Tearing after an accepted step (with [tear] cut > 0), and the lag of
 * the barriers' friction (contact/barrier.h), which changes the force law:
 * adaptive methods restart from the state the lag was taken at.
 * Allocates only on a step where something tore. */
static cl_status sys_step_done(void *data, double t, const double *x,
                               const double *v, bool *changed)
{
    cl_model *m = data;
    size_t broken = 0;
    cl_cloth_scatter(&m->cloth, t, x, v, m->xf, m->vf);
    for (size_t k = 0; m->tears && k < m->nterm; k++)
        if (m->type[k]->step_done)
            broken += m->type[k]->step_done(m->state[k], m->xf, m->vf);
    *changed = broken > 0;
    if (m->lags) {
        cl_contact_lag(m->contact, t, m->xf);
        *changed = true;
    }
    return broken > 0 ? update_torn(m) : CL_OK;
}

/* The least distance to a barrier obstacle after a recorded step (m->xf
 * at t). */
static void barrier_step_done(cl_model *m, double t, bool record)
{
    if (!record)
        return;
    double d = cl_contact_min_distance(m->contact, t, m->xf);
    if (d < m->min_dist) {
        m->min_dist = d;
        m->min_dist_t = t;
    }
}

/* Contact (system/system.h): the deepest penetration, then the
 * projections; with track_work their energy change (kinetic and
 * potential, friction included) is added to contact_work, for recorded
 * calls only (not CVODE's trial projections inside its steps). */
static cl_status sys_contact(void *data, double t, double *x, double *v,
                             unsigned what)
{
    cl_model *m = data;
    size_t n = 3 * m->cloth.nfree;
    bool projects = m->sys.projects; /* else the velocities are not read */
    bool barriers = m->sys.step_fraction != NULL;
    bool record = what & CL_CONTACT_RECORD;
    bool project = projects && (what & CL_CONTACT_PROJECT);
    if (!project && !record)
        return CL_OK;                    /* nothing to record or move */
    const double *xf = x; /* without pins the free state is the cloth's */
    if (project || barriers || m->cloth.nfree < m->cloth.np) {
        cl_cloth_scatter(&m->cloth, t, x, project ? v : NULL, m->xf,
                         project ? m->vf : NULL);
        xf = m->xf;
    }
    double pen = record ? cl_contact_penetration(m->contact, t, xf) : 0.0;
    if (pen > m->worst_pen) {
        m->worst_pen = pen;
        m->worst_t = t;
    }
    if (barriers)
        barrier_step_done(m, t, record);
    if (projects && !project) /* the state before an accepted trial */
        cl_contact_accept(m->contact, t);
    if (!project)
        return CL_OK;
    bool track = m->track_work && record;
    if (track) {
        memcpy(m->xw, x, n * sizeof *x);
        memcpy(m->vw, v, n * sizeof *v);
    }
    size_t moved = cl_contact_project(m->contact, t, m->xf, m->vf, !record);
    cl_cloth_gather(&m->cloth, m->xf, x);
    cl_cloth_gather(&m->cloth, m->vf, v);
    if (track && moved) {
        cl_energy before, after;
        cl_status rc;
        if ((rc = sys_energy(m, t, m->xw, m->vw, &before)) ||
            (rc = sys_energy(m, t, x, v, &after)))
            return rc;
        m->contact_work += after.total - before.total;
    }
    return cl_all_finite(x, n) && cl_all_finite(v, n) ? CL_OK : CL_EBLOWUP;
}

/* Baraff-Witkin constraints (system/system.h): those of the step from
 * (t, x, v), or their release by the impulses of the last solve. */
static cl_status sys_constrain(void *data, double t, double h,
                               const double *x, const double *v,
                               const double *impulse, cl_constraint_set *cs,
                               bool *changed)
{
    cl_model *m = data;
    *changed = false;
    if (impulse) {
        *changed = cl_contact_release(m->contact, impulse, cs->S, cs->z,
                                      cs->y, cs->g);
        return CL_OK;
    }
    cl_cloth_scatter(&m->cloth, t, x, v, m->xf, m->vf);
    cl_contact_constrain(m->contact, t, h, m->xf, m->vf, cs->S, cs->z, cs->y,
                         cs->g);
    return CL_OK;
}

static bool any_hook(const cl_model *m, size_t offset)
{
    for (size_t k = 0; k < m->nterm; k++)
        if (*(void *const *)((const char *)m->type[k] + offset))
            return true;
    return false;
}

/* ---- life cycle ------------------------------------------------------- */

static cl_status alloc_work(cl_model *m, cl_error *err)
{
    size_t n3 = 3 * m->cloth.np, nf3 = 3 * m->cloth.nfree;
    m->xf = calloc(n3, sizeof *m->xf);
    m->vf = calloc(n3, sizeof *m->vf);
    m->ff = calloc(n3, sizeof *m->ff);
    m->mass3 = malloc(nf3 * sizeof *m->mass3);
    m->xw = malloc((nf3 + 1) * sizeof *m->xw);
    m->vw = malloc((nf3 + 1) * sizeof *m->vw);
    if (!m->xf || !m->vf || !m->ff || !m->mass3 || !m->xw || !m->vw)
        return cl_error_set(err, CL_ENOMEM, "out of memory (model)");
    for (size_t k = 0; k < nf3; k++)
        m->mass3[k] = m->cloth.mass[m->cloth.free_p[k / 3]];
    return CL_OK;
}

cl_status cl_model_create(cl_config *cfg, cl_model **model, cl_error *err)
{
    cl_status rc;
    cl_model *m = calloc(1, sizeof *m);
    *model = NULL;
    if (!m)
        return cl_error_set(err, CL_ENOMEM, "out of memory (model)");
    gsl_set_error_handler_off(); /* GSL reports through return codes */
    if ((rc = cl_cloth_read(cfg, &m->cloth, err)) ||
        (rc = cl_pins_read(cfg, &m->cloth, err)) ||
        (rc = read_init(cfg, m, err)) ||
        (rc = cl_cloth_finalize(&m->cloth, err)) ||
        (rc = read_state(cfg, m, err)) ||
        (rc = read_opts(cfg, &m->opts, err)) ||
        (rc = create_terms(cfg, m, err)) || (rc = name_terms(m, err)) ||
        (rc = read_imex(cfg, m, err)) ||
        (rc = build_pattern(m, m->cloth.dof, m->cloth.nfree, &m->pattern,
                            err)) ||
        (rc = alloc_work(m, err)) ||
        (rc = cl_distance_set_build(&m->cloth, m->nterm, m->type, m->state,
                                    &m->dist, err))) {
        cl_model_free(m);
        return rc;
    }
    m->min_dist = INFINITY;
    m->tears = m->opts.tear_cut > 0 &&
               any_hook(m, offsetof(cl_term_type, step_done));
    m->lags = m->contact && cl_contact_lags(m->contact);
    m->sys = (cl_system){
        .n = 3 * m->cloth.nfree, .mass = m->mass3, .pattern = &m->pattern,
        .threads = 1,
        .data = m, .force = sys_force, .jacobian = sys_jacobian,
        .energy = sys_energy, .nterm = m->nterm,
        .implicit_terms = m->implicit, .force_terms = sys_force_terms,
        .jacobian_terms = sys_jacobian_terms,
        .project = any_hook(m, offsetof(cl_term_type, project)) ? sys_project
                                                                 : NULL,
        .step_done = m->tears || m->lags ? sys_step_done : NULL,
        .contact = m->contact ? sys_contact : NULL,
        .step_fraction = m->contact && cl_contact_barriers(m->contact)
                             ? sys_step_fraction : NULL,
        .constrain = m->contact && cl_contact_constrains(m->contact)
                         ? sys_constrain : NULL,
        .projects = m->contact && cl_contact_projects(m->contact),
        .projects_friction =
            m->contact && cl_contact_projects_friction(m->contact)};
    if (m->dist.d.n && !m->tears) {
        m->sys.distances = &m->dist.d;
        m->sys.force_other = sys_force_other;
        m->sys.anchors = sys_anchors;
    }
    *model = m;
    return CL_OK;
}

void cl_model_free(cl_model *m)
{
    if (!m)
        return;
    for (size_t k = 0; k < m->nterm; k++)
        m->type[k]->free(m->state[k]);
    free(m->type);
    free(m->state);
    free(m->term_name);
    free(m->pot_name);
    free(m->pot_value);
    cl_bpattern_free(&m->pattern);
    cl_cloth_free(&m->cloth);
    free(m->mass3);
    free(m->xs);
    free(m->vs);
    free(m->xf);
    free(m->vf);
    free(m->ff);
    free(m->torn);
    free(m->xw);
    free(m->vw);
    cl_distance_set_free(&m->dist);
    free(m);
}

cl_status cl_model_set_threads(cl_model *m, int threads, cl_error *err)
{
    if (threads < 1 || threads > CL_MODEL_MAX_THREADS)
        return cl_error_set(err, CL_EINVAL, "threads = %d: need 1 .. %d",
                            threads, CL_MODEL_MAX_THREADS);
    for (size_t k = 0; k < m->nterm; k++) {
        cl_status rc = m->type[k]->threads
                           ? m->type[k]->threads(m->state[k], threads, err)
                           : CL_OK;
        if (rc)
            return rc;
    }
    m->sys.threads = threads;
    return CL_OK;
}

const cl_system *cl_model_system(cl_model *m) { return &m->sys; }

const cl_cloth *cl_model_cloth(const cl_model *m) { return &m->cloth; }

/* Out-of-plane (y) noise, uniform in [-perturb, perturb], reproducible
 * from the seed (GSL's MT19937). */
static cl_status perturb_positions(const cl_model *m, double *x)
{
    gsl_rng *r = gsl_rng_alloc(gsl_rng_mt19937);
    if (!r)
        return CL_ENOMEM;
    gsl_rng_set(r, (unsigned long)m->seed);
    for (size_t k = 0; k < m->cloth.nfree; k++)
        x[3 * k + 1] += m->perturb * (2.0 * gsl_rng_uniform(r) - 1.0);
    gsl_rng_free(r);
    return CL_OK;
}

cl_status cl_model_initial_state(const cl_model *m, double *x, double *v)
{
    size_t n = 3 * m->cloth.nfree;
    if (m->xs) {
        memcpy(x, m->xs, n * sizeof *x);
        memcpy(v, m->vs, n * sizeof *v);
        return CL_OK;
    }
    cl_cloth_gather(&m->cloth, m->cloth.X0, x);
    for (size_t k = 0; k < n; k++)
        v[k] = m->v0[k % 3];
    return m->perturb > 0 ? perturb_positions(m, x) : CL_OK;
}

double cl_model_start_time(const cl_model *m) { return m->t0; }

size_t cl_model_terms(const cl_model *m, const char *const **names)
{
    *names = m->term_name;
    return m->nterm;
}

size_t cl_model_potentials(const cl_model *m) { return m->npot; }

cl_status cl_model_eval_full(cl_model *m, double t, const double *x,
                             const double *v, double *f, cl_energy *e,
                             cl_error *err)
{
    size_t n3 = 3 * m->cloth.np;
    memcpy(m->xf, x, n3 * sizeof *x);
    memcpy(m->vf, v, n3 * sizeof *v);
    eval_terms(m, UINT64_MAX, t, f, NULL, NULL, e);
    e->kinetic = kinetic_free(&m->cloth, v);
    e->total = e->kinetic + e->potential;
    if (!cl_all_finite(f, n3) || !isfinite(e->total))
        return cl_error_set(err, CL_EBLOWUP,
                            "forces or energy are not finite at this state");
    return CL_OK;
}

cl_status cl_model_jacobian_full(cl_model *m, double t, const double *x,
                                 const double *v, cl_bpattern *pat,
                                 double **dfdx, double **dfdv, cl_error *err)
{
    size_t np = m->cloth.np;
    int *all = malloc(np * sizeof *all);
    if (!all)
        return cl_error_set(err, CL_ENOMEM, "out of memory (dof map)");
    for (size_t p = 0; p < np; p++)
        all[p] = (int)p;
    cl_status rc = build_pattern(m, all, np, pat, err);
    free(all);
    *dfdx = rc ? NULL : calloc(9 * pat->nnzb + 1, sizeof **dfdx);
    *dfdv = rc ? NULL : calloc(9 * pat->nnzb + 1, sizeof **dfdv);
    if (!rc && (!*dfdx || !*dfdv))
        rc = cl_error_set(err, CL_ENOMEM, "out of memory (jacobian)");
    if (!rc) {
        memcpy(m->xf, x, 3 * np * sizeof *x);
        memcpy(m->vf, v, 3 * np * sizeof *v);
        eval_terms(m, UINT64_MAX, t, NULL, *dfdx, *dfdv, NULL);
    }
    /* Terms go back to the free-particle pattern the system uses. */
    cl_error ignored;
    for (size_t k = 0; k < m->nterm; k++)
        if (m->type[k]->bind(m->state[k], &m->pattern, m->cloth.dof,
                             &ignored) && rc == CL_OK)
            rc = cl_error_set(err, CL_ENOMEM, "out of memory (rebind)");
    return rc;
}

size_t cl_model_broken(const cl_model *m) { return m->ntorn; }

bool cl_model_tears(const cl_model *m) { return m->tears; }

static int cmp_pair(const void *a, const void *b)
{
    const int *p = a, *q = b;
    return p[0] != q[0] ? (p[0] > q[0]) - (p[0] < q[0])
                        : (p[1] > q[1]) - (p[1] < q[1]);
}

/* Unordered pairs as sorted (min, max) rows of all terms' broken lists. */
static int (*broken_pairs(const cl_model *m, size_t *n))[2]
{
    size_t total = 0;
    for (size_t k = 0; k < m->nterm; k++) {
        const int(*p)[2];
        if (m->type[k]->broken)
            total += m->type[k]->broken(m->state[k], &p);
    }
    int(*all)[2] = malloc((total + 1) * sizeof *all);
    if (!all)
        return NULL;
    *n = 0;
    for (size_t k = 0; k < m->nterm; k++) {
        const int(*p)[2];
        size_t c = m->type[k]->broken ? m->type[k]->broken(m->state[k], &p)
                                      : 0;
        for (size_t i = 0; i < c; i++, (*n)++) {
            all[*n][0] = p[i][0] < p[i][1] ? p[i][0] : p[i][1];
            all[*n][1] = p[i][0] < p[i][1] ? p[i][1] : p[i][0];
        }
    }
    qsort(all, *n, sizeof *all, cmp_pair);
    return all;
}

bool cl_model_is_broken(const cl_model *m, int a, int b)
{
    int key[2] = {a < b ? a : b, a < b ? b : a};
    return m->ntorn &&
           bsearch(key, m->torn, m->ntorn, sizeof *m->torn, cmp_pair);
}

cl_status cl_model_triangles(const cl_model *m, int (*tri)[3], size_t *ntri,
                             cl_error *err)
{
    size_t kept = 0;
    (void)err; /* nothing can fail: the torn set is kept by step_done */
    memcpy(tri, m->cloth.tri, m->cloth.ntri * sizeof *tri);
    for (size_t t = 0; t < m->cloth.ntri; t++) {
        const int *v = tri[t];
        if (cl_model_is_broken(m, v[0], v[1]) ||
            cl_model_is_broken(m, v[1], v[2]) ||
            cl_model_is_broken(m, v[2], v[0]))
            continue;
        memmove(tri[kept++], v, sizeof tri[0]);
    }
    *ntri = kept;
    return CL_OK;
}

bool cl_model_selfcontact_closest(cl_model *m, const double *x, double *d)
{
    for (size_t k = 0; k < m->nterm; k++)
        if (m->type[k] == &cl_term_selfcontact) {
            *d = cl_selfcontact_closest(m->state[k], x);
            return true;
        }
    return false;
}

const cl_contact *cl_model_contact(const cl_model *m) { return m->contact; }

void cl_model_contact_start(cl_model *m, double t0, bool track_work)
{
    m->worst_pen = 0.0;
    m->worst_t = 0.0;
    m->min_dist = INFINITY;
    m->min_dist_t = 0.0;
    m->track_work = track_work;
    m->contact_work = 0.0;
    if (m->contact)
        cl_contact_restart(m->contact, t0);
    /* a saved state starts with the friction lag the run it continues had
     * after its last step (sys_step_done); the problem's own start, 0 */
    if (m->lags && m->xs) {
        cl_cloth_scatter(&m->cloth, t0, m->xs, m->vs, m->xf, m->vf);
        cl_contact_lag(m->contact, t0, m->xf);
    }
}

void cl_model_contact_worst(const cl_model *m, double *pen, double *t)
{
    *pen = m->worst_pen;
    *t = m->worst_t;
}

void cl_model_contact_closest(const cl_model *m, double *d, double *t)
{
    *d = m->min_dist;
    *t = m->min_dist_t;
}

cl_status cl_model_contact_figures(cl_model *m, double t, const double *x,
                                   const double *v, cl_contact_figures *f)
{
    cl_cloth_scatter(&m->cloth, t, x, v, m->xf, m->vf);
    cl_contact_measure(m->contact, t, m->xf, m->vf, f);
    if (f->max_penetration > m->worst_pen) {
        m->worst_pen = f->max_penetration;
        m->worst_t = t;
    }
    return isfinite(f->force) ? CL_OK : CL_EBLOWUP;
}

/* Append surface b to a (vertex numbers shifted). */
static cl_status append_surface(cl_shape_surface *a,
                                const cl_shape_surface *b, cl_error *err)
{
    double *v = realloc(a->vert, 3 * (a->nvert + b->nvert) * sizeof *v);
    if (v)
        a->vert = v;
    int(*t)[3] = realloc(a->tri, (a->ntri + b->ntri) * sizeof *t);
    if (t)
        a->tri = t;
    if (!v || !t)
        return cl_error_set(err, CL_ENOMEM, "out of memory (obstacles)");
    memcpy(a->vert + 3 * a->nvert, b->vert, 3 * b->nvert * sizeof *v);
    for (size_t k = 0; k < b->ntri; k++)
        for (int i = 0; i < 3; i++)
            a->tri[a->ntri + k][i] = b->tri[k][i] + (int)a->nvert;
    a->nvert += b->nvert;
    a->ntri += b->ntri;
    return CL_OK;
}

cl_status cl_model_obstacle_surface(const cl_model *m, double t,
                                    cl_shape_surface *all, cl_error *err)
{
    cl_status rc = CL_OK;
    memset(all, 0, sizeof *all);
    size_t n = m->contact ? cl_contact_obstacles(m->contact) : 0;
    for (size_t k = 0; k < n && rc == CL_OK; k++) {
        cl_shape_surface one = {0};
        rc = cl_obstacle_surface(cl_contact_obstacle(m->contact, k), t, &one,
                                 err);
        if (rc == CL_OK)
            rc = append_surface(all, &one, err);
        cl_shape_surface_free(&one);
    }
    if (rc)
        cl_shape_surface_free(all);
    return rc;
}
