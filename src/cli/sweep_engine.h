/* The engines that run a sweep's jobs (README "Sweeps"): GNU parallel on
 * this machine or over ssh, and Slurm job arrays.  They are invoked, not
 * imitated: clothode writes the job list (and for Slurm the array
 * script) and hands it over. */
#ifndef CL_CLI_SWEEP_ENGINE_H
#define CL_CLI_SWEEP_ENGINE_H

#include <stdbool.h>

#include "analysis/sweep.h"
#include "cli/options.h"
#include "core/decls.h"

CL_BEGIN_DECLS

enum { CL_SWEEP_LOCAL = 1u, CL_SWEEP_SSH = 2u, CL_SWEEP_SLURM = 4u };

typedef struct {
    cl_cli_args a;
    unsigned engine;          /* one CL_SWEEP_ bit */
    long jobs;                /* GNU parallel's --jobs (0: one per core) */
    bool resume;
    const char *sshloginfile; /* --engine ssh */
    long chunk, throttle;     /* Slurm: jobs per array task, %K (0: none) */
    long time_min, mem_mb;    /* Slurm requests (0: from a pilot run) */
    bool wait;                /* Slurm: sbatch --wait */
} cl_sweep_run_args;

/* Run the commands of the file `list` (DIR/jobs.txt, or the pending ones)
 * with GNU parallel, its joblog DIR/joblog started afresh or appended to,
 * SIGINT and SIGTERM passed on to it.  0 when it has run every job (failed
 * ones included: collect reports them); 1 with a message when it could
 * not start or was stopped. */
int cl_sweep_parallel(const cl_sweep *sw, const cl_sweep_run_args *r,
                      const char *list, bool append);

/* Submit jobs todo[0..n) as a Slurm array (sbatch), time and memory from
 * r or estimated from a pilot run of the first of them here; the array's
 * id is kept in DIR/slurm/job.  Returns the exit status; *ran counts the
 * first of todo that were run (the pilots) or queued (all, once sbatch
 * has queued the array). */
int cl_sweep_slurm(const cl_sweep *sw, const cl_sweep_run_args *r,
                   const int *todo, int n, int *ran);

/* CL_OK unless the array job a 'sweep run' of this sweep submitted
 * (DIR/slurm/job) still has tasks queued or running, as squeue says:
 * CL_EINVAL then, naming it, and CL_EIO when squeue cannot tell. */
cl_status cl_sweep_slurm_idle(const cl_sweep *sw, cl_error *err);

CL_END_DECLS

#endif
