/* Tests for the mesh shape (contact/shape_mesh.c): cubes read from OBJ
 * against the analytic box (flat diagonals, straight creases through
 * vertices), scale and translate, the nearest distance and its sign
 * against brute force and the winding number on a lumpy sphere (and the
 * shape's cheap lower bound of d never above it, inside or outside), G
 * against central differences, the committed sphere against the analytic
 * one, every refusal, and surfaces of several parts (a cavity taken, a
 * part facing inwards beside another refused). */
#include <criterion/criterion.h>

#include <stdio.h>
#include <string.h>

#include "contact/icosphere.h"
#include "contact/triangle.h"
#include "cube_obj.h"
#include "shapecheck.h"
#include "tmpdir.h"

#define SEC "obstacle.m"

static char dir[64];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "shape-mesh");
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

TestSuite(shape_mesh, .init = setup, .fini = teardown);

/* dir/m.obj holding obj, and dir/p.ini whose [obstacle.m] names it
 * (relative to p.ini) with the extra lines `keys`; the loaded
 * configuration. */
static cl_config *problem(const char *obj, const char *keys)
{
    char path[256], ini[1024];
    cl_error err = {0};
    snprintf(path, sizeof path, "%s/m.obj", dir);
    tmp_put(path, obj);
    snprintf(path, sizeof path, "%s/p.ini", dir);
    snprintf(ini, sizeof ini, "[%s]\nfile = m.obj\n%s", SEC, keys);
    tmp_put(path, ini);
    cl_config *cfg = cl_config_alloc();
    cr_assert_eq(cl_config_load(cfg, path, &err), CL_OK, "%s", err.msg);
    return cfg;
}

static void mesh_shape(sc_shape *s, const char *obj, const char *keys)
{
    sc_create_from(s, "mesh", problem(obj, keys), SEC);
}

/* The OBJ text of a surface (malloc'd). */
static char *obj_text(const cl_shape_surface *sf)
{
    char *text = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&text, &size);
    cr_assert_not_null(f);
    for (size_t v = 0; v < sf->nvert; v++)
        fprintf(f, "v %.17g %.17g %.17g\n", sf->vert[3 * v],
                sf->vert[3 * v + 1], sf->vert[3 * v + 2]);
    for (size_t t = 0; t < sf->ntri; t++)
        fprintf(f, "f %d %d %d\n", sf->tri[t][0] + 1, sf->tri[t][1] + 1,
                sf->tri[t][2] + 1);
    cr_assert_eq(fclose(f), 0);
    return text;
}

/* ---- cubes against the box ------------------------------------------ */

/* The unit cube with every face split into 2 x 2 quads: 26 vertices at
 * (i, j, k) / 2, i, j, k in {-1, 0, 1}, not all 0.  Its edge midpoints
 * are vertices on straight creases, its face centres flat vertices. */
static char *split_cube_obj(void)
{
    char *text = NULL;
    size_t size = 0;
    int id[3][3][3], n = 0;
    FILE *f = open_memstream(&text, &size);
    cr_assert_not_null(f);
    for (int i = -1; i <= 1; i++)
        for (int j = -1; j <= 1; j++)
            for (int k = -1; k <= 1; k++)
                if (i || j || k) {
                    id[i + 1][j + 1][k + 1] = ++n;
                    fprintf(f, "v %g %g %g\n", 0.5 * i, 0.5 * j, 0.5 * k);
                }
    for (int a = 0; a < 3; a++)     /* face axis; u, v the next ones */
        for (int s = 0; s <= 2; s += 2)
            for (int u = 0; u < 2; u++)
                for (int v = 0; v < 2; v++) {
                    int p[4][3], q[4];
                    sc_cube_square(2, a, s, u, v, p);
                    for (int c = 0; c < 4; c++)
                        q[c] = id[p[c][0]][p[c][1]][p[c][2]];
                    fprintf(f, "f %d %d %d %d\n", q[0], q[1], q[2], q[3]);
                }
    cr_assert_eq(fclose(f), 0);
    return text;
}

/* The mesh's answer equals the box's at x: d, n, c, G (n and G to the
 * round-off of x - c over |d|). */
