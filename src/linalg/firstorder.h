/* Sparse Jacobian of the first-order form (docs/model.md, 1).
 *
 *   y = (x, v),  x' = v,  v' = M^-1 f(t, x, v),  size 2n (n = 3 nb),
 *
 *       J = [ 0                I            ]
 *           [ M^-1 df/dx       M^-1 df/dv   ]
 *
 * stored in compressed sparse column form (SUNDIALS CSC_MAT, sunindextype
 * indices).  The pattern is computed once from the 3x3-block pattern of
 * df/dx and df/dv (cl_bpattern, the same for both blocks): column pointers,
 * sorted row indices, and for every stored value the place its number comes
 * from (a block-value index into df/dx or df/dv, the identity's 1, or an
 * explicit 0).  Every diagonal entry of J is stored, including the x-block's
 * structural zeros, so that CVODE's I - gamma J (SUNMatScaleAddI, which in
 * SUNDIALS 6.4.1 rebuilds the matrix on a slow path when a diagonal entry is
 * missing) keeps the storage and the pattern KLU analysed.  Filling copies
 * the index arrays (CVODE's SUNMatZero wipes them before every Jacobian
 * call) and writes the values, scaled by 1/mass of their row: no search, no
 * allocation.  No symmetry of df/dx or df/dv is assumed.
 *
 * The implicit form F(t, y, y') = [x' - v ; M v' - f(t, x, v)] = 0 (IDA)
 * has the iteration matrix
 *
 *       G = dF/dy + c_j dF/dy' = [ c_j I       -I              ]
 *                                [ -df/dx      c_j M - df/dv   ]
 *                              = c_j diag(I, M) - diag(I, M) J,
 *
 * with exactly the pattern of J (every diagonal entry is stored), so the
 * same pattern and value map serve it: cl_firstorder_fill_implicit writes
 * the negated unscaled block values and adds c_j (x rows) or c_j m_i
 * (v rows) at the recorded position of each diagonal entry. */
#ifndef CL_FIRSTORDER_H
#define CL_FIRSTORDER_H

#include <stddef.h>

#include <sundials/sundials_types.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "core/decls.h"
#include "core/error.h"
#include "linalg/bpattern.h"

CL_BEGIN_DECLS

/* Value sources that are not block values. */
#define CL_FO_ZERO (-1L) /* explicit (structural) zero */
#define CL_FO_ONE (-2L)  /* identity entry of the x' = v rows */

typedef struct {
    size_t n;              /* 3 nb: half the system size */
    size_t nval;           /* 9 nnzb: length of each block-value array */
    sunindextype size;     /* 2n */
    sunindextype nnz;      /* stored entries: 2n + 18 nnzb */
    sunindextype *colptr;  /* size + 1 */
    sunindextype *rowval;  /* nnz, ascending within each column */
    /* Per stored value: k in [0, nval) for dfdx[k], nval + k for dfdv[k],
     * or CL_FO_ZERO / CL_FO_ONE. */
    long *src;
    double *inv_mass;      /* n: 1 / mass, indexed by the v-row minus n */
    double *mass;          /* n: the masses, same indexing */
    sunindextype *diag;    /* size: position of entry (i, i) in column i */
} cl_firstorder;

/* Build the pattern and the value map for the blocks of `pat` and the n
 * diagonal masses (finite, > 0). */
cl_status cl_firstorder_create(const cl_bpattern *pat, const double *mass,
                               cl_firstorder *fo, cl_error *err);
void cl_firstorder_free(cl_firstorder *fo);

/* Write the complete CSC matrix (colptr, rowval, values) into caller arrays
 * of sizes size + 1, nnz, nnz, from block values dfdx, dfdv (nval each). */
void cl_firstorder_fill_arrays(const cl_firstorder *fo, const double *dfdx,
                               const double *dfdv, sunindextype *colptr,
                               sunindextype *rowval, sunrealtype *val);

/* The same into a SUNDIALS sparse matrix, which must be CSC, size x size,
 * with room for nnz entries (CL_EINVAL otherwise). */
cl_status cl_firstorder_fill(const cl_firstorder *fo, const double *dfdx,
                             const double *dfdv, SUNMatrix J, cl_error *err);

/* J dense and row-major (2n x 2n, n = 3 pat->nb) from the block values
 * and the inverse masses (n), for small systems (GSL's msbdf, spectra). */
void cl_firstorder_dense(const cl_bpattern *pat, const double *inv_mass,
                         const double *dfdx, const double *dfdv, double *J);

/* The implicit-form iteration matrix G (c_j as IDA passes it) into caller
 * arrays, resp. into a SUNDIALS sparse matrix (same checks as above). */
void cl_firstorder_fill_implicit_arrays(const cl_firstorder *fo,
                                        const double *dfdx, const double *dfdv,
                                        double cj, sunindextype *colptr,
                                        sunindextype *rowval, sunrealtype *val);
cl_status cl_firstorder_fill_implicit(const cl_firstorder *fo,
                                      const double *dfdx, const double *dfdv,
                                      double cj, SUNMatrix G, cl_error *err);

CL_END_DECLS

#endif
