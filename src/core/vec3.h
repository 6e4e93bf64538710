/* Small 3-vector operations on double[3], for the geometry of the OBJ
 * reader and the contact layer.  Header only (static inline). */
#ifndef CL_VEC3_H
#define CL_VEC3_H

#include <math.h>

#include "core/decls.h"

CL_BEGIN_DECLS

static inline double cl_v3_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline double cl_v3_norm(const double a[3])
{
    return sqrt(cl_v3_dot(a, a));
}

/* The component operations below are written out rather than looped:
 * GCC at -O2 keeps a three-trip loop as a loop, which holds the result in
 * memory (stored, then loaded back by the next operation) instead of in
 * registers.  The same operations, so the same results. */

/* out = a + b (out may alias a or b). */
static inline void cl_v3_add(const double a[3], const double b[3],
                             double out[3])
{
    out[0] = a[0] + b[0];
    out[1] = a[1] + b[1];
    out[2] = a[2] + b[2];
}

/* out = a - b (out may alias a or b). */
static inline void cl_v3_sub(const double a[3], const double b[3],
                             double out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

/* out = a + s b (out may alias a or b). */
static inline void cl_v3_axpy(const double a[3], double s, const double b[3],
                              double out[3])
{
    out[0] = a[0] + s * b[0];
    out[1] = a[1] + s * b[1];
    out[2] = a[2] + s * b[2];
}

/* out = s a (out may alias a). */
static inline void cl_v3_scale(double s, const double a[3], double out[3])
{
    out[0] = s * a[0];
    out[1] = s * a[1];
    out[2] = s * a[2];
}

/* out = a x b (out must not alias a or b). */
static inline void cl_v3_cross(const double a[3], const double b[3],
                               double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* (b - a) x (c - a): twice the area times the unit normal of the triangle
 * a, b, c (counter-clockwise). */
static inline void cl_v3_tri_cross(const double a[3], const double b[3],
                                   const double c[3], double out[3])
{
    double u[3], v[3];
    cl_v3_sub(b, a, u);
    cl_v3_sub(c, a, v);
    cl_v3_cross(u, v, out);
}

/* a / |a| in place; returns |a| (a is left alone when it is 0). */
static inline double cl_v3_normalize(double a[3])
{
    double r = cl_v3_norm(a);
    if (r > 0)
        for (int i = 0; i < 3; i++)
            a[i] /= r;
    return r;
}

CL_END_DECLS

#endif
