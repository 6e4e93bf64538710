/* The entry points of the petsc-ts integrators in the plug-in
 * clothode-petsc.so (linalg/plugin.h; docs/integrators.md, "PETSc TS"):
 * plain C types and callbacks only, so that the plug-in calls nothing of
 * the library.  Looked up as "clp_ts_create", ... by integrators/petsc_ts.c.
 *
 * A callback returns 0 on success, 1 for a state the step cannot take (a
 * force that is not finite, a particle inside a barrier obstacle: PETSc
 * retries with a smaller step) and -1 for a failure that ends the run; the
 * library keeps the reason on its side. */
#ifndef CL_PETSC_TS_ABI_H
#define CL_PETSC_TS_ABI_H

#include <stddef.h>

#include "core/decls.h"
#include "core/stats.h"
#include "linalg/plugin.h"

CL_BEGIN_DECLS

/* f(t, x, v), n entries each. */
typedef int (*clp_ts_force_fn)(void *ctx, double t, const double *x,
                               const double *v, double *f);
/* df/dx, df/dv as 3x3 blocks, row-major, in the order of the pattern. */
typedef int (*clp_ts_jacobian_fn)(void *ctx, double t, const double *x,
                                  const double *v, double *dfdx,
                                  double *dfdv);

typedef struct {
    const char *name;      /* the integrator, for messages */
    const char *ts_type;   /* PETSc's TSType: "bdf", "alpha2", ... */
    int second_order;      /* 1: I2Function on x (TSALPHA2); 0: IFunction
                            * on y = (x, v) */
    int order;             /* TSBDF's order 1..6, 0 for PETSc's own */
    size_t n;              /* unknowns of x (3 per free particle) */
    const double *mass;    /* n diagonal masses */
    size_t nb, nnzb;       /* block pattern: block rows, stored blocks */
    const size_t *rowptr;  /* nb + 1 */
    const size_t *col;     /* nnzb, sorted within a row */
    const size_t *diag;    /* nb: the diagonal block of each row */
    double t0;
    const double *x0, *v0;
    double dt;             /* fixed step (fixed = 1) or first step */
    int fixed;             /* 1: TSAdapt none, steps of dt */
    double rtol, atol;
    long max_steps;        /* per advance, 0: no limit of ours */
    const char *options;   /* PETSc options ("-ts_adapt_type basic ...") */
    void *ctx;
    clp_ts_force_fn force;
    clp_ts_jacobian_fn jacobian;
} clp_ts_setup;

/* Entry points of the plug-in (the types integrators/petsc_ts.c calls
 * them by).  Each returns 0, or nonzero with msg filled. */
typedef int (*clp_ts_create_fn)(const clp_ts_setup *s, void **ts,
                                cl_plugin_msg *msg);
/* Advance to t_out (steps end on it exactly); x, v receive the state.
 * Nonzero on failure: CLP_TS_BAD_OPTION when the options given turn out
 * bad only once the first step is taken (one that no object read). */
#define CLP_TS_BAD_OPTION 2
typedef int (*clp_ts_advance_fn)(void *ts, double t_out, double *x,
                                 double *v, cl_plugin_msg *msg);
/* The force law changed (tearing): multistep history is dropped. */
typedef int (*clp_ts_restart_fn)(void *ts, cl_plugin_msg *msg);
typedef void (*clp_ts_stats_fn)(const void *ts, cl_stats *st);
typedef void (*clp_ts_free_fn)(void *ts);

CL_END_DECLS

#endif
