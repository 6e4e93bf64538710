/* Bounding-volume hierarchy of a triangle mesh (contact/bvh.h). */
#include "contact/bvh.h"

#include <limits.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "contact/segment.h"
#include "core/vec3.h"

/* Pending nodes of a query: at most one per level plus one (depth <= 30). */
#define STACK 64

typedef struct {
    int node;
    double d2;      /* squared distance from the point to its box */
} pending;

void cl_bvh_free(cl_bvh *b)
{
    free(b->order);
    free(b->node);
    free(b->normal);
    free(b->geom);
    *b = (cl_bvh){0};
}

/* The bounds of the triangles idx[0..n). */
static void node_bounds(const cl_bvh *b, cl_bvh_node *nd, const int *idx,
                        int n)
{
    for (int i = 0; i < 3; i++) {
        nd->lo[i] = INFINITY;
        nd->hi[i] = -INFINITY;
    }
    for (int t = 0; t < n; t++)
        for (int k = 0; k < 3; k++) {
            const double *v = b->vert + 3 * b->tri[idx[t]][k];
            for (int i = 0; i < 3; i++) {
                nd->lo[i] = fmin(nd->lo[i], v[i]);
                nd->hi[i] = fmax(nd->hi[i], v[i]);
            }
        }
}

/* The axis along which the centroids of idx[0..n) spread most. */
static int longest_axis(const double *cent, const int *idx, int n)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY};
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int t = 0; t < n; t++)
        for (int i = 0; i < 3; i++) {
            lo[i] = fmin(lo[i], cent[3 * idx[t] + i]);
            hi[i] = fmax(hi[i], cent[3 * idx[t] + i]);
        }
    int axis = 0;
    for (int i = 1; i < 3; i++)
        if (hi[i] - lo[i] > hi[axis] - lo[axis])
            axis = i;
    return axis;
}

/* Reorder a[0..n) so that a[k] has the k-th least key (key[3 a[i]]), none
 * before it a greater one and none after it a smaller one (Hoare's FIND,
 * as given by Wirth, "Algorithms + Data Structures = Programs", 1976). */
static void select_nth(int *a, long n, long k, const double *key)
{
    long l = 0, r = n - 1;
    while (l < r) {
        double x = key[3 * a[k]];
        long i = l, j = r;
        do {
            while (key[3 * a[i]] < x)
                i++;
            while (x < key[3 * a[j]])
                j--;
            if (i <= j) {
                int s = a[i];
                a[i++] = a[j];
                a[j--] = s;
            }
        } while (i <= j);
        if (j < k)
            l = i;
        if (k < i)
            r = j;
    }
}

/* The subtree of order[first .. first + n), depth first; its root. */
static int build_node(cl_bvh *b, const double *cent, int first, int n)
{
    int id = (int)b->nnode++;
    node_bounds(b, &b->node[id], b->order + first, n);
    if (n <= CL_BVH_LEAF) {
        b->node[id].first = first;
        b->node[id].count = n;
        return id;
    }
    int half = n / 2;
    select_nth(b->order + first, n, half,
               cent + longest_axis(cent, b->order + first, n));
    b->node[id].count = 0;
    build_node(b, cent, first, half);
    b->node[id].first = build_node(b, cent, first + half, n - half);
    return id;
}

