/* CSV time-series writer on top of atomic output files. */
#include "io/series.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"

struct cl_series {
    cl_afile af;
    size_t ncol;
    unsigned char *na; /* per column: written as "NA" */
};

cl_status cl_series_open(const char *path, size_t ncol,
                         const char *const *names, cl_series **out,
                         cl_error *err)
{
    *out = NULL;
    if (ncol == 0 || !names)
        return cl_error_set(err, CL_EINVAL, "%s: a series needs at least "
                            "one column", path);
    for (size_t k = 0; k < ncol; k++)
        if (!names[k] || !names[k][0] || strpbrk(names[k], ",\"\r\n"))
            return cl_error_set(err, CL_EINVAL,
                                "%s: column %zu name \"%.40s\" is empty or "
                                "contains ',', '\"' or a line break", path,
                                k + 1, names[k] ? names[k] : "");

    cl_series *s = malloc(sizeof *s);
    unsigned char *na = calloc(ncol, 1);
    if (!s || !na) {
        free(s);
        free(na);
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
    }
    s->ncol = ncol;
    s->na = na;
    cl_status st = cl_afile_open(&s->af, path, err);
    if (st) {
        free(s->na);
        free(s);
        return st;
    }
    for (size_t k = 0; k < ncol; k++) {
        if (fprintf(s->af.fp, "%s%s", k ? "," : "", names[k]) < 0) {
            st = cl_afile_write_error(&s->af, err);
            break;
        }
    }
    if (st == CL_OK && (fputc('\n', s->af.fp) == EOF ||
                        fflush(s->af.fp) != 0))
        st = cl_afile_write_error(&s->af, err);
    if (st) {
        cl_series_discard(s);
        return st;
    }
    *out = s;
    return CL_OK;
}

void cl_series_not_applicable(cl_series *s, size_t col)
{
    if (s && col < s->ncol)
        s->na[col] = 1;
}

cl_status cl_series_row(cl_series *s, const double *values, cl_error *err)
{
    if (!s || !s->af.fp || !values)
        return cl_error_set(err, CL_EINVAL, "series row without a series "
                            "or values");
    for (size_t k = 0; k < s->ncol; k++)
        if ((s->na[k] ? fprintf(s->af.fp, "%sNA", k ? "," : "")
                      : fprintf(s->af.fp, "%s%.10g", k ? "," : "",
                                values[k])) < 0)
            return cl_afile_write_error(&s->af, err);
    if (fputc('\n', s->af.fp) == EOF || fflush(s->af.fp) != 0)
        return cl_afile_write_error(&s->af, err);
    return CL_OK;
}

cl_status cl_series_close(cl_series *s, cl_error *err)
{
    if (!s)
        return CL_OK;
    cl_status st = cl_afile_commit(&s->af, err);
    free(s->na);
    free(s);
    return st;
}

void cl_series_discard(cl_series *s)
{
    if (!s)
        return;
    cl_afile_abort(&s->af);
    free(s->na);
    free(s);
}
