/* clothode: particle cloth as a stiff ODE, integrators side by side.
 * One program, subcommands (README "Using it", docs/clothode.1). */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"

static const cl_command commands[] = {
    {"run", cl_cmd_run, "integrate a problem, write series, frames, stats"},
    {"stability", cl_cmd_stability,
     "largest stable step of fixed-step integrators"},
    {"energy", cl_cmd_energy, "energy balance of integrators over a run"},
    {"spectrum", cl_cmd_spectrum,
     "eigenvalues at a state and the step limits they predict"},
    {"convergence", cl_cmd_convergence,
     "observed orders against a tight reference"},
    {"workprecision", cl_cmd_workprecision,
     "error against CPU time, the fastest method per accuracy"},
    {"eval", cl_cmd_eval, "forces, energies and Jacobians at a given state"},
    {"asinc", cl_cmd_asinc,
     "the exact inverse sinc beside Jiao's polynomial"},
    {"counts", cl_cmd_counts, "connection counts beside Jiao's formulas"},
    {"list", cl_cmd_list, "problems, integrators and force terms"},
    {"sweep", cl_cmd_sweep,
     "parameter sweeps: plan, run (GNU parallel, ssh, Slurm), collect"},
};

static int usage(FILE *fp)
{
    fprintf(fp, "usage: clothode COMMAND [options]   (COMMAND --help for "
                "more)\ncommands:\n");
    for (size_t k = 0; k < sizeof commands / sizeof *commands; k++)
        fprintf(fp, "  %-13s %s\n", commands[k].name, commands[k].summary);
    return fp == stdout ? 0 : 2;
}

int main(int argc, char **argv)
{
    if (argc < 2)
        return usage(stderr);
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") ||
        !strcmp(argv[1], "help"))
        return usage(stdout);
    for (size_t k = 0; k < sizeof commands / sizeof *commands; k++)
        if (!strcmp(argv[1], commands[k].name))
            return commands[k].main(argc - 1, argv + 1);
    fprintf(stderr, "clothode: unknown command '%s'\n", argv[1]);
    return usage(stderr);
}
