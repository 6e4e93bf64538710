/* One simulation run: schedule of output times, integration, time series,
 * frames, final state, statistics.
 *
 * The stretch diagnostic looks at the nearest neighbours
 * (cl_pairs_neighbours: Type1's pairs on a grid, the triangle edges on a
 * mesh cloth).  On a mesh cloth the series writes NA for wrinkles (a grid's
 * centre line) and, unless the rest mesh is flat and horizontal, for
 * max_offplane (cl_offplane_applies); the summary's max_offplane is then
 * NaN.
 *
 * Tearing (a model with [tear] cut > 0, or with connections already torn):
 * frames leave out the triangles with a torn edge (cl_model_triangles into
 * a buffer allocated once per run), the max_stretch diagnostic and its
 * blow-up limit look at intact neighbour pairs only, and the series'
 * last column, broken, counts the torn connections (cl_model_broken).
 *
 * Contact (a model with obstacles): four more columns, the contact figures
 * at the sample (contact/contact.h), obstacle frames beside the cloth's,
 * and the deepest penetration of the run with its time in the result. */
#include "analysis/simulate.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/diagnostics.h"
#include "core/clock.h"
#include "core/stop.h"
#include "io/atomic.h"
#include "io/frames.h"
#include "io/series.h"
#include "io/state.h"

typedef struct {
    cl_model *m;
    const cl_cloth *c;
    const cl_system *sys;
    const cl_sim_opts *so;
    cl_pairset near;        /* neighbours, for the stretch diagnostic */
    bool tearing;           /* the model can tear (see the header) */
    cl_pairset intact;      /* near without torn pairs (tearing) */
    size_t torn_seen;       /* cl_model_broken when intact was built */
    int (*tri)[3];          /* frame triangles (tearing), c->ntri */
    bool offplane;          /* max_offplane applies (cl_offplane_applies) */
    double *x, *v;          /* free state */
    double *xf, *vf;        /* full-particle state */
    double *vgood;          /* full-particle velocities of the last good
                             * sample (its positions: res->xfinal) */
    unsigned char *pinned;
    cl_series *series;
    double *row;
    long frame_index;
    double *e0_terms, *e1_terms; /* term energies of res->e0, res->e1 */
} sim;

/* ---- output schedule -------------------------------------------------- */

typedef struct {
    double t0;     /* the model's start time */
    long nticks;   /* output times are t0 + tick * dt_tick */
    double dt_tick;
    bool fixed;    /* fixed steps of dt_tick: the last tick is a step's
                    * end, not t_end itself */
} schedule;

static cl_status make_schedule(const cl_integrator_type *type,
                               const cl_integrator_opts *o,
                               const cl_sim_opts *so, double t0, schedule *s,
                               cl_error *err)
{
    double span = so->t_end - t0;
    s->t0 = t0;
    if (!(span > 0))
        return cl_error_set(err, CL_EINVAL, "t_end = %g is not after the "
                            "start, [init] time = %g", so->t_end, t0);
    s->fixed = cl_integrator_fixed(type, o->dt);
    if (!s->fixed) {
        s->nticks = so->samples * (so->frames > 0 ? so->frames : 1);
        s->dt_tick = span / (double)s->nticks;
        return CL_OK;
    }
    double steps = span / o->dt;
    s->nticks = (long)llround(steps);
    s->dt_tick = o->dt;
    if (s->nticks < 1 || fabs(steps - (double)s->nticks) > 1e-9 * steps)
        return cl_error_set(err, CL_EINVAL,
                            "t_end - [init] time = %.10g is not a whole "
                            "number of steps dt = %g (%.12g steps); choose "
                            "t_end or dt so that it is", span, o->dt, steps);
    return CL_OK;
}

/* Tick of the k-th of `count` evenly spread outputs (k = 1..count). */
static long tick_of(long k, long count, long nticks)
{
    return (long)llround((double)k * (double)nticks / (double)count);
}

/* ---- outputs ---------------------------------------------------------- */

/* The series' columns: t, kinetic, the potential terms, and at most 14
 * more (the header of simulate.h). */
