/* The plug-in's side of the petsc-ts integrators (integrators/petsc_ts.h,
 * the entry points of integrators/petsc_ts_abi.h; docs/integrators.md,
 * "PETSc TS").  Built into clothode-petsc.so only; it calls nothing of the
 * library: the model comes in as its pattern, masses and two callbacks.
 *
 * First-order methods (TSBDF, TSARKIMEX fully implicit, TSROSW) solve
 * the implicit form on y = (x, v), 2n unknowns,
 *
 *   F(t, y, y') = [x' - v; v' - M^-1 f(t, x, v)] = 0,
 *   dF/dy + a dF/dy' = [[a I, -I], [-M^-1 df/dx, a I - M^-1 df/dv]],
 *
 * y' with the identity (TSARKIMEX's tableaux with an explicit first stage
 * need F = y' + G(t, y); with M v' in F they are wrong);
 * TSALPHA2 (Chung and Hulbert, "A time integration algorithm for
 * structural dynamics with improved numerical dissipation: the
 * generalized-alpha method", 1993) the second-order form on x, n unknowns,
 *
 *   F(t, x, x', x'') = M x'' - f(t, x, x') = 0,
 *   dF/dx + s_v dF/dx' + s_a dF/dx'' = s_a M - s_v df/dv - df/dx,
 *
 * the half-size matrix of docs/integrators.md.  Either matrix is a
 * SeqAIJ whose pattern is built once from the block pattern; the slot of
 * every value in its value array is looked up once, and each Jacobian
 * writes its values straight into them.  Nothing is allocated per step on
 * this side. */
#include <petscts.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "integrators/petsc_ts_abi.h"

/* Under AddressSanitizer: PETSc 3.18 leaks the 32 bytes of an options
 * item when TSSetFromOptions fails on a bad value (an error return skips
 * its PetscOptionsEnd), e.g. --petsc "-ts_bdf_order 9"; LeakSanitizer
 * ignores what that one call allocates, and nothing else. */
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define OPTIONS_READ_BEGIN() __lsan_disable()
#define OPTIONS_READ_END() __lsan_enable()
#else
#define OPTIONS_READ_BEGIN() ((void)0)
#define OPTIONS_READ_END() ((void)0)
#endif

int clp_ts_create(const clp_ts_setup *s, void **ts, cl_plugin_msg *msg);
int clp_ts_advance(void *ts, double t_out, double *x, double *v,
                   cl_plugin_msg *msg);
int clp_ts_restart(void *ts, cl_plugin_msg *msg);
void clp_ts_stats(const void *ts, cl_stats *st);
void clp_ts_free(void *ts);

typedef struct {
    clp_ts_setup s;       /* the library's set-up (its arrays stay its) */
    TS ts;
    Mat J;
    Vec y, yv;            /* y = (x, v), or x and v (second order) */
    PetscOptions opts;    /* --petsc, this integrator's own */
    char bad_option[400]; /* every_option_read's refusal, after step 1 */
    PetscScalar *dfdx, *dfdv;    /* 9 nnzb each */
    PetscInt *slot_x, *slot_v;   /* 9 nnzb: where -df/dx, -df/dv go */
    PetscInt *slot_m;            /* n: the diagonal the shift adds to */
    size_t *row_of;              /* 9 nnzb: the unknown of each value */
    PetscInt *slot_xx, *slot_xv; /* n: a I and -I (first order) */
    int cb;               /* the last callback's status */
    char linsol[32];      /* "petsc:KSP+PC" as set up */
    long steps, nfun, njac, nsolve, nkspit, nnewton, nsnesfail, nreject;
} clp_ts;

/* ---- pattern and slots ------------------------------------------------- */

/* Unknowns and the first row of the force rows. */
static PetscInt nrows(const clp_ts *p)
{
    return (PetscInt)(p->s.second_order ? p->s.n : 2 * p->s.n);
}

static PetscInt force_row0(const clp_ts *p)
{
    return p->s.second_order ? 0 : (PetscInt)p->s.n;
}

