/* The small block pattern of the first-order Jacobian and reduced matrix
 * tests (test_firstorder.c, test_reduced.c, test_bsym.c, test_amat.c):
 * five particles, particle 2 pinned (no unknowns), so NB = 4 block rows;
 * coupled pairs that touch the pinned particle, close a cycle and repeat
 * one pair reversed; masses 0.5 + 0.25 i; and the deterministic random
 * numbers the tests fill block values with.  Header only, included
 * after <criterion/criterion.h> and after every library header (the short
 * macros NP, NB, N would clash with SUNDIALS' parameter names). */
#ifndef CL_TESTS_BLOCKCASE_H
#define CL_TESTS_BLOCKCASE_H

#include <criterion/criterion.h>

#include <stdbool.h>
#include <stdlib.h>

#include "linalg/bpattern.h"

#define NP 5
#define NB 4
#define N (3 * NB)

/* Uniform in [-1, 1), advancing the state *s. */
static inline double bc_rand(unsigned long *s)
{
    *s = *s * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(*s >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

/* The pattern, the N masses, and block-value arrays *dfdx, *dfdv of
 * 9 nnzb entries each (not initialised; bc_free releases all three). */
static inline void bc_init(cl_bpattern *pat, double *mass, double **dfdx,
                           double **dfdv)
{
    const int dof[NP] = {0, 1, -1, 2, 3};
    const int pairs[][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 0}, {1, 3},
                            {1, 0}};
    cr_assert_eq(cl_bpattern_build(NP, dof, NB, 7, pairs, pat, NULL), CL_OK);
    for (size_t i = 0; i < N; i++)
        mass[i] = 0.5 + 0.25 * (double)i;
    size_t nval = 9 * pat->nnzb;
    *dfdx = malloc(nval * sizeof **dfdx);
    *dfdv = malloc(nval * sizeof **dfdv);
    cr_assert(*dfdx && *dfdv);
}

/* Random values in blk (9 nnzb on pat) with block (j, i) = block (i, j)^T
 * exactly; with `own` every block symmetric as well. */
static inline void bc_symmetric(const cl_bpattern *pat, double *blk,
                                unsigned long seed, bool own)
{
    for (size_t i = 0; i < pat->nb; i++)
        for (size_t k = pat->rowptr[i]; k < pat->rowptr[i + 1]; k++) {
            size_t j = pat->col[k];
            if (j < i)
                continue;
            long t = cl_bpattern_find(pat, (long)j, (long)i);
            cr_assert_geq(t, 0);
            for (int r = 0; r < 3; r++)
                for (int q = 0; q < 3; q++) {
                    if ((j == i || own) && q < r)
                        continue;
                    double v = bc_rand(&seed);
                    double *b = blk + 9 * k, *bt = blk + 9 * (size_t)t;
                    b[3 * r + q] = bt[3 * q + r] = v;
                    if (own)
                        b[3 * q + r] = bt[3 * r + q] = v;
                }
        }
}

static inline void bc_free(cl_bpattern *pat, double *dfdx, double *dfdv)
{
    cl_bpattern_free(pat);
    free(dfdx);
    free(dfdv);
}

#endif
