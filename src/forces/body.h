/* Body forces acting on each particle alone. */
#ifndef CL_BODY_H
#define CL_BODY_H

#include "core/decls.h"
#include "forces/term.h"

CL_BEGIN_DECLS

extern const cl_term_type cl_term_gravity;

CL_END_DECLS

#endif
