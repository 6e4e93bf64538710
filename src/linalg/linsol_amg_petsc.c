/* The plug-in's side of the algebraic-multigrid solvers amg and amg-hypre
 * (linalg/linsol_amg.c): PETSc's KSP CG preconditioned by PCGAMG
 * (smoothed aggregation) or by hypre's BoomerAMG (PCHYPRE), on a SeqAIJ
 * matrix of block size 3 whose pattern is built once from the block
 * pattern; later setups only overwrite its values in place.  Built into
 * clothode-petsc.so only; it calls nothing of the library: the block
 * pattern and values come in as plain arrays.
 *
 * Options are PETSc's own, under the prefix clamg_ (GAMG) or clamgh_
 * (hypre), set here unless the user set them first (PETSC_OPTIONS):
 *   GAMG   -pc_type gamg, block size 3, Chebyshev smoothing with point-block
 *          (3x3) Jacobi: -mg_levels_ksp_type chebyshev
 *          -mg_levels_pc_type pbjacobi;
 *   hypre  -pc_type hypre -pc_hypre_type boomeramg with nodal coarsening
 *          and the vector interpolation for systems of PDEs
 *          (-pc_hypre_boomeramg_nodal_coarsen 6
 *          -pc_hypre_boomeramg_vec_interp_variant 2).
 * The preconditioner is built on a SeqAIJ copy of A (GAMG's graph and
 * Galerkin products need it); when A is symmetric (clp_amg_setup's
 * `symmetric`), CG, the residuals of the multigrid cycle and the finest
 * smoother multiply by a SeqSBAIJ copy instead (3x3 blocks, diagonal and
 * upper blocks only: about a third of the AIJ's memory traffic, and these
 * products are bound by memory traffic).
 * The Krylov test is ||b - A x||_2 <= max(rtol ||b||_2, atol) from x = 0
 * (KSP_NORM_UNPRECONDITIONED).
 *
 * Reuse (clp_amg_setup's `rebuild` = 0): GAMG keeps its prolongators
 * (PCGAMGSetReuseInterpolation) and recomputes the Galerkin coarse
 * operators P^T A P and the smoothers on the new values; hypre cannot
 * keep its interpolation, so its reuse keeps the whole preconditioner
 * (KSPSetReusePreconditioner). */
#include <petscksp.h>
#include <stdio.h>

#include "linalg/plugin.h"

typedef struct {
    PetscInt n;             /* 3 nb */
    PetscInt nb;
    const size_t *rowptr;   /* borrowed: the block pattern */
    const size_t *col;
    Mat A;                  /* SeqAIJ, block size 3 */
    Mat S;                  /* SeqSBAIJ: upper and diagonal 3x3 blocks */
    Vec b, x;
    KSP ksp;
    int hypre;
} clp_amg;

int clp_amg_create(size_t nb, const size_t *rowptr, const size_t *col,
                   int hypre, long maxit, void **handle, cl_plugin_msg *msg);
int clp_amg_setup(void *handle, const double *ablk, int symmetric,
                  int rebuild, cl_plugin_msg *msg);
int clp_amg_solve(void *handle, const double *rhs, double *x, double rtol,
                  double atol, long *iters, cl_plugin_msg *msg);
void clp_amg_free(void *handle);

static int amg_fail(cl_plugin_msg *msg, const char *what, PetscErrorCode ec)
{
    const char *text = NULL;
    PetscErrorMessage(ec, &text, NULL);
    snprintf(msg->text, sizeof msg->text, "PETSc: %s failed (error %d: %s)",
             what, (int)ec, text ? text : "unknown");
    return 1;
}

/* Set -PREFIXname value unless the options database has it already. */
static PetscErrorCode amg_default(const char *prefix, const char *name,
                                  const char *value)
{
    char key[128];
    PetscBool set = PETSC_FALSE;
    snprintf(key, sizeof key, "-%s%s", prefix, name);
    PetscErrorCode ec = PetscOptionsHasName(NULL, NULL, key, &set);
    if (ec || set)
        return ec;
    return PetscOptionsSetValue(NULL, key, value);
}

static PetscErrorCode amg_options(const char *prefix, int hypre)
{
    static const char *const gamg[][2] = {
        {"pc_type", "gamg"},
        {"mg_levels_ksp_type", "chebyshev"},
        {"mg_levels_pc_type", "pbjacobi"},
    };
    static const char *const boomer[][2] = {
        {"pc_type", "hypre"},
        {"pc_hypre_type", "boomeramg"},
        {"pc_hypre_boomeramg_nodal_coarsen", "6"},
        {"pc_hypre_boomeramg_vec_interp_variant", "2"},
    };
    const char *const (*opt)[2] = hypre ? boomer : gamg;
    size_t nopt = hypre ? sizeof boomer / sizeof *boomer
                        : sizeof gamg / sizeof *gamg;
    for (size_t k = 0; k < nopt; k++) {
        PetscErrorCode ec = amg_default(prefix, opt[k][0], opt[k][1]);
        if (ec)
            return ec;
    }
    return 0;
}