static void same_as_box(const sc_shape *mesh, const sc_shape *box,
                        const double x[3])
{
    cl_shape_query a = sc_query(mesh, x), b = sc_query(box, x);
    double tol = 1e-15 * (1 + 1 / fabs(b.d));
    cr_assert(fabs(a.d - b.d) <= 1e-15, "d %.17g, box %.17g at (%g, %g, %g)",
              a.d, b.d, x[0], x[1], x[2]);
    cr_assert_leq(fd_relerr(a.c, b.c, 3), 1e-15, "c at (%g, %g, %g)", x[0],
                  x[1], x[2]);
    cr_assert_leq(fd_relerr(a.n, b.n, 3), tol, "n at (%g, %g, %g)", x[0],
                  x[1], x[2]);
    cr_assert_leq(fd_relerr(a.G, b.G, 9), tol, "G at (%g, %g, %g): regions "
                  "%d, box %d", x[0], x[1], x[2], sc_region(&a),
                  sc_region(&b));
}

/* Points in every region of the unit cube, some exactly above the faces'
 * diagonals and above the split cube's edge midpoints and face centres,
 * then random points away from the boundaries of the box's regions. */
static void compare_with_box(const sc_shape *mesh)
{
    static const double pts[][3] = {
        {0, 0, 1},          {0.2, 0.2, 0.8},  {-0.3, -0.3, -0.9},
        {0.3, 0.1, 0.9},    {0.3, 0, 0.9},    {0, 0.7, 0},
        {0.8, 0.7, 0.1},    {0.6, 0.7, 0},    {0.7, 0, 0.8},
        {0.501, 0.502, 0.3}, {0.501, 0.502, 0}, {0.7, 0.8, 0.9},
        {0.501, 0.502, 0.503}, {-0.6, 0.55, -0.7}, {0.1, 0.2, 0.3},
        {0.45, 0, 0.1},     {0, 0, -0.499}};
    sc_shape box;
    sc_create(&box, "box", SC_SETS("size = 1, 1, 1"));
    for (size_t k = 0; k < sizeof pts / sizeof *pts; k++)
        same_as_box(mesh, &box, pts[k]);
    fd_rng r = {17};
    for (int k = 0; k < 3000; k++) {
        double x[3], gap[3], g0 = -INFINITY, g1 = -INFINITY;
        bool skip = false;
        for (int i = 0; i < 3; i++) {
            x[i] = 1.2 * fd_rand(&r);
            gap[i] = fabs(x[i]) - 0.5;
            skip |= fabs(gap[i]) < 1e-6;
            g1 = fmax(g1, fmin(g0, gap[i]));
            g0 = fmax(g0, gap[i]);
        }
        if (!skip && !(g0 < 0 && g0 - g1 < 1e-6))
            same_as_box(mesh, &box, x);
    }
    sc_free(&box);
}

Test(shape_mesh, cube_against_box)
{
    sc_shape s;
    mesh_shape(&s, cube_obj, "");
    cr_assert(s.pivot[0] == 0 && s.pivot[1] == 0 && s.pivot[2] == 0);
    compare_with_box(&s);
    sc_check_surface(&s, 12, 0);
    sc_free(&s);
}

Test(shape_mesh, split_cube_against_box)
{
    sc_shape s;
    char *obj = split_cube_obj();
    mesh_shape(&s, obj, "");
    compare_with_box(&s);
    sc_check_surface(&s, 48, 0);
    sc_free(&s);
    free(obj);
}

Test(shape_mesh, scale_and_translate)
{
    sc_shape s, box;
    mesh_shape(&s, cube_obj, "scale = 2\ntranslate = 1, 2, 3\n");
    sc_create(&box, "box", SC_SETS("center = 1 2 3", "size = 2 2 2"));
    cr_assert(s.pivot[0] == 1 && s.pivot[1] == 2 && s.pivot[2] == 3);
    same_as_box(&s, &box, (double[]){1.5, 2.2, 4.5});
    same_as_box(&s, &box, (double[]){2.5, 3.5, 3});
    same_as_box(&s, &box, (double[]){-0.5, 0, 0.5});
    same_as_box(&s, &box, (double[]){1.3, 2.1, 3.2});
    cl_shape_surface sf;
    cl_error err = {0};
    cr_assert_eq(s.type->surface(s.shape, &sf, &err), CL_OK, "%s", err.msg);
    cr_assert(sf.nvert == 8 && sf.vert[0] == 0 && sf.vert[1] == 1 &&
              sf.vert[2] == 2 && sf.tri[0][1] == 3);
    cl_shape_surface_free(&sf);
    sc_free(&box);
    sc_free(&s);
}

/* ---- a lumpy sphere against brute force ----------------------------- */

