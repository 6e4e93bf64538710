/* Linear solvers for the half-size ("reduced") Newton matrix of the
 * second-order form (docs/model.md, 1; docs/integrators.md, 5):
 *     A = M - a df/dv - b df/dx        (3 unknowns per free particle)
 * with method-dependent a, b (backward Euler: a = h, b = h^2; BDF2 as in
 * Jiao's eq. 15: a = 2h/3, b = 4h^2/9; ...).  The blocks of df/dx and
 * df/dv come in the fixed cl_bpattern of the system.
 *
 * Each solver is one file defining a cl_linsol_type plus one row in the
 * registry (linalg/linsol.c), selectable by name with --linsol:
 *   klu         sparse LU (KLU, AMD ordering): symbolic analysis once,
 *               numeric refactorisation at every setup (linsol_klu.c);
 *   pcg         SUNDIALS' SUNLinSol_PCG with a matrix-free product and a
 *               3x3 block-Jacobi preconditioner; A must be symmetric
 *               positive definite, and a breakdown (p^T A p <= 0), an
 *               indefinite diagonal block or no convergence within
 *               lin_maxit is reported as CL_ESOLVER, not hidden; stops at
 *               |b - A x|_2 <= lin_tol |b|_2 (linsol_pcg.c);
 *   pcg-jacobi  the same with the point-Jacobi preconditioner;
 *   cholmod     supernodal sparse Cholesky (SuiteSparse CHOLMOD) for a
 *               symmetric positive definite A, handing a setup whose A is
 *               not (or not symmetric) to klu (linsol_cholmod.c);
 *   auto        pcg, and cholmod (or klu) for a while after a pcg setup
 *               that a factorisation would have done cheaper or that
 *               failed; a failed pcg solve is redone directly
 *               (linsol_auto.c).
 *   amg         CG preconditioned by PETSc's GAMG (smoothed aggregation),
 *               the hierarchy kept across setups; amg-hypre: by hypre's
 *               BoomerAMG, built at every setup (linsol_amg.c, on the
 *               PETSc plug-in).
 *
 * Usage: create once (the pattern must outlive the solver; mass is
 * copied), then per Newton matrix one setup and any number of solves; a
 * solve after a failed setup gives CL_EINVAL.  Nothing is allocated by
 * setup or solve (except KLU's rare fresh factorisation after a bad
 * refactorisation).  All messages start with the solver's name.  The
 * iterative solvers (pcg, pcg-jacobi, amg, amg-hypre; auto through them)
 * end a solve at their next product with A once a stop is requested
 * (core/stop.h: SIGINT, SIGTERM, a budget's timer), with CL_EINTR, so
 * that a long solve does not hold up the stop (amg: also a solve whose
 * recovery the stop came into); a factorisation or a multigrid setup
 * runs to its end. */
#ifndef CL_LINSOL_H
#define CL_LINSOL_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "core/stats.h"
#include "linalg/bpattern.h"

CL_BEGIN_DECLS

/* What an iterative solver is told (0: its defaults). */
typedef struct {
    double tol;   /* relative residual tolerance */
    long maxit;   /* iterations per solve */
    int threads;  /* OpenMP threads for the iterative solvers' products
                   * (pcg, amg; <= 1: serial; results do not depend on
                   * it) */
} cl_linsol_opts;

