/* Cloth frames: legacy VTK polydata and Wavefront OBJ. */
#include "io/frames.h"

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

/* Validate the frame and build its triangle list (*tri NULL if none) when
 * the frame has none of its own (*own: the caller frees *tri). */
static cl_status frame_prepare(const char *path, const cl_frame *f,
                               const int (**tri)[3], size_t *ntri,
                               int (**own)[3], cl_error *err)
{
    *tri = NULL;
    *own = NULL;
    *ntri = 0;
    if (!f || !f->x || f->nu < 1 || f->nv < 0 || (f->nv == 0 && !f->tri))
        return cl_error_set(err, CL_EINVAL, "%s: empty or invalid frame",
                            path);
    if (f->tri) {
        *tri = f->tri;
        *ntri = f->ntri;
        return CL_OK;
    }
    size_t n = cl_grid_triangles(f->nu, f->nv, NULL);
    if (n == 0)
        return CL_OK;
    *own = malloc(n * sizeof **own);
    if (!*own)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
    cl_grid_triangles(f->nu, f->nv, *own);
    *tri = (const int(*)[3]) * own;
    *ntri = n;
    return CL_OK;
}

/* One line "<prefix>a0 a1 a2" per point of the np 3-vectors a; nonzero on
 * a write error. */
static int write_points(FILE *fp, const char *prefix, const double *a,
                        size_t np)
{
    for (size_t p = 0; p < np; p++)
        if (fprintf(fp, "%s%.17g %.17g %.17g\n", prefix, a[3 * p],
                    a[3 * p + 1], a[3 * p + 2]) < 0)
            return 1;
    return 0;
}

/* One line "<prefix>i j k" per triangle, vertex numbers from `base`;
 * nonzero on a write error. */
static int write_triangles(FILE *fp, const char *prefix,
                           const int (*tri)[3], size_t ntri, int base)
{
    for (size_t k = 0; k < ntri; k++)
        if (fprintf(fp, "%s%d %d %d\n", prefix, tri[k][0] + base,
                    tri[k][1] + base, tri[k][2] + base) < 0)
            return 1;
    return 0;
}

/* "nu=NU nv=NV" of a grid, "np=NP" of a mesh cloth, for the header. */
static const char *frame_shape(const cl_frame *f, char *buf, size_t len)
{
    if (f->nv == 0)
        snprintf(buf, len, "np=%d", f->nu);
    else
        snprintf(buf, len, "nu=%d nv=%d", f->nu, f->nv);
    return buf;
}

/* The content of one file format: np points, ntri triangles; nonzero on a
 * write error (errno says why). */
typedef int (*frame_body)(FILE *fp, const cl_frame *f, size_t np,
                          const int (*tri)[3], size_t ntri);

static int vtk_body(FILE *fp, const cl_frame *f, size_t np,
                    const int (*tri)[3], size_t ntri)
{
    char shape[64];
    int bad = fprintf(fp, "# vtk DataFile Version 3.0\n"
                          "clothode frame t=%.17g %s\n"
                          "ASCII\n"
                          "DATASET POLYDATA\n"
                          "FIELD FieldData 1\n"
                          "TIME 1 1 double\n"
                          "%.17g\n"
                          "POINTS %zu double\n",
                      f->t, frame_shape(f, shape, sizeof shape), f->t,
                      np) < 0 ||
              write_points(fp, "", f->x, np);
    if (!bad && ntri > 0)
        bad = fprintf(fp, "POLYGONS %zu %zu\n", ntri, 4 * ntri) < 0 ||
              write_triangles(fp, "3 ", tri, ntri, 0);
    if (!bad && (f->v || f->pinned))
        bad = fprintf(fp, "POINT_DATA %zu\n", np) < 0;
    if (!bad && f->v)
        bad = fprintf(fp, "VECTORS velocity double\n") < 0 ||
              write_points(fp, "", f->v, np);
    if (!bad && f->pinned) {
        bad = fprintf(fp, "SCALARS pinned int 1\n"
                          "LOOKUP_TABLE default\n") < 0;
        for (size_t p = 0; !bad && p < np; p++)
            bad = fprintf(fp, "%d\n", f->pinned[p] ? 1 : 0) < 0;
    }
    return bad;
}

static int obj_body(FILE *fp, const cl_frame *f, size_t np,
                    const int (*tri)[3], size_t ntri)
{
    char shape[64];
    return fprintf(fp, "# clothode frame t=%.17g %s\n"
                       "# %zu vertices, %zu triangles\n",
                   f->t, frame_shape(f, shape, sizeof shape), np, ntri) < 0 ||
           write_points(fp, "v ", f->x, np) ||
           write_triangles(fp, "f ", tri, ntri, 1);
}

/* Validate the frame, write it with `body` to a temporary file and commit
 * it onto path; after a write error the temporary file is removed and the
 * message gives errno's reason. */
static cl_status frame_write(const char *path, const cl_frame *f,
                             frame_body body, cl_error *err)
{
    const int(*tri)[3];
    int(*own)[3];
    size_t ntri;
    cl_status st = frame_prepare(path, f, &tri, &ntri, &own, err);
    if (st)
        return st;
    cl_afile af;
    if ((st = cl_afile_open(&af, path, err)) == CL_OK) {
        size_t np = (size_t)f->nu * (size_t)(f->nv ? f->nv : 1);
        st = body(af.fp, f, np, tri, ntri) ? cl_afile_fail(&af, err)
                                           : cl_afile_commit(&af, err);
    }
    free(own);
    return st;
}

cl_status cl_frame_write_vtk(const char *path, const cl_frame *f,
                             cl_error *err)
{
    return frame_write(path, f, vtk_body, err);
}

cl_status cl_frame_write_obj(const char *path, const cl_frame *f,
                             cl_error *err)
{
    return frame_write(path, f, obj_body, err);
}

cl_status cl_frame_path(const char *dir, long index, const char *ext,
                        char *buf, size_t len, cl_error *err)
{
    return cl_frame_path_stem(dir, "frame", index, ext, buf, len, err);
}

cl_status cl_frame_path_stem(const char *dir, const char *stem, long index,
                             const char *ext, char *buf, size_t len,
                             cl_error *err)
{
    if (!dir || !ext || !buf || index < 0)
        return cl_error_set(err, CL_EINVAL, "invalid frame file request");
    size_t dl = strlen(dir);
    const char *sep = (dl == 0 || dir[dl - 1] == '/') ? "" : "/";
    int n = snprintf(buf, len, "%s%s%s_%05ld.%s", dir, sep, stem, index,
                     ext);
    if (n < 0 || (size_t)n >= len)
        return cl_error_set(err, CL_EINVAL,
                            "frame file name in '%s' is too long", dir);
    return CL_OK;
}