/* An icosphere of level 2 with radii 0.7..1.3: closed, outward and not
 * convex; as a surface and, read from its OBJ text, as a mesh shape. */
static void lumpy_sphere(cl_shape_surface *sf, sc_shape *s)
{
    cl_error err = {0};
    fd_rng r = {23};
    cr_assert_eq(cl_icosphere(2, (double[]){0, 0, 0}, 1, sf, &err), CL_OK);
    for (size_t v = 0; v < sf->nvert; v++) {
        double k = 1 + 0.3 * fd_rand(&r);
        for (int i = 0; i < 3; i++)
            sf->vert[3 * v + i] *= k;
    }
    char *obj = obj_text(sf);
    mesh_shape(s, obj, "");
    free(obj);
}

/* The generalised winding number: the solid angles of the triangles seen
 * from x over 4 pi (contact/triangle.h); 1 inside a closed outward
 * surface, 0 outside. */
static double winding(const cl_shape_surface *sf, const double x[3])
{
    double w = 0;
    for (size_t t = 0; t < sf->ntri; t++)
        w += cl_tri_solid_angle(x, sf->vert + 3 * sf->tri[t][0],
                                sf->vert + 3 * sf->tri[t][1],
                                sf->vert + 3 * sf->tri[t][2]);
    return w / (4 * M_PI);
}

/* Point k of 10^4: uniform around the mesh, or within 0.03 of a vertex,
 * or of a point of an edge. */
static void sample(const cl_shape_surface *sf, fd_rng *r, int k, double x[3])
{
    const int *t = sf->tri[(size_t)k % sf->ntri];
    double s = 0.5 + 0.5 * fd_rand(r), base[3] = {0, 0, 0}, spread = 0.03;
    if (k % 3 == 0)
        spread = 1.6;
    else if (k % 3 == 1)
        memcpy(base, sf->vert + 3 * t[0], sizeof base);
    else
        for (int i = 0; i < 3; i++)
            base[i] = (1 - s) * sf->vert[3 * t[0] + i] +
                      s * sf->vert[3 * t[1] + i];
    for (int i = 0; i < 3; i++)
        x[i] = base[i] + spread * fd_rand(r);
}

Test(shape_mesh, lumpy_sphere_against_brute_force)
{
    cl_shape_surface sf;
    sc_shape s;
    lumpy_sphere(&sf, &s);
    fd_rng r = {29};
    int inside = 0;
    for (int k = 0; k < 10000; k++) {
        double x[3];
        sample(&sf, &r, k, x);
        cl_shape_query q = sc_query(&s, x);
        double d = sc_brute_distance(&sf, x), w = winding(&sf, x);
        cr_assert(fabs(w - round(w)) < 1e-6 && (round(w) == 0 ||
                  round(w) == 1), "winding number %g", w);
        cr_assert(fabs(fabs(q.d) - d) <= 1e-12, "|d| = %.17g, brute force "
                  "%.17g at (%g, %g, %g)", fabs(q.d), d, x[0], x[1], x[2]);
        cr_assert_eq(q.d < 0, w > 0.5, "d = %g, winding number %g at (%g, "
                     "%g, %g)", q.d, w, x[0], x[1], x[2]);
        double low = s.type->lower_bound(s.shape, x);
        cr_assert(low <= q.d, "lower bound %g above d = %g at (%g, %g, %g)",
                  low, q.d, x[0], x[1], x[2]);
        inside += w > 0.5;
    }
    cr_assert(inside > 2000 && inside < 8000, "%d points inside", inside);
    sc_free(&s);
    cl_shape_surface_free(&sf);
}

/* G against central differences near faces, edges and vertices, inside
 * and outside, wherever the steps stay in one region. */
Test(shape_mesh, hessian_against_differences)
{
    cl_shape_surface sf;
    sc_shape s;
    lumpy_sphere(&sf, &s);
    fd_rng r = {31};
    int seen[3] = {0, 0, 0};
    for (int k = 0; k < 3000; k++) {
        double x[3];
        sample(&sf, &r, k, x);
        double e = sc_fd_error(&s, x, 1e-7);
        if (e < 0)
            continue;
        cr_assert(e <= 1e-6, "G vs central differences: relative error "
                  "%.3g at (%g, %g, %g)", e, x[0], x[1], x[2]);
        cl_shape_query q = sc_query(&s, x);
        seen[sc_region(&q)]++;
    }
    cr_assert(seen[0] > 100 && seen[1] > 100 && seen[2] > 100,
              "regions met: face %d, edge %d, vertex %d", seen[0], seen[1],
              seen[2]);
    sc_free(&s);
    cl_shape_surface_free(&sf);
}

