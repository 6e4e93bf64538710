/* Value checks shared by every layer: finiteness of an array, and the
 * diagonal masses that integrators and linear solvers divide by. */
#ifndef CL_CHECK_H
#define CL_CHECK_H

#include <stdbool.h>
#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

/* true if all n values of a are finite (n = 0: true). */
bool cl_all_finite(const double *a, size_t n);
/* cl_all_finite on `threads` OpenMP threads over equal ranges (for the
 * Jacobians' values; the same answer for every count). */
bool cl_all_finite_threads(const double *a, size_t n, int threads);

/* CL_OK if all n masses are finite and > 0; otherwise CL_EINVAL with the
 * message "<who>: mass[i] = m, must be finite and > 0" for the first bad
 * one. */
cl_status cl_check_masses(const double *mass, size_t n, const char *who,
                          cl_error *err);

CL_END_DECLS

#endif
