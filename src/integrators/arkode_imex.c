/* arkode-imex: ARKODE ARKStep's additive Runge-Kutta (IMEX) pairs of
 * Kennedy and Carpenter (--table ARK324L2SA, ARK436L2SA (default),
 * ARK548L2SA), adaptive at rtol, atol: the terms the model marks implicit
 * (each term's `imex` key; stiff ones by default) and x' = v in the DIRK
 * half, the others (gravity, Type2 bending by default) in the ERK half
 * (arkode_common.h).  Its bounded stability region (the explicit half's)
 * leaves the step to the error control: the adaptive region. */
#include "integrators/arkode_common.h"

CL_ARK_INTEGRATOR(arkode_imex, "arkode-imex", false, true, &cl_region_adaptive,
                  "ARKODE IMEX ARK pair (--table ARK324L2SA, ARK436L2SA, "
                  "ARK548L2SA), terms split by their imex key, adaptive");