/* problems/meshes/sphere.obj (named by --set: relative to the working
 * directory, the repository root) against the unit sphere: within the
 * chordal gap, the same side. */
Test(shape_mesh, committed_sphere_against_sphere)
{
    sc_shape s, ball;
    sc_create(&s, "mesh", SC_SETS("file = problems/meshes/sphere.obj",
                                  "scale = 0.5", "translate = 0 0 1"));
    sc_create(&ball, "sphere", SC_SETS("center = 0 0 1", "radius = 0.5"));
    cr_assert_leq(fd_relerr(s.pivot, ball.pivot, 3), 1e-15);
    fd_rng r = {37};
    for (int k = 0; k < 2000; k++) {
        double x[3] = {fd_rand(&r), fd_rand(&r), 1 + fd_rand(&r)};
        cl_shape_query a = sc_query(&s, x), b = sc_query(&ball, x);
        cr_assert(b.d - 1e-15 <= a.d && a.d <= b.d + 0.003, "mesh %g, "
                  "sphere %g", a.d, b.d);
    }
    sc_check_surface(&s, 1280, 1e-15);
    sc_free(&ball);
    sc_free(&s);
}

Test(shape_mesh, non_finite_point_does_not_crash)
{
    sc_shape s;
    mesh_shape(&s, cube_obj, "");
    cl_shape_query q;
    s.type->query(s.shape, (double[]){NAN, 0, 0}, NULL, &q);
    cr_assert(isnan(q.d));
    sc_free(&s);
}

/* ---- refusals -------------------------------------------------------- */

static void mesh_refused(const char *obj, const char *keys, cl_status code,
                         const char *sub1, const char *sub2)
{
    sc_refused_from("mesh", problem(obj, keys), SEC, code, sub1, sub2);
}

/* The cube's text with its face line `from` (1-based) replaced by `to`. */
static void cube_with(char *buf, int from, const char *to)
{
    buf[0] = '\0';
    for (const char *s = cube_obj, *e; *s; s = e) {
        e = strchr(s, '\n') + 1;
        from -= s[0] == 'f';
        if (s[0] == 'f' && from == 0)
            strcat(buf, to);
        else
            strncat(buf, s, (size_t)(e - s));
    }
}

Test(shape_mesh, bad_meshes_refused)
{
    char obj[1024];    /* the cube is 300 bytes */
    mesh_refused("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "", CL_EPARSE,
                 "/p.ini:2: [obstacle.m] file: ",
                 "/m.obj:4: vertex index 4 out of range");
    cube_with(obj, 6, "");
    mesh_refused(obj, "", CL_EINVAL, "p.ini:2: [obstacle.m] file: ",
                 "(vertices and triangles counted from 0): edge");
    mesh_refused(obj, "", CL_EINVAL, "has no other triangle: the surface "
                 "is not closed", NULL);
    cube_with(obj, 6, "f 6 7 3 2\n");
    mesh_refused(obj, "", CL_EINVAL, "not consistently oriented", NULL);
    snprintf(obj, sizeof obj, "%sv 9 9 9\n", cube_obj);
    mesh_refused(obj, "", CL_EINVAL, "p.ini:2: [obstacle.m] file: ",
                 "vertex 8 (counted from 0) belongs to no triangle: it "
                 "would move the pivot");
    snprintf(obj, sizeof obj, "%sv 2 2 2\nf 3 7 9\n", cube_obj);
    mesh_refused(obj, "", CL_EINVAL, "edge 2-6 is shared by 3 triangles",
                 NULL);
    snprintf(obj, sizeof obj, "%s", cube_obj);
    for (char *f = strstr(obj, "f "); f; f = strstr(f + 1, "f ")) {
        char *e = strchr(f, '\n');  /* "f a b c d" -> "f d c b a" */
        int a, b, c, d;
        cr_assert_eq(sscanf(f, "f %d %d %d %d", &a, &b, &c, &d), 4);
        int n = snprintf(f, (size_t)(e - f) + 1, "f %d %d %d %d", d, c, b, a);
        cr_assert_eq(n, e - f);
        *e = '\n';
    }
    mesh_refused(obj, "", CL_EINVAL, "encloses a volume of -1 m^3",
                 "counter-clockwise seen from outside");
}

