/* Helpers of the Baraff-Witkin tests (tests/test_bw*.c; docs/model.md 3.3;
 * docs/architecture.md, "Checks every force term passes") on top of fdcheck.h:
 * models with one BW term alone, and an independent reference of a condition (C
 * and dC/dx written in the test from the formulas, d2C/dx2 by central
 * differences of that dC/dx) from which the expected forces, energies, power
 * and the damping Jacobians are assembled densely (n = 3 np, row-major, as
 * fdcheck.h):
 *   kept    = -kd sum_e C'_e d2C_e/dx2           (what BW98 keep),
 *   dropped = -kd sum_e dC_e/dx (d2C_e/dx2 v)^T   (what they drop),
 * so that the finite-difference dd/dx must equal kept + dropped.
 * Header only, included after <criterion/criterion.h>. */
#ifndef CL_TESTS_BWCHECK_H
#define CL_TESTS_BWCHECK_H

#include "fdcheck.h"
#include "forces/bw.h"
#include "io/frames.h"
#include "model/mesh.h"

/* A model with the Choi-Ko terms, gravity and pins off. */
#define BW_ONLY(...)                                                        \
    FD_MODEL("type1.enabled=false", "type2.enabled=false", "damping.kd=0",  \
             "gravity.g=0,0,0", "pins.at=", __VA_ARGS__)

/* Independent reference of one condition on n elements of nv vertices. */
typedef struct bw_ref bw_ref;
struct bw_ref {
    int nv, nc;
    size_t n;
    int *vert;         /* n * nv particle indices */
    const cl_cloth *cloth;
    double b[2];       /* stretch targets (1 unless set) */
    /* C (nc) and dC/dx (nc x 3 nv, vertex-major) of the element with
     * vertices vert at positions xe. */
    void (*cond)(const bw_ref *r, const int *vert, const double *xe,
                 double *C, double (*g)[CL_BW_NX]);
};

/* The triangles (nv = 3) or interior-edge hinges (nv = 4) of the model's
 * grid with the given diagonal. */
static inline bw_ref bw_ref_elements(const cl_model *m, int nv, int nc,
                                     cl_diagonal diag)
{
    const cl_cloth *c = cl_model_cloth(m);
    cl_mesh mesh;
    cl_error err;
    cr_assert_eq(cl_mesh_grid(c->nu, c->nv, diag, &mesh, &err), CL_OK);
    bw_ref r = {.nv = nv, .nc = nc, .cloth = c, .b = {1.0, 1.0}};
    r.n = nv == 3 ? mesh.ntri : mesh.nedge;
    r.vert = malloc((r.n * (size_t)nv + 1) * sizeof *r.vert);
    cr_assert_not_null(r.vert);
    for (size_t e = 0; e < r.n; e++)
        memcpy(r.vert + e * (size_t)nv,
               nv == 3 ? mesh.tri[e] : mesh.edge[e].v,
               (size_t)nv * sizeof(int));
    cl_mesh_free(&mesh);
    return r;
}

/* Triangle reference (stretch, shear), docs/model.md 3.3 written as a linear
 * solve: [w_u w_v] = [dx1 dx2] D^-1, D = [[du1, du2], [dv1, dv2]] the rest
 * edge vectors in (u, v) = (x, z); dW[c][m] = dw_c/dx_m (a scalar).
 * Returns the rest area. */
static inline double bw_ref_w(const cl_cloth *cl, const int *v,
                              const double *xe, double w[2][3],
                              double dW[2][3])
{
    const double *X0 = cl->X0 + 3 * v[0], *X1 = cl->X0 + 3 * v[1],
                 *X2 = cl->X0 + 3 * v[2];
    double D[2][2] = {{X1[0] - X0[0], X2[0] - X0[0]},
                      {X1[2] - X0[2], X2[2] - X0[2]}};
    double det = D[0][0] * D[1][1] - D[0][1] * D[1][0];
    double inv[2][2] = {{D[1][1] / det, -D[0][1] / det},
                        {-D[1][0] / det, D[0][0] / det}};
    for (int c = 0; c < 2; c++) {
        /* column c of D^-1 */
        dW[c][1] = inv[0][c];
        dW[c][2] = inv[1][c];
        dW[c][0] = -(dW[c][1] + dW[c][2]);
        for (int i = 0; i < 3; i++)
            w[c][i] = (xe[3 + i] - xe[i]) * inv[0][c] +
                      (xe[6 + i] - xe[i]) * inv[1][c];
    }
    return 0.5 * fabs(det);
}

/* fd_report of "<label> <what>". */
static inline void bw_report(const char *label, const char *what, double v)
{
    char buf[160];
    snprintf(buf, sizeof buf, "%s %s", label, what);
    fd_report(buf, v);
}

