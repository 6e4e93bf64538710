/* CVODE's and IDA's Newton systems solved through the half-size matrix
 * (docs/model.md, 1; docs/integrators.md, 5): a SUNLinearSolver that
 * eliminates one block of the 2n x 2n system and hands the n x n remainder
 * (3 unknowns per free particle) to a cl_linsol (klu, pcg, pcg-jacobi,
 * cholmod, auto; linalg/linsol.h).
 *
 * Notation: n = 3 (free particles), M = diag(mass), Kx = df/dx, Kv = df/dv
 * (the system's block Jacobians, evaluated at the solver's request),
 * r = (rx, rv) the right-hand side, z = (zx, zv) the solution.
 *
 * CVODE (y' = (v, M^-1 f)), and ARKODE's ARKStep on the same form with
 * gamma = h a_ii of the stage (arkode_common.h): the Newton matrix is
 * I - gamma J with
 * J = [[0, I], [M^-1 Kx, M^-1 Kv]]:
 *
 *     zx - gamma zv = rx
 *     -gamma M^-1 Kx zx + zv - gamma M^-1 Kv zv = rv
 *
 * multiply the second row by M and put zx = rx + gamma zv into it:
 *
 *     (M - gamma Kv - gamma^2 Kx) zv = M rv + gamma Kx rx,
 *     zx = rx + gamma zv,
 *
 * the cl_linsol matrix A = M - a Kv - b Kx with a = gamma, b = gamma^2.
 *
 * IDA (F = [x' - v; M v' - f]): the iteration matrix is
 * G = [[cj I, -I], [-Kx, cj M - Kv]]:
 *
 *     cj zx - zv = rx
 *     -Kx zx + (cj M - Kv) zv = rv
 *
 * with zv = cj zx - rx from the first row, the second gives
 * (cj^2 M - cj Kv - Kx) zx = rv + (cj M - Kv) rx; divided by cj^2:
 *
 *     (M - Kv / cj - Kx / cj^2) zx = (rv + cj M rx - Kv rx) / cj^2,
 *     zv = cj zx - rx,
 *
 * A with a = 1/cj, b = 1/cj^2.
 *
 * Residuals.  With the eliminated block satisfied exactly, the residual of
 * the full system is (0, M^-1 rho) for CVODE and (0, cj^2 rho) for IDA,
 * rho the residual of the half-size system.  An iterative cl_linsol is
 * therefore asked for ||w_red .* rho||_2 <= delta with w_red = w_v / m
 * (CVODE), w_red = cj^2 w_v (IDA), w_v the v-part of the integrator's
 * weights and delta its tolerance: exactly the integrator's own test on
 * the full system.
 *
 * How the integrators call it (SUNDIALS 6.4.1).  The matrix-embedded
 * solver type (SUNLINEARSOLVER_MATRIX_EMBEDDED) exists in 6.4.1, but CVODE
 * and IDA then never call the solver's setup (cvLsInitialize sets
 * cv_lsetup = NULL; checked: 0 setups in 182 steps): the solver would have
 * to guess at every solve when the Jacobian is stale and when gamma has
 * moved, without CVODE's convergence-failure information, and a stale
 * Jacobian could no longer be refreshed within a step (a failed Newton
 * iteration costs a step reduction instead).  Measured with a
 * matrix-embedded prototype (pcg; Jacobian every 51 steps or after a
 * convergence failure, preconditioner at every change of gamma) on hang,
 * rtol 1e-4, T = 2 s: 1.5 Newton iterations per step instead of 1.06 and
 * 38 % (n = 16) / 32 % (n = 32) more CPU time than the design below.
 * So the solver is attached
 * as a matrix-based one with a *shell* SUNMatrix that holds no values (the
 * adapter's, sun_adapter.h: its zero, copy, scale-add-identity and clone
 * operations do nothing but keep the shell), and CVODE's and IDA's own
 * heuristics decide:
 *
 *  - the Jacobian function (CVodeSetJacFn / IDASetJacFn) evaluates Kx, Kv
 *    at the solver's state; CVODE calls it only when it wants a new
 *    Jacobian (its jok / jcur logic: every 51 steps, after a convergence
 *    failure with a stale one); IDA at every setup;
 *  - setup reads gamma (CVodeGetCurrentGamma) or cj (IDAGetCurrentCj),
 *    assembles A from the stored Kx, Kv and sets the cl_linsol up
 *    (factorises, or forms the preconditioner); CVODE calls it when gamma
 *    has changed by more than 30 %, every 20 steps, or after a failure,
 *    and scales the solutions in between by 2 / (1 + gamma / gamma_setup)
 *    itself, as for KLU on the full matrix;
 *  - solve uses the gamma / cj of the last setup, consistent with A.
 * Nothing the size of the first-order matrix exists: no 2n x 2n values,
 * no copies of them.  The product Kx rx (Kv rx for IDA) of the right-hand
 * side uses the halves of the block when it is symmetric (linalg/bsym.h,
 * packed once per Jacobian), as pcg does for A at every setup.
 *
 * Measured (cvode-bdf on hang, rtol 1e-4, atol 1e-6, T = 2 s; CPU seconds
 * in one `make bench` run on a shared two-core machine, so +-10 %):
 *
 *     n    linsol      order  CPU s   steps
 *     16   klu-full     <= 5    7.0   13014
 *     16   klu          <= 5    6.2   12906
 *     16   cholmod      <= 5    7.5   12950
 *     16   pcg          <= 5    1.2   12584
 *     16   pcg-jacobi   <= 5    1.4   12987
 *     16   auto         <= 5    1.3   12584   (all pcg)
 *     32   klu-full     <= 5  122     14970
 *     32   pcg          <= 5    3.8   13529   (32x klu-full)
 *     64   pcg          <= 5   40.5   29914
 *     64   pcg          <= 2   14.7    7365
 *    128   pcg          <= 2  176      9838
 *
 * At these steps A is close to M: a factorisation per setup plus two
 * triangular solves per Newton iteration cost far more than one or two
 * block products (1.1-1.3 pcg iterations per solve).  What remains with
 * pcg (perf, n = 128): the symmetric block products (linalg/bsym.h) ~31 %,
 * the force evaluation ~20 %, SUNDIALS' vector operations ~15 %
 * (linalg/nvec.h), the Jacobian and its symmetry test ~10 %.  BDF orders
 * above 2 are not stable near the imaginary axis, where the cloth's fast,
 * lightly damped modes sit: from n = 32 on, --max-order 2 takes fewer
 * steps (4x fewer at n = 64).
 *
 * The solver type is SUNLINEARSOLVER_DIRECT for direct cl_linsols (klu,
 * cholmod) and SUNLINEARSOLVER_MATRIX_ITERATIVE for those with solve_tol
 * (pcg, pcg-jacobi, auto), which then get the integrator's tolerance and
 * weights as above; every solve is reported to CVODE and IDA as one
 * iteration (IDA would take a residual vector for the solution after 0),
 * the true counts come from the cl_linsol (see cl_sunred_attach).
 *
 * Failures: a cl_linsol setup or solve failing with CL_ESOLVER (singular or
 * indefinite A, no convergence) is a recoverable failure for the
 * integrator, which retries with a fresh Jacobian or a smaller step; other
 * failures are unrecoverable.  The last message is kept and ends the
 * message of a failed advance.
 *
 * Everything is allocated by cl_sunred_attach; setup and solve allocate
 * nothing (beyond what the cl_linsol documents). */
