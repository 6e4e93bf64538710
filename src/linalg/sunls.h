/* Operations shared by clothode's custom SUNLinearSolvers (the LAPACK
 * dense solver, KINSOL's reduced-form solver, the counting shell): the
 * answers every custom direct solver gives SUNDIALS about itself. */
#ifndef CL_SUNLS_H
#define CL_SUNLS_H

#include <sundials/sundials_linearsolver.h>

/* SUNLINEARSOLVER_DIRECT: the solver takes a matrix and solves exactly. */
SUNLinearSolver_Type cl_sunls_type_direct(SUNLinearSolver S);

/* SUNLINEARSOLVER_CUSTOM: not one of SUNDIALS' own solvers. */
SUNLinearSolver_ID cl_sunls_id_custom(SUNLinearSolver S);

#endif
