/* One simulation run: integrate a model with a chosen integrator to t_end,
 * writing into an output directory
 *   series.csv   t, kinetic, each potential term, potential, total,
 *                power_diss, max_stretch, max_offplane, wrinkles, broken
 *                (connections torn so far) (one row per sample, flushed as
 *                it is written, so a failed run keeps its rows; NA in a
 *                column that does not apply, see simulate.c); with
 *                obstacles also contacts, max_penetration, contact_force,
 *                friction_power, and with barrier obstacles min_distance
 *                (contact/contact.h)
 *   frame_NNNNN.vtk / .obj   cloth frames (ParaView / Blender); with
 *                tearing, without the triangles that have a torn edge
 *   obstacles_NNNNN.vtk / .obj   the obstacles at the frame times
 *   final.csv    the final state (p,x,y,z,vx,vy,vz, all particles)
 *   last-good.csv  instead of final.csv after a failure: the state of
 *                the last good sample (below)
 *   stats.csv    the integrator's counters (name,value); its wall and CPU
 *                time are in the result only, so that two identical runs
 *                write identical bytes
 * A run starts at the model's start time t0 (cl_model_start_time: 0, or
 * [init] time) from its initial state.  Fixed-step integrators are sampled
 * on their own step grid; t_end - t0 must be a multiple of dt. */
#ifndef CL_SIMULATE_H
#define CL_SIMULATE_H

#include <stdbool.h>

#include "core/decls.h"
#include "integrators/integrator.h"
#include "system/model.h"

CL_BEGIN_DECLS

typedef struct {
    double t_end;        /* > 0, and > the model's start time t0 */
    long samples;        /* time-series rows after t0, >= 1 */
    long frames;         /* frames after t0 (0: none) */
    bool vtk, obj;       /* frame formats */
    const char *outdir;
    double max_stretch;  /* a larger max d/L counts as a blow-up; >= 1,
                          * INFINITY for none (the command line's
                          * default is 10) */
    double max_wall;     /* budget: wall-clock seconds of the run, 0: none */
    long max_steps;      /* budget: integrator steps of the run, 0: none */
    void (*progress)(void *ctx, double fraction);
    void *progress_ctx;
    /* Called once the integrator has accepted the problem, before
     * anything is written into outdir (NULL: nothing): where the caller
     * clears the directory of an earlier run, so that a refusal (a bad
     * linear solver, a step that does not divide t_end, ...) leaves that
     * run's outputs as they were. */
    cl_status (*before_output)(void *ctx, cl_error *err);
    void *before_output_ctx;
} cl_sim_opts;

typedef struct {
    cl_stats stats;
    double t_reached;    /* last time with a good state */
    cl_energy e0, e1;    /* energies at t0 and at t_reached */
    double max_stretch;  /* at t_reached */
    double max_offplane; /* at t_reached (NaN: does not apply) */
    long rows;           /* time-series rows written (incl. t0) */
    long frames;         /* frames written */
    const char *state_file; /* the state file written, at t_reached:
                             * "final.csv", "last-good.csv" (a failed
                             * run), or NULL (none) */
    double worst_penetration; /* deepest into an obstacle (m; contact) */
    double worst_t;      /* ... and when */
    double min_distance; /* least distance to a barrier obstacle (m;
                          * INFINITY without barriers) */
    double min_distance_t; /* ... and when */
    double *xfinal;      /* full-particle positions at t_reached (3*np),
                          * followed by the term energies of e0 and e1 in
                          * the same block; owned by the caller after the
                          * call: free() */
} cl_sim_result;

/* Options out of their ranges are CL_EINVAL before anything is done.  A
 * wall-time budget (max_wall) is this run's alone: the next call starts
 * without it, and SIGALRM's action is given back (core/stop.h).
 * On failure (e.g. CL_EBLOWUP) the series and frames written so far are in
 * place, `res` describes the last good sample, and, once there is one
 * (res->rows > 0) and the series closed, that sample's state is written
 * as last-good.csv (not final.csv, which only a run that finished or was
 * stopped writes), to be linearised where the failure began.  A run
 * stopped early writes all its outputs up to the last sample, final.csv at
 * that time included, and returns CL_EBUDGET (so->max_wall or
 * so->max_steps reached) or CL_EINTR (SIGINT or SIGTERM, core/stop.h);
 * both are checked after every output time (sample or frame). */
cl_status cl_simulate(cl_model *m, const cl_integrator_type *type,
                      const cl_integrator_opts *iopts, const cl_sim_opts *so,
                      cl_sim_result *res, cl_error *err);

CL_END_DECLS

#endif
