/* Tests for contact/meshfeat: the clearances of a convex icosphere
 * (infinite), of lumpy, non-convex ones (most zero, some finite), of two
 * spheres and of two finely split cubes in one mesh (finite where they
 * face each other, under half the gap); every answer a feature or the
 * walk gives, tried at random points about the last three, equal to the
 * nearest distance by brute force; the walk to a neighbour's region. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/icosphere.h"
#include "contact/meshfeat.h"
#include "contact/shape_impl.h"
#include "contact/triangle.h"
#include "core/vec3.h"
#include "fdcheck.h"
#include "shapecheck.h"

TestSuite(meshfeat);

typedef struct {
    cl_shape_surface sf;
    cl_bvh b;
    cl_closed s;
    cl_meshfeat f;
} built;

/* The regions of a surface none of whose faces are coplanar and all of
 * whose vertices are corners (an icosphere, lumpy or not). */
static void build(built *m)
{
    cl_error err = {0};
    size_t nt = m->sf.ntri, nv = m->sf.nvert;
    const int(*tri)[3] = (const int(*)[3])m->sf.tri;
    cr_assert_eq(cl_bvh_build(&m->b, m->sf.vert, nt, tri, &err), CL_OK);
    cr_assert_eq(cl_closed_build(nt, tri, &m->s, &err), CL_OK, "%s",
                 err.msg);
    unsigned char *flat = calloc(3 * nt, 1), *corner = malloc(nv);
    cr_assert(flat && corner);
    memset(corner, 1, nv);
    cr_assert_eq(cl_meshfeat_build(&m->f, &m->b, &m->s, nv, flat, corner,
                                   1e-12, &err), CL_OK);
    free(flat);
    free(corner);
}

static void release(built *m)
{
    cl_meshfeat_free(&m->f);
    cl_closed_free(&m->s);
    cl_bvh_free(&m->b);
    cl_shape_surface_free(&m->sf);
}

static void icosphere(built *m, int level, double lumps, unsigned long seed)
{
    cl_error err = {0};
    cr_assert_eq(cl_icosphere(level, (double[]){0, 0, 0}, 1, &m->sf, &err),
                 CL_OK);
    fd_rng r = {seed};
    for (size_t v = 0; v < m->sf.nvert; v++) {
        double k = 1 + lumps * fd_rand(&r);
        for (int i = 0; i < 3; i++)
            m->sf.vert[3 * v + i] *= k;
    }
    build(m);
}

static size_t nfeat(const cl_meshfeat *f)
{
    return f->nface + f->nedge + f->nvert;
}

static double clearance(const cl_meshfeat *f, size_t id)
{
    if (id < f->nface)
        return f->face[id].h;
    if ((id -= f->nface) < f->nedge)
        return f->edge[id].h;
    return f->vert[id - f->nedge].h;
}

Test(meshfeat, convex_icosphere_clears_every_feature)
{
    built m;
    icosphere(&m, 3, 0, 1);
    cr_assert_eq(m.f.nface, 1280);
    cr_assert_eq(m.f.nedge, 1920);
    cr_assert_eq(m.f.nvert, 642);
    for (size_t id = 0; id < nfeat(&m.f); id++)
        cr_assert(isinf(clearance(&m.f, id)), "feature %zu: h = %g", id,
                  clearance(&m.f, id));
    release(&m);
}

/* A point within `spread` of a random point of triangle t. */
static void near_triangle(const cl_shape_surface *sf, int t, double spread,
                          fd_rng *r, double x[3])
{
    double u = 0.5 + 0.5 * fd_rand(r), v = 0.5 + 0.5 * fd_rand(r);
    if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
    }
    const double *a = sf->vert + 3 * sf->tri[t][0];
    const double *b = sf->vert + 3 * sf->tri[t][1];
    const double *c = sf->vert + 3 * sf->tri[t][2];
    for (int i = 0; i < 3; i++)
        x[i] = a[i] + u * (b[i] - a[i]) + v * (c[i] - a[i]) +
               spread * fd_rand(r);
}

/* At `count` points within `spread` of the surface in each coordinate
 * (one in ten within 2), the answers of the features of a triangle near
 * the point, of 30 random features and of the walk from that triangle:
 * each is the nearest distance, its closest point x - d n; the number of
 * points answered. */
