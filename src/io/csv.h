/* CSV fields shared by the studies' tables. */
#ifndef CL_CSV_H
#define CL_CSV_H

#include <stdio.h>

#include "core/decls.h"

CL_BEGIN_DECLS

/* s as one quoted CSV field, a quote inside it doubled (RFC 4180). */
void cl_csv_quoted(FILE *fp, const char *s);

/* s as one CSV field: as it is, or quoted (cl_csv_quoted) when it holds a
 * comma, a quote or a newline. */
void cl_csv_text(FILE *fp, const char *s);

CL_END_DECLS

#endif
