/* Parameter sweeps (`clothode sweep`, README "Sweeps"): a sweep file names
 * a problem, integrators and parameter axes; the plan is the cross product
 * of them, one `clothode run` command per job, each with its own output
 * directory DIR/jobs/ID.  The jobs are run by GNU parallel (locally or over
 * ssh) or as a Slurm job array (cli/sweep_engine.c); collect reads every
 * job's outputs back into one table.
 *
 * The sweep file ([sweep] section, read with io/config.h):
 *   problem     = path of the problem file (required)
 *   integrator  = NAME[:LINSOL], ...
 *   reference   = R: one cvode-bdf run at rtol R (atol R/100) per
 *                 combination of the problem's axes, against whose final
 *                 state collect measures every job's error (optional)
 *   KEY = VALUES   an axis; KEY is dt, rtol, atol, t_end (the [run] keys),
 *                  n ([cloth] n) or any SECTION.KEY of the problem; VALUES
 *                  a comma-separated list, linspace(a, b, k) (k values from
 *                  a to b, evenly spaced), logspace(a, b, k) (10^a to
 *                  10^b, evenly spaced exponents), or OTHER * C, OTHER / C
 *                  with OTHER an axis above: the values follow OTHER's job
 *                  by job (atol = rtol / 100) instead of multiplying the
 *                  jobs.  One value is a constant of every job.  When the
 *                  part gives one t_end T, every dt is made T / N with
 *                  N = round(T / dt), so that fixed-step runs end exactly
 *                  at T.
 * Sections [sweep.NAME] are parts: each takes [sweep]'s integrators and
 * axes, replaces or adds its own, and the jobs are the union of the
 * parts' cross products (fixed-step methods over dt, adaptive ones over
 * rtol, in one sweep).
 *
 * Jobs are ordered by part, integrator, then the axes in file order, the
 * last fastest.  A job's id is the FNV-1a hash of its sorted assignments
 * ("integrator=rk4", "run.dt=1e-05", ...), so it stays the same when the
 * plan is expanded again, whatever the order of the axes or the values
 * added around it. */
#ifndef CL_SWEEP_H
#define CL_SWEEP_H

#include <stdbool.h>
#include <stdio.h>

#include "core/decls.h"
#include "core/error.h"
#include "io/config.h"

CL_BEGIN_DECLS

#define CL_SWEEP_MAX_AXES 16
#define CL_SWEEP_MAX_VALUES 100000
#define CL_SWEEP_ID_LEN 13 /* 12 hex digits and the NUL */

#define CL_SWEEP_MAX_PARTS 17

typedef struct {
    char *key;   /* "run.dt", "cloth.n", "type1.ks" */
    int n;
    char **v;    /* the values as written into the job's --set */
    int from;    /* a part's axis following another one's values job by
                  * job (OTHER / C): that axis's index, else -1 */
} cl_sweep_axis;

/* [sweep] or a [sweep.NAME] part, as read. */
typedef struct {
    char *name;  /* "sweep.NAME", NULL for [sweep] */
    int nint;
    char **integrator;
    int naxis;
    cl_sweep_axis axis[CL_SWEEP_MAX_AXES];
} cl_sweep_part;

typedef struct {
    char id[CL_SWEEP_ID_LEN];
    char key[CL_SWEEP_ID_LEN]; /* the id of the values read as numbers:
                                * one key, one run (a plan's check) */
    const char *integrator; /* NAME or NAME:LINSOL, as in the sweep file */
    const char **value;     /* per axis; NULL where a reference job leaves
                             * a method's axis (run.*) unset */
    bool reference;         /* a reference run of the jobs below */
    int ref;                /* index of the job's reference, or -1 */
    char *command;          /* the shell command line of the job */
} cl_sweep_job;

typedef struct {
    char *dir;        /* the sweep directory, absolute */
    char *problem;    /* the problem file, absolute */
    char *clothode;   /* the clothode binary the jobs run, absolute */
    int npart, nplan; /* parts read; part[0 .. nplan) make the jobs */
    cl_sweep_part part[CL_SWEEP_MAX_PARTS];
    int nint;         /* every integrator of the jobs */
    char **integrator;
    int naxis;        /* every axis of the jobs, the distinct values */
    cl_sweep_axis axis[CL_SWEEP_MAX_AXES];
    char ref_rtol[32]; /* "" without references */
    int njob;
    cl_sweep_job *job;
} cl_sweep;

/* The values v of an axis appended to a->v: a comma-separated list,
 * linspace(a, b, k) or logspace(a, b, k) (numbers written as the plan
 * writes them); *ok false when v is none of these.  CL_ENOMEM. */
cl_status cl_sweep_axis_values(cl_sweep_axis *a, const char *v, bool *ok);

/* x as the shortest "%.*g" that reads back as exactly x (at most 17
 * digits; no exponent between 1e-4 and 1e15): a step T / N given to a
 * run as the double the stability study steps with. */
void cl_sweep_exact(double x, char *buf, size_t len);

/* Read the [sweep] sections of cfg into sw's parts (problem into
 * sw->problem as written, for the caller to resolve; integrators; axes
 * with their values expanded).  Refused keys and values: CL_EINVAL naming
 * file, line, key, value and what is allowed. */
cl_status cl_sweep_read(cl_config *cfg, cl_sweep *sw, cl_error *err);
void cl_sweep_parts_free(cl_sweep *sw);

/* The job list of sw (sw->dir, ->problem and ->clothode set): each part's
 * cross product with ids and commands, then the reference jobs; the
 * union of the parts' integrators and axes in sw.  CL_EINVAL when two
 * jobs are the same (a value listed twice). */
