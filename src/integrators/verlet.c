/* verlet: position (Stoermer) Verlet with velocity damping, as in the
 * Verlet-and-PBD report (docs/integrators.md, 2):
 *
 *   x_{k+1} = x_k + (1 - d) (x_k - x_{k-1}) + h^2 M^-1 f(t_k, x_k, v_k)
 *
 * ("Pnext = (2 - DAMPING) Pnow - (1 - DAMPING) Pold + a dt^2" in the
 * Verlet-and-PBD report's code), d = opts->vdamp in [0, 1) (0: plain
 * Verlet), h = opts->dt, t_k = t0 + k h.  The state of the method is
 * (x_k, x_{k-1}); the velocity is not part of it and is estimated, as the
 * report's code does for its spring friction, by the backward difference
 *
 *   v_{k+1} = (x_{k+1} - x_k) / h,
 *
 * which is both the velocity handed to velocity-dependent forces in the
 * next step and the output velocity.  Equivalently v_{k+1} = (1 - d) v_k +
 * h M^-1 f_k: d removes the fraction d of the velocity every step (a drag
 * of d/h per unit time; the Verlet-and-PBD report: Cdamp = 1 - dt Cdrag).
 *
 * First step from (x0, v0): the consistent start
 *
 *   x_{-1} = x0 - h v0 + h^2/2 M^-1 f(t0, x0, v0)
 *
 * (Taylor to O(h^3)), so that x_1 = x0 + h v0 + h^2/2 a0 when d = 0; the
 * force of the first step is evaluated once and used for both.
 *
 * Accuracy: with forces that do not depend on v and d = 0, positions are
 * second order; the output velocity is first order (v_k = v(t_k) -
 * h/2 a(t_k) + O(h^2)).  With velocity-dependent forces (damping terms)
 * this O(h) velocity error enters the force and the positions drop to
 * first order too; d > 0 is a first-order perturbation by design.  For
 * conservative forces and d = 0 the method is symplectic (bounded energy
 * error, no drift, for h below ~2/omega_max).  One force evaluation per
 * step (rhs_evals = steps).  State, output times and the finite-state
 * check: fixed_step.c. */
#include "integrators/verlet.h"

#include <math.h>

/* The positions x_{k+1} of the step onto the system's constraints at the
 * time t_{k+1}. */
static cl_status verlet_project(cl_fixed *s, double t, double *xn,
                                cl_error *err)
{
    const cl_system *sys = s->sys;
    cl_status st = sys->project(sys->data, t, xn);
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: constraint projection failed (%s) "
                            "at t = %.9g (step %ld, dt = %g)",
                            s->method->name, cl_status_name(st), t,
                            s->done + 1, s->dt);
    return CL_OK;
}

/* xo = x - h v + h^2/2 a, a = f M^-1 (im: the inverse masses): the
 * consistent start. */
static void verlet_start(size_t n, double h, const double *restrict x,
                         const double *restrict v, const double *restrict f,
                         const double *restrict im, double *restrict xo)
{
#pragma omp simd
    for (size_t i = 0; i < n; i++)
        xo[i] = x[i] - h * v[i] + 0.5 * h * h * (f[i] * im[i]);
}

/* x_{k+1} = x + keep (x - xo) + h^2 a, one component (a = f im). */
static inline double predicted(double keep, double h, double x, double xo,
                               double f, double im)
{
    return x + keep * (x - xo) + h * h * (f * im);
}

/* Component i of v = (xn - x)/h, xo = x, x = xn. */
static inline void shift(size_t i, double h, double xn, double *restrict x,
                         double *restrict v, double *restrict xo)
{
    v[i] = (xn - x[i]) / h;
    xo[i] = x[i];
    x[i] = xn;
}

/* xn = x + keep (x - xo) + h^2 a. */
static void verlet_predict(size_t n, double keep, double h,
                           const double *restrict x,
                           const double *restrict xo,
                           const double *restrict f,
                           const double *restrict im, double *restrict xn)
{
#pragma omp simd
    for (size_t i = 0; i < n; i++)
        xn[i] = predicted(keep, h, x[i], xo[i], f[i], im[i]);
}

/* v = (xn - x)/h, xo = x, x = xn. */
static void verlet_shift(size_t n, double h, double *restrict x,
                         double *restrict v, double *restrict xo,
                         const double *restrict xn)
{
#pragma omp simd
    for (size_t i = 0; i < n; i++)
        shift(i, h, xn[i], x, v, xo);
}

/* verlet_predict and verlet_shift in one pass (no projection between). */
static void verlet_both(size_t n, double keep, double h, double *restrict x,
                        double *restrict v, double *restrict xo,
                        const double *restrict f, const double *restrict im)
{
#pragma omp simd
    for (size_t i = 0; i < n; i++)
        shift(i, h, predicted(keep, h, x[i], xo[i], f[i], im[i]), x, v, xo);
}

/* w[0]: the force f, w[1]: x_{k-1}, w[2]: x_{k+1} (n each) */
cl_status cl_verlet_step(cl_fixed *s, double t, double h, bool project,
                         cl_error *err)
{
    double *f = s->w[0], *xp = s->w[1], *xn = s->w[2], keep = 1.0 - s->param;
    cl_status st = cl_fixed_force(s, t, s->x, s->v, f, err);
    if (st != CL_OK)
        return st;
    if (s->done == 0)
        verlet_start(s->n, h, s->x, s->v, f, s->inv_mass, xp);
    if (!project) {
        verlet_both(s->n, keep, h, s->x, s->v, xp, f, s->inv_mass);
        return CL_OK;
    }
    verlet_predict(s->n, keep, h, s->x, xp, f, s->inv_mass, xn);
    if ((st = verlet_project(s, t + h, xn, err)) != CL_OK)
        return st;
    verlet_shift(s->n, h, s->x, s->v, xp, xn);
    return CL_OK;
}

static cl_status verlet_step(cl_fixed *s, double t, double h, cl_error *err)
{
    return cl_verlet_step(s, t, h, false, err);
}

cl_status cl_verlet_setup(cl_fixed *s, const cl_integrator_opts *o,
                          cl_error *err)
{
    if (!isfinite(o->vdamp) || o->vdamp < 0.0 || !(o->vdamp < 1.0))
        return cl_error_set(err, CL_EINVAL,
                            "%s: velocity damping vdamp = %g, must lie "
                            "in [0, 1)", s->method->name, o->vdamp);
    s->param = o->vdamp;
    return CL_OK;
}

CL_FIXED_INTEGRATOR(cl_integrator_verlet, "verlet",
                    &cl_region_symplectic,
                    "position Verlet with velocity damping vdamp "
                    "(the Verlet-and-PBD report), fixed step dt",
                    3, cl_verlet_setup, verlet_step, true);
