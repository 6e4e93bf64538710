/* A straight segment p + s d, s in [0, smax], against an axis-aligned box:
 * the first parameter s at which it meets it, for the time of impact
 * (contact/shape.h, toi; a triangle: contact/triangle.h). */
#ifndef CL_SEGMENT_H
#define CL_SEGMENT_H

#include <stdbool.h>

#include "core/decls.h"

CL_BEGIN_DECLS

/* The least s in [0, smax] with p + s d inside the box [lo, hi] (the slab
 * test: Kay and Kajiya, "Ray tracing complex scenes", SIGGRAPH 1986),
 * false if there is none. */
bool cl_segment_box(const double lo[3], const double hi[3], const double p[3],
                    const double d[3], double smax, double *s);

CL_END_DECLS

#endif
