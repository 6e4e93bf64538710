/* The system interface: everything an integrator may know about the cloth.
 *
 * The unknowns are the positions x and velocities v of the free particles
 * (3*nfree each); M is diagonal.  The ODE is x' = v, M v' = f(t, x, v)
 * (docs/model.md 1).  Jacobians are given as 3x3-block values in a fixed
 * pattern (`pattern`, block rows = free particles), so an integrator
 * assembles whatever matrix its linear solver wants from precomputed
 * maps.
 * Modelled on SUNDIALS' user-data pattern and GSL's gsl_odeiv2_system.
 *
 * Once a stop is requested (SIGINT, SIGTERM: core/stop.h), force,
 * jacobian, force_other, force_terms and jacobian_terms return CL_EINTR
 * without evaluating, an error every integrator passes on unrecoverably:
 * a run stops within one evaluation, not at the end of its advance. */
#ifndef CL_SYSTEM_H
#define CL_SYSTEM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "core/decls.h"
#include "core/error.h"
#include "linalg/bpattern.h"

CL_BEGIN_DECLS

typedef struct {
    size_t nterm;
    /* The potential terms by name and their energies, nterm each, in the
     * system's storage (allocated once with it): valid until its next
     * energy evaluation; cl_energy_keep copies them to the holder's. */
    const char *const *name;
    const double *value;
    double kinetic;
    double potential;  /* sum of value[] */
    double total;      /* kinetic + potential */
    double power_diss; /* power of the non-conservative forces (<= 0) */
    double contact_work; /* energy changed by contact projections so far
                          * (J; system/model.h, cl_model_contact_start) */
} cl_energy;

/* *dst = *src with the term energies copied into `keep` (src->nterm
 * entries), which dst->value then points to. */
static inline void cl_energy_keep(cl_energy *dst, const cl_energy *src,
                                  double *keep)
{
    *dst = *src;
    if (src->nterm)
        memcpy(keep, src->value, src->nterm * sizeof *keep);
    dst->value = keep;
}

/* Baraff-Witkin constraints of one step (Baraff & Witkin, "Large Steps in
 * Cloth Simulation", 1998, section 5; docs/model.md, eqs. C10-C13), per
 * free particle i, arrays allocated by the integrator (nb = n / 3):
 *   S[9i..9i+8]  the filter, row-major: I (free), I - n n^T (constrained
 *                along the normal n) or 0 (constrained fully);
 *   z[3i..]      the prescribed velocity change, in the range of I - S;
 *   y[3i..]      the position correction, in the range of I - S;
 *   g[3i..]      a friction impulse added to the right-hand side of the
 *                step's linear system (a sliding constrained particle),
 *                in that system's own units. */
typedef struct {
    double *S, *z, *y, *g;
} cl_constraint_set;

/* Distance constraints (docs/model.md, 3.6): the pairs of the terms that
 * are spring networks (springs: stiffness k; pbd: infinitely stiff), for
 * the constraint-based integrators (xpbd, pd), built once with the model.
 * Constraint c keeps |x_a - x_b| at rest[c] with compliance 1/stiffness[c]
 * (0 for stiffness INFINITY, a hard constraint); its ends end[c][0..1] are
 * free particle indices (0 .. n/3 - 1), or -1 - j for anchor j, a pinned
 * particle whose position at time t the system's `anchors` hook gives. */
typedef struct {
    size_t n;                 /* constraints */
    const int (*end)[2];      /* free index, or -1 - anchor */
    const double *rest;       /* L (m) */
    const double *stiffness;  /* k (N/m), > 0, INFINITY: hard */
    size_t nanchor;           /* pinned particles that constraints reach */
} cl_distances;

/* What the contact hook (cl_system.contact) does: see there. */
enum {
    CL_CONTACT_RECORD = 1u,  /* record the contact figures of the state */
    CL_CONTACT_PROJECT = 2u  /* apply the `project` responses to it */
};

