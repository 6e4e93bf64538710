/* Equal-budget study: see budget.h. */
#include "analysis/budget.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/diagnostics.h"
#include "analysis/trial.h"

/* The options of split S, K and its (sub)step h = dt / S. */
static cl_integrator_opts split_opts(const cl_integrator_type *type,
                                     const cl_integrator_opts *io, long S,
                                     long K, double *h)
{
    cl_integrator_opts o = *io;
    if (type->takes_iterations) {
        o.substeps = S;
        o.iterations = K;
    } else {
        o.dt = io->dt / (double)S;
        if (type->takes_newton_maxit)
            o.newton_maxit = K;
    }
    *h = io->dt / (double)S;
    return o;
}

bool cl_budget_takes_k(const cl_integrator_type *type)
{
    return type->takes_iterations || type->takes_newton_maxit;
}

cl_status cl_budget_check(const cl_integrator_type *type,
                          const cl_integrator_opts *io,
                          const cl_budget_opts *o, cl_error *err)
{
    if (!type->fixed_step)
        return cl_error_set(err, CL_EINVAL, "budget: %s chooses its own "
                            "steps; the study splits fixed steps",
                            type->name);
    if (type->newton_per_stage)
        return cl_error_set(err, CL_EINVAL, "budget: %s caps the Newton "
                            "iterations of each stage, and retries a stage "
                            "that fails, so it cannot be held to B "
                            "iterations per step (10 steps of K = 4 took 236 "
                            "on ms-hang); compare kinsol-* or the "
                            "constraint methods", type->name);
    if (o->budget < 1 || o->budget > 1000)
        return cl_error_set(err, CL_EINVAL, "budget = %ld: expected 1 .. "
                            "1000", o->budget);
    cl_status rc = CL_OK;
    for (long S = 1; !rc && S <= o->budget; S++) {
        double h;
        if (o->budget % S == 0) {
            cl_integrator_opts so = split_opts(type, io, S, o->budget / S,
                                               &h);
            rc = cl_trial_whole_steps(type, so.dt, o->t_end, err);
        }
    }
    return rc;
}

/* E(t0 + T) - E(t0) of a run over T ending at x, v, from the initial
 * state x0, v0 at the model's start time t0. */
static double energy_change(cl_model *m, const double *x, const double *v,
                            double T, const double *x0, const double *v0)
{
    const cl_system *sys = cl_model_system(m);
    double t0 = cl_model_start_time(m);
    cl_energy e0, e1;
    if (sys->energy(sys->data, t0, x0, v0, &e0) ||
        sys->energy(sys->data, t0 + T, x, v, &e1))
        return NAN;
    return e1.total - e0.total;
}

double cl_budget_reference_energy(cl_model *m, const cl_conv_ref *ref,
                                  double T)
{
    size_t n = cl_model_system(m)->n;
    double *x0 = malloc(2 * n * sizeof *x0 + 1);
    double de = x0 && !cl_model_initial_state(m, x0, x0 + n)
                    ? energy_change(m, ref->x, ref->v, T, x0, x0 + n)
                    : NAN;
    free(x0);
    return de;
}

static void run_split(cl_model *m, cl_trial *t, const cl_budget_result *r,
                      const cl_integrator_opts *io, const cl_budget_opts *o,
                      const cl_conv_ref *ref, const double *x0,
                      const double *v0, cl_budget_split *sp)
{
    cl_integrator_opts so = split_opts(r->type, io, sp->S, sp->K, &sp->h);
    sp->rc = cl_trial_run(t, r->type, &so, o->t_end, CL_BUDGET_CHECKS,
                          o->max_stretch, &sp->stats, &sp->why);
    sp->stretch = t->stretch_seen - 1.0;
    sp->err_x = sp->energy = NAN;
    if (sp->rc)
        return;
    size_t np = cl_model_system(m)->n / 3;
    if (ref)
        sp->err_x = cl_max_distance(t->x, ref->x, np);
    sp->energy = energy_change(m, t->x, t->v, o->t_end, x0, v0);
}

cl_status cl_budget(cl_model *m, const cl_integrator_type *type,
                    const cl_integrator_opts *io, const cl_budget_opts *o,
                    const cl_conv_ref *ref, cl_budget_result *r,
                    cl_error *err)
{
    cl_trial t = {0};
    memset(r, 0, sizeof *r);
    r->type = type;
    r->label = type->name;
    r->dt = io->dt;
    cl_status rc = cl_budget_check(type, io, o, err);
    if (rc || (rc = cl_trial_init(&t, m, err)))
        return rc;
    size_t n = cl_model_system(m)->n;
    double *x0 = malloc(2 * n * sizeof *x0 + 1);
    if (!x0 || cl_model_initial_state(m, x0, x0 + n)) {
        free(x0);
        cl_trial_free(&t);
        return cl_error_set(err, CL_ENOMEM, "out of memory (budget)");
    }
    for (long S = 1; S <= o->budget && r->n < CL_BUDGET_MAX_SPLITS; S++) {
        if (o->budget % S)
            continue;
        cl_budget_split *sp = &r->s[r->n++];
        sp->S = S;
        sp->K = cl_budget_takes_k(type) ? o->budget / S : 1;
        run_split(m, &t, r, io, o, ref, x0, x0 + n, sp);
    }
    free(x0);
    cl_trial_free(&t);
    return CL_OK;
}

void cl_budget_write_rows(FILE *fp, const cl_budget_result *r, bool header)
{
    if (header)
        fprintf(fp, "integrator,dt,substeps,iterations,h,err_x,stretch,"
                    "energy,steps,rhs_evals,nonlin_iters,lin_solves,cpu,"
                    "status\n");
    for (int k = 0; k < r->n; k++) {
        const cl_budget_split *s = &r->s[k];
        fprintf(fp, "%s,%.17g,%ld,%ld,%.17g,%.17g,%.17g,%.17g,%ld,%ld,%ld,"
                    "%ld,%.6f,%s\n",
                r->label, r->dt, s->S, s->K, s->h, s->err_x, s->stretch,
                s->energy, s->stats.steps, s->stats.rhs_evals,
                s->stats.nonlin_iters, s->stats.lin_solves, s->stats.cpu,
                s->rc ? cl_status_name(s->rc) : "ok");
    }
}
