/* clothode counts: connection counts measured from the topology beside the
 * seed's formulas. */
#include <getopt.h>
#include <stdlib.h>

#include "analysis/counts.h"
#include "cli/cli.h"
#include "cli/commands.h"

static const char counts_help[] =
    "usage: clothode counts [--n-min N] [--n-max N] [--csv]\n"
    "For n x n grids, the Choi-Ko Type1 and Type2 connection counts measured\n"
    "from the built topology beside the seed's formulas 2(n-1)(2n-1),\n"
    "4(n-1)(n-2) and CK = 8n^2-18n+10 (defaults: n = 3..40).\n";

static int parse_n(const char *s, long *out)
{
    char *end;
    *out = strtol(s, &end, 10);
    return end != s && !*end && *out >= 2 && *out <= 4096;
}

int cl_cmd_counts(int argc, char **argv)
{
    static const struct option opts[] = {
        {"n-min", required_argument, 0, 'a'},
        {"n-max", required_argument, 0, 'b'},
        {"csv", no_argument, 0, 'c'},
        {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0}};
    long lo = 3, hi = 40;
    int c, csv = 0;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        if (c == 'h')
            return fputs(counts_help, stdout), 0;
        if (c == 'c')
            csv = 1;
        else if ((c != 'a' && c != 'b') ||
                 !parse_n(optarg, c == 'a' ? &lo : &hi))
            return cl_cli_usage_error("counts", "bad option '%s' (n must be "
                                      "an integer in [2, 4096])",
                                      argv[optind - 1]);
    }
    if (optind != argc || lo > hi)
        return cl_cli_usage_error("counts", "unexpected arguments or "
                                  "n-min > n-max");
    printf(csv ? "n,type1,type1_formula,type2,type2_formula,ck,ck_formula\n"
               : "   n   type1 2(n-1)(2n-1)   type2 4(n-1)(n-2)      CK "
                 "8n^2-18n+10\n");
    for (long n = lo; n <= hi; n++) {
        cl_counts k;
        cl_error err;
        if (cl_counts_measure((int)n, &k, &err))
            return cl_cli_fail(&err);
        printf(csv ? "%d,%ld,%ld,%ld,%ld,%ld,%ld\n"
                   : "%4d %7ld %13ld %7ld %11ld %7ld %11ld\n",
               k.n, k.type1, k.type1_formula, k.type2, k.type2_formula, k.ck,
               k.ck_formula);
    }
    return 0;
}
