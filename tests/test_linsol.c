/* Linear solvers of the reduced matrix A = M - a df/dv - b df/dx
 * (linalg/linsol.h): registry; klu, pcg and pcg-jacobi solve random SPD
 * block systems (spring-like Laplacians of random SPD 3x3 couplings) to a
 * true relative residual of 1e-10; KLU analyses once over many setups;
 * failures are reported as CL_ESOLVER: pcg on an indefinite A (caught in
 * the preconditioner setup, or by the curvature check during the
 * iteration), pcg at its iteration cap, KLU on a singular A. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

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

static double ls_rand(unsigned long *s)
{
    *s = *s * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(*s >> 11) / 9007199254740992.0 * 2.0 - 1.0;
}

/* A chain plus pairs (i, i + 7) and (i, i + 13): a banded, cloth-like
 * coupling. */
static void ls_pairs(ls_case *c)
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
static void ls_spd3(unsigned long *seed, double s, double S[9])
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
static void ls_add_pair(const ls_case *c, double *val, int i, int j,
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

static void ls_fill(ls_case *c, unsigned long seed, double sign)
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

static void ls_init(ls_case *c, unsigned long seed)
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

static void ls_free(ls_case *c)
{
    cl_bpattern_free(&c->pat);
    free(c->dfdx);
    free(c->dfdv);
}

static const cl_linsol_type *ls_find(const char *name)
{
    const cl_linsol_type *t = cl_linsol_find(name);
    cr_assert_not_null(t, "linear solver %s not registered", name);
    return t;
}

/* True relative residual |b - A x| / |b|. */
static double ls_residual(const ls_case *c, double a, double b,
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

static void ls_rhs(unsigned long seed, double *rhs)
{
    for (size_t i = 0; i < LS_N; i++)
        rhs[i] = ls_rand(&seed);
}

/* Solver t on c's pattern and masses with options o (must succeed). */
static void *ls_create(const cl_linsol_type *t, const ls_case *c,
                       const cl_integrator_opts *o)
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
static double ls_setup_solve(const cl_linsol_type *t, void *st,
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

Test(linsol, registry)
{
    char buf[128];
    cr_assert_str_eq(cl_linsol_names(buf, sizeof buf), "klu, pcg, pcg-jacobi");
    cr_assert_str_eq(cl_linsol_find(NULL)->name, "klu");
    cr_assert_str_eq(cl_linsol_find("")->name, "klu");
    cr_assert_str_eq(ls_find("pcg")->name, "pcg");
    cr_assert_str_eq(ls_find("pcg-jacobi")->name, "pcg-jacobi");
    cr_assert_null(cl_linsol_find("lu"));
    char tiny[8];
    cr_assert_str_eq(cl_linsol_names(tiny, sizeof tiny), "klu, pc");
}

static void ls_solve_spd(const char *name)
{
    ls_case c;
    ls_init(&c, 2024);
    const cl_linsol_type *t = ls_find(name);
    void *st = ls_create(t, &c, &(cl_integrator_opts){0});
    const double h = 1e-2, ab[][2] = {{h, h * h},
                                      {2 * h / 3, 4 * h * h / 9},
                                      {0.1, 0.01}};
    double rhs[LS_N], x[LS_N];
    for (size_t k = 0; k < 3; k++) {
        double res = ls_setup_solve(t, st, &c, ab[k][0], ab[k][1], 100 + k,
                                    rhs, x);
        cr_log_info("%s: a = %g, b = %g: relative residual %.3e", name,
                    ab[k][0], ab[k][1], res);
        cr_assert_leq(res, 1e-10, "%s: residual %g", name, res);
    }
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.lin_setups, 3);
    cr_assert_eq(s.lin_solves, 3);
    if (strcmp(name, "klu") == 0) {
        cr_assert_eq(s.symbolic_facts, 1);
        cr_assert_eq(s.lin_iters, 0);
    } else {
        cr_assert_eq(s.symbolic_facts, 0);
        cr_assert_gt(s.lin_iters, 3);
        cr_log_info("%s: %ld iterations for 3 solves", name, s.lin_iters);
    }
    t->free(st);
    ls_free(&c);
}

Test(linsol, klu_solves_spd) { ls_solve_spd("klu"); }
Test(linsol, pcg_solves_spd) { ls_solve_spd("pcg"); }
Test(linsol, pcg_jacobi_solves_spd) { ls_solve_spd("pcg-jacobi"); }

/* klu also solves a nonsymmetric A (pcg need not). */
Test(linsol, klu_solves_nonsymmetric)
{
    ls_case c;
    ls_init(&c, 77);
    unsigned long seed = 5;
    size_t nval = 9 * c.pat.nnzb;
    for (size_t q = 0; q < nval; q++)
        c.dfdx[q] += 10.0 * ls_rand(&seed);
    const cl_linsol_type *t = ls_find("klu");
    void *st = ls_create(t, &c, &(cl_integrator_opts){0});
    double rhs[LS_N], x[LS_N];
    cr_assert_leq(ls_setup_solve(t, st, &c, 0.01, 1e-4, 9, rhs, x), 1e-12);
    t->free(st);
    ls_free(&c);
}

Test(linsol, klu_analyses_once_over_many_setups)
{
    ls_case c;
    ls_init(&c, 31);
    const cl_linsol_type *t = ls_find("klu");
    void *st = ls_create(t, &c, &(cl_integrator_opts){0});
    double rhs[LS_N], x[LS_N];
    const int nset = 60;
    for (int k = 0; k < nset; k++) {
        double h = 1e-3 * (1.0 + k % 7);
        ls_fill(&c, 1000 + (unsigned long)k, 1.0);
        x[0] = NAN;
        cr_assert_leq(ls_setup_solve(t, st, &c, h, h * h, (unsigned long)k,
                                     rhs, x), 1e-12);
    }
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_eq(s.lin_setups, nset);
    cr_assert_eq(s.lin_solves, nset);
    t->free(st);
    ls_free(&c);
}

/* The stiffness sign flipped: A = M - b L with L >= 0 large, so every
 * diagonal block is negative definite: the preconditioner setup fails. */
static void ls_indefinite_diag(const char *name)
{
    ls_case c;
    ls_init(&c, 8);
    ls_fill(&c, 8, -1.0);
    const cl_linsol_type *t = ls_find(name);
    cl_integrator_opts o = {0};
    cl_error err = {0};
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.0, 1.0, c.dfdx, c.dfdv, &err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "not positive definite"), "%s",
                       err.msg);
    double rhs[LS_N], x[LS_N];
    ls_rhs(1, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_EINVAL, "%s", err.msg);
    t->free(st);
    ls_free(&c);
}