static cl_status open_series(sim *s, double t0, cl_error *err)
{
    cl_energy e;
    size_t n = 0;
    s->sys->energy(s->sys->data, t0, s->x, s->v, &e);
    const char **names = malloc((e.nterm + 14) * sizeof *names);
    if (!names)
        return cl_error_set(err, CL_ENOMEM, "out of memory (series names)");
    names[n++] = "t";
    names[n++] = "kinetic";
    for (size_t k = 0; k < e.nterm; k++)
        names[n++] = e.name[k];
    names[n++] = "potential";
    names[n++] = "total";
    names[n++] = "power_diss";
    names[n++] = "max_stretch";
    size_t offplane_col = n, wrinkles_col = n + 1;
    names[n++] = "max_offplane";
    names[n++] = "wrinkles";
    names[n++] = "broken";
    if (cl_model_contact(s->m)) {
        names[n++] = "contacts";
        names[n++] = "max_penetration";
        names[n++] = "contact_force";
        names[n++] = "friction_power";
        if (cl_contact_barriers(cl_model_contact(s->m)))
            names[n++] = "min_distance";
    }
    s->row = malloc(n * sizeof *s->row);
    char path[4096];
    snprintf(path, sizeof path, "%s/series.csv", s->so->outdir);
    cl_status rc = s->row ? cl_series_open(path, n, names, &s->series, err)
                          : cl_error_set(err, CL_ENOMEM,
                                         "out of memory (series row)");
    free(names);
    if (rc == CL_OK && !s->offplane)
        cl_series_not_applicable(s->series, offplane_col);
    if (rc == CL_OK && s->c->kind == CL_CLOTH_MESH)
        cl_series_not_applicable(s->series, wrinkles_col);
    return rc;
}

/* The neighbour pairs the stretch diagnostic looks at: all of them, or
 * those not torn (rebuilt when more have torn). */
static const cl_pairset *stretch_pairs(sim *s)
{
    size_t torn = s->tearing ? cl_model_broken(s->m) : 0;
    if (torn == 0)
        return &s->near;
    if (torn != s->torn_seen) {
        s->intact.n = 0;
        for (size_t k = 0; k < s->near.n; k++) {
            const cl_pair *p = &s->near.pair[k];
            if (!cl_model_is_broken(s->m, p->a, p->b))
                s->intact.pair[s->intact.n++] = *p;
        }
        s->torn_seen = torn;
    }
    return &s->intact;
}

/* Why a sample ends the run: its energy's status rc, else the stretch. */
static const char *blowup_reason(cl_status rc)
{
    if (rc == CL_EINFEASIBLE)
        return "a particle at d <= 0 of a barrier obstacle (the method's "
               "steps do not keep it outside)";
    return rc ? "energy is not finite" : "runaway stretch";
}

/* Energies and diagnostics at time t; one series row. */
static cl_status sample(sim *s, double t, cl_sim_result *res, cl_error *err)
{
    cl_energy e;
    cl_cloth_scatter(s->c, t, s->x, s->v, s->xf, s->vf);
    cl_status rc = s->sys->energy(s->sys->data, t, s->x, s->v, &e);
    double stretch = cl_max_stretch(stretch_pairs(s), s->xf);
    double offplane = s->offplane ? cl_max_offplane(s->c, s->xf) : NAN;
    if (rc || !(stretch <= s->so->max_stretch))
        return cl_error_set(err, CL_EBLOWUP,
                            "blow-up at t = %g: %s (max stretch d/L = %g, "
                            "limit %g)", t, blowup_reason(rc), stretch,
                            s->so->max_stretch);
    size_t n = 0;
    s->row[n++] = t;
    s->row[n++] = e.kinetic;
    for (size_t k = 0; k < e.nterm; k++)
        s->row[n++] = e.value[k];
    s->row[n++] = e.potential;
    s->row[n++] = e.total;
    s->row[n++] = e.power_diss;
    s->row[n++] = stretch;
    s->row[n++] = offplane;
    s->row[n++] = s->c->kind == CL_CLOTH_GRID
                      ? (double)cl_wrinkles(s->c, s->xf) : NAN;
    s->row[n++] = (double)cl_model_broken(s->m);
    if (cl_model_contact(s->m)) {
        cl_contact_figures cf;
        if ((rc = cl_model_contact_figures(s->m, t, s->x, s->v, &cf)))
            return cl_error_set(err, rc, "blow-up at t = %g: contact force "
                                "is not finite", t);
        s->row[n++] = (double)cf.contacts;
        s->row[n++] = cf.max_penetration;
        s->row[n++] = cf.force;
        s->row[n++] = cf.friction_power;
        if (cl_contact_barriers(cl_model_contact(s->m)))
            s->row[n++] = cf.min_distance;
    }
    if ((rc = cl_series_row(s->series, s->row, err)))
        return rc;
    res->t_reached = t;
    cl_energy_keep(&res->e1, &e, s->e1_terms);
    res->max_stretch = stretch;
    res->max_offplane = offplane;
    res->rows++;
    memcpy(res->xfinal, s->xf, 3 * s->c->np * sizeof *s->xf);
    memcpy(s->vgood, s->vf, 3 * s->c->np * sizeof *s->vf);
    return CL_OK;
}

