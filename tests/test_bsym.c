/* Symmetric block matrices by halves (linalg/bsym.h): the packed product
 * against the full block product on the shared small pattern (a pinned
 * particle, a cycle, a repeated pair) for a random symmetric matrix; the
 * check tells symmetric blocks from symmetric halves, passes round-off
 * and refuses a non-symmetric matrix, an asymmetric diagonal block and a
 * NaN, and a pair of matrices has the lesser kind of the two; the packed
 * A = M - a Kv - b Kx has the values of the full blocks bit for bit, and
 * unpacked gives back the exactly symmetric matrix the halves multiply by;
 * the halves of a pattern cover every off-diagonal block once. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/bsym.h"
#include "linalg/reduced.h"

#include "blockcase.h" /* last: defines NP, NB, N */

typedef struct {
    cl_bpattern pat;
    double mass[N];
    double *blk, *unused;
    cl_bsym sym;
    double *d, *u;
} bs_case;

static void bs_init(bs_case *c, bool own)
{
    memset(c, 0, sizeof *c);
    bc_init(&c->pat, c->mass, &c->blk, &c->unused);
    cr_assert_eq(cl_bsym_create(&c->pat, &c->sym, NULL), CL_OK);
    c->d = malloc(9 * NB * sizeof *c->d);
    c->u = malloc((9 * c->sym.ne + 1) * sizeof *c->u);
    cr_assert(c->d && c->u);
    bc_symmetric(&c->pat, c->blk, 7, own);
}

static void bs_free(bs_case *c)
{
    cl_bsym_free(&c->sym);
    free(c->d);
    free(c->u);
    bc_free(&c->pat, c->blk, c->unused);
}

Test(bsym, halves_cover_each_offdiagonal_block_once)
{
    bs_case c;
    bs_init(&c, false);
    cr_assert_eq(2 * c.sym.ne + NB, c.pat.nnzb);
    unsigned char seen[64] = {0};
    cr_assert_lt(c.pat.nnzb, sizeof seen);
    for (size_t i = 0; i < NB; i++)
        for (size_t e = c.sym.rowptr[i]; e < c.sym.rowptr[i + 1]; e++) {
            cr_assert_gt(c.sym.col[e], i);
            cr_assert_eq(c.pat.col[c.sym.up[e]], c.sym.col[e]);
            cr_assert_eq(c.pat.col[c.sym.low[e]], i);
            seen[c.sym.up[e]]++;
            seen[c.sym.low[e]]++;
        }
    for (size_t i = 0; i < NB; i++)
        for (size_t k = c.pat.rowptr[i]; k < c.pat.rowptr[i + 1]; k++)
            cr_assert_eq(seen[k], k == c.pat.diag[i] ? 0 : 1, "block %zu", k);
    bs_free(&c);
}

/* Packed as its kind, the product equals the full block product. */
static void bs_product(bool own, cl_bsym_kind want)
{
    bs_case c;
    bs_init(&c, own);
    cl_bsym_kind kind = cl_bsym_check(&c.sym, c.blk, CL_BSYM_TOL);
    cr_assert_eq(kind, want);
    cl_bsym_pack(&c.sym, kind, 1.0, c.blk, 0.0, NULL, NULL, c.d, c.u);
    unsigned long seed = 11;
    double p[N], y[N], z[N];
    for (size_t i = 0; i < N; i++)
        p[i] = bc_rand(&seed);
    cl_bmatvec(&c.pat, c.blk, p, y);
    cl_bsym_matvec(&c.sym, kind, c.d, c.u, p, z);
    for (size_t i = 0; i < N; i++)
        cr_assert_float_eq(z[i], y[i], 1e-14, "row %zu: %.17g vs %.17g", i,
                           z[i], y[i]);
    if (kind == CL_BSYM_BLOCKS) { /* the 9-value halves work too */
        cl_bsym_pack(&c.sym, CL_BSYM_HALVES, 1.0, c.blk, 0.0, NULL, NULL,
                     c.d, c.u);
        cl_bsym_matvec(&c.sym, CL_BSYM_HALVES, c.d, c.u, p, z);
        for (size_t i = 0; i < N; i++)
            cr_assert_float_eq(z[i], y[i], 1e-14);
    }
    bs_free(&c);
}

Test(bsym, product_by_halves_equals_full_product)
{
    bs_product(false, CL_BSYM_HALVES);
}

Test(bsym, product_by_symmetric_blocks_equals_full_product)
{
    bs_product(true, CL_BSYM_BLOCKS);
}

