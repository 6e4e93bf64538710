/* An obstacle: a shape (contact/shape.h) moved rigidly along a scripted
 * path, with the response its contacts get (docs/model.md, contact).
 *
 * INI section [obstacle.NAME] (NAME: letters, digits, '-', '_'):
 *   shape     = sphere | plane | box | mesh, then the shape's own keys
 *   path      = keyframes "t: x, y, z; t: x, y, z; ..." of the
 *               displacement of the shape from where its keys put it
 *               (m), times strictly increasing; piecewise linear between
 *               them, held before the first and after the last (default:
 *               none, the obstacle stays put)
 *   omega     = constant angular velocity (rad/s, vector, default 0),
 *               about the shape's pivot carried along the path
 *   response  = penalty | project | constraint
 *   penalty:  k (N/m, > 0), eps (band, m, >= 0), damping (Hunt-Crossley,
 *             s/m, >= 0, default 0), mu (>= 0, default 0), v_smooth (m/s, > 0,
 *             default 1e-3: the friction's smoothing speed)
 *   project:  offset (m, >= 0, default 0), zero_velocity (default false),
 *             mu (>= 0, default 0), iterations (>= 1, default 1),
 *             ccd (default false: continuous detection, docs/model.md 4.8)
 *   barrier:  kappa (J/m^2, > 0), dhat (m, > 0), psd (default true),
 *             mu (>= 0, default 0), eps_v (m/s, > 0, default 1e-3)
 *             (contact/barrier.h; the shape needs a time of impact)
 *   constraint: offset (m, >= 0, default 0), mu (>= 0, default 0):
 *             Baraff-Witkin constraints in the linear solve of semi-be
 *             and semi-bdf2 (contact/constraint.h)
 *
 * The position of a shape point X at time t is
 *     x(t) = q + R(t) (X - q) + s(t),   R(t) = exp(t [omega]x),
 * q the pivot, s(t) the path displacement; the obstacle's velocity field is
 * u(x, t) = s'(t) + omega x (x - q - s(t)), exact (s' piecewise constant). */
#ifndef CL_OBSTACLE_H
#define CL_OBSTACLE_H

#include <stdbool.h>

#include "contact/shape.h"
#include "core/decls.h"

CL_BEGIN_DECLS

typedef enum {
    CL_RESPONSE_PENALTY,
    CL_RESPONSE_PROJECT,
    CL_RESPONSE_BARRIER,
    CL_RESPONSE_CONSTRAINT
} cl_response;

typedef struct {
    cl_response kind;
    double k, eps, damping, v_smooth; /* penalty */
    double offset;                    /* project, constraint */
    bool zero_velocity;               /* project */
    bool ccd;                         /* project: continuous detection */
    long iterations;                  /* project */
    double mu;                        /* all: Coulomb friction */
    double kappa, dhat, eps_v;        /* barrier */
    bool psd;                         /* barrier: projected Hessian */
} cl_response_params;

typedef struct {
    double d, n[3], c[3], G[9]; /* as cl_shape_query, in the world frame */
    double u[3];                /* obstacle velocity at x */
    double W[9];                /* du/dx = [omega]x, row-major */
} cl_contact_point;

/* A contact point without its derivatives (c, G, W): what a force
 * without its Jacobian reads (cl_penalty_forces), 56 bytes a point of a
 * scratch array instead of 224. */
typedef struct {
    double d, n[3], u[3];
} cl_contact_slim;

typedef struct {
    char name[64];
    const cl_shape_type *type;
    void *shape;
    double pivot[3];
    size_t nkey;
    double *key_t;        /* keyframe times */
    double (*key_s)[3];   /* keyframe displacements */
    double omega[3];
    cl_response_params resp;
} cl_obstacle;

/* Read [sec] (sec = "obstacle.NAME"). */
cl_status cl_obstacle_create(cl_config *cfg, const char *sec, cl_obstacle *o,
                             cl_error *err);
void cl_obstacle_free(cl_obstacle *o);

/* Where an obstacle is at a time: computed once for all particles. */
typedef struct {
    double t;
    double R[9];      /* rotation R(t), row-major */
    double s[3];      /* displacement s(t) */
    double sdot[3];   /* its velocity s'(t) */
    double W[9];      /* [omega]x, the gradient of the velocity field */
    bool rotates;     /* omega != 0 (else R = I) */
} cl_pose;

void cl_obstacle_pose(const cl_obstacle *o, double t, cl_pose *P);

/* What is known of the distance of one particle to one obstacle: a lower
 * bound d at the shape-frame point X (the exact distance of the last
 * query there, or the shape's lower bound).  d is 1-Lipschitz in X and the
 * rigid motion is an isometry, so d(X') >= d - |X' - X| at any time
 * (docs/model.md, contact). */