/* The obstacles' surfaces at t, in the formats of the cloth frames. */
static cl_status write_obstacles(sim *s, double t, cl_error *err)
{
    cl_shape_surface all;
    char path[4096];
    cl_status rc = cl_model_obstacle_surface(s->m, t, &all, err);
    cl_frame f = {(int)all.nvert, 1, all.vert, NULL, NULL, t,
                  (const int(*)[3])all.tri, all.ntri};
    if (!rc && s->so->vtk &&
        !(rc = cl_frame_path_stem(s->so->outdir, "obstacles", s->frame_index,
                                  "vtk", path, sizeof path, err)))
        rc = cl_frame_write_vtk(path, &f, err);
    if (!rc && s->so->obj &&
        !(rc = cl_frame_path_stem(s->so->outdir, "obstacles", s->frame_index,
                                  "obj", path, sizeof path, err)))
        rc = cl_frame_write_obj(path, &f, err);
    cl_shape_surface_free(&all);
    return rc;
}

static cl_status write_frame(sim *s, double t, cl_sim_result *res,
                             cl_error *err)
{
    bool mesh = s->c->kind == CL_CLOTH_MESH;
    cl_frame f = {mesh ? (int)s->c->np : s->c->nu, mesh ? 0 : s->c->nv,
                  s->xf, s->vf, s->pinned, t,
                  (const int(*)[3])s->c->tri, s->c->ntri};
    char path[4096];
    cl_status rc = CL_OK;
    if (s->tearing && !(rc = cl_model_triangles(s->m, s->tri, &f.ntri, err)))
        f.tri = (const int(*)[3])s->tri;
    if (!rc && s->so->vtk &&
        (!(rc = cl_frame_path(s->so->outdir, s->frame_index, "vtk", path,
                              sizeof path, err))))
        rc = cl_frame_write_vtk(path, &f, err);
    if (!rc && s->so->obj &&
        (!(rc = cl_frame_path(s->so->outdir, s->frame_index, "obj", path,
                              sizeof path, err))))
        rc = cl_frame_write_obj(path, &f, err);
    if (!rc && cl_model_contact(s->m))
        rc = write_obstacles(s, t, err);
    if (!rc) {
        s->frame_index++;
        res->frames++;
    }
    return rc;
}

static cl_status write_stats(const sim *s, const cl_stats *st, cl_error *err)
{
    char path[4096];
    cl_afile af;
    snprintf(path, sizeof path, "%s/stats.csv", s->so->outdir);
    cl_status rc = cl_afile_open(&af, path, err);
    if (rc)
        return rc;
    cl_stats_print(st, af.fp, false);
    return cl_afile_commit(&af, err);
}

/* ---- the run ---------------------------------------------------------- */

static cl_status sim_alloc(sim *s, cl_error *err)
{
    size_t n = s->sys->n, np = s->c->np;
    s->x = malloc(n * sizeof *s->x);
    s->v = calloc(n, sizeof *s->v);
    s->xf = malloc(3 * np * sizeof *s->xf);
    s->vf = calloc(3 * np, sizeof *s->vf);
    s->vgood = malloc(3 * np * sizeof *s->vgood);
    s->pinned = calloc(np, 1);
    if (!s->x || !s->v || !s->xf || !s->vf || !s->vgood || !s->pinned)
        return cl_error_set(err, CL_ENOMEM, "out of memory (run)");
    for (size_t p = 0; p < np; p++)
        s->pinned[p] = s->c->dof[p] < 0;
    if (cl_model_initial_state(s->m, s->x, s->v))
        return cl_error_set(err, CL_ENOMEM, "out of memory (initial state)");
    cl_status rc = cl_pairs_neighbours(s->c, &s->near, err);
    s->tearing = cl_model_tears(s->m) || cl_model_broken(s->m) > 0;
    s->offplane = cl_offplane_applies(s->c);
    if (rc || !s->tearing)
        return rc;
    s->intact.pair = malloc((s->near.n + 1) * sizeof *s->intact.pair);
    s->tri = malloc((s->c->ntri + 1) * sizeof *s->tri);
    if (!s->intact.pair || !s->tri)
        return cl_error_set(err, CL_ENOMEM, "out of memory (tearing)");
    return CL_OK;
}

