/* The cloth model as a cl_system (docs/model.md 1): free-particle numbering
 * with pins (negative pin indices), scatter/gather with moving pins, mass per
 * degree of freedom, system force = gathered full force, the system Jacobian
 * against finite differences of the system force on the hang defaults, the
 * free-particle pattern against the full-particle Jacobian, exact zeros at
 * rest, configuration errors, and [init] state. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"
#include "forces/term.h"
#include "tmpdir.h"

/* ---- numbering, scatter, gather, mass ---------------------------------- */

Test(model, free_numbering_with_negative_pins)
{
    cl_model *m = FD_MODEL("cloth.n=4", "pins.at=0,0 0,-1 -1,-1 2,1 -4,2");
    const cl_cloth *c = cl_model_cloth(m);
    /* (0,0)=0, (0,3)=3, (3,3)=15, (2,1)=9, (-4,2)=(0,2)=2 */
    static const int pinned[] = {0, 3, 15, 9, 2};
    cr_assert_eq(c->npin, 5);
    for (size_t k = 0; k < 5; k++)
        cr_assert_eq(c->pins[k].p, pinned[k], "pin %zu at %d", k,
                     c->pins[k].p);
    cr_assert_eq(c->nfree, 11);
    cr_assert_eq(cl_model_system(m)->n, 33);
    int next = 0;
    for (int p = 0; p < 16; p++) {
        bool is_pinned = false;
        for (size_t k = 0; k < 5; k++)
            is_pinned |= pinned[k] == p;
        if (is_pinned) {
            cr_assert_eq(c->dof[p], -1, "particle %d", p);
        } else {
            cr_assert_eq(c->dof[p], next, "particle %d", p);
            cr_assert_eq(c->free_p[next], p);
            next++;
        }
    }
    cl_model_free(m);
}

Test(model, scatter_gather_with_moving_pins)
{
    cl_model *m = FD_MODEL("cloth.n=3", "pins.at=0,0 2,-1",
                           "pins.velocity=0.5,-1,0.25");
    const cl_cloth *c = cl_model_cloth(m);
    size_t n = fd_n(m), nf = 3 * c->nfree;
    cr_assert_eq(nf, 21);
    double *x = fd_vec(nf), *v = fd_vec(nf), *xf = fd_vec(n), *vf = fd_vec(n),
           *back = fd_vec(nf);
    fd_rng r = {71};
    fd_random_vec(&r, 1.0, x, nf);
    fd_random_vec(&r, 1.0, v, nf);
    const double t = 2.5, w[3] = {0.5, -1, 0.25};
    cl_cloth_scatter(c, t, x, v, xf, vf);
    for (size_t k = 0; k < c->nfree; k++)
        for (int i = 0; i < 3; i++) {
            cr_assert_eq(xf[3 * c->free_p[k] + i], x[3 * k + i]);
            cr_assert_eq(vf[3 * c->free_p[k] + i], v[3 * k + i]);
        }
    static const int pinned[] = {0, 8};
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 3; i++) {
            int p = pinned[k];
            cr_assert_eq(xf[3 * p + i], c->X0[3 * p + i] + w[i] * t);
            cr_assert_eq(vf[3 * p + i], w[i]);
        }
    cl_cloth_gather(c, xf, back);
    cr_assert_eq(memcmp(back, x, nf * sizeof *x), 0);
    cl_cloth_gather(c, vf, back);
    cr_assert_eq(memcmp(back, v, nf * sizeof *v), 0);
    /* v may be NULL: positions only. */
    memset(vf, 0, n * sizeof *vf);
    cl_cloth_scatter(c, t, x, NULL, xf, NULL);
    cr_assert_eq(xf[3 * 8 + 1], c->X0[3 * 8 + 1] - t);
    free(x);
    free(v);
    free(xf);
    free(vf);
    free(back);
    cl_model_free(m);
}

Test(model, mass_per_dof)
{
    cl_model *m = FD_MODEL("cloth.nu=4", "cloth.nv=5", "cloth.mass=0.4",
                           "pins.at=0,0 -1,-1");
    const cl_system *sys = cl_model_system(m);
    const cl_cloth *c = cl_model_cloth(m);
    cr_assert_eq(sys->n, 3 * 18);
    for (size_t k = 0; k < sys->n; k++)
        cr_assert_eq(sys->mass[k], 0.4 / 20.0, "mass[%zu] = %g", k,
                     sys->mass[k]);
    for (size_t p = 0; p < c->np; p++)
        cr_assert_eq(c->mass[p], 0.4 / 20.0);
    cl_model_free(m);
    m = FD_MODEL("cloth.n=3", "cloth.particle_mass=0.003");
    sys = cl_model_system(m);
    for (size_t k = 0; k < sys->n; k++)
        cr_assert_eq(sys->mass[k], 0.003);
    cl_model_free(m);
}

/* ---- system force, energy, Jacobian ------------------------------------ */

/* The hang defaults (pins at two corners of one edge, gravity, Type1 and
 * Type2 at default parameters) on a 6 x 6 grid, plus extra settings. */
#define HANG(...) FD_MODEL("cloth.n=6", __VA_ARGS__)

/* A state away from every kink: x stretched 3% (Type1 axis-x taut, Type2
 * axis-x in tension), z compressed 5% (axis-z: Type1 slack, Type2 f_b),
 * diagonals ~0.9% compressed (Type1 slack, Type2 f_b; the default f_b/cb
 * crossover is within 3e-6 L of L).  Free particles only. */
