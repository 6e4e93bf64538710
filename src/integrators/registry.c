/* The integrators selectable by name (docs/integrators.md): one row per
 * method file, X(ident) for the table cl_integrator_ident that the file
 * defines; the rows declare the tables and list them in this order.
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
 *   kinsol-galpha     generalized-alpha (Chung and Hulbert), KINSOL Newton
 *   semi-be           Baraff-Witkin linearised backward Euler
 *   semi-bdf2         Choi-Ko semi-implicit BDF2 (Jiao, eq. 15)
 *   xpbd              XPBD on the distance constraints, with substeps
 *   pd                projective dynamics on the springs, CHOLMOD
 *   arkode-dirk, arkode-dirk-fixed  ARKODE DIRK tables, adaptive / fixed
 *   arkode-imex, arkode-imex-fixed  ARKODE IMEX pairs, adaptive / fixed
 *   petsc-bdf, petsc-alpha2, petsc-arkimex, petsc-rosw  PETSc's TS
 *                     (integrators/petsc_ts.h, in the PETSc plug-in) */
#include "integrators/integrator.h"

/* Every row ends in a backslash; the blank line closes the list. */
#define CL_INTEGRATOR_ROWS(X)                                               \
    X(cvode_bdf)                                                            \
    X(cvode_bdf_dense)                                                      \
    X(cvode_bdf_gmres)                                                      \
    X(cvode_adams)                                                          \
    X(ida)                                                                  \
    X(symplectic_euler)                                                     \
    X(fe)                                                                   \
    X(symplectic_euler_x)                                                   \
    X(verlet)                                                               \
    X(verlet_pbd)                                                           \
    X(velocity_verlet)                                                      \
    X(rk4)                                                                  \
    X(gsl_rk8pd)                                                            \
    X(gsl_msbdf)                                                            \
    X(kinsol_be)                                                            \
    X(kinsol_bdf2)                                                          \
    X(kinsol_midpoint)                                                      \
    X(kinsol_galpha)                                                        \
    X(semi_be)                                                              \
    X(semi_bdf2)                                                            \
    X(xpbd)                                                                 \
    X(pd)                                                                   \
    X(arkode_dirk)                                                          \
    X(arkode_dirk_fixed)                                                    \
    X(arkode_imex)                                                          \
    X(arkode_imex_fixed)                                                    \
    X(petsc_bdf)                                                            \
    X(petsc_alpha2)                                                         \
    X(petsc_arkimex)                                                        \
    X(petsc_rosw)                                                           \

#define CL_INTEGRATOR_DECLARE(ident) \
    extern const cl_integrator_type cl_integrator_##ident;
#define CL_INTEGRATOR_ENTRY(ident) &cl_integrator_##ident,

CL_INTEGRATOR_ROWS(CL_INTEGRATOR_DECLARE)

const cl_integrator_type *const cl_integrator_registry[] = {
    CL_INTEGRATOR_ROWS(CL_INTEGRATOR_ENTRY) NULL,
};
