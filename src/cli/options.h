/* The option table of a subcommand: one row per option or problem key,
 * from which the command line is parsed (getopt_long), the values are read
 * and checked (through the problem's configuration, io/config.h) and
 * --help is written.
 *
 * A row with a key (sec.key) stands for that key of the problem: its
 * option --name VAL becomes the assignment "sec.key=VAL", reported as
 * "--name" in messages, so the saved config.ini holds what the command
 * line gave; cl_cli_read then reads every keyed row, given or not, with
 * its default and allowed range.  A row without a key is an option of the
 * command line alone (--out, --quiet, --csv), set while parsing.
 *
 * Every settings struct a table fills starts with a cl_cli_args. */
#ifndef CL_CLI_OPTIONS_H
#define CL_CLI_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "core/decls.h"
#include "io/config.h"

CL_BEGIN_DECLS

typedef enum {
    CL_CLI_END = 0, /* closes a table */
    CL_CLI_DOUBLE,  /* double, in [lo, hi] */
    CL_CLI_LONG,    /* long, in [lo, hi] */
    CL_CLI_INT,     /* int, in [lo, hi] */
    CL_CLI_STRING,  /* const char *: a key's text, or the option's argument */
    CL_CLI_NAMES,   /* unsigned: bit k for names[k] in a list of them */
    CL_CLI_METHODS, /* cl_cli_methods: NAME[:LINSOL],... (cli/runopts.c) */
    CL_CLI_FLAG,    /* bool, true when the option is given */
    CL_CLI_SET,     /* --set SEC.KEY=VAL, any key of the problem */
    CL_CLI_HELP,    /* --help */
    CL_CLI_GROUP    /* the rows of `group`, their fields relative to field */
} cl_cli_type;

typedef struct cl_cli_opt cl_cli_opt;

/* A default or upper bound that depends on values read before (rows
 * above): called with the settings and the row's def and hi to adjust. */
typedef void (*cl_cli_bounds_fn)(const void *settings, double *def,
                                 double *hi);

struct cl_cli_opt {
    const char *name;      /* --name, or NULL: a key without an option */
    const char *arg;       /* its value in --help ("H"); NULL for a flag */
    cl_cli_type type;
    const char *sec, *key; /* the problem key, or NULL */
    double def, lo, hi;    /* numbers; for METHODS hi = most entries */
    const char *sdef;      /* default of STRING, NAMES and METHODS */
    const char *const *names; /* NAMES: the allowed names, NULL-ended */
    const char *help;      /* one sentence, without the default */
    size_t field;          /* offset of the value in the settings */
    bool required;         /* the option must be given */
    cl_cli_bounds_fn bounds;
    const cl_cli_opt *group; /* GROUP: the rows included */
    const char *hide;      /* GROUP: options of it not offered, "a b" */
    const char *unread;    /* GROUP: options whose keys the command does
                            * not read at all, "a b": not offered, not in
                            * --help, ignored in a file, refused from
                            * --set */
};

typedef struct {
    const char *cmd;       /* "run" */
    const char *synopsis;  /* "PROBLEM [options]" */
    const char *about;     /* what the command does, before the options */
    const char *notes;     /* after the options, or NULL */
    int npos;              /* positional arguments: 1 (PROBLEM) or 0 */
    const char *pos;       /* the positional argument's name in messages,
                            * NULL for PROBLEM */
    const cl_cli_opt *rows;
} cl_cli_table;

/* "section.key=value" assignments collected from the command line. */
typedef struct {
    char **v;
    const char **label; /* the option each stands for ("dt" for --dt),
                         * NULL for --set */
    int n;
} cl_cli_sets;

/* Append "key=val" (an option standing for a key, reported in messages as
 * `label`: its name without the dashes), or val itself when key is NULL
 * (--set); -1 if out of memory. */
int cl_cli_sets_add(cl_cli_sets *s, const char *key, const char *val,
                    const char *label);
void cl_cli_sets_free(cl_cli_sets *s);

/* What every command line gives besides the keys' values. */
typedef struct {
    cl_cli_sets sets;  /* the assignments, in command-line order */
    const char *out;   /* --out DIR, or NULL */
    bool quiet;        /* --quiet */
    const char *arg;   /* the positional argument of a command without a
                        * problem (cl_cli_args_main), or NULL */
} cl_cli_args;

/* --set SEC.KEY=VAL and --help, rows of most tables. */
#define CL_CLI_SET_ROW                                                      \
    {.name = "set", .arg = "SEC.KEY=VAL", .type = CL_CLI_SET,              \
     .help = "override any problem key (repeatable)"}
#define CL_CLI_HELP_ROW                                                     \
    {.name = "help", .type = CL_CLI_HELP, .help = "this text"}

/* The rows every command on one PROBLEM ends with: --out, --set, --quiet
 * (help text `quiet_help`) and --help, for the settings type T. */
#define CL_CLI_TAIL(T, quiet_help)                                          \
    {.name = "out", .arg = "DIR", .type = CL_CLI_STRING,                   \
     .field = offsetof(T, a.out),                                          \
     .help = "output directory (default out/PROBLEM)"},                    \
    CL_CLI_SET_ROW,                                                        \
    {.name = "quiet", .type = CL_CLI_FLAG, .field = offsetof(T, a.quiet),  \
     .help = (quiet_help)},                                                \
    CL_CLI_HELP_ROW

/* Parse argv[1..] into settings (a cl_cli_args first): keyed options into
 * its sets, the others into their fields.  Returns the index of the first
 * positional argument; -2 after --help (printed on stdout), -1 after a
 * usage error (printed: the option, its value and what is allowed).  The
 * sets must be freed (cl_cli_sets_free) in every case. */
int cl_cli_parse(int argc, char **argv, const cl_cli_table *t,
                 void *settings);

/* Unless `mode` is on, refuse the first of the keyed rows `names` (a
 * NULL-terminated list of option names, rows of t's own) whose key is
 * set: "--NAME ([SEC] KEY) goes with WITH; without it, it would be
 * ignored" (CL_EINVAL): options of a command's other mode. */
cl_status cl_cli_refuse_unless(const cl_config *cfg, const cl_cli_table *t,
                               const char *const *names, bool mode,
                               const char *with, cl_error *err);

/* [sec] key, which command `cmd` does not read: ignored (counted as used)
 * when a problem file gives it, so that one file serves run and the
 * studies; CL_EINVAL when the command line set it, where it would change
 * nothing ("clothode CMD does not read it"). */
cl_status cl_cli_not_read(cl_config *cfg, const char *cmd, const char *sec,
                          const char *key, cl_error *err);

/* Read every keyed row from cfg into settings, in table order, each with
 * its default and range (a refused value: CL_EINVAL naming the option or
 * the file line, the key, the value and what is allowed). */
cl_status cl_cli_read(cl_config *cfg, const cl_cli_table *t, void *settings,
                      cl_error *err);

/* "a, b, c": the NULL-ended names, for messages; returns buf. */
const char *cl_cli_join(const char *const *names, char *buf, size_t len);

/* The --help text of the table. */
void cl_cli_help(const cl_cli_table *t, FILE *fp);

CL_END_DECLS

#endif
