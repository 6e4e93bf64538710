/* The numerical damping study (`clothode damping`, README "Using it";
 * docs/integrators.md 4.3): how much of an undamped oscillation each
 * implicit fixed-step integrator destroys per step, against w h.
 *
 * The integrators studied by default are the registry's implicit
 * fixed-step ones, chosen by their table, not their names: fixed_step and
 * a CL_REGION_SECTOR stability region (cl_numdamp_selects).  The problem
 * is a linear oscillator whose motion is one mode, spring2 (one particle
 * on a linear spring, w = sqrt(ks/m) = 10 rad/s) or alike: w is the
 * fastest mode of the linearised problem at its initial state
 * (analysis/spectrum.h, w_max), and for each w h of the list the
 * integrator runs `steps` steps of h = (w h)/w from the initial state,
 * recording the energy E_k = kinetic + potential after every step.
 *
 * Measured: the amplitude ratio per step r = exp(s/2), s the least-squares
 * slope of ln E_k against k over the last three quarters of the steps
 * whose E_k > 1e-16 E_0 (all of them if fewer than 4: a method that
 * annihilates the oscillation in a few steps; below 1e-16 the Newton
 * tolerance and round-off decide the energy); the transient of a
 * multistep or multi-stage start is left out, and the slope over many
 * steps is the spectral radius of the method's step, to which the
 * theory is compared: the stability region's amplification (region.h;
 * NAN where the region gives none).  Where the energy reaches the floor in
 * a few steps and the method has a second root of about the first's size
 * (BDF2 at w h >= 50: 0.064 beside 0.078 at w h = 100), the fit is not yet
 * the spectral radius; the spread of the ratios fitted over the window's
 * two halves says so (0 for a one-step method, whose energy falls by the
 * same factor every step).  The loss per period of the
 * oscillation, 1 - r^(2 pi / (w h)), is what a user sees. */
#ifndef CL_NUMDAMP_H
#define CL_NUMDAMP_H

#include <stdbool.h>
#include <stdio.h>

#include "analysis/equilibrium.h"
#include "core/decls.h"
#include "integrators/integrator.h"
#include "system/model.h"

CL_BEGIN_DECLS

#define CL_NUMDAMP_MAX_WH 64

typedef struct {
    double wh, h;
    double measured;      /* r, amplitude ratio per step */
    double theory;        /* the region's amplification, NAN if none */
    double loss_period;   /* 1 - r^(2 pi / wh) */
    long fitted;          /* steps in the fit */
    double spread;        /* |r of the fit's later half - r of its earlier
                           * half| / r (NaN below 4 steps) */
    cl_status rc;         /* CL_OK, or how the run failed ... */
    cl_error why;         /* ... and why (measured NAN) */
} cl_numdamp_point;

typedef struct {
    const cl_integrator_type *type;
    const char *label;    /* how rows name the method (type->name) */
    double w;             /* the mode's w (rad/s) */
    int n;
    cl_numdamp_point p[CL_NUMDAMP_MAX_WH];
} cl_numdamp_result;

/* Whether the study takes `type` by default: an implicit fixed-step
 * integrator (fixed_step and a CL_REGION_SECTOR region). */
bool cl_numdamp_selects(const cl_integrator_type *type);

/* w of m (w_max of its spectrum at the initial state): CL_EUNSUPPORTED
 * for a model that tears or is too large for the dense spectrum,
 * CL_EINVAL when it has no oscillating mode. */
cl_status cl_numdamp_frequency(cl_model *m, double *w, cl_error *err);

/* CL_EUNSUPPORTED, saying what to change, for a model the study's theory
 * does not describe: one with obstacles (one-sided, nonlinear contact) or
 * with forces that dissipate (power at the initial positions moving with
 * v = x).  cl_numdamp_frequency and
 * cl_numdamp_modes_init refuse such a model. */
cl_status cl_numdamp_undamped(cl_model *m, cl_error *err);

/* The runs of `type` at the n values wh[] (n <= CL_NUMDAMP_MAX_WH),
 * `steps` >= 4 steps each: a failing run is recorded in its point (rc),
 * not returned. */
