/* The mesh shape, a closed triangle mesh from an OBJ file: [obstacle.NAME]
 * shape = mesh,
 *   file       the OBJ file (io/obj.h), relative to the problem file
 *   scale      (> 0, default 1) and
 *   translate  (m, vector, default 0): vertices become scale v + translate
 * The pivot is the vertex centroid (a vertex of no triangle is refused).
 *
 * The mesh must be closed (every edge shared by exactly two triangles),
 * consistently oriented (the two run their edge in opposite directions)
 * and face outwards (counter-clockwise seen from outside, so that each
 * part of the surface encloses a positive volume, or, facing inwards,
 * bounds a cavity inside another part); meshes that are not are refused.
 * It should also be free of self-intersections, pinched vertices, parts
 * that touch or overlap, and zero-thickness folds, which are not
 * checked.
 *
 * Query: the nearest triangle by the bounding-volume tree (contact/bvh.h;
 * with a cache, a point's nearby triangles kept from one query to the
 * next) gives the closest point c and the feature it lies on.  With a
 * cache, the feature of the last answer outside, or one of its
 * neighbours, answers alone while the point stays in its region within
 * its clearance (contact/meshfeat.h; docs/model.md 4.1).  The sign comes
 * from the angle-weighted pseudo-normal of that feature (Baerentzen and
 * Aanaes, "Signed distance computation using the angle weighted
 * pseudonormal", IEEE TVCG 11(3), 2005): the face normal on a face, the
 * sum of the two face normals on an edge, the sum of the face normals of
 * the vertex's triangles weighted by their angles at it on a vertex;
 * x - c against it is >= 0 outside.  Then d = sign |x - c| and
 * n = sign (x - c) / |x - c|, taken as the face normal on a face (which
 * it is, without the round-off of x - c) and when |x - c| <= 1e-12 times
 * the mesh's size (x on the surface).
 *
 * G is the Hessian of the distance to the feature: 0 on a face,
 * (I - n n^T - e e^T) / d on an edge of direction e, (I - n n^T) / d on a
 * vertex.  A feature whose faces are coplanar (normals within 1e-6 rad:
 * the diagonal of a flat quad, a vertex inside a flat region) has no
 * region of its own, and a point found on it is on a face: G = 0.
 * Likewise a vertex whose faces all contain one line (a vertex in the
 * middle of a straight crease) has no region of its own and acts as the
 * crease, an edge along that line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "contact/bvh.h"
#include "contact/closed.h"
#include "contact/meshfeat.h"
#include "contact/shape_impl.h"
#include "contact/triangle.h"
#include "core/vec3.h"
#include "io/obj.h"

/* Normals closer than this (sine of their angle) count as parallel. */
#define FLAT_SIN 1e-6

/* What G a feature has: that of a face, an edge or a corner. */
typedef enum { G_FACE, G_EDGE, G_CORNER } g_kind;

typedef struct {
    cl_obj m;               /* vertices (scaled, moved) and triangles */
    cl_bvh bvh;             /* and its unit face normals */
    double (*sn)[3];        /* side k of triangle t at 3t + k: the edge's
                               pseudo-normal */
    unsigned char *sflat;   /* ... whose two faces are coplanar */
    double (*vn)[3];        /* vertex pseudo-normals */
    double (*ve)[3];        /* crease direction of a G_EDGE vertex */
    unsigned char *vkind;   /* g_kind of each vertex */
    cl_meshfeat feat;       /* the features' regions and clearances */
    double tiny;            /* 1e-12 times the bounding box's diagonal */
} mesh;

/* What a moving point keeps between its queries: the tree's cache and
 * the feature of its last answer outside the mesh, if that feature has a
 * region (contact/meshfeat.h). */
typedef struct {
    cl_bvh_cache bvh;
    int feat;               /* 1 + its number; 0: none */
} mesh_cache;

static void mesh_free(void *shape)
{
    mesh *m = shape;
    if (!m)
        return;
    cl_obj_free(&m->m);
    cl_bvh_free(&m->bvh);
    free(m->sn);
    free(m->sflat);
    free(m->vn);
    free(m->ve);
    free(m->vkind);
    cl_meshfeat_free(&m->feat);
    free(m);
}

/* err's message behind "prefix: ". */
static cl_status prefixed(cl_error *err, cl_status rc, const char *prefix)
{
    if (!err)
        return rc;
    char msg[sizeof err->msg];
    snprintf(msg, sizeof msg, "%s", err->msg);
    return cl_error_set(err, rc, "%s: %s", prefix, msg);
}

