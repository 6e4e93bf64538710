/* The entry points of the algebraic-multigrid solvers amg and amg-hypre
 * in the plug-in clothode-petsc.so (linalg/plugin.h): plain C types and
 * one callback, so that the plug-in calls nothing of the library.  Looked
 * up as "clp_amg_create", ... by linalg/linsol_amg.c; defined by
 * linalg/linsol_amg_petsc.c.  Each returns 0, or nonzero with msg
 * filled. */
#ifndef CL_LINSOL_AMG_ABI_H
#define CL_LINSOL_AMG_ABI_H

#include <stddef.h>

#include "core/decls.h"
#include "linalg/plugin.h"

CL_BEGIN_DECLS

/* What a setup of the multigrid preconditioner recomputes: the argument
 * `mode` of clp_amg_setup (amg-hypre: CLP_AMG_BUILD at every setup). */
enum {
    /* a new hierarchy: coarsening, interpolation, coarse operators,
     * smoothers */
    CLP_AMG_BUILD,
    /* the kept interpolation P: the coarse operators P^T A P and every
     * smoother recomputed */
    CLP_AMG_GALERKIN,
    /* the coarse operators and their smoothers kept; only the finest
     * level's smoother (the caller's sweep, clp_amg_sweep) on the new A */
    CLP_AMG_SMOOTHER,
    /* a new hierarchy as CLP_AMG_BUILD, each coarser level's Chebyshev
     * bound estimated with CLP_AMG_RECOVER_STEPS Lanczos steps (the recovery
     * from a failed solve) */
    CLP_AMG_RECOVER,
};

/* Lanczos steps of a recovery's eigenvalue estimates (PETSc's default for
 * the other setups: 10). */
#define CLP_AMG_RECOVER_STEPS 40

/* y = A x, the caller's product (ctx: its own). */
typedef void (*clp_amg_mult)(void *ctx, const double *x, double *y);

/* The finest level's smoother of amg, the caller's block Gauss-Seidel
 * sweep (linalg/blockgs.h) on the values of its last setup: forward = 0,
 * the pre-smoother: x = (D + U)^-1 b and r = b - A x; forward = 1, the
 * post-smoother: x <- x + (D + L)^-1 (b - A x) (r unused). */
typedef void (*clp_amg_sweep)(void *ctx, int forward, const double *b,
                              double *x, double *r);

typedef int (*clp_amg_create_fn)(size_t nb, const size_t *rowptr,
                                 const size_t *col, int hypre, long maxit,
                                 clp_amg_mult mult, clp_amg_sweep sweep,
                                 void *ctx, void **handle,
                                 cl_plugin_msg *msg);
typedef int (*clp_amg_setup_fn)(void *handle, const double *ablk,
                                int mode, cl_plugin_msg *msg);
typedef int (*clp_amg_solve_fn)(void *handle, const double *rhs, double *x,
                                double rtol, double atol, long *iters,
                                cl_plugin_msg *msg);
typedef void (*clp_amg_free_fn)(void *handle);

CL_END_DECLS

#endif
