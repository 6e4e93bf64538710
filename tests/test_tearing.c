/* Tearing (docs/model.md 3.4): a connection breaks for good when d > cut L
 * after an accepted step.  A broken pair gives no force, energy or Jacobian
 * values in any pair term (Type1, damping, springs, spring-damping: the spring
 * and its damper break together, counted once); the pulled hang cloth tears
 * under a fixed-step and under adaptive integrators (solver restart at output
 * times) without NaN; torn triangles leave cl_model_triangles and the frames;
 * without [tear] cut nothing breaks.  Baraff-Witkin elements break with any of
 * their edges: a torn triangle or hinge gives nothing, in the potential and the
 * damping terms alike. */
#include <criterion/criterion.h>

#include "io/frames.h"
#include "pbdcheck.h"
#include "runcli.h"

/* A chain of two free particles joined by all four pair terms. */
#define CHAIN_TERMS                                                        \
    "cloth.nu=1", "cloth.nv=2", "pins.at=", "gravity.g=0,0,0",            \
        "type2.enabled=false", "damping.kd=0.01", "springs.enabled=true", \
        "spring-damping.kd=0.01"

Test(tearing, broken_pair_gives_no_force_energy_or_jacobian)
{
    cl_model *m = FD_MODEL(CHAIN_TERMS, "tear.cut=1.5");
    const char *terms[] = {"type1", "damping", "springs", "spring-damping"};
    for (size_t k = 0; k < 4; k++)
        cr_assert(fd_has_term(m, terms[k]), "%s missing", terms[k]);
    const cl_system *sys = cl_model_system(m);
    cr_assert_not_null(sys->step_done);
    size_t nval = 9 * sys->pattern->nnzb;
    double x[6] = {0, 0, 0, 0, 0.1, 2.0}, v[6] = {0.3, 0, 0, 0, 0, -0.2};
    double f[6], *Jx = fd_vec(nval), *Jv = fd_vec(nval);
    cl_energy e;
    /* d = 2 L: stretched, moving apart, not yet torn (cut is tested after
     * steps only) */
    cr_assert_eq(sys->force(sys->data, 0.0, x, v, f), CL_OK);
    cr_assert_gt(fd_maxabs(f, 6), 0.1);
    bool changed = false;
    cr_assert_eq(sys->step_done(sys->data, 0.0, x, v, &changed), CL_OK);
    cr_assert(changed);
    cr_assert_eq(cl_model_broken(m), 1, "one connection, counted once: %zu",
                 cl_model_broken(m));
    cr_assert(cl_model_is_broken(m, 1, 0) && cl_model_is_broken(m, 0, 1));
    cr_assert_eq(sys->force(sys->data, 0.0, x, v, f), CL_OK);
    cr_assert_eq(fd_maxabs(f, 6), 0.0);
    cr_assert_eq(sys->jacobian(sys->data, 0.0, x, v, f, Jx, Jv), CL_OK);
    cr_assert_eq(fd_maxabs(Jx, nval), 0.0);
    cr_assert_eq(fd_maxabs(Jv, nval), 0.0);
    cr_assert_eq(nval, 9 * sys->pattern->nnzb, "the pattern stays");
    cr_assert_eq(sys->energy(sys->data, 0.0, x, v, &e), CL_OK);
    cr_assert_eq(e.potential, 0.0);
    cr_assert_eq(e.power_diss, 0.0);
    /* torn for good: back at rest length it stays torn, nothing new */
    double x0[6] = {0, 0, 0, 0, 0, 1.0};
    cr_assert_eq(sys->step_done(sys->data, 0.0, x0, v, &changed), CL_OK);
    cr_assert(!changed);
    cr_assert_eq(cl_model_broken(m), 1);
    free(Jx);
    free(Jv);
    cl_model_free(m);
}

Test(tearing, intact_pair_below_cut_is_kept)
{
    cl_model *m = FD_MODEL(CHAIN_TERMS, "tear.cut=1.5");
    const cl_system *sys = cl_model_system(m);
    double x[6] = {0, 0, 0, 0, 0, 1.49}, v[6] = {0}, f[6];
    bool changed = true;
    cr_assert_eq(sys->step_done(sys->data, 0.0, x, v, &changed), CL_OK);
    cr_assert(!changed);
    cr_assert_eq(cl_model_broken(m), 0);
    cr_assert_eq(sys->force(sys->data, 0.0, x, v, f), CL_OK);
    cr_assert_gt(fd_maxabs(f, 6), 1.0);
    cl_model_free(m);
}

