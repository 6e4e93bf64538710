/* Wavefront OBJ reader (io/obj.h): lines of at most CL_OBJ_MAX_LINE
 * characters read into one fixed buffer, `v` and `f` statements parsed
 * token by token, polygons split into fans and every triangle checked. */
#include "io/obj.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec3.h"
#include "io/input.h"

/* Zero area: |(b - a) x (c - a)| at most this times the sum of the squared
 * edge lengths (an equilateral triangle has 1/(2 sqrt 3) ~ 0.29). */
#define FLAT 1e-14

#define BLANKS " \t\r\f\v"

typedef enum { LINE_OK, LINE_EOF, LINE_LONG, LINE_NUL, LINE_ERROR } line_kind;

typedef struct {
    FILE *fp;
    const char *path;
    size_t line;        /* 1-based number of the line in buf */
    char *buf;          /* CL_OBJ_MAX_LINE + 1 bytes */
    cl_obj *m;
    size_t vcap, tcap;  /* room in m->vert (vertices), m->tri */
    int *poly;          /* the vertices of the face being read */
    size_t pcap;
    cl_error *err;
} obj_reader;

static const char *const ignored[] = {"vt", "vn", "o", "g", "s", "usemtl",
                                      "mtllib", NULL};

void cl_obj_free(cl_obj *m)
{
    if (!m)
        return;
    free(m->vert);
    free(m->tri);
    memset(m, 0, sizeof *m);
}