static size_t answers_are_nearest(const built *m, int count, double spread)
{
    size_t answered = 0;
    fd_rng r = {31};
    for (int k = 0; k < count; k++) {
        int t = (int)((size_t)k % m->sf.ntri), ids[37];
        double x[3];
        near_triangle(&m->sf, t, k % 10 ? spread : 2.0, &r, x);
        double want = sc_brute_distance(&m->sf, x);
        ids[0] = t;
        for (int j = 0; j < 3; j++) {
            ids[1 + j] = (int)m->f.nface + m->f.side[t][j];
            ids[4 + j] = (int)(m->f.nface + m->f.nedge) + m->sf.tri[t][j];
        }
        for (int j = 7; j < 37; j++)
            ids[j] = (int)(0.5 * (1 + fd_rand(&r)) * (double)nfeat(&m->f)) %
                     (int)nfeat(&m->f);
        bool any = false;
        for (int j = 0; j <= 37; j++) {
            double d, n[3], c[3], e[3], y[3];
            cl_feat_kind kind;
            int id = j < 37 ? ids[j]
                            : cl_meshfeat_answer_near(&m->f, t, x, &d, n, c,
                                                      &kind, e);
            if (j < 37 ? !cl_meshfeat_answer(&m->f, id, x, &d, n, c, &kind,
                                             e)
                       : id < 0)
                continue;
            any = true;
            cr_assert(fabs(d - want) <= 1e-12, "feature %d: d = %.17g, "
                      "brute force %.17g", id, d, want);
            cl_v3_axpy(x, -d, n, y);
            cr_assert_leq(fd_relerr(y, c, 3), 1e-14, "c != x - d n");
        }
        answered += any;
    }
    return answered;
}

/* Lumpy spheres (radii 1 -+ lumps, not convex): some features unused
 * (a neighbour rises above a face's plane), some with a finite
 * clearance; every answer the nearest. */
static void lumpy(double lumps, size_t least)
{
    built m;
    icosphere(&m, 2, lumps, 23);
    size_t zero = 0, finite = 0;
    for (size_t id = 0; id < nfeat(&m.f); id++) {
        double h = clearance(&m.f, id);
        zero += h == 0;
        finite += h > 0 && isfinite(h);
    }
    cr_assert(zero > 0 && (finite > 0 || lumps < 0.1), "%zu unused, %zu "
              "finite", zero, finite);
    size_t answered = answers_are_nearest(&m, 10000, 0.1);
    cr_assert_geq(answered, least, "answered at %zu points", answered);
    release(&m);
}

Test(meshfeat, lumpy_answers_are_the_nearest)
{
    lumpy(0.3, 40);
    lumpy(0.05, 600);
}

/* Two unit icospheres 0.5 apart in one mesh: each convex, so no feature
 * unused, but the faces that see the other sphere above their plane
 * have a finite clearance, those that face it at most half the gap;
 * every answer the nearest, also in the gap. */
Test(meshfeat, two_spheres_clear_up_to_half_their_gap)
{
    built m;
    cl_shape_surface one;
    cl_error err = {0};
    cr_assert_eq(cl_icosphere(2, (double[]){0, 0, 0}, 1, &one, &err), CL_OK);
    size_t nv = one.nvert, nt = one.ntri;
    int(*tri)[3] = malloc(2 * nt * sizeof *tri);
    cr_assert_not_null(tri);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            tri[t][k] = one.tri[t][k];
            tri[nt + t][k] = one.tri[t][k] + (int)nv;
        }
    cr_assert_eq(cl_shape_surface_alloc(&m.sf, 2 * nv, 2 * nt,
                                        (const int(*)[3])tri, &err), CL_OK);
    for (size_t v = 0; v < nv; v++)
        for (int i = 0; i < 3; i++) {
            m.sf.vert[3 * v + i] = one.vert[3 * v + i];
            m.sf.vert[3 * (nv + v) + i] = one.vert[3 * v + i] + (i ? 0 : 2.5);
        }
    free(tri);
    cl_shape_surface_free(&one);
    build(&m);
    size_t finite = 0, infinite = 0;
    double least = INFINITY;
    for (size_t id = 0; id < nfeat(&m.f); id++) {
        double h = clearance(&m.f, id);
        cr_assert_gt(h, 0, "feature %zu unused", id);
        finite += isfinite(h);
        infinite += isinf(h);
        least = fmin(least, h);
    }
    cr_assert(finite > 0 && infinite > 0, "%zu finite, %zu infinite",
              finite, infinite);
    cr_assert_leq(least, 0.25, "the least clearance %g", least);
    size_t answered = answers_are_nearest(&m, 10000, 0.1);
    cr_assert_gt(answered, 2000, "answered at %zu points", answered);
    release(&m);
}

/* The surface of the unit cube [-0.5, 0.5]^3 shifted by `shift` in x,
 * each face split into n x n squares of two triangles, appended to sf's
 * vertices and triangles (grown), counter-clockwise seen from outside. */
