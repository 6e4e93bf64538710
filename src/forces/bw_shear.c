/* Baraff-Witkin shear (BW98 section 4, shear; docs/model.md 3.3) on every
 * triangle of the grid mesh or mesh cloth, one component:
 *     C = a w_u . w_v
 * with a the rest area and w_u, w_v the stretch directions of forces/bw.h
 * (dw_u/dx_m = cu_m I, dw_v/dx_m = cv_m I, constant), so
 *     dC/dx_m = a (cu_m w_v + cv_m w_u),
 *     d2C/dx_m dx_n = a (cu_m cv_n + cv_m cu_n) I.
 * Energy, force and Jacobians as in forces/bw.h: the potential Jacobian is
 * exact; the damping term (bw-shear-damping) keeps -kd C' d2C/dx2 of dd/dx
 * and drops -kd dC/dx (d2C/dx2 v)^T (BW98 section 4, damping).
 *
 * Units: C in m^2 (w_u . w_v ~ the shear angle), so k in N/m^3 (the
 * in-plane shear stiffness is about k a, in N/m) and kd in N s/m^3.
 *
 * INI section [bw-shear]: enabled (false), k (N/m^3, default 2e5),
 * kd (N s/m^3, default 0; the damping term runs when enabled and kd > 0). */
#include "forces/bw.h"

static void shear_cond(const double *rest, const double b[2],
                       const double *x, bool want_hess, cl_bw_cond *out)
{
    (void)b;
    double wu[3], wv[3], a = rest[CL_BW_AREA];
    const double *cu = rest + CL_BW_CU, *cv = rest + CL_BW_CV;
    cl_bw_tri_w(rest, x, wu, wv);
    out->C[0] = a * (wu[0] * wv[0] + wu[1] * wv[1] + wu[2] * wv[2]);
    for (int m = 0; m < 3; m++)
        for (int i = 0; i < 3; i++)
            out->g[0][3 * m + i] = a * (cu[m] * wv[i] + cv[m] * wu[i]);
    if (!want_hess)
        return;
    for (int m = 0; m < 3; m++)
        for (int n = 0; n < 3; n++)
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    out->H[0][(3 * m + i) * CL_BW_NX + 3 * n + j] =
                        i == j ? a * (cu[m] * cv[n] + cv[m] * cu[n]) : 0.0;
}

static const cl_bw_spec shear_spec = {
    .section = "bw-shear",
    .nv = 3,
    .nc = 1,
    .nrest = CL_BW_TRI_REST,
    .cond = shear_cond,
    .k_default = 2e5,
    .kd_default = 0.0,
};

CL_BW_TERM_TYPES(bw_shear, "bw-shear", shear_spec,
                 "Baraff-Witkin shear C = a w_u . w_v on the mesh triangles",
                 "Baraff-Witkin shear damping -kd (dC/dx) C' ([bw-shear] kd)");
