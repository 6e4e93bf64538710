/* The point of a triangle closest to a given point, and the feature of the
 * triangle it lies on (Ericson, "Real-Time Collision Detection", 2005,
 * section 5.1.5: the Voronoi regions of the vertices, then of the edges,
 * then the face, tested with dot products only).
 *
 * Features are numbered from the triangle's vertex order a, b, c: vertex
 * k is (a, b, c)[k]; edge k runs from vertex k to vertex (k + 1) % 3, so
 * edge 0 is ab, 1 is bc, 2 is ca.  A point on the boundary of two regions
 * gets the first of them in Ericson's order (vertex a, vertex b, edge ab,
 * vertex c, edge ca, edge bc, face).  The triangle must not be degenerate
 * (its vertices not collinear). */
#ifndef CL_TRIANGLE_H
#define CL_TRIANGLE_H

#include "core/decls.h"

CL_BEGIN_DECLS

typedef enum { CL_TRI_FACE, CL_TRI_EDGE, CL_TRI_VERTEX } cl_tri_feature;

typedef struct {
    double c[3];            /* the closest point */
    double dist2;           /* |x - c|^2 */
    cl_tri_feature feature;
    int k;                  /* which edge or vertex (0 for the face) */
} cl_tri_point;

void cl_tri_closest(const double x[3], const double a[3], const double b[3],
                    const double c[3], cl_tri_point *p);

/* A triangle's vertices and edge vectors, computed once (a mesh's
 * bounding-volume tree keeps one a triangle), so that a closest point
 * reads one record instead of the vertex indices and then the vertices. */
typedef struct {
    double a[3], b[3], c[3];
    double ab[3], ac[3], bc[3];     /* b - a, c - a, c - b */
} cl_tri_geom;

void cl_tri_geom_set(const double a[3], const double b[3], const double c[3],
                     cl_tri_geom *g);

/* cl_tri_closest of the triangle g (the same operations: the same
 * answer, bit for bit). */
void cl_tri_closest_geom(const double x[3], const cl_tri_geom *g,
                         cl_tri_point *p);

/* The fraction a in [0, 1] at which the segment x0 + a D crosses the
 * triangle (Moeller and Trumbore, "Fast, minimum storage ray-triangle
 * intersection", 1997), INFINITY if it does not; barycentric coordinates
 * within -1e-9 of the triangle's edges count as inside (conservative
 * along edges shared by two triangles).  A segment parallel to the
 * triangle's plane does not cross it. */
double cl_tri_segment(const double x0[3], const double D[3],
                      const double a[3], const double b[3],
                      const double c[3]);

/* The signed solid angle of the triangle seen from x (van Oosterom and
 * Strackee, "The solid angle of a plane triangle", IEEE Trans. Biomed.
 * Eng. 30(2), 1983), positive where x lies behind it (its normal
 * (b - a) x (c - a) pointing away from x): over a closed surface facing
 * outwards the sum is 4 pi at a point inside, 0 outside (the generalised
 * winding number times 4 pi). */
double cl_tri_solid_angle(const double x[3], const double a[3],
                          const double b[3], const double c[3]);

CL_END_DECLS

#endif
