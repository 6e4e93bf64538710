/* The triangle mesh of a grid cloth and its interior edges (model/mesh.c;
 * docs/model.md 2): counts on n x n grids for n = 3..40 (triangles 2(n-1)^2,
 * interior edges (n-1)(3n-5), all edges 3n^2-4n+1 = Jiao's 2n(n-1)+(n-1)^2) and
 * on rectangles and chains, for both diagonals; every triangle
 * counter-clockwise at rest; every interior edge well formed (oriented as in
 * its first triangle, reversed in its second, opposite vertices right, each
 * edge once); the fixed split equal to cl_grid_triangles, the alternate one a
 * herringbone; meshes from triangle lists (non-manifold and bad triangles
 * rejected); the [cloth] diagonal key. */
#include <criterion/criterion.h>

#include <stdlib.h>
#include <string.h>

#include "io/config.h"
#include "io/frames.h"
#include "model/mesh.h"

static cl_mesh grid_mesh(int nu, int nv, cl_diagonal d)
{
    cl_mesh m;
    cl_error err;
    cr_assert_eq(cl_mesh_grid(nu, nv, d, &m, &err), CL_OK, "%d x %d: %s", nu,
                 nv, err.msg);
    return m;
}

/* Position of a in tri (0..2), or -1. */
static int where(const int *tri, int a)
{
    for (int k = 0; k < 3; k++)
        if (tri[k] == a)
            return k;
    return -1;
}