typedef struct {
    double X[3];
    double d;     /* -INFINITY: nothing known yet */
    bool exact;   /* d is the distance at X, not only a bound */
    void *cache;  /* the shape's cache for this point (shape.h), or NULL */
} cl_contact_memo;

/* Distance, normal, closest point, dn/dx and the obstacle's velocity at
 * the world point x, the obstacle at pose P, for the points closer than
 * dmax to the surface (or inside): false, with q left unset, when the memo
 * (if not NULL) or the shape's lower bound of d (shape.h) already shows
 * d >= dmax (the bound kept in the memo); else the query (kept in the
 * memo), and whether q->d < dmax.
 * The bounds only skip queries that cannot matter; with dmax = INFINITY
 * and no memo every point is queried. */
bool cl_obstacle_near(const cl_obstacle *o, const cl_pose *P,
                      const double x[3], double dmax, cl_contact_memo *memo,
                      cl_contact_point *q);

/* cl_obstacle_near of the points near[0..n) of x (3 per particle, the
 * particles' indices in near[]; memo: the obstacle's memos, one per
 * particle) without derivatives: those with d < dmax kept in near[], in
 * their order, their points in q[]; their number.  d, n and u are
 * cl_obstacle_near's, bit for bit.  A half-space that does not rotate
 * (shape.h) answers without its memos: its distance is one dot product,
 * and the memos it leaves stay valid bounds. */
size_t cl_obstacle_near_slim(const cl_obstacle *o, const cl_pose *P,
                             const double *x, double dmax,
                             cl_contact_memo *memo, size_t *near, size_t n,
                             cl_contact_slim *q);

/* The signed distance d of x when it is below dmax (else false and d =
 * INFINITY): as cl_obstacle_near, but without a query when the memo has
 * the distance at this very point. */
bool cl_obstacle_depth(const cl_obstacle *o, const cl_pose *P,
                       const double x[3], double dmax, cl_contact_memo *memo,
                       double *d);

/* The broad phase of cl_obstacle_near for the np points x (3 each) and
 * their memos: the indices of those whose memo does not already show
 * d >= dmax (for a half-space that does not rotate, shape.h: whose
 * distance, computed directly, is not clearly >= dmax) into near[], and
 * their number.  One pass over the points without the per-point call of
 * cl_obstacle_near, which the points listed then get. */
size_t cl_obstacle_screen(const cl_obstacle *o, const cl_pose *P,
                          const double *x, size_t np, double dmax,
                          const cl_contact_memo *memo, size_t *near);

/* The obstacle's velocity u(x, t) at the world point x, the obstacle at
 * pose P (its gradient is P->W). */
void cl_obstacle_velocity(const cl_obstacle *o, const cl_pose *P,
                          const double x[3], double u[3]);

/* The time of impact of a straight move (docs/model.md, eq. C14;
 * contact/barrier.h with offset 0): the least fraction s in [0, 1] at
 * which the point moving from x0 (the obstacle at pose P0, x0 farther
 * than offset from it) to x1 (at pose P1) comes within offset of the
 * surface, the path taken straight in the shape's frame as the segment
 * between the two shape-frame points (the relative path exactly when the
 * obstacle translates along a path linear over the step; its chord when
 * it turns); INFINITY when it stays outside.  The obstacle's shape has a
 * toi (cl_shape_type). */
double cl_obstacle_toi(const cl_obstacle *o, const cl_pose *P0,
                       const double x0[3], const cl_pose *P1,
                       const double x1[3], double offset);

/* A particle within this distance of the offset surface touches it
 * (m). */
#define CL_ON_SURFACE 1e-9

/* Continuous detection for project (docs/model.md, eq. C14): true if the
 * path of cl_obstacle_toi comes within offset of the surface, with its
 * fraction s and the shape-frame point reached then placed at pose P1 in
 * xhit (the particle carried along by the obstacle since the impact).
 * False when there is no hit, and when x0 is already within offset +
 * CL_ON_SURFACE of the surface (the discrete check answers for a touching
 * particle). */
bool cl_obstacle_sweep(const cl_obstacle *o, const cl_pose *P0,
                       const double x0[3], const cl_pose *P1,
                       const double x1[3], double offset, double *s,
                       double xhit[3]);

/* The obstacle's drawing surface at time t, in the world frame. */
cl_status cl_obstacle_surface(const cl_obstacle *o, double t,
                              cl_shape_surface *s, cl_error *err);

CL_END_DECLS

#endif
