/* Triangle mesh of a grid cloth and its interior edges (docs/model.md 2). */
#include "model/mesh.h"

#include <stdlib.h>
#include <string.h>

#include "io/frames.h"

/* One directed edge tri[t][k] -> tri[t][(k+1)%3], keyed by its endpoints. */
typedef struct {
    int lo, hi;
    size_t t;
    int k;
} half_edge;

static int cmp_half(const void *x, const void *y)
{
    const half_edge *a = x, *b = y;
    if (a->lo != b->lo)
        return (a->lo > b->lo) - (a->lo < b->lo);
    if (a->hi != b->hi)
        return (a->hi > b->hi) - (a->hi < b->hi);
    return (a->t > b->t) - (a->t < b->t);
}

cl_status cl_mesh_read_diagonal(cl_config *cfg, cl_diagonal *diag,
                                cl_error *err)
{
    static const char *const names[] = {"fixed", "alternate", NULL};
    int k = 0;
    cl_status rc = cl_config_choice(cfg, "cloth", "diagonal", names, 0, &k,
                                    err);
    *diag = k == 1 ? CL_DIAGONAL_ALTERNATE : CL_DIAGONAL_FIXED;
    return rc;
}

void cl_mesh_free(cl_mesh *m)
{
    free(m->tri);
    free(m->edge);
    memset(m, 0, sizeof *m);
}

static cl_status check_triangles(size_t ntri, const int (*tri)[3],
                                 cl_error *err)
{
    for (size_t t = 0; t < ntri; t++) {
        const int *v = tri[t];
        if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[0] == v[1] ||
            v[1] == v[2] || v[0] == v[2])
            return cl_error_set(err, CL_EINVAL,
                                "mesh triangle %zu (%d, %d, %d): needs three "
                                "distinct, non-negative vertices",
                                t, v[0], v[1], v[2]);
    }
    return CL_OK;
}

/* The 3*ntri directed edges, sorted by endpoints (then triangle). */
static half_edge *sorted_half_edges(const cl_mesh *m)
{
    half_edge *h = malloc((3 * m->ntri + 1) * sizeof *h);
    if (!h)
        return NULL;
    for (size_t t = 0; t < m->ntri; t++)
        for (int k = 0; k < 3; k++) {
            int a = m->tri[t][k], b = m->tri[t][(k + 1) % 3];
            h[3 * t + k] = (half_edge){a < b ? a : b, a < b ? b : a, t, k};
        }
    qsort(h, 3 * m->ntri, sizeof *h, cmp_half);
    return h;
}

/* Interior edge from the two directed edges p (first) and q. */
static cl_mesh_edge make_edge(const cl_mesh *m, const half_edge *p,
                              const half_edge *q)
{
    const int *t0 = m->tri[p->t], *t1 = m->tri[q->t];
    return (cl_mesh_edge){
        .v = {t0[p->k], t0[(p->k + 1) % 3], t0[(p->k + 2) % 3],
              t1[(q->k + 2) % 3]},
        .tri = {(int)p->t, (int)q->t}};
}

/* The interior edge, unless its two triangles are one given twice (the
 * corners opposite the edge coincide). */
static cl_status add_edge(cl_mesh *m, cl_mesh_edge e, cl_error *err)
{
    if (e.v[2] == e.v[3])
        return cl_error_set(err, CL_EINVAL, "mesh triangles %d and %d have "
                            "the same vertices (%d, %d, %d): a triangle "
                            "given twice", e.tri[0], e.tri[1], e.v[0],
                            e.v[1], e.v[2]);
    m->edge[m->nedge++] = e;
    return CL_OK;
}

static cl_status find_edges(cl_mesh *m, cl_error *err)
{
    half_edge *h = sorted_half_edges(m);
    m->edge = malloc((3 * m->ntri / 2 + 1) * sizeof *m->edge);
    if (!h || !m->edge) {
        free(h);
        return cl_error_set(err, CL_ENOMEM, "out of memory (mesh edges)");
    }
    cl_status rc = CL_OK;
    for (size_t s = 0, e; s < 3 * m->ntri && rc == CL_OK; s = e) {
        for (e = s + 1; e < 3 * m->ntri && h[e].lo == h[s].lo &&
                        h[e].hi == h[s].hi;
             e++)
            ;
        if (e - s == 1)
            m->nboundary++;
        else if (e - s == 2)
            rc = add_edge(m, make_edge(m, &h[s], &h[s + 1]), err);
        else
            rc = cl_error_set(err, CL_EINVAL,
                              "mesh edge %d-%d is shared by %zu triangles "
                              "(at most two allowed)",
                              h[s].lo, h[s].hi, e - s);
    }
    free(h);
    return rc;
}

cl_status cl_mesh_from_triangles(size_t ntri, const int (*tri)[3], cl_mesh *m,
                                 cl_error *err)
{
    memset(m, 0, sizeof *m);
    cl_status rc = check_triangles(ntri, tri, err);
    if (rc)
        return rc;
    m->tri = malloc((ntri + 1) * sizeof *m->tri);
    if (!m->tri)
        return cl_error_set(err, CL_ENOMEM, "out of memory (mesh)");
    if (ntri)
        memcpy(m->tri, tri, ntri * sizeof *tri);
    m->ntri = ntri;
    if ((rc = find_edges(m, err)))
        cl_mesh_free(m);
    return rc;
}

/* Quads with i + j odd: (a,b,c), (a,c,d) becomes (a,b,d), (b,c,d). */
static void alternate(int nv, size_t ntri, int (*tri)[3])
{
    for (size_t q = 0; 2 * q < ntri; q++) {
        int i = (int)(q / (size_t)(nv - 1)), j = (int)(q % (size_t)(nv - 1));
        if ((i + j) % 2 == 0)
            continue;
        int b = tri[2 * q][1], c = tri[2 * q][2], d = tri[2 * q + 1][2];
        tri[2 * q][2] = d;
        tri[2 * q + 1][0] = b;
        tri[2 * q + 1][1] = c;
    }
}

cl_status cl_mesh_grid(int nu, int nv, cl_diagonal diag, cl_mesh *m,
                       cl_error *err)
{
    size_t n = cl_grid_triangles(nu, nv, NULL);
    int(*tri)[3] = malloc((n + 1) * sizeof *tri);
    memset(m, 0, sizeof *m);
    if (!tri)
        return cl_error_set(err, CL_ENOMEM, "out of memory (mesh)");
    cl_grid_triangles(nu, nv, tri);
    if (diag == CL_DIAGONAL_ALTERNATE)
        alternate(nv, n, tri);
    cl_status rc = cl_mesh_from_triangles(n, (const int(*)[3])tri, m, err);
    free(tri);
    return rc;
}
