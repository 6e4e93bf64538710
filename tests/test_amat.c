/* The reduced matrix in the Krylov solvers' storage (linalg/amat.h): on
 * the shared small pattern, symmetric Jacobians are packed by halves (by
 * 6-value blocks when every block is symmetric), a non-symmetric one is
 * kept as all its blocks, and in each form the product and the diagonal
 * blocks are those of A = M - a df/dv - b df/dx formed directly
 * (linalg/reduced.h); the products on 1 and 3 threads are bitwise equal; a
 * value that is not finite is found; a mass that is not positive is
 * refused with the caller's name. */
#include <criterion/criterion.h>

#include <math.h>
#include <string.h>

#include "linalg/amat.h"
#include "linalg/reduced.h"

#include "blockcase.h" /* last: defines NP, NB, N */

#define AM_A 0.3
#define AM_B 0.09

typedef struct {
    cl_bpattern pat;
    double mass[N];
    double *dfdx, *dfdv;
    cl_amat m;
} am_case;

/* df/dx symmetric (each block too if `own`), df/dv symmetric blocks, or
 * df/dx random (not symmetric) if `sym` is false; A filled on `threads`. */
static void am_init(am_case *c, bool sym, bool own, int threads)
{
    memset(c, 0, sizeof *c);
    bc_init(&c->pat, c->mass, &c->dfdx, &c->dfdv);
    bc_symmetric(&c->pat, c->dfdv, 11, true);
    if (sym) {
        bc_symmetric(&c->pat, c->dfdx, 13, own);
    } else {
        unsigned long seed = 17;
        for (size_t k = 0; k < 9 * c->pat.nnzb; k++)
            c->dfdx[k] = bc_rand(&seed);
    }
    cr_assert_eq(cl_amat_init(&c->m, "test", &c->pat, c->mass, threads, NULL),
                 CL_OK);
    cl_amat_jacobian(&c->m, c->dfdx, c->dfdv);
    cl_amat_fill(&c->m, AM_A, AM_B, c->dfdx, c->dfdv);
}

static void am_free(am_case *c)
{
    cl_amat_free(&c->m);
    bc_free(&c->pat, c->dfdx, c->dfdv);
}

/* The product and the diagonal blocks against A formed directly. */
static void am_check_against_reduced(am_case *c)
{
    double p[N], y[N], z[N], d[9 * NB];
    unsigned long seed = 5;
    for (size_t i = 0; i < N; i++)
        p[i] = bc_rand(&seed);
    cl_reduced_matvec(&c->pat, c->mass, AM_A, AM_B, c->dfdx, c->dfdv, p, y);
    cl_amat_mult(&c->m, p, z);
    for (size_t i = 0; i < N; i++)
        cr_assert_float_eq(z[i], y[i], 1e-14, "row %zu: %.17g against %.17g",
                           i, z[i], y[i]);
    cl_reduced_diag_blocks(&c->pat, c->mass, AM_A, AM_B, c->dfdx, c->dfdv, d);
    for (size_t i = 0; i < NB; i++)
        for (int q = 0; q < 9; q++)
            cr_assert_float_eq(cl_amat_diag_block(&c->m, i)[q], d[9 * i + q],
                               1e-15);
    cr_assert(cl_amat_finite(&c->m));
}

/* Symmetric blocks: 6 values an upper block; a symmetric matrix: its
 * halves; a non-symmetric one: all its blocks. */
Test(amat, each_form_multiplies_as_the_matrix_formed_directly)
{
    const cl_bsym_kind want[3] = {CL_BSYM_BLOCKS, CL_BSYM_HALVES,
                                  CL_BSYM_NONE};
    for (int form = 0; form < 3; form++) {
        am_case c;
        am_init(&c, form < 2, form == 0, 1);
        cr_assert_eq(c.m.kind, want[form], "form %d", form);
        am_check_against_reduced(&c);
        am_free(&c);
    }
}

/* Every form on 3 threads gives the serial product bit for bit. */
Test(amat, threaded_product_is_bitwise_serial)
{
    for (int form = 0; form < 3; form++) {
        am_case c1, c3;
        am_init(&c1, form < 2, form == 0, 1);
        am_init(&c3, form < 2, form == 0, 3);
        cr_assert_eq(c1.m.kind, c3.m.kind);
        double p[N], y1[N], y3[N];
        unsigned long seed = 23;
        for (size_t i = 0; i < N; i++)
            p[i] = bc_rand(&seed);
        cl_amat_mult(&c1.m, p, y1);
        cl_amat_mult(&c3.m, p, y3);
        cr_assert_arr_eq(y1, y3, sizeof y1, "form %d", form);
        am_free(&c1);
        am_free(&c3);
    }
}

/* A NaN in df/dx after the Jacobian was told symmetric: packed into the
 * halves, and found; the same in the non-symmetric form. */
Test(amat, value_not_finite_is_found)
{
    for (int sym = 0; sym < 2; sym++) {
        am_case c;
        am_init(&c, sym, true, 1);
        c.dfdx[9 * c.pat.diag[1] + 4] = NAN;
        cl_amat_fill(&c.m, AM_A, AM_B, c.dfdx, c.dfdv);
        cr_assert_not(cl_amat_finite(&c.m), "symmetric %d", sym);
        am_free(&c);
    }
}

Test(amat, mass_not_positive_is_refused_by_name)
{
    cl_bpattern pat;
    double mass[N], *dfdx, *dfdv;
    bc_init(&pat, mass, &dfdx, &dfdv);
    mass[4] = 0.0;
    cl_amat m;
    cl_error err = {0};
    cr_assert_eq(cl_amat_init(&m, "pcg", &pat, mass, 1, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "pcg") != NULL, "%s", err.msg);
    cl_amat_free(&m);
    bc_free(&pat, dfdx, dfdv);
}
