/* Operations shared by the custom SUNLinearSolvers (see sunls.h). */
#include "linalg/sunls.h"

SUNLinearSolver_Type cl_sunls_type_direct(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_DIRECT;
}

SUNLinearSolver_ID cl_sunls_id_custom(SUNLinearSolver S)
{
    (void)S;
    return SUNLINEARSOLVER_CUSTOM;
}
