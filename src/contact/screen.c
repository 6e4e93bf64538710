/* The obstacle screens, four points at a time (contact/screen.h). */
#include "contact/screen.h"

#include <string.h>

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SCREEN_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define SCREEN_KERNEL
#endif

typedef double v4 __attribute__((vector_size(32)));
typedef long long m4 __attribute__((vector_size(32))); /* lanes 0 or -1 */

/* Coordinate i of the four points from y (3 doubles each); |a|; the
 * lanes of a block's far flags that are 0 (near) as bits.  (Macros: a
 * function taking or returning a 4-double vector would have two ABIs,
 * one per clone.) */
#define COORD(y, i) ((v4){(y)[i], (y)[3 + (i)], (y)[6 + (i)], (y)[9 + (i)]})
#define ABS4(a) ((v4)((m4)(a) & 0x7fffffffffffffffLL))
#define NEAR_BITS(far)                                                      \
    ((unsigned)(1 + (far)[0]) | (unsigned)(1 + (far)[1]) << 1 |           \
     (unsigned)(1 + (far)[2]) << 2 | (unsigned)(1 + (far)[3]) << 3)

/* The first count (<= 4) points from p whose bit is set, into
 * near[n...]; the new n.  Each point is written and counted if its bit is
 * set, without a branch a point (near[n] is at most point p + i's own
 * place: n <= p + i). */
static inline size_t append(unsigned bits, size_t p, size_t count,
                            size_t *near, size_t n)
{
    for (size_t i = 0; bits && i < count; i++) {
        near[n] = p + i;
        n += bits >> i & 1;
    }
    return n;
}

/* The memo rule of four points y and memos m (screen.h): the near bits. */
static inline unsigned memos_near(const double *y, const cl_contact_memo *m,
                                  const double q[3], const double s[3],
                                  double dmax)
{
    const v4 zero = {0.0, 0.0, 0.0, 0.0};
    v4 X0 = q[0] + (COORD(y, 0) - q[0] - s[0]);
    v4 X1 = q[1] + (COORD(y, 1) - q[1] - s[1]);
    v4 X2 = q[2] + (COORD(y, 2) - q[2] - s[2]);
    v4 margin = (v4){m[0].d, m[1].d, m[2].d, m[3].d} - dmax;
    v4 e0 = X0 - (v4){m[0].X[0], m[1].X[0], m[2].X[0], m[3].X[0]};
    v4 e1 = X1 - (v4){m[0].X[1], m[1].X[1], m[2].X[1], m[3].X[1]};
    v4 e2 = X2 - (v4){m[0].X[2], m[1].X[2], m[2].X[2], m[3].X[2]};
    m4 far = (margin > zero) &
             (e0 * e0 + e1 * e1 + e2 * e2 <= margin * margin);
    return NEAR_BITS(far);
}

SCREEN_KERNEL
size_t cl_screen_memos(const double *x, size_t np, const double q[3],
                       const double s[3], const cl_contact_memo *memo,
                       double dmax, size_t *near)
{
    size_t n = 0, p = 0;
    for (; p + 4 <= np; p += 4)
        n = append(memos_near(x + 3 * p, memo + p, q, s, dmax), p, 4, near,
                   n);
    if (p < np) { /* the last points, in a block filled up with zeros */
        double y[12] = {0.0};
        cl_contact_memo m[4] = {{.d = 0.0}};
        memcpy(y, x + 3 * p, 3 * (np - p) * sizeof *y);
        memcpy(m, memo + p, (np - p) * sizeof *m);
        n = append(memos_near(y, m, q, s, dmax), p, np - p, near, n);
    }
    return n;
}

/* The half-space rule of four points y (screen.h): the near bits. */
static inline unsigned halfspace_near(const double *y, const double nrm[3],
                                      double c, double scale, double dmax)
{
    v4 y0 = COORD(y, 0), y1 = COORD(y, 1), y2 = COORD(y, 2);
    v4 d = nrm[0] * y0 + nrm[1] * y1 + nrm[2] * y2 - c;
    v4 slack = CL_SCREEN_SLACK * (scale + ABS4(y0) + ABS4(y1) + ABS4(y2));
    m4 far = d >= dmax + slack;
    return NEAR_BITS(far);
}

SCREEN_KERNEL
size_t cl_screen_halfspace(const double *x, size_t np, const double nrm[3],
                           double c, double scale, double dmax,
                           size_t *near)
{
    size_t n = 0, p = 0;
    for (; p + 4 <= np; p += 4)
        n = append(halfspace_near(x + 3 * p, nrm, c, scale, dmax), p, 4, near,
                   n);
    if (p < np) {
        double y[12] = {0.0};
        memcpy(y, x + 3 * p, 3 * (np - p) * sizeof *y);
        n = append(halfspace_near(y, nrm, c, scale, dmax), p, np - p, near,
                   n);
    }
    return n;
}
