/* Cloth frames for viewing: legacy VTK (ASCII polydata) and Wavefront OBJ.
 *
 * The surface is the grid's triangulation (cl_grid_triangles): each quad
 * (i, j)-(i+1, j+1) is split into (i,j),(i+1,j),(i+1,j+1) and
 * (i,j),(i+1,j+1),(i,j+1), particle (i, j) having index i*nv + j; or, when
 * the frame gives one, its own triangle list (a torn cloth: the cloth's
 * triangles without those with a torn edge, cl_model_triangles; a mesh
 * cloth: its triangles, its particles given as nu = np, nv = 0).
 * VTK frames carry the time as field data TIME (read by ParaView) and, when
 * given, point data "velocity" (vectors) and "pinned" (0/1 scalars).  OBJ
 * frames carry positions and faces only, the time in a comment.  Both are
 * written atomically. */
#ifndef CL_FRAMES_H
#define CL_FRAMES_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef struct {
    int nu, nv;                   /* grid size, nu*nv particles; nv = 0:
                                   * a mesh cloth of nu particles (then tri
                                   * is required) */
    const double *x;              /* positions, 3 * particles */
    const double *v;              /* velocities, 3 * particles, or NULL */
    const unsigned char *pinned;  /* per particle, nonzero = pinned, or NULL */
    double t;                     /* time */
    const int (*tri)[3];          /* triangles (0-based particle indices),
                                   * or NULL for all grid triangles */
    size_t ntri;                  /* rows of tri */
} cl_frame;

/* Triangles of an nu x nv grid as 0-based particle indices; returns their
 * number 2(nu-1)(nv-1) (0 if nu < 2 or nv < 2).  tri may be NULL to only
 * count; otherwise it must hold that many entries.  Order: quads by i then
 * j, the two triangles of each quad in the order given above. */
size_t cl_grid_triangles(int nu, int nv, int (*tri)[3]);

cl_status cl_frame_write_vtk(const char *path, const cl_frame *f,
                             cl_error *err);
cl_status cl_frame_write_obj(const char *path, const cl_frame *f,
                             cl_error *err);

/* "DIR/frame_00042.EXT" (index zero-padded to 5 digits, more if needed;
 * just "frame_00042.EXT" if dir is "") into buf; CL_EINVAL if it does not
 * fit in len bytes or index < 0. */
cl_status cl_frame_path(const char *dir, long index, const char *ext,
                        char *buf, size_t len, cl_error *err);
/* The same with another stem than "frame" ("obstacles_00042.EXT"). */
cl_status cl_frame_path_stem(const char *dir, const char *stem, long index,
                             const char *ext, char *buf, size_t len,
                             cl_error *err);

CL_END_DECLS

#endif