/* "PATH:LINE: what" as CL_EPARSE. */
__attribute__((format(printf, 2, 3)))
static cl_status fail(const obj_reader *r, const char *fmt, ...)
{
    char what[sizeof r->err->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    return cl_error_set(r->err, CL_EPARSE, "%s:%zu: %s", r->path, r->line,
                        what);
}

static cl_status no_memory(const obj_reader *r)
{
    return cl_error_set(r->err, CL_ENOMEM, "%s:%zu: out of memory", r->path,
                        r->line);
}

/* Room for `need` elements of `size` bytes in *arr (capacity *cap). */
static bool grow(void *arr, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return true;
    size_t ncap = *cap ? *cap : 64;
    while (ncap < need) {
        if (ncap > SIZE_MAX / 2 / size)
            return false;
        ncap *= 2;
    }
    void *p = realloc(*(void **)arr, ncap * size);
    if (!p)
        return false;
    *(void **)arr = p;
    *cap = ncap;
    return true;
}

/* The next line into r->buf without its '\n'.  Reading stops at the first
 * character past CL_OBJ_MAX_LINE (LINE_LONG) or at a NUL byte. */
static line_kind next_line(obj_reader *r)
{
    size_t n = 0;
    int ch;
    while ((ch = getc(r->fp)) != EOF && ch != '\n') {
        if (n == CL_OBJ_MAX_LINE)
            return LINE_LONG;
        if (ch == '\0')
            return LINE_NUL;
        r->buf[n++] = (char)ch;
    }
    r->buf[n] = '\0';
    if (ch == EOF && ferror(r->fp))
        return LINE_ERROR;
    return ch == EOF && n == 0 ? LINE_EOF : LINE_OK;
}

/* The next blank-separated token of *s (NUL-terminated in place), or
 * NULL at the end. */
static char *next_token(char **s)
{
    char *p = *s + strspn(*s, BLANKS);
    if (!*p)
        return NULL;
    char *e = p + strcspn(p, BLANKS);
    if (*e)
        *e++ = '\0';
    *s = e;
    return p;
}

static cl_status parse_vertex(obj_reader *r, char *s)
{
    double x[4];
    int n = 0;
    for (char *tok; (tok = next_token(&s)); n++) {
        if (n == 4)
            return fail(r, "a vertex has 3 or 4 numbers (x y z [w]), found "
                           "more");
        char *end;
        x[n] = strtod(tok, &end);
        if (end == tok || *end)
            return fail(r, "\"%.40s\" is not a number", tok);
        if (!isfinite(x[n]))
            return fail(r, "\"%.40s\" is not a finite number", tok);
    }
    if (n < 3)
        return fail(r, "a vertex has 3 or 4 numbers (x y z [w]), found %d",
                    n);
    cl_obj *m = r->m;
    if (m->nvert == INT_MAX)
        return fail(r, "more than %d vertices", INT_MAX);
    if (!grow(&m->vert, &r->vcap, m->nvert + 1, 3 * sizeof *m->vert))
        return no_memory(r);
    memcpy(m->vert + 3 * m->nvert++, x, 3 * sizeof *x);
    return CL_OK;
}

/* An integer at s; *end past it.  false if there is none. */
static bool parse_int(const char *s, char **end, long *out)
{
    *out = strtol(s, end, 10);
    return *end != s && (*s == '-' || *s == '+' || (*s >= '0' && *s <= '9'));
}

/* What may follow a face vertex's index: "", "/t", "//n" or "/t/n". */
static bool ref_tail_ok(const char *s)
{
    char *end;
    long t;
    if (!*s)
        return true;
    if (*s++ != '/')
        return false;
    if (*s != '/') {
        if (!parse_int(s, &end, &t))
            return false;
        if (!*end)
            return true;
        if (*end != '/')
            return false;
        s = end;
    }
    return parse_int(s + 1, &end, &t) && !*end;
}

/* A face vertex: its 0-based index.  Huge indices saturate in strtol and
 * are out of range like any other (named as written). */
static cl_status parse_ref(obj_reader *r, const char *tok, int *out)
{
    char *end;
    long i;
    if (!parse_int(tok, &end, &i) || !ref_tail_ok(end))
        return fail(r, "\"%.40s\" is not a face vertex (i, i/t, i//n or "
                       "i/t/n, with integers)", tok);
    if (i == 0)
        return fail(r, "vertex index 0 (indices start at 1, or count back "
                       "from -1)");
    long nv = (long)r->m->nvert, k = i > 0 ? i - 1 : nv + i;
    if (k < 0 || k >= nv)
        return fail(r, "vertex index %.*s out of range (%ld vertices defined "
                       "so far)", (int)(end - tok), tok, nv);
    *out = (int)k;
    return CL_OK;
}

/* Whether the triangle (a, b, c) has zero area (also when it overflows). */
static bool zero_area(const double *a, const double *b, const double *c)
{
    double ab[3], bc[3], ca[3], n[3];
    cl_v3_sub(b, a, ab);
    cl_v3_sub(c, b, bc);
    cl_v3_sub(a, c, ca);
    cl_v3_cross(ab, bc, n);
    double scale = cl_v3_dot(ab, ab) + cl_v3_dot(bc, bc) + cl_v3_dot(ca, ca);
    return !(cl_v3_norm(n) > FLAT * scale);
}

static cl_status add_triangle(obj_reader *r, int a, int b, int c)
{
    cl_obj *m = r->m;
    if (a == b || b == c || a == c)
        return fail(r, "triangle of vertices %d, %d, %d repeats a vertex",
                    a + 1, b + 1, c + 1);
    if (zero_area(m->vert + 3 * a, m->vert + 3 * b, m->vert + 3 * c))
        return fail(r, "triangle of vertices %d, %d, %d has zero area",
                    a + 1, b + 1, c + 1);
    if (!grow(&m->tri, &r->tcap, m->ntri + 1, sizeof *m->tri))
        return no_memory(r);
    m->tri[m->ntri][0] = a;
    m->tri[m->ntri][1] = b;
    m->tri[m->ntri][2] = c;
    m->ntri++;
    return CL_OK;
}

static cl_status parse_face(obj_reader *r, char *s)
{
    size_t n = 0;
    cl_status st;
    for (char *tok; (tok = next_token(&s)); n++) {
        if (!grow(&r->poly, &r->pcap, n + 1, sizeof *r->poly))
            return no_memory(r);
        if ((st = parse_ref(r, tok, &r->poly[n])))
            return st;
    }
    if (n < 3)
        return fail(r, "a face has at least 3 vertices, found %zu", n);
    for (size_t k = 1; k + 1 < n; k++)
        if ((st = add_triangle(r, r->poly[0], r->poly[k], r->poly[k + 1])))
            return st;
    return CL_OK;
}

static cl_status parse_line(obj_reader *r)
{
    char *s = r->buf, *hash = strchr(s, '#');
    if (hash)
        *hash = '\0';
    char *kw = next_token(&s);
    if (!kw)
        return CL_OK;
    if (!strcmp(kw, "v"))
        return parse_vertex(r, s);
    if (!strcmp(kw, "f"))
        return parse_face(r, s);
    for (size_t k = 0; ignored[k]; k++)
        if (!strcmp(kw, ignored[k]))
            return CL_OK;
    return fail(r, "unsupported statement \"%.40s\" (read: v, f; ignored: "
                   "vt, vn, o, g, s, usemtl, mtllib)", kw);
}

static cl_status read_lines(obj_reader *r)
{
    cl_status st = CL_OK;
    line_kind k;
    while (!st && (k = next_line(r)) != LINE_EOF) {
        r->line++;
        if (k == LINE_ERROR)
            st = cl_error_set(r->err, CL_EIO, "cannot read '%s': %s",
                              r->path, strerror(errno ? errno : EIO));
        else if (k == LINE_LONG)
            st = fail(r, "line longer than %d characters", CL_OBJ_MAX_LINE);
        else if (k == LINE_NUL)
            st = fail(r, "NUL byte (not a text file)");
        else
            st = parse_line(r);
    }
    if (st)
        return st;
    if (r->line == 0) {
        r->line = 1;
        return fail(r, "empty file");
    }
    if (!r->m->nvert)
        return fail(r, "end of file without vertices");
    return r->m->ntri ? CL_OK : fail(r, "end of file without faces");
}

cl_status cl_obj_read(const char *path, cl_obj *m, cl_error *err)
{
    memset(m, 0, sizeof *m);
    obj_reader r = {.path = path, .m = m, .err = err};
    const char *why;
    if (!(r.fp = cl_input_open(path, "r", &why)))
        return cl_error_set(err, CL_EIO, "cannot open '%s': %s", path, why);
    r.buf = malloc(CL_OBJ_MAX_LINE + 1);
    errno = 0;
    cl_status st = r.buf ? read_lines(&r) : no_memory(&r);
    free(r.buf);
    free(r.poly);
    (void)fclose(r.fp); /* read-only: nothing left to lose */
    if (st)
        cl_obj_free(m);
    return st;
}

void cl_obj_place(cl_obj *m, double scale, const double shift[3])
{
    for (size_t k = 0; k < 3 * m->nvert; k++)
        m->vert[k] = scale * m->vert[k] + shift[k % 3];
}
