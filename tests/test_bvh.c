/* Tests for contact/bvh: the tree's structure (every triangle once, leaves
 * of at most CL_BVH_LEAF, boxes nested, depth), the nearest triangle
 * against trying them all, the first crossing of a segment against trying
 * them all, and the refusals. */
#include <criterion/criterion.h>

#include "contact/bvh.h"
#include "contact/icosphere.h"
#include "contact/triangle.h"
#include "core/vec3.h"
#include "fdcheck.h"

TestSuite(bvh);

static bool box_holds(const cl_bvh_node *outer, const double lo[3],
                      const double hi[3])
{
    for (int i = 0; i < 3; i++)
        if (lo[i] < outer->lo[i] || hi[i] > outer->hi[i])
            return false;
    return true;
}

/* Walk the subtree of node id at depth `depth`: counts of triangles seen
 * in leaves; returns the deepest level. */
static int walk(const cl_bvh *b, int id, int depth, int *seen)
{
    const cl_bvh_node *nd = &b->node[id];
    if (nd->count) {
        cr_assert(nd->count <= CL_BVH_LEAF);
        for (int i = 0; i < nd->count; i++) {
            int t = b->order[nd->first + i];
            seen[t]++;
            for (int k = 0; k < 3; k++) {
                const double *v = b->vert + 3 * b->tri[t][k];
                cr_assert(box_holds(nd, v, v), "triangle %d outside its "
                          "leaf", t);
            }
        }
        return depth;
    }
    int l = id + 1, r = nd->first;
    cr_assert(box_holds(nd, b->node[l].lo, b->node[l].hi));
    cr_assert(box_holds(nd, b->node[r].lo, b->node[r].hi));
    int dl = walk(b, l, depth + 1, seen), dr = walk(b, r, depth + 1, seen);
    return dl > dr ? dl : dr;
}

Test(bvh, structure)
{
    cl_shape_surface s;
    cl_bvh b;
    cl_error err = {0};
    cr_assert_eq(cl_icosphere(4, (double[]){0, 0, 0}, 1, &s, &err), CL_OK);
    cr_assert_eq(cl_bvh_build(&b, s.vert, s.ntri, (const int(*)[3])s.tri,
                              &err), CL_OK, "%s", err.msg);
    int *seen = calloc(s.ntri, sizeof *seen);
    int depth = walk(&b, 0, 0, seen);
    for (size_t t = 0; t < s.ntri; t++)
        cr_assert_eq(seen[t], 1, "triangle %zu in %d leaves", t, seen[t]);
    cr_assert_leq(depth, (int)ceil(log2((double)s.ntri / CL_BVH_LEAF)));
    cr_assert_lt(b.nnode, 2 * s.ntri);
    free(seen);
    cl_bvh_free(&b);
    cl_shape_surface_free(&s);
}

/* An answer against the closest point of every triangle, computed here
 * without the tree's shortcuts (cl_bvh_nearest_brute shares them). */
static void check_hit(const cl_bvh *b, const double x[3],
                      const cl_bvh_hit *fast)
{
    double slow = INFINITY;
    for (size_t t = 0; t < b->ntri; t++) {
        const int *v = b->tri[t];
        cl_tri_point p;
        cl_tri_closest(x, b->vert + 3 * v[0], b->vert + 3 * v[1],
                       b->vert + 3 * v[2], &p);
        slow = fmin(slow, p.dist2);
    }
    cr_assert(fast->tri >= 0);
    cr_assert(fast->dist == sqrt(fast->p.dist2), "dist %.17g, dist2 %.17g",
              fast->dist, fast->p.dist2);
    cr_assert(fabs(sqrt(fast->p.dist2) - sqrt(slow)) <= 1e-14,
              "tree %.17g, every triangle %.17g at (%g, %g, %g)",
              sqrt(fast->p.dist2), sqrt(slow), x[0], x[1], x[2]);
}

static void same_answer(const cl_bvh *b, const double x[3])
{
    cl_bvh_hit fast;
    cl_bvh_nearest(b, x, &fast);
    check_hit(b, x, &fast);
}

