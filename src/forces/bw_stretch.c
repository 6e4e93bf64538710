/* Baraff-Witkin stretch (BW98 section 4, stretch; docs/model.md 3.3) on
 * every triangle of the grid mesh or mesh cloth, two components:
 *     C = a (|w_u| - bu, |w_v| - bv)
 * with a the rest area and w_u, w_v the stretch directions of forces/bw.h
 * (dw_u/dx_m = cu_m I, dw_v/dx_m = cv_m I, constant).  With
 * uhat = w_u/|w_u|:
 *     dC_u/dx_m = a cu_m uhat,
 *     d2C_u/dx_m dx_n = a cu_m cu_n (I - uhat uhat^T)/|w_u|,
 * and likewise for C_v with cv, w_v.  Energy, force and Jacobians as in
 * forces/bw.h: the potential Jacobian is exact; the damping term
 * (bw-stretch-damping) keeps -kd C' d2C/dx2 of dd/dx and drops
 * -kd dC/dx (d2C/dx2 v)^T (BW98 section 4, damping).  A triangle whose w_u (or
 * w_v) vanishes has no direction: that component exerts no force there.
 *
 * Units: C in m^2, so k in N/m^3 (energy k a^2 eps^2 / 2 per triangle for a
 * strain eps: the membrane stiffness is k a, in N/m, and depends on the
 * mesh) and kd in N s/m^3.
 *
 * INI section [bw-stretch]: enabled (false), k (N/m^3, default 2e6),
 * ku, kv (default k: warp and weft may differ; on a mesh cloth u and v
 * follow each triangle's first edge, forces/bw.h, so unequal values make
 * no consistent warp and weft), bu, bv (target stretch, default 1; < 1
 * shrinks), kd (N s/m^3, default 0), kdu, kdv (default kd).
 * The damping term runs when enabled and kd (or kdu, kdv) is not zero. */
#include <math.h>

#include "forces/bw.h"

/* One component: C = a (|w| - b) with dw/dx_m = cw_m I. */
static void stretch_component(double a, const double *cw, const double w[3],
                              double b, bool want_hess, double *C, double *g,
                              double *H)
{
    double len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double u[3] = {0.0, 0.0, 0.0};
    if (len > 0)
        for (int i = 0; i < 3; i++)
            u[i] = w[i] / len;
    *C = a * (len - b);
    for (int m = 0; m < 3; m++)
        for (int i = 0; i < 3; i++)
            g[3 * m + i] = len > 0 ? a * cw[m] * u[i] : 0.0;
    if (!want_hess)
        return;
    for (int m = 0; m < 3; m++)
        for (int n = 0; n < 3; n++)
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    H[(3 * m + i) * CL_BW_NX + 3 * n + j] =
                        len > 0 ? a * cw[m] * cw[n] *
                                      ((i == j) - u[i] * u[j]) / len
                                : 0.0;
}

static void stretch_cond(const double *rest, const double b[2],
                         const double *x, bool want_hess, cl_bw_cond *out)
{
    double w[2][3];
    cl_bw_tri_w(rest, x, w[0], w[1]);
    for (int c = 0; c < 2; c++)
        stretch_component(rest[CL_BW_AREA],
                          rest + (c ? CL_BW_CV : CL_BW_CU), w[c], b[c],
                          want_hess, &out->C[c], out->g[c], out->H[c]);
}

static const cl_bw_spec stretch_spec = {
    .section = "bw-stretch",
    .nv = 3,
    .nc = 2,
    .nrest = CL_BW_TRI_REST,
    .cond = stretch_cond,
    .k_default = 2e6,
    .kd_default = 0.0,
    .suffix = {"u", "v"},
};

CL_BW_TERM_TYPES(bw_stretch, "bw-stretch", stretch_spec,
                 "Baraff-Witkin stretch C = a (|w_u| - bu, |w_v| - bv) on "
                 "the mesh triangles",
                 "Baraff-Witkin stretch damping -kd (dC/dx) C' "
                 "([bw-stretch] kd)");
