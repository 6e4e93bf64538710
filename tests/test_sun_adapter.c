/* The SUNDIALS adapter (integrators/sun_adapter.h): a shell linear solver
 * calls its table's functions with its data and has exactly the optional
 * operations the table gives; the shell matrix holds nothing and clones
 * into another shell; the counting shell counts one KLU analysis per
 * initialisation of the solver, so a klu-full run that restarts CVODE
 * after every tear counts one analysis more per restart; a stop that ends
 * a linear solve ends the advance with CL_EINTR; a negative max_order is
 * refused. */
#include <criterion/criterion.h>

#include <signal.h>

#include <sundials/sundials_matrix.h>

#include "core/stop.h"
#include "integrators/sun_adapter.h"
#include "pbdcheck.h"
#include "runint.h"

/* What the shell passed on: calls per operation, the data it was given. */
typedef struct {
    int inits, setups, solves, frees;
    void *seen;
} probe;

static int probe_init(void *data)
{
    probe *p = data;
    p->inits++;
    p->seen = data;
    return SUNLS_SUCCESS;
}

static int probe_setup(void *data, SUNMatrix A)
{
    probe *p = data;
    (void)A;
    p->setups++;
    return 7; /* a recoverable failure, passed through */
}

static int probe_solve(void *data, SUNMatrix A, N_Vector x, N_Vector b,
                       sunrealtype tol)
{
    probe *p = data;
    (void)A, (void)x, (void)b, (void)tol;
    p->solves++;
    return SUNLS_SUCCESS;
}

static sunindextype probe_lastflag(void *data)
{
    return ((probe *)data)->setups;
}

static void probe_free(void *data)
{
    ((probe *)data)->frees++;
}

static const cl_sun_lsdef bare = {
    .type = SUNLINEARSOLVER_DIRECT,
    .setup = probe_setup,
    .solve = probe_solve,
};

static const cl_sun_lsdef full = {
    .type = SUNLINEARSOLVER_MATRIX_ITERATIVE,
    .setup = probe_setup,
    .solve = probe_solve,
    .initialize = probe_init,
    .lastflag = probe_lastflag,
    .free = probe_free,
};

static SUNContext ctx;

static void open_ctx(void)
{
    cr_assert_eq(SUNContext_Create(NULL, &ctx), 0);
}

static void close_ctx(void)
{
    SUNContext_Free(&ctx);
}

/* The shell of def on p, of def's type and SUNDIALS' custom id. */
static SUNLinearSolver make_shell(const cl_sun_lsdef *def, probe *p)
{
    SUNLinearSolver S = cl_sun_shell_linsol(def, p, ctx);
    cr_assert_not_null(S);
    cr_assert_eq(SUNLinSolGetType(S), def->type);
    cr_assert_eq(SUNLinSolGetID(S), SUNLINEARSOLVER_CUSTOM);
    return S;
}

/* Release S; how often its table's free ran on p. */
static int release(SUNLinearSolver S, const probe *p)
{
    cr_assert_eq(SUNLinSolFree(S), SUNLS_SUCCESS);
    return p->frees;
}

Test(sun_adapter, shell_linsol_calls_its_table_with_its_data,
     .init = open_ctx, .fini = close_ctx)
{
    probe p = {0};
    SUNLinearSolver S = make_shell(&full, &p);
    cr_assert_eq(SUNLinSolInitialize(S), SUNLS_SUCCESS);
    cr_assert_eq(SUNLinSolSetup(S, NULL), 7);
    cr_assert_eq(SUNLinSolSolve(S, NULL, NULL, NULL, 0.0), SUNLS_SUCCESS);
    cr_assert_eq(SUNLinSolSolve(S, NULL, NULL, NULL, 0.0), SUNLS_SUCCESS);
    cr_assert_eq(SUNLinSolLastFlag(S), 1);
    cr_assert_eq(p.seen, &p);
    cr_assert(p.inits == 1 && p.setups == 1 && p.solves == 2,
              "%d inits, %d setups, %d solves", p.inits, p.setups, p.solves);
    cr_assert_eq(release(S, &p), 1, "owned data is released once");
}

Test(sun_adapter, shell_linsol_has_only_the_operations_given,
     .init = open_ctx, .fini = close_ctx)
{
    probe p = {0};
    SUNLinearSolver S = make_shell(&bare, &p);
    cr_assert_null(S->ops->lastflag);
    cr_assert_null(S->ops->space);
    cr_assert_null(S->ops->setscalingvectors);
    cr_assert_null(S->ops->numiters);
    cr_assert_null(S->ops->resid);
    cr_assert_eq(SUNLinSolInitialize(S), SUNLS_SUCCESS);
    cr_assert_eq(p.inits, 0);
    cr_assert_eq(release(S, &p), 0, "borrowed data is not released");
}

