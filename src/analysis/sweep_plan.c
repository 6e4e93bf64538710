/* A sweep's plan (analysis/sweep.h): the sweep file read, its axes
 * expanded, the cross product with stable ids and the job commands. */
#include "analysis/sweep.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"

/* The keys of [sweep] that are not axes. */
static bool reserved(const char *key)
{
    return !strcmp(key, "problem") || !strcmp(key, "integrator") ||
           !strcmp(key, "reference");
}

static char *dup_n(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

/* The shortest "%.*g" of x that reads back as x, without an exponent
 * between 1e-4 and 1e15 (200, not 2e+02). */
static void shortest(double x, char *buf, size_t len)
{
    bool plain = fabs(x) >= 1e-4 && fabs(x) < 1e15;
    for (int p = 1; p <= 17; p++) {
        snprintf(buf, len, "%.*g", p, x);
        if (strtod(buf, NULL) == x && !(plain && strchr(buf, 'e')))
            return;
    }
}

static const char *trimmed(const char *s, size_t *n)
{
    while (*n && (*s == ' ' || *s == '\t'))
        s++, (*n)--;
    while (*n && (s[*n - 1] == ' ' || s[*n - 1] == '\t'))
        (*n)--;
    return s;
}

static cl_status add_value(cl_sweep_axis *a, const char *s, size_t n)
{
    char **grown = realloc(a->v, (size_t)(a->n + 1) * sizeof *grown);
    char *v = grown ? dup_n(s, n) : NULL;
    if (grown)
        a->v = grown;
    if (!v)
        return CL_ENOMEM;
    a->v[a->n++] = v;
    return CL_OK;
}

/* linspace(a, b, k) or logspace(a, b, k): k values (1 .. MAX) from a to b,
 * evenly spaced, or 10 to the power of evenly spaced exponents a .. b. */
static cl_status spaced(cl_sweep_axis *a, const char *v, bool log, bool *ok)
{
    double lo, hi, k;
    int used = 0;
    *ok = sscanf(v + 9, " %lf , %lf , %lf ) %n", &lo, &hi, &k, &used) == 3 &&
          v[9 + used] == '\0' && isfinite(lo) && isfinite(hi) && k >= 1 &&
          k <= CL_SWEEP_MAX_VALUES && k == floor(k);
    cl_status rc = CL_OK;
    for (int i = 0; *ok && !rc && i < (int)k; i++) {
        double e = k == 1 ? lo : lo + (hi - lo) * i / (k - 1);
        char buf[32];
        shortest(log ? pow(10, e) : e, buf, sizeof buf);
        rc = add_value(a, buf, strlen(buf));
    }
    return rc;
}

/* A comma-separated list of non-empty values. */
static cl_status listed(cl_sweep_axis *a, const char *v, bool *ok)
{
    cl_status rc = CL_OK;
    *ok = true;
    for (const char *p = v; *ok && !rc; p += strcspn(p, ",") + 1) {
        size_t n = strcspn(p, ",");
        const char *s = trimmed(p, &n);
        *ok = n > 0;
        rc = *ok ? add_value(a, s, n) : CL_OK;
        if (!p[strcspn(p, ",")])
            break;
    }
    return rc;
}

/* dt, rtol, atol, t_end: [run]; n: [cloth] n; else SECTION.KEY. */
static char *axis_key(const char *key)
{
    static const char *const run_keys[] = {"dt", "rtol", "atol", "t_end",
                                           NULL};
    char buf[256];
    for (int k = 0; run_keys[k]; k++)
        if (!strcmp(key, run_keys[k])) {
            snprintf(buf, sizeof buf, "run.%s", key);
            return strdup(buf);
        }
    if (!strcmp(key, "n"))
        return strdup("cloth.n");
    const char *dot = strrchr(key, '.');
    return dot && dot != key && dot[1] ? strdup(key) : NULL;
}

static cl_status read_axis(cl_config *cfg, const char *key, cl_sweep *sw,
                           cl_error *err)
{
    if (sw->naxis == CL_SWEEP_MAX_AXES)
        return cl_config_refuse(cfg, "sweep", key, CL_EINVAL,
                                "too many axes (at most 16)", err);
    cl_sweep_axis *a = &sw->axis[sw->naxis];
    const char *v = cl_config_string(cfg, "sweep", key, "");
    bool ok = false;
    if (!(a->key = axis_key(key)))
        return cl_config_refuse(cfg, "sweep", key, CL_EINVAL,
                                "expected problem, integrator, reference, an "
                                "axis dt, rtol, atol, t_end, n or "
                                "SECTION.KEY", err);
    sw->naxis++;
    cl_status rc = !strncmp(v, "linspace(", 9) ? spaced(a, v, false, &ok)
                   : !strncmp(v, "logspace(", 9) ? spaced(a, v, true, &ok)
                                                 : listed(a, v, &ok);
    if (rc)
        return cl_error_set(err, rc, "out of memory");
    return ok ? CL_OK
              : cl_config_refuse(cfg, "sweep", key, CL_EINVAL,
                                 "expected a list v1, v2, ... of non-empty "
                                 "values, linspace(a, b, k) or logspace(a, "
                                 "b, k) with 1 <= k <= 100000", err);
}

/* "NAME[:LINSOL], ...", each NAME an integrator of the registry. */
static cl_status read_integrators(cl_config *cfg, cl_sweep *sw,
                                  cl_error *err)
{
    cl_sweep_axis list = {0};
    bool ok = false;
    const char *v = cl_config_string(cfg, "sweep", "integrator", "");
    if (!*v)
        return cl_error_set(err, CL_EINVAL, "%s: [sweep] integrator: "
                            "NAME[:LINSOL], ... is required",
                            cl_config_path(cfg));
    cl_status rc = listed(&list, v, &ok);
    char name[64];
    for (int k = 0; ok && !rc && k < list.n; k++) {
        snprintf(name, sizeof name, "%.*s", (int)strcspn(list.v[k], ":"),
                 list.v[k]);
        ok = cl_integrator_find(name) != NULL;
    }
    sw->integrator = list.v;
    sw->nint = list.n;
    if (rc)
        return cl_error_set(err, rc, "out of memory");
    return ok ? CL_OK
              : cl_config_refuse(cfg, "sweep", "integrator", CL_EINVAL,
                                 "expected NAME[:LINSOL], ... with each NAME "
                                 "an integrator (clothode list)", err);
}

static cl_sweep_axis *find_axis(cl_sweep *sw, const char *key)
{
    for (int a = 0; a < sw->naxis; a++)
        if (!strcmp(sw->axis[a].key, key))
            return &sw->axis[a];
    return NULL;
}

/* With one t_end T, every dt becomes T / N, N = round(T / dt) >= 1, so
 * that a fixed-step run ends exactly at T (as in the stability study);
 * values that are not positive numbers are left for the run to refuse. */
static void snap_dt(cl_sweep *sw)
{
    cl_sweep_axis *dt = find_axis(sw, "run.dt"), *te = find_axis(sw,
                                                                "run.t_end");
    char *end;
    double T = te && te->n == 1 ? strtod(te->v[0], &end) : NAN;
    if (!dt || !(T > 0) || *end)
        return;
    for (int k = 0; k < dt->n; k++) {
        double h = strtod(dt->v[k], &end), n = round(T / h);
        char buf[32];
        if (!(h > 0) || *end || !isfinite(n) || n > 1e15)
            continue;
        shortest(T / fmax(n, 1), buf, sizeof buf);
        char *v = strdup(buf);
        if (v) {
            free(dt->v[k]);
            dt->v[k] = v;
        }
    }
}

cl_status cl_sweep_read(cl_config *cfg, cl_sweep *sw, cl_error *err)
{
    const char *problem = cl_config_string(cfg, "sweep", "problem", "");
    double ref = 0;
    cl_status rc = read_integrators(cfg, sw, err);
    if (!rc && !*problem)
        rc = cl_error_set(err, CL_EINVAL, "%s: [sweep] problem: a problem "
                          "file is required", cl_config_path(cfg));
    if (!rc && !(sw->problem = strdup(problem)))
        rc = cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!rc)
        rc = cl_config_double(cfg, "sweep", "reference", 0, 1e-15, 1e-4,
                              &ref, err);
    if (!rc && ref > 0)
        shortest(ref, sw->ref_rtol, sizeof sw->ref_rtol);
    const char *key;
    for (size_t k = 0; !rc && (key = cl_config_key_at(cfg, "sweep", k)); k++)
        if (!reserved(key))
            rc = read_axis(cfg, key, sw, err);
    if (!rc)
        snap_dt(sw);
    return rc;
}

