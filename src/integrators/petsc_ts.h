/* The petsc-ts family (docs/integrators.md, "PETSc TS"): PETSc's TS
 * integrators on clothode's model and analytic Jacobians, one method per
 * file (petsc_bdf.c, petsc_alpha2.c, petsc_arkimex.c, petsc_rosw.c), this
 * module shared by them.  PETSc itself lives in the plug-in
 * clothode-petsc.so (integrators/petsc_ts_petsc.c, linalg/plugin.h): this
 * side hands it the pattern, the masses and the force and Jacobian as
 * callbacks (integrators/petsc_ts_abi.h) and sees only the cl_system.
 *
 * Steps: adaptive at rtol/atol (defaults 1e-6, 1e-8) from a first step dt
 * or 1e-5 s, PETSc's TSAdapt choosing them; with opts->dt > 0 fixed steps
 * of dt (TSAdapt none).  Every step that reaches an output time ends on it
 * (TS_EXACTFINALTIME_MATCHSTEP: TSALPHA2 cannot interpolate).
 * opts->petsc (--petsc) is handed to PETSc's options, read after
 * clothode's own choices so that they override them ("-ts_adapt_type
 * basic -pc_type gamg -ksp_type cg"). */
#ifndef CL_PETSC_TS_H
#define CL_PETSC_TS_H

#include "core/decls.h"
#include "integrators/define.h"
#include "integrators/integrator.h"

CL_BEGIN_DECLS

typedef struct {
    const char *name;     /* "petsc-bdf" */
    const char *ts_type;  /* PETSc's TSType, "bdf" */
    bool second_order;    /* TSSetI2Function on x (TSALPHA2) */
    bool takes_order;     /* opts->max_order is TSBDF's order 1..6 */
} cl_petsc_ts_method;

cl_status cl_petsc_ts_create(const cl_petsc_ts_method *m,
                             const cl_system *sys,
                             const cl_integrator_opts *o, double t0,
                             const double *x0, const double *v0,
                             void **state, cl_error *err);
cl_status cl_petsc_ts_advance(void *state, double t_out, double *x,
                              double *v, cl_error *err);
void cl_petsc_ts_stats(const void *state, cl_stats *s);
void cl_petsc_ts_free(void *state);

/* The method and the table cl_integrator_IDENT of one method of the
 * family: its name, PETSc's TSType, the form (second order or not),
 * whether --max-order sets its order, its stability region and the line
 * of `clothode list`. */
#define CL_PETSC_TS_DEFINE(ident, name_, ts_type_, second_, order_,        \
                           region_, doc_)                                   \
    static const cl_petsc_ts_method ident##_method = {                      \
        .name = (name_),                                                    \
        .ts_type = (ts_type_),                                              \
        .second_order = (second_),                                          \
        .takes_order = (order_),                                            \
    };                                                                      \
    CL_INTEGRATOR_CREATE(ident, cl_petsc_ts_create, &ident##_method)        \
    const cl_integrator_type cl_integrator_##ident = {                      \
        .name = (name_),                                                    \
        .region = (region_),                                                \
        .doc = (doc_),                                                      \
        .fixed_step = false,                                                \
        .dt_fixes_step = true,                                              \
        .takes_max_order = (order_),                                        \
        .takes_petsc = true,                                                \
        .create = ident##_create,                                           \
        .advance = cl_petsc_ts_advance,                                     \
        .stats = cl_petsc_ts_stats,                                         \
        .free = cl_petsc_ts_free,                                           \
    }

CL_END_DECLS

#endif
