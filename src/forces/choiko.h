/* Parameters shared by the Choi-Ko terms (type1, type2, damping): read in one
 * place so that every term sees the same value and default. */
#ifndef CL_CHOIKO_H
#define CL_CHOIKO_H

#include <stdbool.h>

#include "forces/term.h"

/* [type1] ks (N/m): Type1 stiffness, also the Type2 tension spring. */
cl_status cl_choiko_ks(cl_config *cfg, double *ks, cl_error *err);
/* [type1] enabled, [type2] enabled. */
cl_status cl_choiko_type1_enabled(cl_config *cfg, bool *on, cl_error *err);
cl_status cl_choiko_type2_enabled(cl_config *cfg, bool *on, cl_error *err);

extern const cl_term_type cl_term_type1;
extern const cl_term_type cl_term_type2;
extern const cl_term_type cl_term_damping;

#endif
