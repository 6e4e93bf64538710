/* Helpers of the obstacle-shape tests (tests/test_shape_*.c): shapes made
 * from "key=value" settings of one section or from a loaded problem file,
 * the checks every answer must pass, expected answers, central differences
 * of the normal against G, the orientation of the drawn surfaces, and the
 * squares of a split cube's faces.
 * Header only (static inline), included after <criterion/criterion.h>. */
#ifndef CL_TESTS_SHAPECHECK_H
#define CL_TESTS_SHAPECHECK_H

#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "contact/shape.h"
#include "contact/triangle.h"
#include "core/vec3.h"
#include "fdcheck.h"

#define SC_SEC "ob"
#define SC_SETS(...) ((const char *const[]){__VA_ARGS__, NULL})

typedef struct {
    cl_config *cfg;
    const cl_shape_type *type;
    void *shape;
    double pivot[3];
} sc_shape;

/* A configuration holding the NULL-terminated "key=value" settings in
 * section SC_SEC. */
static inline cl_config *sc_config(const char *const *sets)
{
    cl_config *cfg = cl_config_alloc();
    cr_assert_not_null(cfg);
    for (size_t k = 0; sets[k]; k++) {
        char buf[512];
        cl_error err = {0};
        snprintf(buf, sizeof buf, "%s.%s", SC_SEC, sets[k]);
        cr_assert_eq(cl_config_set(cfg, buf, &err), CL_OK, "%s", err.msg);
    }
    return cfg;
}

/* Shape `name` from section sec of cfg (which s then owns). */
static inline void sc_create_from(sc_shape *s, const char *name,
                                  cl_config *cfg, const char *sec)
{
    cl_error err = {0};
    s->cfg = cfg;
    s->type = cl_shape_find(name);
    cr_assert_not_null(s->type, "no shape named %s", name);
    cr_assert_eq(s->type->create(cfg, sec, s->pivot, &s->shape, &err), CL_OK,
                 "%s", err.msg);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_OK, "%s", err.msg);
}

static inline void sc_create(sc_shape *s, const char *name,
                             const char *const *sets)
{
    sc_create_from(s, name, sc_config(sets), SC_SEC);
}

static inline void sc_free(sc_shape *s)
{
    s->type->free(s->shape);
    cl_config_free(s->cfg);
}

/* The settings must be refused with `code` and a message holding sub1
 * and sub2 (NULL: not checked). */
static inline void sc_refused_from(const char *name, cl_config *cfg,
                                   const char *sec, cl_status code,
                                   const char *sub1, const char *sub2)
{
    cl_error err = {0};
    double pivot[3];
    void *shape = NULL;
    cl_status rc = cl_shape_find(name)->create(cfg, sec, pivot, &shape, &err);
    cr_assert_eq(rc, code, "status %d: %s", rc, err.msg);
    cr_assert(strstr(err.msg, sub1), "'%s' not in: %s", sub1, err.msg);
    cr_assert(!sub2 || strstr(err.msg, sub2), "'%s' not in: %s", sub2,
              err.msg);
    cl_config_free(cfg);
}

static inline void sc_refused(const char *name, const char *const *sets,
                              const char *sub1, const char *sub2)
{
    sc_refused_from(name, sc_config(sets), SC_SEC, CL_EINVAL, sub1, sub2);
}

/* The answer at x, which must hold together: |n| = 1, c = x - d n, G
 * symmetric, n G = 0 (G only turns n). */
static inline cl_shape_query sc_query(const sc_shape *s, const double x[3])
{
    cl_shape_query q;
    s->type->query(s->shape, x, NULL, &q);
    double len = cl_v3_norm(q.n), r[3];
    cr_assert(fabs(len - 1) <= 1e-14, "|n| = %.17g at (%g, %g, %g)", len,
              x[0], x[1], x[2]);
    cl_v3_axpy(x, -q.d, q.n, r);
    cl_v3_sub(r, q.c, r);
    cr_assert(cl_v3_norm(r) <= 1e-12 * (1 + cl_v3_norm(x)),
              "c != x - d n at (%g, %g, %g)", x[0], x[1], x[2]);
    double gmax = fd_maxabs(q.G, 9);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            cr_assert(fabs(q.G[3 * i + j] - q.G[3 * j + i]) <= 1e-14 * gmax,
                      "G not symmetric");
            double ng = q.n[0] * q.G[j] + q.n[1] * q.G[3 + j] +
                        q.n[2] * q.G[6 + j];
            cr_assert(fabs(ng) <= 1e-12 * gmax, "n G != 0");
        }
    return q;
}

/* The answer at x must be d and n (to tol); returns it. */
static inline cl_shape_query sc_expect(const sc_shape *s, const double x[3],
                                       double d, const double n[3],
                                       double tol)
{
    cl_shape_query q = sc_query(s, x);
    cr_assert(fabs(q.d - d) <= tol, "d = %.17g, expected %.17g at (%g, %g, "
              "%g)", q.d, d, x[0], x[1], x[2]);
    for (int i = 0; i < 3; i++)
        cr_assert(fabs(q.n[i] - n[i]) <= tol, "n = (%g, %g, %g), expected "
                  "(%g, %g, %g) at (%g, %g, %g)", q.n[0], q.n[1], q.n[2],
                  n[0], n[1], n[2], x[0], x[1], x[2]);
    return q;
}

/* What G says of the region of x: the rank of G, a projector divided by a
 * distance, is (trace G)^2 / |G|^2: 0 on a face, 1 near an edge, 2 near a
 * vertex (or around a sphere's centre). */
