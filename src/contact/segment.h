/* A straight segment p + s d, s in [0, smax], against an axis-aligned box
 * and a triangle: the first parameter s at which it meets them, for
 * continuous collision detection (contact/shape.h, toi). */
#ifndef CL_SEGMENT_H
#define CL_SEGMENT_H

#include <stdbool.h>

/* The least s in [0, smax] with p + s d inside the box [lo, hi] (the slab
 * test: Kay and Kajiya, "Ray tracing complex scenes", SIGGRAPH 1986),
 * false if there is none. */
bool cl_segment_box(const double lo[3], const double hi[3], const double p[3],
                    const double d[3], double smax, double *s);

/* The s in [0, smax] at which p + s d crosses the triangle a, b, c
 * (Moeller and Trumbore, "Fast, minimum storage ray-triangle
 * intersection", J. Graphics Tools 2(1), 1997; edges and vertices
 * included), false if it does not; a segment in the triangle's plane
 * does not cross it. */
bool cl_segment_triangle(const double a[3], const double b[3],
                         const double c[3], const double p[3],
                         const double d[3], double smax, double *s);

#endif
