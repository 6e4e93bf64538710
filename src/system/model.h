/* A cloth problem: the cloth (a grid or a mesh), its pins and its force
 * terms, presented to the integrators as a cl_system (docs/model.md, 1).
 *
 * INI sections read here:
 *   [cloth]    the grid or the mesh (model/cloth_read.h)
 *   [pins] .. [pins4]  pinned particles and their motion (model/pins.h)
 *   [init]     velocity = initial velocity of every free particle (vector,
 *              default 0,0,0); perturb = amplitude (m) of a uniform random
 *              displacement along y of the free particles, out of the
 *              plane of a grid or of a horizontal mesh (default 0:
 *              positions start at rest); seed = its random seed (default 1)
 *   [jacobian] transverse = full|clamp (docs/model.md, 3.1)
 *   [tear]     cut = a connection breaks for good when d > cut L (0, the
 *              default: no tearing; docs/model.md, 3.4).  The system's
 *              step_done hook (tearing, checked after every accepted step
 *              or output time, see system/system.h) is installed only when
 *              cut > 0.
 * plus each force term's own section (forces/registry.c). */
#ifndef CL_MODEL_H
#define CL_MODEL_H

#include "contact/contact.h"
#include "core/decls.h"
#include "forces/term.h"
#include "io/config.h"
#include "model/cloth.h"
#include "system/system.h"

CL_BEGIN_DECLS

typedef struct cl_model cl_model;

cl_status cl_model_create(cl_config *cfg, cl_model **model, cl_error *err);
void cl_model_free(cl_model *m);

/* Forces and Jacobians of every pair term (Type1, Type2, damping,
 * springs, spring damping: cl_term_type.threads) run on `threads` OpenMP
 * threads: per-pair results first, then each thread adds those of its own
 * particles and Jacobian slots in the serial order (forces/pairkern.h), so
 * results are bitwise the same for every count.  The count is also the
 * system's (cl_system.threads: the Krylov solvers' matrix-vector
 * products).  Energies and every other term stay serial.  1 (the default)
 * is serial. */
#define CL_MODEL_MAX_THREADS 64
cl_status cl_model_set_threads(cl_model *m, int threads, cl_error *err);

const cl_system *cl_model_system(cl_model *m);
const cl_cloth *cl_model_cloth(const cl_model *m);

/* Initial state of the free particles (3*nfree each): rest positions plus
 * the [init] out-of-plane noise, and the [init] velocity; or those of the
 * [init] state file.  CL_ENOMEM is the only failure. */
cl_status cl_model_initial_state(const cl_model *m, double *x, double *v);

/* The free state x, v (3*nfree each) of a state file (final.csv's
 * format, io/state.h) of this cloth; cl_state_read's failures. */
cl_status cl_model_read_state(const cl_model *m, const char *path, double *x,
                              double *v, cl_error *err);

/* The time of that initial state: [init] time (s, >= 0), 0 unless an
 * [init] state gives another; runs start there. */
double cl_model_start_time(const cl_model *m);

/* [init] time as the model reads it, before a model is made (a command
 * that needs its runs' span first): 0 when absent, CL_EINVAL with the
 * entry when it does not parse or lies outside [0, 1e12] s. */
cl_status cl_model_config_start_time(cl_config *cfg, double *t0,
                                     cl_error *err);

/* Connections torn so far (docs/model.md, 3.4): distinct particle pairs,
 * however many terms (a spring and its damper, ...) had a force on the
 * pair. */
size_t cl_model_broken(const cl_model *m);

/* Whether the model can tear ([tear] cut > 0 and a term that tears). */
bool cl_model_tears(const cl_model *m);

/* Whether the connection a-b (either order) has torn. */
bool cl_model_is_broken(const cl_model *m, int a, int b);

/* The cloth's triangles (cl_cloth tri, in order) without those that have a
 * torn edge: tri must hold cl_model_cloth(m)->ntri rows; *ntri is the
 * number kept. */
cl_status cl_model_triangles(const cl_model *m, int (*tri)[3], size_t *ntri,
                             cl_error *err);

/* The number of active force terms; *names = their names, in evaluation
 * order (the model's table). */
size_t cl_model_terms(const cl_model *m, const char *const **names);

/* The number of conservative terms, cl_energy.nterm of every energy
 * evaluation. */
size_t cl_model_potentials(const cl_model *m);

/* Forces on every particle (pinned ones included) and the energies for
 * full-particle positions and velocities (3*np each). */
cl_status cl_model_eval_full(cl_model *m, double t, const double *x,
                             const double *v, double *f, cl_energy *e,
                             cl_error *err);

/* df/dx and df/dv over all particles (pinned ones included): fills pat (the
 * caller frees it with cl_bpattern_free) and allocates *dfdx and *dfdv
 * (9 * pat->nnzb each; the caller frees them). */
cl_status cl_model_jacobian_full(cl_model *m, double t, const double *x,
                                 const double *v, cl_bpattern *pat,
                                 double **dfdx, double **dfdv, cl_error *err);

/* The self-contact term's closest distance between non-neighbours at
 * full-particle positions x (3 np; forces/selfcontact.h
 * cl_selfcontact_closest: INFINITY when no pair is closer than its
 * thickness); false, *d untouched, when the model has no self-contact. */
bool cl_model_selfcontact_closest(cl_model *m, const double *x, double *d);

/* ---- contact (contact/contact.h) ------------------------------------- */

/* The obstacles, or NULL when the problem has none. */
const cl_contact *cl_model_contact(const cl_model *m);

/* Start of a run at t0, before its integrator's first step (cl_simulate
 * and the studies' trials call it; a program of one's own calls it before
 * each run): the worst penetration and the contact layer's memory of the
 * last run (cl_contact_restart: its last projection, now at t0, the
 * barriers' lagged friction) are forgotten (from an [init] state, the lag
 * is that state's, as after the step that ended there), and with
 * track_work the
 * contact hook accounts the energy every projection changes
 * (cl_energy.contact_work; two energy evaluations per projecting step,
 * so only the energy study asks for it).  A model carries one run at a
 * time, and a model that tears keeps its torn connections: a new run of
 * it needs a new model (analysis/trial.h, cl_trial_repeatable). */
void cl_model_contact_start(cl_model *m, double t0, bool track_work);

/* The deepest penetration since cl_model_contact_start, seen by the
 * contact hook after every accepted step (fixed-step methods, CVODE BDF)
 * or at output times, and by cl_model_contact_figures; and its time. */
void cl_model_contact_worst(const cl_model *m, double *pen, double *t);

/* The least signed distance of a free particle to a barrier obstacle
 * since cl_model_contact_start (INFINITY without barriers), seen by the
 * contact hook after every accepted step (fixed-step methods, CVODE BDF
 * on a problem that projects) or at output times (contact/barrier.h); and
 * its time. */
void cl_model_contact_closest(const cl_model *m, double *d, double *t);

/* The surfaces of all obstacles at time t, in one triangle list (free
 * with cl_shape_surface_free); none without obstacles. */
cl_status cl_model_obstacle_surface(const cl_model *m, double t,
                                    cl_shape_surface *all, cl_error *err);

/* The contact figures at time t for the free state x, v (only with
 * obstacles). */
cl_status cl_model_contact_figures(cl_model *m, double t, const double *x,
                                   const double *v, cl_contact_figures *f);

CL_END_DECLS

#endif