static void hang_state(const cl_model *m, fd_rng *r, double *x, double *v)
{
    const cl_cloth *c = cl_model_cloth(m);
    size_t n = fd_n(m);
    double *xf = fd_vec(n), A[9];
    fd_scale(1.03, 0.95, A);
    fd_deform(m, A, 0.001, 0.02, r, xf);
    /* Pins stay where they are prescribed; the pairs at pin (0,-1) are then
     * stretched further (kink_margin checks every pair). */
    cl_cloth_gather(c, xf, x);
    fd_random_vec(r, 0.3, v, 3 * c->nfree);
    free(xf);
}

/* Smallest |d/L - 1| over Type1 and Type2 pairs at the free state x. */
static double kink_margin(const cl_model *m, const double *x, double t)
{
    const cl_cloth *c = cl_model_cloth(m);
    size_t n = fd_n(m);
    double *xf = fd_vec(n), margin = INFINITY;
    cl_cloth_scatter(c, t, x, NULL, xf, NULL);
    for (int type = 1; type <= 2; type++) {
        cl_pairset s;
        cl_error err;
        cr_assert_eq(type == 1 ? cl_pairs_type1(c, &s, &err)
                               : cl_pairs_type2(c, &s, &err),
                     CL_OK);
        for (size_t k = 0; k < s.n; k++) {
            const cl_pair *p = &s.pair[k];
            double e = cl_dist(xf + 3 * p->a, xf + 3 * p->b) / p->rest - 1;
            margin = fmin(margin, fabs(e));
        }
        cl_pairs_free(&s);
    }
    free(xf);
    return margin;
}

/* Dense (3 nfree)^2 matrices from the system's block values. */
static void sys_dense(const cl_system *sys, const double *bx, const double *bv,
                      double *Jx, double *Jv)
{
    size_t n = sys->n;
    const cl_bpattern *pat = sys->pattern;
    cr_assert_eq(pat->nb * 3, n);
    memset(Jx, 0, n * n * sizeof *Jx);
    memset(Jv, 0, n * n * sizeof *Jv);
    for (size_t bi = 0; bi < pat->nb; bi++)
        for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++)
            for (size_t r = 0; r < 3; r++)
                for (size_t c = 0; c < 3; c++) {
                    size_t at = (3 * bi + r) * n + 3 * pat->col[k] + c;
                    Jx[at] = bx[9 * k + 3 * r + c];
                    Jv[at] = bv[9 * k + 3 * r + c];
                }
}

/* Central differences of sys->force w.r.t. x or v. */
static void sys_fd(const cl_system *sys, double t, const double *x,
                   const double *v, bool wrt_v, double h, double *J)
{
    size_t n = sys->n;
    double *xx = fd_vec(n), *vv = fd_vec(n), *fp = fd_vec(n), *fm = fd_vec(n);
    memcpy(xx, x, n * sizeof *x);
    memcpy(vv, v, n * sizeof *v);
    double *z = wrt_v ? vv : xx;
    for (size_t c = 0; c < n; c++) {
        double z0 = z[c], zp = z0 + h, zm = z0 - h;
        z[c] = zp;
        cr_assert_eq(sys->force(sys->data, t, xx, vv, fp), CL_OK);
        z[c] = zm;
        cr_assert_eq(sys->force(sys->data, t, xx, vv, fm), CL_OK);
        z[c] = z0;
        for (size_t r = 0; r < n; r++)
            J[r * n + c] = (fp[r] - fm[r]) / (zp - zm);
    }
    free(xx);
    free(vv);
    free(fp);
    free(fm);
}

static void check_system_jacobian(cl_model *m, double t, fd_rng *r,
                                  const char *label)
{
    const cl_system *sys = cl_model_system(m);
    size_t n = sys->n, nb = 9 * sys->pattern->nnzb;
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), *f2 = fd_vec(n),
           *bx = fd_vec(nb), *bv = fd_vec(nb), *Jx = fd_vec(n * n),
           *Jv = fd_vec(n * n), *Fx = fd_vec(n * n), *Fv = fd_vec(n * n);
    hang_state(m, r, x, v);
    double margin = kink_margin(m, x, t);
    cr_assert_gt(margin, 0.005, "%s: kink margin %g", label, margin);
    /* Values are overwritten, not accumulated: fill with garbage first. */
    for (size_t k = 0; k < nb; k++)
        bx[k] = bv[k] = 1e300;
    cr_assert_eq(sys->jacobian(sys->data, t, x, v, f, bx, bv), CL_OK);
    cr_assert_eq(sys->force(sys->data, t, x, v, f2), CL_OK);
    cr_assert_eq(memcmp(f, f2, n * sizeof *f), 0,
                 "%s: jacobian's f differs from force", label);
    sys_dense(sys, bx, bv, Jx, Jv);
    sys_fd(sys, t, x, v, false, 2e-7, Fx);
    sys_fd(sys, t, x, v, true, 1e-6, Fv);
    double ex = fd_relerr(Fx, Jx, n * n), ev = fd_relerr(Fv, Jv, n * n);
    char buf[128];
    snprintf(buf, sizeof buf, "%s system df/dx", label);
    fd_report(buf, ex);
    snprintf(buf, sizeof buf, "%s system df/dv", label);
    fd_report(buf, ev);
    cr_assert_lt(ex, 1e-8, "%s: system df/dx vs FD %g", label, ex);
    cr_assert_lt(ev, 1e-8, "%s: system df/dv vs FD %g", label, ev);
    free(x);
    free(v);
    free(f);
    free(f2);
    free(bx);
    free(bv);
    free(Jx);
    free(Jv);
    free(Fx);
    free(Fv);
}

Test(model, system_jacobian_fd_hang_defaults)
{
    cl_model *m = HANG("type1.enabled=true");
    fd_rng r = {72};
    check_system_jacobian(m, 0.0, &r, "hang");
    cl_model_free(m);
}

