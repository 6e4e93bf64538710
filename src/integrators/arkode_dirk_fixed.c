/* arkode-dirk-fixed: ARKODE ARKStep's DIRK methods (arkode-dirk) at the
 * fixed step dt, the embedded estimate unused; besides SUNDIALS' tables
 * BACKWARD_EULER_1_1 and IMPLICIT_MIDPOINT_1_2 (kinsol-be's and
 * kinsol-midpoint's methods; arkode_common.h).  A-stable. */
#include "integrators/arkode_common.h"

CL_ARK_INTEGRATOR(arkode_dirk_fixed, "arkode-dirk-fixed", true, false,
                  &cl_region_a_stable,
                  "ARKODE DIRK (--table, also BACKWARD_EULER_1_1, "
                  "IMPLICIT_MIDPOINT_1_2), fixed step dt, Newton on the "
                  "half-size matrix");