#ifndef CL_SUN_REDUCED_H
#define CL_SUN_REDUCED_H

#include "core/decls.h"
#include "integrators/sun_adapter.h"

CL_BEGIN_DECLS

/* The linear solver of cvode-bdf and ida when --linsol is not given. */
#define CL_SUNRED_DEFAULT "auto"

/* The Newton linear solver named by o->linsol (NULL or "":
 * CL_SUNRED_DEFAULT) on s, for the y' = f form (CVODE, ARKStep: the
 * package's get_gamma and set_jac_fn) when ida is false, IDA's otherwise
 * (s->mem, s->dfdx, s->dfdv must exist), attached with its Jacobian
 * function and plugged into s (sun_adapter.h), which releases it:
 *
 *   klu-full  KLU on the first-order matrix (the baseline), assembled from
 *             the pattern built once (linalg/firstorder.h) and wrapped in
 *             the adapter's counting shell; statistics linsol = "klu-full";
 *   klu, pcg, pcg-jacobi, cholmod, auto
 *             the half-size solver above with that cl_linsol (options
 *             lin_tol, lin_maxit); statistics lin_solves, lin_iters,
 *             symbolic_facts, lin_fallbacks, lin_recoveries and linsol
 *             from the cl_linsol
 *             (steps, setups, Jacobian evaluations stay the
 *             integrator's); a failure's message ends with the last
 *             linear-solver failure.
 *
 * CL_EINVAL naming the known solvers for an unknown name. */
cl_status cl_sunred_attach(cl_sun *s, const cl_integrator_opts *o, bool ida,
                           cl_error *err);

CL_END_DECLS

#endif