typedef struct cl_system {
    size_t n;                    /* 3 * free particles */
    const double *mass;          /* n diagonal masses */
    const cl_bpattern *pattern;  /* blocks over free particles */
    int threads;                 /* OpenMP threads for forces, Jacobians and
                                  * the linear solvers' products (>= 1;
                                  * results do not depend on it) */
    void *data;
    /* f(t, x, v) on the free particles (n entries). */
    cl_status (*force)(void *data, double t, const double *x,
                       const double *v, double *f);
    /* Block values of df/dx and df/dv (9 * pattern->nnzb each); the callee
     * zeroes and fills them, and may also return f (or NULL). */
    cl_status (*jacobian)(void *data, double t, const double *x,
                          const double *v, double *f, double *dfdx,
                          double *dfdv);
    /* The energies at (t, x, v); CL_EINFEASIBLE, like force and jacobian,
     * for a state with a particle at d <= 0 of a barrier obstacle (below,
     * step_fraction). */
    cl_status (*energy)(void *data, double t, const double *x,
                        const double *v, cl_energy *e);
    /* Position-based constraints (the Verlet-and-PBD report; docs/model.md
     * 3.4), NULL if the model has none: move the positions x (n entries)
     * toward satisfying the constraints, in place.  Used by position-based
     * integrators (verlet-pbd) only. */
    cl_status (*project)(void *data, double t, double *x);
    /* Distance constraints (above), NULL if the model has none (or tears:
     * a torn network changes them).  With them, `force_other` is f(t, x,
     * v) without the forces of the constrained terms (gravity, damping,
     * ...: the external forces of XPBD's and projective dynamics'
     * predictor) and `anchors` writes the positions of the anchors at t
     * (3 * nanchor). */
    const cl_distances *distances;
    cl_status (*force_other)(void *data, double t, const double *x,
                             const double *v, double *f);
    void (*anchors)(void *data, double t, double *xa);
    /* Changes of the model after an accepted step (tearing, the lag of
     * the barriers' friction), NULL if the model has none.  *changed is set when the force law
     * changed, so that multistep and adaptive methods restart from (t, x,
     * v).  Fixed-step integrators call it after every step; adaptive ones
     * at every output time. */
    cl_status (*step_done)(void *data, double t, const double *x,
                           const double *v, bool *changed);
    /* Contact with obstacles (docs/model.md, contact), NULL if the
     * problem has no obstacle; `what` (CL_CONTACT_*, below) says what to
     * do with the state (t, x, v) (n each):
     *   RECORD | PROJECT  after an accepted step: record the contact
     *                     figures (the deepest penetration the step
     *                     reached, the barriers' least distance), then
     *                     apply every `project` response, moving x and v
     *                     in place;
     *   PROJECT           a trial: project a step that may still be
     *                     rejected (recording nothing);
     *   RECORD            the step of the last trial was accepted, and
     *                     (x, v) is its state before that projection:
     *                     record it (x and v are not changed).
     * The rule, one for every integrator: penalty contact is a force term
     * like any other; projection runs after every step of the fixed-step
     * methods (RECORD | PROJECT, before step_done) and inside CVODE's BDF
     * steps through its projection interface (PROJECT, then RECORD with
     * the state before it once the step is accepted: its outputs are
     * steps' ends, RECORD | PROJECT); the other adaptive methods call
     * this hook at their output times (RECORD | PROJECT) for the figures
     * only and refuse a problem with `projects`. */
    cl_status (*contact)(void *data, double t, double *x, double *v,
                         unsigned what);
    /* The filter of the barrier responses (contact/barrier.h), NULL if
     * the problem has no barrier obstacle: the largest fraction in [0, 1]
     * of the straight move of the free positions from x0 (feasible, at
     * t0) to x1 (at t1) that keeps every particle outside every barrier
     * obstacle, with IPC's safety factor (cl_contact_step_fraction).  With
     * barriers, force and jacobian return CL_EINFEASIBLE for a state with
     * a particle at d <= 0 of a barrier obstacle. */
    double (*step_fraction)(void *data, double t0, const double *x0,
                            double t1, const double *x1);
    /* Baraff-Witkin constraints (response = constraint), NULL if no
     * obstacle has them: with impulse NULL, the constraints of the step of
     * length h from (t, x, v) into cs; else impulse (n entries, the
     * constraint impulses A sol - rhs - g the last solve needed, in its
     * units) releases the constraints that pull and demotes the sticking
     * ones that leave the friction cone, updating cs, and *changed says
     * whether any did.  Only semi-be and semi-bdf2 apply them; every other
     * integrator refuses such a system (cl_integrator_refuse_constraints). */
    cl_status (*constrain)(void *data, double t, double h, const double *x,
                           const double *v, const double *impulse,
                           cl_constraint_set *cs, bool *changed);
    /* The force terms one by one, for methods that treat them apart (the
     * IMEX methods, docs/integrators.md 10): a term mask has bit k for the
     * k-th of the nterm <= 64 terms (cl_model_terms order); force_terms and
     * jacobian_terms are force and jacobian over the terms of mask alone
     * (UINT64_MAX: all, the same numbers as force and jacobian), NULL
     * when the system is not made of terms.  implicit_terms: the terms
     * an IMEX method treats implicitly (each term's `imex` key). */
    size_t nterm;
    uint64_t implicit_terms;
    cl_status (*force_terms)(void *data, uint64_t mask, double t,
                             const double *x, const double *v, double *f);
    cl_status (*jacobian_terms)(void *data, uint64_t mask, double t,
                                const double *x, const double *v, double *f,
                                double *dfdx, double *dfdv);
    bool projects;  /* some obstacle has response = project */
    bool projects_friction; /* ... with friction: mu > 0 or zero_velocity
                             * (a velocity-level law that CVODE's error
                             * control cannot follow, see sun_adapter.h) */
} cl_system;

CL_END_DECLS

#endif