static const double *vertex(const mesh *m, int v)
{
    return m->m.vert + 3 * v;
}

static cl_status allocate(mesh *m, const char *path, cl_error *err)
{
    size_t nv = m->m.nvert, nt = m->m.ntri;
    m->sn = malloc(3 * nt * sizeof *m->sn);
    m->sflat = malloc(3 * nt * sizeof *m->sflat);
    m->vn = calloc(nv, sizeof *m->vn);
    m->ve = calloc(nv, sizeof *m->ve);
    m->vkind = malloc(nv * sizeof *m->vkind);
    if (m->sn && m->sflat && m->vn && m->ve && m->vkind)
        return CL_OK;
    return cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
}

/* The signed volume of the tetrahedron from vertex 0 to triangle t; over
 * a closed part of the surface they add up to the volume it encloses,
 * positive when its triangles face outwards. */
static double tet_volume(const mesh *m, size_t t)
{
    double a[3], b[3], c[3], n[3];
    cl_v3_sub(vertex(m, m->m.tri[t][0]), m->m.vert, a);
    cl_v3_sub(vertex(m, m->m.tri[t][1]), m->m.vert, b);
    cl_v3_sub(vertex(m, m->m.tri[t][2]), m->m.vert, c);
    cl_v3_tri_cross(a, b, c, n);
    return cl_v3_dot(a, n) / 6.0;
}

/* The parts of the surface (triangles joined across their edges): part[t]
 * numbered from 0 in the order of their first triangles, first[p] that
 * triangle; their count. */
static size_t label_parts(const mesh *m, const cl_closed *s, int *part,
                          size_t *first, int *stack)
{
    size_t nt = m->m.ntri, np = 0;
    for (size_t t = 0; t < nt; t++)
        part[t] = -1;
    for (size_t t0 = 0; t0 < nt; t0++) {
        if (part[t0] >= 0)
            continue;
        size_t top = 0;
        first[np] = t0;
        part[t0] = (int)np;
        stack[top++] = (int)t0;
        while (top > 0) {
            int t = stack[--top];
            for (int k = 0; k < 3; k++) {
                int u = cl_closed_across(s, t, k);
                if (part[u] < 0) {
                    part[u] = (int)np;
                    stack[top++] = u;
                }
            }
        }
        np++;
    }
    return np;
}

/* The generalised winding number at x of the triangles outside part p
 * (contact/triangle.h): 1 inside the solid the other parts bound, 0
 * outside it. */
static double winding_of_others(const mesh *m, const int *part, int p,
                                const double x[3])
{
    double w = 0;
    for (size_t t = 0; t < m->m.ntri; t++)
        if (part[t] != p)
            w += cl_tri_solid_angle(x, vertex(m, m->m.tri[t][0]),
                                    vertex(m, m->m.tri[t][1]),
                                    vertex(m, m->m.tri[t][2]));
    return w / (4 * M_PI);
}

/* The centroid of triangle t. */
static void triangle_centroid(const mesh *m, size_t t, double c[3])
{
    for (int i = 0; i < 3; i++)
        c[i] = (vertex(m, m->m.tri[t][0])[i] + vertex(m, m->m.tri[t][1])[i] +
                vertex(m, m->m.tri[t][2])[i]) / 3.0;
}

/* Every part of the surface must face outwards: enclose a positive
 * volume, or, facing inwards, bound a cavity inside another part (the
 * centroid of its first triangle within the solid of the others; parts
 * that touch are not checked, see the head). */
static cl_status check_part(const mesh *m, const int *part, int p,
                            size_t first, double vol, const char *path,
                            cl_error *err)
{
    double c[3];
    triangle_centroid(m, first, c);
    if (vol > 0 || (vol < 0 && winding_of_others(m, part, p, c) > 0.5))
        return CL_OK;
    return cl_error_set(err, CL_EINVAL, "%s: the part of the surface holding "
                        "triangle %zu (counted from 0) encloses a volume of "
                        "%g m^3%s", path, first, vol,
                        vol < 0 ? " and is no cavity of another part: its "
                                  "triangles must be counter-clockwise seen "
                                  "from outside (reverse the vertex order of "
                                  "its faces)"
                                : ": it is flat (a closed surface must "
                                  "enclose a solid)");
}

