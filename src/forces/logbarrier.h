/* The clamped log barrier of Incremental Potential Contact (Li, Ferguson,
 * Schneider, Langlois, Zorin, Panozzo, Jiang and Kaufman, "Incremental
 * Potential Contact: Intersection- and Inversion-free, Large-Deformation
 * Dynamics", 2020, eq. 6) as a scalar function of a distance d with its
 * two derivatives (docs/model.md 3.5, eq. 3.7):
 *     b(d)   = -(d - dh)^2 ln(d / dh)                       (0 < d < dh)
 *     b'(d)  = -2 (d - dh) ln(d / dh) - (d - dh)^2 / d
 *     b''(d) = -2 ln(d / dh) - 4 (d - dh) / d + (d - dh)^2 / d^2
 * and 0 for d >= dh: b, b', b'' all vanish at dh (b is twice
 * continuously differentiable there), b grows without
 * bound as d -> 0, and b'' > 0 below dh (convex). */
#ifndef CL_LOGBARRIER_H
#define CL_LOGBARRIER_H

#include <math.h>

#include "core/decls.h"

CL_BEGIN_DECLS

typedef struct {
    double b, db, d2b;
} cl_logbarrier;

static inline cl_logbarrier cl_logbarrier_eval(double d, double dh)
{
    cl_logbarrier r = {0.0, 0.0, 0.0};
    if (!(d < dh))
        return r;
    double g = d - dh, l = log(d / dh);
    r.b = -g * g * l;
    r.db = -2.0 * g * l - g * g / d;
    r.d2b = -2.0 * l - 4.0 * g / d + g * g / (d * d);
    return r;
}

CL_END_DECLS

#endif
