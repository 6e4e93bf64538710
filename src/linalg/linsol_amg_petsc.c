/* The plug-in's side of the algebraic-multigrid solvers amg and amg-hypre
 * (linalg/linsol_amg.c): PETSc's KSP CG preconditioned by PCGAMG
 * (smoothed aggregation) or by hypre's BoomerAMG (PCHYPRE).  Built into
 * clothode-petsc.so only; it calls nothing of the library: the block
 * pattern and values come in as plain arrays, and the product y = A x and
 * the finest level's sweep as callbacks (clp_amg_mult, clp_amg_sweep).
 *
 * Two matrices.  The operator (KSP's Amat) is a MATSHELL whose product is the
 * caller's: CG (and the finest level's residual, where the smoother did not
 * form it) multiply through it (the library's block product reads, for a
 * symmetric A, only the diagonal and upper 3x3 blocks, each by its 6
 * distinct entries: under a third of the bytes of a SeqAIJ product, and
 * these products are bound by memory traffic).  The preconditioner is built
 * on a SeqAIJ copy of A of block size 3 (Pmat: GAMG's graph and Galerkin
 * products, hypre) whose pattern is built once from the block pattern; each
 * setup that builds or recomputes the preconditioner writes its values in
 * place.
 *
 * GAMG's finest level is smoothed by the caller's block Gauss-Seidel
 * sweeps (clp_amg_sweep, linalg/blockgs.h) on its own storage: a
 * backward sweep from x = 0 before the coarse correction, which also
 * forms the residual b - A x the cycle restricts (PCMGSetResidual), and
 * a forward sweep after it, the adjoint of the first, so the cycle stays
 * symmetric; each a PCSHELL's PCApplyRichardson under one step of
 * KSPRICHARDSON (amg_fine_gs).  Per CG iteration that reads the fine
 * matrix three times (CG's product and the two sweeps) where the
 * degree-2 Chebyshev smoother read it five times, and a setup needs no
 * eigenvalue estimate on that level (the caller inverts the diagonal
 * blocks).  The coarser levels keep GAMG's own smoothers.
 *
 * Options are PETSc's own, under the prefix clamg_ (GAMG) or clamgh_
 * (hypre), set here unless the user set them first (PETSC_OPTIONS):
 *   GAMG   -pc_type gamg, block size 3, one Chebyshev step with
 *          point-block (3x3) Jacobi on the coarser levels (the finest:
 *          above): -mg_levels_ksp_type chebyshev -mg_levels_ksp_max_it 1
 *          -mg_levels_pc_type pbjacobi (degree 2, PETSc's default, makes
 *          the same number of CG iterations on hang and costs 4-6 % more
 *          time a step at n = 128 and 256: paper/findings.md);
 *          and, without a prefix (GAMG's Galerkin products have none),
 *          -matptap_via rap: P^T A P as the triple product R A P of a
 *          stored transpose R = P^T, the same operators as the default's
 *          in about half its time (hang, n = 256, paper/findings.md);
 *   hypre  -pc_type hypre -pc_hypre_type boomeramg with nodal coarsening
 *          and the vector interpolation for systems of PDEs
 *          (-pc_hypre_boomeramg_nodal_coarsen 6
 *          -pc_hypre_boomeramg_vec_interp_variant 2).
 * The Krylov test is ||b - A x||_2 <= max(rtol ||b||_2, atol) from x = 0
 * (KSP_NORM_UNPRECONDITIONED).  The right-hand side and the solution are
 * the caller's arrays (VecPlaceArray), not copies.
 *
 * Reuse (clp_amg_setup's `mode`, linalg/linsol_amg_abi.h): CLP_AMG_GALERKIN
 * keeps GAMG's prolongators (PCGAMGSetReuseInterpolation) and recomputes
 * the Galerkin coarse operators P^T A P and the smoothers on the new
 * values; CLP_AMG_SMOOTHER keeps the whole preconditioner
 * (KSPSetReusePreconditioner): the finest level's sweeps read the
 * caller's new values, and nothing here is set up again (nor is the
 * SeqAIJ copy written).  hypre cannot keep its interpolation, and kept
 * whole its finest relaxation sweeps the old matrix: amg-hypre is set up
 * with CLP_AMG_BUILD only.
 *
 * Eigenvalue bounds.  The SeqAIJ copy is marked symmetric positive
 * definite (MAT_SPD, for good: CG needs it so; MAT_SPD_ETERNAL needs
 * PETSc 3.18), and GAMG's Galerkin operators inherit the mark; Chebyshev
 * then estimates the largest eigenvalue of D^-1 A on every coarser level
 * (and on the finest in a setup that builds or recomputes the hierarchy,
 * which sets that level's smoothers up from the options before
 * amg_fine_gs replaces them: 10 products a build) by
 * Lanczos (CG, 10 steps) instead of GMRES, whose 10 steps on the
 * nonsymmetric D^-1 A fell 17 % short of the finest level's largest
 * eigenvalue on hang at n = 64 and 256 (against 300 Lanczos steps;
 * paper/findings.md, "Algebraic multigrid").  The bound used is 1.1
 * times the estimate, and a Chebyshev smoother over [0.1, 1.1] times the
 * estimate stops contracting in the energy norm above 1.2 times it: there
 * the residual polynomial of one step, 1 - t/0.6 (t in units of the
 * estimate), is at -1, that of two steps back at +1 (its value at 0), and
 * beyond either exceeds 1 in modulus; an estimate short by more than that
 * made the multigrid cycle indefinite.  CLP_AMG_RECOVER rebuilds the
 * hierarchy and estimates every level's bound with CLP_AMG_RECOVER_STEPS
 * Lanczos steps, once, in the build (kept by those levels until the next
 * build, which restores the steps before). */
