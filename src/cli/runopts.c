/* The [run] keys of the subcommands that run integrators (run, stability,
 * convergence, energy): the rows they share, the list of integrators and
 * the check of their options against what each integrator takes. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

#define RUN_ROW(f) .sec = "run", .field = offsetof(cl_cli_run, f)

/* [run] format's names, bit k for the k-th (CL_CLI_FMT_...) */
static const char *const run_formats[] = {"csv", "vtk", "obj", NULL};

const cl_cli_opt cl_cli_run_rows[] = {
    {.name = "dt", .arg = "H", .type = CL_CLI_DOUBLE, .key = "dt",
     RUN_ROW(io.dt), .lo = 0, .hi = INFINITY,
     .help = "step of the fixed-step integrators, and of petsc-* given "
             "one; in run, also the first step of the other adaptive ones "
             "(the studies leave theirs to them) (s)"},
    {.name = "rtol", .arg = "R", .type = CL_CLI_DOUBLE, .key = "rtol",
     RUN_ROW(io.rtol), .def = 1e-6, .lo = 1e-15, .hi = 1,
     .help = "relative tolerance of the adaptive integrators"},
    {.name = "atol", .arg = "A", .type = CL_CLI_DOUBLE, .key = "atol",
     RUN_ROW(io.atol), .def = 1e-8, .lo = 1e-300, .hi = INFINITY,
     .help = "absolute tolerance of the adaptive integrators"},
    {.name = "linsol", .arg = "NAME", .type = CL_CLI_STRING, .key = "linsol",
     RUN_ROW(io.linsol),
     .help = "linear solver of implicit integrators (klu, pcg, ...; "
             "clothode list)"},
    {.name = "table", .arg = "NAME", .type = CL_CLI_STRING, .key = "table",
     RUN_ROW(io.table),
     .help = "Butcher table of the arkode-* integrators (SDIRK_2_1_2, "
             "ARK436L2SA, ...; clothode list)"},
    {.name = "petsc", .arg = "OPTIONS", .type = CL_CLI_STRING,
     .key = "petsc", RUN_ROW(io.petsc),
     .help = "PETSc options of the petsc-* integrators (\"-ts_adapt_type "
             "basic -pc_type gamg\"), over clothode's own choices"},
    {.name = "max-order", .arg = "K", .type = CL_CLI_INT, .key = "max_order",
     RUN_ROW(io.max_order), .lo = 0, .hi = 12,
     .help = "highest order of CVODE / IDA, 0 for theirs (at most 5 for "
             "BDF, 12 for Adams; BDF beyond 2 is not A-stable); petsc-bdf's "
             "fixed order, 1 .. 6 (1 .. 2 at fixed steps)"},
    {.name = "t-end", .arg = "T", .type = CL_CLI_DOUBLE, .key = "t_end",
     RUN_ROW(t_end), .def = 2.0, .lo = 1e-300, .hi = INFINITY,
     .help = "final time (s)"},
    {.type = CL_CLI_LONG, .key = "max_steps", RUN_ROW(io.max_steps),
     .lo = 0, .hi = 1099511627776.0,
     .help = "steps per output interval of an adaptive solver, 0 for its "
             "own limit"},
    {.type = CL_CLI_DOUBLE, .key = "newton_tol", RUN_ROW(io.newton_tol),
     .lo = 0, .hi = 1,
     .help = "Newton tolerance of kinsol-* (convergence coefficient of "
             "arkode-*), 0 for theirs"},
    {.name = "max-newton", .arg = "N", .type = CL_CLI_LONG,
     .key = "newton_maxit", RUN_ROW(io.newton_maxit), .lo = 0, .hi = 1000000,
     .help = "Newton iterations per step of kinsol-* (per stage of "
             "arkode-*), 0 for theirs; 1: one linearisation"},
    {.type = CL_CLI_DOUBLE, .key = "lin_tol", RUN_ROW(io.lin_tol), .lo = 0,
     .hi = 1, .help = "tolerance of the iterative linear solvers of "
                      "semi-* and kinsol-*, and of cvode-bdf-gmres, 0 for "
                      "theirs (CVODE, IDA and ARKODE set it themselves)"},
    {.type = CL_CLI_LONG, .key = "lin_maxit", RUN_ROW(io.lin_maxit), .lo = 0,
     .hi = 100000000,
     .help = "iterations of the iterative linear solvers, 0 for theirs"},
    {.type = CL_CLI_DOUBLE, .key = "verlet_damping", RUN_ROW(io.vdamp),
     .lo = 0, .hi = 0.999999,
     .help = "velocity damping of the Verlet integrators (the Verlet-and-PBD "
             "report)"},
    {.name = "rho-inf", .arg = "RHO", .type = CL_CLI_DOUBLE,
     .key = "rho_inf", RUN_ROW(io.rho_inf), .def = 0.5, .lo = 0, .hi = 1,
     .help = "kinsol-galpha's spectral radius at infinite step (1: no "
             "numerical damping, 0: the most)"},
    {.type = CL_CLI_DOUBLE, .key = "rayleigh_alpha",
     RUN_ROW(io.rayleigh_alpha), .lo = 0, .hi = INFINITY,
     .help = "Rayleigh damping of the kinsol-* integrators, mass part "
             "alpha M (1/s)"},
    {.type = CL_CLI_DOUBLE, .key = "rayleigh_beta",
     RUN_ROW(io.rayleigh_beta), .lo = 0, .hi = INFINITY,
     .help = "Rayleigh damping of the kinsol-* integrators, stiffness part "
             "beta K (s)"},
    {.name = "substeps", .arg = "S", .type = CL_CLI_LONG, .key = "substeps",
     RUN_ROW(io.substeps), .lo = 0, .hi = 1000000,
     .help = "substeps per step of xpbd and pd, 0 for 1 (Macklin et al., "
             "\"Small steps in physics simulation\")"},
    {.name = "iterations", .arg = "K", .type = CL_CLI_LONG,
     .key = "iterations", RUN_ROW(io.iterations), .lo = 0, .hi = 1000000,
     .help = "constraint iterations per substep of xpbd and pd, 0 for "
             "theirs (xpbd 1, pd 10)"},
    {.type = CL_CLI_DOUBLE, .key = "max_stretch", RUN_ROW(max_stretch),
     .def = 10.0, .lo = 1.0, .hi = INFINITY,
     .help = "a stretch d/L beyond this counts as a blow-up"},
    /* run's own outputs and budgets: the studies do not read them
     * (CL_CLI_RUN_OUTPUTS, unread), so that a problem file written for run
     * serves the studies too */
    {.name = "threads", .arg = "N", .type = CL_CLI_LONG, .key = "threads",
     RUN_ROW(threads), .def = 1, .lo = 1, .hi = CL_MODEL_MAX_THREADS,
     .help = "threads for the pair terms' forces and Jacobians, the "
             "Krylov products and pcg's preconditioner and vector "
             "operations; results are the same for every N"},
    {.name = "samples", .arg = "S", .type = CL_CLI_LONG, .key = "samples",
     RUN_ROW(samples), .def = 200, .lo = 1, .hi = 100000000,
     .help = "time-series rows after t = 0; with fixed steps on the "
             "nearest steps, so at most one a step"},
    {.name = "frames", .arg = "K", .type = CL_CLI_LONG, .key = "frames",
     RUN_ROW(frames), .def = 10, .lo = 0, .hi = 1000000,
     .help = "frames after t = 0, 0 for none"},
    {.name = "format", .arg = "LIST", .type = CL_CLI_NAMES, .key = "format",
     RUN_ROW(format), .sdef = "vtk,obj", .names = run_formats,
     .help = "frame formats among csv,vtk,obj (csv alone: the time "
             "series, no frames; --frames is refused with it)"},
    {.name = "max-wall", .arg = "SECONDS", .type = CL_CLI_DOUBLE,
     .key = "budget_wall", RUN_ROW(budget_wall), .def = 0, .lo = 0,
     .hi = INFINITY,
     .help = "end the run with status budget (exit 5) once it has run this "
             "long, 0 for no limit"},
    {.name = "max-steps", .arg = "N", .type = CL_CLI_LONG,
     .key = "budget_steps", RUN_ROW(budget_steps), .def = 0, .lo = 0,
     .hi = 1099511627776.0,
     .help = "end the run with status budget (exit 5) at the first output "
             "time after the integrator has taken N steps, 0 for no limit"},
    {.type = CL_CLI_END}};

