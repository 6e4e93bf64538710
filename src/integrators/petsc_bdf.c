/* petsc-bdf: PETSc's TSBDF, fixed-order BDF with variable steps, on the
 * first-order implicit form (integrators/petsc_ts.h; docs/integrators.md,
 * "PETSc TS").  --max-order K sets the order, 1 .. 6 (PETSc's default 2,
 * A-stable; orders 3 .. 6 are A(alpha)-stable only, and the region given
 * here is that of order 2). */
#include "integrators/petsc_ts.h"

CL_PETSC_TS_DEFINE(petsc_bdf, "petsc-bdf", "bdf", false, true,
                   &cl_region_a_stable,
                   "PETSc TSBDF (--max-order 1..6, default 2), analytic "
                   "Jacobian, LU; --petsc OPTIONS");
