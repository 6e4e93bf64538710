/* The scipy peer of the benchmarks (scripts/peers/hang_scipy.py, a numpy
 * implementation of hang written from the formulas of docs/model.md 3.1-3.2,
 * not from the C code) against `clothode eval`: total forces on every particle
 * of hang at n = 6 agree to 1e-10 of the largest force, at the rest state and
 * at random perturbations (many interlaced pairs compressed onto the buckling
 * branch), without and with velocities (pair damping).  Both programs run as
 * child processes.
 *
 * The peer needs a Python with numpy and scipy (`make test` installs
 * Debian's python3-numpy python3-scipy; bench/child.h says which
 * interpreter is used).  Without one these tests fail, naming what is
 * missing. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench/child.h"
#include "io/config.h"
#include "io/state.h"
#include "system/model.h"
#include "runcli.h"
#include "timelimit.h"

#define N 6
#define NP (N * N)
#define PEER "scripts/peers/hang_scipy.py"

static char tmp[512];

static void setup(void)
{
    time_limit(300);
    tmp_mkdtemp(tmp, sizeof tmp, "peer");
}

static void teardown(void)
{
    tmp_rm_rf(tmp);
}

TestSuite(peer, .init = setup, .fini = teardown);

static const char *in_tmp(char *buf, const char *name)
{
    snprintf(buf, 1024, "%s/%s", tmp, name);
    return buf;
}

/* hang at n = 6, as clothode builds it; the configuration in *cfg. */
static cl_model *hang6(cl_config **cfg)
{
    const char *dir = getenv("CLOTHODE_PROBLEMS");
    char path[1024];
    snprintf(path, sizeof path, "%s/hang.ini", dir && *dir ? dir : "problems");
    cl_error err = {0};
    cl_model *m = NULL;
    *cfg = cl_config_alloc();
    cr_assert_not_null(*cfg);
    cl_status rc = cl_config_load(*cfg, path, &err);
    if (!rc)
        rc = cl_config_set(*cfg, "cloth.n=6", &err);
    if (!rc)
        rc = cl_model_create(*cfg, &m, &err);
    cr_assert_eq(rc, CL_OK, "%s: %s", path, err.msg);
    return m;
}

/* Deterministic numbers in [-1, 1). */
static double uniform(unsigned long long *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return 2.0 * ((double)(*s >> 11) / 9007199254740992.0) - 1.0;
}

/* Rest positions of the free particles moved by up to `dx` spacings per
 * coordinate, velocities up to `dv` m/s; pinned particles at rest. */
static void make_state(const cl_cloth *c, double dx, double dv,
                       unsigned long long seed, double *x, double *v)
{
    for (size_t p = 0; p < c->np; p++)
        for (int d = 0; d < 3; d++) {
            double ux = uniform(&seed), uv = uniform(&seed);
            bool pinned = c->dof[p] < 0;
            x[3 * p + d] = c->X0[3 * p + d] + (pinned ? 0 : dx * c->hu * ux);
            v[3 * p + d] = pinned ? 0 : dv * uv;
        }
}

/* Interlaced axis pairs (i,j)-(i+2,j) compressed by more than 1 %: the
 * buckling branch, f_b = kb kappa^2/(cos - sinc), acts on them. */
static int buckled_pairs(const double *x)
{
    int count = 0;
    for (int i = 0; i + 2 < N; i++)
        for (int j = 0; j < N; j++) {
            const double *a = x + 3 * (i * N + j), *b = a + 3 * 2 * N;
            double d = sqrt((b[0] - a[0]) * (b[0] - a[0]) +
                            (b[1] - a[1]) * (b[1] - a[1]) +
                            (b[2] - a[2]) * (b[2] - a[2]));
            count += d < 0.99 * 0.4; /* rest length 2 h, h = 1/5 m */
        }
    return count;
}

