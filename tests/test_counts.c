/* Connection counts (analysis/counts.c, clothode counts; Jiao, section 4.1;
 * docs/model.md 2): the Baraff-Witkin elements measured from the mesh against
 * their formulas for n = 3..40 (triangles 2(n-1)^2, hinges (n-1)(3n-5), all
 * edges = Jiao's bending count 2n(n-1)+(n-1)^2, BW with hinges 5n^2-12n+7,
 * Jiao's BW 5n^2-8n+3 = triangles + all edges), and the CSV columns of
 * `clothode counts --csv --bw`: the Choi-Ko columns first, unchanged, the
 * Baraff-Witkin ones appended. */
#include <criterion/criterion.h>

#include <stdlib.h>
#include <string.h>

#include "analysis/counts.h"
#include "runcli.h"

Test(counts, baraff_witkin_formulas)
{
    for (long n = 3; n <= 40; n++) {
        cl_counts k;
        cl_error err;
        cr_assert_eq(cl_counts_measure((int)n, &k, &err), CL_OK, "%s",
                     err.msg);
        cr_assert_eq(k.bw_tri, 2 * (n - 1) * (n - 1));
        cr_assert_eq(k.bw_tri_formula, k.bw_tri);
        cr_assert_eq(k.bw_bend, (n - 1) * (3 * n - 5), "n = %ld: %ld", n,
                     k.bw_bend);
        cr_assert_eq(k.bw_bend_formula, k.bw_bend);
        cr_assert_eq(k.bw_edges, 3 * n * n - 4 * n + 1);
        cr_assert_eq(k.bw_bend_seed, k.bw_edges);
        cr_assert_eq(k.bw, 5 * n * n - 12 * n + 7);
        cr_assert_eq(k.bw_formula, k.bw);
        cr_assert_eq(k.bw_seed, 5 * n * n - 8 * n + 3);
        cr_assert_eq(k.bw_seed, k.bw_tri + k.bw_edges);
        cr_assert_eq(k.bw_seed - k.bw, 4 * (n - 1)); /* boundary edges */
        cr_assert_eq(k.ck, 8 * n * n - 18 * n + 10);
    }
}

Test(counts, csv_columns)
{
    cli_result r;
    cli_run(&r, "counts", "--csv", "--bw", "--n-max", "40", NULL);
    cli_assert_ok(&r);
    char *save, *line = strtok_r(r.out, "\n", &save);
    cr_assert_not_null(line);
    cr_assert_str_eq(line,
                     "n,type1,type1_formula,type2,type2_formula,ck,ck_formula,"
                     "bw_tri,bw_tri_formula,bw_bend,bw_bend_formula,bw_edges,"
                     "bw_bend_seed,bw,bw_formula,bw_seed");
    long expect_n = 3;
    while ((line = strtok_r(NULL, "\n", &save))) {
        double k[16];
        cli_parse_row(line, k, 16, "counts --csv --bw");
        long n = (long)k[0];
        cr_assert_eq(n, expect_n);
        double want[16] = {
            n, 2.0 * (n - 1) * (2 * n - 1), 2.0 * (n - 1) * (2 * n - 1),
            4.0 * (n - 1) * (n - 2), 4.0 * (n - 1) * (n - 2),
            8.0 * n * n - 18.0 * n + 10, 8.0 * n * n - 18.0 * n + 10,
            2.0 * (n - 1) * (n - 1), 2.0 * (n - 1) * (n - 1),
            (n - 1) * (3.0 * n - 5), (n - 1) * (3.0 * n - 5),
            2.0 * n * (n - 1) + (n - 1) * (n - 1),
            2.0 * n * (n - 1) + (n - 1) * (n - 1),
            5.0 * n * n - 12.0 * n + 7, 5.0 * n * n - 12.0 * n + 7,
            5.0 * n * n - 8.0 * n + 3};
        for (int c = 0; c < 16; c++)
            cr_assert_eq(k[c], want[c], "n = %ld, column %d: %g, want %g", n,
                         c + 1, k[c], want[c]);
        expect_n++;
    }
    cr_assert_eq(expect_n, 41);
    cli_result_free(&r);
    /* Without --bw the Choi-Ko columns alone, as before. */
    cli_run(&r, "counts", "--csv", "--n-max", "3", NULL);
    cli_assert_ok(&r);
    cr_assert_str_eq(r.out,
                     "n,type1,type1_formula,type2,type2_formula,ck,ck_formula\n"
                     "3,20,20,8,8,28,28\n");
    cli_result_free(&r);
    /* The table shows both models. */
    cli_run(&r, "counts", "--n-max", "4", NULL);
    cli_assert_ok(&r);
    cr_assert(strstr(r.out, "Choi-Ko") && strstr(r.out, "Baraff-Witkin") &&
                  strstr(r.out, "(n-1)(3n-5)"),
              "%s", r.out);
    cli_result_free(&r);
    /* --bw without --csv would change nothing */
    cli_run(&r, "counts", "--bw", "--n-max", "4", NULL);
    cli_assert_error(&r, 1, "--bw goes with --csv", NULL);
    cli_result_free(&r);
}