cl_status cl_bvh_build(cl_bvh *b, const double *vert, size_t ntri,
                       const int (*tri)[3], cl_error *err)
{
    *b = (cl_bvh){.vert = vert, .tri = tri, .ntri = ntri};
    if (ntri < 1 || ntri > INT_MAX / 2)
        return cl_error_set(err, CL_EINVAL, "bounding-volume tree of %zu "
                            "triangles: need 1 to %d", ntri, INT_MAX / 2);
    double *cent = malloc(3 * ntri * sizeof *cent);
    b->order = malloc(ntri * sizeof *b->order);
    b->node = malloc(2 * ntri * sizeof *b->node);
    b->normal = malloc(ntri * sizeof *b->normal);
    b->geom = malloc(ntri * sizeof *b->geom);
    if (!cent || !b->order || !b->node || !b->normal || !b->geom) {
        free(cent);
        cl_bvh_free(b);
        return cl_error_set(err, CL_ENOMEM, "out of memory (bounding-volume "
                            "tree of %zu triangles)", ntri);
    }
    for (size_t t = 0; t < ntri; t++) {
        b->order[t] = (int)t;
        cl_v3_tri_cross(vert + 3 * tri[t][0], vert + 3 * tri[t][1],
                        vert + 3 * tri[t][2], b->normal[t]);
        cl_v3_normalize(b->normal[t]);
        cl_tri_geom_set(vert + 3 * tri[t][0], vert + 3 * tri[t][1],
                        vert + 3 * tri[t][2], &b->geom[t]);
        for (int i = 0; i < 3; i++)
            cent[3 * t + i] = (vert[3 * tri[t][0] + i] +
                               vert[3 * tri[t][1] + i] +
                               vert[3 * tri[t][2] + i]) / 3.0;
    }
    build_node(b, cent, 0, (int)ntri);
    free(cent);
    return CL_OK;
}

/* Squared distance from x to the node's box (0 inside). */
static inline double box_dist2(const cl_bvh_node *nd, const double x[3])
{
    return cl_box_dist2(nd->lo, nd->hi, x);
}

/* The triangles nearest to a point found so far: at most cap of them
 * (cap <= CL_BVH_KEEP), their closest points by ascending distance. */
typedef struct {
    int cap, n;
    int tri[CL_BVH_KEEP];
    cl_tri_point p[CL_BVH_KEEP];
} kept;

/* An empty list of at most cap: its counts and its first entry (the
 * answer read from it) are set, not the whole list (hundreds of bytes),
 * which a query would otherwise clear every time. */
static void kept_start(kept *k, int cap)
{
    k->cap = cap;
    k->n = 0;
    k->tri[0] = 0;
    k->p[0] = (cl_tri_point){.dist2 = INFINITY};
}

/* Whether something at squared distance d2 cannot be kept: the list is
 * full and its last is nearer.  (Not while there is room, so that a point
 * at an infinite distance still gets a triangle.) */
static bool farther(const kept *k, double d2)
{
    return k->n == k->cap && d2 > k->p[k->n - 1].dist2;
}

/* The order of the list: by distance, then by index, so that the answer
 * does not depend on the order the triangles are tried in.  Whether
 * triangle t at squared distance d2 comes before triangle u at e2. */
static bool precedes(double d2, int t, double e2, int u)
{
    return d2 < e2 || (d2 == e2 && t < u);
}

/* Whether triangle t at squared distance d2 comes before entry i. */
static bool before(double d2, int t, const kept *k, int i)
{
    return precedes(d2, t, k->p[i].dist2, k->tri[i]);
}

/* The closest point of triangle t to x. */
static void measure(const cl_bvh *b, int t, const double x[3],
                    cl_tri_point *p)
{
    cl_tri_closest_geom(x, &b->geom[t], p);
}

/* Keep triangle t, at p, if there is room or it comes before the last (so
 * also when the distances are not numbers: a non-finite point still gets
 * a triangle). */
static void keep(kept *k, int t, const cl_tri_point *p)
{
    if (k->n == k->cap && !before(p->dist2, t, k, k->n - 1))
        return;
    int i = k->n < k->cap ? k->n++ : k->n - 1;
    for (; i > 0 && before(p->dist2, t, k, i - 1); i--) {
        k->tri[i] = k->tri[i - 1];
        k->p[i] = k->p[i - 1];
    }
    k->tri[i] = t;
    k->p[i] = *p;
}

/* keep() triangle t unless its plane already shows it is too far. */
static void try_triangle(const cl_bvh *b, int t, const double x[3],
                         kept *k)
{
    double ap[3];
    cl_v3_sub(x, b->geom[t].a, ap);
    double hgt = cl_v3_dot(ap, b->normal[t]);
    if (farther(k, hgt * hgt))
        return;
    cl_tri_point p;
    measure(b, t, x, &p);
    keep(k, t, &p);
}

/* Whether t is among list[0..n). */
static bool listed(const int *list, int n, int t)
{
    for (int i = 0; i < n; i++)
        if (list[i] == t)
            return true;
    return false;
}

/* Branch and bound for the k->cap nearest triangles, the nskip of skip
 * already tried (in k). */
