/* Per-particle sums of per-pair forces (forces/pairgather.h): the lists
 * against known sums, and the same sums bitwise for every thread count. */
#include <criterion/criterion.h>

#include <stdlib.h>
#include <string.h>

#include "forces/pairgather.h"

/* Pairs of a 5-particle chain with a chord, forces in whole numbers
 * (sums exact in any order). */
Test(pairgather, sums_per_particle)
{
    const int ia[] = {0, 1, 2, 3, 0};
    const int ib[] = {1, 2, 3, 4, 2};
    cl_pairgather g;
    cl_error err = {0};
    cr_assert_eq(cl_pairgather_init(&g, ia, ib, 5, 5, &err), CL_OK);
    for (size_t k = 0; k < 5; k++) {
        double fa[4] = {(double)(k + 1), 10.0 * (double)(k + 1), -1.0, 0.0};
        for (int i = 0; i < 4; i++)
            g.f4[4 * k + i] = fa[i];
    }
    double f[15];
    for (size_t i = 0; i < 15; i++)
        f[i] = 100.0; /* sums are added to what is there */
    cl_pairgather_add(&g, 1, f);
    /* p0: +f0 +f4; p1: -f0 +f1; p2: -f1 +f2 -f4; p3: -f2 +f3; p4: -f3 */
    const double want[5][3] = {{106, 160, 98}, {101, 110, 100},
                               {96, 60, 101}, {101, 110, 100},
                               {96, 60, 101}};
    for (size_t p = 0; p < 5; p++)
        for (int i = 0; i < 3; i++)
            cr_assert_eq(f[3 * p + i], want[p][i], "p %zu, %d: %g", p, i,
                         f[3 * p + i]);
    cl_pairgather_free(&g);
}

/* Random pairs among 300 particles, random forces: 1, 2 and 3 threads
 * give the same bits. */
Test(pairgather, threads_bitwise_equal)
{
    enum { NP = 300, N = 2000 };
    int *ia = malloc(N * sizeof *ia), *ib = malloc(N * sizeof *ib);
    unsigned long long s = 7;
    for (size_t k = 0; k < N; k++) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        ia[k] = (int)((s >> 33) % NP);
        ib[k] = (ia[k] + 1 + (int)((s >> 13) % (NP - 1))) % NP;
    }
    cl_pairgather g;
    cl_error err = {0};
    cr_assert_eq(cl_pairgather_init(&g, ia, ib, N, NP, &err), CL_OK);
    for (size_t k = 0; k < 4 * (size_t)N; k++) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        double v = k % 4 == 3 ? 0.0 : (double)(s >> 11) / 9007199254740992.0;
        g.f4[k] = v;
    }
    double *f1 = calloc(3 * NP, sizeof *f1), *fk = calloc(3 * NP,
                                                           sizeof *fk);
    cl_pairgather_add(&g, 1, f1);
    for (int t = 2; t <= 3; t++) {
        memset(fk, 0, 3 * NP * sizeof *fk);
        cl_pairgather_add(&g, t, fk);
        cr_assert_eq(memcmp(fk, f1, 3 * NP * sizeof *fk), 0, "%d threads",
                     t);
    }
    cl_pairgather_free(&g);
    free(ia);
    free(ib);
    free(f1);
    free(fk);
}
