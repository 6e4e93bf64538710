/* Shared set-ups of the constraint-based integrator tests
 * (tests/test_xpbd.c, tests/test_pd.c, tests/test_distances.c): a chain
 * of springs hanging along gravity, whose static equilibrium is known in
 * closed form, and a hard-constraint chain (the pbd term).  Header only,
 * included after "pbdcheck.h". */
#ifndef CL_TESTS_CDYNCHECK_H
#define CL_TESTS_CDYNCHECK_H

#include "pbdcheck.h"

/* N = 5 free particles below a pin, links L = 0.2 m, m = 0.01 kg, springs
 * k = 50 N/m on neighbours only, gravity 9.81 m/s^2 along the chain (+x),
 * no damping. */
#define CD_N 5
#define CD_L 0.2
#define CD_MG (0.01 * 9.81)
#define CD_K 50.0
#define CD_CHAIN                                                           \
    "cloth.nu=6", "cloth.nv=1", "cloth.size=1", "cloth.particle_mass=0.01", \
        "pins.at=0,0", "type1.enabled=false", "type2.enabled=false",       \
        "damping.kd=0", "springs.enabled=true", "springs.k_structural=50", \
        "springs.k_shear=0", "springs.k_bend=0", "gravity.g=9.81,0,0"

/* The static equilibrium of CD_CHAIN: link l (1..N) carries the weight of
 * particles l..N, k (d_l - L) = (N - l + 1) m g, so free particle i sits at
 * x = sum_{l <= i} (L + (N - l + 1) m g / k), y = z = 0. */
static inline void cd_equilibrium(double *x)
{
    double at = 0.0;
    for (int i = 1; i <= CD_N; i++) {
        at += CD_L + (CD_N - i + 1) * CD_MG / CD_K;
        x[3 * (i - 1)] = at;
        x[3 * (i - 1) + 1] = x[3 * (i - 1) + 2] = 0.0;
    }
}

/* The largest distance from the equilibrium seen at the outputs. */
static inline void cd_watch_rest(pb_case *c, double t, void *ctx)
{
    (void)t;
    double eq[3 * CD_N], *worst = ctx;
    cd_equilibrium(eq);
    for (size_t i = 0; i < c->n; i++)
        *worst = fmax(*worst, fabs(c->x[i] - eq[i]));
}

/* Integrate the chain from its equilibrium at rest with `name`, step dt,
 * S substeps and K iterations, to T = 0.5 s: the largest distance from
 * the equilibrium at 10 outputs. */
static inline double cd_rest_drift(const char *name, double dt, long S,
                                   long K)
{
    pb_case c = pb_open(FD_MODEL(CD_CHAIN));
    cr_assert_eq(c.n, 3 * CD_N);
    cd_equilibrium(c.x);
    memset(c.v, 0, c.n * sizeof *c.v);
    cl_integrator_opts o = {.dt = dt, .substeps = S, .iterations = K};
    double worst = 0.0;
    pb_integrate(&c, name, &o, 0.5, 10, cd_watch_rest, &worst);
    pb_close(&c);
    return worst;
}

#endif
