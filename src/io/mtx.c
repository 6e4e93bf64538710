/* Matrix Market writer for block matrices and a coordinate-format reader. */
#include "io/mtx.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "io/atomic.h"
#include "io/input.h"

#define MTX_LINE_MAX 65536 /* bytes of a line, comments included */

cl_status cl_mtx_write_blocks(const char *path, const cl_bpattern *pat,
                              const double *val, cl_error *err)
{
    if (!pat || (pat->nnzb > 0 && (!val || !pat->col)) || !pat->rowptr)
        return cl_error_set(err, CL_EINVAL, "%s: no matrix to write", path);
    cl_afile af;
    cl_status st = cl_afile_open(&af, path, err);
    if (st)
        return st;
    FILE *fp = af.fp;
    size_t n = 3 * pat->nb;
    if (fprintf(fp, "%%%%MatrixMarket matrix coordinate real general\n"
                    "%% clothode: %zu x %zu blocks of 3x3, %zu stored\n"
                    "%zu %zu %zu\n",
                pat->nb, pat->nb, pat->nnzb, n, n, 9 * pat->nnzb) < 0)
        goto write_fail;
    /* Row by row so the entries come out sorted (columns are sorted within
     * each block row). */
    for (size_t bi = 0; bi < pat->nb; bi++)
        for (size_t r = 0; r < 3; r++)
            for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++)
                for (size_t c = 0; c < 3; c++)
                    if (fprintf(fp, "%zu %zu %.17g\n", 3 * bi + r + 1,
                                3 * pat->col[k] + c + 1,
                                val[9 * k + 3 * r + c]) < 0)
                        goto write_fail;
    return cl_afile_commit(&af, err);

write_fail:
    return cl_afile_fail(&af, err);
}

void cl_triplets_free(cl_triplets *t)
{
    if (!t)
        return;
    free(t->row);
    free(t->col);
    free(t->val);
    memset(t, 0, sizeof *t);
}

static const char *skip_blanks(const char *s)
{
    while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\n')
        s++;
    return s;
}

/* An unsigned decimal integer at *s (after blanks); advances *s. */
static int next_size(const char **s, size_t *out)
{
    const char *p = skip_blanks(*s);
    if (!isdigit((unsigned char)*p))
        return 0;
    char *end;
    errno = 0;
    unsigned long long u = strtoull(p, &end, 10);
    if (errno == ERANGE || u > (size_t)-1)
        return 0;
    if (*end && !isspace((unsigned char)*end))
        return 0;
    *out = (size_t)u;
    *s = end;
    return 1;
}

static int next_double(const char **s, double *out)
{
    const char *p = skip_blanks(*s);
    char *end;
    double d = strtod(p, &end);
    if (end == p || (*end && !isspace((unsigned char)*end)))
        return 0;
    *out = d;
    *s = end;
    return 1;
}

static cl_status check_banner(const char *path, const char *line,
                              cl_error *err)
{
    char w[5][32];
    int n = sscanf(line, "%31s %31s %31s %31s %31s", w[0], w[1], w[2], w[3],
                   w[4]);
    if (n != 5 || strcmp(w[0], "%%MatrixMarket") != 0 ||
        strcasecmp(w[1], "matrix") != 0)
        return cl_error_set(err, CL_EPARSE,
                            "%s:1: not a Matrix Market file (expected "
                            "\"%%%%MatrixMarket matrix coordinate real "
                            "general\")", path);
    if (strcasecmp(w[2], "coordinate") != 0 || strcasecmp(w[3], "real") != 0
        || strcasecmp(w[4], "general") != 0)
        return cl_error_set(err, CL_EPARSE,
                            "%s:1: unsupported Matrix Market type \"%s %s "
                            "%s\" (only coordinate real general)", path, w[2],
                            w[3], w[4]);
    return CL_OK;
}

