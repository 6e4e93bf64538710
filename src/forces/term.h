/* The force-term interface.  A force model (Choi-Ko Type1, Type2, damping,
 * gravity, ...) is one file defining a cl_term_type and one row in the
 * registry table of forces/registry.c; nothing else changes.
 *
 * A term reads its own INI section in `create` and returns *state = NULL if
 * it is switched off.  It works on full-particle arrays (all particles,
 * pinned ones included, 3*np), so it never knows which particles are free or
 * which integrator runs it.  Jacobian blocks go into the slots of a
 * cl_bpattern that the term looks up once in `bind`. */
#ifndef CL_TERM_H
#define CL_TERM_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "io/config.h"
#include "linalg/bpattern.h"
#include "model/cloth.h"
#include "model/pairs.h"

CL_BEGIN_DECLS

/* Options shared by every term (docs/model.md 3.1: jacobian.transverse;
 * 3.4: tearing). */
typedef struct {
    bool clamp_transverse; /* drop (s/d)(I - uu^T) where s < 0 */
    double tear_cut;       /* [tear] cut: a connection breaks when
                            * d > cut L; 0 for no tearing */
} cl_term_opts;

typedef struct {
    double t;
    const double *x;  /* positions, 3*np */
    const double *v;  /* velocities, 3*np */
    double *f;        /* forces are added here (3*np), or NULL */
    double *dfdx;     /* blocks added into pattern slots, or NULL */
    double *dfdv;     /* likewise for the velocity Jacobian, or NULL */
    bool want_energy;
    double energy;    /* out (if want_energy): this term's potential energy */
    double power;     /* out (if want_energy): sum of f . v of a dissipative
                       * term (damping); 0 for conservative terms */
} cl_eval;

typedef struct cl_term_type {
    const char *name;   /* also the energy column and INI section */
    const char *doc;    /* one line for `clothode list` */
    bool conservative;  /* energy is a potential (else: dissipative power) */
    bool soft;          /* explicit by default in an IMEX split (the
                         * term's `imex` key; docs/integrators.md 10) */
    cl_status (*create)(cl_config *cfg, const cl_cloth *cloth,
                        const cl_term_opts *opts, void **state,
                        cl_error *err);
    /* Particle pairs whose blocks this term writes (may be 0). */
    size_t (*couplings)(const void *state, const int (**pairs)[2]);
    /* Look up block slots in the pattern (called once per pattern). */
    cl_status (*bind)(void *state, const cl_bpattern *pat, const int *dof,
                      cl_error *err);
    void (*eval)(void *state, cl_eval *ev);
    /* Optional (NULL if not needed): */
    /* Project full-particle positions onto the term's position-based
     * constraints (the Verlet-and-PBD report); dof[p] < 0 marks particles
     * that must not move (pinned). */
    void (*project)(void *state, double *x, const int *dof);
    /* Distance constraints (system/system.h, cl_distances) that stand for
     * this term's forces in the constraint-based integrators (xpbd, pd):
     * returns their number, *pair their particles and rest lengths, *k
     * their stiffnesses (N/m), or *k = NULL for hard constraints. */
    size_t (*distances)(const void *state, const cl_pair **pair,
                        const double **k);
    /* After an accepted step: irreversible updates (tearing: a pair breaks
     * when d > cut L); returns the number of newly broken connections. */
    size_t (*step_done)(void *state, const double *x, const double *v);
    /* Connections (particle pairs) broken so far, for leaving torn
     * triangles out of frames. */
    size_t (*broken)(const void *state, const int (**pairs)[2]);
    /* Evaluate forces and Jacobians with `threads` OpenMP threads from now
     * on (cl_model_set_threads), with results bitwise independent of the
     * count (forces/pairkern.h); allocates what that needs, once. */
    cl_status (*threads)(void *state, int threads, cl_error *err);
    /* Forces alone (ev asks for no Jacobian and no energy) of this term
     * and of the terms evaluated right after it, next[0..nnext) (states
     * next_state[]), in one pass over the pairs they share; returns how
     * many of them it evaluated with itself (the first ones), 0 having
     * done nothing where it cannot (then each term evaluates on its own).
     * Per-pair forces are summed before they are added, so the sums
     * round differently from separate passes. */
    size_t (*fuse)(void *state, const struct cl_term_type *const *next,
                   void *const *next_state, size_t nnext, cl_eval *ev);
    void (*free)(void *state);
} cl_term_type;

/* Registry (forces/registry.c), NULL-terminated, in evaluation order. */
extern const cl_term_type *const cl_term_registry[];

CL_END_DECLS

#endif