static void nearest_kept(const cl_bvh *b, const double x[3], const int *skip,
                         int nskip, kept *k)
{
    pending stack[STACK];
    int top = 0;
    stack[top++] = (pending){0, box_dist2(&b->node[0], x)};
    while (top > 0) {
        pending e = stack[--top];
        const cl_bvh_node *nd = &b->node[e.node];
        if (farther(k, e.d2))
            continue;
        for (int i = 0; i < nd->count; i++) {
            int t = b->order[nd->first + i];
            if (!listed(skip, nskip, t))
                try_triangle(b, t, x, k);
        }
        if (nd->count)
            continue;
        pending l = {e.node + 1, box_dist2(&b->node[e.node + 1], x)};
        pending r = {nd->first, box_dist2(&b->node[nd->first], x)};
        stack[top++] = l.d2 <= r.d2 ? r : l;   /* the farther one first */
        stack[top++] = l.d2 <= r.d2 ? l : r;
    }
}

static void hit_of(const kept *k, cl_bvh_hit *hit)
{
    hit->tri = k->tri[0];
    hit->p = k->p[0];
    hit->dist = sqrt(k->p[0].dist2);
}

void cl_bvh_nearest(const cl_bvh *b, const double x[3], cl_bvh_hit *hit)
{
    kept k;
    kept_start(&k, 1);
    nearest_kept(b, x, NULL, 0, &k);
    hit_of(&k, hit);
}

/* Move the cache's anchor to x, where the first ntried of its n kept
 * triangles were measured (at[]): their distances there, and for the
 * others their distances at the old anchor less the distance moved, lower
 * bounds of their distances at x (the distance to a triangle is
 * 1-Lipschitz), as r0 less it is for the triangles not kept.  The kept
 * ones are sorted by these again, without measuring any (bvh.h). */
static void reanchor(const double x[3], double moved, int ntried,
                     const cl_tri_point at[CL_BVH_KEEP], cl_bvh_cache *c)
{
    double dist[CL_BVH_KEEP];
    int tri[CL_BVH_KEEP];
    for (int i = 0; i < c->n; i++) {
        double d = i < ntried ? sqrt(at[i].dist2) : c->dist[i] - moved;
        int j = i;
        for (; j > 0 && d < dist[j - 1]; j--) {
            dist[j] = dist[j - 1];
            tri[j] = tri[j - 1];
        }
        dist[j] = d;
        tri[j] = c->tri[i];
    }
    memcpy(c->x0, x, sizeof c->x0);
    memcpy(c->dist, dist, sizeof dist); /* whole: a fixed size, inlined */
    memcpy(c->tri, tri, sizeof tri);
    c->r0 -= moved;
}

/* Whether a triangle whose distance is at least `low` may be within the
 * distance sqrt(best2) of the best so far: low <= sqrt(best2) without the
 * square root, in squares with a slack of 1e-12 relative that covers
 * their rounding (a triangle that low <= sqrt(best2) lets through is let
 * through; one more let through is measured and found farther), so that
 * the loop over the kept triangles does not wait for a square root. */
static inline bool may_be_within(double low, double best2)
{
    return low <= 0.0 || low * low <= best2 * (1.0 + 1e-12);
}

/* The answer from the cache alone, if its certificate holds at x; the
 * anchor moves to x when more than CL_BVH_TRIED kept triangles had to be
 * tried (bvh.h). */
static bool nearest_from_cache(const cl_bvh *b, const double x[3],
                               cl_bvh_cache *c, cl_bvh_hit *hit)
{
    double e[3], best2 = INFINITY;
    cl_tri_point at[CL_BVH_KEEP];
    int first = 0;  /* the first of those measured in the list's order */
    cl_v3_sub(x, c->x0, e);
    double moved = sqrt(cl_v3_dot(e, e));
    int i = 0;
    for (; i < c->n && may_be_within(c->dist[i] - moved, best2); i++) {
        measure(b, c->tri[i], x, &at[i]);
        if (i == 0 ||
            precedes(at[i].dist2, c->tri[i], at[first].dist2, c->tri[first])) {
            first = i;
            best2 = at[first].dist2;
        }
    }
    double best = i > 0 ? sqrt(best2) : INFINITY;
    if (!(best < c->r0 - moved))
        return false;
    hit->tri = c->tri[first];
    hit->p = at[first];
    hit->dist = best;
    if (i > CL_BVH_TRIED)
        reanchor(x, moved, i, at, c);
    return true;
}

