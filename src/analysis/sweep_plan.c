/* A sweep's plan (analysis/sweep.h): the parts' cross products with
 * stable ids and the job commands. */
#include "analysis/sweep.h"

#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"

/* ---- ids and commands --------------------------------------------------- */

static int by_text(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* A value as the job's identity sees it: a finite number by the double
 * it reads as (1e-4, 0.0001 and 1.0e-4 are one run; cl_sweep_exact), any
 * other text as written. */
static const char *canonical_value(const char *v, char *buf, size_t len)
{
    char *end;
    double x = strtod(v, &end);
    if (end == v || *end || !isfinite(x))
        return v;
    cl_sweep_exact(x, buf, len);
    return buf;
}

/* cl_sweep_canonical, the values as written or (numbers) as the doubles
 * they read as. */
static void canonical(const cl_sweep *sw, const cl_sweep_job *j,
                      bool numbers, char *buf, size_t len)
{
    char line[CL_SWEEP_MAX_AXES + 2][320], num[32];
    const char *sorted[CL_SWEEP_MAX_AXES + 2];
    int n = 0;
    for (int a = 0; a < sw->naxis; a++)
        if (j->value[a])
            snprintf(line[n++], sizeof line[0], "%s=%s", sw->axis[a].key,
                     numbers ? canonical_value(j->value[a], num, sizeof num)
                             : j->value[a]);
    if (j->reference) /* the reference's tolerance is part of the run */
        snprintf(line[n++], sizeof line[0], "reference=%s", sw->ref_rtol);
    for (int k = 0; k < n; k++)
        sorted[k] = line[k];
    qsort(sorted, (size_t)n, sizeof *sorted, by_text);
    size_t u = (size_t)snprintf(buf, len, "integrator=%s", j->integrator);
    for (int k = 0; k < n && u < len; k++)
        u += (size_t)snprintf(buf + u, len - u, "\n%s", sorted[k]);
}

void cl_sweep_canonical(const cl_sweep *sw, const cl_sweep_job *j, char *buf,
                        size_t len)
{
    canonical(sw, j, false, buf, len);
}

void cl_sweep_describe(const cl_sweep *sw, const cl_sweep_job *j, char *buf,
                       size_t len)
{
    cl_sweep_canonical(sw, j, buf, len);
    for (char *c = buf; (c = strchr(c, '\n'));)
        *c = ' ';
}

int cl_sweep_job_sets(const cl_sweep *sw, const cl_sweep_job *j,
                      char set[][CL_SWEEP_SET_LEN])
{
    int n = 0;
    bool frames = false;
    for (int a = 0; a < sw->naxis; a++)
        frames |= !strcmp(sw->axis[a].key, "run.frames");
    if (!frames)
        snprintf(set[n++], CL_SWEEP_SET_LEN, "run.frames=0");
    for (int a = 0; a < sw->naxis; a++)
        if (j->value[a])
            snprintf(set[n++], CL_SWEEP_SET_LEN, "%s=%s", sw->axis[a].key,
                     j->value[a]);
    return n;
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

/* A command line being written: too long once `over`. */
typedef struct {
    char buf[16384];
    size_t u;
    bool over;
} cmdline;

static void put(cmdline *c, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static void put(cmdline *c, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int k = c->over ? 0 : vsnprintf(c->buf + c->u, sizeof c->buf - c->u,
                                     fmt, ap);
    va_end(ap);
    if (k < 0 || (size_t)k >= sizeof c->buf - c->u)
        c->over = true;
    else
        c->u += (size_t)k;
}

/* s quoted for the shell (cl_sweep_quote). */
static void put_quoted(cmdline *c, const char *s)
{
    size_t k = c->over ? 0 : cl_sweep_quote(s, c->buf + c->u,
                                            sizeof c->buf - c->u);
    if (k >= sizeof c->buf - c->u)
        c->over = true;
    else
        c->u += k;
}

/* DIR/jobs/ID/name, quoted. */
static void put_job_path(cmdline *c, const cl_sweep *sw, const char *id,
                         const char *name)
{
    char path[8192];
    int k = snprintf(path, sizeof path, "%s/jobs/%s/%s", sw->dir, id, name);
    if (k < 0 || (size_t)k >= sizeof path)
        c->over = true;
    else
        put_quoted(c, path);
}

/* The job's command line: the status and the outputs of an earlier run
 * removed (a run refused before its first output leaves its directory as
 * it was: an earlier run's statistics must not stand for it), and the job
 * given up, with no status, if they cannot be; the run (its messages into
 * DIR/jobs/ID/stderr), then its exit status into DIR/jobs/ID/exit through
 * a rename, and that status as the line's own:
 *   rm -rf E R || exit 125; clothode run ... --out R 2> S; s=$?;
 *   echo $s > E.tmp && mv E.tmp E; exit $s
 * (POSIX sh) so that every engine leaves the same record, and a job
 * killed before it finished leaves none (analysis/sweep_outcome.c).
 * CL_EINVAL when it does not fit (a sweep directory of thousands of
 * characters). */
static cl_status make_command(const cl_sweep *sw, cl_sweep_job *j)
{
    cmdline c = {.u = 0};
    char set[CL_SWEEP_MAX_AXES + 1][CL_SWEEP_SET_LEN];
    put(&c, "rm -rf ");
    put_job_path(&c, sw, j->id, "exit");
    put(&c, " ");
    put_job_path(&c, sw, j->id, "run");
    put(&c, " || exit 125; ");
    put_quoted(&c, sw->clothode);
    put(&c, " run ");
    put_quoted(&c, sw->problem);
    put(&c, " --integrator ");
    put_quoted(&c, j->integrator);
    for (int k = 0, n = cl_sweep_job_sets(sw, j, set); k < n; k++) {
        put(&c, " --set ");
        put_quoted(&c, set[k]);
    }
    if (j->reference)
        put(&c, " --rtol %s --atol %.6g", sw->ref_rtol,
            strtod(sw->ref_rtol, NULL) / 100);
    /* the run's outputs in jobs/ID/run, its messages and exit status
     * beside them: a run's directory holds nothing but its own outputs */
    put(&c, " --out ");
    put_job_path(&c, sw, j->id, "run");
    put(&c, " --quiet 2> ");
    put_job_path(&c, sw, j->id, "stderr");
    put(&c, "; s=$?; echo $s > ");
    put_job_path(&c, sw, j->id, "exit.tmp");
    put(&c, " && mv ");
    put_job_path(&c, sw, j->id, "exit.tmp");
    put(&c, " ");
    put_job_path(&c, sw, j->id, "exit");
    put(&c, "; exit $s");
    if (c.over)
        return CL_EINVAL;
    return (j->command = strdup(c.buf)) ? CL_OK : CL_ENOMEM;
}

int cl_sweep_find(const cl_sweep *sw, const char *id)
{
    for (int k = 0; k < sw->njob; k++)
        if (!strcmp(sw->job[k].id, id))
            return k;
    return -1;
}

/* An earlier job than k with job k's id or value key, or -1. */
static int twin_of(const cl_sweep *sw, int k)
{
    for (int i = 0; i < k; i++)
        if (!strcmp(sw->job[i].id, sw->job[k].id) ||
            !strcmp(sw->job[i].key, sw->job[k].key))
            return i;
    return -1;
}

/* Set job k's id, value key and command; CL_EINVAL (and *dup its twin)
 * when an earlier job has the same id, or the same values as numbers
 * (rtol = 1e-4 and 0.0001: one run; the id hashes the values as written,
 * so that the ids of sweeps planned before stay). */
static cl_status finish_job(cl_sweep *sw, int k, int *dup, cl_error *err)
{
    char text[8192];
    cl_sweep_job *j = &sw->job[k];
    cl_sweep_canonical(sw, j, text, sizeof text);
    make_id(text, j->id);
    canonical(sw, j, true, text, sizeof text);
    make_id(text, j->key);
    *dup = twin_of(sw, k);
    if (*dup >= 0) {
        cl_sweep_describe(sw, j, text, sizeof text);
        return cl_error_set(err, CL_EINVAL, "sweep: two jobs are the same "
                            "run, %s (a value listed twice, or two steps "
                            "that dt = t_end / N makes one)", text);
    }
    cl_status rc = make_command(sw, j);
    if (rc == CL_EINVAL)
        return cl_error_set(err, rc, "sweep: job %s: its command line is "
                            "longer than %zu characters (a shorter sweep "
                            "directory or problem path)", j->id,
                            sizeof ((cmdline *)0)->buf - 1);
    return rc ? cl_error_set(err, rc, "sweep: job %s: out of memory", j->id)
              : CL_OK;
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
    r->value = calloc(CL_SWEEP_MAX_AXES + 1, sizeof *r->value);
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

/* ---- the union of the parts -------------------------------------------- */

/* The index of sw's axis `key`, added if new; -1 if there are too many. */
static int union_axis(cl_sweep *sw, const char *key)
{
    for (int a = 0; a < sw->naxis; a++)
        if (!strcmp(sw->axis[a].key, key))
            return a;
    if (sw->naxis == CL_SWEEP_MAX_AXES)
        return -1;
    sw->axis[sw->naxis] = (cl_sweep_axis){.key = strdup(key), .from = -1};
    return sw->axis[sw->naxis].key ? sw->naxis++ : -1;
}

/* The list's own copy of the string v, added if new; NULL without
 * memory. */
static const char *union_value(char ***list, int *n, const char *v)
{
    for (int k = 0; k < *n; k++)
        if (!strcmp((*list)[k], v))
            return (*list)[k];
    char **grown = realloc(*list, (size_t)(*n + 1) * sizeof *grown);
    if (!grown)
        return NULL;
    *list = grown;
    return (grown[*n] = strdup(v)) ? grown[(*n)++] : NULL;
}

/* The jobs of a part: integrators times its axes' values (derived axes
 * following their source). */
static long part_size(const cl_sweep_part *p)
{
    long n = p->nint;
    for (int a = 0; a < p->naxis && n <= CL_SWEEP_MAX_VALUES; a++)
        n *= p->axis[a].from < 0 ? p->axis[a].n : 1;
    return n;
}

/* Job k of part p: its value of every axis, the last axis fastest. */
static cl_status fill_job(cl_sweep *sw, const cl_sweep_part *p,
                          const int *map, long k, cl_sweep_job *j)
{
    int idx[CL_SWEEP_MAX_AXES];
    long rest = k;
    for (int a = p->naxis - 1; a >= 0; a--)
        if (p->axis[a].from < 0) {
            idx[a] = (int)(rest % p->axis[a].n);
            rest /= p->axis[a].n;
        }
    for (int a = 0; a < p->naxis; a++) {
        cl_sweep_axis *u = &sw->axis[map[a]];
        int at = p->axis[a].from < 0 ? idx[a] : idx[p->axis[a].from];
        if (!(j->value[map[a]] = union_value(&u->v, &u->n,
                                             p->axis[a].v[at])))
            return CL_ENOMEM;
    }
    j->integrator = union_value(&sw->integrator, &sw->nint,
                                p->integrator[rest]);
    j->ref = -1;
    return j->integrator ? CL_OK : CL_ENOMEM;
}

static cl_status expand_part(cl_sweep *sw, const cl_sweep_part *p,
                             cl_error *err)
{
    int map[CL_SWEEP_MAX_AXES], dup;
    for (int a = 0; a < p->naxis; a++)
        if ((map[a] = union_axis(sw, p->axis[a].key)) < 0)
            return cl_error_set(err, CL_EINVAL, "sweep: more than %d axes "
                                "over all parts", CL_SWEEP_MAX_AXES);
    cl_status rc = CL_OK;
    for (long k = 0; !rc && k < part_size(p); k++) {
        cl_sweep_job *j = &sw->job[sw->njob++];
        if (!(j->value = calloc(CL_SWEEP_MAX_AXES + 1, sizeof *j->value)) ||
            fill_job(sw, p, map, k, j))
            return cl_error_set(err, CL_ENOMEM, "out of memory");
        rc = finish_job(sw, sw->njob - 1, &dup, err);
    }
    return rc;
}

cl_status cl_sweep_expand(cl_sweep *sw, cl_error *err)
{
    long n = 0;
    for (int p = 0; p < sw->nplan; p++)
        n += part_size(&sw->part[p]);
    if (n > CL_SWEEP_MAX_VALUES)
        return cl_error_set(err, CL_EINVAL, "sweep: more than %d jobs",
                            CL_SWEEP_MAX_VALUES);
    /* at most one reference per job */
    sw->job = calloc((size_t)n * (sw->ref_rtol[0] ? 2 : 1), sizeof *sw->job);
    if (!sw->job)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    cl_status rc = CL_OK;
    for (int p = 0; !rc && p < sw->nplan; p++)
        rc = expand_part(sw, &sw->part[p], err);
    for (long k = 0; !rc && sw->ref_rtol[0] && k < n; k++)
        rc = add_reference(sw, (int)k, err);
    return rc;
}

cl_status cl_sweep_add_job(cl_sweep *sw, const char *integrator,
                           const char *const *value, cl_error *err)
{
    cl_sweep_job *grown = realloc(sw->job, (size_t)(sw->njob + 1) *
                                               sizeof *grown);
    if (!grown)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    sw->job = grown;
    cl_sweep_job *j = &sw->job[sw->njob];
    *j = (cl_sweep_job){.ref = -1};
    if (!(j->value = calloc(CL_SWEEP_MAX_AXES + 1, sizeof *j->value)))
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    sw->njob++;
    for (int a = 0; a < sw->naxis; a++)
        if (value[a] && !(j->value[a] = union_value(&sw->axis[a].v,
                                                    &sw->axis[a].n,
                                                    value[a])))
            return cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!(j->integrator = union_value(&sw->integrator, &sw->nint,
                                      integrator)))
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    int dup;
    return finish_job(sw, sw->njob - 1, &dup, err);
}

void cl_sweep_strings_free(char **v, int n)
{
    for (int k = 0; k < n; k++)
        free(v[k]);
    free(v);
}

void cl_sweep_free(cl_sweep *sw)
{
    for (int k = 0; k < sw->njob; k++) {
        free(sw->job[k].value);
        free(sw->job[k].command);
    }
    free(sw->job);
    for (int a = 0; a < sw->naxis; a++) {
        cl_sweep_strings_free(sw->axis[a].v, sw->axis[a].n);
        free(sw->axis[a].key);
    }
    cl_sweep_strings_free(sw->integrator, sw->nint);
    free(sw->dir);
    free(sw->problem);
    free(sw->clothode);
    cl_sweep_parts_free(sw);
    memset(sw, 0, sizeof *sw);
}
