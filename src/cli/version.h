/* What built this clothode and what it runs on: `clothode --version` and
 * the "build" and "host" objects of run.json (README "Provenance"). */
#ifndef CL_CLI_VERSION_H
#define CL_CLI_VERSION_H

#include <stdio.h>

#include <jansson.h>

#include "core/decls.h"

CL_BEGIN_DECLS

/* The version, its git commit, the compiler and flags, the program's GNU
 * build ID (null when it was linked without one), and the versions of
 * the libraries linked (SUNDIALS, SuiteSparse, GSL, the BLAS and LAPACK
 * actually loaded, jansson, nettle): {"version", "commit", "compiler",
 * "flags", "build_id", "libraries": {...}}; NULL if out of memory. */
json_t *cl_cli_build_json(void);

/* The plug-ins this process has loaded (linalg/plugin.h), each
 * {"path" (resolved), "build_id"}: [] for a run that used none; NULL if
 * out of memory. */
json_t *cl_cli_plugins_json(void);

/* The machine: {"cpu" (model name), "cores", "system", "hostname"};
 * NULL if out of memory. */
json_t *cl_cli_host_json(void);

/* `clothode --version`: the build object as "name value" lines on fp;
 * returns the exit status. */
int cl_cli_version(FILE *fp);

CL_END_DECLS

#endif
