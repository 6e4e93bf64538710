/* The force terms, in evaluation order.  A new term is one file defining a
 * cl_term_type plus one row here. */
#include "forces/body.h"
#include "forces/bw.h"
#include "forces/choiko.h"
#include "forces/pbd.h"
#include "forces/selfcontact.h"
#include "forces/springs.h"

const cl_term_type *const cl_term_registry[] = {
    &cl_term_type1,
    &cl_term_type2,
    &cl_term_damping,
    &cl_term_springs,
    &cl_term_spring_damping,
    &cl_term_bw_stretch,
    &cl_term_bw_stretch_damping,
    &cl_term_bw_shear,
    &cl_term_bw_shear_damping,
    &cl_term_bw_bend,
    &cl_term_bw_bend_damping,
    &cl_term_gravity,
    &cl_term_pbd,
    &cl_term_selfcontact,
    NULL,
};
