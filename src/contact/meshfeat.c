/* Feature regions of a closed mesh and their clearances
 * (contact/meshfeat.h; docs/model.md 4.1, eq. C1a-C1c). */
#include "contact/meshfeat.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec3.h"

/* What the clearance of one face is computed from: its plane, its
 * bounding sphere, and the mesh. */
typedef struct {
    const cl_bvh *b;
    const double (*tc)[4];  /* each triangle's centroid and radius */
    const double *n;        /* the face's unit normal ... */
    double p[3];            /* ... and a point of it */
    double c[3], r;         /* its bounding sphere */
    double tau;
    double h;               /* the clearance so far */
} clearance;

/* Whether every point y of the box lies within tau of the plane's lower
 * side: n . (y - p) <= tau. */
static bool box_below(const clearance *q, const double lo[3],
                      const double hi[3])
{
    double top = 0;
    for (int i = 0; i < 3; i++)
        top += q->n[i] * ((q->n[i] > 0 ? hi[i] : lo[i]) - q->p[i]);
    return top <= q->tau;
}

static bool vertex_below(const clearance *q, const double y[3])
{
    double r[3];
    cl_v3_sub(y, q->p, r);
    return cl_v3_dot(q->n, r) <= q->tau;
}

/* A box may hold a triangle that lowers h: one not below the plane (eq.
 * C1b) and nearer than 2 h to the face's sphere. */
static bool enter(const double lo[3], const double hi[3], void *ctx)
{
    clearance *q = ctx;
    if (q->h <= 0 || box_below(q, lo, hi))
        return false;
    return sqrt(cl_box_dist2(lo, hi, q->c)) - q->r < 2 * q->h;
}

/* Triangle t, unless below the plane, bounds h by half a lower bound of
 * its distance to the face (eq. C1c). */
static void visit(int t, void *ctx)
{
    clearance *q = ctx;
    const int *v = q->b->tri[t];
    if (vertex_below(q, q->b->vert + 3 * v[0]) &&
        vertex_below(q, q->b->vert + 3 * v[1]) &&
        vertex_below(q, q->b->vert + 3 * v[2]))
        return;
    double e[3];
    cl_v3_sub(q->tc[t], q->c, e);
    double low = cl_v3_norm(e) - q->tc[t][3] - q->r;
    q->h = fmin(q->h, fmax(low, 0.0) / 2);
}

static const double *vertex(const cl_bvh *b, int v)
{
    return b->vert + 3 * v;
}

/* Whether the face's own vertices v[] lie within tau of its computed
 * plane (its normal's rounding can tilt a sliver's plane more). */
static bool on_plane(const clearance *q, const cl_bvh *b, const int v[3])
{
    for (int k = 0; k < 3; k++) {
        double r[3];
        cl_v3_sub(vertex(b, v[k]), q->p, r);
        if (fabs(cl_v3_dot(q->n, r)) > q->tau)
            return false;
    }
    return true;
}

/* Each triangle's centroid and the largest distance from it to a
 * vertex. */
static void spheres(const cl_bvh *b, double (*tc)[4])
{
    for (size_t t = 0; t < b->ntri; t++) {
        const int *v = b->tri[t];
        for (int i = 0; i < 3; i++)
            tc[t][i] = (vertex(b, v[0])[i] + vertex(b, v[1])[i] +
                        vertex(b, v[2])[i]) / 3;
        tc[t][3] = 0;
        for (int k = 0; k < 3; k++) {
            double e[3];
            cl_v3_sub(vertex(b, v[k]), tc[t], e);
            tc[t][3] = fmax(tc[t][3], cl_v3_norm(e));
        }
    }
}

/* The unit in-plane normal of the side from a to b of a triangle with
 * unit normal n, pointing out of the triangle (which runs a -> b
 * counter-clockwise about n). */
static void side_normal(const double a[3], const double b[3],
                        const double n[3], double m[3])
{
    double e[3];
    cl_v3_sub(b, a, e);
    cl_v3_cross(e, n, m);
    cl_v3_normalize(m);
}

static void faces(cl_meshfeat *f, clearance *q)
{
    const cl_bvh *b = q->b;
    for (size_t t = 0; t < f->nface; t++) {
        cl_feat_face *F = &f->face[t];
        const int *v = b->tri[t];
        memcpy(F->n, b->normal[t], sizeof F->n);
        F->off = cl_v3_dot(F->n, vertex(b, v[0]));
        for (int k = 0; k < 3; k++) {
            const double *a = vertex(b, v[k]);
            side_normal(a, vertex(b, v[(k + 1) % 3]), F->n, F->m[k]);
            F->mo[k] = cl_v3_dot(F->m[k], a);
        }
        q->n = F->n;
        memcpy(q->p, vertex(b, v[0]), sizeof q->p);
        memcpy(q->c, q->tc[t], sizeof q->c);
        q->r = q->tc[t][3];
        q->h = on_plane(q, b, v) ? INFINITY : 0.0; /* a sliver: unused */
        cl_bvh_walk(b, enter, visit, q);
        F->h = q->h;
    }
}