Test(model, system_jacobian_fd_hang_damped_moving_pins)
{
    cl_model *m = HANG("damping.kd=0.05", "pins.velocity=0,0,0.001",
                       "jacobian.transverse=full");
    fd_rng r = {73};
    check_system_jacobian(m, 0.5, &r, "hang damped");
    cl_model_free(m);
}

/* With obstacles, through the system's assembly: every free particle of
 * the 1 m cloth inside the penalty bands (eps = 0.3 m) of a plane 0.1 m
 * below it and of a sphere of radius 2 m whose top is there too (clearances
 * 0.1-0.23 m, away from the bands' edges), both moving and the sphere
 * turning, with friction smoothed over 10 m/s on the plane (every
 * particle in the smoothed regime) and 1e-4 m/s on the sphere (every
 * particle sliding); the blocks of docs/model.md (C4)-(C8) land in their
 * slots of the pattern beside the cloth's own. */
Test(model, system_jacobian_fd_with_moving_obstacles)
{
    cl_model *m = HANG("damping.kd=0.05", "obstacle.ground.shape=plane",
                       "obstacle.ground.point=0, -0.1, 0",
                       "obstacle.ground.normal=0, 1, 0",
                       "obstacle.ground.response=penalty",
                       "obstacle.ground.k=50", "obstacle.ground.eps=0.3",
                       "obstacle.ground.damping=0.5", "obstacle.ground.mu=0.4",
                       "obstacle.ground.v_smooth=10",
                       "obstacle.ground.path=0: 0, 0, 0; 1: 0.01, 0.02, 0",
                       "obstacle.ball.shape=sphere",
                       "obstacle.ball.center=0.5, -2.1, 0.5",
                       "obstacle.ball.radius=2",
                       "obstacle.ball.response=penalty",
                       "obstacle.ball.k=30", "obstacle.ball.eps=0.3",
                       "obstacle.ball.damping=0.2", "obstacle.ball.mu=0.3",
                       "obstacle.ball.v_smooth=1e-4",
                       "obstacle.ball.omega=0, 0.5, 0.2",
                       "obstacle.ball.path=0: 0, 0, 0; 1: 0, 0.02, 0.01");
    /* the state check_system_jacobian draws: every free particle deep in
     * both bands, where the obstacles are at t = 0.5 */
    const cl_system *sys = cl_model_system(m);
    double *x = fd_vec(sys->n), *v = fd_vec(sys->n);
    fd_rng r = {75};
    hang_state(m, &r, x, v);
    const double ball[3] = {0.5, -2.1 + 0.01, 0.5 + 0.005};
    const double u_floor[3] = {0.01, 0.02, 0}, u_path[3] = {0, 0.02, 0.01},
                 omega[3] = {0, 0.5, 0.2};
    for (size_t i = 0; i < sys->n; i += 3) {
        double d_floor = x[i + 1] - (-0.1 + 0.01);
        double d_ball = cl_dist(x + i, ball) - 2.0;
        cr_assert(d_floor > 0.05 && d_floor < 0.25, "floor: d = %g", d_floor);
        cr_assert(d_ball > 0.05 && d_ball < 0.25, "ball: d = %g", d_ball);
        /* sliding speeds: within the floor's smoothing, beyond the ball's */
        double r[3], w[3], n[3], wn = 0, floor_t = 0, ball_t = 0;
        for (int k = 0; k < 3; k++)
            r[k] = x[i + k] - ball[k];
        for (int k = 0; k < 3; k++) {
            int a = (k + 1) % 3, b = (k + 2) % 3;
            w[k] = v[i + k] - u_path[k] - (omega[a] * r[b] - omega[b] * r[a]);
            n[k] = r[k] / (d_ball + 2.0);
            wn += w[k] * n[k];
        }
        for (int k = 0; k < 3; k++) {
            double ft = k == 1 ? 0.0 : v[i + k] - u_floor[k];
            floor_t += ft * ft;
            ball_t += (w[k] - wn * n[k]) * (w[k] - wn * n[k]);
        }
        cr_assert(sqrt(floor_t) < 10.0 && sqrt(ball_t) > 1e-3,
                  "tangential speeds %g (floor), %g (ball)", sqrt(floor_t),
                  sqrt(ball_t));
    }
    free(x);
    free(v);
    r = (fd_rng){75};
    check_system_jacobian(m, 0.5, &r, "hang with obstacles");
    cl_model_free(m);
}

/* The system force is the full force gathered to the free particles, with
 * the pins at their prescribed place; energies agree too.  The energy
 * path evaluates term by term, scattering each pair's force; the force
 * path evaluates Type1, Type2 and the damping in one pass (forces/term.h,
 * fuse) and sums each particle's per-pair forces in one list: the same
 * per-pair forces (u = x_ab (1/d) instead of x_ab / d, one rounding off),
 * added in another order, so the two agree to a few ulp of the largest
 * per-pair force, 1e-13 of the largest force here (the gradient of the
 * energy to round-off: the finite-difference tests above and in
 * test_type1.c, test_type2.c). */