typedef struct {
    const char *name;
    const char *doc;
    cl_status (*create)(const cl_bpattern *pat, const double *mass,
                        const cl_linsol_opts *opts, void **state,
                        cl_error *err);
    /* Optional: told of every new df/dx, df/dv (their values, the arrays
     * later setups receive) before the setups that use them.  A solver
     * that exploits symmetry (pcg) tests for it here, once per Jacobian;
     * one never told assumes none.  Callers: every integrator with a
     * cl_linsol (cl_linsol_jacobian). */
    void (*jacobian)(void *state, const double *dfdx, const double *dfdv);
    /* Assemble A = M - a dfdv - b dfdx from block values (9 * nnzb each)
     * and factorise / set up the preconditioner. */
    cl_status (*setup)(void *state, double a, double b, const double *dfdx,
                       const double *dfdv, cl_error *err);
    /* Solve A x = rhs (3 * nb entries each; x may be rhs). */
    cl_status (*solve)(void *state, const double *rhs, double *x,
                       cl_error *err);
    /* Iterative solvers only (NULL for direct ones, which always solve to
     * rounding): the same, stopping once ||w .* (rhs - A x)||_2 <= delta
     * (w: 3 nb positive weights) instead of at opts->tol: the test SUNDIALS'
     * integrators ask of an iterative linear solver. */
    cl_status (*solve_tol)(void *state, const double *rhs, double *x,
                           const double *w, double delta, cl_error *err);
    /* Optional (direct solvers): the flops of one setup (numeric
     * factorisation) and of one solve, as the symbolic analysis predicts
     * them; auto weighs them against pcg's iterations. */
    void (*cost)(const void *state, double *setup_flops,
                 double *solve_flops);
    /* Add this solver's counters: lin_setups, lin_solves, lin_iters,
     * symbolic_facts, lin_fallbacks, lin_recoveries; a solver that can
     * hand work to another one also writes the names into linsol. */
    void (*stats)(const void *state, cl_stats *s);
    void (*free)(void *state);
    /* Triangular factors kept: 2 (LU), 1 (Cholesky), 0 (iterative), for
     * the memory guard's estimate (integrators/memguard.c). */
    int factors;
} cl_linsol_type;

extern const cl_linsol_type *const cl_linsol_registry[];

/* By name; NULL or "" gives the first (default) solver; NULL if unknown. */
const cl_linsol_type *cl_linsol_find(const char *name);

/* cl_linsol_find into *lt, or CL_EINVAL naming `who` (the integrator),
 * the name and the known ones, `also` (NULL or names the caller accepts
 * besides the registry's) first. */
cl_status cl_linsol_get(const char *who, const char *name, const char *also,
                        const cl_linsol_type **lt, cl_error *err);

/* Tell solver `lt` (state `ls`) of new Jacobian values, if it listens. */
static inline void cl_linsol_jacobian(const cl_linsol_type *lt, void *ls,
                                      const double *dfdx, const double *dfdv)
{
    if (lt->jacobian)
        lt->jacobian(ls, dfdx, dfdv);
}

/* Add solver lt's counters (state ls) to s, with the names of the solvers
 * that did the work in s->linsol: those the solver wrote (auto, cholmod),
 * else its own name. */
void cl_linsol_report(const cl_linsol_type *lt, const void *ls, cl_stats *s);

/* The iterative solvers' start of create: CL_EINVAL naming `name` for an
 * empty pattern, or a lin_tol or lin_maxit that is not finite >= 0; else
 * a zeroed state of `size` bytes into *state (CL_ENOMEM if none). */
cl_status cl_linsol_new_state(const char *name, const cl_bpattern *pat,
                              const cl_linsol_opts *o, size_t size,
                              void **state, cl_error *err);

/* The iterative solvers' checks before a solve: CL_EINVAL naming `name`
 * when no setup succeeded (`ready` false), CL_ESOLVER when an entry of
 * rhs (n) is not finite. */
cl_status cl_linsol_check_solve(const char *name, bool ready,
                                const double *rhs, size_t n, cl_error *err);

/* The weights and bound of a solve_tol: CL_EINVAL naming `name` unless
 * every weight of w (n) and delta are positive and finite. */
cl_status cl_linsol_check_weights(const char *name, const double *w,
                                  size_t n, double delta, cl_error *err);

/* The iterative solvers' iteration cap: lin_maxit, or max(1000, 2 n) when
 * it is 0; at most INT_MAX. */
int cl_linsol_maxit(long lin_maxit, size_t n);

/* "klu, pcg": the names, for messages. */
const char *cl_linsol_names(char *buf, size_t len);

CL_END_DECLS

#endif