static inline void bw_ref_gather(const bw_ref *r, size_t e, const double *x,
                                 double *xe)
{
    for (int m = 0; m < r->nv; m++)
        memcpy(xe + 3 * m, x + 3 * r->vert[e * (size_t)r->nv + (size_t)m],
               3 * sizeof *xe);
}

/* d2C_c/dx2 of element e (3 nv x 3 nv, stride CL_BW_NX) by central
 * differences of the reference gradient, step h. */
static inline void bw_ref_hessian(const bw_ref *r, size_t e,
                                  const double *xe, double h,
                                  double (*H)[CL_BW_NX * CL_BW_NX])
{
    double y[CL_BW_NX], C[2], gp[2][CL_BW_NX], gm[2][CL_BW_NX];
    const int *v = r->vert + e * (size_t)r->nv;
    memcpy(y, xe, sizeof y);
    for (int col = 0; col < 3 * r->nv; col++) {
        double y0 = y[col], yp = y0 + h, ym = y0 - h;
        y[col] = yp;
        r->cond(r, v, y, C, gp);
        y[col] = ym;
        r->cond(r, v, y, C, gm);
        y[col] = y0;
        for (int c = 0; c < r->nc; c++)
            for (int row = 0; row < 3 * r->nv; row++)
                H[c][row * CL_BW_NX + col] =
                    (gp[c][row] - gm[c][row]) / (yp - ym);
    }
}

/* Force and energy of the potential part (k per component) from the
 * reference: f = -sum k C dC/dx, E = sum k C^2 / 2. */
static inline double bw_ref_potential(const bw_ref *r, const double k[2],
                                      const double *x, double *f)
{
    size_t n = 3 * r->cloth->np;
    double E = 0.0;
    memset(f, 0, n * sizeof *f);
    for (size_t e = 0; e < r->n; e++) {
        double xe[CL_BW_NX], C[2], g[2][CL_BW_NX];
        const int *v = r->vert + e * (size_t)r->nv;
        bw_ref_gather(r, e, x, xe);
        r->cond(r, v, xe, C, g);
        for (int c = 0; c < r->nc; c++) {
            E += 0.5 * k[c] * C[c] * C[c];
            for (int m = 0; m < r->nv; m++)
                for (int i = 0; i < 3; i++)
                    f[3 * v[m] + i] -= k[c] * C[c] * g[c][3 * m + i];
        }
    }
    return E;
}

/* Damping from the reference: force, power (returned), and the dense
 * kept / dropped parts of dd/dx (either may be NULL). */
static inline double bw_ref_damping(const bw_ref *r, const double kd[2],
                                    const double *x, const double *v,
                                    double *f, double *kept, double *dropped)
{
    size_t n = 3 * r->cloth->np;
    double power = 0.0;
    memset(f, 0, n * sizeof *f);
    if (kept)
        memset(kept, 0, n * n * sizeof *kept);
    if (dropped)
        memset(dropped, 0, n * n * sizeof *dropped);
    for (size_t e = 0; e < r->n; e++) {
        double xe[CL_BW_NX], ve[CL_BW_NX], C[2], g[2][CL_BW_NX];
        double H[2][CL_BW_NX * CL_BW_NX];
        const int *vv = r->vert + e * (size_t)r->nv;
        bw_ref_gather(r, e, x, xe);
        bw_ref_gather(r, e, v, ve);
        r->cond(r, vv, xe, C, g);
        bw_ref_hessian(r, e, xe, 1e-6, H);
        for (int c = 0; c < r->nc; c++) {
            double Cdot = 0.0, Hv[CL_BW_NX] = {0};
            for (int a = 0; a < 3 * r->nv; a++) {
                Cdot += g[c][a] * ve[a];
                for (int b = 0; b < 3 * r->nv; b++)
                    Hv[a] += H[c][a * CL_BW_NX + b] * ve[b];
            }
            power -= kd[c] * Cdot * Cdot;
            for (int a = 0; a < 3 * r->nv; a++) {
                size_t ra = 3 * (size_t)vv[a / 3] + (size_t)(a % 3);
                f[ra] -= kd[c] * Cdot * g[c][a];
                for (int b = 0; b < 3 * r->nv; b++) {
                    size_t cb = 3 * (size_t)vv[b / 3] + (size_t)(b % 3);
                    if (kept)
                        kept[ra * n + cb] -=
                            kd[c] * Cdot * H[c][a * CL_BW_NX + b];
                    if (dropped)
                        dropped[ra * n + cb] -= kd[c] * g[c][a] * Hv[b];
                }
            }
        }
    }
    return power;
}

static inline void bw_ref_free(bw_ref *r)
{
    free(r->vert);
    r->vert = NULL;
}