Test(model, system_force_equals_gathered_full_force)
{
    cl_model *m = HANG("damping.kd=0.05", "pins.at=0,0 0,-1 -1,2",
                       "pins.velocity=0.01,0.02,-0.03");
    const cl_system *sys = cl_model_system(m);
    const cl_cloth *c = cl_model_cloth(m);
    size_t n = sys->n, nf = fd_n(m);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), *g = fd_vec(n),
           *xf = fd_vec(nf), *vf = fd_vec(nf), *ff = fd_vec(nf),
           *keep = fd_vec(cl_model_potentials(m));
    fd_rng r = {74};
    const double t = 0.75;
    hang_state(m, &r, x, v);
    cr_assert_eq(sys->force(sys->data, t, x, v, f), CL_OK);
    cl_cloth_scatter(c, t, x, v, xf, vf);
    cl_energy ef, e = fd_eval(m, xf, vf, ff);
    cl_energy_keep(&ef, &e, keep);
    cl_cloth_gather(c, ff, g);
    double big = 0.0, worst = 0.0;
    for (size_t i = 0; i < n; i++) {
        big = fmax(big, fabs(g[i]));
        worst = fmax(worst, fabs(f[i] - g[i]));
    }
    cr_assert_gt(big, 0.0);
    cr_assert_leq(worst, 1e-13 * big, "%.3g of %.3g", worst, big);
    /* The pinned particles feel forces the system does not report. */
    cr_assert_neq(ff[3 * c->pins[0].p + 1], 0.0);
    cl_energy es;
    cr_assert_eq(sys->energy(sys->data, t, x, v, &es), CL_OK);
    cr_assert_eq(es.nterm, ef.nterm);
    for (size_t k = 0; k < es.nterm; k++) {
        cr_assert_str_eq(es.name[k], ef.name[k]);
        cr_assert_eq(es.value[k], ef.value[k]);
    }
    cr_assert_eq(es.potential, ef.potential);
    cr_assert_eq(es.power_diss, ef.power_diss);
    double ke = 0.0;
    for (size_t k = 0; k < n; k++)
        ke += 0.5 * sys->mass[k] * v[k] * v[k];
    cr_assert(fabs(es.kinetic - ke) <= 1e-14 * ke, "kinetic %g vs %g",
              es.kinetic, ke);
    cr_assert(fabs(es.total - (es.kinetic + es.potential)) <=
              1e-15 * fabs(es.total));
    free(x);
    free(v);
    free(f);
    free(g);
    free(xf);
    free(vf);
    free(ff);
    free(keep);
    cl_model_free(m);
}

/* The free-particle blocks of the system Jacobian equal the corresponding
 * blocks of the full-particle Jacobian (same state, pins in place). */
/* Threaded forces and Jacobians (cl_model_set_threads) are bitwise the
 * serial ones for 2, 3 and 7 threads (a count that does not divide the
 * pairs evenly), on a 12 x 12 hang with every pair term active (Type1
 * taut and slack, Type2 on its f_b branch, damping) and on springs with
 * axial damping (forces in one pass with the springs', forces/term.h
 * fuse; the Jacobian's forces are theirs); bad counts are refused. */
static void eval_all(const cl_system *sys, const double *x, const double *v,
                     double *f, double *fj, double *jx, double *jv)
{
    cr_assert_eq(sys->force(sys->data, 0.3, x, v, f), CL_OK);
    cr_assert_eq(sys->jacobian(sys->data, 0.3, x, v, fj, jx, jv), CL_OK);
}

static void check_threads(cl_model *m, fd_rng *r)
{
    const cl_system *sys = cl_model_system(m);
    size_t n = sys->n, nv = 9 * sys->pattern->nnzb;
    double *x = fd_vec(n), *v = fd_vec(n), *f1 = fd_vec(n), *fk = fd_vec(n);
    double *fj1 = fd_vec(n), *fjk = fd_vec(n), *jx1 = fd_vec(nv),
           *jxk = fd_vec(nv), *jv1 = fd_vec(nv), *jvk = fd_vec(nv);
    hang_state(m, r, x, v);
    eval_all(sys, x, v, f1, fj1, jx1, jv1);
    cr_assert_eq(memcmp(fj1, f1, n * sizeof *f1), 0,
                 "the Jacobian's forces are the force evaluation's");
    double big = 0.0;
    for (size_t i = 0; i < n; i++)
        big = fmax(big, fabs(f1[i]));
    cr_assert_gt(big, 0.0);
    static const int counts[] = {2, 3, 7, 1};
    for (size_t c = 0; c < 4; c++) {
        cr_assert_eq(cl_model_set_threads(m, counts[c], NULL), CL_OK);
        cr_assert_eq(sys->threads, counts[c]);
        eval_all(sys, x, v, fk, fjk, jxk, jvk);
        cr_assert_eq(memcmp(fk, f1, n * sizeof *fk), 0, "%d threads",
                     counts[c]);
        cr_assert_eq(memcmp(fjk, fj1, n * sizeof *fk), 0);
        cr_assert_eq(memcmp(jxk, jx1, nv * sizeof *jxk), 0);
        cr_assert_eq(memcmp(jvk, jv1, nv * sizeof *jvk), 0);
    }
    cl_error err = {0};
    cr_assert_eq(cl_model_set_threads(m, 0, &err), CL_EINVAL);
    cr_assert_eq(cl_model_set_threads(m, CL_MODEL_MAX_THREADS + 1, &err),
                 CL_EINVAL);
    double *arr[] = {x, v, f1, fk, fj1, fjk, jx1, jxk, jv1, jvk};
    for (size_t i = 0; i < sizeof arr / sizeof *arr; i++)
        free(arr[i]);
}

Test(model, threaded_force_and_jacobian_are_bitwise_serial)
{
    fd_rng r = {75};
    cl_model *m = FD_MODEL("cloth.n=12", "damping.kd=0.05");
    check_threads(m, &r);
    cl_model_free(m);
    m = FD_MODEL("cloth.n=12", "type1.enabled=false", "type2.enabled=false",
                 "damping.kd=0", "springs.enabled=true",
                 "spring-damping.kd=0.02", "spring-damping.model=axial");
    check_threads(m, &r);
    cl_model_free(m);
}