/* The columns of row r (cols: room for 6 nnzb / nb + 2), returned count. */
static PetscInt row_cols(const clp_ts *p, PetscInt r, PetscInt *cols)
{
    const clp_ts_setup *s = &p->s;
    PetscInt n = (PetscInt)s->n, r0 = force_row0(p), c = 0;
    if (r < r0) { /* x' - v */
        cols[0] = r;
        cols[1] = n + r;
        return 2;
    }
    size_t i = (size_t)(r - r0) / 3;
    for (size_t k = s->rowptr[i]; k < s->rowptr[i + 1]; k++)
        for (PetscInt b = 0; b < 3; b++)
            cols[c++] = 3 * (PetscInt)s->col[k] + b;
    if (!s->second_order)
        for (size_t k = s->rowptr[i]; k < s->rowptr[i + 1]; k++)
            for (PetscInt b = 0; b < 3; b++)
                cols[c++] = n + 3 * (PetscInt)s->col[k] + b;
    return c;
}

static PetscErrorCode make_matrix(clp_ts *p)
{
    PetscInt N = nrows(p), maxrow = 2, *nnz, *cols;
    PetscScalar *zero;
    PetscFunctionBeginUser;
    for (size_t i = 0; i < p->s.nb; i++) {
        PetscInt len = 6 * (PetscInt)(p->s.rowptr[i + 1] - p->s.rowptr[i]);
        maxrow = len > maxrow ? len : maxrow;
    }
    PetscCall(PetscMalloc1(N, &nnz));
    PetscCall(PetscMalloc1(maxrow, &cols));
    PetscCall(PetscCalloc1(maxrow, &zero));
    for (PetscInt r = 0; r < N; r++)
        nnz[r] = row_cols(p, r, cols);
    PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, N, N, 0, nnz, &p->J));
    for (PetscInt r = 0; r < N; r++)
        PetscCall(MatSetValues(p->J, 1, &r, row_cols(p, r, cols), cols, zero,
                               INSERT_VALUES));
    PetscCall(MatAssemblyBegin(p->J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(p->J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatSetOption(p->J, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE));
    PetscCall(PetscFree(nnz));
    PetscCall(PetscFree(cols));
    PetscCall(PetscFree(zero));
    PetscFunctionReturn(0);
}

/* Index of (r, c) in the CSR arrays ia, ja (present by construction). */
static PetscInt find_slot(const PetscInt *ia, const PetscInt *ja, PetscInt r,
                          PetscInt c)
{
    PetscInt lo = ia[r], hi = ia[r + 1] - 1;
    while (lo < hi) {
        PetscInt mid = (lo + hi) / 2;
        if (ja[mid] < c)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

static void fill_slots(clp_ts *p, const PetscInt *ia, const PetscInt *ja)
{
    const clp_ts_setup *s = &p->s;
    PetscInt n = (PetscInt)s->n, r0 = force_row0(p),
             vo = s->second_order ? 0 : n;
    for (size_t i = 0; i < s->nb; i++)
        for (size_t k = s->rowptr[i]; k < s->rowptr[i + 1]; k++)
            for (PetscInt a = 0; a < 3; a++)
                for (PetscInt b = 0; b < 3; b++) {
                    PetscInt r = r0 + 3 * (PetscInt)i + a,
                             c = 3 * (PetscInt)s->col[k] + b;
                    size_t e = 9 * k + (size_t)(3 * a + b);
                    p->row_of[e] = 3 * i + (size_t)a;
                    p->slot_x[e] = find_slot(ia, ja, r, c);
                    p->slot_v[e] = find_slot(ia, ja, r, vo + c);
                }
    for (PetscInt i = 0; i < n; i++) {
        p->slot_m[i] = find_slot(ia, ja, r0 + i, vo + i);
        if (!s->second_order) {
            p->slot_xx[i] = find_slot(ia, ja, i, i);
            p->slot_xv[i] = find_slot(ia, ja, i, n + i);
        }
    }
}

static PetscErrorCode make_slots(clp_ts *p)
{
    size_t nval = 9 * p->s.nnzb;
    const PetscInt *ia, *ja;
    PetscInt nr;
    PetscBool done;
    PetscFunctionBeginUser;
    PetscCall(PetscMalloc2(nval, &p->dfdx, nval, &p->dfdv));
    PetscCall(PetscMalloc3(nval, &p->slot_x, nval, &p->slot_v, nval,
                           &p->row_of));
    PetscCall(PetscMalloc3(p->s.n, &p->slot_m, p->s.n, &p->slot_xx, p->s.n,
                           &p->slot_xv));
    PetscCall(MatGetRowIJ(p->J, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia, &ja,
                          &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_PLIB, "no CSR of the matrix");
    fill_slots(p, ia, ja);
    PetscCall(MatRestoreRowIJ(p->J, 0, PETSC_FALSE, PETSC_FALSE, &nr, &ia,
                              &ja, &done));
    PetscFunctionReturn(0);
}

/* ---- the callbacks ------------------------------------------------------ */

/* A callback's status into PETSc's: 1 a domain error (the step is retried
 * smaller), -1 an error that ends the solve. */
static PetscErrorCode callback_status(clp_ts *p, int rc, PetscBool jac)
{
    SNES snes;
    p->cb = rc;
    if (rc == 0)
        return 0;
    if (rc < 0)
        return PETSC_ERR_USER;
    PetscCall(TSGetSNES(p->ts, &snes));
    PetscCall(jac ? SNESSetJacobianDomainError(snes)
                  : SNESSetFunctionDomainError(snes));
    return 0;
}

static PetscErrorCode ifunction(TS ts, PetscReal t, Vec Y, Vec Yd, Vec F,
                                void *ctx)
{
    clp_ts *p = ctx;
    size_t n = p->s.n;
    const PetscScalar *y, *yd;
    PetscScalar *f;
    (void)ts;
    PetscCall(VecGetArrayRead(Y, &y));
    PetscCall(VecGetArrayRead(Yd, &yd));
    PetscCall(VecGetArray(F, &f));
    int rc = p->s.force(p->s.ctx, t, y, y + n, f + n);
    p->nfun++;
    for (size_t i = 0; rc == 0 && i < n; i++) {
        f[i] = yd[i] - y[n + i];
        f[n + i] = yd[n + i] - f[n + i] / p->s.mass[i];
    }
    PetscCall(VecRestoreArray(F, &f));
    PetscCall(VecRestoreArrayRead(Yd, &yd));
    PetscCall(VecRestoreArrayRead(Y, &y));
    return callback_status(p, rc, PETSC_FALSE);
}

static PetscErrorCode ijacobian(TS ts, PetscReal t, Vec Y, Vec Yd,
                                PetscReal a, Mat A, Mat P, void *ctx)
{
    clp_ts *p = ctx;
    const PetscScalar *y;
    PetscScalar *val;
    (void)ts, (void)Yd, (void)A;
    PetscCall(VecGetArrayRead(Y, &y));
    int rc = p->s.jacobian(p->s.ctx, t, y, y + p->s.n, p->dfdx, p->dfdv);
    PetscCall(VecRestoreArrayRead(Y, &y));
    p->njac++;
    if (rc != 0)
        return callback_status(p, rc, PETSC_TRUE);
    PetscCall(MatSeqAIJGetArray(P, &val));
    for (size_t e = 0; e < 9 * p->s.nnzb; e++) {
        double m = p->s.mass[p->row_of[e]];
        val[p->slot_x[e]] = -p->dfdx[e] / m;
        val[p->slot_v[e]] = -p->dfdv[e] / m;
    }
    for (size_t i = 0; i < p->s.n; i++) {
        val[p->slot_m[i]] += a;
        val[p->slot_xx[i]] = a;
        val[p->slot_xv[i]] = -1.0;
    }
    PetscCall(MatSeqAIJRestoreArray(P, &val));
    PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
    return callback_status(p, 0, PETSC_TRUE);
}

static PetscErrorCode i2function(TS ts, PetscReal t, Vec X, Vec V, Vec A,
                                 Vec F, void *ctx)
{
    clp_ts *p = ctx;
    const PetscScalar *x, *v, *acc;
    PetscScalar *f;
    (void)ts;
    PetscCall(VecGetArrayRead(X, &x));
    PetscCall(VecGetArrayRead(V, &v));
    PetscCall(VecGetArrayRead(A, &acc));
    PetscCall(VecGetArray(F, &f));
    int rc = p->s.force(p->s.ctx, t, x, v, f);
    p->nfun++;
    for (size_t i = 0; rc == 0 && i < p->s.n; i++)
        f[i] = p->s.mass[i] * acc[i] - f[i];
    PetscCall(VecRestoreArray(F, &f));
    PetscCall(VecRestoreArrayRead(A, &acc));
    PetscCall(VecRestoreArrayRead(V, &v));
    PetscCall(VecRestoreArrayRead(X, &x));
    return callback_status(p, rc, PETSC_FALSE);
}

static PetscErrorCode i2jacobian(TS ts, PetscReal t, Vec X, Vec V, Vec A,
                                 PetscReal sv, PetscReal sa, Mat J, Mat P,
                                 void *ctx)
{
    clp_ts *p = ctx;
    const PetscScalar *x, *v;
    PetscScalar *val;
    (void)ts, (void)A, (void)J;
    PetscCall(VecGetArrayRead(X, &x));
    PetscCall(VecGetArrayRead(V, &v));
    int rc = p->s.jacobian(p->s.ctx, t, x, v, p->dfdx, p->dfdv);
    PetscCall(VecRestoreArrayRead(V, &v));
    PetscCall(VecRestoreArrayRead(X, &x));
    p->njac++;
    if (rc != 0)
        return callback_status(p, rc, PETSC_TRUE);
    PetscCall(MatSeqAIJGetArray(P, &val));
    for (size_t e = 0; e < 9 * p->s.nnzb; e++)
        val[p->slot_x[e]] = -p->dfdx[e] - sv * p->dfdv[e];
    for (size_t i = 0; i < p->s.n; i++)
        val[p->slot_m[i]] += sa * p->s.mass[i];
    PetscCall(MatSeqAIJRestoreArray(P, &val));
    PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
    return callback_status(p, 0, PETSC_TRUE);
}

/* ---- counters ----------------------------------------------------------- */

/* After the first step, every option of --petsc read by an object (the
 * SNES, KSP, PC and line search read some only when first set up): an
 * option none of them read is misspelt, for another method or solver, or
 * global, and PETSc itself would ignore it ("-ts_alpha_radius=0.5" ran at
 * PETSc's radius 1).  False with the message in p->bad_option. */
static bool every_option_read(clp_ts *p)
{
    PetscInt n;
    char **names, **values, list[256] = "";
    if (PetscOptionsLeftGet(p->opts, &n, &names, &values))
        return true; /* nothing to tell */
    for (PetscInt k = 0, used = 0; k < n && used < (PetscInt)sizeof list;
         k++)
        used += snprintf(list + used, sizeof list - (size_t)used, "%s-%s",
                         k ? ", " : "", names[k]);
    if (n > 0)
        snprintf(p->bad_option, sizeof p->bad_option, "--petsc: no PETSc "
                 "object of %s read %s: misspelt, for another method or "
                 "solver, or a global option, which --petsc does not take",
                 p->s.name, list);
    PetscOptionsLeftRestore(p->opts, &n, &names, &values);
    return *p->bad_option == '\0';
}

static PetscErrorCode count_step(TS ts)
{
    clp_ts *p;
    PetscCall(TSGetApplicationContext(ts, &p));
    p->steps++;
    if (p->steps == 1 && !every_option_read(p))
        return PETSC_ERR_ARG_WRONG; /* ends TSSolve: clp_ts_advance says */
    return 0;
}

static PetscErrorCode count_solve(KSP ksp, Vec b, Vec x, void *ctx)
{
    clp_ts *p = ctx;
    PetscInt its;
    (void)b, (void)x;
    PetscCall(KSPGetIterationNumber(ksp, &its));
    p->nsolve++;
    p->nkspit += its;
    return 0;
}

/* A monitor that does nothing: with one, SNESKSPONLY evaluates the
 * residual at its solution, and TSALPHA2 sets its stage velocity and
 * acceleration from the iterate in that evaluation (without it they stay
 * those of the first guess: the velocities came out 0 on hang-smooth). */
static PetscErrorCode residual_at_solution(SNES snes, PetscInt it,
                                           PetscReal norm, void *ctx)
{
    (void)snes, (void)it, (void)norm, (void)ctx;
    return 0;
}

/* ---- set-up ------------------------------------------------------------- */

static PetscErrorCode make_vectors(clp_ts *p)
{
    const clp_ts_setup *s = &p->s;
    PetscInt n = (PetscInt)s->n;
    PetscScalar *y;
    PetscFunctionBeginUser;
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, nrows(p), &p->y));
    PetscCall(VecGetArray(p->y, &y));
    memcpy(y, s->x0, s->n * sizeof *y);
    if (!s->second_order)
        memcpy(y + n, s->v0, s->n * sizeof *y);
    PetscCall(VecRestoreArray(p->y, &y));
    if (s->second_order) {
        PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &p->yv));
        PetscCall(VecGetArray(p->yv, &y));
        memcpy(y, s->v0, s->n * sizeof *y);
        PetscCall(VecRestoreArray(p->yv, &y));
    }
    PetscFunctionReturn(0);
}