/* ---- ids and commands --------------------------------------------------- */

static int by_text(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

void cl_sweep_canonical(const cl_sweep *sw, const cl_sweep_job *j, char *buf,
                        size_t len)
{
    char line[CL_SWEEP_MAX_AXES + 2][320];
    const char *sorted[CL_SWEEP_MAX_AXES + 2];
    int n = 0;
    for (int a = 0; a < sw->naxis; a++)
        if (j->value[a])
            snprintf(line[n++], sizeof line[0], "%s=%s", sw->axis[a].key,
                     j->value[a]);
    if (j->reference) /* the reference's tolerance is part of the run */
        snprintf(line[n++], sizeof line[0], "reference=%s", sw->ref_rtol);
    for (int k = 0; k < n; k++)
        sorted[k] = line[k];
    qsort(sorted, (size_t)n, sizeof *sorted, by_text);
    size_t u = (size_t)snprintf(buf, len, "integrator=%s", j->integrator);
    for (int k = 0; k < n && u < len; k++)
        u += (size_t)snprintf(buf + u, len - u, "\n%s", sorted[k]);
}

/* FNV-1a, 64 bits (Fowler, Noll and Vo), its top 48 bits in hex. */
static void make_id(const char *text, char id[CL_SWEEP_ID_LEN])
{
    uint64_t h = 14695981039346656037ull;
    for (const unsigned char *p = (const unsigned char *)text; *p; p++)
        h = (h ^ *p) * 1099511628211ull;
    snprintf(id, CL_SWEEP_ID_LEN, "%012llx", (unsigned long long)(h >> 16));
}

size_t cl_sweep_quote(const char *s, char *buf, size_t len)
{
    if (*s && strspn(s, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                        "0123456789_./:=,+-@%") == strlen(s))
        return (size_t)snprintf(buf, len, "%s", s);
    size_t u = (size_t)snprintf(buf, len, "'");
    for (; *s && u < len; s++)
        u += (size_t)snprintf(buf + u, len - u, *s == '\'' ? "'\\''" : "%c",
                              *s);
    return u + (size_t)snprintf(buf + u, u < len ? len - u : 0, "'");
}

static cl_status make_command(const cl_sweep *sw, cl_sweep_job *j)
{
    char buf[8192], set[512];
    size_t u = cl_sweep_quote(sw->clothode, buf, sizeof buf);
    u += (size_t)snprintf(buf + u, sizeof buf - u, " run ");
    u += cl_sweep_quote(sw->problem, buf + u, sizeof buf - u);
    u += (size_t)snprintf(buf + u, sizeof buf - u, " --integrator ");
    u += cl_sweep_quote(j->integrator, buf + u, sizeof buf - u);
    /* no frames unless the sweep asks for them ([run] frames after this) */
    u += (size_t)snprintf(buf + u, sizeof buf - u, " --frames 0");
    for (int a = 0; a < sw->naxis && u < sizeof buf; a++)
        if (j->value[a]) {
            snprintf(set, sizeof set, "%s=%s", sw->axis[a].key, j->value[a]);
            u += (size_t)snprintf(buf + u, sizeof buf - u, " --set ");
            u += cl_sweep_quote(set, buf + u, sizeof buf - u);
        }
    if (j->reference && u < sizeof buf)
        u += (size_t)snprintf(buf + u, sizeof buf - u,
                              " --rtol %s --atol %.6g", sw->ref_rtol,
                              strtod(sw->ref_rtol, NULL) / 100);
    snprintf(set, sizeof set, "%s/jobs/%s", sw->dir, j->id);
    if (u < sizeof buf)
        u += (size_t)snprintf(buf + u, sizeof buf - u, " --out ");
    if (u < sizeof buf)
        u += cl_sweep_quote(set, buf + u, sizeof buf - u);
    if (u < sizeof buf)
        u += (size_t)snprintf(buf + u, sizeof buf - u, " --quiet");
    if (u >= sizeof buf)
        return CL_EINVAL;
    return (j->command = strdup(buf)) ? CL_OK : CL_ENOMEM;
}

int cl_sweep_find(const cl_sweep *sw, const char *id)
{
    for (int k = 0; k < sw->njob; k++)
        if (!strcmp(sw->job[k].id, id))
            return k;
    return -1;
}

/* Set job k's id and command; CL_EINVAL (and *dup its twin) when an earlier
 * job has the same id. */
static cl_status finish_job(cl_sweep *sw, int k, int *dup, cl_error *err)
{
    char text[8192];
    cl_sweep_job *j = &sw->job[k];
    cl_sweep_canonical(sw, j, text, sizeof text);
    make_id(text, j->id);
    *dup = cl_sweep_find(sw, j->id);
    if (*dup >= 0 && *dup < k)
        return cl_error_set(err, CL_EINVAL, "sweep: two jobs are the same "
                            "run (a value listed twice?): %s",
                            strchr(text, '\n') ? strchr(text, '\n') + 1
                                               : text);
    cl_status rc = make_command(sw, j);
    return rc ? cl_error_set(err, rc, "sweep: job %s: command too long or "
                             "no memory", j->id) : CL_OK;
}

/* An axis of a method's options ([run] keys other than t_end), which a
 * reference run does not take over from its jobs. */
static bool method_axis(const char *key)
{
    return !strncmp(key, "run.", 4) && strcmp(key, "run.t_end") != 0;
}

/* The reference of job k: the cvode-bdf run with job k's values on the
 * problem's axes, added after the jobs unless it is one already. */
static cl_status add_reference(cl_sweep *sw, int k, cl_error *err)
{
    cl_sweep_job *r = &sw->job[sw->njob];
    r->value = calloc((size_t)sw->naxis + 1, sizeof *r->value);
    if (!r->value)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    for (int a = 0; a < sw->naxis; a++)
        r->value[a] = method_axis(sw->axis[a].key) ? NULL
                                                   : sw->job[k].value[a];
    r->integrator = "cvode-bdf";
    r->reference = true;
    r->ref = -1;
    char text[8192];
    cl_sweep_canonical(sw, r, text, sizeof text);
    make_id(text, r->id);
    int at = cl_sweep_find(sw, r->id);
    if (at >= 0 && at < sw->njob) {
        free(r->value);
        memset(r, 0, sizeof *r);
        sw->job[k].ref = at;
        return CL_OK;
    }
    sw->job[k].ref = sw->njob++;
    int dup;
    return finish_job(sw, sw->njob - 1, &dup, err);
}

static long product(const cl_sweep *sw)
{
    long n = sw->nint;
    for (int a = 0; a < sw->naxis && n <= CL_SWEEP_MAX_VALUES; a++)
        n *= sw->axis[a].n;
    return n;
}

cl_status cl_sweep_expand(cl_sweep *sw, cl_error *err)
{
    long n = product(sw);
    if (n > CL_SWEEP_MAX_VALUES)
        return cl_error_set(err, CL_EINVAL, "sweep: more than %d jobs",
                            CL_SWEEP_MAX_VALUES);
    /* at most one reference per job */
    sw->job = calloc((size_t)n * (sw->ref_rtol[0] ? 2 : 1), sizeof *sw->job);
    if (!sw->job)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    cl_status rc = CL_OK;
    for (long k = 0; !rc && k < n; k++) {
        cl_sweep_job *j = &sw->job[sw->njob++];
        long rest = k;
        j->value = calloc((size_t)sw->naxis + 1, sizeof *j->value);
        if (!j->value)
            return cl_error_set(err, CL_ENOMEM, "out of memory");
        for (int a = sw->naxis - 1; a >= 0; a--) { /* the last fastest */
            j->value[a] = sw->axis[a].v[rest % sw->axis[a].n];
            rest /= sw->axis[a].n;
        }
        j->integrator = sw->integrator[rest];
        j->ref = -1;
        int dup;
        rc = finish_job(sw, (int)k, &dup, err);
    }
    for (long k = 0; !rc && sw->ref_rtol[0] && k < n; k++)
        rc = add_reference(sw, (int)k, err);
    return rc;
}

void cl_sweep_free(cl_sweep *sw)
{
    for (int k = 0; k < sw->njob; k++) {
        free(sw->job[k].value);
        free(sw->job[k].command);
    }
    free(sw->job);
    for (int a = 0; a < sw->naxis; a++) {
        for (int k = 0; k < sw->axis[a].n; k++)
            free(sw->axis[a].v[k]);
        free(sw->axis[a].v);
        free(sw->axis[a].key);
    }
    for (int k = 0; k < sw->nint; k++)
        free(sw->integrator[k]);
    free(sw->integrator);
    free(sw->dir);
    free(sw->problem);
    free(sw->clothode);
    memset(sw, 0, sizeof *sw);
}