Test(model, system_jacobian_is_restriction_of_full)
{
    cl_model *m = HANG("damping.kd=0.05", "pins.at=0,0 0,-1 3,3");
    const cl_system *sys = cl_model_system(m);
    const cl_cloth *c = cl_model_cloth(m);
    size_t n = sys->n, nf = fd_n(m), nb = 9 * sys->pattern->nnzb;
    double *x = fd_vec(n), *v = fd_vec(n), *bx = fd_vec(nb), *bv = fd_vec(nb),
           *Jx = fd_vec(n * n), *Jv = fd_vec(n * n), *xf = fd_vec(nf),
           *vf = fd_vec(nf), *Kx = fd_vec(nf * nf), *Kv = fd_vec(nf * nf);
    fd_rng r = {75};
    hang_state(m, &r, x, v);
    cr_assert_eq(sys->jacobian(sys->data, 0.0, x, v, NULL, bx, bv), CL_OK);
    sys_dense(sys, bx, bv, Jx, Jv);
    cl_cloth_scatter(c, 0.0, x, v, xf, vf);
    fd_jacobian(m, xf, vf, Kx, Kv);
    for (size_t a = 0; a < c->nfree; a++)
        for (size_t b = 0; b < c->nfree; b++)
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    size_t pa = (size_t)c->free_p[a], pb = (size_t)c->free_p[b];
                    size_t s = (3 * a + i) * n + 3 * b + j;
                    size_t t = (3 * pa + i) * nf + 3 * pb + j;
                    cr_assert_eq(Jx[s], Kx[t]);
                    cr_assert_eq(Jv[s], Kv[t]);
                }
    /* And the system pattern still works after the full-Jacobian call. */
    double *bx2 = fd_vec(nb), *bv2 = fd_vec(nb);
    cr_assert_eq(sys->jacobian(sys->data, 0.0, x, v, NULL, bx2, bv2), CL_OK);
    cr_assert_eq(memcmp(bx, bx2, nb * sizeof *bx), 0);
    cr_assert_eq(memcmp(bv, bv2, nb * sizeof *bv), 0);
    free(bx2);
    free(bv2);
    free(x);
    free(v);
    free(bx);
    free(bv);
    free(Jx);
    free(Jv);
    free(xf);
    free(vf);
    free(Kx);
    free(Kv);
    cl_model_free(m);
}

/* Pattern: every diagonal block, symmetric structure, no duplicate blocks,
 * and no block touching a pinned particle. */
Test(model, pattern_structure)
{
    cl_model *m = HANG("pins.at=0,0 0,-1 2,2");
    const cl_bpattern *pat = cl_model_system(m)->pattern;
    cr_assert_eq(pat->nb, 33);
    for (size_t i = 0; i < pat->nb; i++) {
        cr_assert_eq(pat->col[pat->diag[i]], i);
        for (size_t k = pat->rowptr[i]; k < pat->rowptr[i + 1]; k++) {
            if (k > pat->rowptr[i])
                cr_assert_lt(pat->col[k - 1], pat->col[k]);
            cr_assert_geq(cl_bpattern_find(pat, (long)pat->col[k], (long)i),
                          0);
        }
    }
    cl_model_free(m);
}

/* At rest (pins fixed), every term at once: forces exactly zero. */
Test(model, rest_state_forces_exactly_zero)
{
    static const char *const grids[][3] = {
        {"cloth.n=7", "cloth.size=0.7", "cloth.mass=0.1"},
        {"cloth.nu=5", "cloth.nv=9", "cloth.su=1.3"},
        {"cloth.nu=11", "cloth.nv=3", "cloth.sv=0.1"},
    };
    for (size_t g = 0; g < 3; g++) {
        cl_model *m = FD_MODEL(grids[g][0], grids[g][1], grids[g][2],
                               "gravity.g=0,0,0", "damping.kd=0.1",
                               "pins.at=0,0 -1,-1");
        const cl_system *sys = cl_model_system(m);
        size_t n = sys->n, nf = fd_n(m);
        double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n),
               *vf = fd_vec(nf), *ff = fd_vec(nf);
        cl_model_initial_state(m, x, v);
        cr_assert_eq(sys->force(sys->data, 0.0, x, v, f), CL_OK);
        cr_assert_eq(fd_maxabs(f, n), 0.0, "grid %zu: system force at rest",
                     g);
        cl_energy e = fd_eval(m, cl_model_cloth(m)->X0, vf, ff);
        cr_assert_eq(fd_maxabs(ff, nf), 0.0);
        cr_assert_eq(e.potential, 0.0);
        free(x);
        free(v);
        free(f);
        free(vf);
        free(ff);
        cl_model_free(m);
    }
}

/* Every row of the force registry and the obstacles at once: the model
 * holds as many terms as its configuration makes (no fixed bound), names
 * the conservative ones in its energies, and an energy kept with
 * cl_energy_keep survives the next evaluation. */