/* Every kept triangle has three intact edges, every dropped one a torn
 * edge; returns the number kept. */
static size_t check_triangles(const cl_model *m)
{
    const cl_cloth *c = cl_model_cloth(m);
    size_t all = cl_grid_triangles(c->nu, c->nv, NULL), kept = 0, k = 0;
    int(*grid)[3] = malloc(all * sizeof *grid);
    int(*tri)[3] = malloc(all * sizeof *tri);
    cl_error err = {0};
    cr_assert(grid && tri);
    cl_grid_triangles(c->nu, c->nv, grid);
    cr_assert_eq(cl_model_triangles(m, tri, &kept, &err), CL_OK);
    for (size_t t = 0; t < all; t++) {
        const int *g = grid[t];
        bool torn = cl_model_is_broken(m, g[0], g[1]) ||
                    cl_model_is_broken(m, g[1], g[2]) ||
                    cl_model_is_broken(m, g[2], g[0]);
        bool listed = k < kept && !memcmp(tri[k], g, sizeof *g * 3);
        cr_assert_eq(listed, !torn, "triangle %zu: torn %d, listed %d", t,
                     torn, listed);
        k += listed;
    }
    cr_assert_eq(k, kept);
    free(grid);
    free(tri);
    return kept;
}

Test(tearing, pulled_cloth_tears_under_symplectic_euler)
{
    pb_case c = pb_open(FD_MODEL(PB_PULL, "damping.kd=1e-3", "tear.cut=1.5"));
    cl_integrator_opts o = {.dt = 1e-4};
    pb_integrate(&c, "symplectic-euler", &o, 0.5, 10, NULL, NULL);
    size_t broken = cl_model_broken(c.m), kept = check_triangles(c.m);
    cr_log_info("symplectic-euler: %zu connections torn, %zu of 98 "
                "triangles kept", broken, kept);
    /* the pull tears the same 19 connections under every method here */
    cr_assert_eq(broken, 19);
    cr_assert_eq(kept, 83);
    pb_close(&c);
}

Test(tearing, without_cut_nothing_breaks)
{
    pb_case c = pb_open(FD_MODEL(PB_PULL, "damping.kd=1e-3"));
    cr_assert_null(c.sys->step_done, "no tearing hook without [tear] cut");
    cl_integrator_opts o = {.dt = 1e-4};
    pb_integrate(&c, "symplectic-euler", &o, 0.5, 10, NULL, NULL);
    cr_assert_eq(cl_model_broken(c.m), 0);
    cr_assert_eq(check_triangles(c.m), 98);
    pb_close(&c);
}

/* Adaptive methods see the tear at output times and restart there; they
 * tear what symplectic Euler tears. */
static void adaptive_run(const char *name)
{
    pb_case c = pb_open(FD_MODEL(PB_PULL, "damping.kd=1e-3", "tear.cut=1.5"));
    cl_integrator_opts o = {.rtol = 1e-4, .atol = 1e-6};
    pb_integrate(&c, name, &o, 0.5, 100, NULL, NULL);
    size_t broken = cl_model_broken(c.m);
    cr_log_info("%s: %zu connections torn, %ld steps", name, broken,
                c.st.steps);
    cr_assert_eq(broken, 19, "%s", name);
    cr_assert_eq(check_triangles(c.m), 83, "%s", name);
    pb_close(&c);
}

Test(tearing, cvode_bdf_continues_after_tearing)
{
    adaptive_run("cvode-bdf");
}

Test(tearing, ida_continues_after_tearing)
{
    adaptive_run("ida");
}