cl_status cl_numdamp_run(cl_model *m, const cl_integrator_type *type,
                         const cl_integrator_opts *io, double w,
                         const double *wh, int n, long steps,
                         cl_numdamp_result *r, cl_error *err);

/* integrator,wh,h,measured,theory,loss_period,fitted,spread,status rows
 * (status ok or the failure's class), the header first when `header`. */
void cl_numdamp_write_rows(FILE *fp, const cl_numdamp_result *r,
                           bool header);

/* ---- on the cloth: energy per eigenmode (numdamp_modes.c) ------------
 *
 * The problem's initial state x0 must be at rest (max |M^-1 f(0, x0, 0)|
 * <= 1e-8 m/s^2: e.g. hang-smooth without gravity).  Its modes at x0
 * (cl_spectrum_modes: mu_k, phi_k) define the modal coordinates q_k =
 * phi_k . M^1/2 (x - x0), p_k = phi_k . M^1/2 v and the modal energies
 * E_k = (p_k^2 + mu_k q_k^2)/2, which a linear motion keeps mode by mode.
 * Every oscillating mode (mu_k > 1e-6 mu_max) is given the same energy at
 * t = 0: v0 = s M^-1/2 sum_k phi_k, s such that max |v0| = `speed` (small,
 * so that the motion stays linear).  Each integrator runs from (x0, v0)
 * to T in steps of dt; its ratio E_k(T)/E_k(0) per mode is its numerical
 * damping of that mode, against the theory amplification(w_k dt)^(2 T /
 * dt) (NAN without a formula).
 *
 * With `equilibrium`, x0 is first moved to the static equilibrium at
 * t = 0 (analysis/equilibrium.h; max |M^-1 f| <= 1e-9 m/s^2): e.g. the
 * hanging cloth under gravity, whose tension gives the out-of-plane
 * (bending, wrinkle) modes a stiffness they lack on the flat cloth at
 * rest.  Each mode is classed by its normal fraction: the part of its
 * mass-weighted squared amplitude sum_i phi_ki^2 along the normal of the
 * plane that fits x0 best (least squares: the covariance's least
 * eigenvector); above 1/2 it is out-of-plane. */
typedef struct {
    size_t n;             /* unknowns, = modes */
    double *mu, *phi;     /* the modes at x0 */
    double *sqm;          /* sqrt of the masses */
    double *x0, *v0;      /* the start */
    size_t nosc;          /* the oscillating modes: the last nosc */
    double *normal;       /* n: each mode's normal fraction */
    size_t nneg;          /* modes with mu_k < -1e-6 mu_max (buckling) */
    cl_equilibrium_info eq; /* the equilibrium's steps (0: not sought) */
} cl_numdamp_modes;

typedef struct {
    const cl_integrator_type *type;
    const char *label;
    double dt, T;
    size_t nosc;
    double *w, *ratio, *theory; /* per oscillating mode, ascending w */
    double *normal;       /* per oscillating mode, its normal fraction */
    cl_status rc;         /* CL_OK, or how the run failed ... */
    cl_error why;
} cl_numdamp_modal;

cl_status cl_numdamp_modes_init(cl_model *m, double speed,
                                bool equilibrium, cl_numdamp_modes *b,
                                cl_error *err);
void cl_numdamp_modes_free(cl_numdamp_modes *b);

/* One integrator's run: a failing run is recorded in r (rc), not
 * returned; CL_EINVAL when T is not a whole number of steps dt. */
cl_status cl_numdamp_modal_run(cl_model *m, const cl_numdamp_modes *b,
                               const cl_integrator_type *type,
                               const cl_integrator_opts *io, double dt,
                               double T, cl_numdamp_modal *r, cl_error *err);
void cl_numdamp_modal_free(cl_numdamp_modal *r);

/* integrator,mode,w,wh,ratio,theory,normal,status rows, header first. */
void cl_numdamp_modal_rows(FILE *fp, const cl_numdamp_modal *r, bool header);

CL_END_DECLS

#endif
