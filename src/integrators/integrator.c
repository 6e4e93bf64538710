/* Integrator registry lookup, fixed-step bookkeeping and statistics output
 * (docs/integrators.md, 1).
 *
 * Fixed-step methods count steps, never accumulate time: the time after step
 * k is t0 + k dt, and an output time must be a whole number of steps from t0
 * (to 1e-9 relative), so a run to T in steps of dt takes exactly T/dt steps
 * whatever the number of output times in between. */
#include "integrators/integrator.h"

#include "integrators/memguard.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A system with barriers needs a start outside every barrier obstacle
 * (system.h, step_fraction): its force is CL_EINFEASIBLE there, which the
 * integrators would report as a failed step or a blow-up at t0. */
static cl_status check_feasible_start(const cl_system *sys, double t0,
                                      const double *x0, const double *v0,
                                      cl_error *err)
{
    if (!sys->step_fraction)
        return CL_OK;
    double *f = malloc(sys->n * sizeof *f);
    if (!f)
        return cl_error_set(err, CL_ENOMEM, "out of memory");
    cl_status st = sys->force(sys->data, t0, x0, v0, f);
    free(f);
    if (st != CL_EINFEASIBLE)
        return CL_OK; /* other failures are the integrator's to report */
    return cl_error_set(err, CL_EINVAL, "the initial state (t = %g) has a "
                        "particle at d <= 0 of a barrier obstacle, inside it "
                        "or on its surface; a barrier needs every particle "
                        "outside at the start (move the cloth or the "
                        "obstacle, or use response = penalty)", t0);
}

cl_status cl_integrator_create(const cl_integrator_type *type,
                               const cl_system *sys,
                               const cl_integrator_opts *o, double t0,
                               const double *x0, const double *v0,
                               void **state, cl_error *err)
{
    *state = NULL;
    if (!type || !sys || !o) /* cl_integrator_find: NULL for an unknown name */
        return cl_error_set(err, CL_EINVAL, "no integrator%s", type ? (sys ?
                            " options" : " system") : " (an unknown name?)");
    cl_status rc = o->force ? CL_OK
                            : cl_memguard_check(type, sys, o->linsol, err);
    if (!rc)
        rc = check_feasible_start(sys, t0, x0, v0, err);
    if (!rc && !type->takes_rayleigh &&
        (o->rayleigh_alpha != 0.0 || o->rayleigh_beta != 0.0))
        rc = cl_error_set(err, CL_EUNSUPPORTED, "%s: no Rayleigh damping "
                          "(rayleigh_alpha = %g, rayleigh_beta = %g; the "
                          "kinsol-* integrators take it)", type->name,
                          o->rayleigh_alpha, o->rayleigh_beta);
    return rc ? rc : type->create(sys, o, t0, x0, v0, state, err);
}

const cl_integrator_type *cl_integrator_find(const char *name)
{
    if (!name)
        return NULL;
    for (size_t i = 0; cl_integrator_registry[i]; i++) {
        if (strcmp(cl_integrator_registry[i]->name, name) == 0)
            return cl_integrator_registry[i];
    }
    return NULL;
}

cl_status cl_output_time_check(const char *name, double t_out, double t_now,
                               cl_error *err)
{
    if (!isfinite(t_out))
        return cl_error_set(err, CL_EINVAL, "%s: output time %g is not "
                            "finite", name, t_out);
    if (t_out < t_now)
        return cl_error_set(err, CL_EINVAL, "%s: output time %.17g lies "
                            "behind the current time %.17g", name, t_out,
                            t_now);
    return CL_OK;
}

cl_status cl_fixed_steps_to(double t_out, double dt, long done, long *nsteps,
                            cl_error *err)
{
    if (!isfinite(dt) || !(dt > 0.0))
        return cl_error_set(err, CL_EINVAL,
                            "fixed step dt = %g: must be finite and > 0", dt);
    if (!isfinite(t_out))
        return cl_error_set(err, CL_EINVAL, "output time %g is not finite",
                            t_out);
    double q = t_out / dt;
    if (!(fabs(q) < (double)(LONG_MAX / 2)))
        return cl_error_set(err, CL_EINVAL,
                            "output time %g is %g steps of dt = %g: too many",
                            t_out, q, dt);
    double k = nearbyint(q);
    if (fabs(q - k) > 1e-9 * fmax(1.0, fabs(q)))
        return cl_error_set(err, CL_EINVAL,
                            "output time %.17g is not a multiple of the fixed "
                            "step dt = %.17g (%.12g steps)", t_out, dt, q);
    if ((long)k < done)
        return cl_error_set(err, CL_EINVAL,
                            "output time %.17g (step %ld) lies behind the "
                            "current step %ld (dt = %g)", t_out, (long)k,
                            done, dt);
    *nsteps = (long)k - done;
    return CL_OK;
}

