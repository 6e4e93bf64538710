/* Serial N_Vectors with compiled vector operations.
 *
 * Debian's SUNDIALS 6.4.1 libraries are built without optimisation: the
 * serial vector operations (N_VLinearSum_Serial, N_VWrmsNorm_Serial,
 * N_VDotProd_Serial, ...) run at about 17-21 instructions per entry (the
 * loop keeps every variable on the stack), and at CVODE's small steps on
 * hang they were a third of all instructions of a cvode-bdf run (callgrind,
 * n = 16, --linsol pcg).  cl_nvec_fast keeps a serial vector exactly as it
 * is (content, N_VGetVectorID = SUNDIALS_NVEC_SERIAL, so NV_DATA_S and
 * every solver that checks for a serial vector still work) and replaces
 * its elementwise operations and reductions by the same arithmetic,
 * operation for operation and in the same order (the special cases of
 * N_VLinearSum and N_VScale included), compiled with our flags:
 *
 *     linearsum, const, prod, div, scale, abs, inv, addconst, dotprod,
 *     maxnorm, wrmsnorm, wrmsnormmask, min, wl2norm, l1norm, compare,
 *     invtest
 *
 * so results are bitwise those of N_Vector_Serial (no fused multiply-add
 * on the default x86-64 target), except the dot product and the weighted
 * norms: they sum in four interleaved partial sums (a fixed order, equal
 * to the serial sums to round-off), at every CVODE step and PCG iteration
 * ~4x faster than one running sum.  Clones inherit the operations
 * (N_VClone_Serial copies the operation table).  Fused and vector-array
 * operations stay disabled (NULL), as in N_VNew_Serial: SUNDIALS then
 * composes them from the operations above.
 *
 * Threads.  The operations SUNDIALS' PCG calls at every iteration
 * (linearsum, scale, prod, const, dotprod) run on cl_nvec_threads(N)
 * OpenMP threads, split into chunks that depend on the vector's length
 * alone: P = ceil(n / CL_NVEC_CHUNK) about equal chunks of a multiple of
 * 4 entries each, the last one the rest.  The elementwise ones give the
 * same values for any split; the dot product of the threaded vectors
 * (cl_nvec_new_threaded: pcg's) sums each chunk by the four partial sums
 * and adds the chunks' sums in chunk order, so it does not depend on N
 * either, and a vector of at most CL_NVEC_CHUNK entries (one chunk) sums
 * as the others do.  The other vectors (CVODE's, IDA's) keep one chunk
 * at every length. */
#ifndef CL_NVEC_H
#define CL_NVEC_H

#include <stddef.h>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include "core/decls.h"

CL_BEGIN_DECLS

/* Most entries per chunk of the threaded operations and of the sums
 * (beyond 1024 chunks the chunks grow): the chunks depend on the length
 * alone, never on the thread count. */
#define CL_NVEC_CHUNK 8192

/* Threads (>= 1; less counts as 1) of the operations called from the
 * calling thread from now on; returns the previous count.  Default 1. */
int cl_nvec_threads(int threads);

/* sum_i x_i y_i over n entries in the order of the dot product above, on
 * `threads` threads (the same value for every count). */
double cl_nvec_dot(const double *x, const double *y, size_t n, int threads);

/* Replace the operations of serial vector v (see above). */
void cl_nvec_fast(N_Vector v);

/* N_VNew_Serial(n, ctx) with cl_nvec_fast; NULL if out of memory. */
N_Vector cl_nvec_new(sunindextype n, SUNContext ctx);

/* cl_nvec_new with the chunked dot product (see Threads above), for
 * vectors whose operations run on several threads; NULL if out of
 * memory. */
N_Vector cl_nvec_new_threaded(sunindextype n, SUNContext ctx);

CL_END_DECLS

#endif
