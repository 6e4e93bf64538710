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
} gravity_state;

static void gravity_eval(void *state, cl_eval *ev)
{
    const gravity_state *st = state;
    double energy = 0.0;
    if (ev->f && !ev->want_energy) { /* every right-hand side */
        const double *mass = st->cloth->mass;
        double g[3] = {st->g[0], st->g[1], st->g[2]};
        double F[3] = {st->F[0], st->F[1], st->F[2]};
        double *restrict f = ev->f;
        for (size_t p = 0; p < st->cloth->np; p++) {
            f[3 * p] += mass[p] * g[0] + F[0];
            f[3 * p + 1] += mass[p] * g[1] + F[1];
            f[3 * p + 2] += mass[p] * g[2] + F[2];
        }
        return;
    }
    for (size_t p = 0; p < st->cloth->np; p++)
        for (int i = 0; i < 3; i++) {
            double f = st->cloth->mass[p] * st->g[i] + st->F[i];
            if (ev->f)
                ev->f[3 * p + i] += f;
            if (ev->want_energy) /* not on every right-hand side */
                energy -= f * ev->x[3 * p + i];
        }
    if (ev->want_energy) {
        ev->energy = energy;
        ev->power = 0.0;
    }
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
    gravity_state st = {cloth, {0.0, -9.81, 0.0}, {0.0, 0.0, 0.0}};
    cl_status rc;
    *state = NULL;
    if ((rc = cl_config_vector(cfg, "gravity", "g", 3, st.g, err)) ||
        (rc = cl_config_vector(cfg, "gravity", "per_particle", 3, st.F,
                               err)))
        return rc;
    if (!st.g[0] && !st.g[1] && !st.g[2] && !st.F[0] && !st.F[1] && !st.F[2])
        return CL_OK;
    gravity_state *s = malloc(sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "out of memory (gravity)");
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
    .free = free,
};
