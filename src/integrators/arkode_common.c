/* ARKODE's ARKStep on the SUNDIALS adapter (see arkode_common.h): the
 * package table, the right-hand sides of the DIRK and IMEX forms, the
 * Butcher tables by name, the step and Newton options, fixed-step
 * advance. */
#include "integrators/arkode_common.h"

#include <stdio.h>
#include <string.h>

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_butcher_dirk.h>
#include <arkode/arkode_butcher_erk.h>

#include "integrators/sun_newton.h"
#include "integrators/sun_reduced.h"

typedef struct {
    cl_sun base;             /* first: the adapter's state */
    const cl_ark_method *m;
    ARKRhsFn fe, fi;         /* the right-hand sides (fe NULL: DIRK) */
    uint64_t expl;           /* the explicit terms (IMEX) */
    double dt;               /* the fixed step */
    double t0;               /* the initial time: fixed steps end at
                              * t0 + k dt */
    long done;               /* fixed steps taken */
    long todo;               /* fixed steps of the current advance */
} cl_ark;

/* ---- the package table ------------------------------------------------ */

/* f_E and f_I evaluations together (arkode_common.h). */
static int ark_rhs_count(void *mem, long *n)
{
    long ne = 0, ni = 0;
    int flag = ARKStepGetNumRhsEvals(mem, &ne, &ni);
    *n = ne + ni;
    return flag;
}

/* One advance: the counted fixed steps, or to t_out by error control. */
static int ark_solve(cl_sun *s, double t_out)
{
    cl_ark *a = (cl_ark *)s;
    sunrealtype tret;
    if (!a->m->fixed)
        return ARKStepEvolve(s->mem, t_out, s->y, &tret, ARK_NORMAL);
    for (; a->todo > 0; a->todo--, a->done++) {
        int flag = ARKStepEvolve(s->mem, t_out, s->y, &tret, ARK_ONE_STEP);
        if (flag < 0)
            return flag;
    }
    return ARK_SUCCESS;
}

static cl_status ark_reinit(cl_sun *s, double t, cl_error *err)
{
    cl_ark *a = (cl_ark *)s;
    int flag = ARKStepReInit(s->mem, a->fe, a->fi, t, s->y);
    return flag < 0 ? cl_sun_fail(s, "ARKStepReInit", flag, err) : CL_OK;
}

static const cl_sun_api ark_api = {
    .pkg = "ARKStep",
    .solve_name = "ARKStepEvolve",
    .has_yp = false,
    .set_err_handler = ARKStepSetErrHandlerFn,
    .set_user_data = ARKStepSetUserData,
    .sstolerances = ARKStepSStolerances,
    .set_max_num_steps = ARKStepSetMaxNumSteps,
    .set_init_step = ARKStepSetInitStep,
    .set_linear_solver = ARKStepSetLinearSolver,
    .get_current_time = ARKStepGetCurrentTime,
    .get_current_step = ARKStepGetCurrentStep,
    .get_gamma = ARKStepGetCurrentGamma,
    .set_jac_fn = ARKStepSetJacFn,
    .flag_name = ARKStepGetReturnFlagName,
    .collapse_warning = ARK_WARNING,
    .free_mem = ARKStepFree,
    .solve = ark_solve,
    .reinit = ark_reinit,
    .steps = ARKStepGetNumSteps,
    .rhs = ark_rhs_count,
    .lin_rhs = ARKStepGetNumLinRhsEvals,
    .jac = ARKStepGetNumJacEvals,
    .setups = ARKStepGetNumLinSolvSetups,
    .lin_iters = ARKStepGetNumLinIters,
    .nl_iters = ARKStepGetNumNonlinSolvIters,
    .nl_fails = ARKStepGetNumNonlinSolvConvFails,
    .err_fails = ARKStepGetNumErrTestFails,
};

/* ---- right-hand sides of the IMEX split -------------------------------- */

/* (xd, vd) = (v or 0, M^-1 f_mask(t, x, v)). */
static int ark_part(cl_sun *s, uint64_t mask, bool with_v, sunrealtype t,
                    N_Vector y, N_Vector ydot)
{
    size_t n = s->sys->n;
    const double *x = N_VGetArrayPointer(y), *v = x + n;
    double *xd = N_VGetArrayPointer(ydot), *vd = xd + n;
    int ret = cl_sun_force_terms(s, mask, t, x, v, vd);
    if (ret != 0)
        return ret;
    if (with_v)
        memcpy(xd, v, n * sizeof *xd);
    else
        memset(xd, 0, n * sizeof *xd);
    for (size_t i = 0; i < n; i++)
        vd[i] *= s->inv_mass[i];
    return cl_sun_rhs_finite(s, xd, 2 * n, t);
}

