/* The loop shared by the subcommands that study several integrators on
 * one problem (convergence, workprecision, stability, energy): begin
 * (check every request, print the header), then for each integrator run
 * and print its result, then a summary over them all, then write the
 * results measured into one CSV file, also when a later integrator failed,
 * and release them. */
#ifndef CL_CLI_STUDY_H
#define CL_CLI_STUDY_H

#include <stdbool.h>
#include <stdio.h>

#include "cli/cli.h"
#include "core/decls.h"

CL_BEGIN_DECLS

typedef struct {
    const char *csv;      /* file name in the output directory */
    const char *columns;  /* the table's header line, printed after begin */
    size_t size;          /* bytes of one result */
    cl_status (*begin)(cl_model *m, const cl_cli_job *job, void *ctx,
                       cl_error *err);
    cl_status (*run)(cl_model *m, void *ctx, int k, void *result,
                     cl_error *err);
    void (*print)(const void *result);
    /* NULL, or a table over all results once they are in (not --quiet) */
    void (*summary)(const void *results, int n);
    void (*rows)(FILE *fp, const void *result, bool header);
    void (*release)(void *result); /* NULL: nothing to release */
    void (*end)(void *ctx);        /* NULL: nothing to release */
} cl_cli_study;

/* The study of n integrators; ctx is the command's own. */
cl_status cl_cli_study_run(cl_model *m, const cl_cli_job *job,
                           const cl_cli_study *st, int n, void *ctx,
                           cl_error *err);

CL_END_DECLS

#endif
