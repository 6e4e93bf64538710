/* SHA-256 of a file (FIPS 180-4), by nettle: the problem file and every
 * output a run lists in its run.json; and of a text. */
#ifndef CL_SHA256_H
#define CL_SHA256_H

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

#define CL_SHA256_HEX 65 /* 64 hex digits and the NUL */

/* The digest of the file at path as lowercase hex into hex; CL_EIO naming
 * the path and the reason if it cannot be read. */
cl_status cl_sha256_file(const char *path, char hex[CL_SHA256_HEX],
                         cl_error *err);

/* The digest of the NUL-terminated text as lowercase hex into hex. */
void cl_sha256_text(const char *text, char hex[CL_SHA256_HEX]);

CL_END_DECLS

#endif