Test(sun_adapter, shell_matrix_holds_nothing_and_clones_a_shell,
     .init = open_ctx, .fini = close_ctx)
{
    SUNMatrix A = cl_sun_shell_matrix(ctx);
    cr_assert_not_null(A);
    cr_assert_null(A->content);
    cr_assert_eq(SUNMatGetID(A), SUNMATRIX_CUSTOM);
    cr_assert_eq(SUNMatZero(A), SUNMAT_SUCCESS);
    cr_assert_eq(SUNMatScaleAddI(2.0, A), SUNMAT_SUCCESS);
    SUNMatrix B = SUNMatClone(A);
    cr_assert_not_null(B);
    cr_assert_neq(A, B);
    cr_assert_eq(SUNMatGetID(B), SUNMATRIX_CUSTOM);
    cr_assert_eq(SUNMatCopy(A, B), SUNMAT_SUCCESS);
    SUNMatDestroy(B);
    SUNMatDestroy(A);
}

/* Outputs after which the model tore further: CVODE restarts there. */
typedef struct {
    size_t broken;
    int restarts;
} tears;

static void count_tears(pb_case *c, double t, void *ctx)
{
    tears *k = ctx;
    size_t now = cl_model_broken(c->m);
    (void)t;
    k->restarts += now > k->broken;
    k->broken = now;
}

Test(sun_adapter, klu_analyses_once_per_restart)
{
    pb_case c = pb_open(FD_MODEL(PB_PULL, "damping.kd=1e-3", "tear.cut=1.5"));
    cl_integrator_opts o = {.rtol = 1e-4, .atol = 1e-6, .linsol = "klu-full"};
    tears k = {0};
    pb_integrate(&c, "cvode-bdf", &o, 0.5, 100, count_tears, &k);
    cr_log_info("klu-full: %d restarts, %ld analyses", k.restarts,
                c.st.symbolic_facts);
    cr_assert_gt(k.restarts, 0);
    cr_assert_eq(c.st.symbolic_facts, 1 + k.restarts);
    pb_close(&c);
}

/* A stop that ends an iterative linear solve (linalg/linsol.h) on a
 * system whose own evaluations do not look at it (the model's do) ends
 * the advance as a stop, CL_EINTR naming the signal, for CVODE and IDA
 * (before: CL_ESOLVER, a solver failure, which a run reports as its
 * own). */
static void stopped_in_a_solve(const char *name)
{
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 3), 0);
    double x[9], v[9], x0[9], v0[9];
    ri_start(&ts, x0, v0, x, v);
    const cl_integrator_type *it = cl_integrator_find(name);
    cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8, .linsol = "pcg"};
    void *st = NULL;
    cl_error err = {0};
    cr_assert_eq(it->create(&ts.sys, &o, 0.0, x, v, &st, &err), CL_OK, "%s",
                 err.msg);
    cl_stop_install();
    cr_assert_eq(raise(SIGTERM), 0);
    cr_assert_eq(it->advance(st, 1.0, x, v, &err), CL_EINTR, "%s", err.msg);
    cr_assert(strstr(err.msg, "stopped by SIGTERM in a linear solve"), "%s",
              err.msg);
    it->free(st);
    ts_free(&ts);
}

Test(sun_adapter, cvode_stopped_in_a_linear_solve)
{
    stopped_in_a_solve("cvode-bdf");
}

Test(sun_adapter, ida_stopped_in_a_linear_solve)
{
    stopped_in_a_solve("ida");
}

/* Options out of range are refused by every SUNDIALS integrator when it is
 * created (before: a negative max_order ran at the solver's own). */
Test(sun_adapter, negative_max_order_refused)
{
    static const char *const names[] = {"cvode-bdf", "cvode-adams", "ida",
                                        "arkode-dirk", "arkode-imex"};
    ts_sys ts;
    cr_assert_eq(ts_oscillators(&ts, 3), 0);
    double x[9], v[9], x0[9], v0[9];
    ri_start(&ts, x0, v0, x, v);
    for (size_t k = 0; k < sizeof names / sizeof *names; k++) {
        const cl_integrator_type *it = cl_integrator_find(names[k]);
        cl_integrator_opts o = {.rtol = 1e-6, .atol = 1e-8, .max_order = -3};
        void *st = NULL;
        cl_error err = {0};
        cr_assert_eq(it->create(&ts.sys, &o, 0.0, x, v, &st, &err),
                     CL_EINVAL, "%s: %s", names[k], err.msg);
        cr_assert(strstr(err.msg, "max_order = -3"), "%s", err.msg);
        cr_assert_null(st);
    }
    ts_free(&ts);
}
