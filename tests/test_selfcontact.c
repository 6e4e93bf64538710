/* The self-contact term (forces/selfcontact.h; docs/model.md 3.5) on a
 * folded 6 x 6 grid (spacing 0.2 m, thickness 0.25 m, k_s = 40 N/m): the
 * upper half laid back over the lower half 0.06 m above it, jittered, so
 * that about 40 pairs across the fold are in contact.
 *   - for the penalty and the log barrier (forces/logbarrier.h): force
 *     = -dE/dx (central differences of the energy), Newton's third law;
 *   - the exact Jacobian (cl_selfcontact_dense) against central
 *     differences of the force;
 *   - the lumped Jacobian the term writes into the pattern: the diagonal
 *     blocks -k_s sum u u^T over each particle's contacts, nothing else;
 *   - the energy column of a model, and the refusals (thickness above the
 *     rest distance of non-neighbours, missing keys);
 *   - the fold scene (problems/fold.ini, reduced to 10 x 10 particles, dt
 *     = 2e-3 s, h_s = 0.13 m): no two non-neighbours closer than h_s / 2
 *     at the end with self-contact on, closer with it off. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"
#include "forces/logbarrier.h"
#include "forces/selfcontact.h"
#include "runcli.h"
#include "timelimit.h"
#include "tmpdir.h"

#define N 6
#define NP (N * N)
#define N3 (3 * NP)
#define H_S 0.25
#define K_S 40.0

typedef struct {
    cl_cloth cloth;
    cl_config *cfg;
    void *st;
} sc_case;

/* law: "penalty" or "barrier".  The term keeps a pointer to c->cloth. */
static void make_case(sc_case *c, const char *law)
{
    c->cfg = cl_config_alloc();
    cl_error err = {0};
    cl_term_opts opts = {0};
    cr_assert_eq(cl_cloth_grid(N, N, 1.0, 1.0, 1e-3, &c->cloth, &err), CL_OK);
    cr_assert_not_null(c->cfg);
    const char *sets[] = {"selfcontact.enabled=true",
                          "selfcontact.thickness=0.25",
                          "selfcontact.stiffness=40", NULL};
    char lawset[64];
    snprintf(lawset, sizeof lawset, "selfcontact.law=%s", law);
    for (size_t k = 0; sets[k]; k++)
        cr_assert_eq(cl_config_set(c->cfg, sets[k], &err), CL_OK);
    cr_assert_eq(cl_config_set(c->cfg, lawset, &err), CL_OK);
    cr_assert_eq(cl_term_selfcontact.create(c->cfg, &c->cloth, &opts, &c->st,
                                            &err),
                 CL_OK, "%s", err.msg);
    cr_assert_not_null(c->st);
}

static void free_case(sc_case *c)
{
    cl_term_selfcontact.free(c->st);
    cl_config_free(c->cfg);
    cl_cloth_free(&c->cloth);
}

/* Rows i >= 3 laid back over rows 0..2 (x -> 1 - x, 0.06 m up), every
 * coordinate jittered by up to 0.01 m. */
static void folded(const cl_cloth *c, double *x)
{
    fd_rng r = {7};
    for (size_t p = 0; p < NP; p++) {
        const double *X = c->X0 + 3 * p;
        bool upper = p / N >= 3;
        x[3 * p] = upper ? 1.0 - X[0] : X[0];
        x[3 * p + 1] = upper ? 0.06 : 0.0;
        x[3 * p + 2] = X[2];
        for (int i = 0; i < 3; i++)
            x[3 * p + i] += 0.01 * fd_rand(&r);
    }
}

static double eval(sc_case *c, const double *x, double *f, double *dfdx)
{
    double v[N3] = {0};
    if (f)
        memset(f, 0, N3 * sizeof *f);
    cl_eval ev = {.x = x, .v = v, .f = f, .dfdx = dfdx, .want_energy = true};
    cl_term_selfcontact.eval(c->st, &ev);
    return ev.energy;
}

/* Pairs more than 2 rows or columns apart closer than h_s (brute force). */
static size_t contacts(const double *x)
{
    size_t n = 0;
    for (int a = 0; a < NP; a++)
        for (int b = a + 1; b < NP; b++) {
            int di = abs(a / N - b / N), dj = abs(a % N - b % N);
            n += (di > 2 || dj > 2) && cl_dist(x + 3 * a, x + 3 * b) < H_S;
        }
    return n;
}