/* The equations, the Jacobian and the linear solver's default, by
 * measurement on hang (README "Benchmarks", workload 11): for the
 * half-size matrix (11.4) of TSALPHA2, symmetric and positive definite at
 * the steps it takes, CG preconditioned by PETSc's algebraic multigrid
 * GAMG (3.8x faster than LU at n = 16); for the nonsymmetric matrix (11.2)
 * of the first-order form, a direct sparse LU (PETSc's own,
 * nested-dissection ordering). */
static PetscErrorCode set_problem(clp_ts *p)
{
    SNES snes;
    KSP ksp;
    PC pc;
    PetscFunctionBeginUser;
    if (p->s.second_order) {
        PetscCall(TSSetI2Function(p->ts, NULL, i2function, p));
        PetscCall(TSSetI2Jacobian(p->ts, p->J, p->J, i2jacobian, p));
        PetscCall(TS2SetSolution(p->ts, p->y, p->yv));
    } else {
        PetscCall(TSSetIFunction(p->ts, NULL, ifunction, p));
        PetscCall(TSSetIJacobian(p->ts, p->J, p->J, ijacobian, p));
        PetscCall(TSSetSolution(p->ts, p->y));
    }
    /* Newton iterations are counted by TSGetSNESIterations, not by a
     * monitor, which makes SNESKSPONLY evaluate one more residual per
     * solve: the other methods do not need it */
    PetscCall(TSGetSNES(p->ts, &snes));
    if (p->s.second_order)
        PetscCall(SNESMonitorSet(snes, residual_at_solution, NULL, NULL));
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    if (p->s.second_order) {
        PetscCall(KSPSetType(ksp, KSPCG));
        PetscCall(PCSetType(pc, PCGAMG));
    } else {
        PetscCall(KSPSetType(ksp, KSPPREONLY));
        PetscCall(PCSetType(pc, PCLU));
        PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGND));
    }
    PetscCall(KSPSetPostSolve(ksp, count_solve, p));
    PetscFunctionReturn(0);
}

