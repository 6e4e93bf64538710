/* Tests for the grid triangulation and VTK / OBJ frame output. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/frames.h"
#include "tmpdir.h"

static char dir[64];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "frames");
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

TestSuite(frames, .init = setup, .fini = teardown);

/* A flat nu x nv grid in the x-z plane (spacing hu, hv), velocities and
 * pins made up so that every value is recognisable. */
typedef struct {
    int nu, nv;
    double *x, *v;
    unsigned char *pinned;
} grid;

static grid make_grid(int nu, int nv, double hu, double hv)
{
    grid g = {nu, nv, NULL, NULL, NULL};
    size_t np = (size_t)nu * nv;
    g.x = calloc(3 * np, sizeof *g.x);
    g.v = calloc(3 * np, sizeof *g.v);
    g.pinned = calloc(np, 1);
    cr_assert(g.x && g.v && g.pinned);
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            int p = i * nv + j;
            g.x[3 * p] = i * hu;
            g.x[3 * p + 2] = j * hv;
            g.v[3 * p] = p;
            g.v[3 * p + 1] = -p;
            g.v[3 * p + 2] = 0.5 * p;
            g.pinned[p] = (i == 0);
        }
    return g;
}

static void free_grid(grid *g)
{
    free(g->x);
    free(g->v);
    free(g->pinned);
}

Test(frames, triangle_count_and_order)
{
    cr_assert_eq(cl_grid_triangles(3, 4, NULL), 12);
    cr_assert_eq(cl_grid_triangles(2, 2, NULL), 2);
    cr_assert_eq(cl_grid_triangles(1, 5, NULL), 0);
    cr_assert_eq(cl_grid_triangles(5, 1, NULL), 0);
    cr_assert_eq(cl_grid_triangles(0, 0, NULL), 0);

    int tri[12][3];
    cr_assert_eq(cl_grid_triangles(3, 4, tri), 12);
    /* Quad (0,0): (0,0),(1,0),(1,1) and (0,0),(1,1),(0,1). */
    cr_assert_eq(tri[0][0], 0);
    cr_assert_eq(tri[0][1], 4);
    cr_assert_eq(tri[0][2], 5);
    cr_assert_eq(tri[1][0], 0);
    cr_assert_eq(tri[1][1], 5);
    cr_assert_eq(tri[1][2], 1);
    /* Last quad (1,2): particles 6, 10, 11, 7. */
    cr_assert_eq(tri[10][0], 6);
    cr_assert_eq(tri[10][1], 10);
    cr_assert_eq(tri[10][2], 11);
    cr_assert_eq(tri[11][0], 6);
    cr_assert_eq(tri[11][1], 11);
    cr_assert_eq(tri[11][2], 7);
}

