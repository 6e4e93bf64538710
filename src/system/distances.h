/* The distance constraints of a model (system/system.h, cl_distances;
 * docs/model.md, 3.6): the pairs of every term with a `distances` hook
 * (forces/term.h), in term order, with their ends numbered for the
 * integrators (free index, or -1 - j for the pinned particle of pin j). */
#ifndef CL_DISTANCES_H
#define CL_DISTANCES_H

#include "core/decls.h"
#include "forces/term.h"
#include "model/cloth.h"
#include "system/system.h"

CL_BEGIN_DECLS

/* The arrays behind a cl_distances, owned. */
typedef struct {
    cl_distances d;
    int (*end)[2];
    double *rest, *stiffness;
} cl_distance_set;

/* Gather the constraints of the nterm terms (type[k], state[k]) on cloth
 * c into *ds; ds->d.n = 0 when none has any.  CL_ENOMEM only. */
cl_status cl_distance_set_build(const cl_cloth *c, size_t nterm,
                                const cl_term_type *const *type,
                                void *const *state, cl_distance_set *ds,
                                cl_error *err);
void cl_distance_set_free(cl_distance_set *ds);

CL_END_DECLS

#endif
