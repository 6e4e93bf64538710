/* Shared pieces of the clothode subcommands. */
#ifndef CL_CLI_H
#define CL_CLI_H

#include <getopt.h>
#include <stdbool.h>
#include <stdio.h>

#include "integrators/integrator.h"
#include "io/config.h"
#include "system/model.h"

typedef struct {
    const char *name;
    int (*main)(int argc, char **argv);
    const char *summary;
} cl_command;

/* Print "clothode: message" to stderr and return the exit status 1; the
 * form every subcommand uses to fail. */
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

/* "section.key=value" assignments collected from the command line. */
typedef struct {
    char **v;
    const char **label; /* the option each came from, NULL for --set */
    int n;
} cl_cli_sets;

/* Append "key=val" (an option standing for a key, reported in messages as
 * `label`), or val itself when key is NULL (--set); -1 if out of memory. */
int cl_cli_sets_add(cl_cli_sets *s, const char *key, const char *val,
                    const char *label);
void cl_cli_sets_free(cl_cli_sets *s);

/* The options of a subcommand that takes one PROBLEM (run, convergence). */
typedef struct {
    cl_cli_sets sets;
    const char *out;   /* --out DIR, or NULL */
    bool quiet;        /* --quiet */
} cl_cli_args;

/* Its option table: getopt_long's `opts`, where 'o' is --out, 'q' --quiet,
 * 's' --set and 'h' --help, and every other option c stands for the key
 * key[c] ("run.dt"), named label[c] ("--dt") in messages. */
typedef struct {
    const char *cmd;
    const char *help;
    const struct option *opts;
    const char *const *key;    /* 128 entries */
    const char *const *label;  /* 128 entries */
} cl_cli_spec;

/* The options every such subcommand ends with: --out, --set, --quiet and
 * --help as getopt_long entries (closing the table), and the help lines of
 * --out and --set. */
#define CL_CLI_OPTS_TAIL                                                     \
    {"out", required_argument, 0, 'o'}, {"set", required_argument, 0, 's'}, \
    {"quiet", no_argument, 0, 'q'}, {"help", no_argument, 0, 'h'},           \
    {0, 0, 0, 0}
#define CL_CLI_HELP_OUT_SET                                                  \
    "  --out DIR          output directory (default out/PROBLEM)\n"          \
    "  --set SEC.KEY=VAL  override any problem key (repeatable)\n"

/* Parse argv: the index of PROBLEM; -2 after --help (printed), -1 after a
 * usage error (printed).  a->sets must be freed by the caller. */
int cl_cli_parse(int argc, char **argv, const cl_cli_spec *spec,
                 cl_cli_args *a);

/* What a subcommand on one problem does once the model exists: the
 * problem's path and configuration, the output directory (--out or
 * out/PROBLEM), --quiet, and the command's own context. */
typedef struct {
    const char *problem;
    cl_config *cfg;
    const char *outdir;
    bool quiet;
} cl_cli_job;

typedef cl_status (*cl_cli_setup_fn)(cl_config *cfg, void *ctx,
                                     cl_error *err);
typedef cl_status (*cl_cli_work_fn)(cl_model *m, const cl_cli_job *job,
                                    void *ctx, cl_error *err);

/* main() of such a subcommand: parse argv by spec, load the problem with
 * its assignments, setup() reads the command's keys, the model is made,
 * keys nobody read are refused, then work().  Returns the exit status: 0,
 * 1 with the one-line message of a failure, 2 for a usage error. */
int cl_cli_problem_main(int argc, char **argv, const cl_cli_spec *spec,
                        cl_cli_setup_fn setup, cl_cli_work_fn work,
                        void *ctx);

/* Write DIR/NAME atomically (DIR made first): write(fp, ctx, n) puts the
 * rows of the first n results of ctx. */
typedef void (*cl_cli_rows_fn)(FILE *fp, const void *ctx, int n);
cl_status cl_cli_write_csv(const char *dir, const char *name,
                           cl_cli_rows_fn write, const void *ctx, int n,
                           cl_error *err);

/* Load a problem file and apply the assignments. */
cl_status cl_cli_load(cl_config *cfg, const char *problem,
                      const cl_cli_sets *sets, cl_error *err);

/* Directory where a problem's outputs go by default: out/BASENAME. */
void cl_cli_default_out(const char *problem, char *buf, size_t len);

/* The options of integrator `type` from [run] (dt, rtol, atol, max_steps,
 * newton_tol, newton_maxit, lin_tol, lin_maxit, verlet_damping, max_order,
 * linsol), checked against what the integrator takes: a linear solver or
 * an order cap it has no choice of, or (need_dt) a fixed-step method
 * without dt > 0, is an error naming the key (cli/runopts.c). */
cl_status cl_cli_integrator_opts(cl_config *cfg,
                                 const cl_integrator_type *type,
                                 bool need_dt, cl_integrator_opts *io,
                                 cl_error *err);

/* One entry of [run] integrator as a list "NAME[:LINSOL],...": the
 * integrator, its options (cl_cli_integrator_opts; a LINSOL given here
 * overrides [run] linsol) and how it is labelled in tables. */
typedef struct {
    const cl_integrator_type *type;
    cl_integrator_opts io;  /* io.linsol may point into linsol */
    char linsol[32];
    char label[64];         /* the entry as written */
} cl_cli_method;

/* The entries of [run] integrator (default cvode-bdf), at most max. */
cl_status cl_cli_methods(cl_config *cfg, bool need_dt, int max,
                         cl_cli_method *m, int *n, cl_error *err);

/* Create and free every method on the model's initial state, so that an
 * option it refuses (an unknown linear solver, a cloth too large for a
 * dense method) stops a study before it starts. */
cl_status cl_cli_methods_try(cl_model *model, const cl_cli_method *m, int n,
                             cl_error *err);

/* Progress bar on stderr (only when stderr is a terminal). */
void cl_cli_progress(void *ctx, double fraction);

#endif
