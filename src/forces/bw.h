/* Baraff-Witkin cloth (D. Baraff, A. Witkin, "Large steps in cloth
 * simulation", SIGGRAPH 1998, section 4; docs/model.md 3.3): forces from
 * condition functions C(x) of small groups of particles ("elements": the
 * triangles of the grid mesh, or of a mesh cloth's own mesh
 * (model/cloth.h), for stretch and shear, the two triangles of an interior
 * edge for bend; model/mesh.h).
 *
 * Potential part (BW98 section 4: condition energy), per element and
 * component c:
 *     E = k/2 C^T C,   f = -k (dC/dx) C,
 *     df/dx = -k (dC/dx dC/dx^T + C d2C/dx2)          (exact).
 * Damping part (BW98 section 4: damping), with C' = dC/dx^T v:
 *     d = -kd (dC/dx) C',   dd/dv = -kd dC/dx dC/dx^T   (exact),
 *     dd/dx = -kd (C' d2C/dx2 + dC/dx (d2C/dx2 v)^T)
 *   of which only the symmetric -kd C' d2C/dx2 is assembled: the second
 *   part is dropped, as Baraff and Witkin do (it breaks the symmetry of the
 *   matrix).  The damping power sum_c -kd C'^2 <= 0 goes to cl_eval.power.
 * The two parts are separate term types (bw-stretch and bw-stretch-damping,
 * ...) so that potential energies and dissipated power stay apart; both read
 * the condition's INI section.
 *
 * Each condition file (bw_stretch.c, bw_shear.c, bw_bend.c) supplies C, dC/dx
 * and d2C/dx2 of one element; this module builds the elements, the Jacobian
 * couplings (all vertex pairs of an element) and runs the loops above.
 *
 * Tearing ([tear] cut, docs/model.md 3.4): the connections of an element
 * are the mesh edges of its triangles (3 for a triangle; 5 for a hinge: the
 * shared edge and the four outer edges of its two triangles).  After an
 * accepted step an element whose connection a-b has d > cut L (L its rest
 * length) breaks for good and gives no force, energy or Jacobian values;
 * the connections over the cut are reported as broken.  The test is the same
 * for every term and for the pair terms, so a torn edge takes every
 * triangle and hinge it belongs to, in all terms at once. */
#ifndef CL_BW_H
#define CL_BW_H

#include <stdbool.h>

#include "core/decls.h"
#include "forces/term.h"
#include "model/mesh.h"

CL_BEGIN_DECLS

#define CL_BW_MAXV 4                /* vertices of an element */
#define CL_BW_NX (3 * CL_BW_MAXV)   /* coordinates of an element */

/* C and its derivatives for one element, vertex-major: g[c][3m + i] =
 * dC_c/dx_{m,i}; H[c][(3m + i) CL_BW_NX + 3n + j] = d2C_c/dx_{m,i}dx_{n,j}.
 * Only the entries of the element's nv vertices are written. */
typedef struct {
    double C[2];
    double g[2][CL_BW_NX];
    double H[2][CL_BW_NX * CL_BW_NX];
} cl_bw_cond;

/* C of one element at positions x (3 nv), from its rest constants and the
 * term's targets b (stretch: bu, bv); H only if want_hess. */
typedef void (*cl_bw_cond_fn)(const double *rest, const double b[2],
                              const double *x, bool want_hess,
                              cl_bw_cond *out);

typedef struct {
    const char *name;   /* INI section, for messages */
    int nv;             /* vertices per element: 3 or 4 */
    int nc;             /* components of C: 1 or 2 */
    int nrest;          /* rest constants per element */
    cl_bw_cond_fn cond;
    double k[2];        /* stiffness, or damping coefficient, per component */
    double b[2];        /* stretch targets bu, bv */
    bool damping;       /* the damping part of the condition */
    size_t n;           /* elements */
    int *vert;          /* n * nv particle indices */
    double *rest;       /* n * nrest */
    int (*couple)[2];   /* n * nv(nv-1)/2 vertex pairs */
    long *slot;         /* n * nv * nv pattern slots (-1: no unknowns) */
    /* tearing (NULL / 0 without [tear] cut) */
    double cut;
    double *edge_rest;  /* rest lengths of the n * (3 or 5) connections */
    unsigned char *torn; /* n flags */
    int (*broken)[2];   /* connections broken so far */
    size_t nbroken;
} cl_bw_term;

/* ---- triangles (stretch, shear) ----------------------------------------
 * Rest (u, v) = (X, Z) of the flat grid (model/cloth.h).  On a mesh cloth
 * each triangle (i, j, k) has its own rest (u, v), in metres, in the plane
 * of its rest shape: u along its first edge X_j - X_i, v perpendicular to
 * it towards X_k, so du1 = |X_j - X_i|, dv1 = 0, du2 = the projection of
 * X_k - X_i on u, dv2 = twice the area / du1 (det > 0).  The warp and weft
 * directions w_u, w_v then change from triangle to triangle with the mesh's
 * edges: bu, bv and ku, kv (stretch) act isotropically only when equal.
 * For triangle
 * (i, j, k): du1 = u_j - u_i, du2 = u_k - u_i, dv1, dv2 likewise,
 * det = du1 dv2 - du2 dv1, a = |det|/2; with dx1 = x_j - x_i,
 * dx2 = x_k - x_i:
 *     w_u = (dx1 dv2 - dx2 dv1)/det,   w_v = (-dx1 du2 + dx2 du1)/det,
 * so dw_u/dx_m = cu_m I and dw_v/dx_m = cv_m I with
 *     cu = ((dv1 - dv2), dv2, -dv1)/det,  cv = ((du2 - du1), -du2, du1)/det.
 * At rest w_u = (1, 0, 0) and w_v = (0, 0, 1) exactly on a grid; on a
 * mesh they are the triangle's unit u and v directions in space, up to
 * round-off. */