/* Entry "name" or "name:linsol" of the list into m. */
static cl_status parse_method(cl_config *cfg, const cl_cli_opt *row,
                              const char *p, size_t len, cl_cli_method *m,
                              cl_error *err)
{
    char name[64], why[1024];
    size_t nlen = strcspn(p, ":");
    nlen = nlen < len ? nlen : len;
    if (len >= sizeof m->label || nlen == 0 || nlen + 1 == len ||
        (nlen < len && len - nlen - 1 >= sizeof m->linsol)) {
        snprintf(why, sizeof why, "bad entry \"%.*s\" (expected NAME or "
                 "NAME:LINSOL)", (int)len, p);
        return cl_config_refuse(cfg, row->sec, row->key, CL_EINVAL, why, err);
    }
    memcpy(m->label, p, len);
    m->label[len] = '\0';
    memcpy(name, p, nlen);
    name[nlen] = '\0';
    snprintf(m->linsol, sizeof m->linsol, "%s",
             nlen < len ? m->label + nlen + 1 : "");
    if ((m->type = cl_integrator_find(name)))
        return CL_OK;
    const char *names[64];
    size_t n = 0;
    for (; cl_integrator_registry[n] && n < 63; n++)
        names[n] = cl_integrator_registry[n]->name;
    names[n] = NULL;
    int at = snprintf(why, sizeof why, "unknown integrator \"%s\" (expected "
                      "one of ", name);
    cl_cli_join(names, why + at, sizeof why - (size_t)at - 1);
    strcat(why, ")");
    return cl_config_refuse(cfg, row->sec, row->key, CL_EINVAL, why, err);
}

