/* The integrators selectable by name (SPEC 5): one row per method file.
 *
 *   cvode-bdf         CVODE BDF + Newton + KLU, analytic sparse Jacobian
 *   symplectic-euler  v += h M^-1 f(x, v); x += h v (seed 000's code) */
#include "integrators/integrator.h"

extern const cl_integrator_type cl_integrator_cvode_bdf;
extern const cl_integrator_type cl_integrator_symplectic_euler;

const cl_integrator_type *const cl_integrator_registry[] = {
    &cl_integrator_cvode_bdf,
    &cl_integrator_symplectic_euler,
    NULL,
};
