/* The linear stability region of an integrator (cl_integrator_type.region):
 * where h lambda may lie for the method to stay bounded on y' = lambda y.
 * The spectrum of the linearised cloth and a method's region give its
 * predicted step limit, or whether an unbounded region holds every step,
 * without knowing the method by name.
 *
 *  - CL_REGION_TAYLOR: an explicit Runge-Kutta method with as many stages
 *    as its order p <= 4, whose stability function is the degree-p Taylor
 *    polynomial of e^z, R(z) = sum_{k <= p} z^k / k!, stable where
 *    |R(h lambda)| <= 1 (Hairer and Wanner, "Solving Ordinary Differential
 *    Equations II", IV.2); these regions lie inside |z| < 4;
 *  - CL_REGION_SYMPLECTIC: a symplectic (partitioned) method, symplectic
 *    Euler or Verlet: stable on an undamped oscillator of frequency w for
 *    h w < 2 (Hairer, Lubich and Wanner, "Geometric Numerical
 *    Integration", I.5); with damping, where its step on x'' = -w^2 x -
 *    c x' (`oscillator`) has spectral radius <= 1, which depends on how
 *    the method hands velocities to the damping forces;
 *  - CL_REGION_SECTOR: an implicit method whose region is unbounded and
 *    contains the sector |arg(-z)| <= alpha (A(alpha)-stable; alpha = 90
 *    degrees: A-stable, the whole left half-plane);
 *  - CL_REGION_ADAPTIVE: a bounded region whose step the method's error
 *    control chooses (explicit Runge-Kutta pairs, Adams with fixed-point
 *    iteration): no fixed step to predict;
 *  - CL_REGION_PROJECTED: the step ends with a nonlinear projection onto
 *    constraints, which linear stability does not describe;
 *  - CL_REGION_SPLIT: an implicit-explicit (IMEX) method at a fixed step:
 *    bounded by its explicit half on the terms it treats explicitly, a
 *    limit that the spectrum of the whole linearisation does not give. */
#ifndef CL_REGION_H
#define CL_REGION_H

#include "core/decls.h"

CL_BEGIN_DECLS

typedef enum {
    CL_REGION_TAYLOR,
    CL_REGION_SYMPLECTIC,
    CL_REGION_SECTOR,
    CL_REGION_ADAPTIVE,
    CL_REGION_PROJECTED,
    CL_REGION_SPLIT,
} cl_region_kind;

typedef struct {
    cl_region_kind kind;
    int degree;    /* CL_REGION_TAYLOR: p, 1..4 */
    double alpha;  /* CL_REGION_SECTOR: the angle alpha, degrees */
    /* The amplification of one step on the undamped oscillator x'' =
     * -w^2 x at w h = wh: the spectral radius of the step's map of the
     * method's state (|R(i wh)| of a one-step method; the largest root of
     * a multistep method's characteristic polynomial), to which the
     * amplitude ratio per step tends over many steps; param is the
     * method's parameter (generalized-alpha: rho_inf), ignored by the
     * others.  NULL where no formula is given. */
    double (*amplification)(double wh, double param);
    /* CL_REGION_SYMPLECTIC: one step h of the method on the damped
     * oscillator x'' = -w2 x - c x', its state y = (x, v, a) in place: a
     * is the acceleration a method keeps from its last step (velocity
     * Verlet), 0 for the others. */
    void (*oscillator)(double h, double w2, double c, double y[3]);
} cl_region;

extern const cl_region cl_region_taylor1;   /* fe */
extern const cl_region cl_region_taylor4;   /* rk4 */
/* Symplectic Euler either way and position Verlet: the same step matrix
 * on the damped oscillator, trace 2 - h^2 w^2 - h c, determinant 1 - h c
 * (stable for h < (sqrt(c^2 + 4 w^2) - c) / w^2; position Verlet at its
 * velocity damping d = 0, which its region does not see: with d > 0,
 * h^2 w^2 < 4 - 2 h c - 2 d); velocity Verlet, whose
 * damping sees the predictor v_k + h a_k and whose a_k is the last step's
 * acceleration, evaluated at the last predictor (velocity_verlet.c), has
 * its own, of three states. */
extern const cl_region cl_region_symplectic;
extern const cl_region cl_region_velocity_verlet;
/* Backward Euler, BDF2, the implicit midpoint rule, and the linearised
 * semi-implicit BE and BDF2, which coincide with them on a linear system. */
extern const cl_region cl_region_a_stable;
/* The same A-stable region with the amplification of each method
 * (region_amplification.c, docs/integrators.md 4.3): backward Euler
 * 1/sqrt(1 + wh^2), BDF2, the implicit midpoint rule 1, and
 * generalized-alpha (Chung and Hulbert 1993) at param = rho_inf. */
extern const cl_region cl_region_be;
extern const cl_region cl_region_bdf2;
extern const cl_region cl_region_midpoint;
extern const cl_region cl_region_galpha;

/* Generalized-alpha's parameters for rho_inf in [0, 1] (Chung and
 * Hulbert 1993, eqs. 25 and 17): alpha_m = (2 rho - 1)/(rho + 1),
 * alpha_f = rho/(rho + 1), gamma = 1/2 - alpha_m + alpha_f,
 * beta = (1 - alpha_m + alpha_f)^2 / 4. */
typedef struct {
    double am, af, gamma, beta;
} cl_galpha;

cl_galpha cl_galpha_params(double rho_inf);
/* Variable-order BDF up to order 5 (CVODE, IDA, GSL msbdf at their default
 * highest order): the order-5 sector, alpha = 51.84 degrees (Hairer and
 * Wanner, V.2, table 2.3); orders 1 and 2 alone are A-stable. */
extern const cl_region cl_region_bdf5;
extern const cl_region cl_region_adaptive;
extern const cl_region cl_region_projected;
extern const cl_region cl_region_split;

CL_END_DECLS

#endif
