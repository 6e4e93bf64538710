/* Shape diagnostics of a cloth state, for time series and blow-up checks. */
#ifndef CL_DIAGNOSTICS_H
#define CL_DIAGNOSTICS_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "model/pairs.h"

CL_BEGIN_DECLS

/* Largest distance |a_p - b_p| over np points (3 np coordinates each): how
 * far apart two states of the same cloth are. */
double cl_max_distance(const double *a, const double *b, size_t np);

/* Largest d/L over the pairs of `set` (e.g. the Type1 neighbours). */
double cl_max_stretch(const cl_pairset *set, const double *xfull);

/* Largest |y - Y0| over all particles: the displacement out of the rest
 * plane (the grid lies in y = 0, docs/model.md 2).  Meaningful only when
 * the rest positions lie in one horizontal plane (cl_offplane_applies). */
double cl_max_offplane(const cl_cloth *c, const double *xfull);

/* Whether every rest position has the same y: always on a grid, on a mesh
 * cloth only if it was built flat and horizontal. */
bool cl_offplane_applies(const cl_cloth *c);

/* Wrinkles along the centre line j = nv/2 of a grid cloth (a mesh cloth
 * has no such line: not to be called there): the number of sign
 * changes of the out-of-plane displacement y - Y0 along i, ignoring points
 * whose |y - Y0| is below 5% of the line's largest (so noise near zero does
 * not count).  0 for a flat or single-signed line. */
long cl_wrinkles(const cl_cloth *c, const double *xfull);

CL_END_DECLS

#endif
