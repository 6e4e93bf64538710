/* A dense direct SUNLinearSolver backed by LAPACK: LU with partial pivoting
 * (dgetrf) at setup, the two triangular solves (dgetrs) per solve, on a
 * SUNDenseMatrix, whose column-major storage LAPACK takes as it is.
 *
 * SUNDIALS' own dense solver (SUNLinSol_Dense) factorises with an
 * unblocked column loop; SUNDIALS' SUNLinSol_LapackDense does what this
 * does but is not in Debian's build of SUNDIALS.  The factorisation then
 * runs at the speed of the system's BLAS (OpenBLAS when installed).
 *
 * Return values follow SUNDIALS' direct solvers: setup returns
 * SUNLS_SUCCESS, or the 1-based column of a zero pivot (> 0: recoverable,
 * the integrator retries with a smaller step); solve SUNLS_SUCCESS, or
 * SUNLS_PACKAGE_FAIL_UNREC if LAPACK rejects its arguments. */
#ifndef CL_SUNLS_LAPACK_H
#define CL_SUNLS_LAPACK_H

#include <nvector/nvector_serial.h>
#include <sundials/sundials_linearsolver.h>

#include "core/decls.h"

CL_BEGIN_DECLS

/* A solver for square dense matrices of y's length, or NULL if out of
 * memory. */
SUNLinearSolver cl_sunls_lapack_dense(N_Vector y, SUNContext ctx);

CL_END_DECLS

#endif