static void check_gradient(const char *law)
{
    sc_case c;
    make_case(&c, law);
    double x[N3], f[N3], g[N3];
    folded(&c.cloth, x);
    cr_assert(contacts(x) >= 30, "%zu contacts", contacts(x));
    double e = eval(&c, x, f, NULL);
    cr_assert_gt(e, 0.0);
    double sum[3] = {0};
    for (size_t k = 0; k < N3; k++) {
        double x0 = x[k], h = 1e-6;
        x[k] = x0 + h;
        double ep = eval(&c, x, NULL, NULL);
        x[k] = x0 - h;
        double em = eval(&c, x, NULL, NULL);
        x[k] = x0;
        g[k] = -(ep - em) / (2 * h);
        sum[k % 3] += f[k];
    }
    double rel = fd_relerr(f, g, N3);
    char label[64];
    snprintf(label, sizeof label, "selfcontact %s f vs -dE/dx", law);
    fd_report(label, rel);
    cr_assert_lt(rel, 1e-8, "%s: f against -dE/dx: %g", law, rel);
    for (int i = 0; i < 3; i++)
        cr_assert_lt(fabs(sum[i]), 1e-12 * fd_maxabs(f, N3), "sum f = %g",
                     sum[i]);
    free_case(&c);
}

Test(selfcontact, force_is_minus_energy_gradient)
{
    check_gradient("penalty");
    check_gradient("barrier");
}

static void check_dense(const char *law)
{
    sc_case c;
    make_case(&c, law);
    double x[N3], fp[N3], fm[N3];
    double *J = fd_vec(N3 * N3), *F = fd_vec(N3 * N3);
    folded(&c.cloth, x);
    cl_selfcontact_dense(c.st, x, J);
    for (size_t col = 0; col < N3; col++) {
        double x0 = x[col], h = 1e-7;
        x[col] = x0 + h;
        eval(&c, x, fp, NULL);
        x[col] = x0 - h;
        eval(&c, x, fm, NULL);
        x[col] = x0;
        for (size_t r = 0; r < N3; r++)
            F[r * N3 + col] = (fp[r] - fm[r]) / (2 * h);
    }
    double rel = fd_relerr(F, J, N3 * N3);
    char label[64];
    snprintf(label, sizeof label, "selfcontact %s dense df/dx", law);
    fd_report(label, rel);
    cr_assert_lt(rel, 1e-8, "%s: df/dx against differences: %g", law, rel);
    double big = fd_maxabs(J, N3 * N3);
    for (size_t r = 0; r < N3; r++) /* a Hessian: symmetric */
        for (size_t col = 0; col < r; col++)
            cr_assert_lt(fabs(J[r * N3 + col] - J[col * N3 + r]),
                         1e-14 * big);
    free(J);
    free(F);
    free_case(&c);
}

Test(selfcontact, dense_jacobian_against_differences)
{
    check_dense("penalty");
    check_dense("barrier");
}

/* s'(d) of the law ((3.6) penalty, (3.7) barrier). */
static double law_ds(bool barrier, double d)
{
    return barrier ? K_S * cl_logbarrier_eval(d, H_S).d2b : K_S;
}

/* The pattern of the diagonal blocks alone (every particle a dof). */
static void check_lumped(bool barrier)
{
    sc_case c;
    make_case(&c, barrier ? "barrier" : "penalty");
    cl_bpattern pat;
    cl_error err = {0};
    int dof[NP];
    for (int p = 0; p < NP; p++)
        dof[p] = p;
    cr_assert_eq(cl_bpattern_build(NP, dof, NP, 0, NULL, &pat, &err), CL_OK);
    cr_assert_eq(cl_term_selfcontact.bind(c.st, &pat, dof, &err), CL_OK);
    double x[N3], vals[9 * NP] = {0}, want[9 * NP] = {0};
    folded(&c.cloth, x);
    eval(&c, x, NULL, vals);
    for (int a = 0; a < NP; a++)
        for (int b = 0; b < NP; b++) {
            int di = abs(a / N - b / N), dj = abs(a % N - b % N);
            double d = cl_dist(x + 3 * a, x + 3 * b);
            if (a == b || (di <= 2 && dj <= 2) || !(d < H_S))
                continue;
            for (int r = 0; r < 3; r++)
                for (int s = 0; s < 3; s++)
                    want[9 * pat.diag[a] + 3 * r + s] -=
                        law_ds(barrier, d) * (x[3 * b + r] - x[3 * a + r]) *
                        (x[3 * b + s] - x[3 * a + s]) / (d * d);
        }
    double rel = fd_relerr(vals, want, 9 * NP);
    cr_assert_lt(rel, 1e-13, "lumped blocks: %g", rel);
    cl_bpattern_free(&pat);
    free_case(&c);
}