static void eval_forces(const char *state, double *f)
{
    char out[1024], path[1100];
    cli_result r;
    cli_run(&r, "eval", "hang", "--set", "cloth.n=6", "--state", state,
            "--out", in_tmp(out, "eval"), NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    snprintf(path, sizeof path, "%s/forces.csv", out);
    cli_read_forces(path, NP, f);
}

static void peer_forces(const char *state, double *f)
{
    char python[512], problem[1024], out[1024];
    cl_error err = {0};
    cr_assert_eq(cl_child_python(python, sizeof python, &err), CL_OK,
                 "the scipy peer cannot run: %s", err.msg);
    const char *dir = getenv("CLOTHODE_PROBLEMS");
    snprintf(problem, sizeof problem, "%s/hang.ini",
             dir && *dir ? dir : "problems");
    char *argv[] = {python, PEER, problem, "--set", "cloth.n=6",
                    "--forces", (char *)state, "--out",
                    (char *)in_tmp(out, "peer.csv"), NULL};
    cli_result r;
    cli_spawn(&r, argv);
    cli_assert_no_crash(&r);
    cr_assert_eq(r.status, 0, "%s: exit status %d\n%s", r.cmd, r.status,
                 r.err);
    cli_result_free(&r);
    cli_read_forces(out, NP, f);
}

/* Both programs at the state (x, v): forces equal to 1e-10 of the largest
 * per-particle force. */
static void compare_at(const double *x, const double *v, const char *what)
{
    char state[1024];
    cl_error err = {0};
    cr_assert_eq(cl_state_write(in_tmp(state, "state.csv"), NP, x, v, &err),
                 CL_OK, "%s", err.msg);
    double fe[3 * NP], fp[3 * NP], scale = 0, worst = 0;
    eval_forces(state, fe);
    peer_forces(state, fp);
    size_t at = 0;
    for (size_t p = 0; p < NP; p++) {
        double d2 = 0, n2 = 0;
        for (int k = 0; k < 3; k++) {
            double e = fe[3 * p + k] - fp[3 * p + k];
            d2 += e * e;
            n2 += fe[3 * p + k] * fe[3 * p + k];
        }
        scale = fmax(scale, sqrt(n2));
        if (sqrt(d2) > worst) {
            worst = sqrt(d2);
            at = p;
        }
    }
    cr_assert_gt(scale, 0.0, "%s: no force at all", what);
    cr_assert(worst <= 1e-10 * scale,
              "%s: forces differ by %.3g N at particle %zu (largest force "
              "%.3g N): eval (%.17g, %.17g, %.17g), peer (%.17g, %.17g, "
              "%.17g)", what, worst, at, scale, fe[3 * at], fe[3 * at + 1],
              fe[3 * at + 2], fp[3 * at], fp[3 * at + 1], fp[3 * at + 2]);
}

/* The state of the given size and seed, checked at both programs. */
static void check(double dx, double dv, unsigned long long seed,
                  const char *what, bool buckled)
{
    cl_config *cfg;
    cl_model *m = hang6(&cfg);
    const cl_cloth *c = cl_model_cloth(m);
    cr_assert_eq(c->np, NP);
    double x[3 * NP], v[3 * NP];
    make_state(c, dx, dv, seed, x, v);
    if (buckled)
        cr_assert_gt(buckled_pairs(x), 0, "%s: no interlaced pair is "
                     "compressed onto the buckling branch", what);
    compare_at(x, v, what);
    cl_model_free(m);
    cl_config_free(cfg);
}

Test(peer, rest_state_gravity_only)
{
    check(0.0, 0.0, 1, "rest state", false);
}

Test(peer, rest_state_with_velocities_damping)
{
    check(0.0, 0.5, 2, "rest positions, random velocities", false);
}

Test(peer, perturbed_without_velocities)
{
    check(0.1, 0.0, 3, "perturbed by 0.1 h", true);
    check(0.3, 0.0, 4, "perturbed by 0.3 h", true);
}

Test(peer, perturbed_with_velocities)
{
    check(0.1, 0.5, 5, "perturbed by 0.1 h, random velocities", true);
    check(0.3, 0.5, 6, "perturbed by 0.3 h, random velocities", true);
}