/* The steps clothode set, kept by the PETSc options: with fixed steps
 * (--dt) the step and no adaptivity, and an order of TSBDF that fixed
 * steps reach (its start, backward Euler with the order raised one step
 * at a time, leaves an O(dt^2) error that no fixed step corrects: orders
 * 3..6 measured 2.0 on spring2); without, adaptivity (TSAdapt none kept
 * the step cut to reach an output time as its step: 1.2e8 steps to 0.1 s);
 * in either mode the end of every output interval on its output time, by
 * which the outputs are labelled (interpolating there would need a
 * solution vector that TSSolve is not given). */
static PetscErrorCode check_steps_kept(clp_ts *p, PetscReal dt)
{
    TSAdapt adapt;
    TSAdaptType adapt_type;
    TSType type;
    TSExactFinalTimeOption end;
    PetscInt order = 0;
    const clp_ts_setup *s = &p->s;
    PetscFunctionBeginUser;
    PetscCall(TSGetAdapt(p->ts, &adapt));
    PetscCall(TSAdaptGetType(adapt, &adapt_type));
    PetscCall(TSGetExactFinalTime(p->ts, &end));
    PetscCall(TSGetType(p->ts, &type));
    if (strcmp(type, TSBDF) == 0)
        PetscCall(TSBDFGetOrder(p->ts, &order));
    PetscCheck(!s->fixed || (dt == s->dt && !strcmp(adapt_type, TSADAPTNONE)),
               PETSC_COMM_SELF, PETSC_ERR_ARG_INCOMP, "fixed steps of --dt "
               "%g: the PETSc options may not change the step (-ts_dt, "
               "-ts_adapt_type); give no --dt for adaptive steps",
               (double)s->dt);
    PetscCheck(s->fixed || strcmp(adapt_type, TSADAPTNONE), PETSC_COMM_SELF,
               PETSC_ERR_ARG_INCOMP, "-ts_adapt_type none: adaptive steps "
               "need an adaptor; give --dt for fixed steps");
    PetscCheck(!s->fixed || order <= 2, PETSC_COMM_SELF,
               PETSC_ERR_ARG_INCOMP, "TSBDF order %d at fixed steps of --dt "
               "%g: its start (backward Euler, the order raised one step at "
               "a time) leaves an O(dt^2) error, so fixed steps reach order "
               "2 at most; give no --dt for adaptive steps at order %d",
               (int)order, (double)s->dt, (int)order);
    PetscCheck(end == (s->fixed ? TS_EXACTFINALTIME_STEPOVER
                                : TS_EXACTFINALTIME_MATCHSTEP),
               PETSC_COMM_SELF, PETSC_ERR_ARG_INCOMP, "-ts_exact_final_time: "
               "clothode ends every output interval on its output time "
               "itself");
    PetscFunctionReturn(0);
}

