/* The integrators selectable by name (docs/integrators.md): one row per
 * method file.
 *
 *   cvode-bdf         CVODE BDF + Newton + KLU, analytic sparse Jacobian
 *   cvode-bdf-dense   CVODE BDF + dense LU, difference-quotient Jacobian
 *   cvode-bdf-gmres   CVODE BDF + SPGMR, analytic J*v, block Jacobi
 *   cvode-adams       CVODE Adams-Moulton, fixed-point iteration
 *   ida               IDA on [x' - v; M v' - f] = 0, KLU
 *   symplectic-euler  v += h M^-1 f(x, v); x += h v (Jiao's own code)
 *   symplectic-euler-x  x += h v; v += h M^-1 f(x, v) (Zischg, Chea
 *                     and Aigner)
 *   fe                forward Euler
 *   verlet            position Verlet with velocity damping (the
 *                     Verlet-and-PBD report)
 *   verlet-pbd        verlet + position-based constraints (the
 *                     Verlet-and-PBD report)
 *   velocity-verlet   kick-drift-kick velocity Verlet
 *   rk4               classical Runge-Kutta 4
 *   gsl-rk8pd         GSL odeiv2 rk8pd, explicit adaptive reference
 *   gsl-msbdf         GSL odeiv2 msbdf, BDF with dense Jacobian (n <= 1728)
 *   kinsol-be, kinsol-bdf2, kinsol-midpoint  fully implicit, KINSOL Newton
 *   semi-be           Baraff-Witkin linearised backward Euler
 *   semi-bdf2         Choi-Ko semi-implicit BDF2 (Jiao, eq. 15) */
#include "integrators/integrator.h"

extern const cl_integrator_type cl_integrator_cvode_bdf;
extern const cl_integrator_type cl_integrator_cvode_bdf_dense;
extern const cl_integrator_type cl_integrator_cvode_bdf_gmres;
extern const cl_integrator_type cl_integrator_cvode_adams;
extern const cl_integrator_type cl_integrator_ida;
extern const cl_integrator_type cl_integrator_symplectic_euler;
extern const cl_integrator_type cl_integrator_fe;
extern const cl_integrator_type cl_integrator_symplectic_euler_x;
extern const cl_integrator_type cl_integrator_verlet;
extern const cl_integrator_type cl_integrator_verlet_pbd;
extern const cl_integrator_type cl_integrator_velocity_verlet;
extern const cl_integrator_type cl_integrator_rk4;
extern const cl_integrator_type cl_integrator_gsl_rk8pd;
extern const cl_integrator_type cl_integrator_gsl_msbdf;
extern const cl_integrator_type cl_integrator_kinsol_be;
extern const cl_integrator_type cl_integrator_kinsol_bdf2;
extern const cl_integrator_type cl_integrator_kinsol_midpoint;
extern const cl_integrator_type cl_integrator_semi_be;
extern const cl_integrator_type cl_integrator_semi_bdf2;

const cl_integrator_type *const cl_integrator_registry[] = {
    &cl_integrator_cvode_bdf,
    &cl_integrator_cvode_bdf_dense,
    &cl_integrator_cvode_bdf_gmres,
    &cl_integrator_cvode_adams,
    &cl_integrator_ida,
    &cl_integrator_symplectic_euler,
    &cl_integrator_fe,
    &cl_integrator_symplectic_euler_x,
    &cl_integrator_verlet,
    &cl_integrator_verlet_pbd,
    &cl_integrator_velocity_verlet,
    &cl_integrator_rk4,
    &cl_integrator_gsl_rk8pd,
    &cl_integrator_gsl_msbdf,
    &cl_integrator_kinsol_be,
    &cl_integrator_kinsol_bdf2,
    &cl_integrator_kinsol_midpoint,
    &cl_integrator_semi_be,
    &cl_integrator_semi_bdf2,
    NULL,
};
