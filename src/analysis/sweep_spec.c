/* A sweep file read (analysis/sweep.h): [sweep] and its parts
 * [sweep.NAME], their integrators and axes with the values expanded. */
#include "analysis/sweep.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "integrators/integrator.h"

static char *dup_n(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

/* The shortest "%.*g" of x that reads back as x, at most `digits` digits,
 * and without an exponent between 1e-4 and 1e15 (200, not 2e+02). */
static void shortest_of(double x, int digits, char *buf, size_t len)
{
    bool plain = fabs(x) >= 1e-4 && fabs(x) < 1e15;
    for (int p = 1; p <= digits; p++) {
        snprintf(buf, len, "%.*g", p, x);
        if (strtod(buf, NULL) == x && !(plain && strchr(buf, 'e')))
            return;
    }
    snprintf(buf, len, "%.*g", digits, x);
}

/* Digits of a value computed from the spec (linspace, logspace, C * OTHER,
 * the reference's tolerance): 15, so that 1e-5 / 100 is 1e-07, not its
 * rounding 1.0000000000000001e-07; a step made T / N takes 17
 * (cl_sweep_exact). */
#define SPEC_DIGITS 15
#define EXACT_DIGITS 17

void cl_sweep_exact(double x, char *buf, size_t len)
{
    shortest_of(x, EXACT_DIGITS, buf, len);
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

/* x as an axis value of at most `digits` digits (shortest_of). */
static cl_status add_number(cl_sweep_axis *a, double x, int digits)
{
    char buf[32];
    shortest_of(x, digits, buf, sizeof buf);
    return add_value(a, buf, strlen(buf));
}

/* ---- axis values -------------------------------------------------------- */

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
        rc = add_number(a, log ? pow(10, e) : e, SPEC_DIGITS);
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

cl_status cl_sweep_axis_values(cl_sweep_axis *a, const char *v, bool *ok)
{
    return !strncmp(v, "linspace(", 9)   ? spaced(a, v, false, ok)
           : !strncmp(v, "logspace(", 9) ? spaced(a, v, true, ok)
                                         : listed(a, v, ok);
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

static int find_axis(const cl_sweep_part *p, const char *key)
{
    for (int a = 0; a < p->naxis; a++)
        if (!strcmp(p->axis[a].key, key))
            return a;
    return -1;
}

/* "KEY * C" or "KEY / C", KEY an axis of the part above this one: the
 * values follow KEY's, job by job (atol = rtol / 100). */
static cl_status derived(cl_sweep_part *p, int self, const char *v, bool *ok,
                         bool *is)
{
    char name[128], op;
    double c;
    int used = 0;
    *is = sscanf(v, "%127[A-Za-z0-9_.-] %c %lf %n", name, &op, &c, &used) ==
              3 && !v[used] && (op == '*' || op == '/');
    char *key = *is ? axis_key(name) : NULL;
    int from = key ? find_axis(p, key) : -1;
    free(key);
    *ok = *is && from >= 0 && from != self && p->axis[from].from < 0 &&
          isfinite(c) && c != 0;
    cl_status rc = CL_OK;
    for (int k = 0; *ok && !rc && k < p->axis[from].n; k++) {
        char *end;
        double x = strtod(p->axis[from].v[k], &end);
        *ok = !*end && isfinite(x);
        rc = *ok ? add_number(&p->axis[self], op == '*' ? x * c : x / c,
                              SPEC_DIGITS)
                 : CL_OK;
    }
    p->axis[self].from = *ok ? from : -1;
    return rc;
}

static void free_axis(cl_sweep_axis *a)
{
    cl_sweep_strings_free(a->v, a->n);
    free(a->key);
    memset(a, 0, sizeof *a);
}

/* The axis KEY = VALUE of section sec into part p (replacing one of the
 * same key that p took over from [sweep]); mine[a]: axis a was set by
 * this section already (the same key written two ways, as n and
 * cloth.n, is refused). */
static cl_status read_axis(cl_config *cfg, const char *sec, const char *key,
                           cl_sweep_part *p, bool *mine, cl_error *err)
{
    char *name = axis_key(key);
    const char *v = cl_config_string(cfg, sec, key, "");
    if (!name)
        return cl_config_refuse(cfg, sec, key, CL_EINVAL, "expected "
                                "problem, integrator, reference, an axis dt, "
                                "rtol, atol, t_end, n or SECTION.KEY", err);
    int self = find_axis(p, name);
    if (self >= 0 && mine[self]) {
        cl_status rc = cl_config_refuse(cfg, sec, key, CL_EINVAL, "an axis "
                                        "given twice in one section (dt is "
                                        "run.dt, n is cloth.n)", err);
        free(name);
        return rc;
    }
    if (self < 0 && p->naxis == CL_SWEEP_MAX_AXES) {
        free(name);
        return cl_config_refuse(cfg, sec, key, CL_EINVAL,
                                "too many axes (at most 16)", err);
    }
    self = self >= 0 ? self : p->naxis++;
    mine[self] = true;
    free_axis(&p->axis[self]);
    p->axis[self] = (cl_sweep_axis){.key = name, .from = -1};
    bool ok = false, is = false;
    cl_status rc = derived(p, self, v, &ok, &is);
    if (!rc && !is)
        rc = cl_sweep_axis_values(&p->axis[self], v, &ok);
    if (rc)
        return cl_error_set(err, rc, "out of memory");
    return ok ? CL_OK
              : cl_config_refuse(cfg, sec, key, CL_EINVAL,
                                 "expected a list v1, v2, ... of non-empty "
                                 "values, linspace(a, b, k) or logspace(a, "
                                 "b, k) with 1 <= k <= 100000, or KEY * C "
                                 "or KEY / C of a numeric axis above", err);
}

/* "NAME[:LINSOL], ...", each NAME an integrator of the registry. */
static cl_status read_integrators(cl_config *cfg, const char *sec,
                                  cl_sweep_part *p, cl_error *err)
{
    cl_sweep_axis list = {0};
    bool ok = false;
    const char *v = cl_config_string(cfg, sec, "integrator", "");
    cl_status rc = listed(&list, v, &ok);
    char name[64];
    for (int k = 0; ok && !rc && k < list.n; k++) {
        snprintf(name, sizeof name, "%.*s", (int)strcspn(list.v[k], ":"),
                 list.v[k]);
        ok = cl_integrator_find(name) != NULL;
    }
    p->integrator = list.v;
    p->nint = list.n;
    if (rc)
        return cl_error_set(err, rc, "out of memory");
    return ok ? CL_OK
              : cl_config_refuse(cfg, sec, "integrator", CL_EINVAL,
                                 "expected NAME[:LINSOL], ... with each NAME "
                                 "an integrator (clothode list)", err);
}

/* With one t_end T, every dt becomes T / N, N = round(T / dt) >= 1, so
 * that a fixed-step run ends exactly at T, written to the last digit
 * (cl_sweep_exact), so that its steps are the stability study's T / N
 * (fifteen digits made some of them another step, stable where T / N
 * blows up);
 * values that are not positive finite numbers are left as written, for
 * the plan's check to refuse. */
static cl_status snap_dt(cl_sweep_part *p)
{
    int dt = find_axis(p, "run.dt"), te = find_axis(p, "run.t_end");
    char *end = NULL;
    double T = dt >= 0 && te >= 0 && p->axis[te].n == 1
                   ? strtod(p->axis[te].v[0], &end)
                   : NAN;
    if (!(T > 0) || *end)
        return CL_OK;
    cl_sweep_axis *a = &p->axis[dt], snapped = {.from = a->from};
    cl_status rc = CL_OK;
    for (int k = 0; !rc && k < a->n; k++) {
        double h = strtod(a->v[k], &end), n = round(T / h);
        rc = h > 0 && isfinite(h) && !*end && isfinite(n) && n <= 1e15
                 ? add_number(&snapped, T / fmax(n, 1), EXACT_DIGITS)
                 : add_value(&snapped, a->v[k], strlen(a->v[k]));
    }
    snapped.key = a->key;
    a->key = NULL;
    free_axis(a);
    *a = snapped;
    return rc;
}

/* ---- the parts ---------------------------------------------------------- */

static bool reserved(const char *key)
{
    return !strcmp(key, "problem") || !strcmp(key, "integrator") ||
           !strcmp(key, "reference");
}

static cl_status copy_part(const cl_sweep_part *from, cl_sweep_part *to)
{
    for (int a = 0; a < from->naxis; a++) {
        cl_sweep_axis *d = &to->axis[to->naxis++];
        *d = (cl_sweep_axis){.key = strdup(from->axis[a].key),
                             .from = from->axis[a].from};
        for (int k = 0; d->key && k < from->axis[a].n; k++)
            if (add_value(d, from->axis[a].v[k], strlen(from->axis[a].v[k])))
                return CL_ENOMEM;
        if (!d->key)
            return CL_ENOMEM;
    }
    return CL_OK;
}

/* Section sec into part p: integrators (else those of base), axes. */
static cl_status read_part(cl_config *cfg, const char *sec,
                           const cl_sweep_part *base, cl_sweep_part *p,
                           cl_error *err)
{
    cl_status rc = base && copy_part(base, p)
                       ? cl_error_set(err, CL_ENOMEM, "out of memory")
                       : CL_OK;
    bool own = cl_config_string(cfg, sec, "integrator", NULL) != NULL;
    cl_sweep_axis ints = {0};
    if (!rc && own)
        rc = read_integrators(cfg, sec, p, err);
    for (int k = 0; !rc && !own && base && k < base->nint; k++)
        if (add_value(&ints, base->integrator[k], strlen(base->integrator[k])))
            rc = cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!own && base) {
        p->integrator = ints.v;
        p->nint = ints.n;
    }
    const char *key;
    bool mine[CL_SWEEP_MAX_AXES] = {false};
    for (size_t k = 0; !rc && (key = cl_config_key_at(cfg, sec, k)); k++)
        if (base && (!strcmp(key, "problem") || !strcmp(key, "reference")))
            rc = cl_config_refuse(cfg, sec, key, CL_EINVAL, "belongs in "
                                  "[sweep]", err);
        else if (!reserved(key))
            rc = read_axis(cfg, sec, key, p, mine, err);
    return rc ? rc : snap_dt(p);
}

void cl_sweep_parts_free(cl_sweep *sw)
{
    for (int p = 0; p < sw->npart; p++) {
        cl_sweep_part *part = &sw->part[p];
        for (int a = 0; a < part->naxis; a++)
            free_axis(&part->axis[a]);
        cl_sweep_strings_free(part->integrator, part->nint);
        free(part->name);
    }
    sw->npart = 0;
}

/* [sweep] alone is the one part; with [sweep.NAME] sections it is their
 * template and they are the parts. */
static cl_status read_parts(cl_config *cfg, cl_sweep *sw, cl_error *err)
{
    const char *sec;
    sw->npart = 1;
    cl_status rc = read_part(cfg, "sweep", NULL, &sw->part[0], err);
    for (size_t k = 0;
         !rc && (sec = cl_config_section_at(cfg, "sweep.", k)); k++) {
        if (sw->npart == CL_SWEEP_MAX_PARTS)
            return cl_error_set(err, CL_EINVAL, "%s: [%s]: too many parts "
                                "(at most %d)", cl_config_path(cfg), sec,
                                CL_SWEEP_MAX_PARTS - 1);
        cl_sweep_part *p = &sw->part[sw->npart++];
        if (!(p->name = strdup(sec)))
            return cl_error_set(err, CL_ENOMEM, "out of memory");
        rc = read_part(cfg, sec, &sw->part[0], p, err);
    }
    if (!rc && sw->npart > 1) { /* the template makes no jobs itself */
        cl_sweep_part base = sw->part[0];
        memmove(&sw->part[0], &sw->part[1],
                (size_t)(sw->npart - 1) * sizeof base);
        sw->part[sw->npart - 1] = base;
    }
    sw->nplan = sw->npart > 1 ? sw->npart - 1 : 1;
    for (int p = 0; !rc && p < sw->nplan; p++)
        if (!sw->part[p].nint)
            rc = cl_error_set(err, CL_EINVAL, "%s: [%s] integrator: "
                              "NAME[:LINSOL], ... is required (there or in "
                              "[sweep])", cl_config_path(cfg),
                              sw->part[p].name ? sw->part[p].name : "sweep");
    return rc;
}

cl_status cl_sweep_read(cl_config *cfg, cl_sweep *sw, cl_error *err)
{
    const char *problem = cl_config_string(cfg, "sweep", "problem", "");
    double ref = 0;
    if (!*problem)
        return cl_error_set(err, CL_EINVAL, "%s: [sweep] problem: a problem "
                            "file is required", cl_config_path(cfg));
    if (!(sw->problem = strdup(problem)))
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    cl_status rc = cl_config_double(cfg, "sweep", "reference", 0, 1e-15,
                                    1e-4, &ref, err);
    if (!rc && ref > 0)
        shortest_of(ref, SPEC_DIGITS, sw->ref_rtol, sizeof sw->ref_rtol);
    return rc ? rc : read_parts(cfg, sw, err);
}
