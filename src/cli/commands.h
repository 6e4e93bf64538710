/* The clothode subcommands; each is `int main`-like. */
#ifndef CL_COMMANDS_H
#define CL_COMMANDS_H

int cl_cmd_run(int argc, char **argv);
int cl_cmd_eval(int argc, char **argv);
int cl_cmd_counts(int argc, char **argv);
int cl_cmd_list(int argc, char **argv);
int cl_cmd_convergence(int argc, char **argv);
int cl_cmd_workprecision(int argc, char **argv);
int cl_cmd_stability(int argc, char **argv);
int cl_cmd_spectrum(int argc, char **argv);
int cl_cmd_energy(int argc, char **argv);
int cl_cmd_asinc(int argc, char **argv);
int cl_cmd_contact(int argc, char **argv);
int cl_cmd_replay(int argc, char **argv);
int cl_cmd_sweep(int argc, char **argv);
int cl_cmd_damping(int argc, char **argv);
int cl_cmd_budget(int argc, char **argv);

#endif
