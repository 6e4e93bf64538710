/* petsc-arkimex: PETSc's TSARKIMEX, additive Runge-Kutta, here fully
 * implicit (every term in the implicit part: clothode's forces have no
 * non-stiff part worth splitting off) on the first-order implicit form
 * (integrators/petsc_ts.h; docs/integrators.md, "PETSc TS").  PETSc's
 * default tableau 3 (Kennedy and Carpenter, "Additive Runge-Kutta schemes
 * for convection-diffusion-reaction equations", 2003: ARK3(2)4L[2]SA, an
 * L-stable SDIRK with an embedded second-order error estimate); others by
 * --petsc "-ts_arkimex_type NAME". */
#include "integrators/petsc_ts.h"

CL_PETSC_TS_DEFINE(petsc_arkimex, "petsc-arkimex", "arkimex", false, false,
                   &cl_region_a_stable,
                   "PETSc TSARKIMEX fully implicit (ARK3 SDIRK), analytic "
                   "Jacobian, LU; --petsc OPTIONS");