enum {
    CL_BW_DU1, CL_BW_DU2, CL_BW_DV1, CL_BW_DV2, CL_BW_DET, CL_BW_AREA,
    CL_BW_CU, CL_BW_CV = CL_BW_CU + 3, CL_BW_TRI_REST = CL_BW_CV + 3
};

/* Rest constants of triangle tri from rest positions X0, (u, v) = (X, Z)
 * (a grid); false if its rest area is zero (such a triangle carries no
 * force). */
bool cl_bw_tri_rest(const double *X0, const int tri[3],
                    double rest[CL_BW_TRI_REST]);
/* The same with (u, v) in the triangle's own plane (a mesh cloth). */
bool cl_bw_tri_rest_plane(const double *X0, const int tri[3],
                          double rest[CL_BW_TRI_REST]);
/* w_u, w_v of a triangle at positions x (9). */
void cl_bw_tri_w(const double *rest, const double *x, double wu[3],
                 double wv[3]);

/* ---- creating a term -----------------------------------------------------
 * What a condition file tells cl_bw_create.  Keys read from [section]:
 *   enabled (default false), k (stiffness, >= 0), kd (damping, >= 0) and,
 *   for a two-component condition with suffixes {"u", "v"}: ku, kv (default
 *   k), kdu, kdv (default kd), bu, bv (targets, > 0, default 1);
 * and [cloth] diagonal (model/mesh.h; a grid's triangulation, a mesh
 * cloth has its own triangles).  All keys are read even when the
 * term is off.  The term is off (state NULL) unless enabled and its
 * coefficients (k for the potential part, kd for the damping part) are not
 * all zero.  A grid with fewer than two particles along a side has no
 * triangles: an error naming the section. */
typedef struct {
    const char *section;
    int nv, nc, nrest;
    cl_bw_cond_fn cond;
    double k_default, kd_default;
    const char *suffix[2];  /* per-component key suffixes (nc = 2) */
    /* Hinge elements: rest constants of (x0, x1, x2, x3) (12 coordinates);
     * false: degenerate at rest, skipped.  NULL: triangle elements (one
     * per mesh triangle of non-zero rest area, cl_bw_tri_rest). */
    bool (*hinge_rest)(const double *x, double *rest);
} cl_bw_spec;

cl_status cl_bw_create(cl_config *cfg, const cl_cloth *cloth,
                       const cl_bw_spec *spec, const cl_term_opts *opts,
                       bool damping, void **state, cl_error *err);

/* The two term types of a condition, cl_term_<var> (potential, named
 * tname, described by tdoc) and cl_term_<var>_damping (tname "-damping",
 * ddoc), both made by cl_bw_create from spec. */
#define CL_BW_TERM_TYPES(var, tname, spec, tdoc, ddoc)                      \
    static cl_status var##_create(cl_config *cfg, const cl_cloth *cloth,    \
                                  const cl_term_opts *opts, void **state,   \
                                  cl_error *err)                            \
    {                                                                       \
        return cl_bw_create(cfg, cloth, &spec, opts, false, state, err);    \
    }                                                                       \
    static cl_status var##_damping_create(                                  \
        cl_config *cfg, const cl_cloth *cloth, const cl_term_opts *opts,    \
        void **state, cl_error *err)                                        \
    {                                                                       \
        return cl_bw_create(cfg, cloth, &spec, opts, true, state, err);     \
    }                                                                       \
    const cl_term_type cl_term_##var = {                                    \
        .name = tname, .doc = tdoc, .conservative = true,                   \
        .create = var##_create, .couplings = cl_bw_couplings,               \
        .bind = cl_bw_bind, .eval = cl_bw_eval,                             \
        .step_done = cl_bw_step_done, .broken = cl_bw_broken,               \
        .free = cl_bw_free};                                                \
    const cl_term_type cl_term_##var##_damping = {                          \
        .name = tname "-damping", .doc = ddoc, .conservative = false,     \
        .create = var##_damping_create, .couplings = cl_bw_couplings,       \
        .bind = cl_bw_bind, .eval = cl_bw_eval,                             \
        .step_done = cl_bw_step_done, .broken = cl_bw_broken,               \
        .free = cl_bw_free}

/* cl_term_type hooks for a cl_bw_term state. */
size_t cl_bw_couplings(const void *state, const int (**pairs)[2]);
cl_status cl_bw_bind(void *state, const cl_bpattern *pat, const int *dof,
                     cl_error *err);
void cl_bw_eval(void *state, cl_eval *ev);
size_t cl_bw_step_done(void *state, const double *x, const double *v);
size_t cl_bw_broken(const void *state, const int (**pairs)[2]);
void cl_bw_free(void *state);

/* ---- bending hinge (bw_bend.c) -------------------------------------------
 * theta of the hinge x = (x0, x1, x2, x3) (12 coordinates), its gradient
 * (12) and, if H is not NULL, its Hessian (12 x 12 row-major).  Returns
 * false (theta, g, H zero) for a degenerate hinge (an edge or a triangle of
 * zero length or area). */
bool cl_bw_hinge(const double *x, double *theta, double *g, double *H);

extern const cl_term_type cl_term_bw_stretch;
extern const cl_term_type cl_term_bw_stretch_damping;
extern const cl_term_type cl_term_bw_shear;
extern const cl_term_type cl_term_bw_shear_damping;
extern const cl_term_type cl_term_bw_bend;
extern const cl_term_type cl_term_bw_bend_damping;

CL_END_DECLS

#endif