static cl_status check_outward(const mesh *m, const cl_closed *s,
                               const char *path, cl_error *err)
{
    size_t nt = m->m.ntri;
    int *part = malloc(nt * sizeof *part), *stack = malloc(nt * sizeof *stack);
    double *vol = calloc(nt, sizeof *vol);
    size_t *first = malloc(nt * sizeof *first);
    cl_status rc = part && stack && vol && first
                       ? CL_OK
                       : cl_error_set(err, CL_ENOMEM, "%s: out of memory",
                                      path);
    size_t np = rc ? 0 : label_parts(m, s, part, first, stack);
    for (size_t t = 0; t < nt && !rc; t++)
        vol[part[t]] += tet_volume(m, t);
    for (size_t p = 0; !rc && p < np; p++)
        rc = check_part(m, part, (int)p, first[p], vol[p], path, err);
    free(part);
    free(stack);
    free(vol);
    free(first);
    return rc;
}

/* Whether unit vectors a and b are parallel (and not opposite). */
static bool parallel(const double a[3], const double b[3])
{
    double c[3];
    cl_v3_cross(a, b, c);
    return cl_v3_norm(c) <= FLAT_SIN && cl_v3_dot(a, b) > 0;
}

/* The pseudo-normal of every side, from the unit face normals the tree
 * keeps. */
static void edge_normals(mesh *m, const cl_closed *s)
{
    const double(*fn)[3] = m->bvh.normal;
    for (size_t t = 0; t < m->m.ntri; t++)
        for (int k = 0; k < 3; k++) {
            const double *other = fn[cl_closed_across(s, (int)t, k)];
            cl_v3_axpy(fn[t], 1.0, other, m->sn[3 * t + k]);
            m->sflat[3 * t + k] = parallel(fn[t], other);
        }
}

/* The angle of triangle t at its corner k. */
static double corner_angle(const mesh *m, size_t t, int k)
{
    const int *v = m->m.tri[t];
    double u[3], w[3], c[3];
    cl_v3_sub(vertex(m, v[(k + 1) % 3]), vertex(m, v[k]), u);
    cl_v3_sub(vertex(m, v[(k + 2) % 3]), vertex(m, v[k]), w);
    cl_v3_cross(u, w, c);
    return atan2(cl_v3_norm(c), cl_v3_dot(u, w));
}

/* Vertex pseudo-normals (unit), and each vertex's kind: flat when every
 * face normal is parallel to its pseudo-normal, else a crease when they
 * are all perpendicular to one direction (that of the pseudo-normal
 * crossed with the face normal farthest from it), else a corner. */
static cl_status vertex_normals(mesh *m, const char *path, cl_error *err)
{
    size_t nv = m->m.nvert, nt = m->m.ntri;
    double *spread = calloc(nv, sizeof *spread);
    if (!spread)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++)
            cl_v3_axpy(m->vn[m->m.tri[t][k]], corner_angle(m, t, k),
                       m->bvh.normal[t], m->vn[m->m.tri[t][k]]);
    for (size_t v = 0; v < nv; v++)
        cl_v3_normalize(m->vn[v]);
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            int v = m->m.tri[t][k];
            double c[3];
            cl_v3_cross(m->vn[v], m->bvh.normal[t], c);
            if (cl_v3_norm(c) > spread[v]) {
                spread[v] = cl_v3_norm(c);
                cl_v3_normalize(c);
                memcpy(m->ve[v], c, sizeof c);
            }
        }
    for (size_t v = 0; v < nv; v++)
        m->vkind[v] = spread[v] <= FLAT_SIN ? G_FACE : G_EDGE;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            int v = m->m.tri[t][k];
            if (m->vkind[v] == G_EDGE &&
                fabs(cl_v3_dot(m->bvh.normal[t], m->ve[v])) > FLAT_SIN)
                m->vkind[v] = G_CORNER;
        }
    free(spread);
    return CL_OK;
}

/* The regions of the faces, of the edges between faces that are not
 * coplanar and of the corners. */
static cl_status regions(mesh *m, const cl_closed *s, cl_error *err)
{
    unsigned char *corner = malloc(m->m.nvert + 1);
    if (!corner)
        return cl_error_set(err, CL_ENOMEM, "out of memory (mesh regions)");
    for (size_t v = 0; v < m->m.nvert; v++)
        corner[v] = m->vkind[v] == G_CORNER;
    cl_status rc = cl_meshfeat_build(&m->feat, &m->bvh, s, m->m.nvert,
                                     m->sflat, corner, m->tiny, err);
    free(corner);
    return rc;
}