Test(selfcontact, lumped_jacobian_is_the_normal_diagonal)
{
    check_lumped(false);
    check_lumped(true);
}

/* b, b', b'' vanish at dh; b'' > 0 below it; b grows as d -> 0. */
Test(selfcontact, barrier_shape)
{
    cl_logbarrier at = cl_logbarrier_eval(0.25, 0.25),
                  beyond = cl_logbarrier_eval(0.3, 0.25);
    cr_assert(at.b == 0 && at.db == 0 && at.d2b == 0);
    cr_assert(beyond.b == 0 && beyond.db == 0 && beyond.d2b == 0);
    double last = 0;
    for (double d = 0.24; d > 1e-6; d *= 0.5) {
        cl_logbarrier b = cl_logbarrier_eval(d, 0.25);
        cr_assert(b.b > last && b.db < 0 && b.d2b > 0, "d = %g", d);
        last = b.b;
    }
    /* b(dh / e) = (dh (1 - 1/e))^2 */
    double dh = 0.25, d = dh / M_E;
    cr_assert_float_eq(cl_logbarrier_eval(d, dh).b, (dh - d) * (dh - d),
                       1e-15);
}

Test(selfcontact, model_energy_column_and_refusals)
{
    cl_model *m = FD_MODEL("cloth.n=6", "selfcontact.enabled=true",
                           "selfcontact.thickness=0.25",
                           "selfcontact.stiffness=40");
    cr_assert(fd_has_term(m, "selfcontact"));
    double x[N3], v[N3] = {0}, f[N3];
    folded(cl_model_cloth(m), x);
    cl_energy e = fd_eval(m, x, v, f);
    sc_case c;
    make_case(&c, "penalty");
    cr_assert_eq(fd_term_energy(&e, "selfcontact"), eval(&c, x, NULL, NULL));
    free_case(&c);
    cl_model_free(m);

    cl_error err = {0};
    /* non-neighbours of a 6 x 6 grid are 3 x 0.2 m apart at rest */
    cr_assert_eq(fd_model_try(FD_SETS("cloth.n=6", "selfcontact.enabled=true",
                                      "selfcontact.thickness=0.61",
                                      "selfcontact.stiffness=40"),
                              &m, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "thickness = 0.61") &&
                  strstr(err.msg, "0.6 m apart"),
              "%s", err.msg);
    cr_assert_eq(fd_model_try(FD_SETS("selfcontact.enabled=true",
                                      "selfcontact.thickness=0.01"),
                              &m, &err),
                 CL_EINVAL);
    cr_assert(strstr(err.msg, "stiffness"), "%s", err.msg);
}

/* The smallest distance between particles of a 10 x 10 grid more than two
 * rows or columns apart, in final.csv of the run into dir. */
static double closest_at_end(const char *dir)
{
    char path[4400];
    double x[300], v[300], best = INFINITY;
    snprintf(path, sizeof path, "%s/final.csv", dir);
    cli_read_state(path, 100, x, v);
    for (int a = 0; a < 100; a++)
        for (int b = a + 1; b < 100; b++)
            if (abs(a / 10 - b / 10) > 2 || abs(a % 10 - b % 10) > 2)
                best = fmin(best, cl_dist(x + 3 * a, x + 3 * b));
    return best;
}

static double fold_run(const char *tmp, const char *on)
{
    char out[4200], set[64];
    cli_result r;
    snprintf(out, sizeof out, "%s/%s", tmp, on);
    snprintf(set, sizeof set, "selfcontact.enabled=%s", on);
    cli_run(&r, "run", "problems/fold.ini", "--out", out, "--format", "csv",
            "--quiet", "--set", "cloth.n=10", "--set",
            "selfcontact.thickness=0.13", "--set", "run.dt=2e-3", "--set",
            set, NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    return closest_at_end(out);
}

Test(selfcontact, fold_scene_keeps_layers_apart)
{
    time_limit(600);
    char tmp[256];
    tmp_mkdtemp(tmp, sizeof tmp, "fold");
    double on = fold_run(tmp, "true"), off = fold_run(tmp, "false");
    fd_report("fold closest, self-contact on", on);
    fd_report("fold closest, self-contact off", off);
    cr_assert_gt(on, 0.5 * 0.13, "self-contact on: closest %g m", on);
    cr_assert_lt(off, 0.5 * 0.13, "self-contact off: closest %g m", off);
    tmp_rm_rf(tmp);
}
