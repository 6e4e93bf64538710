/* The force terms, in evaluation order.  A new term is one file defining a
 * cl_term_type plus one row here. */
#include "forces/body.h"
#include "forces/choiko.h"

const cl_term_type *const cl_term_registry[] = {
    &cl_term_type1,
    &cl_term_type2,
    &cl_term_damping,
    &cl_term_gravity,
    NULL,
};
