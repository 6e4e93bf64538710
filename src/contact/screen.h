/* The obstacle screens' loops (contact/obstacle.h, cl_obstacle_screen),
 * four points at a time: a block whose four points are all far costs one
 * test instead of four branches, and the lanes are computed with GCC's
 * vector extensions, which the AVX2 clone (target_clones, as the pair
 * kernels of forces/pairkern.h) turns into 4-wide instructions.  Each lane
 * computes the scalar rule's operations in its order (no FMA contraction:
 * ISO C mode, -ffp-contract=off), so the points listed are exactly those
 * the scalar rule lists, in increasing order. */
#ifndef CL_SCREEN_H
#define CL_SCREEN_H

#include <stddef.h>

#include "contact/obstacle.h"
#include "core/decls.h"

CL_BEGIN_DECLS

/* The relative slack of a screen computed in another order than the
 * query (a few units of rounding, 1.1e-16 each, with a wide margin). */
#define CL_SCREEN_SLACK 1e-12

/* The points p of x (3 each, np of them) whose memo does not show
 * d >= dmax at the shape-frame point X = q + (x_p - q - s) of an obstacle
 * that does not rotate (q its pivot, s its displacement): not
 * (memo.d - dmax > 0 and |X - memo.X|^2 <= (memo.d - dmax)^2), into
 * near[]; their number. */
size_t cl_screen_memos(const double *x, size_t np, const double q[3],
                       const double s[3], const cl_contact_memo *memo,
                       double dmax, size_t *near);

/* The points p whose distance to the half-space d(x) = n . x - c lies
 * not clearly above dmax: not (n . x_p - c >= dmax + CL_SCREEN_SLACK
 * (scale + |x_p,0| + |x_p,1| + |x_p,2|)), into near[]; their number.
 * Points that are not numbers are near. */
size_t cl_screen_halfspace(const double *x, size_t np, const double n[3],
                           double c, double scale, double dmax,
                           size_t *near);

CL_END_DECLS

#endif