static void sim_free(sim *s)
{
    cl_pairs_free(&s->near);
    cl_pairs_free(&s->intact);
    free(s->tri);
    free(s->x);
    free(s->v);
    free(s->xf);
    free(s->vf);
    free(s->vgood);
    free(s->pinned);
    free(s->row);
}

/* The stop asked for after the sample at res->t_reached, during the
 * advance to t_to (NaN: between advances): CL_EBUDGET for --max-wall's
 * timer (SIGALRM), else CL_EINTR naming the signal. */
static cl_status stop_error(const sim *s, const cl_sim_result *res,
                            double t_to, cl_error *err)
{
    if (cl_stop_requested() != SIGALRM)
        return cl_stop_error(err, res->t_reached, t_to);
    char during[64] = "";
    if (!isnan(t_to))
        snprintf(during, sizeof during, " (during the advance to t = %g)",
                 t_to);
    return cl_error_set(err, CL_EBUDGET, "budget --max-wall %g s reached at "
                        "t = %.10g%s", s->so->max_wall, res->t_reached,
                        during);
}

/* Advance to tick `tick` (unless already there) and sample it. */
static cl_status reach(sim *s, const cl_integrator_type *type, void *state,
                       const schedule *sch, long tick, cl_sim_result *res,
                       cl_error *err)
{
    double t = tick == sch->nticks && !sch->fixed
                   ? s->so->t_end : sch->t0 + (double)tick * sch->dt_tick;
    double w0 = cl_clock_wall();
    double c0 = cl_clock_cpu();
    cl_status rc = type->advance(state, t, s->x, s->v, err);
    res->stats.wall += cl_clock_wall() - w0;
    res->stats.cpu += cl_clock_cpu() - c0;
    if (rc == CL_EINTR && cl_stop_requested()) /* the evaluations stopped */
        return stop_error(s, res, t, err);
    return rc ? rc : sample(s, t, res, err);
}

/* A stop asked for (a signal) or a budget spent after the sample at
 * res->t_reached: CL_EINTR or CL_EBUDGET with the reason. */
static cl_status check_stop(const sim *s, const cl_integrator_type *type,
                            const void *state, const cl_sim_result *res,
                            cl_error *err)
{
    const cl_sim_opts *so = s->so;
    if (cl_stop_requested())
        return stop_error(s, res, NAN, err);
    if (so->max_steps > 0) {
        cl_stats st = {0};
        type->stats(state, &st);
        if (st.steps >= so->max_steps)
            return cl_error_set(err, CL_EBUDGET, "budget --max-steps %ld "
                                "reached at t = %.10g (%ld steps)",
                                so->max_steps, res->t_reached, st.steps);
    }
    return CL_OK;
}

/* Integrate over the schedule, sampling and writing frames.  Samples and
 * frames that round to the same tick (more outputs than fixed steps) are
 * produced once. */
static cl_status integrate(sim *s, const cl_integrator_type *type,
                           void *state, const schedule *sch,
                           cl_sim_result *res, cl_error *err)
{
    const cl_sim_opts *so = s->so;
    long ks = 1, kf = 1, nf = so->frames, last = 0, last_frame = 0;
    cl_status rc = CL_OK;
    while (rc == CL_OK && ks <= so->samples) {
        long ts = tick_of(ks, so->samples, sch->nticks);
        long tf = kf <= nf ? tick_of(kf, nf, sch->nticks) : ts + 1;
        long tick = ts < tf ? ts : tf;
        if (tick > last) {
            rc = reach(s, type, state, sch, tick, res, err);
            last = tick;
        }
        if (!rc && tick == tf && tick > last_frame) {
            rc = write_frame(s, res->t_reached, res, err);
            last_frame = tick;
        }
        ks += tick == ts;
        kf += tick == tf;
        if (so->progress)
            so->progress(so->progress_ctx, (res->t_reached - sch->t0) /
                                               (so->t_end - sch->t0));
        if (!rc && ks <= so->samples)
            rc = check_stop(s, type, state, res, err);
    }
    return rc;
}

/* The options' own ranges (the command line's, for callers of the
 * library). */
