/* Shared pieces of the clothode subcommands. */
#ifndef CL_CLI_H
#define CL_CLI_H

#include <stdbool.h>
#include <stdio.h>

#include "cli/options.h"
#include "core/decls.h"
#include "core/exit.h"
#include "integrators/integrator.h"
#include "io/config.h"
#include "system/model.h"

CL_BEGIN_DECLS

typedef struct {
    const char *name;
    int (*main)(int argc, char **argv);
    const char *summary;
} cl_command;

/* The exit status of a failure of class `code`. */
int cl_cli_exit_status(cl_status code);

/* Print "clothode: message" to stderr and return the exit status of its
 * class (cl_cli_exit_status); the form every subcommand uses to fail. */
int cl_cli_fail(const cl_error *err);
int cl_cli_usage_error(const char *cmd, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* A problem given as a path or as a bare name (NAME -> problems/NAME.ini,
 * looked up under $CLOTHODE_PROBLEMS if set). */
const char *cl_cli_problem_path(const char *arg, char *buf, size_t len);

/* Where problems are looked up by name: $CLOTHODE_PROBLEMS, else
 * ./problems if it is a directory, else the installed
 * PREFIX/share/clothode/problems beside PREFIX/bin/clothode, else
 * "problems". */
const char *cl_cli_problems_dir(void);

/* What a subcommand on one problem does once the model exists: the
 * problem's path and configuration, the output directory (--out or
 * out/PROBLEM), --quiet, and the command's own context. */
typedef struct {
    const char *problem;
    cl_config *cfg;
    const char *outdir;
    bool quiet;
} cl_cli_job;

typedef cl_status (*cl_cli_check_fn)(cl_config *cfg, void *settings,
                                     cl_error *err);
typedef cl_status (*cl_cli_work_fn)(cl_model *m, const cl_cli_job *job,
                                    void *settings, cl_error *err);

/* cl_model_create with the data size capped at what the machine, or the
 * job's memory cgroup, can give (core/meminfo.h): a model too large for it
 * is refused as out of memory (its allocations fail, each one checked)
 * instead of ending in the kernel's OOM kill.  The cap is lifted once the
 * model exists; the integrators' memory guard (integrators/memguard.h)
 * takes over from there. */
cl_status cl_cli_model_create(cl_config *cfg, cl_model **m, cl_error *err);

/* The checks of cl_cli_problem_main on a loaded problem (its assignments
 * applied): read the table's keys into settings, check() them, make the
 * model into *m, refuse keys nobody read. */
cl_status cl_cli_problem_ready(cl_config *cfg, const cl_cli_table *t,
                               void *settings, cl_cli_check_fn check,
                               cl_model **m, cl_error *err);

/* main() of such a subcommand: parse argv by the table t into settings
 * (a cl_cli_args first), load the problem with its assignments, read the
 * table's keys, check() the values against each other (NULL: nothing to
 * check), make the model, refuse keys nobody read, then work().  Returns
 * the exit status: 0, that of the failure's class with its one-line
 * message (cl_cli_fail), 2 for a usage error. */
int cl_cli_problem_main(int argc, char **argv, const cl_cli_table *t,
                        void *settings, cl_cli_check_fn check,
                        cl_cli_work_fn work);

/* For the commands that do not integrate (spectrum, eval, named by cmd):
 * the [run] keys of a problem file are theirs to ignore; one set on the
 * command line is refused (cl_cli_not_read). */
cl_status cl_cli_ignore_run(cl_config *cfg, const char *cmd, cl_error *err);

/* main() of a subcommand without a problem: parse argv by t, read the
 * keys of the command line alone into settings (a refused value is a usage
 * error), then return work(settings), the exit status.  A positional
 * argument (t->npos 1) is in the settings' cl_cli_args arg. */
int cl_cli_args_main(int argc, char **argv, const cl_cli_table *t,
                     void *settings, int (*work)(void *settings));

/* Whether DIR/NAME can receive an output, checked before any work: DIR
 * absent or a directory, DIR/NAME absent or a regular file (CL_EIO naming
 * what is there otherwise, io/atomic.h), and DIR made (if absent),
 * held by this process (cli/outdir.h, cl_cli_outdir_hold) and writable
 * (CL_EIO with the system's reason otherwise). */
cl_status cl_cli_check_output(const char *dir, const char *name,
                              cl_error *err);

/* Write DIR/NAME atomically (DIR made first): write(fp, ctx, n) puts the
 * rows of the first n results of ctx. */
typedef void (*cl_cli_rows_fn)(FILE *fp, const void *ctx, int n);
cl_status cl_cli_write_csv(const char *dir, const char *name,
                           cl_cli_rows_fn write, const void *ctx, int n,
                           cl_error *err);

/* Apply the assignments of the command line, each reported as its option
 * (--dt) or as --set. */
cl_status cl_cli_apply(cl_config *cfg, const cl_cli_sets *sets,
                       cl_error *err);

/* Load a problem file and apply the assignments. */
cl_status cl_cli_load(cl_config *cfg, const char *problem,
                      const cl_cli_sets *sets, cl_error *err);

/* Directory where a problem's outputs go by default: out/NAME for
 * problems/NAME.ini, out/NAME-HASH for NAME.ini elsewhere (HASH: 8 hex
 * digits of its absolute path), so that two problems never share it. */
void cl_cli_default_out(const char *problem, char *buf, size_t len);

/* The [run] keys of the commands that run integrators (run, stability,
 * convergence, energy): cl_cli_run_rows, a group of their tables. */
typedef struct {
    cl_integrator_opts io; /* dt, rtol, atol, ..., linsol, max_order */
    double t_end;
    double max_stretch;
    long threads, samples, frames; /* run's outputs (the studies do */
    unsigned format;               /* not read them); format: */
    double budget_wall;            /* CL_CLI_FMT_ bits; run's budgets, */
    long budget_steps;             /* 0: none (not read either) */
} cl_cli_run;
extern const cl_cli_opt cl_cli_run_rows[];

/* The bits of [run] format, in the order of its names csv, vtk, obj. */
enum { CL_CLI_FMT_CSV = 1u, CL_CLI_FMT_VTK = 2u, CL_CLI_FMT_OBJ = 4u };

/* The options of cl_cli_run_rows that only run reads (a group's unread
 * list in the studies). */
#define CL_CLI_RUN_OUTPUTS \
    "threads samples frames format max-wall max-steps"

/* One entry of [run] integrator, a list "NAME[:LINSOL],...": the
 * integrator, its options (a LINSOL given here overrides [run] linsol)
 * and how it is labelled in tables. */
typedef struct {
    const cl_integrator_type *type;
    cl_integrator_opts io;  /* io.linsol may point into linsol */
    char linsol[32];
    char label[64];         /* the entry as written */
} cl_cli_method;

#define CL_CLI_MAX_METHODS 32

/* The value of a CL_CLI_METHODS row (at most row->hi entries). */
typedef struct {
    int n;
    cl_cli_method m[CL_CLI_MAX_METHODS];
} cl_cli_methods;

cl_status cl_cli_methods_read(cl_config *cfg, const cl_cli_opt *row,
                              cl_cli_methods *ms, cl_error *err);

/* How a command uses [run] dt: the first step of every integrator (run),
 * the step of the fixed-step ones while the adaptive ones choose their
 * own (convergence, energy), or not at all (stability). */
typedef enum { CL_CLI_DT_ALL, CL_CLI_DT_FIXED, CL_CLI_DT_NONE } cl_cli_dt_use;

/* Give every method the options io and check them against what its
 * integrator takes.  An option of [run] (a linear solver, PETSc options,
 * an order cap, substeps, iterations, a table, Rayleigh damping) serves
 * the methods of the list that take it and is cleared for the others; it
 * is an error naming the key only when none takes it.  So is a linear
 * solver of an entry NAME:LINSOL whose integrator has no choice of one,
 * and a fixed-step method without dt > 0 (unless CL_CLI_DT_NONE).
 * newton_maxit and rho_inf, which problem files set for their own
 * integrator, are left to the integrators that read them. */
cl_status cl_cli_methods_check(cl_config *cfg, cl_cli_methods *ms,
                               const cl_integrator_opts *io, cl_cli_dt_use dt,
                               cl_error *err);

/* Refuse a method whose integrator chooses its own steps: command `cmd`
 * (stability, contact) takes fixed-step integrators only. */
cl_status cl_cli_methods_fixed(cl_config *cfg, const cl_cli_methods *ms,
                               const char *cmd, cl_error *err);

/* Create and free every method on the model's initial state, so that an
 * option it refuses (an unknown linear solver, a cloth too large for a
 * dense method) stops a study before it starts. */
cl_status cl_cli_methods_try(cl_model *model, const cl_cli_methods *ms,
                             cl_error *err);

/* A study's span: its runs go from the model's start time ([init] time,
 * read and checked as the model does) to t_end, so the span is t_end -
 * time; CL_EINVAL when that time is malformed or the span not > 0. */
cl_status cl_cli_span(cl_config *cfg, double t_end, double *span,
                      cl_error *err);

/* A search's largest step: as given ([sec] dt_max), else the span / 100
 * (the option's own default saw t_end before the span was known). */
double cl_cli_dt_max(const cl_config *cfg, const char *sec, double given,
                     double span);

/* The time of the state a command linearises at: [sec] t (--t) when
 * given, else the model's start time ([init] time, 0 by default). */
double cl_cli_state_time(const cl_config *cfg, const char *sec,
                         const cl_model *m, double t);

/* The free state x, v of m read from a state file (final.csv's format),
 * or its initial state when path is "". */
cl_status cl_cli_free_state(cl_model *m, const char *path, double *x,
                            double *v, cl_error *err);

CL_END_DECLS

#endif