/* ---- whole checks -------------------------------------------------------- */

typedef struct {
    double jac_x, jac_v, energy, structure, net, torque;
} bw_errors;

/* A potential term alone at (x, v): df/dx vs central differences, df/dv
 * exactly zero, f = -dE/dx, df/dx symmetric with zero block row sums, zero
 * net force and torque.  Every error is reported (CLOTHODE_FD_VERBOSE). */
static inline bw_errors bw_check_potential(cl_model *m, const double *x,
                                           const double *v, double h,
                                           const char *label)
{
    size_t n = fd_n(m);
    bw_errors e;
    double *f = fd_vec(n);
    fd_check_jacobian(m, x, v, h, 1e-6, true, label, &e.jac_x, &e.jac_v);
    e.energy = fd_check_energy(m, x, v, h, label);
    e.structure = fd_check_structure(m, x, v);
    fd_eval(m, x, v, f);
    e.net = fd_net_force(x, f, n / 3, &e.torque);
    bw_report(label, "structure", e.structure);
    bw_report(label, "net force", e.net);
    cr_assert_lt(e.jac_x, 1e-6, "%s: df/dx vs FD rel err %g", label, e.jac_x);
    cr_assert_eq(e.jac_v, 0.0, "%s: df/dv should vanish (%g)", label,
                 e.jac_v);
    cr_assert_lt(e.energy, 1e-6, "%s: f vs -dE/dx rel err %g", label,
                 e.energy);
    cr_assert_lt(e.structure, 1e-10, "%s: asymmetry / row sums %g", label,
                 e.structure);
    cr_assert_lt(e.net, 1e-12, "%s: net force %g", label, e.net);
    cr_assert_lt(e.torque, 1e-12, "%s: net torque %g", label, e.torque);
    free(f);
    return e;
}

/* A damping term alone at (x, v) against the reference r with damping
 * coefficients kd: force and power, dd/dv vs central differences, the
 * assembled dd/dx equal to `kept` and the central differences of dd/dx
 * equal to kept + dropped, with the dropped part not negligible.  Returns
 * the worst relative error; *dd_dv_err, *kept_err, *fd_err receive the
 * three Jacobian errors. */
static inline double bw_check_damping(cl_model *m, const bw_ref *r,
                                      const double kd[2], const double *x,
                                      const double *v, const char *label,
                                      double *dd_dv_err, double *kept_err,
                                      double *fd_err)
{
    size_t n = fd_n(m), nn = n * n;
    double *f = fd_vec(n), *g = fd_vec(n), *Jx = fd_vec(nn),
           *Jv = fd_vec(nn), *Fx = fd_vec(nn), *Fv = fd_vec(nn),
           *kept = fd_vec(nn), *dropped = fd_vec(nn);
    cl_energy en = fd_eval(m, x, v, f);
    double power = bw_ref_damping(r, kd, x, v, g, kept, dropped);
    double ef = fd_relerr(f, g, n);
    cr_assert_lt(ef, 1e-12, "%s: force vs reference %g", label, ef);
    cr_assert(fabs(en.power_diss - power) <= 1e-12 * fabs(power),
              "%s: power %.17g vs %.17g", label, en.power_diss, power);
    cr_assert_lt(power, 0.0);
    cr_assert_eq(en.potential, 0.0, "%s: damping has no potential", label);
    fd_jacobian(m, x, v, Jx, Jv);
    fd_jacobian_fd(m, x, v, false, 1e-6, true, Fx);
    fd_jacobian_fd(m, x, v, true, 1e-6, true, Fv);
    double ev = fd_relerr(Fv, Jv, nn), ek = fd_relerr(Jx, kept, nn);
    for (size_t i = 0; i < nn; i++)
        kept[i] = Jx[i] + dropped[i];
    double ex = fd_relerr(Fx, kept, nn);
    double share = fd_maxabs(dropped, nn) / fd_maxabs(Fx, nn);
    bw_report(label, "dd/dv vs FD", ev);
    bw_report(label, "dd/dx vs -kd C' d2C/dx2", ek);
    bw_report(label, "FD dd/dx vs kept + dropped", ex);
    bw_report(label, "dropped / max |FD dd/dx|", share);
    cr_assert_lt(ev, 1e-6, "%s: dd/dv vs FD rel err %g", label, ev);
    cr_assert_lt(ek, 1e-6, "%s: dd/dx vs -kd C' d2C/dx2 rel err %g", label,
                 ek);
    cr_assert_lt(ex, 1e-6, "%s: FD dd/dx vs kept + dropped rel err %g", label,
                 ex);
    cr_assert_gt(share, 1e-2, "%s: the dropped part is negligible (%g): the "
                 "check has no teeth", label, share);
    if (dd_dv_err)
        *dd_dv_err = ev;
    if (kept_err)
        *kept_err = ek;
    if (fd_err)
        *fd_err = ex;
    free(f);
    free(g);
    free(Jx);
    free(Jv);
    free(Fx);
    free(Fv);
    free(kept);
    free(dropped);
    return fmax(ev, fmax(ek, ex));
}

