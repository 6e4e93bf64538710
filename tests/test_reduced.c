/* Reduced matrix A = M - a df/dv - b df/dx (linalg/reduced.h): the CSC form
 * compared entry by entry with a dense matrix built independently from the
 * block pattern (random non-symmetric blocks, a pattern with a pinned
 * particle), structure (column pointers, strictly ascending rows, every
 * diagonal entry stored at diagpos), refill with other a, b; block values,
 * block products and diagonal blocks against dense products; the
 * Baraff-Witkin filter S B S against filtering the product's argument and
 * result; mass checks. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/reduced.h"

#include "blockcase.h" /* last: defines NP, NB, N */

typedef struct {
    cl_bpattern pat;
    double mass[N];
    double *dfdx, *dfdv;
} rd_case;

static void rd_init(rd_case *c, unsigned long seed)
{
    memset(c, 0, sizeof *c);
    bc_init(&c->pat, c->mass, &c->dfdx, &c->dfdv);
    size_t nval = 9 * c->pat.nnzb;
    for (size_t k = 0; k < nval; k++) {
        c->dfdx[k] = 3.0 * bc_rand(&seed);
        c->dfdv[k] = 2.0 * bc_rand(&seed);
    }
}

static void rd_free(rd_case *c)
{
    bc_free(&c->pat, c->dfdx, c->dfdv);
}

/* Dense A, row-major N x N, straight from the block CSR. */
static void rd_dense(const rd_case *c, double a, double b, double *D)
{
    memset(D, 0, N * N * sizeof *D);
    for (size_t i = 0; i < N; i++)
        D[i * N + i] = c->mass[i];
    for (size_t bi = 0; bi < NB; bi++) {
        for (size_t k = c->pat.rowptr[bi]; k < c->pat.rowptr[bi + 1]; k++) {
            size_t bj = c->pat.col[k];
            for (size_t r = 0; r < 3; r++)
                for (size_t q = 0; q < 3; q++)
                    D[(3 * bi + r) * N + 3 * bj + q] -=
                        a * c->dfdv[9 * k + 3 * r + q] +
                        b * c->dfdx[9 * k + 3 * r + q];
        }
    }
}

/* The CSC matrix expanded to dense; every (row, col) at most once. */
static void rd_expand(const cl_reduced *r, const double *val, double *D)
{
    unsigned char seen[N * N] = {0};
    memset(D, 0, N * N * sizeof *D);
    for (size_t j = 0; j < N; j++) {
        for (SuiteSparse_long e = r->colptr[j]; e < r->colptr[j + 1]; e++) {
            size_t i = (size_t)r->rowind[e];
            cr_assert_lt(i, N);
            cr_assert_eq(seen[i * N + j], 0, "entry (%zu, %zu) twice", i, j);
            seen[i * N + j] = 1;
            D[i * N + j] = val[e];
        }
    }
}

static void rd_dense_mv(const double *D, const double *p, double *y)
{
    for (size_t i = 0; i < N; i++) {
        y[i] = 0;
        for (size_t j = 0; j < N; j++)
            y[i] += D[i * N + j] * p[j];
    }
}

static void rd_assert_close(const double *x, const double *y, size_t n,
                            const char *what)
{
    for (size_t i = 0; i < n; i++)
        cr_assert(fabs(x[i] - y[i]) <= 1e-13 * (1.0 + fabs(y[i])),
                  "%s[%zu]: %.17g vs %.17g", what, i, x[i], y[i]);
}

Test(reduced, csc_equals_dense_reference)
{
    rd_case c;
    rd_init(&c, 7);
    cl_reduced r;
    cl_error err;
    cr_assert_eq(cl_reduced_create(&c.pat, c.mass, &r, &err), CL_OK, "%s",
                 err.msg);
    cr_assert_eq(r.n, N);
    cr_assert_eq((size_t)r.nnz, 9 * c.pat.nnzb);
    double *val = malloc((size_t)r.nnz * sizeof *val);
    double D[N * N], E[N * N];
    const double ab[][2] = {{0.1, 0.01}, {2.0 / 3.0 * 0.1, 4.0 / 9.0 * 0.01},
                            {0.0, 0.0}, {-1.5, 3.0}};
    for (size_t t = 0; t < sizeof ab / sizeof ab[0]; t++) {
        cl_reduced_fill(&r, ab[t][0], ab[t][1], c.dfdx, c.dfdv, val);
        rd_expand(&r, val, E);
        rd_dense(&c, ab[t][0], ab[t][1], D);
        rd_assert_close(E, D, N * N, "A");
    }
    free(val);
    cl_reduced_free(&r);
    rd_free(&c);
}