/* The method, steps and tolerances, then the user's options over them. */
static PetscErrorCode set_method(clp_ts *p)
{
    const clp_ts_setup *s = &p->s;
    TSAdapt adapt;
    PetscFunctionBeginUser;
    PetscCall(TSSetType(p->ts, s->ts_type));
    if (s->order > 0)
        PetscCall(TSBDFSetOrder(p->ts, s->order));
    if (strcmp(s->ts_type, TSARKIMEX) == 0)
        PetscCall(TSARKIMEXSetFullyImplicit(p->ts, PETSC_TRUE));
    PetscCall(TSSetTime(p->ts, s->t0));
    PetscCall(TSSetTimeStep(p->ts, s->dt));
    /* fixed steps: whole steps of dt up to the output time (stop_time);
     * adaptive: the step that would pass an output time ends on it */
    PetscCall(TSSetExactFinalTime(p->ts, s->fixed
                                             ? TS_EXACTFINALTIME_STEPOVER
                                             : TS_EXACTFINALTIME_MATCHSTEP));
    PetscCall(TSSetTolerances(p->ts, s->atol, NULL, s->rtol, NULL));
    PetscCall(TSGetAdapt(p->ts, &adapt));
    /* TSALPHA2 would not adapt unless told; a failed Newton solve
     * retries a smaller step, as in CVODE */
    PetscCall(TSAdaptSetType(adapt, s->fixed ? TSADAPTNONE : TSADAPTBASIC));
    if (!s->fixed)
        PetscCall(TSSetMaxSNESFailures(p->ts, -1));
    PetscCall(TSSetApplicationContext(p->ts, p));
    PetscCall(TSSetPostStep(p->ts, count_step));
    OPTIONS_READ_BEGIN();
    PetscErrorCode ec = TSSetFromOptions(p->ts);
    OPTIONS_READ_END();
    PetscCall(ec);
    /* -ts_dt is the user's to set, and PETSc takes any number */
    PetscReal dt;
    char shown[32];
    PetscCall(TSGetTimeStep(p->ts, &dt));
    snprintf(shown, sizeof shown, "%g", (double)dt); /* PETSc's %g: "1." */
    PetscCheck(dt > 0 && !PetscIsInfOrNanReal(dt), PETSC_COMM_SELF,
               PETSC_ERR_ARG_OUTOFRANGE, "-ts_dt %s: expected a finite "
               "number > 0", shown);
    PetscCall(check_steps_kept(p, dt));
    PetscCall(TSSetUp(p->ts));
    PetscFunctionReturn(0);
}

