/* CSV time series (energies, step sizes, error norms, ...).
 *
 * The header line (column names joined by ',') is written first, then one
 * line per cl_series_row, values printed with "%.10g" (ten significant
 * digits; non-finite values appear as nan / inf / -inf, which common CSV
 * readers accept).  Each row is flushed at once, so the data survive in the
 * temporary file "PATH.tmp.XXXXXX" even if the process dies.  The file
 * appears at PATH only when cl_series_close renames it there, atomically;
 * callers close the series on error paths as well (e.g. after a blow-up),
 * so that everything computed up to that point ends up at PATH. */
#ifndef CL_SERIES_H
#define CL_SERIES_H

#include <stddef.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

typedef struct cl_series cl_series;

/* Open a series with ncol >= 1 columns.  Names must be non-empty and
 * contain no ',', '"', or line breaks (CL_EINVAL). */
cl_status cl_series_open(const char *path, size_t ncol,
                         const char *const *names, cl_series **out,
                         cl_error *err);

/* Mark column col (0-based, < ncol) as not applicable to this series:
 * every row then writes "NA" there, whatever its value (a diagnostic that
 * has no meaning for the problem at hand, e.g. a grid's on a mesh cloth). */
void cl_series_not_applicable(cl_series *s, size_t col);

/* Append one row of ncol values and flush it.  CL_EIO on a write error. */
cl_status cl_series_row(cl_series *s, const double *values, cl_error *err);

/* Rename the file onto its path and free s (also on failure).  s may be
 * NULL.  CL_EIO if the file could not be completed (a failed row write
 * included); the temporary file is then removed. */
cl_status cl_series_close(cl_series *s, cl_error *err);

/* Free s and remove its temporary file without publishing it. */
void cl_series_discard(cl_series *s);

CL_END_DECLS

#endif
