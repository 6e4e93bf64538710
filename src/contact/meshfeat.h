/* The outer regions of a closed mesh's features in which a feature is
 * known to be the nearest of the whole mesh, so that a point that stays
 * near one feature is answered by that feature alone (docs/model.md 4.1,
 * eq. C1a-C1c).
 *
 * Every face, edge and vertex F has a set of supporting face normals
 * N_F (its own face; the two faces of an edge; the faces around a
 * vertex), a closest point c_F(x) and an outer region R_F: above the
 * face within its prism; for an edge, beside its segment within the
 * wedge between the two faces' planes through it; for a vertex, within
 * the cone where x - v makes no acute angle with any edge leaving v.
 * For x in R_F, x - c_F is a non-negative combination of N_F when F's
 * neighbourhood is convex.  A triangle all of whose vertices y satisfy
 * m . (y - c_F) <= tau for every m in N_F is then no nearer than
 * |x - c_F| less a few tau (eq. C1b); any other triangle T is farther
 * than |x - c_F| as long as |x - c_F| <= dist(T, F) / 2 (eq. C1c).  The
 * clearance h_F of a face is the least dist(T, F) / 2 over the
 * triangles of the second kind, a lower bound of it from bounding
 * spheres (infinite when there are none, as on a convex mesh; 0, the
 * feature unused, when such a triangle's sphere meets F's, as when it
 * touches F around a concave edge); an edge or vertex takes the least of
 * its faces'.  A face whose own vertices lie off its computed plane by
 * more than tau (a sliver) is unused.  tau is 1e-12 times the mesh's
 * size, and answers are the nearest distance to within a few tau.
 *
 * Only faces, edges between faces that are not coplanar and corner
 * vertices have regions of full dimension; edges between coplanar faces
 * and vertices inside flat regions or on straight creases are not used.
 *
 * Features are numbered faces first (triangle t is t), then the edges
 * of contact/closed.h (edge e is ntri + e), then the vertices (v is
 * ntri + nedge + v). */
#ifndef CL_MESHFEAT_H
#define CL_MESHFEAT_H

#include <stdbool.h>
#include <stddef.h>

#include "contact/bvh.h"
#include "contact/closed.h"
#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef enum { CL_FEAT_FACE, CL_FEAT_EDGE, CL_FEAT_CORNER } cl_feat_kind;

typedef struct {
    double n[3], off;       /* unit normal; n . x - off is the height */
    double m[3][3], mo[3];  /* in-plane outward normals of its sides:
                               inside the prism where m[k] . x <= mo[k] */
    double h;               /* clearance (0: unused) */
} cl_feat_face;

typedef struct {
    double a[3], e[3], len; /* from a along the unit direction e */
    double ma[3], mb[3];    /* the two faces' in-plane outward normals */
    double h;
    int face;               /* a face of it, where a walk starts */
} cl_feat_edge;

typedef struct {
    double p[3];
    double h;
    int first, count;       /* its edges' unit directions from it in w[] */
    int face;               /* a face of it, where a walk starts */
} cl_feat_vertex;

typedef struct {
    size_t nface, nedge, nvert;
    cl_feat_face *face;
    cl_feat_edge *edge;
    cl_feat_vertex *vert;
    double (*w)[3];         /* directions of the edges leaving vertices */
    const int (*tri)[3];    /* the triangles (borrowed from the tree) */
    int (*side)[3];         /* side k of triangle t is edge side[t][k] */
    int (*across)[3];       /* the triangle across it */
    double tiny;            /* tau, and the least distance answered */
} cl_meshfeat;

/* The regions and clearances of the closed, outward mesh of tree b and
 * surface s (its vertices vert, nvert of them; flat[3 t + k] true when
 * side k of triangle t joins coplanar faces; corner[v] true for a corner
 * vertex); tiny as above.  CL_EINVAL when the features are too many to
 * number with an int, CL_ENOMEM. */
cl_status cl_meshfeat_build(cl_meshfeat *f, const cl_bvh *b,
                            const cl_closed *s, size_t nvert,
                            const unsigned char *flat,
                            const unsigned char *corner, double tiny,
                            cl_error *err);

void cl_meshfeat_free(cl_meshfeat *f);

/* The number of feature k of kind `feature` (contact/triangle.h's
 * numbering) of triangle t, -1 when it is not used. */
int cl_meshfeat_id(const cl_meshfeat *f, int t, cl_tri_feature feature,
                   int k);

/* The answer of feature id at x when x lies in its region, outside, at a
 * distance d in (tiny, h]: then true, with d, the unit normal n
 * ((x - c) / d; a face's own normal), c and the feature's kind (and an
 * edge's direction in e). */
bool cl_meshfeat_answer(const cl_meshfeat *f, int id, const double x[3],
                        double *d, double n[3], double c[3],
                        cl_feat_kind *kind, double e[3]);

/* Feature id, or else the first feature that answers at x on a walk
 * over the faces from one of id's (each face's own features tried, then
 * the face across the side x lies farthest beyond, CL_MESHFEAT_HOPS faces
 * at most), as cl_meshfeat_answer; -1 if none does.  A point that moved
 * off its feature is mostly in a neighbour's region, or a few faces
 * on. */
#define CL_MESHFEAT_HOPS 8

int cl_meshfeat_answer_near(const cl_meshfeat *f, int id, const double x[3],
                            double *d, double n[3], double c[3],
                            cl_feat_kind *kind, double e[3]);

CL_END_DECLS

#endif