/* The linear solver's name after the options, "petsc:preonly+lu". */
static PetscErrorCode name_linsol(clp_ts *p)
{
    SNES snes;
    KSP ksp;
    PC pc;
    KSPType kt;
    PCType pt;
    PetscFunctionBeginUser;
    PetscCall(TSGetSNES(p->ts, &snes));
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(KSPGetType(ksp, &kt));
    PetscCall(PCGetType(pc, &pt));
    snprintf(p->linsol, sizeof p->linsol, "petsc:%s+%s", kt ? kt : "?",
             pt ? pt : "?");
    PetscFunctionReturn(0);
}

static PetscErrorCode setup(clp_ts *p)
{
    PetscFunctionBeginUser;
    PetscCall(make_matrix(p));
    PetscCall(make_slots(p));
    PetscCall(make_vectors(p));
    PetscCall(TSCreate(PETSC_COMM_SELF, &p->ts));
    /* before the SNES, KSP, PC and TSAdapt are made: they inherit them */
    PetscCall(PetscOptionsCreate(&p->opts));
    PetscCall(PetscOptionsInsertString(p->opts, p->s.options ? p->s.options
                                                             : ""));
    PetscCall(PetscObjectSetOptions((PetscObject)p->ts, p->opts));
    PetscCall(set_problem(p));
    PetscCall(set_method(p));
    PetscCall(name_linsol(p));
    PetscFunctionReturn(0);
}

