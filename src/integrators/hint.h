/* What to change when a solver gives up: for a failure flag of CVODE, IDA
 * or KINSOL (by its name, e.g. "CV_LSETUP_FAIL") or GSL ("GSL_EMAXITER"),
 * a sentence naming the options (--rtol, --linsol, --dt, [run] max_steps,
 * ...) that address it, for the end of the failure's message. */
#ifndef CL_HINT_H
#define CL_HINT_H

/* Never NULL: unknown flags get the general advice. */
const char *cl_solver_hint(const char *flag_name);

#endif