static cl_status push_entry(cl_triplets *t, size_t *cap, size_t i, size_t j,
                            double v)
{
    if (t->nnz == *cap) {
        size_t nc = *cap ? 2 * *cap : 64;
        size_t *r = realloc(t->row, nc * sizeof *r);
        if (!r)
            return CL_ENOMEM;
        t->row = r;
        size_t *c = realloc(t->col, nc * sizeof *c);
        if (!c)
            return CL_ENOMEM;
        t->col = c;
        double *x = realloc(t->val, nc * sizeof *x);
        if (!x)
            return CL_ENOMEM;
        t->val = x;
        *cap = nc;
    }
    t->row[t->nnz] = i;
    t->col[t->nnz] = j;
    t->val[t->nnz] = v;
    t->nnz++;
    return CL_OK;
}

cl_status cl_mtx_read(const char *path, cl_triplets *t, cl_error *err)
{
    memset(t, 0, sizeof *t);
    const char *why;
    FILE *fp = cl_input_open(path, "r", &why);
    if (!fp)
        return cl_error_set(err, CL_EIO, "cannot open '%s': %s", path, why);

    cl_status st = CL_OK;
    char *line = NULL;
    size_t cap = 0, lineno = 0, tcap = 0, expect = 0;
    int have_size = 0;
    ssize_t len;
    errno = 0;
    while (st == CL_OK && (len = cl_input_line(fp, &line, &cap, MTX_LINE_MAX))
                              != CL_INPUT_END) {
        if ((st = cl_input_line_ok(line, len, MTX_LINE_MAX, path, ++lineno,
                                   "a Matrix Market file", "", err)))
            break;
        if (lineno == 1) {
            st = check_banner(path, line, err);
            continue;
        }
        const char *s = skip_blanks(line);
        if (*s == '%' || *s == '\0')
            continue;
        if (!have_size) {
            if (!next_size(&s, &t->nrows) || !next_size(&s, &t->ncols) ||
                !next_size(&s, &expect) || *skip_blanks(s) != '\0')
                st = cl_error_set(err, CL_EPARSE,
                                  "%s:%zu: expected size line \"rows cols "
                                  "entries\"", path, lineno);
            have_size = 1;
            continue;
        }
        size_t i, j;
        double v;
        if (!next_size(&s, &i) || !next_size(&s, &j) ||
            !next_double(&s, &v) || *skip_blanks(s) != '\0') {
            st = cl_error_set(err, CL_EPARSE,
                              "%s:%zu: expected entry \"row col value\"",
                              path, lineno);
        } else if (i < 1 || i > t->nrows || j < 1 || j > t->ncols) {
            st = cl_error_set(err, CL_EPARSE,
                              "%s:%zu: entry (%zu, %zu) outside the %zu x "
                              "%zu matrix", path, lineno, i, j, t->nrows,
                              t->ncols);
        } else if (!isfinite(v)) {
            st = cl_error_set(err, CL_EPARSE,
                              "%s:%zu: entry (%zu, %zu) is not finite",
                              path, lineno, i, j);
        } else if (t->nnz == expect) {
            st = cl_error_set(err, CL_EPARSE,
                              "%s:%zu: more entries than the %zu announced",
                              path, lineno, expect);
        } else if (push_entry(t, &tcap, i - 1, j - 1, v) != CL_OK) {
            st = cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
        }
    }
    if (st == CL_OK && ferror(fp))
        st = cl_error_set(err, CL_EIO, "cannot read '%s': %s", path,
                          strerror(errno ? errno : EIO));
    if (st == CL_OK && lineno == 0)
        st = cl_error_set(err, CL_EPARSE, "%s:1: empty file", path);
    if (st == CL_OK && !have_size)
        st = cl_error_set(err, CL_EPARSE, "%s:%zu: missing size line", path,
                          lineno);
    if (st == CL_OK && t->nnz != expect)
        st = cl_error_set(err, CL_EPARSE,
                          "%s: %zu entries announced, %zu found", path,
                          expect, t->nnz);
    free(line);
    (void)fclose(fp);   /* read-only: nothing left to lose */
    if (st != CL_OK)
        cl_triplets_free(t);
    return st;
}