Test(linsol, pcg_indefinite_fails_setup) { ls_indefinite_diag("pcg"); }
Test(linsol, pcg_jacobi_indefinite_fails_setup)
{
    ls_indefinite_diag("pcg-jacobi");
}

/* Positive diagonal blocks (M), coupling blocks 2 m I between neighbours
 * on the chain: A = M (I + 2 P) with P the path adjacency, whose smallest
 * eigenvalue is ~ 1 - 4 < 0.  Only CG's curvature check can tell. */
static void ls_indefinite_coupling(const char *name)
{
    ls_case c;
    ls_init(&c, 9);
    size_t nval = 9 * c.pat.nnzb;
    memset(c.dfdx, 0, nval * sizeof *c.dfdx);
    memset(c.dfdv, 0, nval * sizeof *c.dfdv);
    for (size_t i = 0; i < LS_N; i++)
        c.mass[i] = 1.0;
    for (int i = 0; i + 1 < LS_NB; i++) {
        long k1 = cl_bpattern_find(&c.pat, i, i + 1);
        long k2 = cl_bpattern_find(&c.pat, i + 1, i);
        for (int r = 0; r < 3; r++) {
            c.dfdx[9 * k1 + 4 * r] = -2.0;
            c.dfdx[9 * k2 + 4 * r] = -2.0;
        }
    }
    const cl_linsol_type *t = ls_find(name);
    cl_integrator_opts o = {0};
    cl_error err = {0};
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.0, 1.0, c.dfdx, c.dfdv, &err), CL_OK, "%s",
                 err.msg);
    ls_rhs(3, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_ESOLVER);
    cr_log_info("%s: %s", name, err.msg);
    cr_assert_not_null(strstr(err.msg, "not positive definite"), "%s",
                       err.msg);
    cr_assert_not_null(strstr(err.msg, "p^T A p"), "%s", err.msg);
    /* KLU solves the same (nonsingular, indefinite) matrix */
    const cl_linsol_type *k = ls_find("klu");
    void *kst = ls_create(k, &c, &o);
    cr_assert_leq(ls_setup_solve(k, kst, &c, 0.0, 1.0, 3, rhs, x), 1e-12);
    k->free(kst);
    t->free(st);
    ls_free(&c);
}

Test(linsol, pcg_indefinite_fails_solve) { ls_indefinite_coupling("pcg"); }
Test(linsol, pcg_jacobi_indefinite_fails_solve)
{
    ls_indefinite_coupling("pcg-jacobi");
}

Test(linsol, pcg_iteration_cap_reported)
{
    ls_case c;
    ls_init(&c, 12);
    const cl_linsol_type *t = ls_find("pcg-jacobi");
    cl_integrator_opts o = {.lin_maxit = 2};
    cl_error err = {0};
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err), CL_OK);
    ls_rhs(4, rhs);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "no convergence in 2 iterations"),
                       "%s", err.msg);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.lin_iters, 2);
    t->free(st);
    ls_free(&c);
}

Test(linsol, pcg_tolerance_option)
{
    ls_case c;
    ls_init(&c, 13);
    const cl_linsol_type *t = ls_find("pcg");
    double rhs[LS_N], x[LS_N], res[2];
    long iters[2];
    const double tol[2] = {1e-4, 1e-11};
    for (int k = 0; k < 2; k++) {
        void *st = ls_create(t, &c, &(cl_integrator_opts){.lin_tol = tol[k]});
        res[k] = ls_setup_solve(t, st, &c, 0.1, 0.01, 6, rhs, x);
        cl_stats s = {0};
        t->stats(st, &s);
        iters[k] = s.lin_iters;
        t->free(st);
        cr_log_info("pcg lin_tol %g: residual %.3e in %ld iterations",
                    tol[k], res[k], iters[k]);
        cr_assert_leq(res[k], tol[k] * 1.01);
    }
    cr_assert_lt(iters[0], iters[1]);
    ls_free(&c);
}

