/* Pins from the problem file (SPEC 6).
 *
 * Up to four groups, INI sections [pins], [pins2], [pins3], [pins4], each
 *   at       = particles to pin, separated by spaces: "i,j" for one
 *              particle, "i=K" for the whole row i = K, "j=K" for the whole
 *              column j = K; negative indices count from the far edge
 *              ("0,-1" is (0, nv-1), "i=-1" the last row).  Default for
 *              [pins]: "0,0 0,-1"; the other groups default to none.
 *   velocity = prescribed velocity of the group (vector, m/s, default 0)
 *   stop     = time at which the group stops moving (s, default never)
 * A particle may be pinned once. */
#ifndef CL_PINS_H
#define CL_PINS_H

#include "io/config.h"
#include "model/cloth.h"

cl_status cl_pins_read(cl_config *cfg, cl_cloth *c, cl_error *err);

#endif
