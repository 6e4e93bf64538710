/* Tests for cli/study: a study stopped by a signal writes the rows of
 * every run it finished and returns CL_EINTR. */
#include <criterion/criterion.h>

#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "cli/study.h"
#include "core/stop.h"
#include "tmpdir.h"

static cl_status begin(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err)
{
    (void)m, (void)job, (void)ctx, (void)err;
    return CL_OK;
}

/* Run k yields k * k; SIGINT arrives during run 1. */
static cl_status run(cl_model *m, void *ctx, int k, void *result,
                     cl_error *err)
{
    (void)m, (void)ctx, (void)err;
    *(int *)result = k * k;
    if (k == 1)
        raise(SIGINT);
    return CL_OK;
}

static void print(const void *result)
{
    (void)result;
}

static void rows(FILE *fp, const void *result, bool header)
{
    if (header)
        fputs("square\n", fp);
    fprintf(fp, "%d\n", *(const int *)result);
}

Test(study, signal_keeps_the_rows_of_finished_runs)
{
    char dir[64], path[128], text[256];
    tmp_mkdtemp(dir, sizeof dir, "study");
    cl_cli_job job = {"none", NULL, dir, true};
    cl_cli_study st = {.csv = "squares.csv", .columns = "square",
                       .size = sizeof(int), .begin = begin, .run = run,
                       .print = print, .rows = rows};
    cl_error err = {0};
    cl_stop_install();
    cr_assert_eq(cl_cli_study_run(NULL, &job, &st, 5, NULL, &err), CL_EINTR);
    cr_assert(strstr(err.msg, "SIGINT after 2 of 5 runs"), "%s", err.msg);
    snprintf(path, sizeof path, "%s/squares.csv", dir);
    tmp_slurp(path, text, sizeof text);
    cr_assert_str_eq(text, "square\n0\n1\n");
    tmp_rm_rf(dir);
}
