/* The numerical damping study on the cloth: energy per eigenmode after a
 * run (analysis/numdamp.h, "on the cloth"). */
#include "analysis/numdamp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/spectrum.h"
#include "analysis/trial.h"

#define ND_REST_TOL 1e-8  /* m/s^2: max |M^-1 f| of a state at rest */
#define ND_OSC_TOL 1e-6   /* mu_k / mu_max of an oscillating mode */

void cl_numdamp_modes_free(cl_numdamp_modes *b)
{
    free(b->mu);
    free(b->phi);
    free(b->sqm);
    free(b->x0);
    free(b->v0);
    memset(b, 0, sizeof *b);
}

/* CL_EINVAL unless M^-1 f(0, x0, 0) vanishes; v0 = 0 after it (sqm is
 * scratch for f). */
static cl_status nd_at_rest(const cl_system *sys, cl_numdamp_modes *b,
                            cl_error *err)
{
    double *f = b->sqm, worst = 0.0;
    memset(b->v0, 0, b->n * sizeof *b->v0);
    cl_status rc = sys->force(sys->data, 0.0, b->x0, b->v0, f);
    if (rc)
        return cl_error_set(err, rc, "damping: force at the initial state "
                            "failed");
    for (size_t i = 0; i < b->n; i++)
        worst = fmax(worst, fabs(f[i]) / sys->mass[i]);
    if (!(worst <= ND_REST_TOL))
        return cl_error_set(err, CL_EINVAL, "damping: the modes need an "
                            "initial state at rest, max |M^-1 f| = %g m/s^2 "
                            "(at most %g; e.g. --set gravity.g=0,0,0)",
                            worst, ND_REST_TOL);
    return CL_OK;
}

/* v0 = s M^-1/2 sum over the oscillating modes of phi_k, max |v0| = speed. */
static void nd_excite(cl_numdamp_modes *b, double speed)
{
    size_t n = b->n, first = n - b->nosc;
    double vmax = 0.0;
    for (size_t i = 0; i < n; i++) {
        double sum = 0.0;
        for (size_t k = first; k < n; k++)
            sum += b->phi[i * n + k];
        b->v0[i] = sum / b->sqm[i];
        vmax = fmax(vmax, fabs(b->v0[i]));
    }
    for (size_t i = 0; i < n && vmax > 0; i++)
        b->v0[i] *= speed / vmax;
}

cl_status cl_numdamp_modes_init(cl_model *m, double speed,
                                cl_numdamp_modes *b, cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    size_t n = sys->n;
    memset(b, 0, sizeof *b);
    cl_status rc = cl_trial_repeatable(m, err);
    if (rc)
        return rc;
    if (n > CL_SPECTRUM_MAX_N)
        return cl_error_set(err, CL_EUNSUPPORTED, "damping: %zu unknowns, "
                            "at most %d for the modes", n,
                            CL_SPECTRUM_MAX_N);
    b->n = n;
    b->mu = malloc(n * sizeof *b->mu);
    b->phi = malloc(n * n * sizeof *b->phi);
    b->sqm = malloc(n * sizeof *b->sqm);
    b->x0 = malloc(n * sizeof *b->x0);
    b->v0 = malloc(n * sizeof *b->v0);
    if (!b->mu || !b->phi || !b->sqm || !b->x0 || !b->v0)
        rc = cl_error_set(err, CL_ENOMEM, "damping: out of memory (%zu "
                          "modes)", n);
    if (!rc)
        rc = cl_model_initial_state(m, b->x0, b->v0);
    if (!rc)
        rc = nd_at_rest(sys, b, err);
    if (!rc)
        rc = cl_spectrum_modes(m, 0.0, b->x0, b->v0, b->mu, b->phi, err);
    for (size_t k = 0; !rc && k < n; k++) {
        b->sqm[k] = sqrt(sys->mass[k]);
        b->nosc += b->mu[k] > ND_OSC_TOL * b->mu[n - 1];
    }
    if (!rc && b->nosc == 0)
        rc = cl_error_set(err, CL_EINVAL, "damping: no oscillating mode at "
                          "the initial state");
    if (!rc)
        nd_excite(b, speed);
    if (rc)
        cl_numdamp_modes_free(b);
    return rc;
}