cl_status cl_cli_methods_read(cl_config *cfg, const cl_cli_opt *row,
                              cl_cli_methods *ms, cl_error *err)
{
    const char *list = cl_config_string(cfg, row->sec, row->key,
                                        row->sdef ? row->sdef : "");
    int max = (int)row->hi;
    char why[64];
    ms->n = 0;
    for (const char *p = list; *p;) {
        size_t len = strcspn(p, ",");
        if (ms->n == max) {
            snprintf(why, sizeof why, "more than %d entr%s", max,
                     max == 1 ? "y" : "ies");
            return cl_config_refuse(cfg, row->sec, row->key, CL_EINVAL, why,
                                    err);
        }
        cl_status rc = parse_method(cfg, row, p, len, &ms->m[ms->n], err);
        if (rc)
            return rc;
        ms->n++;
        p += len + (p[len] == ',');
    }
    return ms->n ? CL_OK
                 : cl_config_refuse(cfg, row->sec, row->key, CL_EINVAL,
                                    "no integrator", err);
}

/* "ORIGIN: [run] key = value: integrator NAME why" for a number. */
static cl_status refuse_number(cl_config *cfg, const char *key, double value,
                               const cl_integrator_type *type,
                               const char *why, cl_error *err)
{
    char where[256];
    return cl_error_set(err, CL_EINVAL, "%s: [run] %s = %g: integrator %s %s",
                        cl_config_origin(cfg, "run", key, where,
                                         sizeof where),
                        key, value, type->name, why);
}

