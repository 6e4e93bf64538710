/* Wavefront OBJ triangle meshes (io/obj.h): vertices and faces, the other
 * statements of the header ignored, polygons split into fans. */
#include "io/obj.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *path;
    long line;
    cl_obj *m;
    size_t vcap, tcap;
} obj_reader;

static cl_status bad(const obj_reader *r, cl_error *err, const char *why)
{
    return cl_error_set(err, CL_EPARSE, "%s:%ld: %s", r->path, r->line, why);
}

static cl_status add_vertex(obj_reader *r, const char *s, cl_error *err)
{
    double x[3];
    char *end;
    for (int i = 0; i < 3; i++) {
        errno = 0;
        x[i] = strtod(s, &end);
        if (end == s || errno == ERANGE || !isfinite(x[i]))
            return bad(r, err, "a vertex needs three finite coordinates");
        s = end;
    }
    cl_obj *m = r->m;
    if (m->nvert == r->vcap) {
        size_t cap = r->vcap ? 2 * r->vcap : 64;
        double *v = realloc(m->vert, 3 * cap * sizeof *v);
        if (!v)
            return cl_error_set(err, CL_ENOMEM, "%s: out of memory", r->path);
        m->vert = v;
        r->vcap = cap;
    }
    memcpy(m->vert + 3 * m->nvert++, x, sizeof x);
    return CL_OK;
}

/* One face vertex "i", "i/t", "i//n" or "i/t/n" as a 0-based index. */
static cl_status face_index(const obj_reader *r, const char **s, int *out,
                            cl_error *err)
{
    char *end;
    errno = 0;
    long i = strtol(*s, &end, 10);
    if (end == *s || errno == ERANGE)
        return bad(r, err, "a face vertex must be an integer index");
    long k = i < 0 ? (long)r->m->nvert + i : i - 1;
    if (i == 0 || k < 0 || k >= (long)r->m->nvert)
        return bad(r, err, "face vertex index 0 or out of range");
    *out = (int)k;
    *s = end + strcspn(end, " \t\r\n");
    return CL_OK;
}

static cl_status add_triangle(obj_reader *r, const int v[3], cl_error *err)
{
    const double *a = r->m->vert + 3 * v[0], *b = r->m->vert + 3 * v[1],
                 *c = r->m->vert + 3 * v[2];
    double e[3], f[3];
    for (int i = 0; i < 3; i++) {
        e[i] = b[i] - a[i];
        f[i] = c[i] - a[i];
    }
    double n[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2],
                   e[0] * f[1] - e[1] * f[0]};
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] ||
        (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0))
        return bad(r, err, "degenerate triangle (a repeated vertex or zero "
                           "area)");
    cl_obj *m = r->m;
    if (m->ntri == r->tcap) {
        size_t cap = r->tcap ? 2 * r->tcap : 64;
        int(*t)[3] = realloc(m->tri, cap * sizeof *t);
        if (!t)
            return cl_error_set(err, CL_ENOMEM, "%s: out of memory", r->path);
        m->tri = t;
        r->tcap = cap;
    }
    memcpy(m->tri[m->ntri++], v, 3 * sizeof *v);
    return CL_OK;
}

static cl_status add_face(obj_reader *r, const char *s, cl_error *err)
{
    int first = 0, prev = 0, cur = 0, n = 0;
    cl_status rc = CL_OK;
    for (s += strspn(s, " \t\r\n"); rc == CL_OK && *s;
         s += strspn(s, " \t\r\n"), n++) {
        if ((rc = face_index(r, &s, &cur, err)))
            return rc;
        if (n >= 2)
            rc = add_triangle(r, (int[3]){first, prev, cur}, err);
        if (n == 0)
            first = cur;
        prev = cur;
    }
    return rc == CL_OK && n < 3 ? bad(r, err, "a face needs three vertices")
                                : rc;
}

static cl_status read_line(obj_reader *r, const char *s, cl_error *err)
{
    static const char *const ignored[] = {"vt", "vn", "o", "g", "s",
                                          "usemtl", "mtllib", NULL};
    s += strspn(s, " \t\r\n");
    size_t len = strcspn(s, " \t\r\n");
    if (len == 0 || *s == '#')
        return CL_OK;
    if (len == 1 && *s == 'v')
        return add_vertex(r, s + 1, err);
    if (len == 1 && *s == 'f')
        return add_face(r, s + 1, err);
    for (size_t k = 0; ignored[k]; k++)
        if (strlen(ignored[k]) == len && !strncmp(s, ignored[k], len))
            return CL_OK;
    return bad(r, err, "unknown statement");
}

cl_status cl_obj_read(const char *path, cl_obj *m, cl_error *err)
{
    memset(m, 0, sizeof *m);
    FILE *fp = fopen(path, "r");
    if (!fp)
        return cl_error_set(err, CL_EIO, "%s: cannot open: %s", path,
                            strerror(errno));
    obj_reader r = {.path = path, .m = m};
    char *buf = malloc(CL_OBJ_MAX_LINE + 2);
    cl_status rc = buf ? CL_OK
                       : cl_error_set(err, CL_ENOMEM, "%s: out of memory",
                                      path);
    while (rc == CL_OK && fgets(buf, CL_OBJ_MAX_LINE + 2, fp)) {
        r.line++;
        if (strlen(buf) > CL_OBJ_MAX_LINE)
            rc = bad(&r, err, "line too long");
        else
            rc = read_line(&r, buf, err);
    }
    if (rc == CL_OK && ferror(fp))
        rc = cl_error_set(err, CL_EIO, "%s: read error", path);
    if (rc == CL_OK && (m->nvert == 0 || m->ntri == 0))
        rc = cl_error_set(err, CL_EPARSE, "%s: no %s", path,
                          m->nvert == 0 ? "vertices" : "faces");
    free(buf);
    fclose(fp);
    if (rc)
        cl_obj_free(m);
    return rc;
}

void cl_obj_free(cl_obj *m)
{
    free(m->vert);
    free(m->tri);
    memset(m, 0, sizeof *m);
}
