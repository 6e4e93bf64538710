/* arkode-dirk: ARKODE ARKStep, a diagonally implicit Runge-Kutta method
 * (SDIRK / ESDIRK) with its embedded error estimate, adaptive at rtol,
 * atol, on y' = (v, M^-1 f) with the Newton matrix of cvode-bdf (the
 * half-size system, every --linsol); the table by name (--table, default
 * ARK436L2SA_DIRK_6_3_4).  Everything else is the module's
 * (arkode_common.h).  The built-in tables are A-stable (most L-stable):
 * the a-stable region, as for the fixed-step implicit methods. */
#include "integrators/arkode_common.h"

CL_ARK_INTEGRATOR(arkode_dirk, "arkode-dirk", false, false,
                  &cl_region_a_stable,
                  "ARKODE DIRK (--table, default ARK436L2SA_DIRK_6_3_4), "
                  "adaptive, Newton on the half-size matrix, --linsol as "
                  "cvode-bdf");
