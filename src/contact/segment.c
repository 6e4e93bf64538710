/* Segment against box (segment.h). */
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