Test(bsym, roundoff_asymmetry_passes_real_asymmetry_does_not)
{
    bs_case c;
    bs_init(&c, true);
    size_t k = c.sym.low[0];
    double keep = c.blk[9 * k + 1];
    c.blk[9 * k + 1] = keep * (1 + 4e-16);
    cr_assert_eq(cl_bsym_check(&c.sym, c.blk, CL_BSYM_TOL), CL_BSYM_BLOCKS);
    c.blk[9 * k + 1] = keep + 1e-6;
    cr_assert_eq(cl_bsym_check(&c.sym, c.blk, CL_BSYM_TOL), CL_BSYM_NONE);
    c.blk[9 * k + 1] = NAN;
    cr_assert_eq(cl_bsym_check(&c.sym, c.blk, CL_BSYM_TOL), CL_BSYM_NONE);
    c.blk[9 * k + 1] = keep;
    /* an off-diagonal block and its partner made non-symmetric alike */
    double *b = c.blk + 9 * c.sym.up[0], *bt = c.blk + 9 * c.sym.low[0];
    b[1] += 0.25;
    bt[3] += 0.25;
    cr_assert_eq(cl_bsym_check(&c.sym, c.blk, CL_BSYM_TOL), CL_BSYM_HALVES);
    double *D = c.blk + 9 * c.pat.diag[2];
    D[5] += 0.5; /* (1, 2) of a diagonal block, (2, 1) unchanged */
    cr_assert_eq(cl_bsym_check(&c.sym, c.blk, CL_BSYM_TOL), CL_BSYM_NONE);
    bs_free(&c);
}

/* The kind of a pair is the lesser of the two: blocks with blocks,
 * halves with blocks, none with anything. */
Test(bsym, pair_takes_the_lesser_kind)
{
    bs_case c, h;
    bs_init(&c, true);
    bs_init(&h, false);
    cr_assert_eq(cl_bsym_check_pair(&c.sym, c.blk, c.blk, CL_BSYM_TOL, 1),
                 CL_BSYM_BLOCKS);
    cr_assert_eq(cl_bsym_check_pair(&c.sym, c.blk, h.blk, CL_BSYM_TOL, 1),
                 CL_BSYM_HALVES);
    cr_assert_eq(cl_bsym_check_pair(&c.sym, h.blk, c.blk, CL_BSYM_TOL, 1),
                 CL_BSYM_HALVES);
    h.blk[9 * h.sym.low[0] + 1] += 1e-6;
    cr_assert_eq(cl_bsym_check_pair(&c.sym, c.blk, h.blk, CL_BSYM_TOL, 1),
                 CL_BSYM_NONE);
    cr_assert_eq(cl_bsym_check_pair(&c.sym, h.blk, c.blk, CL_BSYM_TOL, 1),
                 CL_BSYM_NONE);
    bs_free(&c);
    bs_free(&h);
}

/* A = M - a Kv - b Kx packed from two symmetric Jacobians: the values of
 * the full blocks of cl_reduced_blocks bit for bit, and its product. */
Test(bsym, reduced_matrix_of_symmetric_jacobians_packs)
{
    static const int six[6] = {0, 1, 2, 4, 5, 8};
    bs_case c;
    bs_init(&c, true);
    double *kv = malloc(9 * c.pat.nnzb * sizeof *kv);
    double *a = malloc(9 * c.pat.nnzb * sizeof *a);
    cr_assert(kv && a);
    memcpy(kv, c.blk, 9 * c.pat.nnzb * sizeof *kv);
    bc_symmetric(&c.pat, c.blk, 99, true);
    cr_assert_eq(cl_bsym_check(&c.sym, kv, CL_BSYM_TOL), CL_BSYM_BLOCKS);
    cl_bsym_pack(&c.sym, CL_BSYM_BLOCKS, -0.3, kv, -0.09, c.blk, c.mass,
                 c.d, c.u);
    cl_reduced_blocks(&c.pat, c.mass, 0.3, 0.09, c.blk, kv, a);
    for (size_t i = 0; i < NB; i++)
        cr_assert_arr_eq(c.d + 9 * i, a + 9 * c.pat.diag[i],
                         9 * sizeof(double));
    for (size_t e = 0; e < c.sym.ne; e++)
        for (int q = 0; q < 6; q++)
            cr_assert_eq(c.u[6 * e + (size_t)q], a[9 * c.sym.up[e] + six[q]]);
    double p[N], y[N], z[N];
    unsigned long seed = 5;
    for (size_t i = 0; i < N; i++)
        p[i] = bc_rand(&seed);
    cl_reduced_matvec(&c.pat, c.mass, 0.3, 0.09, c.blk, kv, p, y);
    cl_bsym_matvec(&c.sym, CL_BSYM_BLOCKS, c.d, c.u, p, z);
    for (size_t i = 0; i < N; i++)
        cr_assert_float_eq(z[i], y[i], 1e-14);
    free(kv);
    free(a);
    bs_free(&c);
}

/* Unpacking the halves: for 9-value halves of a matrix whose lower
 * blocks carry a round-off asymmetry, the diagonal and upper blocks come
 * back as they were and each lower block as the transpose of its upper
 * one; 6-value halves of a matrix of symmetric blocks come back exactly. */
