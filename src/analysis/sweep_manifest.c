/* A sweep's files (analysis/sweep.h): DIR/jobs.txt, the commands, and
 * DIR/sweep.json, the manifest from which run and collect read the plan
 * back (JSON with Jansson). */
#include "analysis/sweep.h"

#include <jansson.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic.h"
#include "io/jsonfile.h"

static json_t *axes_json(const cl_sweep *sw)
{
    json_t *axes = json_array();
    for (int a = 0; a < sw->naxis; a++) {
        json_t *v = json_array();
        for (int k = 0; k < sw->axis[a].n; k++)
            json_array_append_new(v, json_string(sw->axis[a].v[k]));
        json_array_append_new(axes, json_pack("{s:s, s:o}", "key",
                                              sw->axis[a].key, "values", v));
    }
    return axes;
}

static json_t *job_json(const cl_sweep *sw, const cl_sweep_job *j)
{
    json_t *values = json_object();
    for (int a = 0; a < sw->naxis; a++)
        if (j->value[a])
            json_object_set_new(values, sw->axis[a].key,
                                json_string(j->value[a]));
    return json_pack("{s:s, s:s, s:o, s:b, s:o, s:s}", "id", j->id,
                     "integrator", j->integrator, "values", values,
                     "reference", j->reference, "ref",
                     j->ref >= 0 ? json_string(sw->job[j->ref].id)
                                 : json_null(),
                     "command", j->command);
}

static json_t *manifest(const cl_sweep *sw)
{
    json_t *ints = json_array(), *jobs = json_array();
    for (int k = 0; k < sw->nint; k++)
        json_array_append_new(ints, json_string(sw->integrator[k]));
    for (int k = 0; k < sw->njob; k++)
        json_array_append_new(jobs, job_json(sw, &sw->job[k]));
    return json_pack("{s:i, s:s, s:s, s:s, s:o, s:o, s:s, s:o}", "format", 1,
                     "dir", sw->dir, "problem", sw->problem, "clothode",
                     sw->clothode, "integrators", ints, "axes",
                     axes_json(sw), "reference_rtol", sw->ref_rtol, "jobs",
                     jobs);
}

cl_status cl_sweep_write(const cl_sweep *sw, cl_error *err)
{
    char path[4200];
    cl_afile af;
    cl_status rc = cl_mkdir_p(sw->dir, err);
    /* every job's directory, where its command sends its stderr */
    for (int k = 0; !rc && k < sw->njob; k++) {
        snprintf(path, sizeof path, "%s/jobs/%s", sw->dir, sw->job[k].id);
        rc = cl_mkdir_p(path, err);
    }
    snprintf(path, sizeof path, "%s/jobs.txt", sw->dir);
    if (rc || (rc = cl_afile_open(&af, path, err)))
        return rc;
    for (int k = 0; k < sw->njob; k++)
        fprintf(af.fp, "%s\n", sw->job[k].command);
    if ((rc = cl_afile_commit(&af, err)))
        return rc;
    json_t *m = manifest(sw);
    snprintf(path, sizeof path, "%s/sweep.json", sw->dir);
    if (!m)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!(rc = cl_afile_open(&af, path, err))) {
        if (json_dumpf(m, af.fp, JSON_INDENT(1)) || fputc('\n', af.fp) < 0)
            rc = cl_afile_fail(&af, err);
        else
            rc = cl_afile_commit(&af, err);
    }
    json_decref(m);
    return rc;
}

/* ---- reading it back ---------------------------------------------------- */

static cl_status bad(const char *path, const char *what, cl_error *err)
{
    return cl_error_set(err, CL_EPARSE, "%s: not a sweep manifest (%s); "
                        "made by 'clothode sweep plan'", path, what);
}

static char *text_of(json_t *o, const char *key)
{
    const char *s = json_string_value(json_object_get(o, key));
    return s ? strdup(s) : NULL;
}

static cl_status load_axes(json_t *root, cl_sweep *sw)
{
    json_t *axes = json_object_get(root, "axes"), *a, *v;
    size_t i, k;
    if (!json_is_array(axes) || json_array_size(axes) > CL_SWEEP_MAX_AXES)
        return CL_EPARSE;
    json_array_foreach(axes, i, a) {
        cl_sweep_axis *ax = &sw->axis[sw->naxis++];
        ax->from = -1;
        json_t *vals = json_object_get(a, "values");
        if (!(ax->key = text_of(a, "key")) || !json_is_array(vals) ||
            !(ax->v = calloc(json_array_size(vals) + 1, sizeof *ax->v)))
            return CL_EPARSE;
        json_array_foreach(vals, k, v)
            if (!(ax->v[ax->n++] = strdup(json_string_value(v) ? json_string_value(v) : "")))
                return CL_EPARSE;
    }
    json_t *ints = json_object_get(root, "integrators");
    if (!json_is_array(ints) ||
        !(sw->integrator = calloc(json_array_size(ints) + 1, sizeof(char *))))
        return CL_EPARSE;
    json_array_foreach(ints, i, v)
        if (!(sw->integrator[sw->nint++] = strdup(json_string_value(v) ? json_string_value(v) : "")))
            return CL_EPARSE;
    return CL_OK;
}

