/* Cloth frames: legacy VTK polydata and Wavefront OBJ. */
#include "io/frames.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"

size_t cl_grid_triangles(int nu, int nv, int (*tri)[3])
{
    if (nu < 2 || nv < 2)
        return 0;
    size_t n = 0;
    for (int i = 0; i + 1 < nu; i++) {
        for (int j = 0; j + 1 < nv; j++) {
            int a = i * nv + j;         /* (i, j)     */
            int b = (i + 1) * nv + j;   /* (i+1, j)   */
            int c = b + 1;              /* (i+1, j+1) */
            int d = a + 1;              /* (i, j+1)   */
            if (tri) {
                tri[n][0] = a; tri[n][1] = b; tri[n][2] = c;
                tri[n + 1][0] = a; tri[n + 1][1] = c; tri[n + 1][2] = d;
            }
            n += 2;
        }
    }
    return n;
}

/* Validate the frame and build its triangle list (*tri NULL if none). */
static cl_status frame_prepare(const char *path, const cl_frame *f,
                               int (**tri)[3], size_t *ntri, cl_error *err)
{
    *tri = NULL;
    *ntri = 0;
    if (!f || f->nu < 1 || f->nv < 1 || !f->x)
        return cl_error_set(err, CL_EINVAL, "%s: empty or invalid frame",
                            path);
    size_t n = cl_grid_triangles(f->nu, f->nv, NULL);
    if (n == 0)
        return CL_OK;
    *tri = malloc(n * sizeof **tri);
    if (!*tri)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
    cl_grid_triangles(f->nu, f->nv, *tri);
    *ntri = n;
    return CL_OK;
}

static cl_status frame_write_fail(cl_afile *af, const char *path,
                                  int (*tri)[3], cl_error *err)
{
    int e = errno;
    cl_afile_abort(af);
    free(tri);
    return cl_error_set(err, CL_EIO, "cannot write '%s': %s", path,
                        strerror(e ? e : EIO));
}

cl_status cl_frame_write_vtk(const char *path, const cl_frame *f,
                             cl_error *err)
{
    int (*tri)[3];
    size_t ntri;
    cl_status st = frame_prepare(path, f, &tri, &ntri, err);
    if (st)
        return st;
    cl_afile af;
    if ((st = cl_afile_open(&af, path, err))) {
        free(tri);
        return st;
    }
    FILE *fp = af.fp;
    size_t np = (size_t)f->nu * (size_t)f->nv;

    if (fprintf(fp, "# vtk DataFile Version 3.0\n"
                    "clothode frame t=%.17g nu=%d nv=%d\n"
                    "ASCII\n"
                    "DATASET POLYDATA\n"
                    "FIELD FieldData 1\n"
                    "TIME 1 1 double\n"
                    "%.17g\n"
                    "POINTS %zu double\n",
                f->t, f->nu, f->nv, f->t, np) < 0)
        return frame_write_fail(&af, path, tri, err);
    for (size_t p = 0; p < np; p++)
        if (fprintf(fp, "%.17g %.17g %.17g\n", f->x[3 * p], f->x[3 * p + 1],
                    f->x[3 * p + 2]) < 0)
            return frame_write_fail(&af, path, tri, err);
    if (ntri > 0) {
        if (fprintf(fp, "POLYGONS %zu %zu\n", ntri, 4 * ntri) < 0)
            return frame_write_fail(&af, path, tri, err);
        for (size_t k = 0; k < ntri; k++)
            if (fprintf(fp, "3 %d %d %d\n", tri[k][0], tri[k][1],
                        tri[k][2]) < 0)
                return frame_write_fail(&af, path, tri, err);
    }
    if (f->v || f->pinned)
        if (fprintf(fp, "POINT_DATA %zu\n", np) < 0)
            return frame_write_fail(&af, path, tri, err);
    if (f->v) {
        if (fprintf(fp, "VECTORS velocity double\n") < 0)
            return frame_write_fail(&af, path, tri, err);
        for (size_t p = 0; p < np; p++)
            if (fprintf(fp, "%.17g %.17g %.17g\n", f->v[3 * p],
                        f->v[3 * p + 1], f->v[3 * p + 2]) < 0)
                return frame_write_fail(&af, path, tri, err);
    }
    if (f->pinned) {
        if (fprintf(fp, "SCALARS pinned int 1\nLOOKUP_TABLE default\n") < 0)
            return frame_write_fail(&af, path, tri, err);
        for (size_t p = 0; p < np; p++)
            if (fprintf(fp, "%d\n", f->pinned[p] ? 1 : 0) < 0)
                return frame_write_fail(&af, path, tri, err);
    }
    free(tri);
    return cl_afile_commit(&af, err);
}

cl_status cl_frame_write_obj(const char *path, const cl_frame *f,
                             cl_error *err)
{
    int (*tri)[3];
    size_t ntri;
    cl_status st = frame_prepare(path, f, &tri, &ntri, err);
    if (st)
        return st;
    cl_afile af;
    if ((st = cl_afile_open(&af, path, err))) {
        free(tri);
        return st;
    }
    FILE *fp = af.fp;
    size_t np = (size_t)f->nu * (size_t)f->nv;

    if (fprintf(fp, "# clothode frame t=%.17g nu=%d nv=%d\n"
                    "# %zu vertices, %zu triangles\n",
                f->t, f->nu, f->nv, np, ntri) < 0)
        return frame_write_fail(&af, path, tri, err);
    for (size_t p = 0; p < np; p++)
        if (fprintf(fp, "v %.17g %.17g %.17g\n", f->x[3 * p],
                    f->x[3 * p + 1], f->x[3 * p + 2]) < 0)
            return frame_write_fail(&af, path, tri, err);
    for (size_t k = 0; k < ntri; k++)
        if (fprintf(fp, "f %d %d %d\n", tri[k][0] + 1, tri[k][1] + 1,
                    tri[k][2] + 1) < 0)
            return frame_write_fail(&af, path, tri, err);
    free(tri);
    return cl_afile_commit(&af, err);
}

cl_status cl_frame_path(const char *dir, long index, const char *ext,
                        char *buf, size_t len, cl_error *err)
{
    if (!dir || !ext || !buf || index < 0)
        return cl_error_set(err, CL_EINVAL, "invalid frame file request");
    size_t dl = strlen(dir);
    const char *sep = (dl == 0 || dir[dl - 1] == '/') ? "" : "/";
    int n = snprintf(buf, len, "%s%sframe_%05ld.%s", dir, sep, index, ext);
    if (n < 0 || (size_t)n >= len)
        return cl_error_set(err, CL_EINVAL,
                            "frame file name in '%s' is too long", dir);
    return CL_OK;
}