Test(tearing, frames_and_series_of_a_tearing_run)
{
    char dir[256], out[320], path[400];
    tmp_mkdtemp(dir, sizeof dir, "tear");
    snprintf(out, sizeof out, "%s/run", dir);
    cli_result r;
    cli_run(&r, "run", "verlet-scene3", "--t-end", "2.0", "--frames", "1",
            "--format", "obj", "--out", out, "--quiet", NULL);
    cli_assert_ok(&r);
    cli_result_free(&r);
    cli_lines L;
    snprintf(path, sizeof path, "%s/series.csv", out);
    cli_read_lines(path, &L);
    /* the column `broken` (contact columns follow it: scene 3 has its
     * sphere) */
    const char *h = L.line[0], *at = strstr(h, ",broken,");
    cr_assert_not_null(at, "columns: %s", h);
    int col = 0;
    for (const char *c = h; c <= at; c++)
        col += *c == ',';
    const char *last = L.line[L.n - 1];
    for (int k = 0; k < col && last; k++)
        last = strchr(last, ',') ? strchr(last, ',') + 1 : NULL;
    cr_assert_not_null(last);
    long broken = strtol(last, NULL, 10);
    cr_assert_gt(broken, 0, "series: %s", L.line[L.n - 1]);
    cli_lines_free(&L);
    snprintf(path, sizeof path, "%s/frame_00001.obj", out);
    cli_read_lines(path, &L);
    size_t faces = 0;
    for (size_t k = 0; k < L.n; k++)
        faces += L.line[k][0] == 'f';
    cr_assert_lt(faces, 2 * 29 * 29, "%zu faces", faces);
    cr_assert_gt(faces, 2 * 29 * 29 - 100, "%zu faces", faces);
    cli_lines_free(&L);
    tmp_rm_rf(dir);
}

/* The Baraff-Witkin terms (stretch, shear, bend and their damping) on one
 * quad a = (0,0,0), b = (1,0,0), c = (1,0,1), d = (0,0,1): triangles
 * (a,b,c), (a,c,d) and the hinge across a-c. */
#define BW_QUAD                                                             \
    "cloth.n=2", "pins.at=", "gravity.g=0,0,0", "type1.enabled=false",     \
        "type2.enabled=false", "damping.kd=0", "bw-stretch.enabled=true",  \
        "bw-stretch.k=100", "bw-stretch.kd=1", "bw-shear.enabled=true",    \
        "bw-shear.k=10", "bw-shear.kd=1", "bw-bend.enabled=true",          \
        "bw-bend.k=1", "bw-bend.kd=0.1", "tear.cut=1.5"

/* The particle at rest position (X, 0, Z). */
static int quad_particle(const cl_model *m, double X, double Z)
{
    const cl_cloth *c = cl_model_cloth(m);
    for (size_t p = 0; p < c->np; p++)
        if (c->X0[3 * p] == X && c->X0[3 * p + 2] == Z)
            return (int)p;
    cr_assert_fail("no particle at (%g, 0, %g)", X, Z);
    return -1;
}

Test(tearing, baraff_witkin_elements_break_with_an_edge)
{
    cl_model *m = FD_MODEL(BW_QUAD);
    const cl_system *sys = cl_model_system(m);
    cr_assert_not_null(sys->step_done);
    int b = quad_particle(m, 1, 0), d = quad_particle(m, 0, 1);
    size_t n = sys->n;
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    cr_assert_eq(cl_model_initial_state(m, x, v), CL_OK);
    x[3 * b] = 1.6;      /* |ab| = 1.6 L > 1.5 L, |bc| = 1.17 L */
    x[3 * d + 1] = 0.3;  /* folds the hinge, stretches (a,c,d) */
    v[3 * b + 1] = 0.5;
    v[3 * d] = -0.2;
    cr_assert_eq(sys->force(sys->data, 0.0, x, v, f), CL_OK);
    cr_assert_gt(fd_maxabs(f + 3 * b, 3), 1.0, "intact: b pulled back");
    bool changed = false;
    cr_assert_eq(sys->step_done(sys->data, 0.0, x, v, &changed), CL_OK);
    cr_assert(changed);
    cr_assert_eq(cl_model_broken(m), 1, "a-b only, merged over the six "
                 "terms: %zu", cl_model_broken(m));
    cr_assert(cl_model_is_broken(m, quad_particle(m, 0, 0), b));
    /* b belongs only to the torn triangle and hinge: no force on it; the
     * intact triangle (a,c,d) still acts on d */
    cr_assert_eq(sys->force(sys->data, 0.0, x, v, f), CL_OK);
    cr_assert_eq(fd_maxabs(f + 3 * b, 3), 0.0);
    cr_assert_gt(fd_maxabs(f + 3 * d, 3), 0.1);
    cl_energy e;
    cr_assert_eq(sys->energy(sys->data, 0.0, x, v, &e), CL_OK);
    for (size_t k = 0; k < e.nterm; k++)
        if (!strcmp(e.name[k], "bw-bend"))
            cr_assert_eq(e.value[k], 0.0, "the hinge is torn");
    size_t kept = check_triangles(m);
    cr_assert_eq(kept, 1);
    /* for good: back at rest nothing comes back or breaks anew */
    cr_assert_eq(cl_model_initial_state(m, x, v), CL_OK);
    cr_assert_eq(sys->step_done(sys->data, 0.0, x, v, &changed), CL_OK);
    cr_assert(!changed);
    cr_assert_eq(cl_model_broken(m), 1);
    free(x);
    free(v);
    free(f);
    cl_model_free(m);
}