static void add_box(cl_shape_surface *sf, int n, double shift)
{
    int side = n + 1, *id = malloc((size_t)side * side * side * sizeof *id);
    size_t nv0 = sf->nvert, nt0 = sf->ntri;
    size_t nv = nv0 + 6 * (size_t)n * n + 2, nt = nt0 + 12 * (size_t)n * n;
    sf->vert = realloc(sf->vert, 3 * nv * sizeof *sf->vert);
    sf->tri = realloc(sf->tri, nt * sizeof *sf->tri);
    cr_assert(id && sf->vert && sf->tri);
    for (int i = 0; i <= n; i++)
        for (int j = 0; j <= n; j++)
            for (int k = 0; k <= n; k++) {
                int *at = &id[(i * side + j) * side + k];
                *at = -1;
                if (i % n && j % n && k % n)
                    continue;   /* inside */
                *at = (int)sf->nvert;
                double p[3] = {(double)i / n - 0.5 + shift,
                               (double)j / n - 0.5, (double)k / n - 0.5};
                memcpy(sf->vert + 3 * sf->nvert++, p, sizeof p);
            }
    for (int a = 0; a < 3; a++)         /* face axis; u, v the next ones */
        for (int s = 0; s <= n; s += n)
            for (int u = 0; u < n; u++)
                for (int v = 0; v < n; v++) {
                    int p[4][3], q[4];
                    sc_cube_square(n, a, s, u, v, p);
                    for (int c = 0; c < 4; c++)
                        q[c] = id[(p[c][0] * side + p[c][1]) * side +
                                  p[c][2]];
                    int t1[3] = {q[0], q[1], q[2]}, t2[3] = {q[0], q[2], q[3]};
                    memcpy(sf->tri[sf->ntri++], t1, sizeof t1);
                    memcpy(sf->tri[sf->ntri++], t2, sizeof t2);
                }
    cr_assert_eq(sf->nvert, nv);
    cr_assert_eq(sf->ntri, nt);
    free(id);
}

/* Two cubes 0.3 apart, faces split 16 x 16: the faces that face each
 * other have a finite clearance, under half the gap (0.15), and every
 * answer is the nearest, also at points in the gap farther than that
 * from one cube and nearer the other. */
Test(meshfeat, two_boxes_clear_under_half_their_gap)
{
    built m = {.sf = {0}};
    add_box(&m.sf, 16, 0.0);
    add_box(&m.sf, 16, 1.3);
    build(&m);
    size_t finite = 0;
    for (size_t t = 0; t < m.f.nface; t++) {
        double h = m.f.face[t].h;
        cr_assert(h > 0, "face %zu unused", t);
        cr_assert(isinf(h) || h < 0.15, "face %zu: h = %g", t, h);
        finite += isfinite(h);
    }
    cr_assert_eq(finite, 2 * 2 * 16 * 16, "%zu faces with a finite h",
                 finite);
    size_t answered = answers_are_nearest(&m, 4000, 0.2);
    cr_assert_gt(answered, 600, "answered at %zu points", answered);
    release(&m);
}

/* A point that leaves a face of the icosphere across one of its sides
 * is answered by the edge of that side or the face across it. */
Test(meshfeat, a_point_off_a_face_is_answered_by_a_neighbour)
{
    built m;
    icosphere(&m, 2, 0, 1);
    int walked = 0;
    for (int t = 0; t < (int)m.f.nface; t++) {
        const cl_feat_face *F = &m.f.face[t];
        double mid[3], x[3], d, n[3], c[3], e[3];
        cl_feat_kind kind;
        const double *a = m.sf.vert + 3 * m.sf.tri[t][0];
        const double *b = m.sf.vert + 3 * m.sf.tri[t][1];
        for (int i = 0; i < 3; i++)   /* beyond the middle of side 0 */
            mid[i] = 0.5 * (a[i] + b[i]) + 1e-3 * F->m[0][i];
        cl_v3_axpy(mid, 0.01, F->n, x);
        cr_assert(!cl_meshfeat_answer(&m.f, t, x, &d, n, c, &kind, e));
        int id = cl_meshfeat_answer_near(&m.f, t, x, &d, n, c, &kind, e);
        int edge = (int)m.f.nface + m.f.side[t][0];
        cr_assert(id == edge || id == m.f.across[t][0], "face %d: %d", t,
                  id);
        cr_assert(fabs(d - sc_brute_distance(&m.sf, x)) <= 1e-12);
        walked += id == edge;
    }
    cr_assert_gt(walked, 0);
    release(&m);
}