/* Normals, pseudo-normals and kinds of a closed, outward mesh. */
static cl_status geometry(mesh *m, const char *path, cl_error *err)
{
    cl_closed s;
    cl_status rc = cl_closed_build(m->m.ntri, (const int(*)[3])m->m.tri, &s,
                                   err);
    if (rc) {
        char where[4200];
        snprintf(where, sizeof where, "%s (vertices and triangles counted "
                 "from 0)", path);
        return prefixed(err, rc, where);
    }
    if (!(rc = check_outward(m, &s, path, err)) &&
        !(rc = allocate(m, path, err))) {
        edge_normals(m, &s);
        rc = vertex_normals(m, path, err);
    }
    if (!rc)
        rc = regions(m, &s, err);
    cl_closed_free(&s);
    return rc;
}

/* CL_EINVAL naming a vertex of no triangle, which would move the pivot
 * (the vertex centroid) away from the solid's. */
static cl_status every_vertex_used(const cl_obj *o, cl_error *err)
{
    bool *used = calloc(o->nvert + 1, sizeof *used);
    if (!used)
        return cl_error_set(err, CL_ENOMEM, "out of memory (mesh shape)");
    for (size_t t = 0; t < o->ntri; t++)
        for (int k = 0; k < 3; k++)
            used[o->tri[t][k]] = true;
    size_t v = 0;
    while (v < o->nvert && used[v])
        v++;
    free(used);
    return v < o->nvert
               ? cl_error_set(err, CL_EINVAL, "vertex %zu (counted from 0) "
                              "belongs to no triangle: it would move the "
                              "pivot, the vertices' centroid; remove it", v)
               : CL_OK;
}

/* Read, scale and move the mesh; its size for tiny. */
static cl_status load(mesh *m, const char *path, double scale,
                      const double shift[3], cl_error *err)
{
    cl_status rc = cl_obj_read(path, &m->m, err);
    if (!rc)
        rc = every_vertex_used(&m->m, err);
    if (rc)
        return rc;
    double lo[3] = {INFINITY, INFINITY, INFINITY};
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    cl_obj_place(&m->m, scale, shift);
    for (size_t v = 0; v < m->m.nvert; v++) {
        const double *x = m->m.vert + 3 * v;
        for (int i = 0; i < 3; i++) {
            lo[i] = fmin(lo[i], x[i]);
            hi[i] = fmax(hi[i], x[i]);
        }
    }
    cl_v3_sub(hi, lo, hi);
    m->tiny = 1e-12 * cl_v3_norm(hi);
    return CL_OK;
}

static void centroid(const mesh *m, double c[3])
{
    c[0] = c[1] = c[2] = 0;
    for (size_t v = 0; v < m->m.nvert; v++)
        cl_v3_axpy(c, 1.0 / (double)m->m.nvert, vertex(m, (int)v), c);
}

static cl_status mesh_create(cl_config *cfg, const char *sec,
                             double pivot[3], void **shape, cl_error *err)
{
    char path[4096], where[512];
    double scale = 1, shift[3] = {0, 0, 0};
    cl_status rc;
    if ((rc = cl_config_path_of(cfg, sec, "file", path, sizeof path, err)) ||
        (rc = cl_shape_positive(cfg, sec, "scale", 1.0, &scale, err)) ||
        (rc = cl_shape_vector(cfg, sec, "translate", false, shift, err)))
        return rc;
    mesh *m = calloc(1, sizeof *m);
    if (!m)
        return cl_error_set(err, CL_ENOMEM, "out of memory (mesh shape)");
    if ((rc = load(m, path, scale, shift, err)) ||
        (rc = cl_bvh_build(&m->bvh, m->m.vert, m->m.ntri,
                           (const int(*)[3])m->m.tri, err)) ||
        (rc = geometry(m, path, err))) {
        mesh_free(m);
        cl_config_origin(cfg, sec, "file", where, sizeof where);
        snprintf(where + strlen(where), sizeof where - strlen(where),
                 ": [%s] file", sec);
        return prefixed(err, rc, where);
    }
    centroid(m, pivot);
    *shape = m;
    return CL_OK;
}

/* The pseudo-normal (for the sign) and the kind of the feature hit, with
 * the direction e of an edge or crease. */
