/* Closed, consistently oriented triangle surfaces (contact/closed.h). */
#include "contact/closed.h"

#include <stdlib.h>

void cl_closed_free(cl_closed *s)
{
    cl_mesh_free(&s->mesh);
    free(s->side);
    s->side = NULL;
}

/* The side of triangle t running from vertex a to vertex b, or -1. */
static int side_from_to(const int *t, int a, int b)
{
    for (int k = 0; k < 3; k++)
        if (t[k] == a && t[(k + 1) % 3] == b)
            return k;
    return -1;
}

/* Record edge e on its two triangles: the first runs it v[0] -> v[1], the
 * second must run it back. */
static cl_status mark_edge(cl_closed *s, const int (*tri)[3], int e,
                           cl_error *err)
{
    const cl_mesh_edge *ed = &s->mesh.edge[e];
    int k0 = side_from_to(tri[ed->tri[0]], ed->v[0], ed->v[1]);
    int k1 = side_from_to(tri[ed->tri[1]], ed->v[1], ed->v[0]);
    if (k1 < 0)
        return cl_error_set(err, CL_EINVAL, "triangles %d and %d run their "
                            "common edge %d-%d the same way: they are not "
                            "consistently oriented", ed->tri[0], ed->tri[1],
                            ed->v[0], ed->v[1]);
    s->side[ed->tri[0]][k0] = e;
    s->side[ed->tri[1]][k1] = e;
    return CL_OK;
}

/* Every side has an edge, or the surface has a hole. */
static cl_status check_closed(const cl_closed *s, size_t ntri,
                              const int (*tri)[3], cl_error *err)
{
    for (size_t t = 0; t < ntri; t++)
        for (int k = 0; k < 3; k++)
            if (s->side[t][k] < 0)
                return cl_error_set(err, CL_EINVAL, "edge %d-%d of triangle "
                                    "%zu has no other triangle: the surface "
                                    "is not closed", tri[t][k],
                                    tri[t][(k + 1) % 3], t);
    return CL_OK;
}

cl_status cl_closed_build(size_t ntri, const int (*tri)[3], cl_closed *s,
                          cl_error *err)
{
    s->side = NULL;
    cl_status rc = cl_mesh_from_triangles(ntri, tri, &s->mesh, err);
    if (rc)
        return rc;
    s->side = malloc((ntri + 1) * sizeof *s->side);
    if (!s->side) {
        cl_closed_free(s);
        return cl_error_set(err, CL_ENOMEM, "out of memory (surface of %zu "
                            "triangles)", ntri);
    }
    for (size_t t = 0; t < ntri; t++)
        s->side[t][0] = s->side[t][1] = s->side[t][2] = -1;
    for (size_t e = 0; e < s->mesh.nedge && !rc; e++)
        rc = mark_edge(s, tri, (int)e, err);
    if (!rc)
        rc = check_closed(s, ntri, tri, err);
    if (rc)
        cl_closed_free(s);
    return rc;
}

int cl_closed_across(const cl_closed *s, int t, int k)
{
    const cl_mesh_edge *e = &s->mesh.edge[s->side[t][k]];
    return e->tri[0] == t ? e->tri[1] : e->tri[0];
}
