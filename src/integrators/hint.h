/* What to change when a solver gives up: for a failure flag of CVODE, IDA
 * or KINSOL (by its name, e.g. "CV_LSETUP_FAIL") or GSL ("GSL_EMAXITER"),
 * a sentence naming the options (--rtol, --linsol, --dt, [run] max_steps,
 * ...) that address it, for the end of the failure's message. */
#ifndef CL_HINT_H
#define CL_HINT_H

#include <stdbool.h>

#include "core/decls.h"

CL_BEGIN_DECLS

/* Never NULL: unknown flags get the general advice.  fixed_step: the
 * method takes fixed steps, which a failed Newton iteration does not make
 * smaller (arkode-*-fixed), so its advice names --dt and the Newton
 * iterations instead of the tolerances. */
const char *cl_solver_hint(const char *flag_name, bool fixed_step);

CL_END_DECLS

#endif