static cl_status check_opts(const cl_sim_opts *so, cl_error *err)
{
    if (!(so->t_end > 0) || !isfinite(so->t_end))
        return cl_error_set(err, CL_EINVAL, "t_end = %g: expected a finite "
                            "number > 0 (and after the model's start time)",
                            so->t_end);
    if (so->samples < 1 || so->frames < 0 || so->max_steps < 0)
        return cl_error_set(err, CL_EINVAL, "samples = %ld, frames = %ld, "
                            "max_steps = %ld: expected samples >= 1, "
                            "frames >= 0, max_steps >= 0", so->samples,
                            so->frames, so->max_steps);
    if (!(so->max_stretch >= 1))
        return cl_error_set(err, CL_EINVAL, "max_stretch = %g: expected >= 1 "
                            "(the stretch d/L beyond which a run counts as "
                            "blown up; INFINITY for none)", so->max_stretch);
    if (!(so->max_wall >= 0) || !so->outdir || !*so->outdir)
        return cl_error_set(err, CL_EINVAL, "max_wall = %g, outdir %s: "
                            "expected max_wall >= 0 (0: none) and an output "
                            "directory", so->max_wall,
                            so->outdir ? so->outdir : "NULL");
    return CL_OK;
}

cl_status cl_simulate(cl_model *m, const cl_integrator_type *type,
                      const cl_integrator_opts *iopts, const cl_sim_opts *so,
                      cl_sim_result *res, cl_error *err)
{
    sim s = {.m = m, .c = cl_model_cloth(m), .sys = cl_model_system(m),
             .so = so};
    schedule sch = {0};
    void *state = NULL;
    bool writing = false; /* outdir prepared: outputs may go there */
    memset(res, 0, sizeof *res);
    cl_status bad = check_opts(so, err);
    if (bad)
        return bad;
    double t0 = cl_model_start_time(m);
    cl_model_contact_start(m, t0, false);
    size_t n3 = 3 * s.c->np, npot = cl_model_potentials(m);
    res->xfinal = malloc((n3 + 2 * npot) * sizeof *res->xfinal);
    cl_status rc = res->xfinal ? CL_OK
                               : cl_error_set(err, CL_ENOMEM, "out of memory");
    /* --max-wall by a wall-time timer (core/stop.h): once it rings, the
     * model's evaluations end the advance where it is */
    if (!rc && so->max_wall > 0)
        rc = cl_stop_after(CL_STOP_WALL, so->max_wall, err);
    if (!rc) {
        s.e0_terms = res->xfinal + n3;
        s.e1_terms = s.e0_terms + npot;
    }
    /* the integrator first: one that refuses the problem (a contact
     * response it cannot apply, ...) stops the run before any output */
    if (!rc && !(rc = make_schedule(type, iopts, so, t0, &sch, err)) &&
        !(rc = sim_alloc(&s, err)) &&
        !(rc = cl_integrator_create(type, s.sys, iopts, t0, s.x, s.v,
                                    &state, err)) &&
        !(rc = so->before_output
                   ? so->before_output(so->before_output_ctx, err)
                   : CL_OK) &&
        !(rc = cl_mkdir_p(so->outdir, err)) && (writing = true) &&
        !(rc = open_series(&s, t0, err)) && !(rc = sample(&s, t0, res, err))) {
        cl_energy_keep(&res->e0, &res->e1, s.e0_terms);
        if (so->frames > 0)
            rc = write_frame(&s, t0, res, err);
        if (!rc)
            rc = integrate(&s, type, state, &sch, res, err);
    }
    cl_model_contact_worst(m, &res->worst_penetration, &res->worst_t);
    cl_model_contact_closest(m, &res->min_distance, &res->min_distance_t);
    if (state) {
        double wall = res->stats.wall, cpu = res->stats.cpu;
        type->stats(state, &res->stats);
        res->stats.wall = wall;
        res->stats.cpu = cpu;
        type->free(state);
    }
    /* What was computed is published even after a failure; a run stopped
     * early (stopped) writes everything a finished one does. */
    cl_error later;
    bool stopped = rc == CL_EINTR || rc == CL_EBUDGET;
    cl_status rc2 = cl_series_close(s.series, rc ? &later : err);
    if (!rc)
        rc = rc2;
    if (res->rows > 0 && !rc2) {
        const char *name = !rc || stopped ? "final.csv" : "last-good.csv";
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", so->outdir, name);
        rc2 = cl_state_write(path, s.c->np, res->xfinal, s.vgood,
                             rc ? &later : err);
        res->state_file = rc2 == CL_OK ? name : NULL;
        rc = rc ? rc : rc2;
    }
    if (s.x && writing)
        rc2 = write_stats(&s, &res->stats, rc ? &later : err);
    if (!rc)
        rc = rc2;
    if (so->max_wall > 0) /* the budget was this run's: the next starts
                           * clean (a SIGINT or SIGTERM stays) */
        cl_stop_clear();
    sim_free(&s);
    return rc;
}