/* CL_EUNSUPPORTED for a contact response the method cannot apply. */
static cl_status refuse_response(const char *name, const char *response,
                                 const char *instead, cl_error *err)
{
    return cl_error_set(err, CL_EUNSUPPORTED, "%s cannot apply a contact "
                        "response = %s; %s", name, response, instead);
}

cl_status cl_integrator_refuse_projection(const char *name,
                                          const cl_system *sys,
                                          cl_error *err)
{
    return sys->projects
               ? refuse_response(name, "project (only the explicit, "
                                 "semi-*, kinsol-*, xpbd and pd methods and "
                                 "CVODE BDF can)", "use response = penalty, "
                                 "or another integrator", err)
               : CL_OK;
}

cl_status cl_integrator_refuse_constraints(const char *name,
                                           const cl_system *sys,
                                           cl_error *err)
{
    return sys->constrain
               ? refuse_response(name, "constraint (only semi-be and "
                                 "semi-bdf2 can, inside their linear solve)",
                                 "use response = penalty or project, or one "
                                 "of those two", err)
               : CL_OK;
}

cl_status cl_integrator_contact_at(const char *name, const cl_system *sys,
                                   double t, double *x, double *v,
                                   cl_error *err)
{
    cl_status st = sys->contact
                       ? sys->contact(sys->data, t, x, v,
                                      CL_CONTACT_RECORD | CL_CONTACT_PROJECT)
                       : CL_OK;
    if (st != CL_OK)
        return cl_error_set(err, st, "%s: contact at t = %.9g failed (%s)",
                            name, t, cl_status_name(st));
    return CL_OK;
}

typedef struct {
    const char *csv;   /* CSV name */
    const char *human; /* label in the human block */
} cl_stat_name;

static const cl_stat_name cl_counter_names[] = {
    {"steps", "steps"},
    {"rhs_evals", "RHS evaluations"},
    {"jac_evals", "Jacobian evaluations"},
    {"lin_setups", "linear setups"},
    {"lin_solves", "linear solves"},
    {"lin_iters", "linear (Krylov) iterations"},
    {"nonlin_iters", "nonlinear iterations"},
    {"nonlin_fails", "nonlinear conv. failures"},
    {"err_fails", "error test failures"},
    {"symbolic_facts", "symbolic factorisations"},
    {"lin_fallbacks", "linear solver fallbacks"},
};

static void stats_counters(const cl_stats *s, long out[11])
{
    out[0] = s->steps;
    out[1] = s->rhs_evals;
    out[2] = s->jac_evals;
    out[3] = s->lin_setups;
    out[4] = s->lin_solves;
    out[5] = s->lin_iters;
    out[6] = s->nonlin_iters;
    out[7] = s->nonlin_fails;
    out[8] = s->err_fails;
    out[9] = s->symbolic_facts;
    out[10] = s->lin_fallbacks;
}

/* human: one aligned block "label  value", then wall and cpu in seconds;
 * otherwise one "name,value" row per counter (no header row), then the
 * recovered linear solves and the linear solver's name (each only when
 * reported), without the times (stats.csv: identical runs write identical
 * bytes; the times go to run.json). */
void cl_stats_print(const cl_stats *s, FILE *fp, bool human)
{
    enum { NC = sizeof cl_counter_names / sizeof cl_counter_names[0] };
    long c[NC];
    stats_counters(s, c);
    for (size_t i = 0; i < NC; i++) {
        if (human && c[i] == CL_STAT_NA)
            fprintf(fp, "  %-28s %14s\n", cl_counter_names[i].human, "n/a");
        else if (human)
            fprintf(fp, "  %-28s %14ld\n", cl_counter_names[i].human, c[i]);
        else if (c[i] == CL_STAT_NA)
            fprintf(fp, "%s,NA\n", cl_counter_names[i].csv);
        else
            fprintf(fp, "%s,%ld\n", cl_counter_names[i].csv, c[i]);
    }
    if (s->lin_recoveries > 0 && human)
        fprintf(fp, "  %-28s %14ld\n", "linear solve recoveries",
                s->lin_recoveries);
    else if (s->lin_recoveries > 0)
        fprintf(fp, "lin_recoveries,%ld\n", s->lin_recoveries);
    if (s->linsol[0] && human)
        fprintf(fp, "  %-28s %14s\n", "linear solver", s->linsol);
    else if (s->linsol[0])
        fprintf(fp, "linsol,%s\n", s->linsol);
    if (human) {
        fprintf(fp, "  %-28s %14.6f\n", "wall time [s]", s->wall);
        fprintf(fp, "  %-28s %14.6f\n", "cpu time [s]", s->cpu);
    }
}
