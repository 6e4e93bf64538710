/* The spatial hash (forces/sphash.h): on 10^4 random points it finds
 * exactly the pairs closer than the cell that trying every pair finds,
 * each once, also when many cells share a bucket, and without any pair on
 * points farther apart than the cell. */
#include <criterion/criterion.h>

#include <stdlib.h>
#include <string.h>

#include "forces/sphash.h"

#define NPTS 10000

typedef struct {
    int (*pair)[2];
    size_t n, cap;
} pairlist;

static void collect(void *ctx, int a, int b, double d2)
{
    pairlist *l = ctx;
    (void)d2;
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 1024;
        l->pair = realloc(l->pair, l->cap * sizeof *l->pair);
        cr_assert_not_null(l->pair);
    }
    l->pair[l->n][0] = a;
    l->pair[l->n++][1] = b;
}

static int cmp_pair(const void *x, const void *y)
{
    const int *p = x, *q = y;
    return p[0] != q[0] ? (p[0] > q[0]) - (p[0] < q[0])
                        : (p[1] > q[1]) - (p[1] < q[1]);
}

/* Uniform in [0, side)^3 (a linear congruential generator). */
static void random_points(double *x, size_t n, double side)
{
    unsigned long long s = 12345;
    for (size_t k = 0; k < 3 * n; k++) {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        x[k] = side * (double)(s >> 11) * 0x1.0p-53;
    }
}

/* Every pair a < b with d^2 < r^2, in order. */
static void brute(const double *x, size_t n, double r, pairlist *l)
{
    for (size_t a = 0; a < n; a++)
        for (size_t b = a + 1; b < n; b++) {
            double d2 = 0;
            for (int i = 0; i < 3; i++)
                d2 += (x[3 * b + i] - x[3 * a + i]) *
                      (x[3 * b + i] - x[3 * a + i]);
            if (d2 < r * r)
                collect(l, (int)a, (int)b, d2);
        }
}

/* The hash's pairs (sorted) against brute force's; returns their number. */
static size_t compare(const double *x, size_t n, double cell)
{
    cl_sphash h;
    cl_error err = {0};
    cr_assert_eq(cl_sphash_init(&h, n, cell, &err), CL_OK, "%s", err.msg);
    pairlist got = {0}, want = {0};
    cl_sphash_build(&h, x);
    cl_sphash_pairs(&h, x, collect, &got);
    brute(x, n, cell, &want);
    if (got.n)
        qsort(got.pair, got.n, sizeof *got.pair, cmp_pair);
    cr_assert_eq(got.n, want.n, "hash %zu pairs, brute force %zu", got.n,
                 want.n);
    for (size_t k = 0; k < got.n; k++)
        cr_assert(got.pair[k][0] == want.pair[k][0] &&
                      got.pair[k][1] == want.pair[k][1],
                  "pair %zu: (%d, %d) against (%d, %d)", k, got.pair[k][0],
                  got.pair[k][1], want.pair[k][0], want.pair[k][1]);
    size_t found = got.n;
    free(got.pair);
    free(want.pair);
    cl_sphash_free(&h);
    return found;
}

/* 10^4 points in a unit cube, cells of 0.05: about 2.6 pairs per point
 * (4/3 pi r^3 n / 2, less near the faces), and the same points shifted to
 * negative coordinates. */
Test(sphash, random_points_equal_brute_force)
{
    double *x = malloc(3 * NPTS * sizeof *x);
    cr_assert_not_null(x);
    random_points(x, NPTS, 1.0);
    size_t n = compare(x, NPTS, 0.05);
    cr_assert(n > 20000 && n < 27000, "%zu pairs", n);
    for (size_t k = 0; k < 3 * NPTS; k++)
        x[k] -= 0.5;
    cr_assert_eq(compare(x, NPTS, 0.05), n);
    free(x);
}

/* A large cell (0.2: 2000 points in 125 cells, 16 a cell, 27 cells
 * scanned per point) and a tiny one (1e-3: no pair). */
Test(sphash, crowded_and_empty_buckets)
{
    double *x = malloc(3 * 2000 * sizeof *x);
    cr_assert_not_null(x);
    random_points(x, 2000, 1.0);
    size_t crowded = compare(x, 2000, 0.2);
    cr_assert(crowded > 30000, "%zu pairs", crowded);
    cr_assert_eq(compare(x, 2000, 1e-3), 0);
    free(x);
}

Test(sphash, refuses_a_bad_cell)
{
    cl_sphash h;
    cl_error err = {0};
    cr_assert_eq(cl_sphash_init(&h, 10, 0.0, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "cell = 0"), "%s", err.msg);
}
