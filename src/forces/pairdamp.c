/* Pair damping, linear (Jiao, eq. 14) and axial (the Verlet-and-PBD
 * report, "Spring and Friction"): equations and Jacobians in
 * forces/pairdamp.h. */
#include "forces/pairdamp.h"

cl_status cl_pairdamp_init(cl_pairdamp *pd, cl_pairset set, double kd,
                           cl_damp_model model, cl_error *err)
{
    pd->kd = kd;
    pd->model = model;
    return cl_pairterm_init(&pd->pt, set, NULL, NULL, false, err);
}

void cl_pairdamp_free(cl_pairdamp *pd)
{
    cl_pairterm_free(&pd->pt);
}

cl_status cl_pairdamp_read_model(cl_config *cfg, const char *sec,
                                 cl_damp_model def, cl_damp_model *model,
                                 cl_error *err)
{
    static const char *const names[] = {"linear", "axial", NULL};
    int k;
    cl_status rc = cl_config_choice(cfg, sec, "model", names, (int)def, &k,
                                    err);
    *model = k == 1 ? CL_DAMP_AXIAL : CL_DAMP_LINEAR;
    return rc;
}

/* -sc B on the aa, bb blocks, +sc B on ab, ba (slots s[0..3]). */
static void add_blocks(double *vals, const long *s, double sc,
                       const double B[9])
{
    cl_block_add(vals, s[0], -sc, B);
    cl_block_add(vals, s[1], -sc, B);
    cl_block_add(vals, s[2], sc, B);
    cl_block_add(vals, s[3], sc, B);
}

/* f_a += fa, f_b -= fa; returns fa . (v_a - v_b). */
static double add_pair_force(cl_eval *ev, const cl_pair *pr,
                             const double fa[3])
{
    double p = 0.0;
    for (int i = 0; i < 3; i++) {
        if (ev->f) {
            ev->f[3 * pr->a + i] += fa[i];
            ev->f[3 * pr->b + i] -= fa[i];
        }
        p += fa[i] * (ev->v[3 * pr->a + i] - ev->v[3 * pr->b + i]);
    }
    return p;
}

static double damp_linear(double kd, const cl_pair *pr, const long *s,
                          cl_eval *ev)
{
    static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double *va = ev->v + 3 * pr->a, *vb = ev->v + 3 * pr->b;
    double fa[3];
    for (int i = 0; i < 3; i++)
        fa[i] = -kd * (va[i] - vb[i]);
    if (ev->dfdv)
        add_blocks(ev->dfdv, s, kd, I3);
    return add_pair_force(ev, pr, fa);
}

/* G = (kd/d) [u (P w)^T + (u . w) P], P = I - u u^T (row-major). */
static void axial_dx_block(double kd, double d, const double u[3],
                           const double w[3], double uw, double G[9])
{
    double pw[3];
    for (int i = 0; i < 3; i++)
        pw[i] = w[i] - uw * u[i];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            G[3 * r + c] = kd / d *
                           (u[r] * pw[c] + uw * ((r == c) - u[r] * u[c]));
}

static double damp_axial(double kd, const cl_pair *pr, const long *s,
                         cl_eval *ev)
{
    const double *xa = ev->x + 3 * pr->a, *xb = ev->x + 3 * pr->b;
    const double *va = ev->v + 3 * pr->a, *vb = ev->v + 3 * pr->b;
    double d = cl_dist(xa, xb);
    if (!(d > 0))
        return 0.0;
    double u[3], w[3], uw = 0.0, fa[3], B[9];
    for (int i = 0; i < 3; i++) {
        u[i] = (xb[i] - xa[i]) / d;
        w[i] = vb[i] - va[i];
        uw += u[i] * w[i];
    }
    for (int i = 0; i < 3; i++)
        fa[i] = kd * uw * u[i];
    if (ev->dfdv) {
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                B[3 * r + c] = kd * u[r] * u[c];
        add_blocks(ev->dfdv, s, 1.0, B);
    }
    if (ev->dfdx) {
        axial_dx_block(kd, d, u, w, uw, B);
        add_blocks(ev->dfdx, s, 1.0, B);
    }
    return add_pair_force(ev, pr, fa);
}

/* Axial damping's force (f0, f1, f2) on a of pair a-b:
 * kd (u . (v_b - v_a)) u, the arithmetic of damp_axial; none for
 * coincident particles.  Scalars, not an array: a force stored entry by
 * entry and read back two at a time stalls on store forwarding. */
static inline void axial_force(double kd, const double *xa, const double *xb,
                               const double *va, const double *vb,
                               double *f0, double *f1, double *f2)
{
    double d = cl_dist(xa, xb), uw = 0.0;
    if (!(d > 0)) {
        *f0 = *f1 = *f2 = 0.0;
        return;
    }
    double u0 = (xb[0] - xa[0]) / d, u1 = (xb[1] - xa[1]) / d;
    double u2 = (xb[2] - xa[2]) / d;
    uw += u0 * (vb[0] - va[0]);
    uw += u1 * (vb[1] - va[1]);
    uw += u2 * (vb[2] - va[2]);
    *f0 = kd * uw * u0;
    *f1 = kd * uw * u1;
    *f2 = kd * uw * u2;
}

/* Forces only, linear or axial: the path of every right-hand side. */
static void damp_forces(const cl_pairdamp *pd, size_t k0, size_t k1,
                        const double *restrict x, const double *restrict v,
                        double *restrict f)
{
    const cl_pair *pair = pd->pt.set.pair;
    double kd = pd->kd;
    bool axial = pd->model == CL_DAMP_AXIAL;
    for (size_t k = k0; k < k1; k++) {
        if (cl_pairterm_is_torn(&pd->pt, k))
            continue;
        const double *va = v + 3 * pair[k].a, *vb = v + 3 * pair[k].b;
        double f0, f1, f2;
        if (axial) {
            axial_force(kd, x + 3 * pair[k].a, x + 3 * pair[k].b, va, vb,
                        &f0, &f1, &f2);
        } else {
            f0 = -kd * (va[0] - vb[0]);
            f1 = -kd * (va[1] - vb[1]);
            f2 = -kd * (va[2] - vb[2]);
        }
        cl_pair_scatter(f, &pair[k], f0, f1, f2);
    }
}

void cl_pairdamp_eval(cl_pairdamp *pd, cl_eval *ev, cl_pairdamp_keep keep,
                      const void *ctx)
{
    size_t k0, k1;
    cl_eval_share(ev, pd->pt.set.n, &k0, &k1);
    if (!keep && !ev->dfdx && !ev->dfdv && !ev->want_energy) {
        if (ev->f)
            damp_forces(pd, k0, k1, ev->x, ev->v, ev->f);
        return;
    }
    double power = 0.0;
    for (size_t k = k0; k < k1; k++) {
        if (cl_pairterm_is_torn(&pd->pt, k) ||
            (keep && !keep(ctx, k, ev->x)))
            continue;
        const cl_pair *pr = &pd->pt.set.pair[k];
        const long *s = pd->pt.slot ? pd->pt.slot + 4 * k : NULL;
        power += pd->model == CL_DAMP_AXIAL ? damp_axial(pd->kd, pr, s, ev)
                                            : damp_linear(pd->kd, pr, s, ev);
    }
    if (ev->want_energy) {
        ev->energy = 0.0;
        ev->power = power;
    }
}