Test(model, every_term_at_once)
{
    cl_model *m = FD_MODEL("cloth.n=4", "pins.at=", "damping.kd=0.01",
                           "springs.enabled=true", "spring-damping.kd=0.01",
                           "bw-stretch.enabled=true", "bw-stretch.kd=1",
                           "bw-shear.enabled=true", "bw-shear.kd=1",
                           "bw-bend.enabled=true", "bw-bend.kd=1e-6",
                           "pbd.enabled=true", "selfcontact.enabled=true",
                           "selfcontact.thickness=0.1",
                           "selfcontact.stiffness=10",
                           "obstacle.floor.shape=plane",
                           "obstacle.floor.point=0,-5,0",
                           "obstacle.floor.normal=0,1,0",
                           "obstacle.floor.response=penalty",
                           "obstacle.floor.k=50");
    size_t rows = 0, npot = 0;
    while (cl_term_registry[rows])
        rows++;
    const char *const *names;
    size_t n = cl_model_terms(m, &names);
    cr_assert_eq(n, rows + 1, "%zu terms of %zu rows", n, rows);
    for (size_t k = 0; k < rows; k++)
        cr_assert_str_eq(names[k], cl_term_registry[k]->name);
    cr_assert_str_eq(names[rows], "contact");
    for (size_t k = 0; k < rows; k++)
        npot += cl_term_registry[k]->conservative;
    cr_assert_eq(cl_model_potentials(m), npot + 1); /* penalty contact */
    size_t nf = fd_n(m);
    double *x = fd_vec(nf), *v = fd_vec(nf), *f = fd_vec(nf),
           *keep = fd_vec(npot + 1);
    memcpy(x, cl_model_cloth(m)->X0, nf * sizeof *x);
    cl_energy e0, e = fd_eval(m, x, v, f);
    cr_assert_eq(e.nterm, npot + 1);
    cl_energy_keep(&e0, &e, keep);
    x[1] -= 0.3; /* one particle down: gravity's energy changes */
    cl_energy e1 = fd_eval(m, x, v, f);
    size_t g = 0;
    while (strcmp(e0.name[g], "gravity"))
        g++;
    cr_assert_float_eq(e1.value[g] - e0.value[g],
                       -0.3 * 9.81 * cl_model_cloth(m)->mass[0], 1e-12);
    free(x);
    free(v);
    free(f);
    free(keep);
    cl_model_free(m);
}

Test(model, default_terms)
{
    cl_model *m = FD_MODEL("cloth.n=4");
    const char *const *names;
    size_t n = cl_model_terms(m, &names);
    cr_assert_eq(n, 3);
    cr_assert_str_eq(names[0], "type1");
    cr_assert_str_eq(names[1], "type2");
    cr_assert_str_eq(names[2], "gravity");
    /* Default pins: two corners of the edge i = 0. */
    const cl_cloth *c = cl_model_cloth(m);
    cr_assert_eq(c->npin, 2);
    cr_assert_eq(c->pins[0].p, 0);
    cr_assert_eq(c->pins[1].p, 3);
    cl_model_free(m);
}

/* ---- configuration errors ---------------------------------------------- */

/* The model of `sets` is refused with status `want` and a message
 * containing `needle`. */
static void expect_status(const char *const *sets, cl_status want,
                          const char *needle)
{
    cl_model *m = NULL;
    cl_error err;
    memset(&err, 0, sizeof err);
    cl_status rc = fd_model_try(sets, &m, &err);
    cr_assert_eq(rc, want, "expected status %d, got %d (%s)", want, rc,
                 err.msg);
    cr_assert_null(m);
    cr_assert_not_null(strstr(err.msg, needle), "message \"%s\" lacks \"%s\"",
                       err.msg, needle);
}

static void expect_error(const char *const *sets, const char *needle)
{
    expect_status(sets, CL_EINVAL, needle);
}

Test(model, error_pin_outside_grid)
{
    expect_error(FD_SETS("cloth.n=5", "pins.at=0,5"), "outside");
    expect_error(FD_SETS("cloth.n=5", "pins.at=5,0"), "outside");
    expect_error(FD_SETS("cloth.n=5", "pins.at=-6,0"), "outside");
    expect_error(FD_SETS("cloth.n=5", "pins.at=0,0 0,-6"), "outside");
}

Test(model, error_pin_twice)
{
    /* Twice with different motions (a group moving, another fixed); the
     * same particle also through a negative index. */
    expect_error(FD_SETS("cloth.n=5", "pins.at=1,1", "pins2.at=1,1",
                         "pins2.velocity=0,1,0"), "twice");
    expect_error(FD_SETS("cloth.n=5", "pins.at=0,-1", "pins.velocity=1,0,0",
                         "pins2.at=0,4", "pins2.velocity=1,0,0",
                         "pins2.stop=1"), "twice");
    expect_error(FD_SETS("cloth.n=5", "pins.at=-5,-5", "pins2.at=0,0",
                         "pins2.velocity=1,0,0"), "twice");
    /* The same pin with the same motion again is no error. */
    cl_model *m = FD_MODEL("cloth.n=5", "pins.at=1,1 1,1 i=1");
    cr_assert_eq(cl_model_cloth(m)->npin, 5);
    cl_model_free(m);
}

Test(model, error_everything_pinned)
{
    expect_error(FD_SETS("cloth.n=2", "type2.enabled=false",
                         "pins.at=0,0 0,1 1,0 1,1"),
                 "pinned");
    expect_error(FD_SETS("cloth.n=3", "pins.at=0,0 0,1 0,2 1,0 1,1 1,2 2,0 "
                                      "2,1 2,2"),
                 "pinned");
}

Test(model, error_malformed_pins)
{
    expect_error(FD_SETS("cloth.n=4", "pins.at=0;0"), "pins");
    expect_error(FD_SETS("cloth.n=4", "pins.at=0,0,1"), "pins");
    expect_error(FD_SETS("cloth.n=4", "pins.at=a,b"), "pins");
}

/* n = 2 has no interlaced pairs: Type2 refuses it rather than silently
 * doing nothing; with Type2 off the grid is fine. */
Test(model, n2_with_type2)
{
    expect_error(FD_SETS("cloth.n=2"), "Type2");
    expect_error(FD_SETS("cloth.nu=2", "cloth.nv=2", "pins.at=0,0"), "Type2");
    /* One side of 3 or more has interlaced pairs along it. */
    cl_model *m = FD_MODEL("cloth.nu=2", "cloth.nv=7");
    cr_assert(fd_has_term(m, "type2"));
    cl_model_free(m);
    m = FD_MODEL("cloth.n=2", "type2.enabled=false");
    cr_assert(!fd_has_term(m, "type2"));
    cr_assert_eq(cl_model_cloth(m)->nfree, 2);
    cl_model_free(m);
}

