/* semi-be: Baraff-Witkin's linearised backward Euler (docs/integrators.md,
 * 3.1; Baraff & Witkin 1998, section 2.3), fixed step h = opts->dt:
 *
 *     (M - h df/dv - h^2 df/dx) dv = h (f_n + h df/dx v_n),
 *     v_{n+1} = v_n + dv,    x_{n+1} = x_n + h v_{n+1},
 *
 * with f_n = f(t_n, x_n, v_n) and both Jacobians at (t_n, x_n, v_n),
 * t_n = t0 + n h (pinned particles are placed at t_n by the system).  This
 * is backward Euler  M (v_{n+1} - v_n) = h f(x_{n+1}, v_{n+1}),
 * x_{n+1} = x_n + h v_{n+1}  with f linearised about (x_n, v_n): one linear
 * solve per step, no Newton iteration.  First order: the linearisation
 * error of f, O(|dx|^2 + |dv|^2) = O(h^2), and its time lag (f at t_n
 * instead of t_{n+1}), O(h), enter v multiplied by h, i.e. O(h^3) and
 * O(h^2) per step, within backward Euler's own O(h^2) local error.  For
 * forces linear in (x, v) and independent of t it is backward Euler
 * exactly: unconditionally stable, strongly damping.
 *
 * The reduced matrix is solved by the linear solver named opts->linsol
 * (linalg/linsol.h: klu, pcg, pcg-jacobi; default klu); shared machinery in
 * integrators/semi_common.h.  Statistics: steps, rhs_evals = jac_evals =
 * one force + Jacobian evaluation per step, the solver's lin_setups and
 * lin_solves (one each per step; under contact constraints one each per
 * pass, docs/integrators.md 3.4), lin_iters (Krylov), symbolic_facts (KLU:
 * 1); no nonlinear iterations. */
#include "integrators/semi_common.h"

#include <stdlib.h>

static void sbe_free(void *state)
{
    cl_semi *s = state;
    if (!s)
        return;
    cl_semi_release(s);
    free(s);
}

static cl_status sbe_create(const cl_system *sys, const cl_integrator_opts *o,
                            double t0, const double *x0, const double *v0,
                            void **state, cl_error *err)
{
    *state = NULL;
    cl_semi *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "semi-be: out of memory");
    cl_status st = cl_semi_init(s, "semi-be", sys, o, t0, x0, v0, err);
    if (st != CL_OK) {
        free(s);
        return st;
    }
    *state = s;
    return CL_OK;
}

static cl_status sbe_step(void *state, cl_error *err)
{
    return cl_semi_be_step(state, err);
}

static cl_status sbe_advance(void *state, double t_out, double *x, double *v,
                             cl_error *err)
{
    return cl_semi_advance(state, state, sbe_step, t_out, x, v, err);
}

static void sbe_stats(const void *state, cl_stats *out)
{
    cl_semi_stats(state, out);
}

const cl_integrator_type cl_integrator_semi_be = {
    .name = "semi-be",
    .region = &cl_region_be,
    .doc = "Baraff-Witkin linearised backward Euler, one linear solve per "
           "step, fixed step dt",
    .fixed_step = true,
    .takes_linsol = true,
    .takes_lin_tol = true,
    .create = sbe_create,
    .advance = sbe_advance,
    .stats = sbe_stats,
    .free = sbe_free,
};
