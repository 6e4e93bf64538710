/* The Baraff-Witkin constraint of one particle on one obstacle (response
 * = constraint; Baraff & Witkin, "Large Steps in Cloth Simulation",
 * SIGGRAPH 1998, section 5; docs/model.md, eqs. C10-C13).
 *
 * A particle in contact at the start of a step (signed distance d, normal
 * n, obstacle velocity u there, relative velocity w = v - u) is
 * constrained inside the step's linear solve: with friction (mu > 0) at
 * first fully (it sticks: filter S = 0, velocity change z = -w), without
 * along the normal only (S = I - n n^T, z = -(w . n) n), so that its
 * velocity relative to the obstacle after the step has no normal part
 * (none at all when it sticks); its position is corrected by
 * y = (offset - d) n, which puts it back at the offset (BW98 eq. 18).
 *
 * After the solve, the impulse r the constraint needed (the residual of
 * the unfiltered system, BW98 section 5.3) decides: r . n < 0 means the
 * constraint pulls the particle toward the obstacle, and it is released
 * (S = I, z = y = 0); a sticking particle whose tangential impulse
 * |r_t| exceeds mu r . n slides instead: constrained along the normal,
 * with the kinetic friction impulse g = mu (r . n) r_t / |r_t| (Coulomb's
 * bound, along the impulse that would have held it) added to the
 * right-hand side. */
#ifndef CL_CONSTRAINT_H
#define CL_CONSTRAINT_H

#include <stdbool.h>

#include "contact/obstacle.h"
#include "core/decls.h"

CL_BEGIN_DECLS

typedef enum {
    CL_CONSTRAINT_FREE,
    CL_CONSTRAINT_NORMAL,
    CL_CONSTRAINT_FULL
} cl_constraint_mode;

typedef struct {
    cl_constraint_mode mode;
    double n[3];   /* normal at the step's start */
    double w[3];   /* relative velocity v - u there */
} cl_constraint;

/* S = I, z = y = g = 0. */
void cl_constraint_none(double S[9], double z[3], double y[3], double g[3]);

/* The constraint of a particle with velocity v at the contact point q of
 * an obstacle with response r (fully if r->mu > 0, else normal) into c,
 * S, z, y, g. */
void cl_constraint_start(const cl_response_params *r,
                         const cl_contact_point *q, const double v[3],
                         cl_constraint *c, double S[9], double z[3],
                         double y[3], double g[3]);

/* Release or demote c by the impulse imp (3) the last solve needed, as
 * described above; true if its mode changed (S, z, y, g updated). */
bool cl_constraint_release(double mu, const double imp[3], cl_constraint *c,
                           double S[9], double z[3], double y[3],
                           double g[3]);

CL_END_DECLS

#endif
