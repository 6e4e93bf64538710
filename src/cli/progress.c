/* The progress line of run and the studies (see progress.h). */
#include "cli/progress.h"

#include <math.h>
#include <stdio.h>
#include <unistd.h>

#include "core/clock.h"

void cl_cli_progress_start(cl_cli_progress_line *p, bool quiet,
                           const char *what, const char *unit, double from,
                           double total)
{
    *p = (cl_cli_progress_line){.on = !quiet && isatty(STDERR_FILENO),
                                .what = what, .unit = unit, .from = from,
                                .total = total, .t0 = cl_clock_wall()};
    p->last = p->t0;
}

void cl_cli_progress_show(cl_cli_progress_line *p, double done)
{
    double now = p->on ? cl_clock_wall() : 0, spent = now - p->t0;
    if (!p->on || (now - p->last < 0.1 && done < p->total))
        return;
    p->last = now;
    double span = p->total - p->from, rate = spent > 0
                                                 ? (done - p->from) / spent
                                                 : NAN;
    fprintf(stderr, "\r\033[K%s %.4g of %.4g %s  %3.0f%%", p->what, done,
            p->total, p->unit, 100 * (done - p->from) / span);
    if (rate > 0)
        fprintf(stderr, "  %.3g %s/s  ETA %.2g s", rate, p->unit,
                (p->total - done) / rate);
    fflush(stderr);
    p->shown = true;
}

void cl_cli_progress_clear(cl_cli_progress_line *p)
{
    if (p->shown)
        fprintf(stderr, "\r\033[K");
    p->shown = false;
}

void cl_cli_progress(void *ctx, double fraction)
{
    cl_cli_progress_line *p = ctx;
    cl_cli_progress_show(p, p->from + fraction * (p->total - p->from));
}
