/* Cloth state files: CSV with header exactly
 *
 *   p,x,y,z,vx,vy,vz
 *
 * and one row per particle (pinned particles included), p being the particle
 * index i*nv + j.  Written with "%.17g" so that doubles round-trip exactly.
 * Rows may come in any order when read, but every particle must appear
 * exactly once. */
#ifndef CL_STATE_H
#define CL_STATE_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

/* Write np particles (x and v are 3*np each, particle-major) atomically. */
cl_status cl_state_write(const char *path, size_t np, const double *x,
                         const double *v, cl_error *err);

/* Read a state file for np particles into x[3*np] and v[3*np].
 * CL_EIO if the file cannot be read; CL_EPARSE "file:line: ..." for a
 * missing or wrong header, a row without exactly 7 fields, a non-numeric or
 * non-finite value, a particle index out of range or repeated; CL_EPARSE
 * naming the first missing particle if some are absent.  Blank lines are
 * ignored and "\r\n" line ends accepted.  On failure x and v may have been
 * partly overwritten. */
cl_status cl_state_read(const char *path, size_t np, double *x, double *v,
                        cl_error *err);

CL_END_DECLS

#endif