static g_kind feature(const mesh *m, const cl_bvh_hit *h, const double **pn,
                      double e[3])
{
    int t = h->tri, k = h->p.k;
    const int *v = m->m.tri[t];
    if (h->p.feature == CL_TRI_FACE) {
        *pn = m->bvh.normal[t];
        return G_FACE;
    }
    if (h->p.feature == CL_TRI_EDGE) {
        *pn = m->sn[3 * t + k];
        cl_v3_sub(vertex(m, v[(k + 1) % 3]), vertex(m, v[k]), e);
        cl_v3_normalize(e);
        return m->sflat[3 * t + k] ? G_FACE : G_EDGE;
    }
    *pn = m->vn[v[k]];
    memcpy(e, m->ve[v[k]], 3 * sizeof *e);
    return m->vkind[v[k]];
}

/* The answer of the feature kept in the cache, when x is in its region
 * within its clearance (contact/meshfeat.h). */
static bool kept_answer(const mesh *m, const double x[3], mesh_cache *mc,
                        cl_shape_query *q)
{
    cl_feat_kind kind;
    double e[3];
    if (!mc->feat)
        return false;
    int id = cl_meshfeat_answer_near(&m->feat, mc->feat - 1, x, &q->d, q->n,
                                     q->c, &kind, e);
    if (id < 0)
        return false;
    mc->feat = 1 + id;
    if (kind == CL_FEAT_FACE)
        memset(q->G, 0, sizeof q->G);
    else
        cl_shape_hessian(q->n, kind == CL_FEAT_EDGE ? e : NULL, q->d, q->G);
    return true;
}

static void mesh_query(const void *shape, const double x[3], void *cache,
                       cl_shape_query *q)
{
    const mesh *m = shape;
    mesh_cache *mc = cache;
    cl_bvh_hit h;
    if (mc && kept_answer(m, x, mc, q))
        return;
    if (mc)
        cl_bvh_nearest_cached(&m->bvh, x, &mc->bvh, &h);
    else
        cl_bvh_nearest(&m->bvh, x, &h);
    const double *pn;
    double e[3], r[3];
    g_kind kind = feature(m, &h, &pn, e);
    cl_v3_sub(x, h.p.c, r);
    double sign = cl_v3_dot(r, pn) >= 0 ? 1.0 : -1.0;
    if (mc)     /* the feature kept for the next query, if outside */
        mc->feat = sign > 0 ? 1 + cl_meshfeat_id(&m->feat, h.tri,
                                                 h.p.feature, h.p.k)
                            : 0;
    if (h.p.feature == CL_TRI_FACE) {   /* exact, not (x - c) / |x - c| */
        q->d = sign * h.dist;
        memcpy(q->c, h.p.c, sizeof q->c);
        memcpy(q->n, m->bvh.normal[h.tri], sizeof q->n);
        memset(q->G, 0, sizeof q->G);
        return;
    }
    if (cl_shape_answer(x, h.p.c, sign, m->bvh.normal[h.tri], m->tiny, q) &&
        kind != G_FACE)
        cl_shape_hessian(q->n, kind == G_EDGE ? e : NULL, q->d, q->G);
}

static cl_status mesh_surface(const void *shape, cl_shape_surface *s,
                              cl_error *err)
{
    const mesh *m = shape;
    cl_status rc = cl_shape_surface_alloc(s, m->m.nvert, m->m.ntri,
                                          (const int(*)[3])m->m.tri, err);
    if (!rc)
        memcpy(s->vert, m->m.vert, 3 * m->m.nvert * sizeof *s->vert);
    return rc;
}

/* The first crossing of the surface itself (contact/bvh.h), whatever the
 * offset: the start is outside, so the segment reaches the surface
 * there. */
static double mesh_toi(const void *shape, const double a[3],
                       const double b[3], double offset)
{
    (void)offset;
    return cl_bvh_segment(&((const mesh *)shape)->bvh, a, b);
}

/* Outside the bounding box the mesh is at least the box's distance away
 * (d > 0); inside it d may be negative, down to minus the depth of the
 * deepest interior point, so the bound there is -inf (the query decides). */
static double mesh_lower_bound(const void *shape, const double x[3])
{
    double box = cl_bvh_box_distance(&((const mesh *)shape)->bvh, x);
    return box > 0.0 ? box : -INFINITY;
}

const cl_shape_type cl_shape_mesh = {
    .name = "mesh",
    .lower_bound = mesh_lower_bound,
    .doc = "closed triangle mesh: file (OBJ, relative to the problem file), "
           "scale (> 0), translate (vector)",
    .create = mesh_create,
    .query = mesh_query,
    .toi = mesh_toi,
    .cache_size = sizeof(mesh_cache),
    .surface = mesh_surface,
    .free = mesh_free,
};