bool cl_bvh_nearest_cached(const cl_bvh *b, const double x[3],
                           cl_bvh_cache *cache, cl_bvh_hit *hit)
{
    if (cache->n > 0 && nearest_from_cache(b, x, cache, hit))
        return true;
    kept k;
    kept_start(&k, CL_BVH_KEEP);
    for (int i = 0; i < cache->n; i++)  /* a warm start: a tighter bound */
        try_triangle(b, cache->tri[i], x, &k);
    nearest_kept(b, x, cache->tri, cache->n, &k);
    memcpy(cache->x0, x, sizeof cache->x0);
    cache->n = k.n;
    for (int i = 0; i < k.n; i++) {
        cache->tri[i] = k.tri[i];
        cache->dist[i] = sqrt(k.p[i].dist2);
    }
    cache->r0 = k.n < k.cap ? INFINITY : cache->dist[k.n - 1];
    hit_of(&k, hit);
    return false;
}

/* The fraction at which x0 + a D enters the node's box widened by pad
 * (0 if x0 is inside), INFINITY if the segment misses it. */
static double box_entry(const cl_bvh_node *nd, const double x0[3],
                        const double D[3], double pad)
{
    double lo[3], hi[3], a;
    for (int i = 0; i < 3; i++) {
        lo[i] = nd->lo[i] - pad;
        hi[i] = nd->hi[i] + pad;
    }
    return cl_segment_box(lo, hi, x0, D, 1.0, &a) ? a : INFINITY;
}

double cl_bvh_segment(const cl_bvh *b, const double x0[3],
                      const double x1[3])
{
    double D[3], best = INFINITY;
    cl_v3_sub(x1, x0, D);
    double pad = 1e-9 * cl_v3_norm(D);
    pending stack[STACK];
    int top = 0;
    stack[top++] = (pending){0, box_entry(&b->node[0], x0, D, pad)};
    while (top > 0) {
        pending e = stack[--top];
        const cl_bvh_node *nd = &b->node[e.node];
        if (e.d2 == INFINITY || e.d2 > best) /* d2: the entry fraction */
            continue;
        for (int i = 0; i < nd->count; i++) {
            const int *t = b->tri[b->order[nd->first + i]];
            best = fmin(best, cl_tri_segment(x0, D, b->vert + 3 * t[0],
                                             b->vert + 3 * t[1],
                                             b->vert + 3 * t[2]));
        }
        if (nd->count)
            continue;
        pending l = {e.node + 1, box_entry(&b->node[e.node + 1], x0, D, pad)};
        pending r = {nd->first, box_entry(&b->node[nd->first], x0, D, pad)};
        stack[top++] = l.d2 <= r.d2 ? r : l;   /* the farther one first */
        stack[top++] = l.d2 <= r.d2 ? l : r;
    }
    return best;
}

double cl_bvh_box_distance(const cl_bvh *b, const double x[3])
{
    return sqrt(box_dist2(&b->node[0], x));
}

void cl_bvh_walk(const cl_bvh *b,
                 bool (*enter)(const double lo[3], const double hi[3],
                               void *ctx),
                 void (*visit)(int t, void *ctx), void *ctx)
{
    int stack[STACK], top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const cl_bvh_node *nd = &b->node[stack[--top]];
        if (!enter(nd->lo, nd->hi, ctx))
            continue;
        for (int i = 0; i < nd->count; i++)
            visit(b->order[nd->first + i], ctx);
        if (nd->count)
            continue;
        stack[top++] = nd->first;
        stack[top++] = (int)(nd - b->node) + 1;
    }
}

void cl_bvh_nearest_brute(const cl_bvh *b, const double x[3],
                          cl_bvh_hit *hit)
{
    kept k;
    kept_start(&k, 1);
    for (size_t t = 0; t < b->ntri; t++)
        try_triangle(b, (int)t, x, &k);
    hit_of(&k, hit);
}
