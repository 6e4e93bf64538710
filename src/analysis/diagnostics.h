/* Shape diagnostics of a cloth state, for time series and blow-up checks. */
#ifndef CL_DIAGNOSTICS_H
#define CL_DIAGNOSTICS_H

#include "model/pairs.h"

/* Largest d/L over the pairs of `set` (e.g. the Type1 neighbours). */
double cl_max_stretch(const cl_pairset *set, const double *xfull);

/* Largest |y - Y0| over all particles: the displacement out of the rest
 * plane (the grid lies in y = 0, SPEC 2). */
double cl_max_offplane(const cl_cloth *c, const double *xfull);

#endif
