/* One progress line on stderr for long work (README "Using it"): the
 * simulated time of `run` or the runs done of a study, the rate and the
 * time left, redrawn in place at most ten times a second.  Only on a
 * terminal and not with --quiet, so that logs and CSV files stay clean. */
#ifndef CL_CLI_PROGRESS_H
#define CL_CLI_PROGRESS_H

#include <stdbool.h>

#include "core/decls.h"

CL_BEGIN_DECLS

typedef struct {
    bool on;           /* stderr is a terminal and not --quiet */
    const char *what;  /* "t =" or "runs" */
    const char *unit;  /* "s" or "runs" */
    double from;       /* where the work starts: run's start time, or 0 */
    double total;      /* where it ends: t_end, or the runs */
    double t0, last;   /* wall clock at the start and at the last line */
    bool shown;        /* a line is on the terminal */
} cl_cli_progress_line;

void cl_cli_progress_start(cl_cli_progress_line *p, bool quiet,
                           const char *what, const char *unit, double from,
                           double total);

/* Redraw at `done`, from `from` to the total (the last one always
 * drawn). */
void cl_cli_progress_show(cl_cli_progress_line *p, double done);

/* Erase the line, before other output and at the end. */
void cl_cli_progress_clear(cl_cli_progress_line *p);

/* cl_sim_opts' progress callback: ctx a started line, fraction of the
 * way from `from` to the total. */
void cl_cli_progress(void *ctx, double fraction);

CL_END_DECLS

#endif
