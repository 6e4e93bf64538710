/* petsc-alpha2: PETSc's TSALPHA2, the generalized-alpha method of Chung
 * and Hulbert ("A time integration algorithm for structural dynamics with
 * improved numerical dissipation: the generalized-alpha method", 1993) on
 * the second-order form M x'' = f(x, x') (integrators/petsc_ts.h;
 * docs/integrators.md, "PETSc TS"): second order, A-stable, its high-
 * frequency damping set by the spectral radius rho_inf at infinity
 * (--petsc "-ts_alpha_radius R", PETSc's default 1: no dissipation, the
 * energy of a linear oscillator conserved).  Its linear solver is CG
 * with PETSc's algebraic multigrid GAMG (petsc_ts_petsc.c). */
#include "integrators/petsc_ts.h"

CL_PETSC_TS_DEFINE(petsc_alpha2, "petsc-alpha2", "alpha2", true, false,
                   &cl_region_a_stable,
                   "PETSc TSALPHA2 generalized-alpha on M x'' = f, "
                   "half-size Jacobian, CG + GAMG; --petsc OPTIONS");