/* An edge's clearance is the lesser of its faces' (a triangle below
 * both faces' planes is below the edge's; one that is not is farther from
 * the edge than from the face whose plane it crosses; eq. C1c). */
static void edges(cl_meshfeat *f, const cl_closed *s,
                  const unsigned char *flat, const cl_bvh *b)
{
    for (size_t k = 0; k < f->nedge; k++) {
        const cl_mesh_edge *E = &s->mesh.edge[k];
        cl_feat_edge *F = &f->edge[k];
        const double *a = vertex(b, E->v[0]), *z = vertex(b, E->v[1]);
        memcpy(F->a, a, sizeof F->a);
        cl_v3_sub(z, a, F->e);
        F->len = cl_v3_normalize(F->e);
        side_normal(a, z, b->normal[E->tri[0]], F->ma); /* tri[0]: a -> z */
        side_normal(z, a, b->normal[E->tri[1]], F->mb);
        F->face = E->tri[0];
        int t = E->tri[0], side = 0;
        while (s->side[t][side] != (int)k)
            side++;
        F->h = flat[3 * t + side]
                   ? 0.0
                   : fmin(f->face[E->tri[0]].h, f->face[E->tri[1]].h);
    }
}

/* The directions of the edges leaving each vertex, into w[], and a face
 * of each. */
static void directions(cl_meshfeat *f, const cl_closed *s)
{
    for (size_t k = 0; k < f->nedge; k++)
        for (int i = 0; i < 2; i++)
            f->vert[s->mesh.edge[k].v[i]].count++;
    int at = 0;
    for (size_t v = 0; v < f->nvert; v++) {
        f->vert[v].first = at;
        at += f->vert[v].count;
        f->vert[v].count = 0;
    }
    for (size_t k = 0; k < f->nedge; k++)
        for (int i = 0; i < 2; i++) {
            cl_feat_vertex *V = &f->vert[s->mesh.edge[k].v[i]];
            if (V->count == 0)  /* its first edge's first face */
                V->face = s->mesh.edge[k].tri[0];
            cl_v3_scale(i ? -1.0 : 1.0, f->edge[k].e,
                        f->w[V->first + V->count++]);
        }
}

/* A corner's clearance is the least of its faces' (as an edge's). */
static void corners(cl_meshfeat *f, const unsigned char *corner,
                    const cl_bvh *b)
{
    for (size_t v = 0; v < f->nvert; v++) {
        memcpy(f->vert[v].p, vertex(b, (int)v), sizeof f->vert[v].p);
        f->vert[v].h = corner[v] ? INFINITY : 0.0;
    }
    for (size_t t = 0; t < b->ntri; t++)
        for (int k = 0; k < 3; k++) {
            cl_feat_vertex *V = &f->vert[b->tri[t][k]];
            V->h = fmin(V->h, f->face[t].h);
        }
}

void cl_meshfeat_free(cl_meshfeat *f)
{
    free(f->face);
    free(f->edge);
    free(f->vert);
    free(f->w);
    free(f->side);
    free(f->across);
    *f = (cl_meshfeat){0};
}

cl_status cl_meshfeat_build(cl_meshfeat *f, const cl_bvh *b,
                            const cl_closed *s, size_t nvert,
                            const unsigned char *flat,
                            const unsigned char *corner, double tiny,
                            cl_error *err)
{
    *f = (cl_meshfeat){.nface = b->ntri, .nedge = s->mesh.nedge,
                       .nvert = nvert, .tri = b->tri, .tiny = tiny};
    if (f->nface + f->nedge + f->nvert > INT_MAX - 1)
        return cl_error_set(err, CL_EINVAL, "%zu triangles, %zu edges and "
                            "%zu vertices: too many features to number",
                            f->nface, f->nedge, f->nvert);
    f->face = malloc(f->nface * sizeof *f->face);
    f->edge = malloc(f->nedge * sizeof *f->edge);
    f->vert = calloc(nvert, sizeof *f->vert);
    f->w = malloc(2 * f->nedge * sizeof *f->w);
    f->side = malloc(b->ntri * sizeof *f->side);
    f->across = malloc(b->ntri * sizeof *f->across);
    double (*tc)[4] = malloc(b->ntri * sizeof *tc);
    cl_status rc = CL_OK;
    if (f->face && f->edge && f->vert && f->w && f->side &&
        f->across && tc) {
        memcpy(f->side, s->side, b->ntri * sizeof *f->side);
        for (size_t t = 0; t < b->ntri; t++)
            for (int k = 0; k < 3; k++)
                f->across[t][k] = cl_closed_across(s, (int)t, k);
        spheres(b, tc);
        clearance q = {.b = b, .tc = (const double(*)[4])tc, .tau = tiny};
        faces(f, &q);
        edges(f, s, flat, b);
        directions(f, s);
        corners(f, corner, b);
    } else {
        rc = cl_error_set(err, CL_ENOMEM, "out of memory (mesh regions)");
    }
    free(tc);
    if (rc)
        cl_meshfeat_free(f);
    return rc;
}