static int ark_fi_split(sunrealtype t, N_Vector y, N_Vector ydot, void *data)
{
    cl_sun *s = data;
    return ark_part(s, s->implicit, true, t, y, ydot);
}

static int ark_fe_split(sunrealtype t, N_Vector y, N_Vector ydot, void *data)
{
    cl_ark *a = data;
    return ark_part(&a->base, a->expl, false, t, y, ydot);
}

/* ---- Butcher tables ---------------------------------------------------- */

#define ARK_ROW(id) {#id, ARKODE_##id}
static const struct {
    const char *name;
    ARKODE_DIRKTableID id;
} ark_dirk[] = {
    ARK_ROW(SDIRK_2_1_2), ARK_ROW(BILLINGTON_3_3_2), ARK_ROW(TRBDF2_3_3_2),
    ARK_ROW(KVAERNO_4_2_3), ARK_ROW(ARK324L2SA_DIRK_4_2_3),
    ARK_ROW(CASH_5_2_4), ARK_ROW(CASH_5_3_4), ARK_ROW(SDIRK_5_3_4),
    ARK_ROW(KVAERNO_5_3_4), ARK_ROW(ARK436L2SA_DIRK_6_3_4),
    ARK_ROW(KVAERNO_7_4_5), ARK_ROW(ARK548L2SA_DIRK_8_4_5),
    ARK_ROW(ARK437L2SA_DIRK_7_3_4), ARK_ROW(ARK548L2SAb_DIRK_8_4_5),
    ARK_ROW(ESDIRK324L2SA_4_2_3), ARK_ROW(ESDIRK325L2SA_5_2_3),
    ARK_ROW(ESDIRK32I5L2SA_5_2_3), ARK_ROW(ESDIRK436L2SA_6_3_4),
    ARK_ROW(ESDIRK43I6L2SA_6_3_4), ARK_ROW(QESDIRK436L2SA_6_3_4),
    ARK_ROW(ESDIRK437L2SA_7_3_4), ARK_ROW(ESDIRK547L2SA_7_4_5),
    ARK_ROW(ESDIRK547L2SA2_7_4_5),
};

static const struct {
    const char *name;
    ARKODE_ERKTableID erk;
    ARKODE_DIRKTableID dirk;
} ark_pairs[] = {
    {"ARK324L2SA", ARKODE_ARK324L2SA_ERK_4_2_3, ARKODE_ARK324L2SA_DIRK_4_2_3},
    {"ARK436L2SA", ARKODE_ARK436L2SA_ERK_6_3_4, ARKODE_ARK436L2SA_DIRK_6_3_4},
    {"ARK548L2SA", ARKODE_ARK548L2SA_ERK_8_4_5, ARKODE_ARK548L2SA_DIRK_8_4_5},
};

#define ARK_LEN(a) (sizeof(a) / sizeof *(a))

/* One-stage tables of our own (arkode_common.h), without embedding. */
static ARKodeButcherTable ark_own(const char *name)
{
    double c = 1.0, A = 1.0, b = 1.0;
    if (strcmp(name, "IMPLICIT_MIDPOINT_1_2") == 0) {
        c = A = 0.5;
        return ARKodeButcherTable_Create(1, 2, 0, &c, &A, &b, NULL);
    }
    if (strcmp(name, "BACKWARD_EULER_1_1") == 0)
        return ARKodeButcherTable_Create(1, 1, 0, &c, &A, &b, NULL);
    return NULL;
}

/* "NAME (expected A, B, ...)" for an unknown table. */
static cl_status ark_unknown(const cl_ark_method *m, const char *name,
                             cl_error *err)
{
    char list[1024];
    size_t at = 0;
    size_t n = m->imex ? ARK_LEN(ark_pairs) : ARK_LEN(ark_dirk);
    for (size_t k = 0; k < n && at < sizeof list; k++)
        at += (size_t)snprintf(list + at, sizeof list - at, "%s, ",
                               m->imex ? ark_pairs[k].name
                                       : ark_dirk[k].name);
    if (!m->imex && at < sizeof list)
        snprintf(list + at, sizeof list - at, "BACKWARD_EULER_1_1, "
                 "IMPLICIT_MIDPOINT_1_2 (fixed steps)");
    else if (at >= 2 && at < sizeof list)
        list[at - 2] = '\0';
    return cl_error_set(err, CL_EINVAL, "%s: unknown table \"%s\" "
                        "(expected one of %s)", m->name, name, list);
}

