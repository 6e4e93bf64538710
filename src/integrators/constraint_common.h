/* Shared state and step loop of the constraint-based integrators
 * (docs/integrators.md, 9): xpbd and pd.  Both see the springs of the
 * model as the distance constraints of the system (system/system.h,
 * cl_distances) and every other force (gravity, damping, ...) through
 * force_other, an external acceleration of the predictor.
 *
 * A step of length dt is `substeps` S substeps of h = dt / S (Macklin,
 * Storey, Lu, Terdiman, Chentanez, Jeschke and Mueller, "Small steps in
 * physics simulation", SCA 2019, algorithm 1), each
 *
 *   v  <- v_n + h M^-1 f_other(t, x_n, v_n)        predictor
 *   y  =  x_n + h v                                 inertial target
 *   x  <- y, then `iterations` K sweeps of the method's constraint solve
 *         (anchors at their positions at t + h)
 *   v  <- (x - x_n) / h.
 *
 * The method supplies the solve (method->solve on s->x, with s->y, s->xa
 * and h) and, optionally, a setup that builds its own state once (s->own,
 * freed by method->free).  This module checks the options, refuses a
 * system without distance constraints, allocates everything once and runs
 * the output times through cl_fixed_run (fixed_step.h): the contact and
 * step_done hooks after every step as for every fixed-step method.
 * Nothing is allocated per step.  Statistics: steps, rhs_evals (force_other
 * evaluations, one per substep), nonlin_iters (constraint sweeps: S K per
 * step) and the method's linear-solver counters. */
#ifndef CL_CONSTRAINT_COMMON_H
#define CL_CONSTRAINT_COMMON_H

#include "core/decls.h"
#include "integrators/define.h"
#include "integrators/integrator.h"

CL_BEGIN_DECLS

typedef struct cl_cdyn cl_cdyn;

typedef struct {
    const char *name;         /* registry name, used in messages */
    long default_iterations;  /* K when opts->iterations is 0 */
    /* Build the method's own state into s->own (NULL: none). */
    cl_status (*setup)(cl_cdyn *s, cl_error *err);
    /* K iterations of the constraint solve of one substep of length h
     * ending at time t, on s->x in place. */
    cl_status (*solve)(cl_cdyn *s, double t, double h, cl_error *err);
    void (*free)(void *own);
} cl_cdyn_method;

struct cl_cdyn {
    const cl_cdyn_method *method;
    const cl_system *sys;
    const cl_distances *dc;
    size_t n;              /* sys->n */
    double t0, dt, h;      /* start, step, substep dt / substeps */
    long substeps, iterations;
    long done, nrhs, sweeps;
    long lin_setups, lin_solves; /* the method's, for the statistics */
    double *x, *v;         /* current state (n each) */
    double *inv_mass;      /* n */
    double *xn;            /* positions at the start of the substep (n) */
    double *y;             /* inertial target x_n + h v (n) */
    double *xa;            /* anchor positions (3 nanchor) */
    void *own;             /* the method's state */
};

/* Position of end e of a constraint (free index or -1 - anchor) and its
 * inverse mass (0 for an anchor). */
static inline double *cl_cdyn_pos(cl_cdyn *s, int e)
{
    return e >= 0 ? s->x + 3 * e : s->xa + 3 * (-1 - e);
}
static inline double cl_cdyn_w(const cl_cdyn *s, int e)
{
    return e >= 0 ? s->inv_mass[3 * e] : 0.0;
}

cl_status cl_cdyn_create(const cl_cdyn_method *m, const cl_system *sys,
                         const cl_integrator_opts *o, double t0,
                         const double *x0, const double *v0, void **state,
                         cl_error *err);
cl_status cl_cdyn_advance(void *state, double t_out, double *x, double *v,
                          cl_error *err);
void cl_cdyn_stats(const void *state, cl_stats *out);
void cl_cdyn_free(void *state);

/* The integrator table `ident` of a constraint-based method. */
#define CL_CDYN_INTEGRATOR(ident, method, name_, doc_)                      \
    CL_INTEGRATOR_CREATE(ident, cl_cdyn_create, &(method))                  \
    const cl_integrator_type ident = {                                      \
        .name = (name_),                                                    \
        .doc = (doc_),                                                      \
        .region = &cl_region_projected,                                     \
        .fixed_step = true,                                                 \
        .takes_iterations = true,                                           \
        .create = ident##_create,                                           \
        .advance = cl_cdyn_advance,                                         \
        .stats = cl_cdyn_stats,                                             \
        .free = cl_cdyn_free,                                               \
    }

CL_END_DECLS

#endif