/* PETSc's message for error code ec. */
static void petsc_message(PetscErrorCode ec, const char *what,
                          const char *name, cl_plugin_msg *msg)
{
    const char *text = NULL;
    char *specific = NULL;
    PetscErrorMessage(ec, &text, &specific);
    snprintf(msg->text, sizeof msg->text, "%s: %s failed: %s%s%s", name, what,
             text ? text : "PETSc error",
             specific && *specific ? ": " : "", specific ? specific : "");
}

void clp_ts_free(void *ts)
{
    clp_ts *p = ts;
    if (!p)
        return;
    TSDestroy(&p->ts);
    MatDestroy(&p->J);
    VecDestroy(&p->y);
    VecDestroy(&p->yv);
    PetscOptionsDestroy(&p->opts);
    PetscFree2(p->dfdx, p->dfdv);
    PetscFree3(p->slot_x, p->slot_v, p->row_of);
    PetscFree3(p->slot_m, p->slot_xx, p->slot_xv);
    PetscFree(p);
}

int clp_ts_create(const clp_ts_setup *s, void **ts, cl_plugin_msg *msg)
{
    clp_ts *p = NULL;
    *ts = NULL;
    PetscErrorCode ec = PetscNew(&p);
    if (ec == 0) {
        p->s = *s;
        ec = setup(p);
    }
    if (ec != 0) {
        petsc_message(ec, "setting up PETSc's TS (check --petsc)", s->name,
                      msg);
        clp_ts_free(p);
        return 1;
    }
    *ts = p;
    return 0;
}

/* ---- stepping ------------------------------------------------------------ */

static PetscErrorCode copy_state(clp_ts *p, double *x, double *v)
{
    const PetscScalar *y;
    size_t n = p->s.n;
    PetscFunctionBeginUser;
    PetscCall(VecGetArrayRead(p->y, &y));
    memcpy(x, y, n * sizeof *x);
    if (!p->s.second_order)
        memcpy(v, y + n, n * sizeof *v);
    PetscCall(VecRestoreArrayRead(p->y, &y));
    if (p->s.second_order) {
        PetscCall(VecGetArrayRead(p->yv, &y));
        memcpy(v, y, n * sizeof *v);
        PetscCall(VecRestoreArrayRead(p->yv, &y));
    }
    PetscFunctionReturn(0);
}

/* The time TSSolve runs to for output time t_out: t_out itself, or with
 * fixed steps half a step before it, so that the step ending on t_out up to
 * the rounding of the summed steps is the last (a cut last step would leave
 * TSAdapt none with the cut, 1e-19 s, as its step from then on). */
static double stop_time(const clp_ts *p, double t_out)
{
    return p->s.fixed ? t_out - 0.5 * p->s.dt : t_out;
}

