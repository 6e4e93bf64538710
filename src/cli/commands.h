/* The clothode subcommands; each is `int main`-like. */
#ifndef CL_COMMANDS_H
#define CL_COMMANDS_H

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

int cl_cmd_run(int argc, char **argv);

/* The checks `clothode run PROBLEM --integrator INTEGRATOR --set S ...`
 * makes before any work (its options, the integrator's, the model built,
 * no key unused), without running: CL_OK, or the first refusal in err
 * (the plan of a sweep checks its jobs with it).  sets: "SECTION.KEY=V";
 * a file one of them names ([init] state, a mesh) must be given by its
 * absolute path, since a sweep's jobs run wherever 'sweep run' starts. */
cl_status cl_cmd_run_check(const char *problem, const char *integrator,
                           const char *const *sets, int nset, cl_error *err);
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

CL_END_DECLS

#endif
