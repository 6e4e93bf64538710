/* Cloth: particles, rest geometry, masses, triangles, pins
 * (docs/model.md, 2).
 *
 * Two kinds, told apart by `kind`:
 *   grid (CL_CLOTH_GRID): nu x nv particles; particle (i, j) has index
 *     i*nv + j and rest position (i*hu, 0, j*hv) in the default horizontal
 *     x-z plane, with hu = Su/(nu-1), hv = Sv/(nv-1) (a side of one
 *     particle, a chain, has spacing 0 along it); its triangles are
 *     cl_grid_triangles (io/frames.h);
 *   mesh (CL_CLOTH_MESH): the vertices and triangles of a triangle mesh
 *     (a Wavefront OBJ file, model/cloth_read.h), as Zischg, Chea and
 *     Aigner build their skirt in Blender ("Cloth Simulation"); nu = nv = 0
 *     and hu = hv = 0, so nothing that needs rows and columns applies.
 * Pinned particles are not part of the ODE
 * state: their position and velocity are prescribed functions of time (here
 * X0 + w t, w = 0 for a fixed pin).  Free particles are numbered 0..nfree-1
 * in particle order; dof[p] is that number, or -1 for a pinned particle. */
#ifndef CL_CLOTH_H
#define CL_CLOTH_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef enum { CL_CLOTH_GRID = 0, CL_CLOTH_MESH = 1 } cl_cloth_kind;

typedef struct {
    int p;          /* particle index */
    double w[3];    /* prescribed velocity (m/s) until t_stop */
    double t_stop;  /* time the motion stops (INFINITY: never) */
} cl_pin;

/* Free particles p .. p + n - 1, free indices k .. k + n - 1. */
typedef struct {
    size_t k, p, n;
} cl_cloth_run;

typedef struct {
    int nu, nv;       /* grid: particles along u (first index) and v */
    size_t np;        /* particles (nu * nv on a grid) */
    double hu, hv;    /* grid: rest spacing */
    double *X0;       /* rest positions, 3*np */
    double *mass;     /* per particle, np */
    size_t npin;
    cl_pin *pins;
    int *dof;         /* particle -> free index, or -1 if pinned */
    size_t nfree;
    int *free_p;      /* free index -> particle */
    size_t nrun;      /* the free particles as runs of consecutive ones: */
    cl_cloth_run *run;  /* nrun of them, in order */
    cl_cloth_kind kind;
    size_t ntri;
    int (*tri)[3];    /* the triangles (grid: cl_grid_triangles order;
                       * mesh: the file's, in its orientation) */
} cl_cloth;

/* Flat rectangular grid in the x-z plane at y = 0 (docs/model.md, 2). */
cl_status cl_cloth_grid(int nu, int nv, double su, double sv,
                        double particle_mass, cl_cloth *c, cl_error *err);

/* Mesh cloth of np particles at rest positions X0 (3 np, copied) and ntri
 * triangles (copied): each triangle needs three distinct vertices in
 * 0..np-1 and a non-zero area, each particle a triangle, each edge at most
 * two triangles (a surface, model/mesh.h).  Masses from
 * vertex areas: particle i gets mass A_i / A, A_i one third of the area of
 * every triangle it belongs to, A the total area (so they sum to mass). */
cl_status cl_cloth_mesh(size_t np, const double *X0, size_t ntri,
                        const int (*tri)[3], double mass, cl_cloth *c,
                        cl_error *err);

/* "nu x nv particles" (grid) or "np particles, ntri triangles" (mesh), for
 * summaries; written to buf (truncated to len), returns buf. */
const char *cl_cloth_shape(const cl_cloth *c, char *buf, size_t len);

/* Pin grid particle (i, j); negative indices count from the far edge (-1 is
 * the last row/column).  Pinning a particle again with the same motion does
 * nothing; with a different motion it is an error. */
cl_status cl_cloth_pin(cl_cloth *c, int i, int j, const double w[3],
                       double t_stop, cl_error *err);

/* Pin particle p; negative p counts from the end (-1 is the last).  The
 * same rules for repeated pins as cl_cloth_pin. */
cl_status cl_cloth_pin_particle(cl_cloth *c, int p, const double w[3],
                                double t_stop, cl_error *err);

/* Build the free-particle numbering; call once after all pins. */
cl_status cl_cloth_finalize(cl_cloth *c, cl_error *err);

void cl_cloth_free(cl_cloth *c);

static inline int cl_cloth_index(const cl_cloth *c, int i, int j)
{
    return i * c->nv + j;
}

/* Full-particle arrays (3*np) from the free state (3*nfree) at time t:
 * free particles copied, pinned ones set to their prescribed motion.
 * v may be NULL (then vfull is not touched). */
void cl_cloth_scatter(const cl_cloth *c, double t, const double *x,
                      const double *v, double *xfull, double *vfull);

/* The prescribed position at time t of pin k (0 .. npin - 1). */
void cl_cloth_pin_position(const cl_cloth *c, size_t k, double t,
                           double x[3]);

/* Free state (3*nfree) from full arrays (3*np). */
void cl_cloth_gather(const cl_cloth *c, const double *full, double *freev);

CL_END_DECLS

#endif
