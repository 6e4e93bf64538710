/* Topology of the Choi-Ko connection sets (docs/model.md 2): counts on square
 * and rectangular grids and chains, each unordered pair exactly once, the set
 * equal to a brute-force enumeration by grid offset, rest lengths bit-equal to
 * cl_dist of the rest positions. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "model/cloth.h"
#include "model/pairs.h"

static cl_cloth grid(int nu, int nv, double su, double sv)
{
    cl_cloth c;
    cl_error err;
    cl_status rc = cl_cloth_grid(nu, nv, su, sv, 1e-3, &c, &err);
    cr_assert_eq(rc, CL_OK, "grid %d x %d: %s", nu, nv, err.msg);
    return c;
}

static cl_pairset pairs(const cl_cloth *c, int type)
{
    cl_pairset s;
    cl_error err;
    cl_status rc = type == 1 ? cl_pairs_type1(c, &s, &err)
                             : cl_pairs_type2(c, &s, &err);
    cr_assert_eq(rc, CL_OK, "%s", err.msg);
    return s;
}

static long pos(long k) { return k > 0 ? k : 0; }

/* Counts by direction: axis u, axis v, two diagonals, at offset `o`. */
static long expected_count(long nu, long nv, long o)
{
    return pos(nu - o) * nv + nu * pos(nv - o) + 2 * pos(nu - o) * pos(nv - o);
}

/* Whether particles p, q are connected in the set of type `type`. */
static bool connected(const cl_cloth *c, int type, int p, int q)
{
    int di = abs(p / c->nv - q / c->nv), dj = abs(p % c->nv - q % c->nv);
    return (di == type || di == 0) && (dj == type || dj == 0) &&
           (di || dj);
}

static int cmp_pair(const void *x, const void *y)
{
    const cl_pair *a = x, *b = y;
    if (a->a != b->a)
        return (a->a > b->a) - (a->a < b->a);
    return (a->b > b->b) - (a->b < b->b);
}

/* Every pair valid (a < b, in range, a connection of this type), no
 * duplicates, and as many as the brute-force enumeration finds. */
static void check_set(const cl_cloth *c, int type)
{
    cl_pairset s = pairs(c, type);
    int np = (int)c->np;
    for (size_t k = 0; k < s.n; k++) {
        const cl_pair *p = &s.pair[k];
        cr_assert(p->a >= 0 && p->b < np && p->a < p->b,
                  "pair %zu = (%d, %d)", k, p->a, p->b);
        cr_assert(connected(c, type, p->a, p->b),
                  "type%d pair (%d, %d) is not a connection", type, p->a,
                  p->b);
        double L = cl_dist(c->X0 + 3 * p->a, c->X0 + 3 * p->b);
        cr_assert_eq(p->rest, L, "rest length not bit-equal to cl_dist");
    }
    cl_pair *sorted = malloc((s.n + 1) * sizeof *sorted);
    cr_assert_not_null(sorted);
    if (s.n)
        memcpy(sorted, s.pair, s.n * sizeof *sorted);
    qsort(sorted, s.n, sizeof *sorted, cmp_pair);
    for (size_t k = 1; k < s.n; k++)
        cr_assert(cmp_pair(&sorted[k - 1], &sorted[k]) != 0,
                  "type%d pair (%d, %d) listed twice", type, sorted[k].a,
                  sorted[k].b);
    size_t brute = 0;
    for (int p = 0; p < np; p++)
        for (int q = p + 1; q < np; q++)
            brute += connected(c, type, p, q);
    cr_assert_eq(s.n, brute, "type%d on %d x %d: %zu pairs, brute force %zu",
                 type, c->nu, c->nv, s.n, brute);
    free(sorted);
    cl_pairs_free(&s);
}

Test(pairs, type1_count_square)
{
    for (long n = 3; n <= 40; n++) {
        cl_cloth c = grid((int)n, (int)n, 1.0, 1.0);
        cl_pairset s = pairs(&c, 1);
        cr_assert_eq((long)s.n, 2 * (n - 1) * (2 * n - 1), "n=%ld: %zu", n,
                     s.n);
        cl_pairs_free(&s);
        cl_cloth_free(&c);
    }
}

