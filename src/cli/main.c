/* clothode: particle cloth as a stiff ODE, integrators side by side.
 * One program, subcommands (README "Using it", docs/clothode.1). */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/version.h"
#include "core/stop.h"
#include "linalg/petscenv.h"

static const cl_command commands[] = {
    {"run", cl_cmd_run, "integrate a problem, write series, frames, stats"},
    {"stability", cl_cmd_stability,
     "largest stable step of fixed-step integrators"},
    {"energy", cl_cmd_energy, "energy balance of integrators over a run"},
    {"spectrum", cl_cmd_spectrum,
     "eigenvalues at a state and the step limits they predict"},
    {"contact", cl_cmd_contact,
     "contact responses against the step, explicit limit against k"},
    {"convergence", cl_cmd_convergence,
     "observed orders against a tight reference"},
    {"workprecision", cl_cmd_workprecision,
     "error against CPU time, the fastest method per accuracy"},
    {"budget", cl_cmd_budget,
     "substeps against iterations at an equal budget per step"},
    {"eval", cl_cmd_eval, "forces, energies and Jacobians at a given state"},
    {"asinc", cl_cmd_asinc,
     "the exact inverse sinc beside Jiao's polynomial"},
    {"counts", cl_cmd_counts, "connection counts beside Jiao's formulas"},
    {"list", cl_cmd_list, "problems, integrators, linear solvers, force "
                          "terms and obstacle shapes"},
    {"replay", cl_cmd_replay,
     "rerun a run from its run.json, check every output is identical"},
    {"sweep", cl_cmd_sweep,
     "parameter sweeps: plan, run (GNU parallel, ssh, Slurm), collect"},
    {"damping", cl_cmd_damping,
     "numerical damping per step against w h, beside the theory"},
};

static int usage(FILE *fp)
{
    fprintf(fp, "usage: clothode COMMAND [options]   (COMMAND --help for "
                "more)\n       clothode --version\ncommands:\n");
    for (size_t k = 0; k < sizeof commands / sizeof *commands; k++)
        fprintf(fp, "  %-13s %s\n", commands[k].name, commands[k].summary);
    fprintf(fp, "exit status: 0 success, 1 out of memory (replay: outputs "
                "differ), 2 bad input,\n  3 solver failure, 4 blow-up, 5 "
                "budget (--max-wall, --max-steps), 6 interrupted\n  (SIGINT, "
                "SIGTERM), 7 I/O error (a file or stdout)\n");
    return fp == stdout ? 0 : CL_EXIT_INPUT;
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2)
        return usage(stderr);
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") ||
        !strcmp(argv[1], "help"))
        return usage(stdout);
    if (!strcmp(argv[1], "--version"))
        return cl_cli_version(stdout);
    for (size_t k = 0; k < sizeof commands / sizeof *commands; k++)
        if (!strcmp(argv[1], commands[k].name))
            return commands[k].main(argc - 1, argv + 1);
    fprintf(stderr, "clothode: unknown command '%s'\n", argv[1]);
    return usage(stderr);
}

/* Everything written to stdout must have reached it: a failed write (a
 * full disk, a closed pipe) is an I/O error. */
static int close_stdout(int status)
{
    int bad = ferror(stdout);
    int e = errno;
    if (fflush(stdout) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    if (fclose(stdout) != 0 && !bad) {
        bad = 1;
        e = errno;
    }
    if (!bad || status) /* a failed command has said why */
        return status;
    fprintf(stderr, "clothode: cannot write standard output: %s\n",
            strerror(e ? e : EIO));
    return CL_EXIT_IO;
}

int main(int argc, char **argv)
{
    cl_stop_install();
    /* a write past a file-size limit (ulimit -f) then fails with EFBIG,
     * an I/O error with its message (exit status 7), instead of SIGXFSZ
     * ending the program with a temporary file behind */
    signal(SIGXFSZ, SIG_IGN);
    int status = dispatch(argc, argv);
    if (status == 0 && cl_stop_interrupted()) {
        /* a command that ran to its end all the same (counts, asinc,
         * sweep plan) was still asked to stop: the caller sees that */
        fprintf(stderr, "clothode: interrupted by %s (after the command "
                        "had done its work)\n",
                cl_stop_signal_name(cl_stop_requested()));
        status = CL_EXIT_INTERRUPTED;
    }
    cl_petsc_stop(); /* its reports at the end, into stdout */
    return close_stdout(status);
}
