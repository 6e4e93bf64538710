/* run.json, the provenance of a run (README "Provenance", its schema):
 * written when the run starts, with status "running", and again when it
 * ends, with its status, times and the SHA-256 of every file it wrote. */
#ifndef CL_CLI_MANIFEST_H
#define CL_CLI_MANIFEST_H

#include <jansson.h>

#include "cli/cli.h"
#include "core/decls.h"
#include "core/stats.h"

CL_BEGIN_DECLS

typedef struct {
    json_t *root;
    const char *dir;
    double wall0, cpu0; /* clocks at the start (cl_manifest_clocks) */
} cl_manifest;

/* Start mf's clocks: run.json's times are from here. */
void cl_manifest_clocks(cl_manifest *mf);

/* Start job's run.json (mf's clocks started): the program, its build, the command line argv
 * (argc entries, the subcommand first), the working directory, the
 * problem file with its SHA-256, the fully resolved configuration, the
 * thread count, the host and the start time, status "running". */
cl_status cl_manifest_begin(cl_manifest *mf, const cl_cli_job *job, int argc,
                            char **argv, long threads, cl_error *err);

/* End it: the status of the run's outcome rc (why: its message), the end
 * time, wall and CPU time of the whole command and of the integrator (st),
 * the exit status, and every file of the run in the directory with its
 * size and SHA-256; then release mf. */
cl_status cl_manifest_end(cl_manifest *mf, cl_status rc, const cl_error *why,
                          const cl_stats *st, cl_error *err);

CL_END_DECLS

#endif