/* A's scalar CSR pattern from the block pattern (rows 3i + r, columns
 * 3 col[k] + c), into a SeqAIJ of block size 3 with zero values. */
static PetscErrorCode amg_matrix(clp_amg *s, const size_t *col)
{
    size_t nnz = 9 * s->rowptr[s->nb];
    PetscInt *ia = NULL, *ja = NULL;
    PetscErrorCode ec = PetscMalloc2(s->n + 1, &ia, nnz, &ja);
    if (ec)
        return ec;
    ia[0] = 0;
    for (PetscInt i = 0; i < s->nb; i++)
        for (PetscInt r = 0; r < 3; r++) {
            PetscInt row = 3 * i + r, at = ia[row];
            for (size_t k = s->rowptr[i]; k < s->rowptr[i + 1]; k++)
                for (PetscInt c = 0; c < 3; c++)
                    ja[at++] = 3 * (PetscInt)col[k] + c;
            ia[row + 1] = at;
        }
    if (!(ec = MatCreate(PETSC_COMM_SELF, &s->A)) &&
        !(ec = MatSetSizes(s->A, s->n, s->n, s->n, s->n)) &&
        !(ec = MatSetBlockSize(s->A, 3)) &&
        !(ec = MatSetType(s->A, MATSEQAIJ)))
        ec = MatSeqAIJSetPreallocationCSR(s->A, ia, ja, NULL);
    PetscErrorCode ec2 = PetscFree2(ia, ja);
    return ec ? ec : ec2;
}

/* The SeqSBAIJ: block CSR of the blocks (i, j >= i), zero values. */
static PetscErrorCode amg_upper(clp_amg *s, const size_t *col)
{
    size_t nup = (s->rowptr[s->nb] + (size_t)s->nb) / 2;
    PetscInt *ib = NULL, *jb = NULL;
    PetscErrorCode ec = PetscMalloc2(s->nb + 1, &ib, nup, &jb);
    if (ec)
        return ec;
    ib[0] = 0;
    for (PetscInt i = 0; i < s->nb; i++) {
        PetscInt at = ib[i];
        for (size_t k = s->rowptr[i]; k < s->rowptr[i + 1]; k++)
            if (col[k] >= (size_t)i && (size_t)at < nup)
                jb[at++] = (PetscInt)col[k];
        ib[i + 1] = at;
    }
    if (!(ec = MatCreate(PETSC_COMM_SELF, &s->S)) &&
        !(ec = MatSetSizes(s->S, s->n, s->n, s->n, s->n)) &&
        !(ec = MatSetType(s->S, MATSEQSBAIJ)))
        ec = MatSeqSBAIJSetPreallocationCSR(s->S, 3, ib, jb, NULL);
    PetscErrorCode ec2 = PetscFree2(ib, jb);
    return ec ? ec : ec2;
}

static PetscErrorCode amg_ksp(clp_amg *s, long maxit)
{
    const char *prefix = s->hypre ? "clamgh_" : "clamg_";
    PetscErrorCode ec;
    if ((ec = amg_options(prefix, s->hypre)) ||
        (ec = MatCreateVecs(s->A, &s->x, &s->b)) ||
        (ec = KSPCreate(PETSC_COMM_SELF, &s->ksp)) ||
        (ec = KSPSetOptionsPrefix(s->ksp, prefix)) ||
        (ec = KSPSetType(s->ksp, KSPCG)) ||
        (ec = KSPSetNormType(s->ksp, KSP_NORM_UNPRECONDITIONED)) ||
        (ec = KSPSetTolerances(s->ksp, 1e-10, 0.0, PETSC_DEFAULT,
                               (PetscInt)maxit)) ||
        (ec = KSPSetOperators(s->ksp, s->A, s->A)))
        return ec;
    return KSPSetFromOptions(s->ksp);
}

void clp_amg_free(void *handle)
{
    clp_amg *s = handle;
    if (!s)
        return;
    KSPDestroy(&s->ksp);
    VecDestroy(&s->b);
    VecDestroy(&s->x);
    MatDestroy(&s->A);
    MatDestroy(&s->S);
    PetscFree(s);
}

int clp_amg_create(size_t nb, const size_t *rowptr, const size_t *col,
                   int hypre, long maxit, void **handle, cl_plugin_msg *msg)
{
    clp_amg *s = NULL;
    *handle = NULL;
    if (3 * nb > (size_t)PETSC_MAX_INT / 3 ||
        9 * rowptr[nb] > (size_t)PETSC_MAX_INT) {
        snprintf(msg->text, sizeof msg->text, "%zu blocks of %zu rows: too "
                 "many for PETSc's %zu-byte indices", rowptr[nb], nb,
                 sizeof(PetscInt));
        return 1;
    }
    PetscErrorCode ec = PetscNew(&s);
    if (ec)
        return amg_fail(msg, "PetscNew", ec);
    s->nb = (PetscInt)nb;
    s->n = 3 * s->nb;
    s->rowptr = rowptr;
    s->col = col;
    s->hypre = hypre;
    if ((ec = amg_matrix(s, col)) || (ec = amg_upper(s, col)))
        amg_fail(msg, "building the matrices", ec);
    else if ((ec = amg_ksp(s, maxit)))
        amg_fail(msg, "setting up the KSP", ec);
    if (ec) {
        clp_amg_free(s);
        return 1;
    }
    *handle = s;
    return 0;
}

