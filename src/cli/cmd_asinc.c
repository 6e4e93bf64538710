/* clothode asinc: the exact inverse sinc beside Jiao's polynomial
 * (analysis/asinc_error.h). */
#include <stdlib.h>

#include "analysis/asinc_error.h"
#include "cli/cli.h"
#include "cli/commands.h"

typedef struct {
    cl_cli_args a;
    long n;
    bool csv;
} asinc_args;

static const cl_cli_opt asinc_rows[] = {
    {.name = "points", .arg = "N", .type = CL_CLI_LONG, .sec = "asinc",
     .key = "points", .def = 20, .lo = 1, .hi = 10000000,
     .field = offsetof(asinc_args, n), .help = "N intervals"},
    {.name = "csv", .type = CL_CLI_FLAG, .field = offsetof(asinc_args, csv),
     .help = "rows y,asinc,asinc_over_pi,seed_poly,residual on stdout"},
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table asinc_table = {
    .cmd = "asinc", .synopsis = "[--points N] [--csv]", .npos = 0,
    .rows = asinc_rows,
    .about =
    "The inverse sinc t = asinc(y) of the Type2 buckling curvature\n"
    "(kappa = (2/L) asinc(d/L), Jiao, eq. 8) on y = k/N, k = 0..N, beside\n"
    "t/pi and Jiao's fifth-order polynomial p(y), which fits t/pi but is\n"
    "used in place of t; with the largest errors and the exact solver's\n"
    "residual |1 - sinc(t) - (1 - y)|.\n"};

static void print_table(const cl_asinc_row *r, size_t n,
                        const cl_asinc_summary *s)
{
    printf("%8s %12s %12s %12s %12s %10s\n", "y", "asinc(y)", "asinc/pi",
           "Jiao p(y)", "p - asinc/pi", "residual");
    for (size_t k = 0; k <= n; k++)
        printf("%8.5f %12.9f %12.9f %12.9f %12.3e %10.2e\n", r[k].y, r[k].t,
               r[k].t_over_pi, r[k].seed, r[k].seed - r[k].t_over_pi,
               r[k].resid);
    printf("Jiao's coefficients (highest power first):");
    for (int i = 0; i < CL_SEED_POLY_NCOEF; i++)
        printf(" %.9g", s->p[i]);
    printf("\nmax |p - asinc/pi| = %.4g at y = %.5g; max |p - asinc| = %.4g "
           "(Jiao's curvature is about 1/pi of the arc's)\n"
           "max residual of the exact inverse: %.2e\n",
           s->max_err_normalised, s->y_err_normalised, s->max_err_true,
           s->max_resid);
}

static int asinc(void *settings)
{
    const asinc_args *a = settings;
    long n = a->n;
    cl_asinc_row *rows = malloc(((size_t)n + 1) * sizeof *rows);
    cl_asinc_summary s;
    cl_error err = {0};
    cl_status rc = rows ? cl_asinc_error((size_t)n, rows, &s, &err)
                        : cl_error_set(&err, CL_ENOMEM, "out of memory");
    if (!rc && a->csv) {
        printf("y,asinc,asinc_over_pi,seed_poly,residual\n");
        for (long k = 0; k <= n; k++)
            printf("%.17g,%.17g,%.17g,%.17g,%.3g\n", rows[k].y, rows[k].t,
                   rows[k].t_over_pi, rows[k].seed, rows[k].resid);
    } else if (!rc) {
        print_table(rows, (size_t)n, &s);
    }
    free(rows);
    return rc ? cl_cli_fail(&err) : 0;
}

int cl_cmd_asinc(int argc, char **argv)
{
    asinc_args a = {0};
    return cl_cli_args_main(argc, argv, &asinc_table, &a, asinc);
}
