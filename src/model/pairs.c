/* Pair connection sets on a cloth (docs/model.md, 2). */
#include "model/pairs.h"

#include <stdlib.h>
#include <string.h>

#include "model/mesh.h"

cl_status cl_pairs_from_offsets(const cl_cloth *c, size_t noff,
                                const int (*off)[2], cl_pairset *s,
                                cl_error *err)
{
    s->n = 0;
    s->pair = malloc((c->np * noff + 1) * sizeof *s->pair);
    if (!s->pair)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pairs)");
    for (int i = 0; i < c->nu; i++)
        for (int j = 0; j < c->nv; j++)
            for (size_t k = 0; k < noff; k++) {
                int i2 = i + off[k][0], j2 = j + off[k][1];
                if (i2 < 0 || i2 >= c->nu || j2 < 0 || j2 >= c->nv)
                    continue;
                cl_pair *pr = &s->pair[s->n++];
                pr->a = cl_cloth_index(c, i, j);
                pr->b = cl_cloth_index(c, i2, j2);
                pr->rest = cl_dist(c->X0 + 3 * pr->a, c->X0 + 3 * pr->b);
            }
    return CL_OK;
}

/* Offsets with di > 0, or di == 0 and dj > 0: each unordered pair once. */
cl_status cl_pairs_type1(const cl_cloth *c, cl_pairset *s, cl_error *err)
{
    static const int off[][2] = {{0, 1}, {1, -1}, {1, 0}, {1, 1}};
    return cl_pairs_from_offsets(c, 4, off, s, err);
}

cl_status cl_pairs_type2(const cl_cloth *c, cl_pairset *s, cl_error *err)
{
    static const int off[][2] = {{0, 2}, {2, -2}, {2, 0}, {2, 2}};
    return cl_pairs_from_offsets(c, 4, off, s, err);
}

size_t cl_level_offsets(long levels, int (*off)[2])
{
    size_t n = 0;
    for (int l = 1; l <= levels; l++) {
        static const int unit[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
        for (int k = 0; k < 4; k++, n++) {
            off[n][0] = l * unit[k][0];
            off[n][1] = l * unit[k][1];
        }
    }
    return n;
}

cl_status cl_pairs_levels(const cl_cloth *c, long levels, cl_pairset *s,
                          cl_error *err)
{
    long span = c->nu > c->nv ? c->nu : c->nv;
    if (levels > span - 1)
        levels = span - 1;
    int(*off)[2] = malloc((4 * (size_t)(levels > 0 ? levels : 0) + 1) *
                          sizeof *off);
    if (!off)
        return cl_error_set(err, CL_ENOMEM, "out of memory (levels)");
    cl_status rc = cl_pairs_from_offsets(c, cl_level_offsets(levels, off),
                                         (const int(*)[2])off, s, err);
    free(off);
    return rc;
}

static int cmp_pair(const void *x, const void *y)
{
    const cl_pair *p = x, *q = y;
    return p->a != q->a ? (p->a > q->a) - (p->a < q->a)
                        : (p->b > q->b) - (p->b < q->b);
}

/* Order s->pair[k] as a < b, sort by (a, b), keep each pair once, and set
 * the rest lengths. */
static void settle(const cl_cloth *c, cl_pairset *s)
{
    for (size_t k = 0; k < s->n; k++) {
        cl_pair *p = &s->pair[k];
        if (p->a > p->b) {
            int t = p->a;
            p->a = p->b;
            p->b = t;
        }
    }
    qsort(s->pair, s->n, sizeof *s->pair, cmp_pair);
    size_t kept = 0;
    for (size_t k = 0; k < s->n; k++)
        if (kept == 0 || cmp_pair(&s->pair[k], &s->pair[kept - 1]))
            s->pair[kept++] = s->pair[k];
    s->n = kept;
    for (size_t k = 0; k < s->n; k++) {
        cl_pair *p = &s->pair[k];
        p->rest = cl_dist(c->X0 + 3 * p->a, c->X0 + 3 * p->b);
    }
}

cl_status cl_pairs_mesh_edges(const cl_cloth *c, cl_pairset *s,
                              cl_error *err)
{
    s->n = 0;
    s->pair = malloc((3 * c->ntri + 1) * sizeof *s->pair);
    if (!s->pair)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pairs)");
    for (size_t t = 0; t < c->ntri; t++)
        for (int k = 0; k < 3; k++)
            s->pair[s->n++] = (cl_pair){c->tri[t][k], c->tri[t][(k + 1) % 3],
                                        0.0};
    settle(c, s);
    return CL_OK;
}

/* The far-vertex pairs of the interior edges of mesh, without those in
 * edges (sorted). */
static cl_status bend_pairs(const cl_cloth *c, const cl_mesh *mesh,
                            const cl_pairset *edges, cl_pairset *s,
                            cl_error *err)
{
    s->n = 0;
    s->pair = malloc((mesh->nedge + 1) * sizeof *s->pair);
    if (!s->pair)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pairs)");
    for (size_t k = 0; k < mesh->nedge; k++)
        if (mesh->edge[k].v[2] != mesh->edge[k].v[3])
            s->pair[s->n++] = (cl_pair){mesh->edge[k].v[2],
                                        mesh->edge[k].v[3], 0.0};
    settle(c, s);
    size_t kept = 0;
    for (size_t k = 0; k < s->n; k++) {
        const cl_pair *p = &s->pair[k];
        if (bsearch(p, edges->pair, edges->n, sizeof *p, cmp_pair))
            continue;
        if (!(p->rest > 0))
            return cl_error_set(err, CL_EINVAL,
                                "mesh vertices %d and %d, the far vertices of "
                                "two neighbouring triangles, coincide at "
                                "rest: a bend spring between them has no "
                                "direction", p->a, p->b);
        s->pair[kept++] = *p;
    }
    s->n = kept;
    return CL_OK;
}

cl_status cl_pairs_mesh_bend(const cl_cloth *c, cl_pairset *s, cl_error *err)
{
    cl_mesh mesh;
    cl_pairset edges = {0};
    *s = (cl_pairset){0};
    cl_status rc = cl_mesh_from_triangles(c->ntri, (const int(*)[3])c->tri,
                                          &mesh, err);
    if (rc)
        return rc;
    if (!(rc = cl_pairs_mesh_edges(c, &edges, err)) &&
        (rc = bend_pairs(c, &mesh, &edges, s, err)))
        cl_pairs_free(s);
    cl_pairs_free(&edges);
    cl_mesh_free(&mesh);
    return rc;
}

cl_status cl_pairs_neighbours(const cl_cloth *c, cl_pairset *s,
                              cl_error *err)
{
    return c->kind == CL_CLOTH_MESH ? cl_pairs_mesh_edges(c, s, err)
                                    : cl_pairs_type1(c, s, err);
}

cl_status cl_pairs_append(cl_pairset *s, cl_pairset *more, cl_error *err)
{
    cl_pair *all = realloc(s->pair, (s->n + more->n + 1) * sizeof *all);
    if (!all) {
        cl_pairs_free(more);
        return cl_error_set(err, CL_ENOMEM, "out of memory (pairs)");
    }
    if (more->n)
        memcpy(all + s->n, more->pair, more->n * sizeof *all);
    s->pair = all;
    s->n += more->n;
    cl_pairs_free(more);
    return CL_OK;
}

void cl_pairs_free(cl_pairset *s)
{
    free(s->pair);
    s->pair = NULL;
    s->n = 0;
}
