/* Segment against box and triangle (segment.h). */
#include "contact/segment.h"

#include <math.h>

#include "core/vec3.h"

bool cl_segment_box(const double lo[3], const double hi[3], const double p[3],
                    const double d[3], double smax, double *s)
{
    double enter = 0.0, leave = smax;
    for (int i = 0; i < 3; i++) {
        if (d[i] == 0.0) {
            if (p[i] < lo[i] || p[i] > hi[i])
                return false;
            continue;
        }
        double t1 = (lo[i] - p[i]) / d[i], t2 = (hi[i] - p[i]) / d[i];
        enter = fmax(enter, fmin(t1, t2));
        leave = fmin(leave, fmax(t1, t2));
    }
    *s = enter;
    return enter <= leave;
}

bool cl_segment_triangle(const double a[3], const double b[3],
                         const double c[3], const double p[3],
                         const double d[3], double smax, double *s)
{
    double e1[3], e2[3], q[3], r[3], k[3];
    cl_v3_sub(b, a, e1);
    cl_v3_sub(c, a, e2);
    cl_v3_cross(d, e2, q);
    double det = cl_v3_dot(e1, q);
    if (det == 0.0 || !isfinite(det))
        return false;
    cl_v3_sub(p, a, r);
    double u = cl_v3_dot(r, q) / det;
    if (u < 0.0 || u > 1.0)
        return false;
    cl_v3_cross(r, e1, k);
    double v = cl_v3_dot(d, k) / det;
    if (v < 0.0 || u + v > 1.0)
        return false;
    *s = cl_v3_dot(e2, k) / det;
    return *s >= 0.0 && *s <= smax;
}