Test(reduced, structure_sorted_with_full_diagonal)
{
    rd_case c;
    rd_init(&c, 11);
    cl_reduced r;
    cr_assert_eq(cl_reduced_create(&c.pat, c.mass, &r, NULL), CL_OK);
    cr_assert_eq(r.colptr[0], 0);
    cr_assert_eq(r.colptr[N], r.nnz);
    for (size_t j = 0; j < N; j++) {
        cr_assert_leq(r.colptr[j], r.colptr[j + 1]);
        for (SuiteSparse_long e = r.colptr[j] + 1; e < r.colptr[j + 1]; e++)
            cr_assert_lt(r.rowind[e - 1], r.rowind[e], "column %zu", j);
        SuiteSparse_long d = r.diagpos[j];
        cr_assert(d >= r.colptr[j] && d < r.colptr[j + 1]);
        cr_assert_eq(r.rowind[d], (SuiteSparse_long)j);
    }
    /* zero Jacobians: A = M, the diagonal carries the masses */
    size_t nval = 9 * c.pat.nnzb;
    double *z = calloc(nval, sizeof *z), *val = malloc(nval * sizeof *val);
    cl_reduced_fill(&r, 1.0, 1.0, z, z, val);
    for (size_t j = 0; j < N; j++)
        cr_assert_eq(val[r.diagpos[j]], c.mass[j]);
    free(z);
    free(val);
    cl_reduced_free(&r);
    rd_free(&c);
}

Test(reduced, block_views_match_dense_products)
{
    rd_case c;
    rd_init(&c, 3);
    const double a = 0.37, b = 0.052;
    double D[N * N], p[N], y[N], yref[N], d3[9 * NB];
    unsigned long seed = 99;
    for (size_t i = 0; i < N; i++)
        p[i] = bc_rand(&seed);
    rd_dense(&c, a, b, D);
    rd_dense_mv(D, p, yref);
    cl_reduced_matvec(&c.pat, c.mass, a, b, c.dfdx, c.dfdv, p, y);
    rd_assert_close(y, yref, N, "matvec");
    double *ablk = malloc(9 * c.pat.nnzb * sizeof *ablk);
    cl_reduced_blocks(&c.pat, c.mass, a, b, c.dfdx, c.dfdv, ablk);
    cl_bmatvec(&c.pat, ablk, p, y);
    rd_assert_close(y, yref, N, "bmatvec(A blocks)");
    cl_reduced_diag_blocks(&c.pat, c.mass, a, b, c.dfdx, c.dfdv, d3);
    for (size_t i = 0; i < NB; i++)
        for (size_t r = 0; r < 3; r++)
            for (size_t q = 0; q < 3; q++)
                cr_assert_float_eq(d3[9 * i + 3 * r + q],
                                   D[(3 * i + r) * N + 3 * i + q], 1e-14);
    /* a plain block product: y = df/dx p */
    cl_bmatvec(&c.pat, c.dfdx, p, y);
    rd_dense(&c, 0.0, -1.0, D);
    for (size_t i = 0; i < N; i++)
        D[i * N + i] -= c.mass[i];
    rd_dense_mv(D, p, yref);
    rd_assert_close(y, yref, N, "df/dx p");
    free(ablk);
    rd_free(&c);
}

Test(reduced, rejects_bad_masses)
{
    rd_case c;
    rd_init(&c, 5);
    const double bad[] = {0.0, -1.0, NAN, INFINITY};
    for (size_t t = 0; t < sizeof bad / sizeof bad[0]; t++) {
        double m[N];
        memcpy(m, c.mass, sizeof m);
        m[4] = bad[t];
        cl_reduced r;
        cl_error err;
        cr_assert_eq(cl_reduced_create(&c.pat, m, &r, &err), CL_EINVAL);
        cr_assert_not_null(strstr(err.msg, "mass[4]"), "%s", err.msg);
        cr_assert_null(r.colptr);
    }
    rd_free(&c);
}

/* Filters of the three kinds (I, I - n n^T, 0) by turns: the filtered
 * blocks' product is S (B (S p)) for every p, and S is a projector. */
Test(reduced, filter_is_s_b_s)
{
    rd_case c;
    rd_init(&c, 5);
    unsigned long seed = 7;
    double S[9 * NB], p[N], sp[N], y[N], yref[N];
    for (size_t i = 0; i < NB; i++) {
        double n[3], nn = 0.0;
        for (int r = 0; r < 3; r++) {
            n[r] = bc_rand(&seed);
            nn += n[r] * n[r];
        }
        for (int r = 0; r < 3; r++)
            for (int q = 0; q < 3; q++)
                S[9 * i + 3 * r + q] = i % 3 == 0 ? (r == q)
                                     : i % 3 == 1 ? (r == q) - n[r] * n[q] / nn
                                                  : 0.0;
    }
    for (size_t i = 0; i < N; i++)
        p[i] = bc_rand(&seed);
    double *f = malloc(9 * c.pat.nnzb * sizeof *f);
    cl_reduced_filter(&c.pat, S, c.dfdx, f);
    cl_bmatvec(&c.pat, f, p, y);
    cl_bdiag_apply(NB, S, p, sp);
    cl_bmatvec(&c.pat, c.dfdx, sp, yref);
    cl_bdiag_apply(NB, S, yref, yref);
    rd_assert_close(y, yref, N, "S B S p");
    cl_bdiag_apply(NB, S, sp, y);       /* S S p = S p, in place too */
    rd_assert_close(y, sp, N, "S S p");
    for (size_t i = 0; i < NB; i++)     /* the zero filter: exactly 0 */
        for (int r = 0; i % 3 == 2 && r < 3; r++)
            cr_assert_eq(sp[3 * i + r], 0.0);
    free(f);
    rd_free(&c);
}