/* The table(s) of the method named by o->table into *bi (and *be). */
static cl_status ark_load(const cl_ark_method *m, const char *name,
                          ARKodeButcherTable *bi, ARKodeButcherTable *be,
                          cl_error *err)
{
    for (size_t k = 0; m->imex && k < ARK_LEN(ark_pairs); k++)
        if (strcmp(name, ark_pairs[k].name) == 0) {
            *bi = ARKodeButcherTable_LoadDIRK(ark_pairs[k].dirk);
            *be = ARKodeButcherTable_LoadERK(ark_pairs[k].erk);
            return CL_OK;
        }
    for (size_t k = 0; !m->imex && k < ARK_LEN(ark_dirk); k++)
        if (strcmp(name, ark_dirk[k].name) == 0) {
            *bi = ARKodeButcherTable_LoadDIRK(ark_dirk[k].id);
            return CL_OK;
        }
    if (!m->imex && (*bi = ark_own(name))) {
        if (m->fixed)
            return CL_OK;
        return cl_error_set(err, CL_EINVAL, "%s: table %s has no embedded "
                            "error estimate; use it with fixed steps "
                            "(arkode-dirk-fixed --dt H)", m->name, name);
    }
    return ark_unknown(m, name, err);
}

static cl_status ark_tables(cl_ark *a, const cl_integrator_opts *o,
                            cl_error *err)
{
    cl_sun *s = &a->base;
    const char *name = o->table && o->table[0] ? o->table
                       : a->m->imex ? CL_ARK_IMEX_DEFAULT
                                    : CL_ARK_DIRK_DEFAULT;
    ARKodeButcherTable bi = NULL, be = NULL;
    cl_status st = ark_load(a->m, name, &bi, &be, err);
    int flag = 0;
    if (st == CL_OK && (!bi || (a->m->imex && !be)))
        st = cl_sun_sunfail(s, "ARKodeButcherTable_Load", 0, err);
    if (st == CL_OK)
        flag = ARKStepSetTables(s->mem, bi->q, a->m->fixed ? 0 : bi->p, bi,
                                be);
    ARKodeButcherTable_Free(bi); /* ARKStep keeps copies */
    ARKodeButcherTable_Free(be);
    if (st == CL_OK && flag < 0)
        return cl_sun_fail(s, "ARKStepSetTables", flag, err);
    return st;
}

/* ---- options ----------------------------------------------------------- */

