/* Damped springs, the `spring-damping` term (the Verlet-and-PBD report,
 * "Spring and Friction or Advanced Physical constraint"; docs/model.md 3.2
 * damping, 3.4): a dashpot on every spring pair of the mass-spring network
 * (forces/springs.h), kept apart from the springs term so that the springs'
 * potential energy and the dissipated power are reported separately.
 *
 *   axial (default, the Verlet-and-PBD report):
 *       f_a = kd (u . (v_b - v_a)) u,  f_b = -f_a,
 *       u = (x_b - x_a)/|x_b - x_a|: resists only the stretching rate;
 *   linear (Jiao, eq. 14):   f_a = -kd (v_a - v_b).
 * Jacobians (axial: df/dv = +-kd u u^T blocks and the nonsymmetric,
 * velocity-dependent df/dx) are derived in forces/pairdamp.h.
 *
 * The pairs are those [springs] defines (sets or levels, stiffness > 0),
 * whether or not the springs term itself is enabled (kd alone then gives a
 * dashpot network).  One kd for every pair, as the Verlet-and-PBD report's
 * single damping factor.
 *
 * INI section [spring-damping]: kd (N s/m, >= 0, default 0: off),
 * model (axial|linear, default axial). */
#include <math.h>
#include <stdlib.h>

#include "forces/pairdamp.h"
#include "forces/springs.h"

#define SEC "spring-damping"

static void spring_damping_eval(void *state, cl_eval *ev)
{
    cl_pairdamp_eval(state, ev, NULL, NULL);
}

static void spring_damping_free(void *state)
{
    if (state)
        cl_pairdamp_free(state);
    free(state);
}

static cl_status spring_damping_create(cl_config *cfg, const cl_cloth *cloth,
                                       const cl_term_opts *opts, void **state,
                                       cl_error *err)
{
    double kd;
    cl_damp_model model;
    cl_status rc;
    *state = NULL;
    if ((rc = cl_config_double(cfg, SEC, "kd", 0.0, 0.0, INFINITY, &kd,
                               err)) ||
        (rc = cl_pairdamp_read_model(cfg, SEC, CL_DAMP_AXIAL, &model, err)))
        return rc;
    if (kd == 0.0)
        return CL_OK;
    cl_pairdamp *pd = calloc(1, sizeof *pd);
    if (!pd)
        return cl_error_set(err, CL_ENOMEM, "out of memory (spring-damping)");
    cl_springnet net;
    if ((rc = cl_springs_network(cfg, cloth, &net, err))) {
        free(pd);
        return rc;
    }
    free(net.k); /* stiffness is the springs term's business */
    if ((rc = cl_pairdamp_init(pd, net.set, kd, model, err)) ||
        (rc = cl_pairterm_tear(&pd->pt, opts->tear_cut, err))) {
        spring_damping_free(pd);
        return rc;
    }
    *state = pd;
    return CL_OK;
}

const cl_term_type cl_term_spring_damping = {
    .name = "spring-damping",
    .doc = "dashpots on the spring pairs: axial kd (u.(v_j - v_i)) u "
           "(Verlet-and-PBD spring and friction) or linear -kd (v_i - v_j)",
    .conservative = false,
    .threads = cl_pairterm_threads,
    .create = spring_damping_create,
    .couplings = cl_pairterm_couplings,
    .bind = cl_pairterm_bind,
    .eval = spring_damping_eval,
    .step_done = cl_pairterm_step_done,
    .broken = cl_pairterm_broken,
    .free = spring_damping_free,
};