/* Whether the integrator of some method of ms has the flag at `flag`
 * (offsetof a bool of cl_integrator_type). */
static bool some_takes(const cl_cli_methods *ms, size_t flag)
{
    for (int k = 0; k < ms->n; k++)
        if (*(const bool *)((const char *)ms->m[k].type + flag))
            return true;
    return false;
}

#define SOME_TAKE(ms, field) some_takes(ms, offsetof(cl_integrator_type, field))

/* The options of [run], one for the whole list, against what the list's
 * integrators take: each is refused (naming the first method's) only when
 * none of them takes it. */
static cl_status check_shared(cl_config *cfg, const cl_cli_methods *ms,
                              const cl_integrator_opts *io, cl_error *err)
{
    const cl_integrator_type *type = ms->m[0].type;
    char why[128];
    if (*io->linsol && !SOME_TAKE(ms, takes_linsol)) {
        snprintf(why, sizeof why, "integrator %s has no choice of linear "
                 "solver", type->name);
        return cl_config_refuse(cfg, "run", "linsol", CL_EINVAL, why, err);
    }
    if (io->petsc && *io->petsc && !SOME_TAKE(ms, takes_petsc))
        return cl_config_refuse(cfg, "run", "petsc", CL_EINVAL,
                                "only the petsc-* integrators take PETSc "
                                "options", err);
    if (io->max_order && !SOME_TAKE(ms, takes_max_order))
        return refuse_number(cfg, "max_order", io->max_order, type,
                             "has no choice of order (CVODE, IDA and "
                             "petsc-bdf have)", err);
    if (io->substeps && !SOME_TAKE(ms, takes_iterations))
        return refuse_number(cfg, "substeps", io->substeps, type,
                             "takes no substeps (xpbd and pd do)", err);
    if (io->iterations && !SOME_TAKE(ms, takes_iterations))
        return refuse_number(cfg, "iterations", io->iterations, type,
                             "has no constraint iterations (xpbd and pd "
                             "have)", err);
    if ((io->rayleigh_alpha != 0.0 || io->rayleigh_beta != 0.0) &&
        !SOME_TAKE(ms, takes_rayleigh)) {
        bool alpha = io->rayleigh_alpha != 0.0;
        return refuse_number(cfg, alpha ? "rayleigh_alpha" : "rayleigh_beta",
                             alpha ? io->rayleigh_alpha : io->rayleigh_beta,
                             type, "has no Rayleigh damping (the kinsol-* "
                             "integrators have)", err);
    }
    if (io->table && *io->table && !SOME_TAKE(ms, takes_table)) {
        snprintf(why, sizeof why, "integrator %s has no choice of table "
                 "(the arkode-* integrators have)", type->name);
        return cl_config_refuse(cfg, "run", "table", CL_EINVAL, why, err);
    }
    return CL_OK;
}

/* Method m's own: the linear solver of its entry NAME:LINSOL, and a
 * fixed step where the command uses one. */
static cl_status check_method(cl_config *cfg, const cl_cli_method *m,
                              cl_cli_dt_use dt, cl_error *err)
{
    const cl_integrator_type *type = m->type;
    char why[128];
    if (*m->linsol && !type->takes_linsol) {
        snprintf(why, sizeof why, "integrator %s has no choice of linear "
                 "solver", type->name);
        return cl_config_refuse(cfg, "run", "integrator", CL_EINVAL, why,
                                err);
    }
    if (dt != CL_CLI_DT_NONE && type->fixed_step && !(m->io.dt > 0))
        return refuse_number(cfg, "dt", m->io.dt, type, "takes fixed steps "
                             "and needs dt > 0 (--dt H)", err);
    return CL_OK;
}

/* The options of [run] that m's integrator does not take, cleared: they
 * serve the others of the list. */