/* Calls ARKStep's setter `fn(s->mem, ...)`, returning its failure. */
#define ARK_SET(s, err, fn, ...)                                            \
    do {                                                                    \
        int flag_ = fn((s)->mem, __VA_ARGS__);                              \
        if (flag_ < 0)                                                      \
            return cl_sun_fail((s), #fn, flag_, (err));                     \
    } while (0)

/* Newton options (arkode_common.h).  One linearisation: a coefficient
 * no finite correction exceeds, and the iterative linear solvers' factor
 * (their tolerance is factor x coefficient) scaled down by as much, so
 * that they solve to ARKODE's default 0.05 x 0.1. */
#define CL_ARK_ONE_COEF 1e100
static cl_status ark_newton(cl_sun *s, bool fixed, const cl_integrator_opts *o,
                            cl_error *err)
{
    if (!(o->newton_tol >= 0.0) || o->newton_maxit < 0 ||
        o->newton_maxit > 1000000)
        return cl_error_set(err, CL_EINVAL, "%s: newton_tol = %g, "
                            "newton_maxit = %ld (need >= 0, 0 .. 1000000; "
                            "0: ARKODE's default)", s->name, o->newton_tol,
                            o->newton_maxit);
    if (fixed && o->newton_maxit != 1) {
        s->nls = cl_sun_newton_full(s->y, s->ctx);
        if (!s->nls)
            return cl_sun_sunfail(s, "cl_sun_newton_full", 0, err);
        ARK_SET(s, err, ARKStepSetNonlinearSolver, s->nls);
    }
    if (o->newton_maxit > 0 || fixed)
        ARK_SET(s, err, ARKStepSetMaxNonlinIters,
                o->newton_maxit > 0 ? (int)o->newton_maxit
                                    : CL_ARK_FIXED_MAXIT);
    if (o->newton_maxit == 1) {
        ARK_SET(s, err, ARKStepSetNonlinConvCoef, CL_ARK_ONE_COEF);
        ARK_SET(s, err, ARKStepSetEpsLin, 0.05 * 0.1 / CL_ARK_ONE_COEF);
        ARK_SET(s, err, ARKStepSetJacEvalFrequency, 1L);
        ARK_SET(s, err, ARKStepSetLSetupFrequency, 1);
    } else if (o->newton_tol > 0) {
        ARK_SET(s, err, ARKStepSetNonlinConvCoef, o->newton_tol);
    }
    /* Adaptive steps: a Newton matrix at every step.  With ARKODE's
     * default (a setup every 20 steps or at a 20 % change of gamma) the
     * stages of an undamped oscillator were solved with a stale matrix to
     * errors that the embedded estimate, which shares the stages, cannot
     * see: spring2 at rtol 1e-4 ended 2.4e-2 m off (24 % of the
     * amplitude) in 16 steps, and 1.8e-4 m with a setup every step in 17;
     * on hang (rtol 1e-4, T = 0.5 s) it costs 4 % of the CPU time. */
    if (!fixed)
        ARK_SET(s, err, ARKStepSetLSetupFrequency, 1);
    return CL_OK;
}

/* ARKStep's memory on the right-hand sides of the method, the tables, the
 * adapter's options, the fixed step. */
static cl_status ark_memory(cl_ark *a, const cl_integrator_opts *o,
                            double t0, cl_error *err)
{
    cl_sun *s = &a->base;
    cl_status st = cl_sun_created(s, ARKStepCreate(a->fe, a->fi, t0, s->y,
                                                   s->ctx),
                                  "ARKStepCreate", err);
    if (st == CL_OK)
        st = ark_tables(a, o, err);
    if (st == CL_OK)
        st = cl_sun_configure(s, o, err);
    if (st != CL_OK)
        return st;
    if (a->m->fixed && !(o->dt > 0))
        return cl_error_set(err, CL_EINVAL, "%s: dt = %g (need > 0)",
                            s->name, o->dt);
    if (a->m->fixed)
        ARK_SET(s, err, ARKStepSetFixedStep, o->dt);
    ARK_SET(s, err, ARKStepSetDeduceImplicitRhs, SUNTRUE);
    return CL_OK;
}

/* The split of an IMEX method: the system's implicit terms, and the rest
 * explicit. */
static cl_status ark_split(cl_ark *a, cl_error *err)
{
    cl_sun *s = &a->base;
    const cl_system *sys = s->sys;
    if (!sys->force_terms || !sys->jacobian_terms || sys->nterm > 64)
        return cl_error_set(err, CL_EUNSUPPORTED, "%s: the system cannot "
                            "evaluate its force terms apart (an IMEX split "
                            "needs a model of terms)", s->name);
    uint64_t all = sys->nterm == 64 ? UINT64_MAX
                                    : (UINT64_C(1) << sys->nterm) - 1;
    s->split = true;
    s->implicit = sys->implicit_terms & all;
    a->expl = all & ~s->implicit;
    a->fe = ark_fe_split;
    a->fi = ark_fi_split;
    return CL_OK;
}

cl_status cl_ark_create(const cl_ark_method *m, const cl_system *sys,
                        const cl_integrator_opts *o, double t0,
                        const double *x0, const double *v0, void **state,
                        cl_error *err)
{
    cl_sun *s = NULL;
    *state = NULL;
    cl_status st = cl_sun_alloc(sizeof(cl_ark), m->name, &ark_api, sys, o,
                                t0, x0, v0, true, false, &s, err);
    if (st != CL_OK)
        return st;
    cl_ark *a = (cl_ark *)s;
    a->m = m;
    a->t0 = t0;
    a->dt = o->dt;
    s->fixed_steps = m->fixed;
    a->fi = cl_sun_cvode_rhs; /* DIRK: y' = (v, M^-1 f), all implicit */
    if (m->imex)
        st = ark_split(a, err);
    if (st == CL_OK)
        st = ark_memory(a, o, t0, err);
    if (st == CL_OK)
        st = cl_sunred_attach(s, o, false, err);
    if (st == CL_OK)
        st = ark_newton(s, m->fixed, o, err);
    return cl_sun_finish(s, st, cl_sun_free, state);
}

/* The fixed-step methods: when the system has hooks (contact figures,
 * step_done: tearing), they follow every step, as for every fixed-step
 * method (system/system.h), not only the output times: the adapter is
 * then advanced one step at a time, and the state is the same whatever
 * the output times. */
cl_status cl_ark_advance(void *state, double t_out, double *x, double *v,
                         cl_error *err)
{
    cl_ark *a = state;
    const cl_system *sys = a->base.sys;
    if (!a->m->fixed)
        return cl_sun_advance(state, t_out, x, v, err);
    cl_status st = cl_fixed_steps_to(t_out - a->t0, a->dt, a->done,
                                     &a->todo, err);
    long steps = a->todo;
    if (st != CL_OK)
        return st;
    if (steps <= 1 || !(sys->step_done || sys->contact))
        return cl_sun_advance(state, t_out, x, v, err);
    for (long k = 0; st == CL_OK && k < steps; k++) {
        a->todo = 1;
        st = cl_sun_advance(state, a->t0 + (double)(a->done + 1) * a->dt, x,
                            v, err);
    }
    return st;
}
