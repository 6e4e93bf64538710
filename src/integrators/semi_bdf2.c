/* semi-bdf2: Choi-Ko's semi-implicit BDF2 (Jiao, section 4.9, eq. 15;
 * docs/integrators.md, 3.2), fixed step h = opts->dt.  With y = x^{n+1} - x^n,
 * d = x^n - x^{n-1}, K = df/dx, D = df/dv:
 *
 *   A y = M [d/3 + (h/9)(8 v^n - 2 v^{n-1})] + (4h^2/9)(f - D v^n)
 *         - (2h/9) D d,                A = M - (2h/3) D - (4h^2/9) K,
 *   x^{n+1} = x^n + y,   v^{n+1} = (3 x^{n+1} - 4 x^n + x^{n-1}) / (2h)
 *                                = (3 y - d) / (2h),
 *
 * f, K, D evaluated at (t_{n+1}, x^n, v^n).  The first step is the semi-be
 * step (integrators/semi_common.h).  Computed as written: the right-hand
 * side needs one block product D (d + 2h v^n), since
 * -(4h^2/9) D v^n - (2h/9) D d = -(2h/9) D (d + 2h v^n).
 *
 * Derivation (checked; Jiao's printed eq. 15 is correct).  Fully
 * implicit BDF2 for x' = v, M v' = f(t, x, v) reads
 *   (B1)  x^{n+1} - 4/3 x^n + 1/3 x^{n-1} = 2h/3 v^{n+1},
 *   (B2)  M (v^{n+1} - 4/3 v^n + 1/3 v^{n-1}) = 2h/3 f(t_{n+1}, x^{n+1},
 *                                                        v^{n+1}).
 * (B1) gives v^{n+1} = (3y - d)/(2h).  Put it into (B2) and multiply by
 * 2h/3: the BDF2 step is the root of
 *   G(y) = M [y - d/3 - (h/9)(8 v^n - 2 v^{n-1})]
 *          - (4h^2/9) f(t_{n+1}, x^n + y, (3y - d)/(2h)),
 *   G'(y) = M - (4h^2/9) K - (4h^2/9)(3/(2h)) D = A.
 * Linearising f about (x^n, v^n),
 *   f(x^n + y, v^{n+1}) ~ f + K y + D (v^{n+1} - v^n)
 *                       = f - D v^n - D d/(2h) + (K + (3/(2h)) D) y,
 * turns G(y) = 0 into A y = M [...] + (4h^2/9)(f - D v^n) - (2h/9) D d:
 * Jiao's eq. (15) multiplied through by M, term by term.
 *
 * The claim that eq. 15 is exactly the first Newton iterate of fully
 * implicit BDF2 started from x^{n+1} = x^n (docs/integrators.md, 3.2)
 * holds under a condition.  That iterate solves A_0 y = -G(0), with f and
 * A_0 taken at the start point (x^n, v_0), v_0 = -d/(2h) (what (B1)
 * implies for x^{n+1} = x^n; about -v^n/2, not v^n).  Every force of this
 * project is affine in v, f = g(x) + D(x) v, so
 * f(x^n, v_0) = f - D v^n - D d/(2h): the right-hand sides agree exactly,
 * and so does D.  K = g'(x) + (dD/dx) v does depend on v when D depends on
 * x (axial damping, Baraff-Witkin damping): then eq. 15 (K at v^n) and the
 * Newton iterate (K at v_0) differ.  So: exact equality
 * when df/dx does not depend on v (Choi-Ko Type1/Type2, isotropic pair
 * damping of Jiao's eq. 14, springs, gravity, linear drag); otherwise eq. 15
 * is a Newton step with K at the current velocity, and it is the better
 * one: linearised about (x^n, v^n) the neglected terms are
 * O(|y|^2 + |y| |v^{n+1} - v^n| + |v^{n+1} - v^n|^2) = O(h^2) in f,
 * O(h^4) in y, while the true first Newton iterate from v_0 neglects
 * (dD/dx) y (v^{n+1} - v_0) = O(h) in f, O(h^3) in y per step, which for
 * this second-order (x-only) two-step recursion costs an order (local
 * perturbations of y must be O(h^4) for global order 2).  Checked on
 * m x'' = -k x - c0 (1 + x^2) x' (D depends on x): eq. 15 converges with
 * order 2.00, the first Newton iterate from v_0 with order 1.00.
 *
 * Difference from Jiao: f, K, D are taken at t_{n+1} (Jiao: "at time step
 * n"; the forces there do not depend on t, so the two coincide there).
 * With moving pins f depends on t, and evaluating at t_n would perturb y by
 * (4h^2/9) h df/dt = O(h^3) per step: first order (observed: 1.00 on the
 * oscillator above pulled by -k (x - w t)).  f(t_{n+1}, ., .) linearised
 * about (x^n, v^n) keeps second order (tested: spring2 with its pin moving
 * at constant velocity).
 *
 * Start: step 1 by semi-be from (x^0, v^0); its O(h^2) errors in x^1 and
 * v^1 enter BDF2's velocity and position invariants only as O(h^2)
 * offsets, so the method stays second order.  Linear forces and t-free:
 * eq. 15 is BDF2 exactly (A-stable, L-stable, damps high frequencies).
 * Statistics as semi-be: one force/Jacobian evaluation, one setup and one
 * solve per step. */