/* The term masks (system.h force_terms, jacobian_terms): the default
 * implicit set (type1, damping; gravity and type2 soft), a key that moves
 * a term, and the two halves adding up to the whole force and Jacobian,
 * bit for bit with all terms. */
static void check_halves(cl_model *m, uint64_t implicit, fd_rng *r)
{
    const cl_system *sys = cl_model_system(m);
    size_t n = sys->n, nv = 9 * sys->pattern->nnzb;
    cr_assert_eq(sys->implicit_terms, implicit);
    uint64_t all = (UINT64_C(1) << sys->nterm) - 1;
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), *fi = fd_vec(n),
           *fe = fd_vec(n), *fa = fd_vec(n);
    double *kx = fd_vec(nv), *kv = fd_vec(nv), *kxi = fd_vec(nv),
           *kvi = fd_vec(nv), *kxe = fd_vec(nv), *kve = fd_vec(nv);
    hang_state(m, r, x, v);
    cr_assert_eq(sys->force(sys->data, 0.1, x, v, f), CL_OK);
    cr_assert_eq(sys->force_terms(sys->data, all, 0.1, x, v, fa), CL_OK);
    cr_assert_eq(memcmp(f, fa, n * sizeof *f), 0);
    cr_assert_eq(sys->force_terms(sys->data, implicit, 0.1, x, v, fi), CL_OK);
    cr_assert_eq(sys->force_terms(sys->data, all & ~implicit, 0.1, x, v, fe),
                 CL_OK);
    cr_assert_eq(sys->jacobian(sys->data, 0.1, x, v, NULL, kx, kv), CL_OK);
    cr_assert_eq(sys->jacobian_terms(sys->data, implicit, 0.1, x, v, NULL,
                                     kxi, kvi), CL_OK);
    cr_assert_eq(sys->jacobian_terms(sys->data, all & ~implicit, 0.1, x, v,
                                     NULL, kxe, kve), CL_OK);
    double big = 0, fbig = 0;
    for (size_t i = 0; i < n; i++) {
        cr_assert_float_eq(fi[i] + fe[i], f[i], 1e-12 * (1 + fabs(f[i])));
        fbig = fmax(fbig, fabs(fe[i]));
    }
    for (size_t i = 0; i < nv; i++) {
        cr_assert_float_eq(kxi[i] + kxe[i], kx[i], 1e-12 * (1 + fabs(kx[i])));
        cr_assert_float_eq(kvi[i] + kve[i], kv[i], 1e-12 * (1 + fabs(kv[i])));
        big = fmax(big, fmax(fabs(kxe[i]), fabs(kve[i])));
    }
    cr_assert_gt(fbig, 0.0, "the explicit half has a force");
    cr_assert_gt(big, 0.0, "the explicit half has a Jacobian");
    free(x), free(v), free(f), free(fi), free(fe), free(fa);
    free(kx), free(kv), free(kxi), free(kvi), free(kxe), free(kve);
}

Test(model, term_masks_split_force_and_jacobian)
{
    fd_rng r = {76};
    /* terms: type1, type2, damping, gravity */
    cl_model *m = HANG("damping.kd=0.05");
    check_halves(m, 0x5, &r);
    cl_model_free(m);
    m = HANG("damping.kd=0.05", "type2.imex=implicit", "damping.imex=explicit");
    check_halves(m, 0x3, &r);
    cl_model_free(m);
    const char *const bad[] = {"cloth.n=4", "type1.imex=both", NULL};
    expect_error(bad, "imex");
}

/* ---- [init] state ------------------------------------------------------ */

/* A state file for model m: every free particle at its rest position plus
 * `shift` times a pseudo-random offset, the pinned ones `pin_shift` along
 * x from theirs, the velocities pseudo-random; into x and v (3 np each). */
static void write_state(const cl_model *m, const char *path, double shift,
                        double pin_shift, double *x, double *v)
{
    const cl_cloth *c = cl_model_cloth(m);
    fd_rng r = {91};
    FILE *f = fopen(path, "w");
    cr_assert_not_null(f);
    fprintf(f, "p,x,y,z,vx,vy,vz\n");
    for (size_t p = 0; p < c->np; p++) {
        bool free_p = c->dof[p] >= 0;
        for (int i = 0; i < 3; i++) {
            x[3 * p + i] = c->X0[3 * p + i] +
                           (free_p ? shift * (2 * fd_rand(&r) - 1)
                                   : i == 0 ? pin_shift : 0.0);
            v[3 * p + i] = 2 * fd_rand(&r) - 1;
        }
        fprintf(f, "%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", p, x[3 * p],
                x[3 * p + 1], x[3 * p + 2], v[3 * p], v[3 * p + 1],
                v[3 * p + 2]);
    }
    cr_assert_eq(fclose(f), 0);
}

/* A state of `plain` (write_state, free particles 0.05 off, pinned ones
 * pin_shift) in a fresh directory dir (512 bytes), named by "init.state=
 * PATH" in set (700 bytes); its arrays into *xs, *vs (to free). */
static void state_case(const cl_model *plain, const char *tag,
                       double pin_shift, char *dir, char *set, double **xs,
                       double **vs)
{
    char path[600];
    tmp_mkdtemp(dir, 512, tag);
    snprintf(path, sizeof path, "%s/s.csv", dir);
    snprintf(set, 700, "init.state=%s", path);
    *xs = fd_vec(fd_n(plain));
    *vs = fd_vec(fd_n(plain));
    write_state(plain, path, 0.05, pin_shift, *xs, *vs);
}

