/* The barrier response of one particle to one obstacle (docs/model.md,
 * 4.6, eq. C20-C26): Incremental Potential Contact's clamped log
 * barrier (Li, Ferguson, Schneider, Langlois, Zorin, Panozzo, Jiang and
 * Kaufman, "Incremental Potential Contact", SIGGRAPH 2020, eq. 6)
 *
 *   E = kappa b(d),   b(d) = -(d - dhat)^2 ln(d / dhat)   for 0 < d < dhat,
 *
 * 0 for d >= dhat and +infinity for d <= 0, so a state with a particle at
 * d <= 0 is outside the feasible set.  Force and Hessian through the
 * signed distance d(x), its normal n = grad d and G = dn/dx:
 *
 *   f = -kappa b'(d) n,      H = d^2 E / dx^2 = kappa (b''(d) n n^T + b'(d) G),
 *
 * df/dx = -H, or -[H]_+ with psd (the default): H with its negative
 * eigenvalues set to 0 (the per-contact projection of IPC, section 4.3;
 * b'' > 0 and b' < 0 on (0, dhat), so only the curvature part b' G of a
 * convex shape is cut).
 *
 * Friction, lagged as in IPC (section 5): the normal force magnitude
 * lambda = -kappa b'(d) and the normal n of the previous step are
 * constants of the step (so is the set of particles in contact: those
 * with lambda > 0, wherever they are now), and with w = v - u the velocity
 * relative to the obstacle, v_t = P w its part across n (P = I - n n^T)
 * and y = |v_t|,
 *
 *   f_t = -mu lambda f1(y) v_t / y,   f1(y) = 2 y / eps_v - y^2 / eps_v^2
 *                                      (y < eps_v), 1 (y >= eps_v),
 *
 * IPC's C1 mollifier f1 of Coulomb's law (eq. 12), in velocity units
 * (IPC's eps_v h of displacement is eps_v of speed here).  f1(y) / y is
 * 2 / eps_v at y = 0, so the force and its Jacobians are smooth:
 * with phi = f1(y) / y and A = phi I + (phi'(y) / y) v_t v_t^T,
 * df_t/dv = -mu lambda A P and df_t/dx = mu lambda A P W (W = du/dx).  Its
 * power f_t . w = -mu lambda f1(y) y <= 0 is dissipated. */
#ifndef CL_BARRIER_H
#define CL_BARRIER_H

#include <stdbool.h>

#include "contact/obstacle.h"
#include "core/decls.h"

CL_BEGIN_DECLS

/* The fraction of the time of impact a filtered step may take (IPC's
 * line-search filter, section 4.2). */
#define CL_BARRIER_SAFETY 0.8

typedef struct {
    double f[3];          /* force on the particle */
    double dfdx[9];       /* row-major; only when asked for */
    double dfdv[9];
    double energy;        /* kappa b(d) */
    double power;         /* friction's power f_t . w, <= 0 */
} cl_barrier_out;

/* The barrier b(d) and its first two derivatives (0 for d >= dhat; d > 0). */
void cl_barrier_law(double d, double dhat, double *b, double *db,
                    double *d2b);

/* The normal force magnitude lambda = -kappa b'(d) >= 0 (0 for d >= dhat
 * or d <= 0). */
double cl_barrier_lambda(const cl_response_params *r, double d);

/* The barrier's force and, when jac is true, df/dx (df/dv = 0): false
 * (and o untouched) outside 0 < d < dhat. */
bool cl_barrier_eval(const cl_response_params *r, const cl_contact_point *q,
                     bool jac, cl_barrier_out *o);

/* The lagged friction of a particle with velocity v where the obstacle
 * moves with velocity u and du/dx = W (row-major), the normal n and force
 * lambda > 0 lagged: f, and with jac df/dx and df/dv, set (energy 0). */
void cl_barrier_friction(const cl_response_params *r, const double n[3],
                         double lambda, const double u[3], const double W[9],
                         const double v[3], bool jac, cl_barrier_out *o);

/* H with its negative eigenvalues set to 0 (symmetric 3x3, in place;
 * LAPACK's dsyev). */
void cl_barrier_project_psd(double H[9]);

CL_END_DECLS

#endif
