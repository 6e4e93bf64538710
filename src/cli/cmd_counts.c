/* clothode counts: connection counts measured from the topology beside
 * Jiao's formulas (section 4.1): Choi-Ko pairs and Baraff-Witkin elements
 * (two tables; with --csv the Choi-Ko columns, and with --bw the
 * Baraff-Witkin columns appended after them). */
#include <getopt.h>
#include <stdlib.h>

#include "analysis/counts.h"
#include "cli/cli.h"
#include "cli/commands.h"

static const char counts_help[] =
    "usage: clothode counts [--n-min N] [--n-max N] [--csv [--bw]]\n"
    "For n x n grids, the Choi-Ko Type1 and Type2 connection counts measured\n"
    "from the built topology beside Jiao's formulas 2(n-1)(2n-1),\n"
    "4(n-1)(n-2) and CK = 8n^2-18n+10 (defaults: n = 3..40), and the\n"
    "Baraff-Witkin elements measured from the triangle mesh: triangles\n"
    "(formula 2(n-1)^2), bending hinges = interior edges ((n-1)(3n-5)), all\n"
    "edges (Jiao's bending count 2n(n-1)+(n-1)^2 counts these), BW =\n"
    "triangles + hinges (5n^2-12n+7) and Jiao's BW = 5n^2-8n+3.\n"
    "  --csv   one CSV row per n: n,type1,type1_formula,type2,type2_formula,\n"
    "          ck,ck_formula\n"
    "  --bw    with --csv, append bw_tri,bw_tri_formula,bw_bend,\n"
    "          bw_bend_formula,bw_edges,bw_bend_seed,bw,bw_formula,bw_seed\n";

static void print_csv(const cl_counts *k, size_t n, int bw)
{
    printf("n,type1,type1_formula,type2,type2_formula,ck,ck_formula%s\n",
           bw ? ",bw_tri,bw_tri_formula,bw_bend,bw_bend_formula,bw_edges,"
                "bw_bend_seed,bw,bw_formula,bw_seed"
              : "");
    for (; n--; k++) {
        printf("%d,%ld,%ld,%ld,%ld,%ld,%ld", k->n, k->type1, k->type1_formula,
               k->type2, k->type2_formula, k->ck, k->ck_formula);
        if (bw)
            printf(",%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld", k->bw_tri,
                   k->bw_tri_formula, k->bw_bend, k->bw_bend_formula,
                   k->bw_edges, k->bw_bend_seed, k->bw, k->bw_formula,
                   k->bw_seed);
        putchar('\n');
    }
}

static void print_tables(const cl_counts *k, size_t n)
{
    printf("Choi-Ko pairs\n"
           "   n   type1 2(n-1)(2n-1)   type2 4(n-1)(n-2)      CK "
           "8n^2-18n+10\n");
    for (size_t i = 0; i < n; i++)
        printf("%4d %7ld %13ld %7ld %11ld %7ld %11ld\n", k[i].n, k[i].type1,
               k[i].type1_formula, k[i].type2, k[i].type2_formula, k[i].ck,
               k[i].ck_formula);
    printf("\nBaraff-Witkin elements (hinges = interior edges; Jiao's "
           "bending count is all edges)\n"
           "   n   tris 2(n-1)^2 hinges (n-1)(3n-5)   edges "
           "2n(n-1)+(n-1)^2      BW 5n^2-12n+7 5n^2-8n+3\n");
    for (size_t i = 0; i < n; i++)
        printf("%4d %6ld %9ld %6ld %13ld %7ld %17ld %7ld %12ld %9ld\n",
               k[i].n, k[i].bw_tri, k[i].bw_tri_formula, k[i].bw_bend,
               k[i].bw_bend_formula, k[i].bw_edges, k[i].bw_bend_seed,
               k[i].bw, k[i].bw_formula, k[i].bw_seed);
}

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
        {"bw", no_argument, 0, 'w'},
        {"help", no_argument, 0, 'h'},
        {0, 0, 0, 0}};
    long lo = 3, hi = 40;
    int c, csv = 0, bw = 0;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        if (c == 'h')
            return fputs(counts_help, stdout), 0;
        if (c == 'c' || c == 'w')
            *(c == 'c' ? &csv : &bw) = 1;
        else if ((c != 'a' && c != 'b') ||
                 !parse_n(optarg, c == 'a' ? &lo : &hi))
            return cl_cli_usage_error("counts", "bad option '%s' (n must be "
                                      "an integer in [2, 4096])",
                                      argv[optind - 1]);
    }
    if (optind != argc || lo > hi)
        return cl_cli_usage_error("counts", "unexpected arguments or "
                                  "n-min > n-max");
    size_t rows = (size_t)(hi - lo + 1);
    cl_counts *k = malloc(rows * sizeof *k);
    if (!k)
        return cl_cli_fail(&(cl_error){CL_ENOMEM, "out of memory"});
    for (size_t i = 0; i < rows; i++) {
        cl_error err;
        if (cl_counts_measure((int)(lo + (long)i), &k[i], &err)) {
            free(k);
            return cl_cli_fail(&err);
        }
    }
    if (csv)
        print_csv(k, rows, bw);
    else
        print_tables(k, rows);
    free(k);
    return 0;
}
