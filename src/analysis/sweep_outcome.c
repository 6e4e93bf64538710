/* What a sweep's job left behind (analysis/sweep.h): its exit status as
 * its command recorded it, its statistics and how far it got.  Every file
 * of a job directory that collect reads is read here. */
#include "analysis/sweep.h"

#include <jansson.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/exit.h"
#include "io/input.h"
#include "io/jsonfile.h"
#include "io/sha256.h"

const char *const cl_sweep_stat_names[CL_SWEEP_NSTAT] = {
    "steps", "rhs_evals", "jac_evals", "lin_setups", "lin_solves",
    "lin_iters", "nonlin_iters", "nonlin_fails", "err_fails",
    "symbolic_facts", "lin_fallbacks", "wall", "cpu"}; /* these two last:
                                                          read_times() */

/* ---- one job ------------------------------------------------------------ */

static FILE *job_file(const cl_sweep *sw, int k, const char *name)
{
    char path[4200];
    snprintf(path, sizeof path, "%s/jobs/%s/%s", sw->dir, sw->job[k].id,
             name);
    const char *why;
    return cl_input_open(path, "r", &why);
}

/* The exit status the job's command recorded as its last step
 * (DIR/jobs/ID/exit: the shell's $?, 0 to 255, 128 + N after signal N,
 * alone on its line); false if there is none (never run, under way, or
 * stopped before it finished) or the file holds anything else. */
static bool exit_status(const cl_sweep *sw, int k, cl_sweep_outcome *o)
{
    FILE *fp = job_file(sw, k, "exit");
    char line[64] = "", *end;
    bool found = fp && fgets(line, sizeof line, fp);
    if (fp)
        fclose(fp);
    long v = strtol(line, &end, 10);
    found = found && end != line && (*end == '\n' || !*end) && v >= 0 &&
            v <= 255;
    if (found) {
        o->exitval = v > 128 ? -1 : (int)v;
        o->signal = v > 128 ? (int)v - 128 : 0;
    }
    return found;
}

void cl_sweep_inputs_add(cl_sweep_inputs *in, const char *key,
                         const char *sha256)
{
    if (in->used < sizeof in->text)
        in->used += (size_t)snprintf(in->text + in->used,
                                     sizeof in->text - in->used, "%s %s\n",
                                     key, sha256);
}

void cl_sweep_inputs_digest(const cl_sweep_inputs *in, char hex[65])
{
    if (in->used)
        cl_sha256_text(in->text, hex);
    else
        snprintf(hex, CL_SHA256_HEX, "none");
}

/* The digest of the files a run's problem named (run.json's "inputs");
 * "" for none recorded. */
static void inputs_digest(json_t *inputs, char hex[CL_SHA256_HEX])
{
    cl_sweep_inputs in = {"", 0};
    size_t k;
    json_t *f;
    if (!json_is_array(inputs)) {
        *hex = '\0';
        return;
    }
    json_array_foreach(inputs, k, f) {
        const char *key = json_string_value(json_object_get(f, "key"));
        const char *sha = json_string_value(json_object_get(f, "sha256"));
        cl_sweep_inputs_add(&in, key ? key : "", sha ? sha : "");
    }
    cl_sweep_inputs_digest(&in, hex);
}

/* From the run's run.json: the integrator's wall and CPU seconds
 * ("times", README "Provenance"; stats.csv holds no timings, so that
 * identical runs write identical bytes) as the statistics "wall" and
 * "cpu", the last two, where run.json has them; and the SHA-256 of the
 * problem file it read and of the files it named. */
static void read_run_json(const cl_sweep *sw, int k, cl_sweep_outcome *o)
{
    static const char *const key[2] = {"integrator_wall", "integrator_cpu"};
    char path[4200];
    snprintf(path, sizeof path, "%s/jobs/%s/run/run.json", sw->dir,
             sw->job[k].id);
    const char *why;
    json_error_t je;
    json_t *root = cl_json_read(path, &je, &why);
    json_t *times = json_object_get(root, "times");
    for (int i = 0; i < 2; i++) {
        json_t *v = json_object_get(times, key[i]);
        if (json_is_number(v))
            o->stat[CL_SWEEP_NSTAT - 2 + i] = json_number_value(v);
    }
    const char *sha = json_string_value(
        json_object_get(json_object_get(root, "problem"), "sha256"));
    snprintf(o->problem_sha256, sizeof o->problem_sha256, "%s",
             sha ? sha : "");
    inputs_digest(json_object_get(root, "inputs"), o->inputs_sha256);
    json_decref(root);
}

