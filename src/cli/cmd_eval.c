/* clothode eval PROBLEM --state STATE.csv: forces, energies and optionally
 * the Jacobians of the model at a given state, for checks against other
 * implementations. */
#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/commands.h"
#include "io/atomic.h"
#include "io/mtx.h"
#include "io/state.h"
#include "system/model.h"

static const char eval_help[] =
    "usage: clothode eval PROBLEM --state STATE.csv [options]\n"
    "Evaluate the model of PROBLEM at a state (CSV with header\n"
    "p,x,y,z,vx,vy,vz, one row per particle, pinned ones included) and write\n"
    "forces.csv (p,fx,fy,fz: total force on every particle, gravity and\n"
    "damping included) and energy.csv (term,value: kinetic, each potential\n"
    "term, total) into the output directory.\n"
    "\n"
    "  --state FILE       the state (required)\n"
    "  --t T              time, for moving pins (default 0)\n"
    "  --jacobian FILE    also write df/dx over all particles (Matrix Market)\n"
    "  --jacobian-v FILE  also write df/dv over all particles (Matrix Market)\n"
    "  --out DIR          output directory (default out/eval)\n"
    "  --set SEC.KEY=VAL  override any problem key (repeatable)\n"
    "  --help             this text\n";

typedef struct {
    cl_cli_sets sets;
    const char *state, *jac_x, *jac_v, *out;
    double t;
} eval_args;

static int parse_args(int argc, char **argv, eval_args *a)
{
    static const struct option opts[] = {
        {"state", required_argument, 0, 'S'},
        {"t", required_argument, 0, 't'},
        {"jacobian", required_argument, 0, 'J'},
        {"jacobian-v", required_argument, 0, 'V'},
        {"out", required_argument, 0, 'o'},
        {"set", required_argument, 0, 's'},
        {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0}};
    int c;
    char *end;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        switch (c) {
        case 'h': fputs(eval_help, stdout); return -2;
        case 'S': a->state = optarg; break;
        case 'J': a->jac_x = optarg; break;
        case 'V': a->jac_v = optarg; break;
        case 'o': a->out = optarg; break;
        case 's':
            if (cl_cli_sets_add(&a->sets, NULL, optarg, NULL))
                return -1;
            break;
        case 't':
            a->t = strtod(optarg, &end);
            if (end == optarg || *end)
                return cl_cli_usage_error("eval", "--t \"%s\": expected a "
                                          "number", optarg), -1;
            break;
        default:
            return cl_cli_usage_error("eval", "unknown or incomplete option "
                                      "'%s'", argv[optind - 1]), -1;
        }
    }
    if (optind != argc - 1)
        return cl_cli_usage_error("eval", "expected exactly one PROBLEM, "
                                  "got %d", argc - optind), -1;
    if (!a->state)
        return cl_cli_usage_error("eval", "--state FILE is required"), -1;
    return optind;
}

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
    if (!rc && a->jac_x)
        rc = cl_mtx_write_blocks(a->jac_x, &pat, jx, err);
    if (!rc && a->jac_v)
        rc = cl_mtx_write_blocks(a->jac_v, &pat, jv, err);
    free(jx);
    free(jv);
    cl_bpattern_free(&pat);
    return rc;
}

static cl_status evaluate(cl_model *m, const eval_args *a, cl_error *err)
{
    size_t np = cl_model_cloth(m)->np;
    double *x = malloc(3 * np * sizeof *x), *v = malloc(3 * np * sizeof *v);
    double *f = malloc(3 * np * sizeof *f);
    cl_energy e;
    const char *out = a->out ? a->out : "out/eval";
    cl_status rc = x && v && f ? CL_OK
                               : cl_error_set(err, CL_ENOMEM, "no memory");
    if (!rc && !(rc = cl_state_read(a->state, np, x, v, err)) &&
        !(rc = cl_model_eval_full(m, a->t, x, v, f, &e, err)) &&
        !(rc = cl_mkdir_p(out, err)) &&
        !(rc = write_forces(out, np, f, err)) &&
        !(rc = write_energy(out, &e, err)) && (a->jac_x || a->jac_v))
        rc = write_jacobians(m, a, x, v, err);
    free(x);
    free(v);
    free(f);
    return rc;
}

int cl_cmd_eval(int argc, char **argv)
{
    eval_args a = {0};
    int at = parse_args(argc, argv, &a);
    if (at < 0) {
        cl_cli_sets_free(&a.sets);
        return at == -2 ? 0 : 2;
    }
    char buf[4096];
    const char *problem = cl_cli_problem_path(argv[at], buf, sizeof buf);
    cl_error err = {0};
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cl_status rc = cfg ? CL_OK : cl_error_set(&err, CL_ENOMEM, "no memory");
    if (!rc && !(rc = cl_cli_load(cfg, problem, &a.sets, &err)) &&
        !(rc = cl_model_create(cfg, &m, &err))) {
        cl_config_ignore_section(cfg, "run"); /* eval does not integrate */
        if (!(rc = cl_config_check_unused(cfg, &err)))
            rc = evaluate(m, &a, &err);
    }
    cl_model_free(m);
    cl_config_free(cfg);
    cl_cli_sets_free(&a.sets);
    return rc ? cl_cli_fail(&err) : 0;
}
