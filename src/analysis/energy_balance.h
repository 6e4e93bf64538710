/* Energy behaviour of an integrator (`clothode energy`, README "Using
 * it"): one run from the model's initial state to T, sampled at `samples`
 * evenly spread times (whole steps for fixed-step methods; the blow-up
 * test of analysis/trial.h applies), where
 *
 *   E(t) = kinetic + potential (every conservative term, gravity included),
 *   W(t) = int_0^t P dt, P <= 0 the power of the dissipative terms
 *          (damping, contact damping and friction), by the trapezoidal
 *          rule between samples, plus the energy the contact projections
 *          changed, summed at every projection (cl_model_contact_start),
 *   B(t) = E(t) - E(0) - W(t),
 *
 * B being the energy the integrator made (> 0) or destroyed (< 0) beyond
 * the model's own dissipation: 0 for the exact solution of a model whose
 * pins stay put (moving pins do work on the cloth, which shows in B).  The
 * trapezoidal W is exact to O(sample spacing^2): sample densely when the
 * damping is strong (a fixed-step method can be sampled at every step).
 * Relative figures divide by the scale S = max over the samples of the
 * kinetic energy, |potential - potential(0)| and |W|: energy that moved,
 * whatever the potential's origin (|E(0)| would count the height of the
 * pins above it). */
#ifndef CL_ENERGY_BALANCE_H
#define CL_ENERGY_BALANCE_H

#include <stdbool.h>
#include <stdio.h>

#include "core/decls.h"
#include "integrators/integrator.h"
#include "system/model.h"

CL_BEGIN_DECLS

typedef struct {
    double t, kinetic, potential, total, dissipated, balance;
    double power;         /* P at t */
} cl_ebal_sample;

typedef struct {
    const cl_integrator_type *type;
    cl_status rc;         /* how the run ended (CL_OK, or a failure: the
                           * samples up to it are kept) ... */
    cl_error why;         /* ... and why */
    size_t n;             /* samples taken, t = 0 included */
    cl_ebal_sample *s;
    double scale;         /* S */
    double balance_max;   /* max |B| */
    cl_stats stats;
    const char *label;    /* how rows name the method (type->name) */
} cl_ebal_result;

/* Whether the run can be made: CL_EINVAL for samples < 1 or a T that is
 * not a whole number of fixed steps; CL_EUNSUPPORTED for a model that
 * tears, and for an adaptive method on a model with contact projections
 * (CVODE projects inside its steps, whose states may be rejected). */
cl_status cl_ebal_check(cl_model *m, const cl_integrator_type *type,
                        const cl_integrator_opts *io, double T, long samples,
                        cl_error *err);

/* The run: cl_ebal_check's refusals are returned; a failing run is
 * recorded in r (r->rc), not returned. */
cl_status cl_ebal_run(cl_model *m, const cl_integrator_type *type,
                      const cl_integrator_opts *io, double T, long samples,
                      double max_stretch, cl_ebal_result *r, cl_error *err);
void cl_ebal_free(cl_ebal_result *r);

/* One more sample of r (r->s holding cap): energies e at t (kinetic,
 * potential, total, power_diss, contact_work), W by the trapezoidal rule
 * from the previous sample (*trapz, 0 before the first); CL_EINVAL when r
 * is full. */
cl_status cl_ebal_add(cl_ebal_result *r, size_t cap, double *trapz,
                      double t, const cl_energy *e);

/* integrator,t,kinetic,potential,total,dissipated,balance rows, header
 * first when `header`. */
void cl_ebal_write_rows(FILE *fp, const cl_ebal_result *r, bool header);

CL_END_DECLS

#endif