/* E_k at (x, v) for the oscillating modes into e (nosc). */
static void nd_modal_energy(const cl_numdamp_modes *b, const double *x,
                            const double *v, double *e)
{
    size_t n = b->n, first = n - b->nosc;
    for (size_t k = first; k < n; k++) {
        double q = 0.0, p = 0.0;
        for (size_t i = 0; i < n; i++) {
            q += b->phi[i * n + k] * b->sqm[i] * (x[i] - b->x0[i]);
            p += b->phi[i * n + k] * b->sqm[i] * v[i];
        }
        e[k - first] = 0.5 * (p * p + b->mu[k] * q * q);
    }
}

static cl_status nd_modal_alloc(const cl_numdamp_modes *b,
                                cl_numdamp_modal *r, cl_error *err)
{
    r->w = malloc(b->nosc * sizeof *r->w);
    r->ratio = malloc(b->nosc * sizeof *r->ratio);
    r->theory = malloc(b->nosc * sizeof *r->theory);
    if (!r->w || !r->ratio || !r->theory)
        return cl_error_set(err, CL_ENOMEM, "damping: out of memory");
    r->nosc = b->nosc;
    return CL_OK;
}

/* The run from (x0, v0) to T into x, v; its failure into r. */
static void nd_modal_integrate(const cl_model *m, const cl_numdamp_modes *b,
                               const cl_integrator_opts *o, cl_numdamp_modal
                               *r, double *x, double *v)
{
    const cl_system *sys = cl_model_system((cl_model *)m);
    void *state = NULL;
    r->rc = cl_integrator_create(r->type, sys, o, 0.0, b->x0, b->v0, &state,
                                 &r->why);
    if (!r->rc)
        r->rc = r->type->advance(state, r->T, x, v, &r->why);
    if (state)
        r->type->free(state);
}

cl_status cl_numdamp_modal_run(cl_model *m, const cl_numdamp_modes *b,
                               const cl_integrator_type *type,
                               const cl_integrator_opts *io, double dt,
                               double T, cl_numdamp_modal *r, cl_error *err)
{
    *r = (cl_numdamp_modal){.type = type, .label = type->name, .dt = dt,
                            .T = T};
    cl_status rc = cl_trial_whole_steps(type, dt, T, err);
    if (!rc && !type->fixed_step)
        rc = cl_error_set(err, CL_EINVAL, "damping: %s chooses its own "
                          "steps; the study takes fixed-step integrators",
                          type->name);
    if (!rc)
        rc = nd_modal_alloc(b, r, err);
    double *x = rc ? NULL : malloc(b->n * sizeof *x);
    double *v = rc ? NULL : malloc(b->n * sizeof *v);
    double *e0 = rc ? NULL : malloc(b->nosc * sizeof *e0);
    if (!rc && (!x || !v || !e0))
        rc = cl_error_set(err, CL_ENOMEM, "damping: out of memory");
    if (!rc) {
        cl_integrator_opts o = *io;
        o.dt = dt;
        nd_modal_integrate(m, b, &o, r, x, v);
        nd_modal_energy(b, b->x0, b->v0, e0);
        if (!r->rc)
            nd_modal_energy(b, x, v, r->ratio);
        for (size_t k = 0; k < b->nosc; k++) {
            const cl_region *reg = type->region;
            r->w[k] = sqrt(b->mu[b->n - b->nosc + k]);
            r->ratio[k] = r->rc ? NAN : r->ratio[k] / e0[k];
            r->theory[k] = reg->amplification
                ? pow(reg->amplification(r->w[k] * dt, io->rho_inf),
                      2.0 * nearbyint(T / dt))
                : NAN;
        }
    }
    free(x);
    free(v);
    free(e0);
    return rc;
}

void cl_numdamp_modal_free(cl_numdamp_modal *r)
{
    free(r->w);
    free(r->ratio);
    free(r->theory);
    r->w = r->ratio = r->theory = NULL;
    r->nosc = 0;
}

void cl_numdamp_modal_rows(FILE *fp, const cl_numdamp_modal *r, bool header)
{
    if (header)
        fprintf(fp, "integrator,mode,w,wh,ratio,theory,status\n");
    for (size_t k = 0; k < r->nosc; k++)
        fprintf(fp, "%s,%zu,%.9g,%.9g,%.9g,%.9g,%s\n", r->label, k, r->w[k],
                r->w[k] * r->dt, r->ratio[k], r->theory[k],
                r->rc ? cl_status_name(r->rc) : "ok");
}
