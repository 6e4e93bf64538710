/* clothode run PROBLEM: integrate one problem and write its outputs. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/simulate.h"
#include "cli/cli.h"
#include "cli/commands.h"
#include "cli/manifest.h"
#include "cli/outdir.h"
#include "cli/progress.h"

typedef struct {
    cl_cli_args a;
    cl_cli_methods integrator; /* one */
    cl_cli_run run;
    cl_sim_opts so;
    int argc;                  /* the command line, for run.json */
    char **argv;
    bool force;
} run_setup;

static const cl_cli_opt run_rows[] = {
    {.name = "integrator", .arg = "NAME", .type = CL_CLI_METHODS,
     .sec = "run", .key = "integrator", .sdef = "cvode-bdf", .hi = 1,
     .field = offsetof(run_setup, integrator),
     .help = "integrator, or NAME:LINSOL (clothode list)"},
    {.type = CL_CLI_GROUP, .group = cl_cli_run_rows,
     .field = offsetof(run_setup, run)},
    {.name = "force", .type = CL_CLI_FLAG, .field = offsetof(run_setup, force),
     .help = "run even if the memory estimate of the Jacobian and its "
             "factors exceeds the available memory"},
    CL_CLI_TAIL(run_setup, "no summary on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table run_table = {
    .cmd = "run", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = run_rows,
    .about =
    "Integrate PROBLEM (a .ini file, or a name under problems/) and write\n"
    "series.csv, frames, final.csv, stats.csv, config.ini and run.json (its\n"
    "provenance) into the output directory, after removing the files of an\n"
    "earlier run there.  SIGINT, SIGTERM and --max-wall stop the run at\n"
    "once, --max-steps at the first output time after its N steps; the\n"
    "outputs up to the last output time are written as after a finished\n"
    "run (the steps since it are not: more --samples keep more); a run\n"
    "from that final.csv (--set init.state=FILE --set init.time=T, T the\n"
    "time reached, into another --out) goes on from there.  A run that\n"
    "fails (a blow-up, a solver failure, ...) after its first sample writes\n"
    "last-good.csv instead of final.csv: the state of its last good sample.\n",
    .notes =
    "exit status: 0 success, 2 bad input, 3 solver failure, 4 blow-up,\n"
    "5 budget, 6 interrupted, 7 I/O error (1 out of memory)\n"};

static cl_status check_run(cl_config *cfg, void *ctx, cl_error *err)
{
    run_setup *r = ctx;
    r->so.t_end = r->run.t_end;
    r->so.max_stretch = r->run.max_stretch;
    r->so.samples = r->run.samples;
    r->so.vtk = r->run.format & CL_CLI_FMT_VTK;
    r->so.obj = r->run.format & CL_CLI_FMT_OBJ;
    /* csv alone writes the series only: its frames are not output times */
    r->so.frames = r->so.vtk || r->so.obj ? r->run.frames : 0;
    /* frames asked for where the format was chosen (the command line,
     * or one file for both), not a file's frames under --format csv */
    bool asked = cl_config_set_by_command(cfg, "run", "frames") ||
                 (cl_config_peek(cfg, "run", "frames") &&
                  !cl_config_set_by_command(cfg, "run", "format"));
    if (r->run.frames > 0 && !r->so.frames && asked)
        return cl_config_refuse(cfg, "run", "frames", CL_EINVAL,
                                "no frame format to write them in: format "
                                "csv writes the series only; add vtk or obj, "
                                "or leave frames out", err);
    r->so.max_wall = r->run.budget_wall;
    r->so.max_steps = r->run.budget_steps;
    r->run.io.force = r->force;
    return cl_cli_methods_check(cfg, &r->integrator, &r->run.io,
                                CL_CLI_DT_ALL, err);
}

/* The closest non-neighbours at the end (forces/selfcontact.h). */
static void print_selfcontact(cl_model *m, const cl_sim_result *res)
{
    double d;
    if (!cl_model_selfcontact_closest(m, res->xfinal, &d))
        return;
    if (isinf(d))
        printf("self-contact no non-neighbours closer than the thickness "
               "at the end\n");
    else
        printf("self-contact closest non-neighbours %.6g m apart at the "
               "end\n", d);
}

static void print_summary(const char *problem, const run_setup *r,
                          cl_model *m, const cl_sim_result *res)
{
    const cl_cloth *c = cl_model_cloth(m);
    const cl_cli_method *im = &r->integrator.m[0];
    char shape[96];
    printf("problem      %s (%s, %zu free)\n", problem,
           cl_cloth_shape(c, shape, sizeof shape), c->nfree);
    printf("integrator   %s", im->type->name);
    if (cl_integrator_fixed(im->type, im->io.dt))
        printf(" (dt = %g)\n", im->io.dt);
    else
        printf(" (rtol = %g, atol = %g)\n", im->io.rtol, im->io.atol);
    printf("time         %.10g of %g s\n", res->t_reached, r->so.t_end);
    printf("energy       %.10g -> %.10g J (kinetic %.6g)\n", res->e0.total,
           res->e1.total, res->e1.kinetic);
    for (size_t k = 0; k < res->e1.nterm; k++)
        printf("  %-10s %.10g J\n", res->e1.name[k], res->e1.value[k]);
    printf("shape        max stretch d/L = %.6f, ", res->max_stretch);
    if (isnan(res->max_offplane))
        printf("max out-of-plane n/a (the rest mesh is not horizontal)\n");
    else
        printf("max out-of-plane %.6g m\n", res->max_offplane);
    if (cl_model_contact(m))
        printf("contact      worst penetration %.6g m at t = %.6g s\n",
               res->worst_penetration, res->worst_t);
    if (cl_model_contact(m) && cl_contact_barriers(cl_model_contact(m)))
        printf("barrier      min distance %.6g m at t = %.6g s\n",
               res->min_distance, res->min_distance_t);
    print_selfcontact(m, res);
    cl_stats_print(&res->stats, stdout, true);
    printf("output       %s (series.csv, %ld frame%s, %s%sstats.csv)\n",
           r->so.outdir, res->frames, res->frames == 1 ? "" : "s",
           res->state_file ? res->state_file : "",
           res->state_file ? ", " : "");
}

/* What run_work's first output needs: the directory cleared of an
 * earlier run and run.json begun, once the integrator has accepted the
 * problem (cl_sim_opts.before_output). */
typedef struct {
    run_setup *r;
    const cl_cli_job *job;
    cl_manifest mf;     /* its clocks from run_work's start */
    bool begun;
} run_output;

static cl_status begin_output(void *ctx, cl_error *err)
{
    run_output *o = ctx;
    cl_status rc = cl_cli_outdir_prepare(o->job->outdir, err);
    if (!rc)
        rc = cl_manifest_begin(&o->mf, o->job, o->r->argc, o->r->argv,
                               o->r->run.threads, err);
    o->begun = rc == CL_OK;
    return rc;
}

/* The first file the configuration read (cl_config_input_files) that
 * `match` accepts, into sec, key, path ("" when none). */
typedef struct {
    const cl_config *cfg;
    bool (*match)(const void *arg, const cl_config *cfg, const char *sec,
                  const char *key, const char *path);
    const void *arg;
    char sec[64], key[64], path[4096];
} input_search;

static void input_visit(void *ctx, const char *sec, const char *key,
                        const char *path, bool given)
{
    input_search *f = ctx;
    (void)given;
    if (!*f->key && f->match(f->arg, f->cfg, sec, key, path)) {
        snprintf(f->sec, sizeof f->sec, "%s", sec);
        snprintf(f->key, sizeof f->key, "%s", key);
        snprintf(f->path, sizeof f->path, "%s", path);
    }
}

/* A file right in directory `arg` (resolved). */
static bool in_dir(const void *arg, const cl_config *cfg, const char *sec,
                   const char *key, const char *path)
{
    const char *dir = arg, *slash = strrchr(path, '/');
    size_t len = strlen(dir);
    (void)cfg, (void)sec, (void)key;
    return slash && (size_t)(slash - path) == len && !strncmp(path, dir, len);
}

/* A file the problem reads ([init] state, a mesh) inside the output
 * directory is refused: the run removes the earlier run's files there
 * (final.csv among them) before it reads them again for run.json. */
static cl_status inputs_outside(const cl_config *cfg, const char *outdir,
                                cl_error *err)
{
    char *dir = realpath(outdir, NULL);
    input_search f = {.cfg = cfg, .match = in_dir, .arg = dir};
    if (dir)
        cl_config_input_files(cfg, input_visit, &f);
    free(dir);
    if (!*f.key)
        return CL_OK;
    return cl_error_set(err, CL_EINVAL, "[%s] %s = %s: in the output "
                        "directory %s, whose files this run removes and "
                        "writes; copy it elsewhere or give --out another "
                        "directory", f.sec, f.key, f.path, outdir);
}

static cl_status run_work(cl_model *m, const cl_cli_job *job, void *ctx,
                          cl_error *err)
{
    run_setup *r = ctx;
    cl_sim_result res = {0};
    run_output out = {.r = r, .job = job};
    cl_manifest_clocks(&out.mf);
    cl_error later;
    cl_cli_progress_line line;
    cl_status rc = cl_model_set_threads(m, (int)r->run.threads, err);
    if (!rc) /* a directory refused before any work */
        rc = cl_cli_outdir_check(job->outdir, err);
    if (!rc)
        rc = inputs_outside(job->cfg, job->outdir, err);
    if (rc)
        return rc;
    r->so.outdir = job->outdir;
    r->so.progress = cl_cli_progress;
    r->so.before_output = begin_output;
    r->so.before_output_ctx = &out;
    cl_cli_progress_start(&line, job->quiet, "t =", "s",
                          cl_model_start_time(m), r->so.t_end);
    r->so.progress_ctx = &line;
    rc = cl_simulate(m, r->integrator.m[0].type, &r->integrator.m[0].io,
                     &r->so, &res, err);
    cl_cli_progress_clear(&line);
    r->so.progress_ctx = NULL;
    if (!job->quiet && res.rows > 0)
        print_summary(job->problem, r, m, &res);
    /* a summary that did not reach stdout fails the run, in run.json too
     * (before: "complete" there, exit status 7) */
    if (!rc && (fflush(stdout) != 0 || ferror(stdout)))
        rc = cl_error_set(err, CL_EIO, "cannot write standard output: %s",
                          strerror(errno ? errno : EIO));
    if (res.rows > 0) {
        char path[4200];
        snprintf(path, sizeof path, "%s/config.ini", job->outdir);
        cl_status rc2 = cl_config_write(job->cfg, path, rc ? &later : err);
        rc = rc ? rc : rc2;
    }
    free(res.xfinal);
    /* a run refused before its first output leaves the directory alone */
    cl_status rc2 = out.begun ? cl_manifest_end(&out.mf, rc, err, &res.stats,
                                                rc ? &later : err)
                              : CL_OK;
    return rc ? rc : rc2;
}

/* A file a --set names by a relative path. */
static bool relative_set(const void *arg, const cl_config *cfg,
                         const char *sec, const char *key, const char *path)
{
    const char *v = cl_config_peek(cfg, sec, key);
    (void)arg, (void)path;
    return v && v[0] != '/' && cl_config_set_by_command(cfg, sec, key);
}

/* A file named by a set (not by the problem file, whose names are
 * relative to it) must be absolute when the command runs elsewhere. */
static cl_status sets_name_absolute_files(const cl_config *cfg,
                                          cl_error *err)
{
    input_search f = {.cfg = cfg, .match = relative_set};
    cl_config_input_files(cfg, input_visit, &f);
    if (!*f.key)
        return CL_OK;
    return cl_error_set(err, CL_EINVAL, "%s.%s = %s: a relative file name, "
                        "which each job would look for in the directory "
                        "'sweep run' starts in; give its absolute path",
                        f.sec, f.key, cl_config_peek(cfg, f.sec, f.key));
}

cl_status cl_cmd_run_check(const char *problem, const char *integrator,
                           const char *const *sets, int nset, cl_error *err)
{
    run_setup r = {0};
    char assign[4200];
    cl_model *m = NULL;
    cl_config *cfg = cl_config_alloc();
    cl_status rc = cfg ? cl_config_load(cfg, problem, err)
                       : cl_error_set(err, CL_ENOMEM, "out of memory");
    snprintf(assign, sizeof assign, "run.integrator=%s", integrator);
    if (!rc)
        rc = cl_config_set_once(cfg, assign, "--integrator", err);
    for (int k = 0; !rc && k < nset; k++)
        rc = cl_config_set_once(cfg, sets[k], NULL, err);
    if (!rc)
        rc = cl_cli_problem_ready(cfg, &run_table, &r, check_run, &m, err);
    if (!rc)
        rc = sets_name_absolute_files(cfg, err);
    cl_model_free(m);
    cl_config_free(cfg);
    return rc;
}

int cl_cmd_run(int argc, char **argv)
{
    run_setup r = {.argc = argc, .argv = argv};
    return cl_cli_problem_main(argc, argv, &run_table, &r, check_run,
                               run_work);
}