#include "integrators/semi_common.h"

#include <stdlib.h>
#include <string.h>

#include "linalg/reduced.h"

typedef struct {
    cl_semi base;
    double *xprev, *vprev;   /* x^{n-1}, v^{n-1} */
} cl_sbdf2;

static void sbdf2_free(void *state)
{
    cl_sbdf2 *s = state;
    if (!s)
        return;
    cl_semi_release(&s->base);
    free(s->xprev);
    free(s->vprev);
    free(s);
}

static cl_status sbdf2_create(const cl_system *sys,
                              const cl_integrator_opts *o, double t0,
                              const double *x0, const double *v0,
                              void **state, cl_error *err)
{
    *state = NULL;
    cl_sbdf2 *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "semi-bdf2: out of memory");
    cl_status st = cl_semi_init(&s->base, "semi-bdf2", sys, o, t0, x0, v0,
                                err);
    if (st != CL_OK) {
        free(s);
        return st;
    }
    s->xprev = calloc(sys->n, sizeof *s->xprev);
    s->vprev = calloc(sys->n, sizeof *s->vprev);
    if (!s->xprev || !s->vprev) {
        sbdf2_free(s);
        return cl_error_set(err, CL_ENOMEM, "semi-bdf2: out of memory");
    }
    *state = s;
    return CL_OK;
}

/* rhs = M [d/3 + (h/9)(8 v - 2 vprev)] + (4h^2/9) f - (2h/9) D (d + 2h v) */
static void sbdf2_rhs(void *state)
{
    cl_sbdf2 *s = state;
    cl_semi *b = &s->base;
    const double *m = b->sys->mass;
    double h = b->h;
    for (size_t i = 0; i < b->n; i++)
        b->work[i] = (b->x[i] - s->xprev[i]) + 2.0 * h * b->v[i];
    cl_bmatvec_threads(b->sys->pattern, b->dfdv, b->work, b->sol,
                       b->sys->threads);
    for (size_t i = 0; i < b->n; i++) {
        double d = b->x[i] - s->xprev[i];
        b->rhs[i] = m[i] * (d / 3.0 + h / 9.0 * (8.0 * b->v[i] -
                                                  2.0 * s->vprev[i])) +
                    4.0 * h * h / 9.0 * b->f[i] - 2.0 * h / 9.0 * b->sol[i];
    }
}

/* Under constraints (docs/integrators.md, 3.4) the unknown y's
 * constrained part is semi-be's position change, h (I - S) v + h z + y_c
 * (y_c the position correction), a constrained particle's velocity
 * after the step is semi-be's, (I - S)(v + z), in its constrained part,
 * and its history there that of a uniform motion (cl_semi_hold_history;
 * after the first step too). */
static cl_status sbdf2_bdf_step(cl_sbdf2 *s, cl_error *err)
{
    cl_semi *b = &s->base;
    double h = b->h;
    const double coef[3] = {h, h, 1.0};
    cl_status st = cl_semi_linearise(b, b->t0 + (double)(b->done + 1) * h,
                                     err);
    if (st == CL_OK)
        st = cl_semi_solve_constrained(b, b->t0 + (double)b->done * h, s,
                                       sbdf2_rhs, 2.0 * h / 3.0,
                                       4.0 * h * h / 9.0, coef, err);
    if (st != CL_OK)
        return st;
    double a = cl_semi_filter(b, b->sol); /* 1 without barriers */
    for (size_t i = 0; i < b->n; i++) {
        double d = b->x[i] - s->xprev[i], y = a * b->sol[i];
        s->xprev[i] = b->x[i];
        s->vprev[i] = b->v[i];
        b->x[i] += y;
        b->v[i] = (3.0 * y - d) / (2.0 * h);
    }
    cl_semi_hold_velocity(b, s->vprev);
    cl_semi_hold_history(b, s->xprev, s->vprev);
    return CL_OK;
}

static cl_status sbdf2_step(void *state, cl_error *err)
{
    cl_sbdf2 *s = state;
    cl_semi *b = &s->base;
    if (b->done > 0)
        return sbdf2_bdf_step(s, err);
    memcpy(s->xprev, b->x, b->n * sizeof *s->xprev);
    memcpy(s->vprev, b->v, b->n * sizeof *s->vprev);
    cl_status st = cl_semi_be_step(b, err);
    if (st == CL_OK)
        cl_semi_hold_history(b, s->xprev, s->vprev);
    return st;
}

static cl_status sbdf2_advance(void *state, double t_out, double *x,
                               double *v, cl_error *err)
{
    cl_sbdf2 *s = state;
    return cl_semi_advance(&s->base, s, sbdf2_step, t_out, x, v, err);
}

static void sbdf2_stats(const void *state, cl_stats *out)
{
    const cl_sbdf2 *s = state;
    cl_semi_stats(&s->base, out);
}

const cl_integrator_type cl_integrator_semi_bdf2 = {
    .name = "semi-bdf2",
    .region = &cl_region_bdf2,
    .doc = "Choi-Ko semi-implicit BDF2 (Jiao, eq. 15), one linear solve per "
           "step, first step semi-be, fixed step dt",
    .fixed_step = true,
    .takes_linsol = true,
    .takes_lin_tol = true,
    .create = sbdf2_create,
    .advance = sbdf2_advance,
    .stats = sbdf2_stats,
    .free = sbdf2_free,
};