static void keep_what_it_takes(cl_cli_method *m)
{
    const cl_integrator_type *type = m->type;
    if (!type->takes_linsol)
        m->io.linsol = "";
    if (!type->takes_petsc)
        m->io.petsc = NULL;
    if (!type->takes_max_order)
        m->io.max_order = 0;
    if (!type->takes_iterations)
        m->io.substeps = m->io.iterations = 0;
    if (!type->takes_table)
        m->io.table = NULL;
    if (!type->takes_rayleigh)
        m->io.rayleigh_alpha = m->io.rayleigh_beta = 0.0;
}

/* m's linear solver (after keep_what_it_takes): the one named, or the
 * integrator's default ("" for the registry's first, klu). */
static const char *linsol_of(const cl_cli_method *m)
{
    return *m->io.linsol || !m->type->linsol_default
               ? m->io.linsol
               : m->type->linsol_default;
}

/* Whether m's linear solver is iterative: a cl_linsol with a tolerance
 * (CVODE's klu-full is no cl_linsol). */
static bool linsol_iterative(const cl_cli_method *m)
{
    const cl_linsol_type *lt = m->type->takes_linsol
                                   ? cl_linsol_find(linsol_of(m))
                                   : NULL;
    return lt && lt->solve_tol;
}

static bool reads_tolerances(const cl_cli_method *m)
{
    return !cl_integrator_fixed(m->type, m->io.dt) || m->type->takes_table;
}

static bool reads_max_steps(const cl_cli_method *m)
{
    return !m->type->fixed_step;
}

static bool reads_newton(const cl_cli_method *m)
{
    return m->type->takes_newton_maxit;
}

static bool reads_rho_inf(const cl_cli_method *m)
{
    return m->type->takes_rho_inf;
}

static bool reads_vdamp(const cl_cli_method *m)
{
    return m->type->takes_vdamp;
}

/* A Krylov solver of its own (cvode-bdf-gmres). */
static bool own_krylov(const cl_cli_method *m)
{
    return m->type->takes_lin_tol && !m->type->takes_linsol;
}

static bool reads_lin_tol(const cl_cli_method *m)
{
    return own_krylov(m) || (m->type->takes_lin_tol && linsol_iterative(m));
}

static bool reads_lin_maxit(const cl_cli_method *m)
{
    return own_krylov(m) || linsol_iterative(m);
}

/* The [run] keys some integrators read and others do not, with who
 * reads them.  A problem file's keys serve whichever integrator runs it;
 * one the command line gave that no method of the list reads would
 * change nothing, and is refused. */
static const struct {
    const char *key;
    bool (*reads)(const cl_cli_method *m);
    const char *who;
} method_keys[] = {
    {"rtol", reads_tolerances, "the adaptive integrators (petsc-* without "
                               "a dt) and arkode-* do"},
    {"atol", reads_tolerances, "the adaptive integrators (petsc-* without "
                               "a dt) and arkode-* do"},
    {"max_steps", reads_max_steps, "the adaptive integrators do"},
    {"newton_tol", reads_newton, "kinsol-* and arkode-* do"},
    {"newton_maxit", reads_newton, "kinsol-* and arkode-* do"},
    {"rho_inf", reads_rho_inf, "kinsol-galpha does; petsc-alpha2 takes "
                               "--petsc \"-ts_alpha_radius R\""},
    {"verlet_damping", reads_vdamp, "verlet and verlet-pbd do"},
    {"lin_tol", reads_lin_tol, "semi-* and kinsol-* with an iterative "
                               "--linsol (pcg, pcg-jacobi, amg, amg-hypre, "
                               "auto) do, and cvode-bdf-gmres; CVODE, IDA "
                               "and ARKODE set an iterative solver's "
                               "tolerance themselves"},
    {"lin_maxit", reads_lin_maxit, "the iterative linear solvers (pcg, "
                                   "pcg-jacobi, amg, amg-hypre, auto) and "
                                   "cvode-bdf-gmres do"},
};

