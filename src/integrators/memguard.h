/* The memory guard: before an implicit integrator allocates its Jacobian
 * and the factors of its Newton matrix, estimate their size and refuse a
 * run that would not fit in the available memory (README "Memory guard";
 * docs/integrators.md, "Memory guard").  --force (cl_integrator_opts.force)
 * skips the check. */
#ifndef CL_MEMGUARD_H
#define CL_MEMGUARD_H

#include "core/decls.h"
#include "integrators/integrator.h"

CL_BEGIN_DECLS

/* Bytes the Jacobian, the Newton matrix and its factors of `type` (with
 * linear solver `linsol`: NULL or "" for the method's default) take on
 * `sys`; 0 for a method without a Jacobian. */
double cl_memguard_estimate(const cl_integrator_type *type,
                            const cl_system *sys, const char *linsol);

/* CL_ENOMEM with the estimate and the available memory when the estimate
 * exceeds it. */
cl_status cl_memguard_check(const cl_integrator_type *type,
                            const cl_system *sys, const char *linsol,
                            cl_error *err);

CL_END_DECLS

#endif