/* The axis's own copy of a value (jobs point into the axes). */
static const char *axis_value(const cl_sweep_axis *a, const char *v)
{
    for (int k = 0; v && k < a->n; k++)
        if (!strcmp(a->v[k], v))
            return a->v[k];
    return NULL;
}

static const char *integrator_of(const cl_sweep *sw, const char *name)
{
    for (int k = 0; name && k < sw->nint; k++)
        if (!strcmp(sw->integrator[k], name))
            return sw->integrator[k];
    return name && !strcmp(name, "cvode-bdf") ? "cvode-bdf" : NULL;
}

static cl_status load_job(json_t *o, cl_sweep *sw, cl_sweep_job *j)
{
    json_t *values = json_object_get(o, "values");
    const char *id = json_string_value(json_object_get(o, "id"));
    j->integrator = integrator_of(
        sw, json_string_value(json_object_get(o, "integrator")));
    j->reference = json_is_true(json_object_get(o, "reference"));
    j->value = calloc((size_t)sw->naxis + 1, sizeof *j->value);
    if (!id || strlen(id) != CL_SWEEP_ID_LEN - 1 || !j->integrator ||
        !json_is_object(values) || !j->value ||
        !(j->command = text_of(o, "command")))
        return CL_EPARSE;
    strcpy(j->id, id);
    for (int a = 0; a < sw->naxis; a++) {
        const char *v = json_string_value(json_object_get(values,
                                                          sw->axis[a].key));
        if (v && !(j->value[a] = axis_value(&sw->axis[a], v)))
            return CL_EPARSE;
    }
    return CL_OK;
}

static cl_status load_jobs(json_t *root, cl_sweep *sw)
{
    json_t *jobs = json_object_get(root, "jobs"), *o;
    size_t i;
    if (!json_is_array(jobs) ||
        !(sw->job = calloc(json_array_size(jobs) + 1, sizeof *sw->job)))
        return CL_EPARSE;
    json_array_foreach(jobs, i, o) {
        sw->njob++;
        if (load_job(o, sw, &sw->job[i]))
            return CL_EPARSE;
    }
    json_array_foreach(jobs, i, o) {
        const char *ref = json_string_value(json_object_get(o, "ref"));
        sw->job[i].ref = ref ? cl_sweep_find(sw, ref) : -1;
        if (ref && sw->job[i].ref < 0)
            return CL_EPARSE;
    }
    return CL_OK;
}

/* Whether every job's command records its exit status (ends as
 * analysis/sweep_plan.c makes it end). */
static bool records_status(const cl_sweep *sw)
{
    static const char tail[] = "; exit $s";
    for (int k = 0; k < sw->njob; k++) {
        size_t n = strlen(sw->job[k].command);
        if (n < sizeof tail - 1 ||
            strcmp(sw->job[k].command + n - (sizeof tail - 1), tail))
            return false;
    }
    return true;
}

cl_status cl_sweep_load(const char *dir, cl_sweep *sw, cl_error *err)
{
    char path[4200];
    json_error_t jerr;
    snprintf(path, sizeof path, "%s/sweep.json", dir);
    const char *why;
    json_t *root = cl_json_read(path, &jerr, &why);
    if (!root && why)
        return cl_error_set(err, CL_EIO, "%s: cannot read it (%s); a sweep "
                            "directory is made by 'clothode sweep plan'",
                            path, why);
    if (!root)
        return cl_error_set(err, CL_EPARSE, "%s:%d: %s; a sweep directory is "
                            "made by 'clothode sweep plan'", path, jerr.line,
                            jerr.text);
    const char *ref = json_string_value(json_object_get(root,
                                                        "reference_rtol"));
    snprintf(sw->ref_rtol, sizeof sw->ref_rtol, "%s", ref ? ref : "");
    cl_status rc = (sw->dir = text_of(root, "dir")) &&
                           (sw->problem = text_of(root, "problem")) &&
                           (sw->clothode = text_of(root, "clothode"))
                       ? CL_OK
                       : CL_EPARSE;
    if (!rc)
        rc = load_axes(root, sw);
    if (!rc)
        rc = load_jobs(root, sw);
    json_decref(root);
    if (rc)
        return bad(path, "a field is missing or malformed", err);
    return records_status(sw) ? CL_OK
           : cl_error_set(err, CL_EINVAL, "%s: planned by an earlier "
                          "clothode, whose jobs do not record their exit "
                          "status; plan it again with 'clothode sweep plan' "
                          "(the ids stay), then 'sweep run --resume'", path);
}
