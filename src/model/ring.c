/* Topological neighbourhoods (model/ring.h): a breadth-first search to
 * depth `ring` from every particle over the nearest-neighbour graph. */
#include "model/ring.h"

#include <stdlib.h>
#include <string.h>

#include "model/pairs.h"

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* The graph in compressed rows: adj[off[p] .. off[p+1]). */
typedef struct {
    size_t *off;
    int *adj;
} ring_graph;

static cl_status graph_build(const cl_cloth *c, ring_graph *g, cl_error *err)
{
    cl_pairset s = {0};
    cl_status rc = cl_pairs_neighbours(c, &s, err);
    if (rc)
        return rc;
    g->off = calloc(c->np + 1, sizeof *g->off);
    g->adj = malloc((2 * s.n + 1) * sizeof *g->adj);
    if (!g->off || !g->adj) {
        cl_pairs_free(&s);
        return cl_error_set(err, CL_ENOMEM, "out of memory (neighbours)");
    }
    for (size_t k = 0; k < s.n; k++) {
        g->off[s.pair[k].a + 1]++;
        g->off[s.pair[k].b + 1]++;
    }
    for (size_t p = 0; p < c->np; p++)
        g->off[p + 1] += g->off[p];
    size_t *fill = malloc((c->np + 1) * sizeof *fill);
    if (!fill) {
        cl_pairs_free(&s);
        return cl_error_set(err, CL_ENOMEM, "out of memory (neighbours)");
    }
    memcpy(fill, g->off, c->np * sizeof *fill);
    for (size_t k = 0; k < s.n; k++) {
        g->adj[fill[s.pair[k].a]++] = s.pair[k].b;
        g->adj[fill[s.pair[k].b]++] = s.pair[k].a;
    }
    free(fill);
    cl_pairs_free(&s);
    return CL_OK;
}

/* The particles within `ring` steps of p (p excluded) into out, sorted;
 * seen[] holds p + 1 for those already reached from p.  Returns their
 * number. */
static size_t reach(const ring_graph *g, int p, int ring, size_t *seen,
                    int *out)
{
    size_t n = 0, lo = 0;
    seen[p] = (size_t)p + 1;
    out[n++] = p;
    for (int step = 0; step < ring; step++) {
        size_t hi = n;
        for (size_t k = lo; k < hi; k++)
            for (size_t e = g->off[out[k]]; e < g->off[out[k] + 1]; e++) {
                int q = g->adj[e];
                if (seen[q] != (size_t)p + 1) {
                    seen[q] = (size_t)p + 1;
                    out[n++] = q;
                }
            }
        lo = hi;
    }
    memmove(out, out + 1, (n - 1) * sizeof *out);
    qsort(out, n - 1, sizeof *out, cmp_int);
    return n - 1;
}

/* Two passes over the particles: count, then fill. */
static cl_status ring_fill(const ring_graph *g, cl_ring *r, size_t *seen,
                           int *buf, cl_error *err)
{
    size_t total = 0;
    for (size_t p = 0; p < r->np; p++)
        total += reach(g, (int)p, r->ring, seen, buf);
    r->nb = malloc((total + 1) * sizeof *r->nb);
    if (!r->nb)
        return cl_error_set(err, CL_ENOMEM, "out of memory (neighbours)");
    memset(seen, 0, r->np * sizeof *seen);
    r->start[0] = 0;
    for (size_t p = 0; p < r->np; p++) {
        size_t n = reach(g, (int)p, r->ring, seen, buf);
        memcpy(r->nb + r->start[p], buf, n * sizeof *buf);
        r->start[p + 1] = r->start[p] + n;
    }
    return CL_OK;
}

cl_status cl_ring_build(const cl_cloth *c, int ring, cl_ring *r,
                        cl_error *err)
{
    *r = (cl_ring){.np = c->np, .ring = ring};
    if (ring < 1)
        return cl_error_set(err, CL_EINVAL, "ring = %d: need >= 1", ring);
    ring_graph g = {0};
    cl_status rc = graph_build(c, &g, err);
    size_t *seen = calloc(c->np + 1, sizeof *seen);
    int *buf = malloc((c->np + 1) * sizeof *buf);
    r->start = malloc((c->np + 1) * sizeof *r->start);
    if (!rc && (!seen || !buf || !r->start))
        rc = cl_error_set(err, CL_ENOMEM, "out of memory (neighbours)");
    if (!rc)
        rc = ring_fill(&g, r, seen, buf, err);
    free(seen);
    free(buf);
    free(g.off);
    free(g.adj);
    if (rc)
        cl_ring_free(r);
    return rc;
}

void cl_ring_free(cl_ring *r)
{
    free(r->start);
    free(r->nb);
    *r = (cl_ring){0};
}

bool cl_ring_has(const cl_ring *r, int a, int b)
{
    const int *lo = r->nb + r->start[a];
    return bsearch(&b, lo, r->start[a + 1] - r->start[a], sizeof b,
                   cmp_int) != NULL;
}