/* A cube of side `side` centred at (x0, 0, 0) as OBJ lines, its vertices
 * numbered from base + 1, facing outwards or (inward) inwards; appended
 * to buf. */
static void cube_part(char *buf, size_t len, double side, double x0,
                      int base, bool inward)
{
    static const int quad[6][4] = {{1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5},
                                   {4, 8, 7, 3}, {1, 5, 8, 4}, {2, 3, 7, 6}};
    size_t n = strlen(buf);
    for (int v = 0; v < 8; v++)
        n += (size_t)snprintf(buf + n, len - n, "v %g %g %g\n",
                              x0 + side * ((v == 1 || v == 2 || v == 5 ||
                                            v == 6) - 0.5),
                              side * ((v == 2 || v == 3 || v == 6 ||
                                       v == 7) - 0.5),
                              side * ((v >= 4) - 0.5));
    for (int f = 0; f < 6; f++) {
        const int *q = quad[f];
        n += (size_t)snprintf(buf + n, len - n, "f %d %d %d %d\n",
                              base + q[inward ? 3 : 0],
                              base + q[inward ? 2 : 1],
                              base + q[inward ? 1 : 2],
                              base + q[inward ? 0 : 3]);
    }
}

/* Every part of the surface is judged: a second cube beside the first,
 * facing inwards, is refused (the total volume, 1 - 0.125 m^3, was
 * positive and let it through); the same cube inside the first, a cavity,
 * is taken, and a point in the cavity is outside the solid. */
Test(shape_mesh, each_part_faces_outwards_or_bounds_a_cavity)
{
    char obj[2048] = "";
    cube_part(obj, sizeof obj, 1.0, 0.0, 0, false);
    cube_part(obj, sizeof obj, 0.5, 3.0, 8, true);
    mesh_refused(obj, "", CL_EINVAL, "the part of the surface holding "
                 "triangle 12", "is no cavity of another part");
    obj[0] = '\0';
    cube_part(obj, sizeof obj, 1.0, 0.0, 0, false);
    cube_part(obj, sizeof obj, 0.5, 0.0, 8, true);
    sc_shape s;
    mesh_shape(&s, obj, "");
    sc_expect(&s, (double[]){0.05, 0.0, 0.0}, 0.2, (double[]){-1, 0, 0},
              1e-12);
    sc_expect(&s, (double[]){0.4, 0.0, 0.0}, -0.1, (double[]){1, 0, 0},
              1e-12);
    sc_free(&s);
}

Test(shape_mesh, bad_keys_refused)
{
    char path[256];
    mesh_refused(cube_obj, "scale = 0\n", CL_EINVAL,
                 "p.ini:3: [obstacle.m] scale = \"0\": expected a number > 0",
                 NULL);
    mesh_refused(cube_obj, "translate = 1 2\n", CL_EINVAL, "translate",
                 "3 finite numbers");
    sc_refused("mesh", SC_SETS("scale = 1"), "[ob] file: a file name is "
               "required", NULL);
    snprintf(path, sizeof path, "file = %s/none.obj", dir);
    sc_refused_from("mesh", sc_config(SC_SETS(path)), SC_SEC, CL_EIO,
                    "--set: [ob] file: cannot open", "none.obj");
}


/* Continuous detection: the cube's first crossing is the box's entry, for
 * segments from outside (offset 0). */
Test(shape_mesh, time_of_impact_of_the_cube_is_the_box_s)
{
    sc_shape m, box;
    mesh_shape(&m, cube_obj, "");
    sc_create(&box, "box", SC_SETS("size = 1, 1, 1"));
    fd_rng r = {23};
    int hits = 0;
    for (int k = 0; k < 1000; k++) {
        double a[3], b[3];
        for (int i = 0; i < 3; i++) {
            a[i] = 1.5 * fd_rand(&r);
            b[i] = 1.5 * fd_rand(&r);
        }
        if (fmax(fabs(a[0]), fmax(fabs(a[1]), fabs(a[2]))) <= 0.5)
            continue;
        double sm = m.type->toi(m.shape, a, b, 0.0);
        double sb = box.type->toi(box.shape, a, b, 0.0);
        cr_assert(isinf(sm) == isinf(sb), "segment %d: mesh %g, box %g", k,
                  sm, sb);
        if (!isinf(sm))
            cr_assert_float_eq(sm, sb, 1e-12, "segment %d", k);
        hits += !isinf(sm);
    }
    cr_assert_gt(hits, 200);
    sc_free(&m);
    sc_free(&box);
}