#include <petscksp.h>
#include <stdio.h>

#include "linalg/linsol_amg_abi.h"

typedef struct clp_amg clp_amg;

/* The context of a finest-level smoother: the solver, and which sweep. */
typedef struct {
    clp_amg *s;
    int forward;
} clp_amg_gs;

struct clp_amg {
    PetscInt n;             /* 3 nb */
    PetscInt nb;
    const size_t *rowptr;   /* borrowed: the block pattern */
    Mat A;                  /* SeqAIJ, block size 3: the preconditioner's */
    Mat op;                 /* MATSHELL: the caller's product */
    clp_amg_mult mult;
    clp_amg_sweep sweep;
    void *ctx;
    Vec res;                /* the finest level's residual, array resv */
    PetscScalar *resv;
    Vec swb, swx;           /* the pre-smoother's b and x while res = b -
                             * A x holds for them; swx NULL: it does not */
    Vec b, x;               /* without arrays: the caller's are placed */
    KSP ksp;
    int hypre;
    PetscInt est_steps;     /* the estimates' Lanczos steps before a
                             * recovery raised them; 0: never raised */
    clp_amg_gs gs[2];       /* the backward and forward sweeps' contexts */
};

int clp_amg_create(size_t nb, const size_t *rowptr, const size_t *col,
                   int hypre, long maxit, clp_amg_mult mult,
                   clp_amg_sweep sweep, void *ctx, void **handle,
                   cl_plugin_msg *msg);
int clp_amg_setup(void *handle, const double *ablk, int mode,
                  cl_plugin_msg *msg);
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
        {"mg_levels_ksp_max_it", "1"},
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
    /* GAMG's Galerkin products P^T A P as R A P with R = P^T stored: the
     * same coarse operators in about half the time at n = 256.  The
     * product matrices GAMG makes carry no prefix, so the option is the
     * process's */
    return hypre ? 0 : amg_default("", "matptap_via", "rap");
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
        !(ec = MatSetType(s->A, MATSEQAIJ)) &&
        !(ec = MatSeqAIJSetPreallocationCSR(s->A, ia, ja, NULL)) &&
        !(ec = MatSetOption(s->A, MAT_SPD, PETSC_TRUE)))
        ec = MatSetOption(s->A, MAT_SPD_ETERNAL, PETSC_TRUE);
    PetscErrorCode ec2 = PetscFree2(ia, ja);
    return ec ? ec : ec2;
}

