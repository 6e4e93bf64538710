/* The exit status of each class of failure of the command line (README
 * "Exit status", docs/clothode.1, `clothode --help`): set by the command
 * line, read back by the sweeps' collection of many runs. */
#ifndef CL_EXIT_H
#define CL_EXIT_H

#include "core/decls.h"

CL_BEGIN_DECLS

enum {
    CL_EXIT_OK = 0,
    CL_EXIT_OTHER = 1,       /* out of memory; replay: outputs differ */
    CL_EXIT_INPUT = 2,       /* bad input: usage, options, problem files */
    CL_EXIT_SOLVER = 3,      /* a solver failed */
    CL_EXIT_BLOWUP = 4,      /* the state blew up */
    CL_EXIT_BUDGET = 5,      /* --max-wall or --max-steps reached */
    CL_EXIT_INTERRUPTED = 6, /* SIGINT or SIGTERM */
    CL_EXIT_IO = 7,          /* a file or stdout could not be written */
    CL_EXIT_CLASSES
};

/* A short name of exit status s: "ok", "other", "input", "solver",
 * "blow-up", "budget", "interrupted", "io"; NULL beyond them. */
const char *cl_exit_name(int s);

CL_END_DECLS

#endif
