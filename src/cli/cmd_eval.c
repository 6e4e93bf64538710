/* clothode eval PROBLEM --state STATE.csv: forces, energies and optionally
 * the Jacobians of the model at a given state, for checks against other
 * implementations. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "io/atomic.h"
#include "io/mtx.h"
#include "io/input.h"
#include "io/state.h"
#include "system/model.h"

typedef struct {
    cl_cli_args a;
    const char *state, *jac_x, *jac_v; /* "": no Jacobian written */
    double t;
} eval_args;

static const cl_cli_opt eval_rows[] = {
    {.name = "state", .arg = "FILE", .type = CL_CLI_STRING, .sec = "eval",
     .key = "state", .required = true, .field = offsetof(eval_args, state),
     .help = "the state"},
    {.name = "t", .arg = "T", .type = CL_CLI_DOUBLE, .sec = "eval",
     .key = "t", .lo = -INFINITY, .hi = INFINITY,
     .field = offsetof(eval_args, t),
     .help = "time of the state, where moving obstacles are (the pinned "
             "particles keep the state's positions; default [init] time, "
             "0 unless given)"},
    {.name = "jacobian", .arg = "FILE", .type = CL_CLI_STRING, .sec = "eval",
     .key = "jacobian", .field = offsetof(eval_args, jac_x),
     .help = "also write df/dx over all particles (Matrix Market): the "
             "Jacobian the implicit methods use, exact but for what "
             "docs/model.md leaves out (Baraff-Witkin damping's dd/dx, a "
             "barrier's projection to PSD, self-contact)"},
    {.name = "jacobian-v", .arg = "FILE", .type = CL_CLI_STRING,
     .sec = "eval", .key = "jacobian_v", .field = offsetof(eval_args, jac_v),
     .help = "also write df/dv over all particles (Matrix Market)"},
    {.name = "out", .arg = "DIR", .type = CL_CLI_STRING, .sdef = "out/eval",
     .field = offsetof(eval_args, a.out), .help = "output directory"},
    CL_CLI_SET_ROW,
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table eval_table = {
    .cmd = "eval", .synopsis = "PROBLEM --state STATE.csv [options]",
    .npos = 1, .rows = eval_rows,
    .about =
    "Evaluate the model of PROBLEM at a state (CSV with header\n"
    "p,x,y,z,vx,vy,vz, one row per particle, pinned ones included) and write\n"
    "forces.csv (p,fx,fy,fz: total force on every particle, gravity,\n"
    "damping and contact included; a barrier's friction, whose normal force\n"
    "is lagged from a run's last step, is zero at a lone state) and\n"
    "energy.csv (term,value: kinetic, of the free particles, each potential\n"
    "term, total) into the output directory.\n"};

static cl_status write_forces(const char *dir, size_t np, const double *f,
                              cl_error *err)
{
    char path[4096];
    cl_afile af;
    snprintf(path, sizeof path, "%s/forces.csv", dir);
    cl_status rc = cl_afile_open(&af, path, err);
    if (rc)
        return rc;
    fprintf(af.fp, "p,fx,fy,fz\n");
    for (size_t p = 0; p < np; p++)
        fprintf(af.fp, "%zu,%.17g,%.17g,%.17g\n", p, f[3 * p], f[3 * p + 1],
                f[3 * p + 2]);
    return cl_afile_commit(&af, err);
}

static cl_status write_energy(const char *dir, const cl_energy *e,
                              cl_error *err)
{
    char path[4096];
    cl_afile af;
    snprintf(path, sizeof path, "%s/energy.csv", dir);
    cl_status rc = cl_afile_open(&af, path, err);
    if (rc)
        return rc;
    fprintf(af.fp, "term,value\nkinetic,%.17g\n", e->kinetic);
    for (size_t k = 0; k < e->nterm; k++)
        fprintf(af.fp, "%s,%.17g\n", e->name[k], e->value[k]);
    fprintf(af.fp, "total,%.17g\n", e->total);
    return cl_afile_commit(&af, err);
}

static cl_status write_jacobians(cl_model *m, const eval_args *a,
                                 const double *x, const double *v,
                                 cl_error *err)
{
    cl_bpattern pat = {0};
    double *jx = NULL, *jv = NULL;
    cl_status rc = cl_model_jacobian_full(m, a->t, x, v, &pat, &jx, &jv, err);
    if (!rc && *a->jac_x)
        rc = cl_mtx_write_blocks(a->jac_x, &pat, jx, err);
    if (!rc && *a->jac_v)
        rc = cl_mtx_write_blocks(a->jac_v, &pat, jv, err);
    free(jx);
    free(jv);
    cl_bpattern_free(&pat);
    return rc;
}

/* path with its directory resolved (symbolic links, "..", relative), so
 * that two spellings of one file compare equal; as given when the
 * directory does not exist yet. */
static void resolved_path(const char *path, char *buf, size_t len)
{
    char dir[PATH_MAX], *real;
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else
        snprintf(dir, sizeof dir, "%.*s",
                 slash == path ? 1 : (int)(slash - path), path);
    if ((real = realpath(dir, NULL))) {
        snprintf(buf, len, "%s/%s", real, slash ? slash + 1 : path);
        free(real);
    } else
        snprintf(buf, len, "%s", path);
}

/* Every output path is a regular file or absent, the outputs are
 * different files (a Jacobian written over forces.csv would lose the
 * forces) and none is an input (the state, the problem file), before any
 * work. */
static cl_status check_outputs(const eval_args *a, const char *dir,
                               const char *problem, cl_error *err)
{
    const char *name[4] = {"forces.csv", "energy.csv", "--jacobian",
                           "--jacobian-v"};
    char path[4][PATH_MAX + 64], given[2][PATH_MAX + 16];
    snprintf(given[0], sizeof given[0], "%s/forces.csv", dir);
    snprintf(given[1], sizeof given[1], "%s/energy.csv", dir);
    const char *file[4] = {given[0], given[1], a->jac_x, a->jac_v};
    cl_status rc = cl_cli_check_output(dir, "forces.csv", err);
    if (!rc)
        rc = cl_cli_check_output(dir, "energy.csv", err);
    for (int i = 2; !rc && i < 4; i++)
        if (*file[i])
            rc = cl_output_check(file[i], err);
    for (int i = 0; i < 4; i++)
        if (*file[i])
            resolved_path(file[i], path[i], sizeof path[i]);
    for (int i = 2; !rc && i < 4; i++)
        for (int j = 0; !rc && j < i; j++)
            if (*file[i] && *file[j] && !strcmp(path[i], path[j]))
                rc = cl_error_set(err, CL_EINVAL, "%s %s: the same file as "
                                  "%s%s%s; each output needs a file of its "
                                  "own", name[i], file[i], name[j],
                                  j < 2 ? " in --out " : "", j < 2 ? dir : "");
    const char *input[2] = {a->state, problem}, *what[2] = {"--state",
                                                           "the problem"};
    for (int i = 0; !rc && i < 4; i++)
        for (int j = 0; !rc && j < 2; j++)
            if (*file[i] && input[j] && cl_same_file(file[i], input[j]))
                rc = cl_error_set(err, CL_EINVAL, "%s %s: the same file as "
                                  "%s, %s, which it would overwrite; write "
                                  "the output elsewhere", name[i], file[i],
                                  what[j], input[j]);
    return rc;
}

static cl_status evaluate(cl_model *m, const cl_cli_job *job, void *ctx,
                         cl_error *err)
{
    eval_args at = *(const eval_args *)ctx, *a = &at;
    at.t = cl_cli_state_time(job->cfg, "eval", m, at.t);
    size_t np = cl_model_cloth(m)->np;
    double *x = malloc(3 * np * sizeof *x), *v = malloc(3 * np * sizeof *v);
    double *f = malloc(3 * np * sizeof *f);
    cl_energy e;
    cl_status rc = x && v && f ? CL_OK
                               : cl_error_set(err, CL_ENOMEM, "no memory");
    if (!rc &&
        !(rc = check_outputs(a, job->outdir, cl_config_path(job->cfg),
                             err)) &&
        !(rc = cl_state_read(a->state, np, x, v, err)) &&
        !(rc = cl_model_eval_full(m, a->t, x, v, f, &e, err)) &&
        !(rc = cl_mkdir_p(job->outdir, err)) &&
        !(rc = write_forces(job->outdir, np, f, err)) &&
        !(rc = write_energy(job->outdir, &e, err)) &&
        (*a->jac_x || *a->jac_v))
        rc = write_jacobians(m, a, x, v, err);
    free(x);
    free(v);
    free(f);
    return rc;
}

/* [run] is not eval's; an empty file name for a Jacobian is refused (it
 * would read as "no Jacobian", as --out "" is refused). */
static cl_status check_eval(cl_config *cfg, void *ctx, cl_error *err)
{
    static const char *const key[2] = {"jacobian", "jacobian_v"};
    (void)ctx;
    cl_status rc = cl_cli_ignore_run(cfg, "eval", err);
    for (int k = 0; !rc && k < 2; k++) {
        const char *v = cl_config_peek(cfg, "eval", key[k]);
        if (v && !*v)
            rc = cl_config_refuse(cfg, "eval", key[k], CL_EINVAL,
                                  "an empty file name (leave the option "
                                  "out for no Jacobian)", err);
    }
    return rc;
}

int cl_cmd_eval(int argc, char **argv)
{
    eval_args a = {0};
    return cl_cli_problem_main(argc, argv, &eval_table, &a, check_eval,
                               evaluate);
}
