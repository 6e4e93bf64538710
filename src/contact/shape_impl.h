/* Internals shared by the shape files (contact/shape_*.c): reading their
 * keys, the answer of a query from a closest point, surfaces.  Not part of
 * the library's interface. */
#ifndef CL_SHAPE_IMPL_H
#define CL_SHAPE_IMPL_H

#include <stdbool.h>

#include "contact/shape.h"
#include "core/decls.h"

CL_BEGIN_DECLS

/* CL_EINVAL "ORIGIN: [sec] key = "value": expected WHAT", the form of the
 * typed getters of io/config.h, for a value they read but the shape does
 * not allow. */
cl_status cl_shape_bad_value(cl_config *cfg, const char *sec,
                             const char *key, const char *what,
                             cl_error *err);

/* A finite number > 0, def if the key is absent (def NaN: required). */
cl_status cl_shape_positive(cl_config *cfg, const char *sec, const char *key,
                            double def, double *out, cl_error *err);

/* Three finite numbers; if absent, out is left alone (required: an
 * error). */
cl_status cl_shape_vector(cl_config *cfg, const char *sec, const char *key,
                          bool required, double out[3], cl_error *err);

/* The end of an analytic shape's create: a copy of the size bytes at src
 * in *shape, and its pivot at `at`. */
cl_status cl_shape_copy(const void *src, size_t size, const double at[3],
                        double pivot[3], void **shape, cl_error *err);

/* q for the point x whose closest surface point is c, on the side `sign`
 * (+1 outside, -1 inside): d = sign |x - c|, n = sign (x - c) / |x - c|,
 * G = 0.  When |x - c| <= tiny (x on the surface, where the direction is
 * lost in round-off) n = n0 instead.  Returns whether the direction of
 * x - c was used. */
bool cl_shape_answer(const double x[3], const double c[3], double sign,
                     const double n0[3], double tiny, cl_shape_query *q);

/* G = (I - n n^T - e e^T) / rho, without the e term when e is NULL: the
 * Hessian of the distance to a line of direction e (or to a point) at
 * distance rho, n the unit direction away from it. */
void cl_shape_hessian(const double n[3], const double *e, double rho,
                      double G[9]);

/* Room for nvert vertices and the ntri triangles tri, copied (free with
 * cl_shape_surface_free). */
cl_status cl_shape_surface_alloc(cl_shape_surface *s, size_t nvert,
                                 size_t ntri, const int (*tri)[3],
                                 cl_error *err);

CL_END_DECLS

#endif
