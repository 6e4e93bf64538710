/* Parameters shared by the Choi-Ko terms (type1, type2, damping): read in one
 * place so that every term sees the same value and default. */
#ifndef CL_CHOIKO_H
#define CL_CHOIKO_H

#include <stdbool.h>

#include "core/decls.h"
#include "forces/pairterm.h"
#include "forces/term.h"

CL_BEGIN_DECLS

/* [type1] ks (N/m): Type1 stiffness, also the Type2 tension spring. */
cl_status cl_choiko_ks(cl_config *cfg, double *ks, cl_error *err);
/* [type1] enabled, [type2] enabled. */
cl_status cl_choiko_type1_enabled(cl_config *cfg, bool *on, cl_error *err);
cl_status cl_choiko_type2_enabled(cl_config *cfg, bool *on, cl_error *err);

/* The forces of the central pair terms pt[0..npt) (Type1, then Type2)
 * and of the damping term (state: its own) in one pass (forces/term.h,
 * fuse; forces/pairdamp.h, cl_pairdamp_fused); false, having done
 * nothing, where the damping acts on engaged pairs only or the pass
 * cannot run. */
bool cl_damping_fused(void *state, cl_pairterm *const *pt, size_t npt,
                      cl_eval *ev);

extern const cl_term_type cl_term_type1;
extern const cl_term_type cl_term_type2;
extern const cl_term_type cl_term_damping;

CL_END_DECLS

#endif
