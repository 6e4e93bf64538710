/* Stopping a run early and cleanly: SIGINT and SIGTERM set a flag that the
 * run loops (analysis/simulate.c, analysis/trial.c, the study loop of the
 * command line) look at between steps, and that the model's force and
 * Jacobian evaluations look at too (system/system.h): they then fail with
 * CL_EINTR, which ends an integrator's advance however long it was to be.
 * What was computed up to the last output is written before the program
 * exits (README "Exit status").  A second SIGINT or SIGTERM ends the
 * program at once (the default action), unless it comes within
 * CL_STOP_REPEAT_S of the first: the same request sent twice, as
 * timeout(1) sends it to the process and then to its process group. */
#ifndef CL_STOP_H
#define CL_STOP_H

#include <stdbool.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

#define CL_STOP_REPEAT_S 0.1

/* Install the handler for SIGINT and SIGTERM (sigaction). */
void cl_stop_install(void);

/* The signal that first asked to stop (SIGINT, SIGTERM; SIGPROF and
 * SIGALRM for a CPU and a wall-time budget), or 0; SIGINT or SIGTERM
 * after a budget's timer replaces it. */
int cl_stop_requested(void);

/* A failure once a stop is requested is the stop's: CL_EINTR for st !=
 * CL_OK then (an iterative linear solve ends at a stop, and what it left
 * is no solver's failure), st otherwise. */
cl_status cl_stop_status(cl_status st);

/* Whether SIGINT or SIGTERM asked to stop (not a budget's timer). */
bool cl_stop_interrupted(void);

/* The clocks of a budget: CPU time of the process (ITIMER_PROF, SIGPROF)
 * and wall time (ITIMER_REAL, SIGALRM). */
typedef enum { CL_STOP_CPU, CL_STOP_WALL } cl_stop_clock;

/* Ask for a stop once `seconds` (> 0) more of `clock` have passed: a
 * one-shot timer whose signal sets the same flag, so that the model's
 * evaluations end an advance at once (a budget kept to the evaluation,
 * not to the next output).  CL_EINVAL for seconds <= 0 or not finite,
 * CL_EIO if the timer cannot be set. */
cl_status cl_stop_after(cl_stop_clock clock, double seconds, cl_error *err);

/* Disarm the timers cl_stop_after armed and give SIGPROF and SIGALRM
 * back the handlers theirs replaced (a host program's own; the default
 * action stays replaced, so that a late signal of the timer does not end
 * the process); other timers are left alone.  A stop already asked for
 * stays. */
void cl_stop_disarm(void);

/* cl_stop_disarm, and forget a budget's stop (SIGPROF, SIGALRM), so that
 * the next run starts clean (cl_simulate after a --max-wall run, a
 * benchmark's runs); a stop SIGINT or SIGTERM asked for stays. */
void cl_stop_clear(void);

/* "SIGINT", "SIGTERM" or "signal N", for messages. */
const char *cl_stop_signal_name(int sig);

/* A run stopped by the requested stop: CL_EINTR, "interrupted by SIGINT
 * at t = t_reached" (its last output time), and " (during the advance to
 * t = t_to)" when t_to is not NaN (the evaluations stopped an advance). */
cl_status cl_stop_error(cl_error *err, double t_reached, double t_to);

CL_END_DECLS

#endif
