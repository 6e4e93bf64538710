/* Topological neighbourhoods (model/ring.h): on a grid, ring r is the
 * (2r+1) x (2r+1) block around each particle (Chebyshev distance <= r),
 * for every pair of a 7 x 5 grid and r = 1, 2, 3; on a mesh, ring 1 is
 * the triangle edges. */
#include <criterion/criterion.h>

#include <stdlib.h>

#include "model/ring.h"

Test(ring, grid_blocks)
{
    cl_cloth c;
    cl_error err = {0};
    cr_assert_eq(cl_cloth_grid(7, 5, 1.0, 1.0, 1e-3, &c, &err), CL_OK);
    for (int r = 1; r <= 3; r++) {
        cl_ring ring;
        cr_assert_eq(cl_ring_build(&c, r, &ring, &err), CL_OK, "%s",
                     err.msg);
        for (int a = 0; a < 35; a++)
            for (int b = 0; b < 35; b++) {
                if (a == b)
                    continue;
                int di = abs(a / 5 - b / 5), dj = abs(a % 5 - b % 5);
                bool want = (di > dj ? di : dj) <= r;
                cr_assert_eq(cl_ring_has(&ring, a, b), want,
                             "ring %d, particles %d and %d", r, a, b);
            }
        cl_ring_free(&ring);
    }
    cl_cloth_free(&c);
}

/* Two triangles 0-1-2 and 1-3-2 sharing edge 1-2: 0 and 3 are two steps
 * apart. */
Test(ring, mesh_edges)
{
    const double X[] = {0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 1};
    const int tri[][3] = {{0, 1, 2}, {1, 3, 2}};
    cl_cloth c;
    cl_ring ring;
    cl_error err = {0};
    cr_assert_eq(cl_cloth_mesh(4, X, 2, tri, 0.1, &c, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(cl_ring_build(&c, 1, &ring, &err), CL_OK);
    cr_assert(cl_ring_has(&ring, 0, 1) && cl_ring_has(&ring, 2, 3) &&
              cl_ring_has(&ring, 1, 2));
    cr_assert(!cl_ring_has(&ring, 0, 3) && !cl_ring_has(&ring, 3, 0));
    cl_ring_free(&ring);
    cr_assert_eq(cl_ring_build(&c, 2, &ring, &err), CL_OK);
    cr_assert(cl_ring_has(&ring, 0, 3));
    cl_ring_free(&ring);
    cr_assert_eq(cl_ring_build(&c, 0, &ring, &err), CL_EINVAL);
    cl_cloth_free(&c);
}