Test(pairs, type2_count_square)
{
    for (long n = 3; n <= 40; n++) {
        cl_cloth c = grid((int)n, (int)n, 1.0, 1.0);
        cl_pairset s = pairs(&c, 2);
        cr_assert_eq((long)s.n, 4 * (n - 1) * (n - 2), "n=%ld: %zu", n, s.n);
        cl_pairs_free(&s);
        cl_cloth_free(&c);
    }
}

Test(pairs, counts_rectangular_and_chains)
{
    for (long nu = 1; nu <= 15; nu++)
        for (long nv = 1; nv <= 15; nv++) {
            if (nu * nv < 2)
                continue;
            cl_cloth c = grid((int)nu, (int)nv, 1.5, 0.7);
            cl_pairset s1 = pairs(&c, 1), s2 = pairs(&c, 2);
            cr_assert_eq((long)s1.n, expected_count(nu, nv, 1),
                         "type1 %ld x %ld: %zu", nu, nv, s1.n);
            cr_assert_eq((long)s2.n, expected_count(nu, nv, 2),
                         "type2 %ld x %ld: %zu", nu, nv, s2.n);
            if (nu == nv && nu >= 3) {
                cr_assert_eq((long)s1.n, 2 * (nu - 1) * (2 * nu - 1));
                cr_assert_eq((long)s2.n, 4 * (nu - 1) * (nu - 2));
            }
            if (nu == 1) { /* chain: n - 1 and n - 2 */
                cr_assert_eq((long)s1.n, nv - 1);
                cr_assert_eq((long)s2.n, pos(nv - 2));
            }
            cl_pairs_free(&s1);
            cl_pairs_free(&s2);
            cl_cloth_free(&c);
        }
}

Test(pairs, each_pair_once_and_complete)
{
    static const int dims[][2] = {{2, 2}, {3, 3}, {4, 7}, {7, 4}, {9, 9},
                                  {1, 6}, {6, 1}, {2, 9}, {12, 5}};
    for (size_t k = 0; k < sizeof dims / sizeof dims[0]; k++) {
        cl_cloth c = grid(dims[k][0], dims[k][1], 1.3, 0.9);
        check_set(&c, 1);
        check_set(&c, 2);
        cl_cloth_free(&c);
    }
}

/* Rest lengths: hu, hv, and their diagonal (2x for Type2). */
Test(pairs, rest_lengths)
{
    cl_cloth c = grid(5, 4, 2.0, 0.9);
    for (int type = 1; type <= 2; type++) {
        cl_pairset s = pairs(&c, type);
        size_t nu_ax = 0, nv_ax = 0, ndiag = 0;
        for (size_t k = 0; k < s.n; k++) {
            const cl_pair *p = &s.pair[k];
            int di = abs(p->a / c.nv - p->b / c.nv);
            int dj = abs(p->a % c.nv - p->b % c.nv);
            double want = hypot(di * c.hu, dj * c.hv);
            cr_assert(fabs(p->rest - want) <= 1e-15 * want, "rest %.17g %.17g",
                      p->rest, want);
            nu_ax += di && !dj;
            nv_ax += dj && !di;
            ndiag += di && dj;
        }
        cr_assert_eq((long)nu_ax, pos(5 - type) * 4);
        cr_assert_eq((long)nv_ax, 5 * pos(4 - type));
        cr_assert_eq((long)ndiag, 2 * pos(5 - type) * pos(4 - type));
        cl_pairs_free(&s);
    }
    cl_cloth_free(&c);
}

Test(pairs, free_resets)
{
    cl_cloth c = grid(3, 3, 1.0, 1.0);
    cl_pairset s = pairs(&c, 1);
    cr_assert_gt(s.n, 0);
    cl_pairs_free(&s);
    cr_assert_eq(s.n, 0);
    cr_assert_null(s.pair);
    cl_pairs_free(&s); /* twice is harmless */
    cl_cloth_free(&c);
}
