/* clothode spectrum PROBLEM: eigenvalues of the linearised cloth and the
 * explicit step limits they predict (analysis/spectrum.h). */
#include <math.h>
#include <stdlib.h>

#include "analysis/spectrum.h"
#include "cli/cli.h"
#include "cli/commands.h"

typedef struct {
    cl_cli_args a;
    const char *state; /* "" for the initial state */
    double t;
} spec_setup;

static const cl_cli_opt spec_rows[] = {
    {.name = "state", .arg = "FILE", .type = CL_CLI_STRING,
     .sec = "spectrum", .key = "state", .field = offsetof(spec_setup, state),
     .help = "state to linearise at, as final.csv (default: the problem's "
             "initial state)"},
    {.name = "t", .arg = "T", .type = CL_CLI_DOUBLE, .sec = "spectrum",
     .key = "t", .lo = -INFINITY, .hi = INFINITY,
     .field = offsetof(spec_setup, t),
     .help = "time of that state, where moving obstacles are (the pinned "
             "particles keep the state's positions; default [init] time, "
             "0 unless given)"},
    CL_CLI_TAIL(spec_setup, "no summary on stdout"),
    {.type = CL_CLI_END}};

static const cl_cli_table spec_table = {
    .cmd = "spectrum", .synopsis = "PROBLEM [options]", .npos = 1,
    .rows = spec_rows,
    .about =
    "Eigenvalues of the cloth linearised at a state: mu = w^2 of the\n"
    "stiffness (-M^-1/2 sym(df/dx) M^-1/2) and lambda of the first-order\n"
    "Jacobian (damping included), and the largest stable steps they predict\n"
    "for the explicit integrators (compare with clothode stability).  Dense\n"
    "eigensolvers: at most a 24 x 24 cloth.  Writes spectrum.csv (kind,\n"
    "index, re, im) into the output directory.\n"};

static void print_summary(const cl_cli_job *job, const cl_spectrum *sp)
{
    printf("problem    %s, %zu unknowns\n", job->problem, sp->n);
    printf("stiffness  w_max = %.6g rad/s (mu %.6g .. %.6g; %zu negative, "
           "%zu zero to 1e-12 mu_max)\n", sp->w_max, sp->mu[0],
           sp->mu[sp->n - 1], sp->n_negative, sp->n_zero);
    printf("first order  |lambda|_max = %.6g 1/s; %zu growing modes%s",
           sp->lambda_max, sp->n_growing,
           sp->n_growing ? "" : "\n");
    if (sp->n_growing)
        printf(", fastest growth rate %.6g 1/s\n", sp->growth_max);
    printf("%-20s %12s   %s\n", "integrator", "predicted dt", "from");
    size_t nlim = cl_spectrum_limits(sp, NULL, 0);
    cl_spectrum_limit *lim = nlim ? malloc(nlim * sizeof *lim) : NULL;
    if (nlim && !lim) {
        printf("(out of memory for the predicted steps)\n");
        return;
    }
    cl_spectrum_limits(sp, lim, nlim);
    for (size_t k = 0; k < nlim; k++)
        printf("%-20s %12.4g   %s\n", lim[k].integrator, lim[k].h,
               lim[k].basis);
    free(lim);
}

static void write_rows(FILE *fp, const void *ctx, int n)
{
    (void)n;
    cl_spectrum_write(fp, ctx);
}

static cl_status spectrum(cl_model *m, const cl_cli_job *job, void *ctx,
                          cl_error *err)
{
    const spec_setup *s = ctx;
    size_t n = cl_model_system(m)->n;
    double *x = malloc(n * sizeof *x), *v = malloc(n * sizeof *v);
    cl_spectrum sp = {0};
    cl_status rc = x && v ? cl_cli_free_state(m, s->state, x, v, err)
                          : cl_error_set(err, CL_ENOMEM, "out of memory");
    if (!rc && !(rc = cl_cli_check_output(job->outdir, "spectrum.csv", err)) &&
        !(rc = cl_spectrum_compute(m, cl_cli_state_time(job->cfg,
                                                         "spectrum", m, s->t),
                                   x, v, &sp, err)) &&
        !(rc = cl_cli_write_csv(job->outdir, "spectrum.csv", write_rows, &sp,
                                1, err)) && !job->quiet) {
        print_summary(job, &sp);
        printf("output     %s/spectrum.csv\n", job->outdir);
    }
    cl_spectrum_free(&sp);
    free(x);
    free(v);
    return rc;
}

static cl_status check_spectrum(cl_config *cfg, void *ctx, cl_error *err)
{
    (void)ctx;
    return cl_cli_ignore_run(cfg, "spectrum", err);
}

int cl_cmd_spectrum(int argc, char **argv)
{
    spec_setup s = {0};
    return cl_cli_problem_main(argc, argv, &spec_table, &s, check_spectrum,
                               spectrum);
}
