/* The study loop of convergence, stability and energy (see study.h). */
#include "cli/study.h"

#include <stdlib.h>

#include "cli/progress.h"
#include "core/stop.h"

typedef struct {
    const cl_cli_study *st;
    const char *res;
} study_rows;

static void write_rows(FILE *fp, const void *ctx, int n)
{
    const study_rows *r = ctx;
    for (int k = 0; k < n; k++)
        r->st->rows(fp, r->res + (size_t)k * r->st->size, k == 0);
}

cl_status cl_cli_study_run(cl_model *m, const cl_cli_job *job,
                           const cl_cli_study *st, int n, void *ctx,
                           cl_error *err)
{
    char *res = calloc((size_t)n, st->size);
    if (!res)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    cl_status rc = cl_cli_check_output(job->outdir, st->csv, err);
    if (!rc)
        rc = st->begin(m, job, ctx, err);
    if (!rc && !job->quiet)
        puts(st->columns);
    int done = 0, ok = 0; /* runs started, runs finished */
    cl_cli_progress_line line;
    cl_cli_progress_start(&line, job->quiet, "integrators", "integrators", 0,
                          n);
    for (; !rc && done < n; done++) {
        if (cl_stop_requested()) {
            rc = cl_error_set(err, CL_EINTR, "interrupted by %s after %d "
                              "of %d runs", cl_stop_signal_name(
                                  cl_stop_requested()), done, n);
            break;
        }
        cl_cli_progress_show(&line, done);
        rc = st->run(m, ctx, done, res + (size_t)done * st->size, err);
        cl_cli_progress_clear(&line);
        if (!rc && !job->quiet)
            st->print(res + (size_t)done * st->size);
        ok += !rc;
        fflush(stdout);
    }
    if (!rc && st->summary && !job->quiet)
        st->summary(res, ok);
    cl_error later;
    if (ok > 0) {
        study_rows rows = {st, res};
        cl_status rc2 = cl_cli_write_csv(job->outdir, st->csv, write_rows,
                                         &rows, ok, rc ? &later : err);
        rc = rc ? rc : rc2;
    }
    if (!rc && !job->quiet)
        printf("output     %s/%s\n", job->outdir, st->csv);
    for (int k = 0; st->release && k < done; k++)
        st->release(res + (size_t)k * st->size);
    if (st->end)
        st->end(ctx);
    free(res);
    return rc;
}
