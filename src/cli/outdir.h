/* The output directory of a run: nothing of an earlier run is left beside
 * a new one (README "Provenance").  Before `run` writes anything, the
 * files an earlier run wrote there (listed in its run.json, or named as a
 * run names its outputs: series.csv, final.csv, last-good.csv,
 * stats.csv, config.ini, run.json, frame_NNNNN.vtk/.obj,
 * obstacles_NNNNN.vtk/.obj, and their temporaries NAME.tmp.XXXXXX) are
 * removed; the tables of the studies (stability.csv, ...) stay.  A
 * directory holding any other file and no run.json of clothode's is not a
 * clothode output and is refused. */
#ifndef CL_CLI_OUTDIR_H
#define CL_CLI_OUTDIR_H

#include <stdbool.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

/* Whether `name` (a file name without directory) is one a run writes. */
bool cl_cli_run_output(const char *name);

/* ... or one a run or another command writes into its output directory
 * (a study's table: stability.csv, damping.csv, ...), which may share
 * out/PROBLEM with a run. */
bool cl_cli_clothode_output(const char *name);

/* Hold the existing directory dir for this process until it ends (an
 * exclusive flock on it), so that no other clothode writes into it
 * meanwhile (two runs into one --out would clear and mix each other's
 * files): CL_EIO naming it when another process holds it; CL_OK when it
 * cannot be opened (the callers report that) or its file system has no
 * flock.  A process holds one directory: holding another releases it. */
cl_status cl_cli_outdir_hold(const char *dir, cl_error *err);

/* The refusals of cl_cli_outdir_prepare without its clearing: CL_OK when
 * prepare would clear dir (or create it); an existing dir is held
 * (cl_cli_outdir_hold). */
cl_status cl_cli_outdir_check(const char *dir, cl_error *err);

/* Clear dir of an earlier run's files, or refuse it (CL_EIO naming the
 * directory and a file that is not clothode's, or an output name taken by
 * something other than a regular file, or a directory another clothode
 * holds), then create it if missing; held either way.  Nothing is removed
 * when it is refused. */
cl_status cl_cli_outdir_prepare(const char *dir, cl_error *err);

CL_END_DECLS

#endif