Test(bsym, unpack_gives_the_matrix_the_halves_multiply_by)
{
    for (int own = 0; own < 2; own++) {
        bs_case c;
        bs_init(&c, own);
        cl_bsym_kind kind = own ? CL_BSYM_BLOCKS : CL_BSYM_HALVES;
        size_t nval = 9 * c.pat.nnzb;
        double *full = malloc(nval * sizeof *full);
        cr_assert(full);
        if (!own)
            for (size_t e = 0; e < c.sym.ne; e++)
                c.blk[9 * c.sym.low[e] + 1] *= 1.0 + 1e-14;
        cr_assert_eq(cl_bsym_check(&c.sym, c.blk, CL_BSYM_TOL), kind);
        cl_bsym_pack(&c.sym, kind, 1.0, c.blk, 0.0, NULL, NULL, c.d, c.u);
        for (size_t k = 0; k < nval; k++)
            full[k] = NAN;
        cl_bsym_unpack(&c.sym, kind, c.d, c.u, full);
        for (size_t i = 0; i < NB; i++)
            cr_assert_arr_eq(full + 9 * c.pat.diag[i],
                             c.blk + 9 * c.pat.diag[i], 9 * sizeof(double));
        for (size_t e = 0; e < c.sym.ne; e++) {
            const double *up = c.blk + 9 * c.sym.up[e];
            cr_assert_arr_eq(full + 9 * c.sym.up[e], up, 9 * sizeof(double));
            for (int r = 0; r < 3; r++)
                for (int q = 0; q < 3; q++)
                    cr_assert_eq(full[9 * c.sym.low[e] + (size_t)(3 * r + q)],
                                 up[3 * q + r]);
        }
        if (own)
            cr_assert_arr_eq(full, c.blk, nval * sizeof(double));
        free(full);
        bs_free(&c);
    }
}

/* The threaded products (cl_bsym_matvec_threads after cl_bsym_transpose,
 * cl_bmatvec_threads) are bitwise the serial ones for 1, 2 and 3
 * threads, with 6-value and 9-value halves. */
Test(bsym, threaded_products_are_bitwise_serial)
{
    static const cl_bsym_kind kinds[] = {CL_BSYM_BLOCKS, CL_BSYM_HALVES};
    bs_case c;
    bs_init(&c, true);
    cr_assert_eq(cl_bsym_transpose(&c.sym, NULL), CL_OK);
    unsigned long seed = 5;
    double p[N], y[N], z[N];
    for (size_t i = 0; i < N; i++)
        p[i] = bc_rand(&seed);
    for (int k = 0; k < 2; k++) {
        cl_bsym_pack(&c.sym, kinds[k], 1.0, c.blk, 0.0, NULL, c.mass, c.d,
                     c.u);
        cl_bsym_matvec(&c.sym, kinds[k], c.d, c.u, p, y);
        for (int t = 1; t <= 3; t++) {
            cl_bsym_matvec_threads(&c.sym, kinds[k], c.d, c.u, p, z, t);
            cr_assert_eq(memcmp(y, z, sizeof y), 0, "%d threads", t);
        }
    }
    cl_bmatvec(&c.pat, c.blk, p, y);
    for (int t = 1; t <= 3; t++) {
        cl_bmatvec_threads(&c.pat, c.blk, p, z, t);
        cr_assert_eq(memcmp(y, z, sizeof y), 0, "%d threads", t);
    }
    bs_free(&c);
}

/* The threaded packing and symmetry check (cl_bsym_pack_threads,
 * cl_bsym_check_threads) give the serial values bit for bit and the
 * serial kind for 1, 2 and 3 threads: symmetric blocks, symmetric halves,
 * and one asymmetric off-diagonal entry. */
Test(bsym, threaded_pack_and_check_are_serial)
{
    static const cl_bsym_kind kinds[] = {CL_BSYM_BLOCKS, CL_BSYM_HALVES};
    for (int k = 0; k < 2; k++) {
        bs_case c;
        bs_init(&c, k == 0);
        size_t nu = (k == 0 ? 6 : 9) * c.sym.ne;
        double *d = malloc(9 * NB * sizeof *d), *u = malloc(nu * sizeof *u);
        cr_assert(d && u);
        cl_bsym_pack(&c.sym, kinds[k], -0.3, c.blk, -0.01, c.blk, c.mass,
                     c.d, c.u);
        for (int t = 1; t <= 3; t++) {
            cr_assert_eq(cl_bsym_check_threads(&c.sym, c.blk, CL_BSYM_TOL,
                                               t),
                         kinds[k], "%d threads", t);
            cl_bsym_pack_threads(&c.sym, kinds[k], -0.3, c.blk, -0.01,
                                 c.blk, c.mass, d, u, t);
            cr_assert_eq(memcmp(d, c.d, 9 * NB * sizeof *d), 0,
                         "%d threads", t);
            cr_assert_eq(memcmp(u, c.u, nu * sizeof *u), 0, "%d threads", t);
        }
        c.blk[9 * c.sym.up[c.sym.ne - 1] + 1] += 1e-3; /* the last pair */
        for (int t = 1; t <= 3; t++)
            cr_assert_eq(cl_bsym_check_threads(&c.sym, c.blk, CL_BSYM_TOL,
                                               t),
                         CL_BSYM_NONE, "%d threads", t);
        free(d);
        free(u);
        bs_free(&c);
    }
}