Test(frames, triangles_tile_the_grid_consistently)
{
    int nu = 4, nv = 3;
    double hu = 0.5, hv = 0.25;
    grid g = make_grid(nu, nv, hu, hv);
    size_t n = cl_grid_triangles(nu, nv, NULL);
    int (*tri)[3] = malloc(n * sizeof *tri);
    cr_assert_not_null(tri);
    cr_assert_eq(cl_grid_triangles(nu, nv, tri), n);
    double area = 0;
    for (size_t k = 0; k < n; k++) {
        const double *a = g.x + 3 * tri[k][0], *b = g.x + 3 * tri[k][1],
                     *c = g.x + 3 * tri[k][2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        /* Normal of a triangle in the x-z plane is along y; same sign for
         * all (consistent orientation). */
        double ny = e1[2] * e2[0] - e1[0] * e2[2];
        cr_assert(ny < 0, "triangle %zu flipped", k);
        area += -0.5 * ny;
    }
    cr_assert_float_eq(area, (nu - 1) * hu * (nv - 1) * hv, 1e-12);
    free(tri);
    free_grid(&g);
}

/* Minimal legacy-VTK reader: counts and contents of the sections. */
typedef struct {
    size_t npoints, ntri, npointdata, nvel, npinned, npinned_set;
    double t;
    int have_time;
    /* the values of the first VTK_KEEP points and triangles */
#define VTK_KEEP 64
    double x[3 * VTK_KEEP], v[3 * VTK_KEEP];
    int tri[VTK_KEEP][3], pinned[VTK_KEEP];
} vtk_info;

static vtk_info read_vtk(const char *path)
{
    vtk_info info;
    memset(&info, 0, sizeof info);
    FILE *fp = fopen(path, "r");
    cr_assert_not_null(fp, "cannot open %s", path);
    char line[512];
    cr_assert_not_null(fgets(line, sizeof line, fp));
    cr_assert_eq(strncmp(line, "# vtk DataFile Version", 22), 0);
    cr_assert_not_null(fgets(line, sizeof line, fp));  /* title */
    cr_assert_not_null(fgets(line, sizeof line, fp));
    cr_assert_str_eq(line, "ASCII\n");
    cr_assert_not_null(fgets(line, sizeof line, fp));
    cr_assert_str_eq(line, "DATASET POLYDATA\n");
    while (fgets(line, sizeof line, fp)) {
        size_t n, m;
        if (!strcmp(line, "TIME 1 1 double\n")) {
            cr_assert_eq(fscanf(fp, "%lf ", &info.t), 1);
            info.have_time = 1;
        } else if (sscanf(line, "POINTS %zu double", &n) == 1) {
            info.npoints = n;
            for (size_t p = 0; p < n; p++) {
                double *q = info.x + 3 * (p < VTK_KEEP ? p : VTK_KEEP - 1);
                cr_assert_eq(fscanf(fp, "%lf %lf %lf ", q, q + 1, q + 2), 3);
            }
        } else if (sscanf(line, "POLYGONS %zu %zu", &n, &m) == 2) {
            cr_assert_eq(m, 4 * n);
            info.ntri = n;
            for (size_t k = 0; k < n; k++) {
                int c, a, b, d;
                cr_assert_eq(fscanf(fp, "%d %d %d %d ", &c, &a, &b, &d), 4);
                cr_assert_eq(c, 3);
                if (k < VTK_KEEP) {
                    info.tri[k][0] = a;
                    info.tri[k][1] = b;
                    info.tri[k][2] = d;
                }
                cr_assert(a >= 0 && (size_t)a < info.npoints);
                cr_assert(b >= 0 && (size_t)b < info.npoints);
                cr_assert(d >= 0 && (size_t)d < info.npoints);
            }
        } else if (sscanf(line, "POINT_DATA %zu", &n) == 1) {
            info.npointdata = n;
        } else if (!strcmp(line, "VECTORS velocity double\n")) {
            for (size_t p = 0; p < info.npointdata; p++) {
                double *q = info.v + 3 * (p < VTK_KEEP ? p : VTK_KEEP - 1);
                cr_assert_eq(fscanf(fp, "%lf %lf %lf ", q, q + 1, q + 2), 3);
            }
            info.nvel = info.npointdata;
        } else if (!strcmp(line, "SCALARS pinned int 1\n")) {
            cr_assert_not_null(fgets(line, sizeof line, fp));
            cr_assert_str_eq(line, "LOOKUP_TABLE default\n");
            for (size_t p = 0; p < info.npointdata; p++) {
                int f;
                cr_assert_eq(fscanf(fp, "%d ", &f), 1);
                cr_assert(f == 0 || f == 1);
                if (p < VTK_KEEP)
                    info.pinned[p] = f;
                info.npinned_set += (size_t)f;
            }
            info.npinned = info.npointdata;
        } else if (strcmp(line, "FIELD FieldData 1\n") != 0) {
            cr_assert_fail("unexpected VTK line: %s", line);
        }
    }
    fclose(fp);
    return info;
}

Test(frames, vtk_full)
{
    int nu = 4, nv = 5;
    grid g = make_grid(nu, nv, 0.1, 0.2);
    cl_frame f = {nu, nv, g.x, g.v, g.pinned, 1.25, NULL, 0};
    char path[256];
    cl_error err;
    cr_assert_eq(cl_frame_path(dir, 42, "vtk", path, sizeof path, &err),
                 CL_OK);
    cr_assert_eq(cl_frame_write_vtk(path, &f, &err), CL_OK, "%s", err.msg);
    vtk_info info = read_vtk(path);
    cr_assert_eq(info.npoints, 20);
    cr_assert_eq(info.ntri, 24);
    cr_assert(info.have_time);
    cr_assert_eq(info.t, 1.25);
    cr_assert_eq(info.npointdata, 20);
    cr_assert_eq(info.nvel, 20);
    cr_assert_eq(info.npinned, 20);
    cr_assert_eq(info.npinned_set, 5);
    /* every point, velocity and flag as given, every triangle the grid's */
    for (size_t k = 0; k < 3 * 20; k++) {
        cr_assert_eq(info.x[k], g.x[k], "x[%zu]", k);
        cr_assert_eq(info.v[k], g.v[k], "v[%zu]", k);
    }
    for (size_t p = 0; p < 20; p++)
        cr_assert_eq(info.pinned[p], g.pinned[p], "pinned[%zu]", p);
    int tri[24][3];
    cr_assert_eq(cl_grid_triangles(nu, nv, tri), 24);
    for (size_t k = 0; k < 24; k++)
        for (int c = 0; c < 3; c++)
            cr_assert_eq(info.tri[k][c], tri[k][c], "triangle %zu", k);
    free_grid(&g);
}

Test(frames, vtk_positions_only)
{
    grid g = make_grid(3, 3, 1, 1);
    cl_frame f = {3, 3, g.x, NULL, NULL, 0, NULL, 0};
    char path[256];
    snprintf(path, sizeof path, "%s/a.vtk", dir);
    cl_error err;
    cr_assert_eq(cl_frame_write_vtk(path, &f, &err), CL_OK, "%s", err.msg);
    vtk_info info = read_vtk(path);
    cr_assert_eq(info.npoints, 9);
    cr_assert_eq(info.ntri, 8);
    cr_assert_eq(info.npointdata, 0);
    cr_assert_eq(info.nvel, 0);
    cr_assert_eq(info.npinned, 0);

    /* Pins without velocities. */
    f.pinned = g.pinned;
    cr_assert_eq(cl_frame_write_vtk(path, &f, &err), CL_OK, "%s", err.msg);
    info = read_vtk(path);
    cr_assert_eq(info.npointdata, 9);
    cr_assert_eq(info.nvel, 0);
    cr_assert_eq(info.npinned_set, 3);
    free_grid(&g);
}

Test(frames, vtk_single_row_has_no_polygons)
{
    grid g = make_grid(1, 4, 1, 1);
    cl_frame f = {1, 4, g.x, g.v, NULL, 0, NULL, 0};
    char path[256];
    snprintf(path, sizeof path, "%s/rope.vtk", dir);
    cl_error err;
    cr_assert_eq(cl_frame_write_vtk(path, &f, &err), CL_OK, "%s", err.msg);
    vtk_info info = read_vtk(path);
    cr_assert_eq(info.npoints, 4);
    cr_assert_eq(info.ntri, 0);
    cr_assert_eq(info.nvel, 4);
    free_grid(&g);
}

Test(frames, obj_counts)
{
    int nu = 3, nv = 6;
    grid g = make_grid(nu, nv, 0.1, 0.1);
    cl_frame f = {nu, nv, g.x, g.v, g.pinned, 0.5, NULL, 0};
    char path[256];
    cl_error err;
    cr_assert_eq(cl_frame_path(dir, 7, "obj", path, sizeof path, &err),
                 CL_OK);
    cr_assert_eq(cl_frame_write_obj(path, &f, &err), CL_OK, "%s", err.msg);

    FILE *fp = fopen(path, "r");
    cr_assert_not_null(fp);
    char line[512];
    size_t nvert = 0, nface = 0;
    int saw_time = 0;
    while (fgets(line, sizeof line, fp)) {
        double a, b, c;
        int i, j, k;
        if (line[0] == '#') {
            saw_time |= strstr(line, "t=0.5") != NULL;
        } else if (sscanf(line, "v %lf %lf %lf", &a, &b, &c) == 3) {
            cr_assert_eq(a, g.x[3 * nvert]);
            cr_assert_eq(c, g.x[3 * nvert + 2]);
            nvert++;
        } else if (sscanf(line, "f %d %d %d", &i, &j, &k) == 3) {
            cr_assert(i >= 1 && i <= nu * nv);
            cr_assert(j >= 1 && j <= nu * nv);
            cr_assert(k >= 1 && k <= nu * nv);
            if (nface == 0) {   /* (0,0),(1,0),(1,1), 1-based */
                cr_assert_eq(i, 1);
                cr_assert_eq(j, nv + 1);
                cr_assert_eq(k, nv + 2);
            }
            nface++;
        } else {
            cr_assert_fail("unexpected OBJ line: %s", line);
        }
    }
    fclose(fp);
    cr_assert(saw_time);
    cr_assert_eq(nvert, 18);
    cr_assert_eq(nface, 20);
    free_grid(&g);
}

Test(frames, frame_path)
{
    char buf[64];
    cl_error err;
    cr_assert_eq(cl_frame_path("out", 42, "vtk", buf, sizeof buf, &err),
                 CL_OK);
    cr_assert_str_eq(buf, "out/frame_00042.vtk");
    cr_assert_eq(cl_frame_path("out/", 0, "obj", buf, sizeof buf, &err),
                 CL_OK);
    cr_assert_str_eq(buf, "out/frame_00000.obj");
    cr_assert_eq(cl_frame_path("", 3, "vtk", buf, sizeof buf, &err), CL_OK);
    cr_assert_str_eq(buf, "frame_00003.vtk");
    cr_assert_eq(cl_frame_path("d", 1234567, "vtk", buf, sizeof buf, &err),
                 CL_OK);
    cr_assert_str_eq(buf, "d/frame_1234567.vtk");

    char small[16];
    cr_assert_eq(cl_frame_path("out", 42, "vtk", small, sizeof small, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "too long") != NULL, "%s", err.msg);
    cr_assert_eq(cl_frame_path("out", -1, "vtk", buf, sizeof buf, &err),
                 CL_EINVAL);
}

Test(frames, write_errors)
{
    grid g = make_grid(2, 2, 1, 1);
    cl_frame f = {2, 2, g.x, NULL, NULL, 0, NULL, 0};
    char path[256];
    cl_error err;
    snprintf(path, sizeof path, "%s/missing/frame.vtk", dir);
    cr_assert_eq(cl_frame_write_vtk(path, &f, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    snprintf(path, sizeof path, "%s/missing/frame.obj", dir);
    cr_assert_eq(cl_frame_write_obj(path, &f, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);

    snprintf(path, sizeof path, "%s/bad.vtk", dir);
    cl_frame bad = {0, 2, g.x, NULL, NULL, 0, NULL, 0};
    cr_assert_eq(cl_frame_write_vtk(path, &bad, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "invalid frame") != NULL, "%s", err.msg);
    bad = (cl_frame){2, 2, NULL, NULL, NULL, 0, NULL, 0};
    cr_assert_eq(cl_frame_write_obj(path, &bad, &err), CL_EINVAL);
    cr_assert_eq(access(path, F_OK), -1);
    free_grid(&g);
}

Test(frames, write_error_leaves_nothing)
{
    grid g = make_grid(20, 20, 1.0 / 3.0, 1.0 / 7.0);
    cl_frame f = {20, 20, g.x, g.v, g.pinned, 0, NULL, 0};
    char path[256];
    snprintf(path, sizeof path, "%s/big.vtk", dir);
    tmp_limit_file_size(2000);
    cl_error err;
    cr_assert_eq(cl_frame_write_vtk(path, &f, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    snprintf(path, sizeof path, "%s/big.obj", dir);
    cr_assert_eq(cl_frame_write_obj(path, &f, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 0);
    free_grid(&g);
}