/* A lumpy sphere of radii 0.6..1.4 (icosphere level 3) into s and b. */
static void lumpy_sphere(cl_shape_surface *s, cl_bvh *b)
{
    cl_error err = {0};
    fd_rng r = {9};
    cr_assert_eq(cl_icosphere(3, (double[]){0, 0, 0}, 1, s, &err), CL_OK);
    for (size_t v = 0; v < s->nvert; v++)
        for (int i = 0; i < 3; i++)
            s->vert[3 * v + i] *= 1 + 0.4 * fd_rand(&r);
    cr_assert_eq(cl_bvh_build(b, s->vert, s->ntri, (const int(*)[3])s->tri,
                              &err), CL_OK, "%s", err.msg);
}

/* A lumpy sphere (radii 0.6..1.4), points near it, far off and near its
 * vertices. */
Test(bvh, nearest_equals_brute_force)
{
    cl_shape_surface s;
    cl_bvh b;
    fd_rng r = {10};
    lumpy_sphere(&s, &b);
    for (int k = 0; k < 3000; k++) {
        double x[3];
        double scale = k % 3 == 0 ? 1.5 : k % 3 == 1 ? 20 : 0.02;
        const double *base = k % 3 == 2 ? s.vert + 3 * (k % s.nvert)
                                        : (const double[]){0, 0, 0};
        for (int i = 0; i < 3; i++)
            x[i] = base[i] + scale * fd_rand(&r);
        same_answer(&b, x);
    }
    cl_bvh_hit h;
    cl_bvh_nearest(&b, (double[]){NAN, 0, 0}, &h);
    cr_assert(h.tri >= 0 && isnan(h.p.dist2));
    cl_bvh_free(&b);
    cl_shape_surface_free(&s);
}

/* Points walking about the lumpy sphere (steps of 1e-4 to 1e-2, now and
 * then a jump): the cached answer is the nearest triangle at every step,
 * the very one cl_bvh_nearest gives (also after the anchor has moved),
 * the cache answers most steps by itself (no tree search), and a point
 * that is not a number, or infinitely far, still gets a triangle. */
Test(bvh, cached_nearest_follows_a_moving_point)
{
    cl_shape_surface s;
    cl_bvh b;
    fd_rng r = {11};
    lumpy_sphere(&s, &b);
    cl_bvh_cache cache = {0};
    double x[3] = {1.2, 0.1, 0.2};
    int steps = 20000, kept = 0;
    for (int k = 0; k < steps; k++) {
        double step = k % 997 == 0 ? 0.5 : k % 3 == 0 ? 1e-2 : 1e-4;
        for (int i = 0; i < 3; i++)
            x[i] += step * fd_rand(&r);
        cl_bvh_hit hit, plain;
        kept += cl_bvh_nearest_cached(&b, x, &cache, &hit);
        cl_bvh_nearest(&b, x, &plain);
        check_hit(&b, x, &hit);
        cr_assert_eq(hit.tri, plain.tri, "step %d", k);
    }
    cr_assert_gt(kept, steps / 2, "the cache answered %d of %d", kept,
                 steps);
    static const double odd[][3] = {{NAN, 0, 0}, {INFINITY, 0, 0},
                                    {0.5, 0.5, 0.5}};
    for (int k = 0; k < 3; k++) {
        cl_bvh_hit hit;
        cl_bvh_nearest_cached(&b, odd[k], &cache, &hit);
        cr_assert(hit.tri >= 0 && hit.tri < (int)b.ntri);
        if (k == 2)
            check_hit(&b, odd[k], &hit);
    }
    cl_bvh_free(&b);
    cl_shape_surface_free(&s);
}

/* The walk's context: a box around a point, the triangles seen. */
typedef struct {
    const cl_bvh *b;
    double lo[3], hi[3];
    int *seen;
} around;

static bool meets(const double lo[3], const double hi[3], void *ctx)
{
    const around *a = ctx;
    for (int i = 0; i < 3; i++)
        if (lo[i] > a->hi[i] || hi[i] < a->lo[i])
            return false;
    return true;
}

static void seen(int t, void *ctx)
{
    ((around *)ctx)->seen[t]++;
}