/* The pulled cloth of the pair-term tests, as a Baraff-Witkin cloth under
 * cvode-bdf. */
Test(tearing, pulled_baraff_witkin_cloth_tears)
{
    pb_case c = pb_open(FD_MODEL(PB_PULL, "type1.enabled=false",
                                 "type2.enabled=false", "damping.kd=0",
                                 "bw-stretch.enabled=true", "bw-stretch.k=2e4",
                                 "bw-stretch.kd=2", "bw-shear.enabled=true",
                                 "bw-shear.k=2e3", "bw-bend.enabled=true",
                                 "bw-bend.k=5e-5", "tear.cut=1.5"));
    cl_integrator_opts o = {.rtol = 1e-4, .atol = 1e-6};
    pb_integrate(&c, "cvode-bdf", &o, 0.5, 100, NULL, NULL);
    size_t broken = cl_model_broken(c.m), kept = check_triangles(c.m);
    cr_log_info("baraff-witkin: %zu connections torn, %zu of 98 triangles "
                "kept, %ld steps", broken, kept, c.st.steps);
    cr_assert_eq(broken, 3);
    cr_assert_eq(kept, 95);
    pb_close(&c);
}

/* A fixed-step method tears after every step (system/system.h): the same
 * connections and state, bit for bit, whatever the output times, here
 * one advance against ten (the pulled cloth at cut = 1.02, 400 steps of
 * 1e-4 s), for every method that takes fixed steps at that dt (the
 * petsc-* ones included).  Before, arkode-*-fixed and petsc-* looked for
 * tears at output times only: 28 connections torn with one output, 10
 * with ten. */
static size_t fixed_run(const cl_integrator_type *it, int nout, double **x,
                        double **v)
{
    pb_case c = pb_open(FD_MODEL(PB_PULL, "damping.kd=1e-3", "tear.cut=1.02"));
    cl_integrator_opts o = {.dt = 1e-4, .rtol = 1e-6, .atol = 1e-8};
    void *st = NULL;
    cl_error err = {0};
    size_t broken = SIZE_MAX; /* a method that refuses the model */
    if (it->create(c.sys, &o, 0.0, c.x, c.v, &st, &err) == CL_OK) {
        for (int k = 1; k <= nout; k++)
            cr_assert_eq(it->advance(st, 0.04 * k / nout, c.x, c.v, &err),
                         CL_OK, "%s: %s", it->name, err.msg);
        broken = cl_model_broken(c.m);
        it->free(st);
    } else {
        cr_log_info("%-18s refuses the model: %s", it->name, err.msg);
    }
    *x = c.x; /* the caller's to free */
    *v = c.v;
    cl_model_free(c.m);
    return broken;
}

Test(tearing, fixed_steps_tear_whatever_the_outputs)
{
    int checked = 0;
    for (size_t k = 0; cl_integrator_registry[k]; k++) {
        const cl_integrator_type *it = cl_integrator_registry[k];
        if (!cl_integrator_fixed(it, 1e-4))
            continue;
        double *x1, *v1, *x10, *v10;
        size_t one = fixed_run(it, 1, &x1, &v1);
        size_t ten = fixed_run(it, 10, &x10, &v10);
        size_t bytes = 186 * sizeof(double); /* 62 free particles */
        if (one != SIZE_MAX) {
            cr_log_info("%-18s %zu connections torn", it->name, one);
            cr_expect_gt(one, 0, "%s", it->name);
            cr_expect_eq(one, ten, "%s: %zu torn with one output, %zu with "
                         "ten", it->name, one, ten);
            cr_expect(!memcmp(x1, x10, bytes) && !memcmp(v1, v10, bytes),
                      "%s: the state depends on the outputs", it->name);
            checked++;
        }
        free(x1);
        free(v1);
        free(x10);
        free(v10);
    }
    cr_assert_geq(checked, 15);
}