/* Rest (u, v) = (i, j) of particle p on an nu x nv grid (unit spacing). */
static long det_uv(int nv, const int *t)
{
    long u[3], v[3];
    for (int k = 0; k < 3; k++) {
        u[k] = t[k] / nv;
        v[k] = t[k] % nv;
    }
    return (u[1] - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (v[1] - v[0]);
}

/* Every triangle counter-clockwise; every interior edge oriented as in
 * tri[0], reversed in tri[1], opposite vertices the third ones; edges
 * distinct. */
static void check_well_formed(const cl_mesh *m, int nu, int nv)
{
    for (size_t t = 0; t < m->ntri; t++) {
        cr_assert_gt(det_uv(nv, m->tri[t]), 0, "triangle %zu clockwise", t);
        for (int k = 0; k < 3; k++)
            cr_assert(m->tri[t][k] >= 0 && m->tri[t][k] < nu * nv);
    }
    char *seen = calloc((size_t)(nu * nv) * (size_t)(nu * nv), 1);
    cr_assert_not_null(seen);
    for (size_t k = 0; k < m->nedge; k++) {
        const cl_mesh_edge *e = &m->edge[k];
        const int *t0 = m->tri[e->tri[0]], *t1 = m->tri[e->tri[1]];
        cr_assert_neq(e->tri[0], e->tri[1]);
        int a0 = where(t0, e->v[0]), b0 = where(t0, e->v[1]);
        int a1 = where(t1, e->v[0]), b1 = where(t1, e->v[1]);
        cr_assert(a0 >= 0 && b0 >= 0 && a1 >= 0 && b1 >= 0);
        cr_assert_eq(b0, (a0 + 1) % 3, "edge %zu not as in its tri[0]", k);
        cr_assert_eq(a1, (b1 + 1) % 3, "edge %zu not reversed in tri[1]", k);
        cr_assert_eq(where(t0, e->v[2]), (a0 + 2) % 3);
        cr_assert_eq(where(t1, e->v[3]), (b1 + 2) % 3);
        cr_assert_eq(where(t1, e->v[2]), -1);
        cr_assert_eq(where(t0, e->v[3]), -1);
        int lo = e->v[0] < e->v[1] ? e->v[0] : e->v[1];
        int hi = e->v[0] ^ e->v[1] ^ lo;
        char *s = &seen[(size_t)lo * (size_t)(nu * nv) + (size_t)hi];
        cr_assert(!*s, "edge %d-%d twice", lo, hi);
        *s = 1;
    }
    free(seen);
}

Test(mesh, counts_square_3_to_40)
{
    for (int d = 0; d < 2; d++)
        for (long n = 3; n <= 40; n++) {
            cl_mesh m = grid_mesh((int)n, (int)n, (cl_diagonal)d);
            cr_assert_eq(m.ntri, (size_t)(2 * (n - 1) * (n - 1)), "n = %ld",
                         n);
            cr_assert_eq(m.nedge, (size_t)((n - 1) * (3 * n - 5)),
                         "n = %ld: %zu interior edges", n, m.nedge);
            cr_assert_eq(m.nboundary, (size_t)(4 * (n - 1)));
            cr_assert_eq(m.nedge + m.nboundary,
                         (size_t)(2 * n * (n - 1) + (n - 1) * (n - 1)));
            if (n <= 12)
                check_well_formed(&m, (int)n, (int)n);
            cl_mesh_free(&m);
        }
}

Test(mesh, counts_rectangles_and_chains)
{
    static const int g[][2] = {{2, 2}, {2, 7}, {5, 3}, {9, 4}, {1, 6},
                               {6, 1}};
    for (int d = 0; d < 2; d++)
        for (size_t k = 0; k < sizeof g / sizeof *g; k++) {
            long nu = g[k][0], nv = g[k][1];
            cl_mesh m = grid_mesh((int)nu, (int)nv, (cl_diagonal)d);
            long q = nu > 1 && nv > 1 ? (nu - 1) * (nv - 1) : 0;
            cr_assert_eq(m.ntri, (size_t)(2 * q));
            cr_assert_eq(m.nedge, (size_t)(q ? 3 * q - (nu - 1) - (nv - 1)
                                             : 0),
                         "%ld x %ld: %zu interior edges", nu, nv, m.nedge);
            cr_assert_eq(m.nboundary,
                         (size_t)(q ? 2 * (nu - 1) + 2 * (nv - 1) : 0));
            check_well_formed(&m, (int)nu, (int)nv);
            cl_mesh_free(&m);
        }
}

Test(mesh, fixed_split_is_the_frames_triangulation)
{
    cl_mesh m = grid_mesh(6, 5, CL_DIAGONAL_FIXED);
    size_t n = cl_grid_triangles(6, 5, NULL);
    int(*tri)[3] = malloc(n * sizeof *tri);
    cr_assert_not_null(tri);
    cl_grid_triangles(6, 5, tri);
    cr_assert_eq(m.ntri, n);
    cr_assert_eq(memcmp(m.tri, tri, n * sizeof *tri), 0);
    free(tri);
    cl_mesh_free(&m);
}

/* Quad (i, j) is split along (i,j)-(i+1,j+1) when i + j is even (and always
 * for the fixed split), along (i+1,j)-(i,j+1) otherwise. */
Test(mesh, alternate_split_is_a_herringbone)
{
    const int nu = 5, nv = 6;
    for (int d = 0; d < 2; d++) {
        cl_mesh m = grid_mesh(nu, nv, (cl_diagonal)d);
        for (int i = 0; i + 1 < nu; i++)
            for (int j = 0; j + 1 < nv; j++) {
                const int *t0 = m.tri[2 * (i * (nv - 1) + j)],
                          *t1 = m.tri[2 * (i * (nv - 1) + j) + 1];
                int a = i * nv + j, c = (i + 1) * nv + j + 1;
                int b = (i + 1) * nv + j, dd = i * nv + j + 1;
                bool ac = d == CL_DIAGONAL_FIXED || (i + j) % 2 == 0;
                int p = ac ? a : b, q = ac ? c : dd;
                cr_assert(where(t0, p) >= 0 && where(t0, q) >= 0 &&
                              where(t1, p) >= 0 && where(t1, q) >= 0,
                          "quad (%d,%d), diagonal %d", i, j, d);
            }
        cl_mesh_free(&m);
    }
}

Test(mesh, from_triangles_rejects_bad_input)
{
    static const int fan[3][3] = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    static const int bad[1][3] = {{0, 0, 2}};
    static const int neg[1][3] = {{0, -1, 2}};
    cl_mesh m;
    cl_error err;
    cr_assert_eq(cl_mesh_from_triangles(3, fan, &m, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "0-1") && strstr(err.msg, "3 triangles"),
              "%s", err.msg);
    cr_assert_eq(cl_mesh_from_triangles(1, bad, &m, &err), CL_EINVAL);
    cr_assert_eq(cl_mesh_from_triangles(1, neg, &m, &err), CL_EINVAL);
    /* Two triangles: one interior edge, four boundary edges. */
    cr_assert_eq(cl_mesh_from_triangles(2, fan, &m, &err), CL_OK);
    cr_assert_eq(m.nedge, 1);
    cr_assert_eq(m.nboundary, 4);
    const int want[4] = {0, 1, 2, 3};
    cr_assert_eq(memcmp(m.edge[0].v, want, sizeof want), 0);
    cl_mesh_free(&m);
    cr_assert_eq(cl_mesh_from_triangles(0, NULL, &m, &err), CL_OK);
    cr_assert_eq(m.ntri + m.nedge + m.nboundary, 0);
    cl_mesh_free(&m);
}

Test(mesh, diagonal_key)
{
    static const struct {
        const char *set;
        cl_status rc;
        cl_diagonal d;
    } cases[] = {{NULL, CL_OK, CL_DIAGONAL_FIXED},
                 {"cloth.diagonal=fixed", CL_OK, CL_DIAGONAL_FIXED},
                 {"cloth.diagonal=alternate", CL_OK, CL_DIAGONAL_ALTERNATE},
                 {"cloth.diagonal=both", CL_EINVAL, CL_DIAGONAL_FIXED}};
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        cl_config *cfg = cl_config_alloc();
        cl_error err;
        cl_diagonal d = CL_DIAGONAL_ALTERNATE;
        cr_assert_not_null(cfg);
        if (cases[k].set)
            cr_assert_eq(cl_config_set(cfg, cases[k].set, &err), CL_OK);
        cr_assert_eq(cl_mesh_read_diagonal(cfg, &d, &err), cases[k].rc);
        if (cases[k].rc == CL_OK)
            cr_assert_eq(d, cases[k].d);
        else
            cr_assert(strstr(err.msg, "fixed") &&
                      strstr(err.msg, "alternate"), "%s", err.msg);
        cl_config_free(cfg);
    }
}