/* Block k (row-major 3x3, row i) into row 3i + r of the CSR values. */
static PetscErrorCode amg_values(clp_amg *s, const double *ablk)
{
    PetscScalar *a;
    PetscErrorCode ec = MatSeqAIJGetArray(s->A, &a);
    if (ec)
        return ec;
    for (PetscInt i = 0; i < s->nb; i++) {
        size_t k0 = s->rowptr[i], len = 3 * (s->rowptr[i + 1] - k0);
        PetscScalar *row = a + 9 * k0;
        for (size_t k = k0; k < s->rowptr[i + 1]; k++)
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 3; c++)
                    row[r * len + 3 * (k - k0) + c] = ablk[9 * k + 3 * r + c];
    }
    return MatSeqAIJRestoreArray(s->A, &a);
}

/* The blocks (i, j >= i) into the SeqSBAIJ, each stored by columns. */
static PetscErrorCode amg_upper_values(clp_amg *s, const double *ablk)
{
    PetscScalar *a;
    PetscErrorCode ec = MatSeqSBAIJGetArray(s->S, &a);
    if (ec)
        return ec;
    for (PetscInt i = 0; i < s->nb; i++)
        for (size_t k = s->rowptr[i]; k < s->rowptr[i + 1]; k++) {
            if (s->col[k] < (size_t)i)
                continue;
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 3; c++)
                    a[3 * c + r] = ablk[9 * k + 3 * r + c];
            a += 9;
        }
    return MatSeqSBAIJRestoreArray(s->S, &a);
}

int clp_amg_setup(void *handle, const double *ablk, int symmetric,
                  int rebuild, cl_plugin_msg *msg)
{
    clp_amg *s = handle;
    PC pc;
    PetscErrorCode ec;
    if ((ec = amg_values(s, ablk)) ||
        (symmetric && (ec = amg_upper_values(s, ablk))))
        return amg_fail(msg, "writing the matrix values", ec);
    if ((ec = KSPGetPC(s->ksp, &pc)))
        return amg_fail(msg, "KSPGetPC", ec);
    if (s->hypre)
        ec = KSPSetReusePreconditioner(s->ksp, rebuild ? PETSC_FALSE
                                                       : PETSC_TRUE);
    else
        ec = PCGAMGSetReuseInterpolation(pc, rebuild ? PETSC_FALSE
                                                     : PETSC_TRUE);
    if (ec)
        return amg_fail(msg, "setting the reuse", ec);
    if ((ec = KSPSetOperators(s->ksp, symmetric ? s->S : s->A, s->A)) ||
        (ec = KSPSetUp(s->ksp)))
        return amg_fail(msg, "the multigrid setup (KSPSetUp)", ec);
    return 0;
}

int clp_amg_solve(void *handle, const double *rhs, double *x, double rtol,
                  double atol, long *iters, cl_plugin_msg *msg)
{
    clp_amg *s = handle;
    PetscErrorCode ec;
    PetscScalar *p;
    KSPConvergedReason why;
    PetscInt its = 0;
    PetscReal res = 0.0;
    *iters = 0;
    if ((ec = VecGetArray(s->b, &p)))
        return amg_fail(msg, "VecGetArray", ec);
    for (PetscInt i = 0; i < s->n; i++)
        p[i] = rhs[i];
    if ((ec = VecRestoreArray(s->b, &p)) ||
        (ec = KSPSetTolerances(s->ksp, rtol, atol, PETSC_DEFAULT,
                               PETSC_DEFAULT)) ||
        (ec = KSPSolve(s->ksp, s->b, s->x)) ||
        (ec = KSPGetConvergedReason(s->ksp, &why)) ||
        (ec = KSPGetIterationNumber(s->ksp, &its)) ||
        (ec = KSPGetResidualNorm(s->ksp, &res)))
        return amg_fail(msg, "KSPSolve", ec);
    *iters = its;
    if (why <= 0) {
        snprintf(msg->text, sizeof msg->text, "CG stopped after %d "
                 "iterations: %s (residual %.6g)%s", (int)its,
                 KSPConvergedReasons[why], (double)res,
                 why == KSP_DIVERGED_INDEFINITE_MAT ||
                         why == KSP_DIVERGED_INDEFINITE_PC
                     ? ": the matrix M - a df/dv - b df/dx (or its "
                       "multigrid preconditioner) is not positive definite"
                     : "");
        return 1;
    }
    const PetscScalar *q;
    if ((ec = VecGetArrayRead(s->x, &q)))
        return amg_fail(msg, "VecGetArrayRead", ec);
    for (PetscInt i = 0; i < s->n; i++)
        x[i] = q[i];
    VecRestoreArrayRead(s->x, &q);
    return 0;
}
