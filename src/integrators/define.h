/* Integrator tables for methods built on a shared module (fixed_step.h,
 * gslode.h): the module provides create(method, ...),
 * advance, stats and free; a method file provides a method description
 * `method` and gets
 *
 *   static create function  ident_create(sys, opts, t0, x0, v0, state, err)
 *                           = module_create(&method, sys, ...)
 *   const cl_integrator_type ident = {name_, region_, doc_, fixed_,
 *                           linsol_, dense_, rayleigh_, vdamp_,
 *                           ident_create, advance_, stats_, free_}
 *
 * for one row of the registry (integrators/registry.c).  The create
 * function alone (CL_INTEGRATOR_CREATE) also serves the families whose
 * tables carry other flags (arkode_common.h, constraint_common.h,
 * kinsol_common.h, petsc_ts.h). */
#ifndef CL_DEFINE_H
#define CL_DEFINE_H

#include "core/decls.h"
#include "integrators/integrator.h"

CL_BEGIN_DECLS

/* static create function ident_create(sys, opts, t0, x0, v0, state, err)
 * = create_(method_, sys, ...), method_ a pointer to the method's
 * description. */
#define CL_INTEGRATOR_CREATE(ident, create_, method_)                       \
    static cl_status ident##_create(const cl_system *sys,                   \
                                    const cl_integrator_opts *o, double t0, \
                                    const double *x0, const double *v0,     \
                                    void **state, cl_error *err)            \
    {                                                                       \
        return create_((method_), sys, o, t0, x0, v0, state, err);          \
    }

#define CL_INTEGRATOR_DEFINE(ident, method, create_, name_, region_, doc_, \
                             fixed_, linsol_, dense_, rayleigh_, vdamp_,  \
                             advance_, stats_, free_)                       \
    CL_INTEGRATOR_CREATE(ident, create_, &(method))                         \
    const cl_integrator_type ident = {                                      \
        .name = (name_),                                                    \
        .region = (region_),                                                \
        .doc = (doc_),                                                      \
        .fixed_step = (fixed_),                                             \
        .takes_linsol = (linsol_),                                          \
        .dense_jacobian = (dense_),                                         \
        .takes_rayleigh = (rayleigh_),                                      \
        .takes_vdamp = (vdamp_),                                            \
        .create = ident##_create,                                           \
        .advance = (advance_),                                              \
        .stats = (stats_),                                                  \
        .free = (free_),                                                    \
    }

CL_END_DECLS

#endif
