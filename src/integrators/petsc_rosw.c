/* petsc-rosw: PETSc's TSROSW, Rosenbrock-W methods (one linear solve per
 * stage, no Newton iteration), on the first-order implicit form
 * (integrators/petsc_ts.h; docs/integrators.md, "PETSc TS").  PETSc's
 * default tableau ra34pw2 (Rang and Angermann, "New Rosenbrock W-methods
 * of order 3 for partial differential algebraic equations of index 1",
 * 2005: third order, L-stable); others by --petsc "-ts_rosw_type NAME". */
#include "integrators/petsc_ts.h"

CL_PETSC_TS_DEFINE(petsc_rosw, "petsc-rosw", "rosw", false, false,
                   &cl_region_a_stable,
                   "PETSc TSROSW Rosenbrock-W (ra34pw2), analytic Jacobian, "
                   "LU; --petsc OPTIONS");