Test(linsol, pcg_zero_rhs_gives_zero)
{
    ls_case c;
    ls_init(&c, 14);
    const cl_linsol_type *t = ls_find("pcg");
    cl_integrator_opts o = {0};
    cl_error err = {0};
    double rhs[LS_N] = {0}, x[LS_N];
    for (size_t i = 0; i < LS_N; i++)
        x[i] = 1.0;
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err), CL_OK);
    cr_assert_eq(t->solve(st, rhs, x, &err), CL_OK, "%s", err.msg);
    for (size_t i = 0; i < LS_N; i++)
        cr_assert_eq(x[i], 0.0);
    t->free(st);
    ls_free(&c);
}

/* First A diagonally dominant (KLU pivots on the diagonal), then every
 * diagonal block zero: the refactorisation in the old pivot order meets an
 * exact zero pivot, and the setup must fall back to a fresh factorisation
 * (same symbolic analysis) that pivots off the diagonal. */
Test(linsol, klu_bad_refactor_falls_back)
{
    ls_case c;
    ls_init(&c, 17);
    const cl_linsol_type *t = ls_find("klu");
    cl_integrator_opts o = {0};
    cl_error err = {0};
    double rhs[LS_N], x[LS_N];
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.01, 1e-4, c.dfdx, c.dfdv, &err), CL_OK);
    unsigned long seed = 17;
    size_t nval = 9 * c.pat.nnzb;
    memset(c.dfdv, 0, nval * sizeof *c.dfdv);
    for (size_t k = 0; k < nval; k++)
        c.dfdx[k] = ls_rand(&seed);
    for (size_t i = 0; i < LS_NB; i++)
        for (int q = 0; q < 9; q++)
            c.dfdx[9 * c.pat.diag[i] + q] = q % 4 == 0 ? c.mass[3 * i + q / 4]
                                                       : 0.0;
    double res = ls_setup_solve(t, st, &c, 0.0, 1.0, 17, rhs, x);
    cr_log_info("klu after fall-back: relative residual %.3e", res);
    cr_assert_leq(res, 1e-10);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.symbolic_facts, 1);
    cr_assert_eq(s.lin_setups, 2);
    t->free(st);
    ls_free(&c);
}

Test(linsol, klu_singular_reported)
{
    ls_case c;
    ls_init(&c, 15);
    size_t nval = 9 * c.pat.nnzb;
    memset(c.dfdx, 0, nval * sizeof *c.dfdx);
    memset(c.dfdv, 0, nval * sizeof *c.dfdv);
    /* A = M - 1 * diag(m): the zero matrix on block 5 */
    for (size_t i = 0; i < LS_NB; i++)
        for (int r = 0; r < 3; r++)
            c.dfdx[9 * c.pat.diag[i] + 4 * r] = i == 5 ? c.mass[3 * i + r]
                                                       : 0.0;
    const cl_linsol_type *t = ls_find("klu");
    cl_integrator_opts o = {0};
    cl_error err = {0};
    void *st = ls_create(t, &c, &o);
    cr_assert_eq(t->setup(st, 0.0, 1.0, c.dfdx, c.dfdv, &err), CL_ESOLVER);
    cr_assert_not_null(strstr(err.msg, "singular"), "%s", err.msg);
    /* a regular matrix afterwards factorises again */
    ls_fill(&c, 15, 1.0);
    cr_assert_eq(t->setup(st, 0.1, 0.01, c.dfdx, c.dfdv, &err), CL_OK, "%s",
                 err.msg);
    cl_stats s = {0};
    t->stats(st, &s);
    cr_assert_eq(s.symbolic_facts, 1);
    t->free(st);
    ls_free(&c);
}

Test(linsol, rejects_bad_options)
{
    ls_case c;
    ls_init(&c, 16);
    cl_error err = {0};
    void *st = (void *)1;
    cl_integrator_opts o = {.lin_tol = -1.0};
    cr_assert_eq(ls_find("pcg")->create(&c.pat, c.mass, &o, &st, &err),
                 CL_EINVAL);
    cr_assert_null(st);
    o = (cl_integrator_opts){.lin_maxit = -3};
    cr_assert_eq(ls_find("pcg-jacobi")->create(&c.pat, c.mass, &o, &st,
                                               &err), CL_EINVAL);
    c.mass[7] = 0.0;
    o = (cl_integrator_opts){0};
    for (size_t k = 0; cl_linsol_registry[k]; k++) {
        st = (void *)1;
        cr_assert_eq(cl_linsol_registry[k]->create(&c.pat, c.mass, &o, &st,
                                                    &err), CL_EINVAL);
        cr_assert_null(st);
        cr_assert_not_null(strstr(err.msg, "mass[7]"), "%s", err.msg);
    }
    ls_free(&c);
}
