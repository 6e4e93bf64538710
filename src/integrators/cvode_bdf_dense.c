/* cvode-bdf-dense: SUNDIALS CVODE BDF with a dense difference-quotient
 * Jacobian, the cross-check of cvode-bdf for small systems
 * (docs/integrators.md, 6)
 *
 *   y = (x, v),   x' = v,   v' = M^-1 f(t, x, v),   2n unknowns,
 *
 * variable-order variable-step BDF (orders 1..5), Newton iteration, the
 * linear systems (I - gamma J) dy = r solved by LAPACK's LU with partial
 * pivoting (sunls_lapack.h) on a SUNDenseMatrix, and J approximated
 * by CVODE's own column-by-column difference quotients (no
 * CVodeSetJacFn): 2n RHS evaluations per Jacobian, counted in rhs_evals.
 * Nothing of the system's analytic Jacobian is used, which is what makes
 * it a check.
 *
 * Dense storage and O((2n)^3) factorisations limit it to systems of at
 * most 24 x 24 particles' worth of unknowns (n <= 3 * 24 * 24 = 1728, a
 * 3456 x 3456 matrix of 95 MB); larger systems are refused with
 * CL_EUNSUPPORTED.
 *
 * Options, error capture, blow-up policy and statistics as in
 * sun_adapter.h; the dense solver is wrapped in its counting shell:
 * lin_solves = solve calls, lin_setups = LU factorisations,
 * symbolic_facts = 0. */
#include "integrators/integrator.h"

#include <stdio.h>

#include <cvode/cvode.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "integrators/sun_adapter.h"
#include "integrators/sunls_lapack.h"

#define CL_DENSE_SIDE 24
#define CL_DENSE_MAX_N ((size_t)3 * CL_DENSE_SIDE * CL_DENSE_SIDE)

static cl_status dense_create(const cl_system *sys,
                              const cl_integrator_opts *o, double t0,
                              const double *x0, const double *v0,
                              void **state, cl_error *err)
{
    *state = NULL;
    if (sys->n > CL_DENSE_MAX_N)
        return cl_error_set(err, CL_EUNSUPPORTED,
                            "cvode-bdf-dense: system has %zu unknowns (%zu "
                            "free particles); the dense solver is limited to "
                            "%d x %d particles' worth, n <= %zu: use "
                            "cvode-bdf", sys->n, sys->n / 3, CL_DENSE_SIDE,
                            CL_DENSE_SIDE, CL_DENSE_MAX_N);
    cl_sun *s = NULL;
    cl_status st = cl_sun_cvode_create(sizeof *s, "cvode-bdf-dense", CV_BDF,
                                       false, sys, o, t0, x0, v0, &s, err);
    if (st == CL_OK) {
        sunindextype m = (sunindextype)(2 * sys->n);
        SUNMatrix A = SUNDenseMatrix(m, m, s->ctx);
        st = cl_sun_attach_direct(
            s, A, A ? cl_sunls_lapack_dense(s->y, s->ctx) : NULL, err);
    }
    return cl_sun_finish(s, st, cl_sun_free, state);
}

static void dense_stats(const void *state, cl_stats *out)
{
    cl_sun_stats(state, out);
    snprintf(out->linsol, sizeof out->linsol, "lapack-dense");
}

const cl_integrator_type cl_integrator_cvode_bdf_dense = {
    .name = "cvode-bdf-dense",
    .region = &cl_region_bdf5,
    .doc = "CVODE BDF, Newton, LAPACK dense LU with CVODE's "
           "difference-quotient Jacobian (n <= 24x24 particles; cross-check)",
    .fixed_step = false,
    .takes_max_order = true,
    .takes_linsol = false,
    .dense_jacobian = true,
    .create = dense_create,
    .advance = cl_sun_advance,
    .stats = dense_stats,
    .free = cl_sun_free,
};
