/* clothode asinc: the exact inverse sinc beside Jiao's polynomial
 * (analysis/asinc_error.h). */
#include <getopt.h>
#include <stdlib.h>

#include "analysis/asinc_error.h"
#include "cli/cli.h"
#include "cli/commands.h"

static const char asinc_help[] =
    "usage: clothode asinc [--points N] [--csv]\n"
    "The inverse sinc t = asinc(y) of the Type2 buckling curvature\n"
    "(kappa = (2/L) asinc(d/L), Jiao, eq. 8) on y = k/N, k = 0..N (default\n"
    "N = 20), beside t/pi and Jiao's fifth-order polynomial p(y), which\n"
    "fits t/pi but is used in place of t; with the largest errors and the\n"
    "exact solver's residual |1 - sinc(t) - (1 - y)|.\n"
    "  --points N  N intervals, 1 .. 10000000\n"
    "  --csv       rows y,asinc,asinc_over_pi,seed_poly,residual on stdout\n";

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

int cl_cmd_asinc(int argc, char **argv)
{
    static const struct option opts[] = {
        {"points", required_argument, 0, 'n'},
        {"csv", no_argument, 0, 'c'},
        {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0}};
    long n = 20;
    int c, csv = 0;
    char *end;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        if (c == 'h')
            return fputs(asinc_help, stdout), 0;
        if (c == 'c')
            csv = 1;
        else if (c != 'n')
            return cl_cli_usage_error("asinc", "unknown or incomplete option "
                                      "'%s'", argv[optind - 1]);
        else if ((n = strtol(optarg, &end, 10), *end) || end == optarg ||
                 n < 1 || n > 10000000)
            return cl_cli_usage_error("asinc", "--points \"%s\": expected "
                                      "an integer in [1, 10000000]", optarg);
    }
    if (optind != argc)
        return cl_cli_usage_error("asinc", "unexpected argument '%s'",
                                  argv[optind]);
    cl_asinc_row *rows = malloc(((size_t)n + 1) * sizeof *rows);
    cl_asinc_summary s;
    cl_error err = {0};
    cl_status rc = rows ? cl_asinc_error((size_t)n, rows, &s, &err)
                        : cl_error_set(&err, CL_ENOMEM, "out of memory");
    if (!rc && csv) {
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