/* A random non-flat state: in-plane scaling A (may be NULL), jitter in
 * the plane and out of it, velocities of size vs. */
static inline void bw_state(const cl_model *m, const double A[9],
                            double jit_plane, double jit_normal, double vs,
                            fd_rng *r, double *x, double *v)
{
    fd_deform(m, A, jit_plane, jit_normal, r, x);
    fd_random_vec(r, vs, v, fd_n(m));
}

/* ---- repeated trials ---------------------------------------------------- */

typedef void (*bw_state_fn)(const cl_model *m, fd_rng *r, double *x,
                            double *v);

/* bw_check_potential at `trials` random states, plus the force and the
 * energy of term `term` against the reference (stiffness k).  Returns the
 * worst df/dx error (also reported). */
static inline double bw_potential_trials(cl_model *m, const bw_ref *ref,
                                         const double k[2], const char *term,
                                         bw_state_fn state, unsigned seed,
                                         int trials, double h,
                                         const char *label)
{
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), *g = fd_vec(n);
    fd_rng r = {seed};
    double worst = 0.0;
    cr_assert(fd_has_term(m, term), "%s: term %s is off", label, term);
    for (int trial = 0; trial < trials; trial++) {
        state(m, &r, x, v);
        bw_errors e = bw_check_potential(m, x, v, h, label);
        worst = fmax(worst, e.jac_x);
        cl_energy en = fd_eval(m, x, v, f);
        double E = bw_ref_potential(ref, k, x, g);
        double ef = fd_relerr(f, g, n);
        cr_assert_lt(ef, 1e-12, "%s: force vs reference %g", label, ef);
        double Em = fd_term_energy(&en, term);
        cr_assert(fabs(Em - E) <= 1e-12 * E, "%s: energy %.17g vs %.17g",
                  label, Em, E);
    }
    bw_report(label, "worst df/dx", worst);
    free(x);
    free(v);
    free(f);
    free(g);
    return worst;
}

/* Three random states of the model m, whose only part of condition `term`
 * must be the potential (stiffness k), against the reference; frees the
 * reference and m. */
static inline void bw_potential_case(cl_model *m, bw_ref ref,
                                     const double k[2], const char *term,
                                     bw_state_fn state, unsigned seed,
                                     const char *label)
{
    char damping[64];
    snprintf(damping, sizeof damping, "%s-damping", term);
    cr_assert(!fd_has_term(m, damping), "%s: %s is on", label, damping);
    bw_potential_trials(m, &ref, k, term, state, seed, 3, 1e-5, label);
    bw_ref_free(&ref);
    cl_model_free(m);
}

/* bw_check_damping at `trials` random states of the model m, whose only
 * part of condition `term` must be its damping; returns the worst error. */
static inline double bw_damping_trials(cl_model *m, const char *term,
                                       const bw_ref *ref, const double kd[2],
                                       bw_state_fn state, unsigned seed,
                                       int trials, const char *label)
{
    char damping[64];
    snprintf(damping, sizeof damping, "%s-damping", term);
    cr_assert(fd_has_term(m, damping), "%s: %s is off", label, damping);
    cr_assert(!fd_has_term(m, term), "%s: %s is on", label, term);
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n);
    fd_rng r = {seed};
    double worst = 0.0;
    for (int trial = 0; trial < trials; trial++) {
        state(m, &r, x, v);
        worst = fmax(worst, bw_check_damping(m, ref, kd, x, v, label, NULL,
                                             NULL, NULL));
    }
    bw_report(label, "worst", worst);
    free(x);
    free(v);
    return worst;
}

/* fd_check_rigid at `trials` random states, rotations, translations and
 * uniform velocities; every deviation must stay below tol. */
static inline void bw_rigid_trials(cl_model *m, bw_state_fn state,
                                   unsigned seed, int trials, double tol,
                                   const char *label)
{
    size_t n = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), R[9], c[3], w[3];
    fd_rng r = {seed};
    for (int trial = 0; trial < trials; trial++) {
        state(m, &r, x, v);
        fd_rotation(&r, R);
        fd_random_vec(&r, 2.0, c, 3);
        fd_random_vec(&r, 1.0, w, 3);
        double e = fd_check_rigid(m, x, v, R, c, w, label);
        cr_assert_lt(e, tol, "%s: rigid-motion deviation %g", label, e);
    }
    free(x);
    free(v);
}

#endif
