/* Cloth state CSV reader and writer. */
#include "io/state.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"
#include "io/input.h"

#define STATE_HEADER "p,x,y,z,vx,vy,vz"
#define STATE_NFIELD 7
#define STATE_LINE_MAX 4096 /* bytes of a line: a row is far shorter */

static const char *const field_name[STATE_NFIELD] = {
    "p", "x", "y", "z", "vx", "vy", "vz"
};

cl_status cl_state_write(const char *path, size_t np, const double *x,
                         const double *v, cl_error *err)
{
    if (np > 0 && (!x || !v))
        return cl_error_set(err, CL_EINVAL, "%s: no state to write", path);
    cl_afile af;
    cl_status st = cl_afile_open(&af, path, err);
    if (st)
        return st;
    if (fprintf(af.fp, STATE_HEADER "\n") < 0)
        goto write_fail;
    for (size_t p = 0; p < np; p++) {
        const double *xp = x + 3 * p, *vp = v + 3 * p;
        if (fprintf(af.fp, "%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", p,
                    xp[0], xp[1], xp[2], vp[0], vp[1], vp[2]) < 0)
            goto write_fail;
    }
    return cl_afile_commit(&af, err);

write_fail:
    return cl_afile_fail(&af, err);
}

/* Strip "\n" / "\r\n" in place; return the new length. */
static size_t chomp(char *s, size_t n)
{
    while (n > 0 && (s[n - 1] == '\n' || s[n - 1] == '\r'))
        s[--n] = '\0';
    return n;
}

static int is_blank(const char *s)
{
    for (; *s; s++)
        if (*s != ' ' && *s != '\t')
            return 0;
    return 1;
}

/* The whole of s (surrounding blanks allowed) as a number; 0 if it is not
 * one. */
static int parse_double(const char *s, double *out)
{
    char *end;
    errno = 0;
    double d = strtod(s, &end);
    if (end == s || !is_blank(end))
        return 0;
    *out = d;   /* ERANGE: +-HUGE_VAL (caught as non-finite) or denormal */
    return 1;
}

static int parse_index(const char *s, long *out)
{
    char *end;
    errno = 0;
    long l = strtol(s, &end, 10);
    if (end == s || errno == ERANGE || !is_blank(end))
        return 0;
    *out = l;
    return 1;
}

/* Parse one data row (already chomped) into the arrays; seen[p] holds the
 * line where particle p appeared (0 = not yet). */
static cl_status parse_row(const char *path, size_t lineno, char *line,
                           size_t np, double *x, double *v, size_t *seen,
                           cl_error *err)
{
    char *field[STATE_NFIELD];
    size_t nf = 1;
    field[0] = line;
    for (char *c = line; *c; c++) {
        if (*c != ',')
            continue;
        if (nf < STATE_NFIELD) {
            *c = '\0';
            field[nf] = c + 1;
        }
        nf++;
    }
    if (nf != STATE_NFIELD)
        return cl_error_set(err, CL_EPARSE,
                            "%s:%zu: expected %d fields (" STATE_HEADER
                            "), found %zu", path, lineno, STATE_NFIELD, nf);

    long p;
    if (!parse_index(field[0], &p))
        return cl_error_set(err, CL_EPARSE,
                            "%s:%zu: particle index p = \"%.40s\" is not an "
                            "integer", path, lineno, field[0]);
    if (p < 0 || (unsigned long)p >= np)
        return cl_error_set(err, CL_EPARSE,
                            "%s:%zu: particle index %ld out of range 0..%zu",
                            path, lineno, p, np ? np - 1 : 0);
    if (seen[p])
        return cl_error_set(err, CL_EPARSE,
                            "%s:%zu: duplicate particle %ld (first on line "
                            "%zu)", path, lineno, p, seen[p]);

    double val[STATE_NFIELD - 1];
    for (int k = 1; k < STATE_NFIELD; k++) {
        if (!parse_double(field[k], &val[k - 1]))
            return cl_error_set(err, CL_EPARSE,
                                "%s:%zu: %s = \"%.40s\" is not a number",
                                path, lineno, field_name[k], field[k]);
        if (!isfinite(val[k - 1]))
            return cl_error_set(err, CL_EPARSE,
                                "%s:%zu: %s = \"%.40s\" is not finite", path,
                                lineno, field_name[k], field[k]);
    }
    seen[p] = lineno;
    for (int k = 0; k < 3; k++) {
        x[3 * p + k] = val[k];
        v[3 * p + k] = val[3 + k];
    }
    return CL_OK;
}

cl_status cl_state_read(const char *path, size_t np, double *x, double *v,
                        cl_error *err)
{
    if (np > 0 && (!x || !v))
        return cl_error_set(err, CL_EINVAL, "%s: no arrays to read into",
                            path);
    const char *why;
    FILE *fp = cl_input_open(path, "r", &why);
    if (!fp)
        return cl_error_set(err, CL_EIO, "cannot open '%s': %s", path, why);
    size_t *seen = calloc(np ? np : 1, sizeof *seen);
    if (!seen) {
        (void)fclose(fp);
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
    }

    cl_status st = CL_OK;
    char *line = NULL;
    size_t cap = 0, lineno = 0;
    ssize_t len;
    int header_ok = 0;
    errno = 0;
    while (st == CL_OK && (len = cl_input_line(fp, &line, &cap, STATE_LINE_MAX))
                              != CL_INPUT_END) {
        if ((st = cl_input_line_ok(line, len, STATE_LINE_MAX, path, ++lineno,
                                   "a state file",
                                   " (a row is p and six numbers)", err)))
            break;
        chomp(line, (size_t)len);
        if (!header_ok) {
            if (strcmp(line, STATE_HEADER) != 0) {
                st = cl_error_set(err, CL_EPARSE,
                                  "%s:%zu: expected header \"" STATE_HEADER
                                  "\", found \"%.60s\"", path, lineno, line);
                break;
            }
            header_ok = 1;
            continue;
        }
        if (is_blank(line))
            continue;
        st = parse_row(path, lineno, line, np, x, v, seen, err);
    }
    if (st == CL_OK && ferror(fp))
        st = cl_error_set(err, CL_EIO, "cannot read '%s': %s", path,
                          strerror(errno ? errno : EIO));
    if (st == CL_OK && !header_ok)
        st = cl_error_set(err, CL_EPARSE,
                          "%s:1: missing header \"" STATE_HEADER "\"", path);
    if (st == CL_OK) {
        size_t present = 0, first_missing = np;
        for (size_t p = 0; p < np; p++) {
            if (seen[p])
                present++;
            else if (first_missing == np)
                first_missing = p;
        }
        if (present < np)
            st = cl_error_set(err, CL_EPARSE,
                              "%s: particle %zu missing (%zu of %zu particles "
                              "present)", path, first_missing, present, np);
    }
    free(line);
    free(seen);
    (void)fclose(fp);   /* read-only: nothing left to lose */
    return st;
}