/* stats.csv's "name,value" rows; false if there is none. */
static bool read_stats(const cl_sweep *sw, int k, cl_sweep_outcome *o)
{
    FILE *fp = job_file(sw, k, "run/stats.csv");
    char line[256];
    if (!fp)
        return false;
    while (fgets(line, sizeof line, fp)) {
        size_t n = strcspn(line, ",");
        for (int s = 0; line[n] && s < CL_SWEEP_NSTAT; s++)
            if (strlen(cl_sweep_stat_names[s]) == n &&
                !strncmp(line, cl_sweep_stat_names[s], n)) {
                char *end;
                double v = strtod(line + n + 1, &end);
                o->stat[s] = end > line + n + 1 ? v : NAN; /* "NA" */
            }
    }
    fclose(fp);
    return true;
}

/* The time of series.csv's last row. */
static double reached(const cl_sweep *sw, int k)
{
    FILE *fp = job_file(sw, k, "run/series.csv");
    char line[1024];
    double t = NAN;
    while (fp && fgets(line, sizeof line, fp)) {
        char *end;
        double v = strtod(line, &end);
        if (end > line && *end == ',')
            t = v;
    }
    if (fp)
        fclose(fp);
    return t;
}

/* The first line of the job's stderr. */
static void first_message(const cl_sweep *sw, int k, cl_sweep_outcome *o)
{
    FILE *fp = job_file(sw, k, "stderr");
    if (fp && fgets(o->message, sizeof o->message, fp))
        o->message[strcspn(o->message, "\n")] = '\0';
    if (fp)
        fclose(fp);
}

static void classify(cl_sweep_outcome *o, bool found, bool stats)
{
    if (!found) {
        o->state = CL_SWEEP_MISSING;
        snprintf(o->exit_class, sizeof o->exit_class, "missing");
    } else if (o->signal) {
        o->state = CL_SWEEP_FAILED;
        snprintf(o->exit_class, sizeof o->exit_class, "signal-%d",
                 o->signal);
    } else if (o->exitval == 0) {
        /* exit 0 without statistics: the outputs were lost */
        o->state = stats ? CL_SWEEP_COMPLETE : CL_SWEEP_FAILED;
        snprintf(o->exit_class, sizeof o->exit_class, "%s",
                 stats ? "ok" : "no-output");
    } else {
        o->state = CL_SWEEP_FAILED;
        const char *name = cl_exit_name(o->exitval);
        if (name)
            snprintf(o->exit_class, sizeof o->exit_class, "%s", name);
        else
            snprintf(o->exit_class, sizeof o->exit_class, "exit-%d",
                     o->exitval);
    }
}

void cl_sweep_outcome_read(const cl_sweep *sw, int k, cl_sweep_outcome *o)
{
    *o = (cl_sweep_outcome){.exitval = -1, .err_x = NAN, .err_v = NAN};
    for (int s = 0; s < CL_SWEEP_NSTAT; s++)
        o->stat[s] = NAN;
    bool found = exit_status(sw, k, o);
    bool stats = found && read_stats(sw, k, o);
    if (stats)
        read_run_json(sw, k, o);
    o->t_reached = found ? reached(sw, k) : NAN;
    if (found)
        first_message(sw, k, o);
    classify(o, found, stats);
}

/* ---- errors against the reference --------------------------------------- */

/* final.csv's rows "p,x,y,z,vx,vy,vz" of two runs: the largest distance
 * of positions and of velocities; false if the files do not match. */
static bool distances(FILE *a, FILE *b, double *dx, double *dv)
{
    char la[512], lb[512];
    double u[7], w[7];
    *dx = *dv = 0;
    if (!fgets(la, sizeof la, a) || !fgets(lb, sizeof lb, b))
        return false; /* the headers */
    while (fgets(la, sizeof la, a)) {
        if (!fgets(lb, sizeof lb, b) ||
            sscanf(la, "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &u[0], &u[1], &u[2],
                   &u[3], &u[4], &u[5], &u[6]) != 7 ||
            sscanf(lb, "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &w[0], &w[1], &w[2],
                   &w[3], &w[4], &w[5], &w[6]) != 7)
            return false;
        *dx = fmax(*dx, hypot(hypot(u[1] - w[1], u[2] - w[2]), u[3] - w[3]));
        *dv = fmax(*dv, hypot(hypot(u[4] - w[4], u[5] - w[5]), u[6] - w[6]));
    }
    return !fgets(lb, sizeof lb, b);
}

void cl_sweep_outcome_error(const cl_sweep *sw, int k, cl_sweep_outcome *o)
{
    int r = sw->job[k].ref;
    if (r < 0 || o->state != CL_SWEEP_COMPLETE)
        return;
    FILE *a = job_file(sw, k, "run/final.csv");
    FILE *b = job_file(sw, r, "run/final.csv");
    double dx, dv;
    if (a && b && distances(a, b, &dx, &dv)) {
        o->err_x = dx;
        o->err_v = dv;
    }
    if (a)
        fclose(a);
    if (b)
        fclose(b);
}
