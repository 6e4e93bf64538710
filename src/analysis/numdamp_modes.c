/* The numerical damping study on the cloth: energy per eigenmode after a
 * run (analysis/numdamp.h, "on the cloth"). */
#include "analysis/numdamp.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_eigen.h>

#include "analysis/spectrum.h"
#include "analysis/trial.h"

#define ND_REST_TOL 1e-8  /* m/s^2: max |M^-1 f| of a state at rest */
#define ND_OSC_TOL 1e-6   /* mu_k / mu_max of an oscillating mode */
#define ND_EQ_TOL 1e-9    /* m/s^2: max |M^-1 f| of the equilibrium (its
                           * round-off floor is 1.5e-10 at 16 x 16) */
#define ND_EQ_STEPS 200   /* its pseudo time steps, at most */

void cl_numdamp_modes_free(cl_numdamp_modes *b)
{
    free(b->mu);
    free(b->phi);
    free(b->sqm);
    free(b->x0);
    free(b->v0);
    free(b->normal);
    memset(b, 0, sizeof *b);
}

/* CL_EINVAL unless M^-1 f(t0, x0, 0) vanishes; v0 = 0 after it (sqm is
 * scratch for f). */
static cl_status nd_at_rest(const cl_system *sys, double t0,
                            cl_numdamp_modes *b, cl_error *err)
{
    double *f = b->sqm, worst = 0.0;
    memset(b->v0, 0, b->n * sizeof *b->v0);
    cl_status rc = sys->force(sys->data, t0, b->x0, b->v0, f);
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

/* The unit normal of the plane that fits the free positions x best: the
 * least eigenvector of their covariance (3 x 3, GSL). */
static cl_status nd_plane_normal(const double *x, size_t n, double nrm[3],
                                 cl_error *err)
{
    double c[3] = {0}, cov[9] = {0}, ev[3], vec[9];
    size_t np = n / 3;
    for (size_t i = 0; i < np; i++)
        for (int a = 0; a < 3; a++)
            c[a] += x[3 * i + a] / (double)np;
    for (size_t i = 0; i < np; i++)
        for (int a = 0; a < 3; a++)
            for (int d = 0; d < 3; d++)
                cov[3 * a + d] += (x[3 * i + a] - c[a]) *
                                  (x[3 * i + d] - c[d]);
    gsl_matrix_view C = gsl_matrix_view_array(cov, 3, 3);
    gsl_matrix_view V = gsl_matrix_view_array(vec, 3, 3);
    gsl_vector_view E = gsl_vector_view_array(ev, 3);
    gsl_eigen_symmv_workspace *ws = gsl_eigen_symmv_alloc(3);
    int grc = ws ? gsl_eigen_symmv(&C.matrix, &E.vector, &V.matrix, ws)
                 : GSL_ENOMEM;
    if (ws)
        gsl_eigen_symmv_free(ws);
    if (grc)
        return cl_error_set(err, CL_ESOLVER, "damping: the cloth's plane "
                            "(GSL %d)", grc);
    gsl_eigen_symmv_sort(&E.vector, &V.matrix, GSL_EIGEN_SORT_VAL_ASC);
    for (int a = 0; a < 3; a++)
        nrm[a] = vec[3 * a];
    return CL_OK;
}

/* Each mode's normal fraction sum_i (phi_ki . nrm)^2 into b->normal. */
static cl_status nd_classify(cl_numdamp_modes *b, cl_error *err)
{
    double nrm[3];
    size_t n = b->n;
    cl_status rc = nd_plane_normal(b->x0, n, nrm, err);
    for (size_t k = 0; !rc && k < n; k++) {
        double s = 0.0;
        for (size_t i = 0; i < n / 3; i++) {
            double d = 0.0;
            for (int a = 0; a < 3; a++)
                d += b->phi[(3 * i + a) * n + k] * nrm[a];
            s += d * d;
        }
        b->normal[k] = s;
    }
    return rc;
}

/* x0 moved to the equilibrium (ND_EQ_TOL) when asked. */
static cl_status nd_equilibrium(cl_model *m, bool equilibrium,
                                cl_numdamp_modes *b, cl_error *err)
{
    if (!equilibrium)
        return CL_OK;
    return cl_equilibrium_find(m, cl_model_start_time(m), b->x0, ND_EQ_TOL,
                               ND_EQ_STEPS,
                               &b->eq, err);
}

cl_status cl_numdamp_modes_init(cl_model *m, double speed, bool equilibrium,
                                cl_numdamp_modes *b, cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    size_t n = sys->n;
    memset(b, 0, sizeof *b);
    cl_status rc = cl_trial_repeatable(m, err);
    if (!rc)
        rc = cl_numdamp_undamped(m, err);
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
    b->normal = malloc(n * sizeof *b->normal);
    if (!b->mu || !b->phi || !b->sqm || !b->x0 || !b->v0 || !b->normal)
        rc = cl_error_set(err, CL_ENOMEM, "damping: out of memory (%zu "
                          "modes)", n);
    if (!rc)
        rc = cl_model_initial_state(m, b->x0, b->v0);
    if (!rc)
        rc = nd_equilibrium(m, equilibrium, b, err);
    if (!rc)
        rc = nd_at_rest(sys, cl_model_start_time(m), b, err);
    if (!rc)
        rc = cl_spectrum_modes(m, cl_model_start_time(m), b->x0, b->v0,
                               b->mu, b->phi, err);
    for (size_t k = 0; !rc && k < n; k++) {
        b->sqm[k] = sqrt(sys->mass[k]);
        b->nosc += b->mu[k] > ND_OSC_TOL * b->mu[n - 1];
        b->nneg += b->mu[k] < -ND_OSC_TOL * b->mu[n - 1];
    }
    if (!rc)
        rc = nd_classify(b, err);
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
    r->normal = malloc(b->nosc * sizeof *r->normal);
    if (!r->w || !r->ratio || !r->theory || !r->normal)
        return cl_error_set(err, CL_ENOMEM, "damping: out of memory");
    r->nosc = b->nosc;
    return CL_OK;
}

/* The run from (x0, v0) at the model's start time over T into x, v; its
 * failure into r. */
static void nd_modal_integrate(const cl_model *m, const cl_numdamp_modes *b,
                               const cl_integrator_opts *o, cl_numdamp_modal
                               *r, double *x, double *v)
{
    const cl_system *sys = cl_model_system((cl_model *)m);
    double t0 = cl_model_start_time(m);
    void *state = NULL;
    r->rc = cl_integrator_create(r->type, sys, o, t0, b->x0, b->v0, &state,
                                 &r->why);
    if (!r->rc)
        r->rc = r->type->advance(state, t0 + r->T, x, v, &r->why);
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
            r->normal[k] = b->normal[b->n - b->nosc + k];
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
    free(r->normal);
    r->w = r->ratio = r->theory = r->normal = NULL;
    r->nosc = 0;
}

void cl_numdamp_modal_rows(FILE *fp, const cl_numdamp_modal *r, bool header)
{
    if (header)
        fprintf(fp, "integrator,mode,w,wh,ratio,theory,normal,status\n");
    for (size_t k = 0; k < r->nosc; k++)
        fprintf(fp, "%s,%zu,%.9g,%.9g,%.9g,%.9g,%.6f,%s\n", r->label, k,
                r->w[k], r->w[k] * r->dt, r->ratio[k], r->theory[k],
                r->normal[k],
                r->rc ? cl_status_name(r->rc) : "ok");
}
