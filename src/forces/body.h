/* Body forces acting on each particle alone. */
#ifndef CL_BODY_H
#define CL_BODY_H

#include "forces/term.h"

extern const cl_term_type cl_term_gravity;

#endif
