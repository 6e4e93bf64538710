/* The linear solvers for the reduced matrix A = M - a df/dv - b df/dx
 * (docs/integrators.md, 5; linalg/linsol.h), selectable by name with --linsol:
 *
 *   klu         sparse LU by KLU (AMD ordering), symbolic analysis once,
 *               numeric refactorisation at every setup (the default)
 *   pcg         SUNDIALS' PCG, matrix-free product, 3x3 block-Jacobi
 *               preconditioner
 *   pcg-jacobi  the same with the point-Jacobi (diagonal) preconditioner
 *   cholmod     supernodal sparse Cholesky (CHOLMOD), klu when A is not
 *               symmetric positive definite
 *   auto        pcg, or cholmod / klu where pcg costs more or fails
 *   amg         PETSc CG + GAMG (smoothed aggregation), the hierarchy reused
 *               across setups (plug-in clothode-petsc.so)
 *   amg-hypre   PETSc CG + hypre BoomerAMG, nodal coarsening */
#include "linalg/linsol.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"

extern const cl_linsol_type cl_linsol_klu;
extern const cl_linsol_type cl_linsol_pcg;
extern const cl_linsol_type cl_linsol_pcg_jacobi;
extern const cl_linsol_type cl_linsol_cholmod;
extern const cl_linsol_type cl_linsol_auto;
extern const cl_linsol_type cl_linsol_amg;
extern const cl_linsol_type cl_linsol_amg_hypre;

const cl_linsol_type *const cl_linsol_registry[] = {
    &cl_linsol_klu,
    &cl_linsol_pcg,
    &cl_linsol_pcg_jacobi,
    &cl_linsol_cholmod,
    &cl_linsol_auto,
    &cl_linsol_amg,
    &cl_linsol_amg_hypre,
    NULL,
};

const cl_linsol_type *cl_linsol_find(const char *name)
{
    if (!name || !name[0])
        return cl_linsol_registry[0];
    for (size_t i = 0; cl_linsol_registry[i]; i++) {
        if (strcmp(cl_linsol_registry[i]->name, name) == 0)
            return cl_linsol_registry[i];
    }
    return NULL;
}

cl_status cl_linsol_get(const char *who, const char *name, const char *also,
                        const cl_linsol_type **lt, cl_error *err)
{
    char names[256];
    *lt = cl_linsol_find(name);
    if (*lt)
        return CL_OK;
    return cl_error_set(err, CL_EINVAL, "%s: unknown linear solver \"%s\" "
                        "(known: %s%s%s)", who, name, also ? also : "",
                        also ? ", " : "",
                        cl_linsol_names(names, sizeof names));
}

const char *cl_linsol_names(char *buf, size_t len)
{
    size_t used = 0;
    if (len == 0)
        return buf;
    buf[0] = '\0';
    for (size_t i = 0; cl_linsol_registry[i] && used < len; i++) {
        int w = snprintf(buf + used, len - used, "%s%s", i ? ", " : "",
                         cl_linsol_registry[i]->name);
        if (w < 0)
            break;
        used += (size_t)w;
    }
    return buf;
}

#define CL_LINSOL_MAXIT_MIN 1000L

int cl_linsol_maxit(long lin_maxit, size_t n)
{
    long m = lin_maxit;
    if (m == 0)
        m = (long)(2 * n) > CL_LINSOL_MAXIT_MIN ? (long)(2 * n)
                                                : CL_LINSOL_MAXIT_MIN;
    return m < INT_MAX ? (int)m : INT_MAX;
}

cl_status cl_linsol_new_state(const char *name, const cl_bpattern *pat,
                              const cl_linsol_opts *o, size_t size,
                              void **state, cl_error *err)
{
    *state = NULL;
    if (!pat || pat->nb == 0)
        return cl_error_set(err, CL_EINVAL, "%s: empty system (no free "
                            "particles)", name);
    if (!isfinite(o->tol) || o->tol < 0.0 || o->maxit < 0)
        return cl_error_set(err, CL_EINVAL, "%s: lin_tol = %g, lin_maxit = "
                            "%ld: need finite >= 0 (0: defaults)", name,
                            o->tol, o->maxit);
    *state = calloc(1, size);
    if (!*state)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", name);
    return CL_OK;
}

void cl_linsol_report(const cl_linsol_type *lt, const void *ls, cl_stats *s)
{
    lt->stats(ls, s);
    if (!s->linsol[0])
        snprintf(s->linsol, sizeof s->linsol, "%s", lt->name);
}

cl_status cl_linsol_check_weights(const char *name, const double *w,
                                  size_t n, double delta, cl_error *err)
{
    size_t i = 0;
    while (i < n && w[i] > 0.0 && isfinite(w[i]))
        i++;
    if (i < n)
        return cl_error_set(err, CL_EINVAL, "%s: weight %zu is %g: the "
                            "weights must be positive and finite", name, i,
                            w[i]);
    if (!(delta > 0.0) || !isfinite(delta))
        return cl_error_set(err, CL_EINVAL, "%s: delta = %g: must be "
                            "positive and finite", name, delta);
    return CL_OK;
}

cl_status cl_linsol_check_solve(const char *name, bool ready,
                                const double *rhs, size_t n, cl_error *err)
{
    if (!ready)
        return cl_error_set(err, CL_EINVAL, "%s: solve without a successful "
                            "setup", name);
    if (!cl_all_finite(rhs, n))
        return cl_error_set(err, CL_ESOLVER, "%s: right-hand side not "
                            "finite", name);
    return CL_OK;
}