static inline int sc_region(const cl_shape_query *q)
{
    double tr = q->G[0] + q->G[4] + q->G[8], ff = 0;
    for (int k = 0; k < 9; k++)
        ff += q->G[k] * q->G[k];
    return ff > 0 ? (int)lround(tr * tr / ff) : 0;
}

/* Whether x + step is in the region of x: the same rank of G and a
 * normal that barely turned (n jumps across the surfaces where two
 * features are equally near). */
static inline bool sc_same_region(const cl_shape_query *q,
                                  const cl_shape_query *qs)
{
    double dn[3];
    cl_v3_sub(q->n, qs->n, dn);
    return sc_region(q) == sc_region(qs) && cl_v3_norm(dn) <= 1e-2;
}

/* Central differences with step h around x: of n against G and of d
 * against n.  Returns the relative error of G (max |FD - G| / max |G|,
 * absolute where G = 0), or -1 when a step left the region of x (the
 * check does not apply there). */
static inline double sc_fd_error(const sc_shape *s, const double x[3],
                                 double h)
{
    cl_shape_query q = sc_query(s, x), qp, qm;
    double fd[9], grad[3];
    for (int j = 0; j < 3; j++) {
        double xp[3] = {x[0], x[1], x[2]}, xm[3] = {x[0], x[1], x[2]};
        xp[j] += h;
        xm[j] -= h;
        s->type->query(s->shape, xp, NULL, &qp);
        s->type->query(s->shape, xm, NULL, &qm);
        if (!sc_same_region(&q, &qp) || !sc_same_region(&q, &qm))
            return -1;
        for (int i = 0; i < 3; i++)
            fd[3 * i + j] = (qp.n[i] - qm.n[i]) / (2 * h);
        grad[j] = (qp.d - qm.d) / (2 * h);
    }
    double gerr = fd_relerr(grad, q.n, 3);
    cr_assert(gerr <= 1e-6, "grad d != n (relative error %.3g) at (%g, %g, "
              "%g)", gerr, x[0], x[1], x[2]);
    return fd_relerr(fd, q.G, 9);
}

/* G within tol of central differences at x, which must stay in its
 * region; returns the region. */
static inline int sc_check_fd(const sc_shape *s, const double x[3], double h,
                              double tol)
{
    double e = sc_fd_error(s, x, h);
    cr_assert(e >= 0, "a step of %g leaves the region of (%g, %g, %g)", h,
              x[0], x[1], x[2]);
    cr_assert(e <= tol, "G vs central differences: relative error %.3g at "
              "(%g, %g, %g)", e, x[0], x[1], x[2]);
    cl_shape_query q = sc_query(s, x);
    return sc_region(&q);
}

/* The drawing: ntri triangles, vertices on the surface (|d| <= tol), each
 * triangle facing the way of the shape's normal at its centroid. */
static inline void sc_check_surface(const sc_shape *s, size_t ntri,
                                    double tol)
{
    cl_shape_surface sf;
    cl_error err = {0};
    cr_assert_eq(s->type->surface(s->shape, &sf, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(sf.ntri, ntri);
    for (size_t v = 0; v < sf.nvert; v++) {
        cl_shape_query q = sc_query(s, sf.vert + 3 * v);
        cr_assert(fabs(q.d) <= tol, "vertex %zu at distance %g", v, q.d);
    }
    for (size_t t = 0; t < sf.ntri; t++) {
        const int *v = sf.tri[t];
        double n[3], c[3] = {0, 0, 0};
        cr_assert(v[0] >= 0 && (size_t)v[0] < sf.nvert && v[1] >= 0 &&
                  (size_t)v[1] < sf.nvert && v[2] >= 0 &&
                  (size_t)v[2] < sf.nvert);
        cl_v3_tri_cross(sf.vert + 3 * v[0], sf.vert + 3 * v[1],
                        sf.vert + 3 * v[2], n);
        for (int k = 0; k < 3; k++)
            cl_v3_axpy(c, 1.0 / 3.0, sf.vert + 3 * v[k], c);
        cl_shape_query q = sc_query(s, c);
        cr_assert(cl_v3_dot(n, q.n) > 0, "triangle %zu faces inwards", t);
    }
    cl_shape_surface_free(&sf);
}

/* The distance from x to a surface by trying every triangle. */
static inline double sc_brute_distance(const cl_shape_surface *sf,
                                       const double x[3])
{
    double best = INFINITY;
    for (size_t t = 0; t < sf->ntri; t++) {
        cl_tri_point p;
        cl_tri_closest(x, sf->vert + 3 * sf->tri[t][0],
                       sf->vert + 3 * sf->tri[t][1],
                       sf->vert + 3 * sf->tri[t][2], &p);
        best = fmin(best, p.dist2);
    }
    return sqrt(best);
}

/* The corners of square (u, v) of a face of the cube of grid points
 * 0..n on each axis: the face on axis a (u, v along the next two axes) at
 * s = 0 or n, each corner its grid point, in the order that goes
 * counter-clockwise seen from outside. */
static inline void sc_cube_square(int n, int a, int s, int u, int v,
                                  int corner[4][3])
{
    for (int c = 0; c < 4; c++) {
        int *p = corner[s == n ? c : 3 - c];
        p[a] = s;
        p[(a + 1) % 3] = u + (c == 1 || c == 2);
        p[(a + 2) % 3] = v + (c >= 2);
    }
}

#endif
