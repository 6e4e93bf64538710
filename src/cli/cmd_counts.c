/* clothode counts: connection counts measured from the topology beside
 * Jiao's formulas (section 4.1): Choi-Ko pairs and Baraff-Witkin elements
 * (two tables; with --csv the Choi-Ko columns, and with --bw the
 * Baraff-Witkin columns appended after them). */
#include <stdlib.h>

#include "analysis/counts.h"
#include "cli/cli.h"
#include "cli/commands.h"

typedef struct {
    cl_cli_args a;
    long lo, hi;
    bool csv, bw;
} counts_args;

static const cl_cli_opt counts_rows[] = {
    {.name = "n-min", .arg = "N", .type = CL_CLI_LONG, .sec = "counts",
     .key = "n_min", .def = 3, .lo = 2, .hi = 4096,
     .field = offsetof(counts_args, lo), .help = "smallest grid n"},
    {.name = "n-max", .arg = "N", .type = CL_CLI_LONG, .sec = "counts",
     .key = "n_max", .def = 40, .lo = 2, .hi = 4096,
     .field = offsetof(counts_args, hi), .help = "largest grid n"},
    {.name = "csv", .type = CL_CLI_FLAG, .field = offsetof(counts_args, csv),
     .help = "one CSV row per n: n, type1, type1_formula, type2, "
             "type2_formula, ck, ck_formula"},
    {.name = "bw", .type = CL_CLI_FLAG, .field = offsetof(counts_args, bw),
     .help = "with --csv, append bw_tri, bw_tri_formula, bw_bend, "
             "bw_bend_formula, bw_edges, bw_bend_seed, bw, bw_formula, "
             "bw_seed"},
    CL_CLI_HELP_ROW,
    {.type = CL_CLI_END}};

static const cl_cli_table counts_table = {
    .cmd = "counts", .synopsis = "[--n-min N] [--n-max N] [--csv [--bw]]",
    .npos = 0, .rows = counts_rows,
    .about =
    "For n x n grids, the Choi-Ko Type1 and Type2 connection counts measured\n"
    "from the built topology beside Jiao's formulas 2(n-1)(2n-1),\n"
    "4(n-1)(n-2) and CK = 8n^2-18n+10, and the Baraff-Witkin elements\n"
    "measured from the triangle mesh: triangles (formula 2(n-1)^2), bending\n"
    "hinges = interior edges ((n-1)(3n-5)), all edges (Jiao's bending count\n"
    "2n(n-1)+(n-1)^2 counts these), BW = triangles + hinges (5n^2-12n+7)\n"
    "and Jiao's BW = 5n^2-8n+3.\n"};

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

static int counts(void *settings)
{
    const counts_args *a = settings;
    if (a->lo > a->hi)
        return cl_cli_usage_error("counts", "--n-min %ld is above --n-max "
                                  "%ld", a->lo, a->hi);
    if (a->bw && !a->csv)
        return cl_cli_usage_error("counts", "--bw goes with --csv (the "
                                  "tables print the Baraff-Witkin counts "
                                  "without it)");
    size_t rows = (size_t)(a->hi - a->lo + 1);
    cl_counts *k = malloc(rows * sizeof *k);
    if (!k)
        return cl_cli_fail(&(cl_error){CL_ENOMEM, "out of memory"});
    for (size_t i = 0; i < rows; i++) {
        cl_error err;
        if (cl_counts_measure((int)(a->lo + (long)i), &k[i], &err)) {
            free(k);
            return cl_cli_fail(&err);
        }
    }
    if (a->csv)
        print_csv(k, rows, a->bw);
    else
        print_tables(k, rows);
    free(k);
    return 0;
}

int cl_cmd_counts(int argc, char **argv)
{
    counts_args a = {0};
    return cl_cli_args_main(argc, argv, &counts_table, &a, counts);
}
