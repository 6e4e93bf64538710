/* JSON documents read from regular files only (io/input.h): run.json,
 * sweep.json. */
#ifndef CL_JSONFILE_H
#define CL_JSONFILE_H

#include <jansson.h>

#include "core/decls.h"

CL_BEGIN_DECLS

/* The document at path, or NULL: with *why saying why when the file
 * cannot be opened (not there, not a regular file, ...), else (*why
 * NULL) with je saying where it is not JSON. */
json_t *cl_json_read(const char *path, json_error_t *je, const char **why);

CL_END_DECLS

#endif
