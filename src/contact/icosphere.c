/* The icosphere (contact/icosphere.h): the icosahedron, then splits of
 * every triangle into four at its edge midpoints, pushed onto the unit
 * sphere; scaled and moved at the end. */
#include "contact/icosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/closed.h"
#include "contact/shape_impl.h"
#include "core/vec3.h"

#define MAX_LEVEL 8

/* The icosahedron's vertices are the cyclic permutations of
 * (0, +-1, +-phi), phi the golden ratio; its faces, counter-clockwise seen
 * from outside. */
static const int ico_tri[20][3] = {
    {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};

static cl_status icosahedron(cl_shape_surface *s, cl_error *err)
{
    const double p = (1.0 + sqrt(5.0)) / 2.0;
    const double v[12][3] = {{-1, p, 0}, {1, p, 0},  {-1, -p, 0}, {1, -p, 0},
                             {0, -1, p}, {0, 1, p},  {0, -1, -p}, {0, 1, -p},
                             {p, 0, -1}, {p, 0, 1},  {-p, 0, -1}, {-p, 0, 1}};
    cl_status rc = cl_shape_surface_alloc(s, 12, 20, ico_tri, err);
    if (rc)
        return rc;
    memcpy(s->vert, v, sizeof v);
    for (size_t k = 0; k < 12; k++)
        cl_v3_normalize(s->vert + 3 * k);
    return CL_OK;
}

/* Triangle (a, b, c) with side midpoints m0 (ab), m1 (bc), m2 (ca) as
 * four triangles of the same orientation. */
static void split_triangle(const int t[3], const int m[3], int (*out)[3])
{
    const int q[4][3] = {{t[0], m[0], m[2]},
                         {m[0], t[1], m[1]},
                         {m[2], m[1], t[2]},
                         {m[0], m[1], m[2]}};
    memcpy(out, q, sizeof q);
}

/* One level: a vertex on the unit sphere above every edge midpoint. */
static cl_status subdivide(cl_shape_surface *s, cl_error *err)
{
    cl_closed c;
    cl_status rc = cl_closed_build(s->ntri, (const int(*)[3])s->tri, &c, err);
    if (rc)
        return rc;
    size_t nv = s->nvert, ne = c.mesh.nedge;
    double *vert = realloc(s->vert, 3 * (nv + ne) * sizeof *vert);
    int(*tri)[3] = malloc(4 * s->ntri * sizeof *tri);
    if (vert)
        s->vert = vert;
    if (!vert || !tri) {
        free(tri);
        cl_closed_free(&c);
        return cl_error_set(err, CL_ENOMEM, "out of memory (icosphere)");
    }
    for (size_t e = 0; e < ne; e++) {
        const int *v = c.mesh.edge[e].v;
        double *m = vert + 3 * (nv + e);
        for (int i = 0; i < 3; i++)
            m[i] = vert[3 * v[0] + i] + vert[3 * v[1] + i];
        cl_v3_normalize(m);
    }
    for (size_t t = 0; t < s->ntri; t++) {
        int m[3];
        for (int k = 0; k < 3; k++)
            m[k] = (int)nv + c.side[t][k];
        split_triangle(s->tri[t], m, tri + 4 * t);
    }
    free(s->tri);
    s->tri = tri;
    s->nvert = nv + ne;
    s->ntri *= 4;
    cl_closed_free(&c);
    return CL_OK;
}

cl_status cl_icosphere(int level, const double centre[3], double radius,
                       cl_shape_surface *s, cl_error *err)
{
    *s = (cl_shape_surface){0};
    if (level < 0 || level > MAX_LEVEL || !(radius > 0) || !isfinite(radius))
        return cl_error_set(err, CL_EINVAL, "icosphere of level %d, radius "
                            "%g: need level 0..%d, radius > 0", level, radius,
                            MAX_LEVEL);
    cl_status rc = icosahedron(s, err);
    for (int l = 0; l < level && !rc; l++)
        rc = subdivide(s, err);
    if (rc) {
        cl_shape_surface_free(s);
        return rc;
    }
    for (size_t k = 0; k < s->nvert; k++)
        cl_v3_axpy(centre, radius, s->vert + 3 * k, s->vert + 3 * k);
    return CL_OK;
}