static PetscErrorCode amg_shell_mult(Mat op, Vec x, Vec y)
{
    clp_amg *s = NULL;
    const PetscScalar *xp;
    PetscScalar *yp;
    PetscErrorCode ec = MatShellGetContext(op, &s);
    if (ec || (ec = VecGetArrayRead(x, &xp)))
        return ec;
    if ((ec = VecGetArrayWrite(y, &yp))) {
        VecRestoreArrayRead(x, &xp);
        return ec;
    }
    s->mult(s->ctx, xp, yp);
    if ((ec = VecRestoreArrayWrite(y, &yp)))
        return ec;
    return VecRestoreArrayRead(x, &xp);
}

/* The operator: a MATSHELL of block size 3 calling s->mult. */
static PetscErrorCode amg_shell(clp_amg *s)
{
    PetscErrorCode ec;
    if ((ec = MatCreateShell(PETSC_COMM_SELF, s->n, s->n, s->n, s->n, s,
                             &s->op)) ||
        (ec = MatSetBlockSize(s->op, 3)))
        return ec;
    return MatShellSetOperation(s->op, MATOP_MULT,
                                (void (*)(void))amg_shell_mult);
}

static PetscErrorCode amg_ksp(clp_amg *s, long maxit)
{
    const char *prefix = s->hypre ? "clamgh_" : "clamg_";
    PetscErrorCode ec;
    if ((ec = amg_options(prefix, s->hypre)) ||
        (ec = VecCreateSeqWithArray(PETSC_COMM_SELF, 3, s->n, NULL,
                                    &s->b)) ||
        (ec = VecCreateSeqWithArray(PETSC_COMM_SELF, 3, s->n, NULL,
                                    &s->x)) ||
        (ec = KSPCreate(PETSC_COMM_SELF, &s->ksp)) ||
        (ec = KSPSetOptionsPrefix(s->ksp, prefix)) ||
        (ec = KSPSetType(s->ksp, KSPCG)) ||
        (ec = KSPSetNormType(s->ksp, KSP_NORM_UNPRECONDITIONED)) ||
        (ec = KSPSetTolerances(s->ksp, 1e-10, 0.0, PETSC_DEFAULT,
                               (PetscInt)maxit)) ||
        (ec = KSPSetOperators(s->ksp, s->op, s->A)))
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
    MatDestroy(&s->op);
    VecDestroy(&s->res);
    PetscFree(s->resv);
    PetscFree(s);
}

int clp_amg_create(size_t nb, const size_t *rowptr, const size_t *col,
                   int hypre, long maxit, clp_amg_mult mult,
                   clp_amg_sweep sweep, void *ctx, void **handle,
                   cl_plugin_msg *msg)
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
    s->mult = mult;
    s->sweep = sweep;
    s->ctx = ctx;
    s->gs[0] = (clp_amg_gs){.s = s, .forward = 0};
    s->gs[1] = (clp_amg_gs){.s = s, .forward = 1};
    s->hypre = hypre;
    if ((ec = amg_matrix(s, col)) || (ec = amg_shell(s)) ||
        (ec = PetscMalloc1(s->n, &s->resv)) ||
        (ec = VecCreateSeqWithArray(PETSC_COMM_SELF, 3, s->n, s->resv,
                                    &s->res)))
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

/* A finest-level smoother (PCShellSetApplyRichardson): one sweep of the
 * caller's, backward from x = 0 before the coarse correction, forward from
 * x after it.  The backward sweep also leaves the residual b - A x in
 * s->res (linalg/blockgs.h), marked valid for these b and x until the
 * residual is asked for (amg_residual) or x is swept again. */
static PetscErrorCode amg_gs_apply(PC pc, Vec b, Vec x, Vec w, PetscReal rtol,
                                   PetscReal atol, PetscReal dtol,
                                   PetscInt its, PetscBool zero,
                                   PetscInt *outits,
                                   PCRichardsonConvergedReason *why)
{
    clp_amg_gs *g = NULL;
    const PetscScalar *bp;
    PetscScalar *xp;
    (void)w, (void)rtol, (void)atol, (void)dtol;
    PetscCall(PCShellGetContext(pc, &g));
    clp_amg *s = g->s;
    PetscCheck(its == 1 && (zero || g->forward), PETSC_COMM_SELF,
               PETSC_ERR_SUP, "the block Gauss-Seidel smoother makes one "
               "sweep, the backward one from x = 0 (%d sweeps, %s sweep, "
               "zero guess %d asked)", (int)its,
               g->forward ? "forward" : "backward", (int)zero);
    s->swx = NULL;
    if (zero && g->forward)
        PetscCall(VecZeroEntries(x));
    PetscCall(VecGetArrayRead(b, &bp));
    PetscCall(VecGetArray(x, &xp));
    s->sweep(s->ctx, g->forward, bp, xp, g->forward ? NULL : s->resv);
    PetscCall(VecRestoreArray(x, &xp));
    PetscCall(VecRestoreArrayRead(b, &bp));
    if (!g->forward) {
        s->swb = b;
        s->swx = x;
    }
    *outits = 1;
    *why = PCRICHARDSON_CONVERGED_ITS;
    return 0;
}

