/* Tests for contact/closed: the edges and neighbours of a closed surface,
 * and the refusal of open, inconsistently oriented and non-manifold
 * triangle sets. */
#include <criterion/criterion.h>

#include <string.h>

#include "contact/closed.h"

TestSuite(closed);

/* A tetrahedron, counter-clockwise seen from outside. */
static const int tet[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

Test(closed, tetrahedron_edges_and_neighbours)
{
    cl_closed s;
    cl_error err = {0};
    cr_assert_eq(cl_closed_build(4, tet, &s, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(s.mesh.nedge, 6);
    cr_assert_eq(s.mesh.nboundary, 0);
    for (int t = 0; t < 4; t++)
        for (int k = 0; k < 3; k++) {
            int u = cl_closed_across(&s, t, k);
            cr_assert(u != t && u >= 0 && u < 4);
            /* u holds the same edge, run the other way */
            int a = tet[t][k], b = tet[t][(k + 1) % 3], found = 0;
            for (int j = 0; j < 3; j++)
                found += tet[u][j] == b && tet[u][(j + 1) % 3] == a &&
                         s.side[u][j] == s.side[t][k];
            cr_assert_eq(found, 1, "side %d of triangle %d", k, t);
        }
    cl_closed_free(&s);
}

static void refused(size_t ntri, const int (*tri)[3], const char *sub)
{
    cl_closed s;
    cl_error err = {0};
    cr_assert_eq(cl_closed_build(ntri, tri, &s, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, sub), "'%s' not in: %s", sub, err.msg);
    cr_assert_null(s.side);
}

Test(closed, open_flipped_and_non_manifold_refused)
{
    refused(3, tet, "has no other triangle: the surface is not closed");
    int flipped[4][3];
    memcpy(flipped, tet, sizeof tet);
    flipped[2][0] = 2;
    flipped[2][1] = 1;
    refused(4, (const int(*)[3])flipped, "not consistently oriented");
    /* a fifth triangle on edge 0-1 */
    const int fin[5][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2},
                           {0, 1, 4}};
    refused(5, fin, "edge 0-1 is shared by 3 triangles");
}
