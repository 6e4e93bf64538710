/* The static equilibrium of a cloth by pseudo-transient continuation (see
 * equilibrium.h). */
#include "analysis/equilibrium.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_linalg.h>

#include "analysis/spectrum.h"

#define EQ_TAU0 1e-3      /* s: the first pseudo time step */
#define EQ_GROW 4.0       /* tau's factor after a step, up or down */
#define EQ_WORSE 10.0     /* a step that raises the residual this much is
                           * undone */

typedef struct {
    size_t n, nval;
    double *f, *dfdx, *dfdv, *v, *A, *dx, *xtry;
    gsl_permutation *perm;
} eq_work;

static void eq_free(eq_work *w)
{
    free(w->f);
    free(w->dfdx);
    free(w->dfdv);
    free(w->v);
    free(w->A);
    free(w->dx);
    free(w->xtry);
    if (w->perm)
        gsl_permutation_free(w->perm);
}

static cl_status eq_alloc(const cl_system *sys, eq_work *w, cl_error *err)
{
    w->n = sys->n;
    w->nval = 9 * sys->pattern->nnzb;
    w->f = malloc(w->n * sizeof *w->f);
    w->dfdx = malloc((w->nval + 1) * sizeof *w->dfdx);
    w->dfdv = malloc((w->nval + 1) * sizeof *w->dfdv);
    w->v = calloc(w->n, sizeof *w->v);
    w->A = malloc(w->n * w->n * sizeof *w->A);
    w->dx = malloc(w->n * sizeof *w->dx);
    w->xtry = malloc(w->n * sizeof *w->xtry);
    w->perm = gsl_permutation_alloc(w->n);
    if (!w->f || !w->dfdx || !w->dfdv || !w->v || !w->A || !w->dx ||
        !w->xtry || !w->perm)
        return cl_error_set(err, CL_ENOMEM, "equilibrium: out of memory "
                            "(%zu unknowns)", w->n);
    return CL_OK;
}

/* res[0] = max |M^-1 f(t, x, 0)| (the test), res[1] = |M^-1/2 f|_2 (the
 * steps' measure), f into w->f. */
static cl_status eq_residual(const cl_system *sys, double t, const double *x,
                             eq_work *w, double res[2], cl_error *err)
{
    cl_status rc = sys->force(sys->data, t, x, w->v, w->f);
    if (rc)
        return cl_error_set(err, rc, "equilibrium: force failed");
    res[0] = res[1] = 0.0;
    for (size_t i = 0; i < w->n; i++) {
        res[0] = fmax(res[0], fabs(w->f[i]) / sys->mass[i]);
        res[1] += w->f[i] * w->f[i] / sys->mass[i];
    }
    res[1] = sqrt(res[1]);
    for (int k = 0; k < 2; k++)
        if (!isfinite(res[k]))
            res[k] = INFINITY;
    return CL_OK;
}

/* w->dx = (M / tau^2 - K)^-1 f, K = df/dx at x (f from w->f kept). */
static cl_status eq_step(const cl_system *sys, double t, const double *x,
                         double tau, eq_work *w, cl_error *err)
{
    const cl_bpattern *p = sys->pattern;
    size_t n = w->n;
    memcpy(w->dx, w->f, n * sizeof *w->dx);
    cl_status rc = sys->jacobian(sys->data, t, x, w->v, w->f, w->dfdx,
                                 w->dfdv);
    if (rc)
        return cl_error_set(err, rc, "equilibrium: Jacobian failed");
    memset(w->A, 0, n * n * sizeof *w->A);
    for (size_t i = 0; i < n; i++)
        w->A[i * n + i] = sys->mass[i] / (tau * tau);
    for (size_t bi = 0; bi < p->nb; bi++)
        for (size_t k = p->rowptr[bi]; k < p->rowptr[bi + 1]; k++)
            for (size_t r = 0; r < 3; r++)
                for (size_t c = 0; c < 3; c++)
                    w->A[(3 * bi + r) * n + 3 * p->col[k] + c] -=
                        w->dfdx[9 * k + 3 * r + c];
    gsl_matrix_view A = gsl_matrix_view_array(w->A, n, n);
    gsl_vector_view b = gsl_vector_view_array(w->dx, n);
    int sign, grc = gsl_linalg_LU_decomp(&A.matrix, w->perm, &sign);
    if (!grc)
        grc = gsl_linalg_LU_svx(&A.matrix, w->perm, &b.vector);
    return grc ? cl_error_set(err, CL_ESOLVER, "equilibrium: singular "
                              "matrix M/tau^2 - K at tau = %g s (GSL %d)",
                              tau, grc)
               : CL_OK;
}

cl_status cl_equilibrium_find(cl_model *m, double t, double *x, double tol,
                              int max_steps, cl_equilibrium_info *info,
                              cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    eq_work w = {0};
    double tau = EQ_TAU0, res[2] = {INFINITY, INFINITY};
    double res_try[2] = {INFINITY, INFINITY};
    *info = (cl_equilibrium_info){0};
    if (sys->n > CL_SPECTRUM_MAX_N)
        return cl_error_set(err, CL_EUNSUPPORTED, "equilibrium: %zu "
                            "unknowns, at most %d (dense LU)", sys->n,
                            CL_SPECTRUM_MAX_N);
    cl_status rc = eq_alloc(sys, &w, err);
    if (!rc)
        rc = eq_residual(sys, t, x, &w, res, err);
    while (!rc && !(res[0] <= tol) && info->steps < max_steps) {
        info->steps++;
        rc = eq_step(sys, t, x, tau, &w, err);
        for (size_t i = 0; !rc && i < w.n; i++)
            w.xtry[i] = x[i] + w.dx[i];
        if (!rc)
            rc = eq_residual(sys, t, w.xtry, &w, res_try, err);
        if (!rc && res_try[1] <= EQ_WORSE * res[1]) {
            memcpy(x, w.xtry, w.n * sizeof *x);
            tau *= res_try[1] <= res[1] ? EQ_GROW : 1.0;
            res[0] = res_try[0];
            res[1] = res_try[1];
        } else if (!rc) {
            tau /= EQ_GROW;
            rc = eq_residual(sys, t, x, &w, res, err);
        }
    }
    info->residual = res[0];
    if (!rc && !(res[0] <= tol))
        rc = cl_error_set(err, CL_ESOLVER, "equilibrium: max |M^-1 f| = %g "
                          "m/s^2 after %d steps (at most %g asked)", res[0],
                          info->steps, tol);
    eq_free(&w);
    return rc;
}
