/* Pins from the problem file (README.md, "Problems", and the problem files
 * under problems/).
 *
 * Up to four groups, INI sections [pins], [pins2], [pins3], [pins4], each
 *   at       = particles to pin, separated by spaces: "p=K" for particle
 *              K (on a mesh cloth the 0-based vertex index of the OBJ file,
 *              on a grid i*nv + j), and on a grid only "i,j" for one
 *              particle, "i=K" for the whole row i = K, "j=K" for the whole
 *              column j = K; negative indices count from the end or the far
 *              edge ("p=-1" is the last particle, "0,-1" is (0, nv-1),
 *              "i=-1" the last row).  Default for [pins] on a grid without
 *              a box: "0,0 0,-1"; otherwise none.
 *   box      = x0, y0, z0, x1, y1, z1: also pin every particle whose rest
 *              position lies in the box x0 <= x <= x1, y0 <= y <= y1,
 *              z0 <= z <= z1 (m; any cloth); a box that holds no particle
 *              is an error
 *   velocity = prescribed velocity of the group (vector, m/s, default 0)
 *   stop     = time at which the group stops moving (s, default never)
 * A particle pinned twice must be given the same motion. */
#ifndef CL_PINS_H
#define CL_PINS_H

#include "core/decls.h"
#include "io/config.h"
#include "model/cloth.h"

CL_BEGIN_DECLS

cl_status cl_pins_read(cl_config *cfg, cl_cloth *c, cl_error *err);

CL_END_DECLS

#endif