/* The finest level's residual r = b - A x: the pre-smoother's, if b and x
 * are the vectors it swept last (PCMG's V-cycle asks for the residual
 * right after the pre-smoother, and changes neither vector in between:
 * PCMGMCycle_Private), once; else by a product. */
static PetscErrorCode amg_residual(Mat op, Vec b, Vec x, Vec r)
{
    clp_amg *s = NULL;
    PetscCall(MatShellGetContext(op, &s));
    int fused = s->swx && b == s->swb && x == s->swx;
    s->swx = NULL;
    if (!fused)
        return PCMGResidualDefault(op, b, x, r);
    return r == s->res ? 0 : VecCopy(s->res, r);
}

/* Smoother k of the finest level: one Richardson step whose preconditioner
 * is the caller's sweep (a shell's PCApplyRichardson, which KSPRICHARDSON
 * calls in place of its own step), on the shell operator; forward: the
 * post-smoother, from the guess the coarse correction left. */
static PetscErrorCode amg_gs_ksp(clp_amg *s, KSP k, int forward)
{
    PC pc;
    PetscCall(KSPSetType(k, KSPRICHARDSON));
    PetscCall(KSPSetTolerances(k, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT,
                               1));
    PetscCall(KSPSetNormType(k, KSP_NORM_NONE));
    PetscCall(KSPSetConvergenceTest(k, KSPConvergedSkip, NULL, NULL));
    PetscCall(KSPSetInitialGuessNonzero(k, forward ? PETSC_TRUE
                                                   : PETSC_FALSE));
    PetscCall(KSPGetPC(k, &pc));
    PetscCall(PCSetType(pc, PCSHELL));
    PetscCall(PCShellSetContext(pc, &s->gs[forward]));
    PetscCall(PCShellSetName(pc, forward ? "forward block Gauss-Seidel "
                                           "(clothode)"
                                         : "backward block Gauss-Seidel "
                                           "(clothode)"));
    PetscCall(PCShellSetApplyRichardson(pc, amg_gs_apply));
    PetscCall(KSPSetOperators(k, s->op, s->A));
    return KSPSetUp(k);
}

/* After a setup that made or recomputed the hierarchy: the finest level's
 * smoothers are the caller's block Gauss-Seidel sweeps, backward before
 * the coarse correction and forward after it (its adjoint: the cycle
 * stays symmetric), and its residual the pre-smoother's.  They need no
 * setup of their own later (the caller inverts its diagonal blocks), and
 * no eigenvalue bound.  A hierarchy of one level keeps GAMG's smoother. */
static PetscErrorCode amg_fine_gs(clp_amg *s, PC pc)
{
    PetscInt levels = 0;
    KSP down, up;
    PetscCall(PCMGGetLevels(pc, &levels));
    if (levels < 2)
        return 0;
    PetscCall(PCMGGetSmootherDown(pc, levels - 1, &down));
    PetscCall(PCMGGetSmootherUp(pc, levels - 1, &up));
    PetscCall(amg_gs_ksp(s, down, 0));
    PetscCall(amg_gs_ksp(s, up, 1));
    PetscCall(PCMGSetR(pc, levels - 1, s->res));
    s->swx = NULL;
    return PCMGSetResidual(pc, levels - 1, amg_residual, s->op);
}

/* Level l's Chebyshev smoother and its eigenvalue estimator; *est NULL
 * if the level has none. */