int cl_meshfeat_id(const cl_meshfeat *f, int t, cl_tri_feature feature,
                   int k)
{
    if (feature == CL_TRI_FACE)
        return f->face[t].h > 0 ? t : -1;
    if (feature == CL_TRI_EDGE) {
        int e = f->side[t][k];
        return f->edge[e].h > 0 ? (int)f->nface + e : -1;
    }
    int v = f->tri[t][k];
    return f->vert[v].h > 0 ? (int)(f->nface + f->nedge) + v : -1;
}

/* d = |r| when it lies in (tiny, h], n = r / d. */
static bool away(double tiny, double h, const double r[3], double *d,
                 double n[3])
{
    *d = cl_v3_norm(r);
    if (!(*d > tiny && *d <= h))
        return false;
    cl_v3_scale(1.0 / *d, r, n);
    return true;
}

/* Above the face, within its prism (eq. C1a). */
static bool face_answer(const cl_meshfeat *f, const cl_feat_face *F,
                        const double x[3], double *d, double n[3],
                        double c[3])
{
    double ht = cl_v3_dot(F->n, x) - F->off;
    if (!(ht > f->tiny && ht <= F->h))
        return false;
    for (int k = 0; k < 3; k++)
        if (cl_v3_dot(F->m[k], x) > F->mo[k])
            return false;
    *d = ht;
    memcpy(n, F->n, 3 * sizeof *n);
    cl_v3_axpy(x, -ht, F->n, c);
    return true;
}

/* Beside the segment, within the wedge of the two faces' planes. */
static bool edge_answer(const cl_meshfeat *f, const cl_feat_edge *F,
                        const double x[3], double *d, double n[3],
                        double c[3])
{
    double r[3];
    cl_v3_sub(x, F->a, r);
    double s = cl_v3_dot(r, F->e);
    if (!(s >= 0 && s <= F->len) || cl_v3_dot(r, F->ma) < 0 ||
        cl_v3_dot(r, F->mb) < 0)
        return false;
    cl_v3_axpy(F->a, s, F->e, c);
    cl_v3_sub(x, c, r);
    return away(f->tiny, F->h, r, d, n);
}

/* Within the cone where x - p makes an obtuse angle with every edge. */
static bool corner_answer(const cl_meshfeat *f, const cl_feat_vertex *F,
                          const double x[3], double *d, double n[3],
                          double c[3])
{
    double r[3];
    cl_v3_sub(x, F->p, r);
    for (int k = 0; k < F->count; k++)
        if (cl_v3_dot(r, f->w[F->first + k]) > 0)
            return false;
    memcpy(c, F->p, 3 * sizeof *c);
    return away(f->tiny, F->h, r, d, n);
}

bool cl_meshfeat_answer(const cl_meshfeat *f, int id, const double x[3],
                        double *d, double n[3], double c[3],
                        cl_feat_kind *kind, double e[3])
{
    size_t i = (size_t)id;
    if (i < f->nface) {
        *kind = CL_FEAT_FACE;
        return face_answer(f, &f->face[i], x, d, n, c);
    }
    if ((i -= f->nface) < f->nedge) {
        *kind = CL_FEAT_EDGE;
        memcpy(e, f->edge[i].e, 3 * sizeof *e);
        return edge_answer(f, &f->edge[i], x, d, n, c);
    }
    *kind = CL_FEAT_CORNER;
    return corner_answer(f, &f->vert[i - f->nedge], x, d, n, c);
}

/* Whether feature id answers at x (into the answer's fields). */
#define TRY(id)                                                         \
    do {                                                                \
        int id_ = (id);                                                 \
        if (cl_meshfeat_answer(f, id_, x, d, n, c, kind, e))            \
            return id_;                                                 \
    } while (0)

/* A face of feature id: itself, or the one an edge or vertex keeps. */
static int face_of(const cl_meshfeat *f, int id)
{
    size_t i = (size_t)id;
    if (i < f->nface)
        return id;
    if ((i -= f->nface) < f->nedge)
        return f->edge[i].face;
    return f->vert[i - f->nedge].face;
}

/* The side of face t that x lies farthest beyond (in-plane), -1 when it
 * lies within all three. */
static int side_beyond(const cl_feat_face *F, const double x[3])
{
    int side = -1;
    double most = 0;
    for (int k = 0; k < 3; k++) {
        double out = cl_v3_dot(F->m[k], x) - F->mo[k];
        if (out > most) {
            most = out;
            side = k;
        }
    }
    return side;
}

int cl_meshfeat_answer_near(const cl_meshfeat *f, int id, const double x[3],
                            double *d, double n[3], double c[3],
                            cl_feat_kind *kind, double e[3])
{
    int ne = (int)f->nface, nv = (int)(f->nface + f->nedge);
    TRY(id);
    int t = face_of(f, id);
    for (int hop = 0; hop < CL_MESHFEAT_HOPS; hop++) {
        if (t != id)
            TRY(t);
        for (int k = 0; k < 3; k++)
            TRY(ne + f->side[t][k]);
        for (int k = 0; k < 3; k++)
            TRY(nv + f->tri[t][k]);
        int k = side_beyond(&f->face[t], x);
        if (k < 0)
            break;
        t = f->across[t][k];
    }
    return -1;
}
