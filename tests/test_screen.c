/* The screens four points at a time (contact/screen.h) list exactly the
 * points the scalar rules list, in order: random points and memos for
 * every count from 0 to 13 (the blocks and the filled-up last block) and
 * for 1000 points, with points that are not numbers, empty memos
 * (d = -infinity), memos that hold (some exactly at their bound) and
 * points exactly on the half-space's bound. */
#include <criterion/criterion.h>

#include <math.h>

#include "contact/screen.h"

#define MAXP 1000

static unsigned long seed = 12345;

/* Uniform in [-0.5, 0.5). */
static double uniform(void)
{
    seed = seed * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(seed >> 11) / 9007199254740992.0 - 0.5;
}

/* The memo rule of one point, written as in screen.h. */
static bool memo_near(const double y[3], const double q[3],
                      const double s[3], const cl_contact_memo *m,
                      double dmax)
{
    double X[3];
    for (int i = 0; i < 3; i++)
        X[i] = q[i] + (y[i] - q[i] - s[i]);
    double e0 = X[0] - m->X[0], e1 = X[1] - m->X[1], e2 = X[2] - m->X[2];
    double margin = m->d - dmax;
    return !(margin > 0.0 && e0 * e0 + e1 * e1 + e2 * e2 <= margin * margin);
}

/* The half-space rule of one point, written as in screen.h. */
static bool halfspace_near(const double y[3], const double n[3], double c,
                           double scale, double dmax)
{
    double d = n[0] * y[0] + n[1] * y[1] + n[2] * y[2] - c;
    double slack = CL_SCREEN_SLACK * (scale + fabs(y[0]) + fabs(y[1]) +
                                      fabs(y[2]));
    return !(d >= dmax + slack);
}

static double x[3 * MAXP];
static cl_contact_memo memo[MAXP];
static size_t got[MAXP];
static bool near[MAXP];

/* The n points listed in got[] are those of the np whose near[] is set,
 * in order. */
static void same_list(size_t np, size_t n)
{
    size_t want = 0;
    for (size_t p = 0; p < np; p++) {
        if (!near[p])
            continue;
        cr_assert_lt(want, n, "%zu points: point %zu not listed", np, p);
        cr_assert_eq(got[want], p, "%zu points: %zu listed, not %zu", np,
                     got[want], p);
        want++;
    }
    cr_assert_eq(n, want, "%zu points: %zu listed, %zu near", np, n, want);
}

/* Random points (every 37th not a number) and memos: empty, far, near or
 * exactly at the bound of their point. */
static void fill(size_t np, const double q[3], const double s[3],
                 double dmax)
{
    for (size_t p = 0; p < np; p++) {
        double *y = x + 3 * p;
        for (int i = 0; i < 3; i++) {
            y[i] = uniform();
            memo[p].X[i] = q[i] + (y[i] - q[i] - s[i]) + 0.05 * uniform();
        }
        if (p % 37 == 5)
            y[1] = NAN;
        double e[3], r2 = 0.0;
        for (int i = 0; i < 3; i++) {
            e[i] = q[i] + (y[i] - q[i] - s[i]) - memo[p].X[i];
            r2 += e[i] * e[i];
        }
        double kind = uniform();
        memo[p].d = kind < -0.3   ? -INFINITY
                    : kind < 0.2  ? dmax + sqrt(r2) * (1.0 + 2.0 * uniform())
                                  : dmax + sqrt(r2);
    }
}

Test(screen, memos_list_exactly_the_scalar_rule)
{
    const double q[3] = {0.1, -0.6, 0.02}, s[3] = {0.3, 0.01, -0.2};
    const double dmax = 0.01;
    size_t counts[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, MAXP};
    size_t listed = 0, total = 0;
    for (size_t k = 0; k < sizeof counts / sizeof *counts; k++) {
        size_t np = counts[k];
        fill(np, q, s, dmax);
        size_t n = cl_screen_memos(x, np, q, s, memo, dmax, got);
        for (size_t p = 0; p < np; p++)
            near[p] = memo_near(x + 3 * p, q, s, &memo[p], dmax);
        same_list(np, n);
        listed += n;
        total += np;
    }
    cr_assert(listed > total / 4 && listed < total - total / 4, "%zu of %zu",
              listed, total);
}

Test(screen, halfspace_lists_exactly_the_scalar_rule)
{
    double n3[3] = {0.1, 1.0, -0.2}, c = 0.02, dmax = 0.01;
    double len = sqrt(n3[0] * n3[0] + n3[1] * n3[1] + n3[2] * n3[2]);
    for (int i = 0; i < 3; i++)
        n3[i] /= len;
    double scale = 2.0 * fabs(c) + 1.0;
    size_t counts[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, MAXP};
    size_t listed = 0, total = 0;
    for (size_t k = 0; k < sizeof counts / sizeof *counts; k++) {
        size_t np = counts[k];
        for (size_t p = 0; p < np; p++) {
            double *y = x + 3 * p;
            for (int i = 0; i < 3; i++)
                y[i] = uniform();
            if (p % 37 == 5)
                y[2] = NAN;
            if (p % 11 == 3) { /* on the bound: d = dmax + slack */
                double d = n3[0] * y[0] + n3[1] * y[1] + n3[2] * y[2] - c;
                y[1] += dmax - d;
            }
        }
        size_t n = cl_screen_halfspace(x, np, n3, c, scale, dmax, got);
        for (size_t p = 0; p < np; p++)
            near[p] = halfspace_near(x + 3 * p, n3, c, scale, dmax);
        same_list(np, n);
        listed += n;
        total += np;
    }
    cr_assert(listed > total / 4 && listed < total - total / 4, "%zu of %zu",
              listed, total);
}
