/* arkode-imex-fixed: the IMEX pairs of arkode-imex at the fixed step dt
 * (arkode_common.h); the split region. */
#include "integrators/arkode_common.h"

CL_ARK_INTEGRATOR(arkode_imex_fixed, "arkode-imex-fixed", true, true,
                  &cl_region_split,
                  "ARKODE IMEX ARK pair (--table), terms split by their "
                  "imex key, fixed step dt");
