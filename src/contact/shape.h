/* The obstacle-shape interface of the contact layer.  A shape (sphere,
 * plane, box, triangle mesh) is one file defining a cl_shape_type plus one
 * row in the registry table of contact/registry.c; nothing else changes.
 *
 * A shape lives in its own frame; the obstacle (contact/obstacle.h) moves
 * that frame rigidly along its scripted path.  A shape answers, for a
 * point x of its frame, the signed distance d (> 0 outside, < 0 inside),
 * the outward unit normal n = grad d, the closest surface point
 * c = x - d n and the derivative of the normal G = dn/dx (the Hessian of
 * d, symmetric; docs/model.md, contact section): 0 on a face, (I - n n^T)/r
 * around a sphere of radius-to-centre r, (I - n n^T - e e^T)/d near an edge
 * of direction e, (I - n n^T)/d near a vertex.  Where d is not
 * differentiable (the centre of a sphere, a point equidistant from two
 * faces of a box) any one of the candidates is returned. */
#ifndef CL_SHAPE_H
#define CL_SHAPE_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"
#include "io/config.h"

CL_BEGIN_DECLS

typedef struct {
    double d;       /* signed distance (m), > 0 outside */
    double n[3];    /* outward unit normal, grad d */
    double c[3];    /* closest point on the surface */
    double G[9];    /* dn/dx, row-major, symmetric */
} cl_shape_query;

/* Triangles that draw a shape (in its own frame), for the frames written
 * beside the cloth. */
typedef struct {
    size_t nvert;
    double *vert;   /* 3 * nvert */
    size_t ntri;
    int (*tri)[3];  /* 0-based, counter-clockwise seen from outside */
} cl_shape_surface;

typedef struct {
    const char *name;   /* the `shape` value in an [obstacle.NAME] section */
    const char *doc;    /* one line for `clothode list` */
    /* Read the geometry keys of INI section `sec` (the keys of each shape
     * are listed in its file and the README) and set pivot, the point the
     * obstacle's rotation turns about (a sphere's or box's centre, a
     * plane's point, a mesh's vertex centroid).  Bad values give CL_EINVAL
     * naming the file, line, key, value and the allowed range. */
    cl_status (*create)(cl_config *cfg, const char *sec, double pivot[3],
                        void **shape, cl_error *err);
    /* cache: NULL, or cache_size bytes kept for one moving point between
     * its queries (zeroed before the first), which the shape may use to
     * answer faster; the answer does not depend on it (up to which of
     * several nearest features is taken, and to rounding where the cache
     * computes it another way; a mesh: contact/bvh.h, meshfeat.h). */
    void (*query)(const void *shape, const double x[3], void *cache,
                  cl_shape_query *q);
    size_t cache_size;  /* 0: the shape keeps nothing */
    /* Optional (NULL: none): a lower bound of the signed d at x, much
     * cheaper than the query (a mesh: the distance to its bounding box
     * outside it, -inf inside), so that particles far from the shape skip
     * the query. */
    double (*lower_bound)(const void *shape, const double x[3]);
    /* Optional (NULL: none): a half-space's outward unit normal n and a
     * point p of its boundary, d(x) = n . (x - p) computed as
     * cl_v3_dot(n, x - p) (the query's d, bit for bit, with n its normal
     * and G = 0), so that a screen of many points is a dot product each
     * instead of a look at each point's memo, and a query without
     * derivatives needs neither the query nor the memo (obstacle.h). */
    void (*halfspace)(const void *shape, double n[3], double p[3]);
    /* Optional (NULL: the shape has no time of impact; response =
     * barrier and project's ccd need it): the least s in [0, 1] at which
     * the point a + s (b - a) of a segment that starts farther than
     * `offset` from the surface comes within it (the barrier asks offset
     * 0: where d reaches 0), INFINITY if it does not (a and b in the
     * shape's frame; docs/model.md, eq. C14).  A sphere and a plane answer
     * exactly, a box for the box grown by offset (exact for offset 0, a
     * little early near edges and corners otherwise), a mesh where the
     * segment crosses the surface itself, whatever the offset
     * (contact/bvh.h). */
    double (*toi)(const void *shape, const double a[3], const double b[3],
                  double offset);
    /* Allocate the drawing surface (free with cl_shape_surface_free). */
    cl_status (*surface)(const void *shape, cl_shape_surface *s,
                         cl_error *err);
    void (*free)(void *shape);
} cl_shape_type;

/* Registry (contact/registry.c), NULL-terminated. */
extern const cl_shape_type *const cl_shape_registry[];

const cl_shape_type *cl_shape_find(const char *name);

void cl_shape_surface_free(cl_shape_surface *s);

CL_END_DECLS

#endif