static PetscErrorCode solve_to(clp_ts *p, double t_out)
{
    PetscInt steps, rejected, failed, newton;
    PetscFunctionBeginUser;
    PetscCall(TSGetStepNumber(p->ts, &steps));
    PetscCall(TSSetMaxSteps(p->ts, p->s.max_steps > 0
                                       ? steps + (PetscInt)p->s.max_steps
                                       : PETSC_MAX_INT));
    PetscCall(TSSetMaxTime(p->ts, stop_time(p, t_out)));
    PetscErrorCode ec = TSSolve(p->ts, NULL);
    /* PETSc's counts over the whole run (reset at step 0 only) */
    PetscCall(TSGetStepRejections(p->ts, &rejected));
    PetscCall(TSGetSNESFailures(p->ts, &failed));
    PetscCall(TSGetSNESIterations(p->ts, &newton));
    p->nreject = rejected;
    p->nsnesfail = failed;
    p->nnewton = newton;
    PetscCall(ec);
    PetscFunctionReturn(0);
}

int clp_ts_advance(void *ts, double t_out, double *x, double *v,
                   cl_plugin_msg *msg)
{
    clp_ts *p = ts;
    PetscReal t;
    TSConvergedReason why = TS_CONVERGED_ITERATING;
    p->cb = 0;
    PetscErrorCode ec = TSGetTime(p->ts, &t);
    if (ec == 0 && t < stop_time(p, t_out) && (ec = solve_to(p, t_out))) {
        if (*p->bad_option) {
            snprintf(msg->text, sizeof msg->text, "%s: %s", p->s.name,
                     p->bad_option);
            return CLP_TS_BAD_OPTION;
        }
        /* a step failed: where, and what to change, as the other
         * integrators' failures say; before the first step, with the
         * options no object read (one may have been meant to help) */
        petsc_message(ec, "TSSolve", p->s.name, msg);
        size_t len = strlen(msg->text);
        if (TSGetTime(p->ts, &t) == 0)
            len += (size_t)snprintf(msg->text + len, sizeof msg->text - len,
                                    " (at t = %.9g); to change: reduce --dt "
                                    "(fixed steps) or --rtol", (double)t);
        if (p->steps == 0 && !every_option_read(p) &&
            len < sizeof msg->text)
            snprintf(msg->text + len, sizeof msg->text - len, "; and %s",
                     p->bad_option);
        return 1;
    }
    if (ec == 0)
        ec = TSGetConvergedReason(p->ts, &why);
    if (ec == 0)
        ec = copy_state(p, x, v);
    if (ec == 0)
        ec = TSGetTime(p->ts, &t);
    if (ec != 0) {
        petsc_message(ec, "TSSolve", p->s.name, msg);
        return 1;
    }
    if (why < 0 || t < stop_time(p, t_out)) {
        snprintf(msg->text, sizeof msg->text, "%s: PETSc's TS stopped at t = "
                 "%.9g on the way to %.9g: %s%s", p->s.name, t, t_out,
                 TSConvergedReasons[why],
                 why == TS_CONVERGED_ITS ? " (more than [run] max_steps "
                                           "steps in one output interval)"
                                         : "");
        return 1;
    }
    return 0;
}

int clp_ts_restart(void *ts, cl_plugin_msg *msg)
{
    clp_ts *p = ts;
    PetscErrorCode ec = TSRestartStep(p->ts);
    if (ec != 0)
        petsc_message(ec, "TSRestartStep", p->s.name, msg);
    return ec != 0;
}

void clp_ts_stats(const void *ts, cl_stats *st)
{
    const clp_ts *p = ts;
    memset(st, 0, sizeof *st);
    st->steps = p->steps;
    st->rhs_evals = p->nfun;
    st->jac_evals = p->njac;
    st->lin_setups = p->njac;
    st->lin_solves = p->nsolve;
    st->lin_iters = p->nkspit;
    st->nonlin_iters = p->nnewton;
    st->nonlin_fails = p->nsnesfail;
    st->err_fails = p->nreject;
    memcpy(st->linsol, p->linsol, sizeof st->linsol);
}