static PetscErrorCode amg_estimator(PC pc, PetscInt l, KSP *smooth, KSP *est)
{
    PetscBool cheb = PETSC_FALSE;
    PetscErrorCode ec;
    *est = NULL;
    if ((ec = PCMGGetSmoother(pc, l, smooth)) ||
        (ec = PetscObjectTypeCompare((PetscObject)*smooth, KSPCHEBYSHEV,
                                     &cheb)) || !cheb)
        return ec;
    return KSPChebyshevEstEigGetKSP(*smooth, est);
}

/* A recovery's bounds: every Chebyshev smoother's estimator raised to
 * CLP_AMG_RECOVER_STEPS Lanczos steps (s->est_steps keeps the number
 * before), reset first: CG sized its arrays of Lanczos coefficients by
 * the max_it of its first setup.  Called before the recovery's build, so
 * that the build's own estimates take those steps: a build with as many
 * levels as before keeps their smoothers (PCMGSetLevels), whose bounds it
 * estimates anew on the new operators, once.  Called again after it
 * (estimate): a build with another number of levels made new smoothers,
 * estimated with the steps of the options; those alone are raised, and
 * KSPChebyshevEstEigSet with the transform unchanged (PETSC_DECIDE)
 * forgets their estimate and their operators set again make KSPSetUp
 * make a new one.  The smoothers keep these steps until the next build
 * (amg_plain_bounds). */
static PetscErrorCode amg_careful_bounds(clp_amg *s, PC pc, int estimate)
{
    PetscInt levels = 0;
    PetscErrorCode ec = PCMGGetLevels(pc, &levels);
    for (PetscInt l = 1; !ec && l < levels; l++) {
        KSP smooth, est;
        Mat op, pmat;
        PetscInt steps = 0;
        if ((ec = amg_estimator(pc, l, &smooth, &est)) || !est ||
            (ec = KSPGetTolerances(est, NULL, NULL, NULL, &steps)) ||
            steps == CLP_AMG_RECOVER_STEPS)
            continue;
        if (!s->est_steps)
            s->est_steps = steps;
        if ((ec = KSPReset(est)) ||
            (ec = KSPSetTolerances(est, PETSC_DEFAULT, PETSC_DEFAULT,
                                   PETSC_DEFAULT, CLP_AMG_RECOVER_STEPS)) ||
            !estimate)
            continue;
        if (!(ec = KSPChebyshevEstEigSet(smooth, PETSC_DECIDE, PETSC_DECIDE,
                                         PETSC_DECIDE, PETSC_DECIDE)) &&
            !(ec = KSPGetOperators(smooth, &op, &pmat)) &&
            !(ec = KSPSetOperators(smooth, op, pmat)))
            ec = KSPSetUp(smooth);
    }
    return ec;
}

/* Before a build: the estimators back to their steps before a recovery
 * raised them (fewer steps fit the arrays sized for more). */
static PetscErrorCode amg_plain_bounds(clp_amg *s, PC pc)
{
    PetscInt levels = 0;
    PetscErrorCode ec = s->est_steps ? PCMGGetLevels(pc, &levels) : 0;
    for (PetscInt l = 1; !ec && l < levels; l++) {
        KSP smooth, est;
        if (!(ec = amg_estimator(pc, l, &smooth, &est)) && est)
            ec = KSPSetTolerances(est, PETSC_DEFAULT, PETSC_DEFAULT,
                                  PETSC_DEFAULT, s->est_steps);
    }
    if (!ec)
        s->est_steps = 0;
    return ec;
}