/* Walking the boxes that meet a box about a point visits every triangle
 * that meets it, each once, and far fewer than all. */
Test(bvh, walk_visits_the_boxes_entered)
{
    cl_shape_surface s;
    cl_bvh b;
    lumpy_sphere(&s, &b);
    around a = {.b = &b, .seen = calloc(s.ntri, sizeof(int))};
    cr_assert_not_null(a.seen);
    for (int i = 0; i < 3; i++) {
        a.lo[i] = (i ? 0.0 : 0.9) - 0.2;
        a.hi[i] = (i ? 0.0 : 0.9) + 0.2;
    }
    cl_bvh_walk(&b, meets, seen, &a);
    int visited = 0;
    for (size_t t = 0; t < s.ntri; t++) {
        double lo[3], hi[3];
        for (int i = 0; i < 3; i++) {
            lo[i] = INFINITY;
            hi[i] = -INFINITY;
            for (int k = 0; k < 3; k++) {
                lo[i] = fmin(lo[i], s.vert[3 * s.tri[t][k] + i]);
                hi[i] = fmax(hi[i], s.vert[3 * s.tri[t][k] + i]);
            }
        }
        cr_assert_leq(a.seen[t], 1, "triangle %zu seen %d times", t,
                      a.seen[t]);
        if (meets(lo, hi, &a))
            cr_assert_eq(a.seen[t], 1, "triangle %zu meets the box", t);
        visited += a.seen[t];
    }
    cr_assert(visited > 0 && visited < (int)s.ntri / 4, "%d of %zu",
              visited, s.ntri);
    free(a.seen);
    cl_bvh_free(&b);
    cl_shape_surface_free(&s);
}

Test(bvh, one_triangle_and_no_triangle)
{
    static const double v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const int t[1][3] = {{0, 1, 2}};
    cl_bvh b;
    cl_error err = {0};
    cr_assert_eq(cl_bvh_build(&b, v, 1, t, &err), CL_OK);
    cr_assert_eq(b.nnode, 1);
    cl_bvh_hit h;
    cl_bvh_nearest(&b, (double[]){0.25, 0.25, 2}, &h);
    cr_assert(h.tri == 0 && h.p.dist2 == 4 && h.p.feature == CL_TRI_FACE);
    cl_bvh_free(&b);
    cr_assert_eq(cl_bvh_build(&b, v, 0, t, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "of 0 triangles"), "%s", err.msg);
    cr_assert_null(b.node);
    cl_bvh_free(&b);
}

/* 2000 segments between random points of [-1.5, 1.5]^3 against an
 * icosphere of radius 1: the walk's first crossing is the least fraction
 * of all triangles'. */
Test(bvh, first_crossing_equals_brute_force)
{
    cl_shape_surface sf;
    cl_bvh b;
    cl_error err = {0};
    cr_assert_eq(cl_icosphere(3, (double[]){0, 0, 0}, 1, &sf, &err), CL_OK);
    cr_assert_eq(cl_bvh_build(&b, sf.vert, sf.ntri,
                              (const int(*)[3])sf.tri, &err), CL_OK);
    fd_rng r = {11};
    int crossings = 0;
    for (int k = 0; k < 2000; k++) {
        double p[3], q[3], d[3], best = INFINITY;
        for (int i = 0; i < 3; i++) {
            p[i] = 1.5 * fd_rand(&r);
            q[i] = 1.5 * fd_rand(&r);
            d[i] = q[i] - p[i];
        }
        for (size_t t = 0; t < sf.ntri; t++) {
            const int *v = sf.tri[t];
            best = fmin(best, cl_tri_segment(p, d, sf.vert + 3 * v[0],
                                             sf.vert + 3 * v[1],
                                             sf.vert + 3 * v[2]));
        }
        double s = cl_bvh_segment(&b, p, q);
        cr_assert_eq(s, best, "segment %d: %.17g, brute %.17g", k, s, best);
        crossings += s <= 1.0;
    }
    cr_assert_gt(crossings, 500);
    cl_bvh_free(&b);
    cl_shape_surface_free(&sf);
}
