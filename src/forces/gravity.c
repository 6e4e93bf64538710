/* Uniform body force (docs/model.md 3.4): f_p = m_p g + F on every
 * particle, with g an acceleration (m/s^2) and F a force per particle (N;
 * Jiao's own code applies F = (0, -0.01, 0) instead of gravity).  Potential
 * E = -sum_p (m_p g + F) . x_p; no Jacobian.
 *
 * INI section [gravity]: g (vector, default 0, -9.81, 0), per_particle
 * (vector, default 0, 0, 0). */
#include <stdlib.h>

#include "forces/body.h"

typedef struct {
    const cl_cloth *cloth;
    double g[3], F[3];
    double *fp; /* m_p g + F of every particle (3 np), formed once */
} gravity_state;

static void gravity_eval(void *state, cl_eval *ev)
{
    const gravity_state *st = state;
    const double *restrict fp = st->fp;
    size_t n = 3 * st->cloth->np;
    double energy = 0.0;
    if (ev->f && !ev->want_energy) { /* every right-hand side */
        double *restrict f = ev->f;
#pragma omp simd
        for (size_t i = 0; i < n; i++)
            f[i] += fp[i];
        return;
    }
    for (size_t i = 0; i < n; i++) {
        if (ev->f)
            ev->f[i] += fp[i];
        if (ev->want_energy) /* not on every right-hand side */
            energy -= fp[i] * ev->x[i];
    }
    if (ev->want_energy) {
        ev->energy = energy;
        ev->power = 0.0;
    }
}

static void gravity_free(void *state)
{
    gravity_state *st = state;
    if (st)
        free(st->fp);
    free(st);
}

static size_t gravity_couplings(const void *state, const int (**pairs)[2])
{
    (void)state;
    *pairs = NULL;
    return 0;
}

static cl_status gravity_bind(void *state, const cl_bpattern *pat,
                              const int *dof, cl_error *err)
{
    (void)state, (void)pat, (void)dof, (void)err;
    return CL_OK;
}

static cl_status gravity_create(cl_config *cfg, const cl_cloth *cloth,
                                const cl_term_opts *opts, void **state,
                                cl_error *err)
{
    (void)opts;
    gravity_state st = {cloth, {0.0, -9.81, 0.0}, {0.0, 0.0, 0.0}, NULL};
    cl_status rc;
    *state = NULL;
    if ((rc = cl_config_vector(cfg, "gravity", "g", 3, st.g, err)) ||
        (rc = cl_config_vector(cfg, "gravity", "per_particle", 3, st.F,
                               err)))
        return rc;
    if (!st.g[0] && !st.g[1] && !st.g[2] && !st.F[0] && !st.F[1] && !st.F[2])
        return CL_OK;
    gravity_state *s = malloc(sizeof *s);
    st.fp = malloc((3 * cloth->np + 1) * sizeof *st.fp);
    if (!s || !st.fp) {
        free(s);
        free(st.fp);
        return cl_error_set(err, CL_ENOMEM, "out of memory (gravity)");
    }
    for (size_t p = 0; p < cloth->np; p++)
        for (int i = 0; i < 3; i++)
            st.fp[3 * p + i] = cloth->mass[p] * st.g[i] + st.F[i];
    *s = st;
    *state = s;
    return CL_OK;
}

const cl_term_type cl_term_gravity = {
    .name = "gravity",
    .doc = "uniform body force m g + F per particle",
    .conservative = true,
    .soft = true,
    .create = gravity_create,
    .couplings = gravity_couplings,
    .bind = gravity_bind,
    .eval = gravity_eval,
    .free = gravity_free,
};
