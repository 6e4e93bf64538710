/* Grid cloth: particles, rest geometry, masses, pins (SPEC 2).
 *
 * A grid has nu x nv particles; particle (i, j) has index i*nv + j and rest
 * position (i*hu, 0, j*hv) in the default horizontal x-z plane, with
 * hu = Su/(nu-1), hv = Sv/(nv-1) (a side of one particle, a chain, has
 * spacing 0 along it).  Pinned particles are not part of the ODE
 * state: their position and velocity are prescribed functions of time (here
 * X0 + w t, w = 0 for a fixed pin).  Free particles are numbered 0..nfree-1
 * in particle order; dof[p] is that number, or -1 for a pinned particle. */
#ifndef CL_CLOTH_H
#define CL_CLOTH_H

#include <stddef.h>

#include "core/error.h"

typedef struct {
    int p;          /* particle index */
    double w[3];    /* prescribed velocity (m/s) until t_stop */
    double t_stop;  /* time the motion stops (INFINITY: never) */
} cl_pin;

typedef struct {
    int nu, nv;       /* particles along u (first index) and v */
    size_t np;        /* nu * nv */
    double hu, hv;    /* rest spacing */
    double *X0;       /* rest positions, 3*np */
    double *mass;     /* per particle, np */
    size_t npin;
    cl_pin *pins;
    int *dof;         /* particle -> free index, or -1 if pinned */
    size_t nfree;
    int *free_p;      /* free index -> particle */
} cl_cloth;

/* Flat rectangular grid in the x-z plane at y = 0 (SPEC 2). */
cl_status cl_cloth_grid(int nu, int nv, double su, double sv,
                        double particle_mass, cl_cloth *c, cl_error *err);

/* Pin particle (i, j); negative indices count from the far edge (-1 is the
 * last row/column).  Pinning a particle again with the same motion does
 * nothing; with a different motion it is an error. */
cl_status cl_cloth_pin(cl_cloth *c, int i, int j, const double w[3],
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

/* Free state (3*nfree) from full arrays (3*np). */
void cl_cloth_gather(const cl_cloth *c, const double *full, double *freev);

#endif
