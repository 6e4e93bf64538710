/* Pair damping, shared by the Choi-Ko damping term (forces/damping.c) and
 * the spring-damping term (forces/spring_damping.c).  For a pair a-b with
 * u = (x_b - x_a)/d, d = |x_b - x_a|, w = v_b - v_a:
 *
 *  linear (Jiao, eq. 14; docs/model.md 3.2):  f_a = -kd (v_a - v_b) = kd w,
 *      df_a/dv_a = df_b/dv_b = -kd I,  df_a/dv_b = df_b/dv_a = kd I,
 *      no position dependence; power f_a.(v_a - v_b) = -kd |w|^2.
 *
 *  axial (the Verlet-and-PBD report, "Spring and Friction":
 *      f_a = k_d (d^ . (v_b - v_a)) d^):
 *      f_a = kd (u . w) u = kd (u u^T) w,   f_b = -f_a;
 *      with D = kd u u^T:  df_a/dv_b = df_b/dv_a = D, df_a/dv_a =
 *      df_b/dv_b = -D.  Positions: du/dx_b = P/d, P = I - u u^T,
 *      du/dx_a = -P/d, hence
 *          G = df_a/dx_b = (kd/d) [ u (P w)^T + (u . w) P ],
 *      df_b/dx_a = G, df_a/dx_a = df_b/dx_b = -G.  G is not symmetric (the
 *      u (P w)^T part; it vanishes when w is along u) and depends on v, so
 *      df/dx of this term is a nonsymmetric matrix.  Power
 *      f_a.(v_a - v_b) = -kd (u . w)^2 <= 0; a rigid rotation w = omega x
 *      (x_b - x_a) is not damped.  Coincident particles (d = 0): no force.
 *
 * The pair list, couplings and Jacobian slots are a cl_pairterm (its law is
 * unused), so a term whose state begins with a cl_pairdamp uses
 * cl_pairterm_couplings and cl_pairterm_bind as its hooks, and for tearing
 * (cl_pairterm_tear on pd->pt) cl_pairterm_step_done and cl_pairterm_broken:
 * a broken pair is not damped. */
#ifndef CL_PAIRDAMP_H
#define CL_PAIRDAMP_H

#include "core/decls.h"
#include "forces/pairgather.h"
#include "forces/pairterm.h"

CL_BEGIN_DECLS

typedef enum { CL_DAMP_LINEAR, CL_DAMP_AXIAL } cl_damp_model;

typedef struct {
    cl_pairterm pt; /* first member: pairs, couplings, slots */
    double kd;      /* N s/m */
    cl_damp_model model;
    const cl_pairterm *fuse_with; /* cl_pairdamp_fused: the first pair
                                   * term last compared, */
    size_t fuse_npt;              /* how many terms from it, */
    bool fuse_same;               /* and whether their pairs are ours */
    cl_pairgather gather;         /* the fused pass's per-particle sums */
} cl_pairdamp;

/* Whether pair k is damped at positions x (ctx: the caller's state). */
typedef bool (*cl_pairdamp_keep)(const void *ctx, size_t k, const double *x);

/* Takes ownership of `set` (also on failure). */
cl_status cl_pairdamp_init(cl_pairdamp *pd, cl_pairset set, double kd,
                           cl_damp_model model, cl_error *err);
void cl_pairdamp_free(cl_pairdamp *pd);

/* [sec] model = linear|axial, default `def`. */
cl_status cl_pairdamp_read_model(cl_config *cfg, const char *sec,
                                 cl_damp_model def, cl_damp_model *model,
                                 cl_error *err);

/* Forces, df/dx, df/dv (whichever ev asks for) of every intact pair (those
 * `keep` accepts, if keep is not NULL); ev->energy = 0, ev->power = sum
 * f.v. */
void cl_pairdamp_eval(cl_pairdamp *pd, cl_eval *ev, cl_pairdamp_keep keep,
                      const void *ctx);

/* Forces alone (ev asks for no Jacobian and no energy) of the central
 * pair terms pt[0..npt) and of pd, whose pairs are theirs one list after
 * the other, in one pass (forces/term.h, fuse): geometry once (u = x_ab
 * (1/d), cl_pairkern_geometry's recip), each term's law on its pairs, per
 * pair f = s u + f_damp, then per-particle sums (forces/pairgather.h)
 * instead of a scatter per term.  The same terms as separate passes,
 * summed in another order: the forces differ from theirs by a few ulp of
 * the largest per-pair force.  Threads as the pair kernels' (results
 * independent of the count).  Returns false, doing nothing, when the
 * pairs differ, a term tears, or ev asks for more. */
bool cl_pairdamp_fused(cl_pairterm *const *pt, size_t npt, cl_pairdamp *pd,
                       cl_eval *ev);

CL_END_DECLS

#endif
