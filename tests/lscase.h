/* Random block systems for the tests of the linear solvers of the reduced
 * matrix A = M - a df/dv - b df/dx (linalg/linsol.h): a banded, cloth-like
 * block pattern on LS_NB particles, spring-like Laplacians of random SPD
 * 3x3 couplings as df/dx and df/dv (so A is SPD for a, b >= 0), random
 * right-hand sides, the true residual, and set-up-and-solve in one call.
 * Header only, included after <criterion/criterion.h>. */
#ifndef CL_TESTS_LSCASE_H
#define CL_TESTS_LSCASE_H

#include <criterion/criterion.h>

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/stop.h"
#include "linalg/linsol.h"
#include "linalg/reduced.h"

#define LS_NB 40
#define LS_N (3 * LS_NB)
#define LS_MAXPAIRS 128

typedef struct {
    cl_bpattern pat;
    double mass[LS_N];
    double *dfdx, *dfdv;
    int pairs[LS_MAXPAIRS][2];
    size_t npairs;
} ls_case;

static inline double ls_rand(unsigned long *s)
{
    *s = *s * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(*s >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

/* A chain plus pairs (i, i + 7) and (i, i + 13): a banded, cloth-like
 * coupling. */
static inline void ls_pairs(ls_case *c)
{
    c->npairs = 0;
    for (int i = 0; i < LS_NB; i++) {
        const int off[3] = {1, 7, 13};
        for (int q = 0; q < 3; q++) {
            if (i + off[q] < LS_NB) {
                c->pairs[c->npairs][0] = i;
                c->pairs[c->npairs][1] = i + off[q];
                c->npairs++;
            }
        }
    }
}

/* S = R R^T + eps I, a random SPD 3x3 scaled by s. */
static inline void ls_spd3(unsigned long *seed, double s, double S[9])
{
    double R[9];
    for (int q = 0; q < 9; q++)
        R[q] = ls_rand(seed);
    for (int r = 0; r < 3; r++)
        for (int q = 0; q < 3; q++) {
            S[3 * r + q] = 0.05 * (r == q);
            for (int k = 0; k < 3; k++)
                S[3 * r + q] += R[3 * r + k] * R[3 * q + k];
            S[3 * r + q] *= s;
        }
}

/* val: block values; the pair (i, j) adds the "spring" -S on the diagonal
 * blocks and +S on the coupling blocks (so -val is positive
 * semi-definite), times sign. */
static inline void ls_add_pair(const ls_case *c, double *val, int i, int j,
                        const double S[9], double sign)
{
    const long blk[4] = {cl_bpattern_find(&c->pat, i, i),
                         cl_bpattern_find(&c->pat, j, j),
                         cl_bpattern_find(&c->pat, i, j),
                         cl_bpattern_find(&c->pat, j, i)};
    for (int b = 0; b < 4; b++) {
        cr_assert_geq(blk[b], 0);
        for (int q = 0; q < 9; q++)
            val[9 * blk[b] + q] += sign * (b < 2 ? -S[q] : S[q]);
    }
}

static inline void ls_fill(ls_case *c, unsigned long seed, double sign)
{
    size_t nval = 9 * c->pat.nnzb;
    memset(c->dfdx, 0, nval * sizeof *c->dfdx);
    memset(c->dfdv, 0, nval * sizeof *c->dfdv);
    for (size_t p = 0; p < c->npairs; p++) {
        double K[9], D[9];
        ls_spd3(&seed, 100.0 * (1.5 + ls_rand(&seed)), K);
        ls_spd3(&seed, 0.1, D);
        ls_add_pair(c, c->dfdx, c->pairs[p][0], c->pairs[p][1], K, sign);
        ls_add_pair(c, c->dfdv, c->pairs[p][0], c->pairs[p][1], D, sign);
    }
}

static inline void ls_init(ls_case *c, unsigned long seed)
{
    memset(c, 0, sizeof *c);
    ls_pairs(c);
    int dof[LS_NB];
    for (int i = 0; i < LS_NB; i++)
        dof[i] = i;
    cr_assert_eq(cl_bpattern_build(LS_NB, dof, LS_NB, c->npairs,
                                   (const int(*)[2])c->pairs, &c->pat, NULL),
                 CL_OK);
    for (size_t i = 0; i < LS_N; i++)
        c->mass[i] = 1e-3 * (1.0 + 0.5 * ls_rand(&seed));
    size_t nval = 9 * c->pat.nnzb;
    c->dfdx = malloc(nval * sizeof *c->dfdx);
    c->dfdv = malloc(nval * sizeof *c->dfdv);
    cr_assert(c->dfdx && c->dfdv);
    ls_fill(c, seed, 1.0);
}

/* Unit masses, df/dv = 0, and df/dx = -2 I on the blocks coupling
 * neighbours on the chain: with a = 0, b = 1, A = M (I + 2 P), P the path
 * adjacency, whose smallest eigenvalue is ~ 1 - 4 < 0 while every
 * diagonal block is positive: indefinite, as only a Krylov iteration can
 * tell. */
static inline void ls_fill_indefinite_chain(ls_case *c)
{
    size_t nval = 9 * c->pat.nnzb;
    memset(c->dfdx, 0, nval * sizeof *c->dfdx);
    memset(c->dfdv, 0, nval * sizeof *c->dfdv);
    for (size_t i = 0; i < LS_N; i++)
        c->mass[i] = 1.0;
    for (int i = 0; i + 1 < LS_NB; i++) {
        long k1 = cl_bpattern_find(&c->pat, i, i + 1);
        long k2 = cl_bpattern_find(&c->pat, i + 1, i);
        for (int r = 0; r < 3; r++) {
            c->dfdx[9 * k1 + 4 * r] = -2.0;
            c->dfdx[9 * k2 + 4 * r] = -2.0;
        }
    }
}

static inline void ls_free(ls_case *c)
{
    cl_bpattern_free(&c->pat);
    free(c->dfdx);
    free(c->dfdv);
}

static inline const cl_linsol_type *ls_find(const char *name)
{
    const cl_linsol_type *t = cl_linsol_find(name);
    cr_assert_not_null(t, "linear solver %s not registered", name);
    return t;
}

/* True relative residual |b - A x| / |b|. */
static inline double ls_residual(const ls_case *c, double a, double b,
                          const double *rhs, const double *x)
{
    double y[LS_N], rr = 0, bb = 0;
    cl_reduced_matvec(&c->pat, c->mass, a, b, c->dfdx, c->dfdv, x, y);
    for (size_t i = 0; i < LS_N; i++) {
        rr += (rhs[i] - y[i]) * (rhs[i] - y[i]);
        bb += rhs[i] * rhs[i];
    }
    return sqrt(rr / bb);
}

static inline void ls_rhs(unsigned long seed, double *rhs)
{
    for (size_t i = 0; i < LS_N; i++)
        rhs[i] = ls_rand(&seed);
}

/* Solver t on c's pattern and masses with options o (must succeed). */
static inline void *ls_create(const cl_linsol_type *t, const ls_case *c,
                              const cl_linsol_opts *o)
{
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(t->create(&c->pat, c->mass, o, &st, &err), CL_OK, "%s: %s",
                 t->name, err.msg);
    return st;
}

/* Set t up for A(a, b) with c's Jacobians and solve for the right-hand
 * side ls_rhs(seed) into rhs, x; both must succeed.  Returns the true
 * relative residual. */
static inline double ls_setup_solve(const cl_linsol_type *t, void *st,
                             const ls_case *c, double a, double b,
                             unsigned long seed, double *rhs, double *x)
{
    cl_error err = {0};
    cr_assert_eq(t->setup(st, a, b, c->dfdx, c->dfdv, &err), CL_OK, "%s: %s",
                 t->name, err.msg);
    ls_rhs(seed, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_OK, "%s: %s", t->name,
                 err.msg);
    return ls_residual(c, a, b, rhs, x);
}

/* A stop requested (SIGTERM) before a solve of t (set up) ends it with
 * CL_EINTR: "WHO: stopped by SIGTERM in iteration K", who the iterative
 * solver (auto's: pcg). */
static inline void ls_solve_stopped(const cl_linsol_type *t, void *st,
                                    const char *who, const double *rhs,
                                    double *x)
{
    cl_error err = {0};
    char want[64];
    cl_stop_install();
    cr_assert_eq(raise(SIGTERM), 0);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_EINTR, "%s", err.msg);
    snprintf(want, sizeof want, "%s: stopped by SIGTERM in iteration ",
             who);
    cr_assert(strstr(err.msg, want), "%s", err.msg);
}

#endif