cl_status cl_sweep_expand(cl_sweep *sw, cl_error *err);

/* One more job of sw (sw->dir, ->problem, ->clothode and the axes set):
 * `integrator` and value[a] for each axis a (NULL: unset), added to the
 * axes' values; its id and command as cl_sweep_expand makes them.
 * CL_EINVAL when it is a job sw has already. */
cl_status cl_sweep_add_job(cl_sweep *sw, const char *integrator,
                           const char *const *value, cl_error *err);

/* The job's assignments "key=value", sorted, joined by '\n' into buf
 * (integrator first as "integrator=NAME"); the text its id hashes. */
void cl_sweep_canonical(const cl_sweep *sw, const cl_sweep_job *j, char *buf,
                        size_t len);

/* cl_sweep_canonical on one line (the assignments separated by spaces),
 * for messages. */
void cl_sweep_describe(const cl_sweep *sw, const cl_sweep_job *j, char *buf,
                       size_t len);

#define CL_SWEEP_SET_LEN 512

/* The --set assignments job j passes to `clothode run`, in its command's
 * order: "run.frames=0" unless an axis sets run.frames (no frames unless
 * the sweep asks for them), then "KEY=VALUE" of every axis the job has;
 * their number, at most CL_SWEEP_MAX_AXES + 1. */
int cl_sweep_job_sets(const cl_sweep *sw, const cl_sweep_job *j,
                      char set[][CL_SWEEP_SET_LEN]);

/* s quoted for a POSIX shell where it needs it, into buf; returns the
 * length it needed (>= len: truncated). */
size_t cl_sweep_quote(const char *s, char *buf, size_t len);

/* Write DIR/jobs.txt (one command a line, in job order) and DIR/sweep.json
 * (the manifest: problem, binary, axes, every job with id, integrator,
 * values, reference and command). */
cl_status cl_sweep_write(const cl_sweep *sw, cl_error *err);

/* Read the manifest DIR/sweep.json back into sw. */
cl_status cl_sweep_load(const char *dir, cl_sweep *sw, cl_error *err);

void cl_sweep_free(cl_sweep *sw);

/* Free the strings v[0 .. n) and the array v. */
void cl_sweep_strings_free(char **v, int n);

/* Index of the job with id, or -1. */
int cl_sweep_find(const cl_sweep *sw, const char *id);

/* ---- one job's outcome (analysis/sweep_outcome.c) ---------------------- */

typedef enum {
    CL_SWEEP_MISSING = 0, /* never ran, or no exit status recorded */
    CL_SWEEP_COMPLETE,    /* exit status 0 and its statistics written */
    CL_SWEEP_FAILED       /* non-zero exit status, or killed by a signal */
} cl_sweep_state;

#define CL_SWEEP_NSTAT 13

/* The names of the statistics columns, in stats.csv's order. */
extern const char *const cl_sweep_stat_names[CL_SWEEP_NSTAT];

typedef struct {
    cl_sweep_state state;
    int exitval;          /* the exit status, or -1 */
    int signal;           /* the signal that ended it, or 0 */
    char exit_class[32];  /* ok, error, usage, signal-N, exit-N, missing */
    double t_reached;     /* last time in series.csv (NAN: none) */
    double stat[CL_SWEEP_NSTAT]; /* NAN where absent ("NA") */
    double err_x, err_v;  /* against the reference's final state (NAN) */
    char message[256];    /* the first line of its stderr, or "" */
    char problem_sha256[65]; /* of the problem file the run read (its
                              * run.json), or "" */
    char inputs_sha256[65];  /* of the files the problem named (meshes):
                              * the SHA-256 of run.json's "inputs" lines
                              * "key sha256", "none" for a problem naming
                              * none, "" when not recorded */
} cl_sweep_outcome;

/* The digest in inputs_sha256, made from the files' lines "key sha256"
 * (key as run.json's: "cloth.mesh", "obstacle.NAME.file") added in the
 * order cl_config_input_files visits them (the configuration's); "none"
 * when none was added. */
typedef struct {
    char text[4096];
    size_t used;
} cl_sweep_inputs;

void cl_sweep_inputs_add(cl_sweep_inputs *in, const char *key,
                         const char *sha256);
void cl_sweep_inputs_digest(const cl_sweep_inputs *in, char hex[65]);

/* Everything known of job k: its exit status (DIR/jobs/ID/exit, which
 * the job's command writes as its last step), its statistics
 * (stats.csv), how far it got (series.csv) and the first line of its
 * messages (stderr).  The one place that knows a job directory's files. */
void cl_sweep_outcome_read(const cl_sweep *sw, int k, cl_sweep_outcome *o);

/* err_x, err_v of job k against its reference (both complete): the
 * largest distance of a particle's position (velocity) in final.csv. */
void cl_sweep_outcome_error(const cl_sweep *sw, int k, cl_sweep_outcome *o);

/* ---- the collected table (analysis/sweep_collect.c) -------------------- */

typedef struct {
    int complete, failed, missing;
} cl_sweep_counts;

/* The outcome of every job into out[njob] (errors included). */
void cl_sweep_outcomes(const cl_sweep *sw, cl_sweep_outcome *out,
                       cl_sweep_counts *c);

/* The table: a header, then a row per job in job order:
 * id,role,integrator,<axis keys>,status,exit,t_reached,<stats>,err_x,err_v,
 * message */
void cl_sweep_write_table(FILE *fp, const cl_sweep *sw,
                          const cl_sweep_outcome *out);

CL_END_DECLS

#endif