int clp_amg_setup(void *handle, const double *ablk, int mode,
                  cl_plugin_msg *msg)
{
    clp_amg *s = handle;
    PC pc;
    PetscErrorCode ec;
    /* GAMG's smoother-only refresh keeps the whole preconditioner but the
     * finest smoother (hypre is only ever built) */
    int build = mode == CLP_AMG_BUILD || mode == CLP_AMG_RECOVER;
    int keep = mode == CLP_AMG_SMOOTHER;
    /* a kept preconditioner does not read the SeqAIJ copy (GAMG's finest
     * smoother sweeps the caller's storage) */
    if (!keep && (ec = amg_values(s, ablk)))
        return amg_fail(msg, "writing the matrix values", ec);
    if ((ec = KSPGetPC(s->ksp, &pc)))
        return amg_fail(msg, "KSPGetPC", ec);
    ec = KSPSetReusePreconditioner(s->ksp, keep ? PETSC_TRUE : PETSC_FALSE);
    if (!ec && !s->hypre)
        ec = PCGAMGSetReuseInterpolation(pc, build ? PETSC_FALSE
                                                   : PETSC_TRUE);
    if (ec)
        return amg_fail(msg, "setting the reuse", ec);
    if (mode == CLP_AMG_BUILD && !s->hypre && (ec = amg_plain_bounds(s, pc)))
        return amg_fail(msg, "the smoothers' eigenvalue estimates", ec);
    if (mode == CLP_AMG_RECOVER && !s->hypre &&
        (ec = amg_careful_bounds(s, pc, 0)))
        return amg_fail(msg, "the smoothers' eigenvalue estimates", ec);
    if ((ec = KSPSetOperators(s->ksp, s->op, s->A)) ||
        (ec = KSPSetUp(s->ksp)))
        return amg_fail(msg, "the multigrid setup (KSPSetUp)", ec);
    if (!keep && !s->hypre && (ec = amg_fine_gs(s, pc)))
        return amg_fail(msg, "the finest smoother's setup", ec);
    if (mode == CLP_AMG_RECOVER && !s->hypre &&
        (ec = amg_careful_bounds(s, pc, 1)))
        return amg_fail(msg, "the smoothers' eigenvalue estimates", ec);
    return 0;
}

/* CG's outcome: 0 if it converged, else 1 with the message. */
static int amg_outcome(clp_amg *s, long *iters, cl_plugin_msg *msg)
{
    KSPConvergedReason why;
    PetscInt its = 0;
    PetscReal res = 0.0;
    PetscErrorCode ec;
    if ((ec = KSPGetConvergedReason(s->ksp, &why)) ||
        (ec = KSPGetIterationNumber(s->ksp, &its)) ||
        (ec = KSPGetResidualNorm(s->ksp, &res)))
        return amg_fail(msg, "KSPSolve", ec);
    *iters = its;
    if (why > 0)
        return 0;
    /* on an indefinite matrix a part of the cycle can fail to set up (a
     * point-block Jacobi or the coarse factorisation meeting a singular
     * or indefinite block): CG then reports the preconditioner failed,
     * and the PC says why */
    PC pc;
    PCFailedReason pcwhy = PC_NOERROR;
    if (why == KSP_DIVERGED_PC_FAILED &&
        ((ec = KSPGetPC(s->ksp, &pc)) || (ec = PCGetFailedReason(pc, &pcwhy))))
        return amg_fail(msg, "KSPSolve", ec);
    snprintf(msg->text, sizeof msg->text, "CG stopped after %d iterations: "
             "%s%s%s (residual %.6g)%s", (int)its, KSPConvergedReasons[why],
             pcwhy != PC_NOERROR ? " " : "",
             pcwhy != PC_NOERROR ? PCFailedReasons[pcwhy] : "", (double)res,
             why == KSP_DIVERGED_INDEFINITE_MAT ||
                     why == KSP_DIVERGED_INDEFINITE_PC ||
                     why == KSP_DIVERGED_PC_FAILED
                 ? ": the matrix M - a df/dv - b df/dx (or its multigrid "
                   "preconditioner) is not positive definite"
                 : "");
    return 1;
}

int clp_amg_solve(void *handle, const double *rhs, double *x, double rtol,
                  double atol, long *iters, cl_plugin_msg *msg)
{
    clp_amg *s = handle;
    PetscErrorCode ec;
    *iters = 0;
    if ((ec = VecPlaceArray(s->b, rhs)))
        return amg_fail(msg, "VecPlaceArray", ec);
    if ((ec = VecPlaceArray(s->x, x))) {
        VecResetArray(s->b);
        return amg_fail(msg, "VecPlaceArray", ec);
    }
    if (!(ec = KSPSetTolerances(s->ksp, rtol, atol, PETSC_DEFAULT,
                                PETSC_DEFAULT)))
        ec = KSPSolve(s->ksp, s->b, s->x);
    VecResetArray(s->b);
    VecResetArray(s->x);
    if (ec)
        return amg_fail(msg, "KSPSolve", ec);
    return amg_outcome(s, iters, msg);
}