/* What state_case made, and the model it was made for. */
static void state_case_free(cl_model *plain, double *xs, double *vs,
                            const char *dir)
{
    cl_model_free(plain);
    free(xs), free(vs);
    tmp_rm_rf(dir);
}

/* m's initial state is the free part of xs, vs (3 np each), bit for bit. */
static void assert_initial_state(const cl_model *m, const double *xs,
                                 const double *vs)
{
    const cl_cloth *c = cl_model_cloth(m);
    size_t nf = 3 * c->nfree;
    double *x = fd_vec(nf), *v = fd_vec(nf), *want = fd_vec(nf);
    cr_assert_eq(cl_model_initial_state(m, x, v), CL_OK);
    cl_cloth_gather(c, xs, want);
    cr_assert_eq(memcmp(x, want, nf * sizeof *x), 0);
    cl_cloth_gather(c, vs, want);
    cr_assert_eq(memcmp(v, want, nf * sizeof *v), 0);
    free(x), free(v), free(want);
}

/* The free particles start where the file puts them, at its velocities,
 * bit for bit, at t = 0 unless [init] time says otherwise. */
Test(model, init_state_is_the_initial_state)
{
    char dir[512], set[700];
    double *xs, *vs;
    cl_model *plain = FD_MODEL("cloth.n=4", "pins.at=0,0 0,-1");
    state_case(plain, "state", 0.0, dir, set, &xs, &vs);
    cl_model *m = FD_MODEL("cloth.n=4", "pins.at=0,0 0,-1", set);
    assert_initial_state(m, xs, vs);
    cr_assert_eq(cl_model_start_time(m), 0.0);
    cl_model_free(m);
    state_case_free(plain, xs, vs, dir);
}

/* A relative [init] state is relative to the problem file, as a mesh;
 * the file's own velocity and perturbation give way to the state. */
Test(model, init_state_relative_to_the_problem_file)
{
    char dir[512], set[700], path[600];
    double *xs, *vs;
    cl_model *plain = FD_MODEL("cloth.n=3");
    state_case(plain, "staterel", 0.0, dir, set, &xs, &vs);
    snprintf(path, sizeof path, "%s/p.ini", dir);
    tmp_put(path, "[cloth]\nn = 3\n\n[init]\nstate = s.csv\n"
                  "velocity = 0, 1, 0\nperturb = 1e-3\n");
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cl_error err = {0};
    cr_assert_eq(cl_config_load(cfg, path, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    assert_initial_state(m, xs, vs);
    cl_model_free(m);
    cl_config_free(cfg);
    state_case_free(plain, xs, vs, dir);
}

/* A state saved at t = 0.5 of a pin moving at 1 m/s until t = 0.25: its
 * pinned row is 0.25 m on, so the state is good at [init] time 0.5 (or
 * any time after the stop) and refused at 0 or 0.1. */
Test(model, init_time_places_the_pins)
{
    char dir[512], set[700];
    double *xs, *vs;
    cl_model *plain = FD_MODEL("cloth.n=4", "pins.at=0,0",
                               "pins.velocity=1,0,0", "pins.stop=0.25");
    state_case(plain, "statetime", 0.25, dir, set, &xs, &vs);
    cl_model *m = FD_MODEL("cloth.n=4", "pins.at=0,0", "pins.velocity=1,0,0",
                           "pins.stop=0.25", set, "init.time=0.5");
    cr_assert_eq(cl_model_start_time(m), 0.5);
    cl_model_free(m);
    expect_error(FD_SETS("cloth.n=4", "pins.at=0,0", "pins.velocity=1,0,0",
                         "pins.stop=0.25", set, "init.time=0.1"),
                 "pinned particle 0");
    expect_error(FD_SETS("cloth.n=4", "pins.at=0,0", "pins.velocity=1,0,0",
                         "pins.stop=0.25", set), "[init] time = 0 s");
    /* a time without a state: the problem's own state is at t = 0 */
    expect_error(FD_SETS("cloth.n=4", "init.time=1"), "[init] time");
    expect_error(FD_SETS("cloth.n=4", set, "init.time=-1"), "time");
    state_case_free(plain, xs, vs, dir);
}

/* Refused: a pinned row away from its pin at t = 0 (a state of a moving
 * pin saved later), [init] velocity or perturb beside a state, a state
 * of another cloth. */
Test(model, init_state_refusals)
{
    char dir[512], path[700], set[700];
    double *xs, *vs;
    cl_model *plain = FD_MODEL("cloth.n=4", "pins.at=0,0",
                               "pins.velocity=1,0,0");
    state_case(plain, "stateno", 0.0, dir, set, &xs, &vs);
    snprintf(path, sizeof path, "%s", set + strlen("init.state="));
    /* the same state is good at t = 0; the pin moved 1 mm is not */
    cl_model_free(FD_MODEL("cloth.n=4", "pins.at=0,0", "pins.velocity=1,0,0",
                           set));
    write_state(plain, path, 0.05, 1e-3, xs, vs);
    expect_error(FD_SETS("cloth.n=4", "pins.at=0,0", "pins.velocity=1,0,0",
                         set), "pinned particle 0");
    write_state(plain, path, 0.05, 0.0, xs, vs);
    expect_error(FD_SETS("cloth.n=4", "pins.at=0,0", "init.velocity=0,1,0",
                         set), "[init] state");
    expect_error(FD_SETS("cloth.n=4", "pins.at=0,0", "init.perturb=1e-3",
                         set), "gives the positions");
    expect_status(FD_SETS("cloth.n=3", set), CL_EPARSE, "out of range");
    expect_status(FD_SETS("cloth.n=5", set), CL_EPARSE, "missing");
    state_case_free(plain, xs, vs, dir);
}
