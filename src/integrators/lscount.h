/* A counting SUNLinearSolver: a thin shell around a direct SUNDIALS linear
 * solver (dense, KLU) that forwards every operation and counts
 *
 *   solves   - solve calls (one per Newton iteration in CVODE and IDA),
 *   analyses - for KLU, setups that ran KLU's symbolic analysis
 *              successfully: setups entered with KLU's first_factorize flag
 *              set that left a symbolic object, or after which the symbolic
 *              object changed (in sunlinsol_klu.c only the first setup
 *              after initialisation or SUNLinSol_KLUReInit analyses; later
 *              setups refactor numerically, or factor numerically again
 *              when rcond is tiny).  With a fixed pattern it is 1 for the
 *              whole run.  Always 0 for other solvers.
 *
 * The counters live in caller memory (cl_lscount); SUNLinSolFree on the
 * shell frees only the shell, not the wrapped solver. */
#ifndef CL_LSCOUNT_H
#define CL_LSCOUNT_H

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

typedef struct {
    SUNLinearSolver inner; /* the wrapped direct solver */
    long solves, analyses;
} cl_lscount;

/* The shell around c->inner (set by the caller), or NULL if out of memory. */
SUNLinearSolver cl_lscount_create(cl_lscount *c, SUNContext ctx);

#endif