static cl_status check_command_keys(cl_config *cfg, const cl_cli_methods *ms,
                                    cl_error *err)
{
    char why[512];
    for (size_t i = 0; i < sizeof method_keys / sizeof *method_keys; i++) {
        const char *key = method_keys[i].key;
        bool read = false;
        for (int k = 0; !read && k < ms->n; k++)
            read = method_keys[i].reads(&ms->m[k]);
        if (read || !cl_config_set_by_command(cfg, "run", key))
            continue;
        const cl_cli_method *m = &ms->m[0];
        if (ms->n == 1)
            snprintf(why, sizeof why, "integrator %s%s%s%s reads no %s (%s)",
                     m->type->name,
                     m->type->takes_linsol ? " with linear solver " : "",
                     !m->type->takes_linsol ? ""
                     : *m->io.linsol        ? m->io.linsol
                     : *linsol_of(m)        ? linsol_of(m)
                                            : "klu",
                     m->type->takes_linsol && !*m->io.linsol
                         ? " (its default)"
                         : "",
                     key, method_keys[i].who);
        else
            snprintf(why, sizeof why, "no integrator of the list reads %s "
                     "(%s)", key, method_keys[i].who);
        return cl_config_refuse(cfg, "run", key, CL_EINVAL, why, err);
    }
    return CL_OK;
}

cl_status cl_cli_methods_check(cl_config *cfg, cl_cli_methods *ms,
                               const cl_integrator_opts *io, cl_cli_dt_use dt,
                               cl_error *err)
{
    cl_status rc = ms->n ? check_shared(cfg, ms, io, err) : CL_OK;
    for (int k = 0; !rc && k < ms->n; k++) {
        cl_cli_method *m = &ms->m[k];
        m->io = *io;
        keep_what_it_takes(m);
        if (*m->linsol)
            m->io.linsol = m->linsol;
        if (dt == CL_CLI_DT_FIXED && !m->type->fixed_step &&
            !m->type->dt_fixes_step)
            m->io.dt = 0.0; /* not a first step: an adaptive one's own */
        rc = check_method(cfg, m, dt, err);
    }
    return rc ? rc : check_command_keys(cfg, ms, err);
}

cl_status cl_cli_methods_fixed(cl_config *cfg, const cl_cli_methods *ms,
                               const char *cmd, cl_error *err)
{
    char where[256];
    for (int k = 0; k < ms->n; k++)
        if (!ms->m[k].type->fixed_step)
            return cl_error_set(err, CL_EINVAL, "%s: [run] integrator: %s "
                                "%s; %s takes fixed-step integrators",
                                cl_config_origin(cfg, "run", "integrator",
                                                 where, sizeof where),
                                ms->m[k].type->name,
                                ms->m[k].type->dt_fixes_step
                                    ? "takes fixed steps only with its own "
                                      "--dt, and is no fixed-step method"
                                    : "chooses its own steps by error "
                                      "control", cmd);
    return CL_OK;
}

cl_status cl_cli_methods_try(cl_model *model, const cl_cli_methods *ms,
                             cl_error *err)
{
    const cl_system *sys = cl_model_system(model);
    double *x = malloc(sys->n * sizeof *x), *v = malloc(sys->n * sizeof *v);
    cl_status rc = x && v ? cl_model_initial_state(model, x, v)
                          : cl_error_set(err, CL_ENOMEM, "out of memory");
    for (int k = 0; !rc && k < ms->n; k++) {
        const cl_cli_method *m = &ms->m[k];
        void *state = NULL;
        cl_integrator_opts io = m->io;
        if (m->type->fixed_step && !(io.dt > 0))
            io.dt = 1.0; /* a search (stability) sets the step later */
        cl_error why = {0};
        if ((rc = cl_integrator_create(m->type, sys, &io,
                                       cl_model_start_time(model), x, v,
                                       &state, &why)))
            cl_error_set(err, rc, "%s: %s", m->label, why.msg);
        if (state)
            m->type->free(state);
    }
    free(x);
    free(v);
    return rc;
}
