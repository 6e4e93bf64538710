/* The Baraff-Witkin term machinery (forces/bw.c; docs/model.md 3.3): switches
 * and defaults (off unless enabled, every key read even when off), errors
 * (chains, bad values), triangles of zero rest area, couplings, pinned
 * particles in the system Jacobian, and the energy / power bookkeeping of the
 * six terms together. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bwcheck.h"

static const char *const bw_terms[] = {
    "bw-stretch", "bw-stretch-damping", "bw-shear",
    "bw-shear-damping", "bw-bend", "bw-bend-damping"};

#define NTERMS (sizeof bw_terms / sizeof *bw_terms)

Test(bw, off_by_default)
{
    cl_model *m = FD_MODEL("cloth.n=4");
    for (size_t k = 0; k < NTERMS; k++)
        cr_assert(!fd_has_term(m, bw_terms[k]), "%s is on", bw_terms[k]);
    cl_model_free(m);
    /* Keys of a switched-off term are still read (no "unused key"). */
    m = FD_MODEL("cloth.n=4", "cloth.diagonal=alternate", "bw-stretch.k=5",
                 "bw-stretch.kdv=2", "bw-stretch.bu=0.9", "bw-shear.kd=1",
                 "bw-bend.k=1e-3");
    for (size_t k = 0; k < NTERMS; k++)
        cr_assert(!fd_has_term(m, bw_terms[k]));
    cl_model_free(m);
}

/* Enabled: the potential part needs k > 0, the damping part kd > 0. */
Test(bw, parts_switch_on_their_coefficients)
{
    cl_model *m = BW_ONLY("cloth.n=3", "bw-stretch.enabled=true",
                          "bw-shear.enabled=true", "bw-bend.enabled=true");
    cr_assert(fd_has_term(m, "bw-stretch") && fd_has_term(m, "bw-shear") &&
              fd_has_term(m, "bw-bend"));
    cr_assert(!fd_has_term(m, "bw-stretch-damping") &&
              !fd_has_term(m, "bw-shear-damping") &&
              !fd_has_term(m, "bw-bend-damping"));
    cl_model_free(m);
    m = BW_ONLY("cloth.n=3", "bw-stretch.enabled=true", "bw-stretch.k=0",
                "bw-stretch.kdu=1", "bw-bend.enabled=true", "bw-bend.k=0");
    cr_assert(!fd_has_term(m, "bw-stretch"));
    cr_assert(fd_has_term(m, "bw-stretch-damping"));
    cr_assert(!fd_has_term(m, "bw-bend") &&
              !fd_has_term(m, "bw-bend-damping"));
    cl_model_free(m);
}

static void expect_error(const char *const *sets, const char *const *words)
{
    cl_model *m = NULL;
    cl_error err;
    memset(&err, 0, sizeof err);
    cl_status rc = fd_model_try(sets, &m, &err);
    cr_assert_eq(rc, CL_EINVAL, "expected CL_EINVAL, got %d (%s)", rc,
                 err.msg);
    cr_assert_null(m);
    for (size_t k = 0; words[k]; k++)
        cr_assert(strstr(err.msg, words[k]), "message lacks \"%s\": %s",
                  words[k], err.msg);
}

Test(bw, chain_is_an_error)
{
    expect_error(FD_SETS("cloth.nu=1", "cloth.nv=5", "pins.at=0,0",
                         "type2.enabled=false", "bw-shear.enabled=true"),
                 FD_SETS("[bw-shear]", "2 x 2", "1 x 5", "chain"));
    expect_error(FD_SETS("cloth.nu=6", "cloth.nv=1", "pins.at=0,0",
                         "type2.enabled=false", "bw-bend.enabled=true"),
                 FD_SETS("[bw-bend]", "6 x 1"));
}

Test(bw, bad_values_are_errors)
{
    expect_error(FD_SETS("cloth.n=3", "bw-stretch.enabled=true",
                         "bw-stretch.k=-1"),
                 FD_SETS("bw-stretch", "k"));
    expect_error(FD_SETS("cloth.n=3", "bw-stretch.enabled=true",
                         "bw-stretch.bv=0"),
                 FD_SETS("bw-stretch", "bv"));
    expect_error(FD_SETS("cloth.n=3", "bw-bend.kd=abc"),
                 FD_SETS("bw-bend", "kd"));
    expect_error(FD_SETS("cloth.n=3", "cloth.diagonal=zigzag"),
                 FD_SETS("diagonal", "alternate"));
}

Test(bw, zero_area_triangles_are_skipped)
{
    /* Three particles on a line in the rest (u, v) plane. */
    const double X0[9] = {0, 0, 0, 1, 0, 0.5, 2, 0, 1};
    const int line[3] = {0, 1, 2}, tri[3] = {0, 1, 2};
    double rest[CL_BW_TRI_REST];
    cr_assert(!cl_bw_tri_rest(X0, line, rest));
    const double Y0[9] = {0, 0, 0, 0.5, 0, 0, 0.2, 0, 0.4};
    cr_assert(cl_bw_tri_rest(Y0, tri, rest));
    cr_assert(fabs(rest[CL_BW_AREA] - 0.1) <= 1e-16);
    /* w_u, w_v of the rest triangle are the unit axes exactly. */
    double wu[3], wv[3];
    cl_bw_tri_w(rest, Y0, wu, wv);
    cr_assert(wu[0] == 1.0 && wu[1] == 0.0 && wu[2] == 0.0);
    cr_assert(wv[0] == 0.0 && wv[1] == 0.0 && wv[2] == 1.0);
}

/* Couplings: the 3 vertex pairs of every triangle, the 6 of every hinge. */
Test(bw, couplings)
{
    static const struct {
        const cl_term_type *type;
        const char *set;
        size_t per;
    } cases[] = {{&cl_term_bw_stretch, "bw-stretch.enabled=true", 3},
                 {&cl_term_bw_shear_damping, "bw-shear.kd=1", 3},
                 {&cl_term_bw_bend, "bw-bend.enabled=true", 6}};
    cl_cloth cloth;
    cl_error err;
    cl_term_opts opts = {0};
    cr_assert_eq(cl_cloth_grid(5, 4, 1.0, 1.0, 1.0, &cloth, &err), CL_OK);
    for (size_t k = 0; k < 3; k++) {
        cl_config *cfg = cl_config_alloc();
        cr_assert_eq(cl_config_set(cfg, cases[k].set, &err), CL_OK);
        if (k == 1)
            cr_assert_eq(cl_config_set(cfg, "bw-shear.enabled=true", &err),
                         CL_OK);
        void *st = NULL;
        cr_assert_eq(cases[k].type->create(cfg, &cloth, &opts, &st, &err),
                     CL_OK, "%s", err.msg);
        cr_assert_not_null(st);
        const int(*pairs)[2];
        size_t n = cases[k].type->couplings(st, &pairs);
        size_t elems = cases[k].per == 3 ? 2 * 4 * 3 : 4 * 3 * 3 - 4 - 3;
        cr_assert_eq(n, cases[k].per * elems, "%zu couplings", n);
        for (size_t p = 0; p < n; p++)
            cr_assert(pairs[p][0] != pairs[p][1] && pairs[p][0] >= 0 &&
                      pairs[p][1] < 20);
        cases[k].type->free(st);
        cl_config_free(cfg);
    }
    cl_cloth_free(&cloth);
}

#define ALL_BW(...)                                                         \
    BW_ONLY("bw-stretch.enabled=true", "bw-stretch.ku=3e5",                 \
            "bw-stretch.kv=2e5", "bw-stretch.kd=20", "bw-shear.enabled=true", \
            "bw-shear.k=1e5", "bw-shear.kd=10", "bw-bend.enabled=true",     \
            "bw-bend.k=2e-3", "bw-bend.kd=1e-3", __VA_ARGS__)

/* With pins, the system (free particles) sees the rows and columns of the
 * full Jacobian that belong to free particles, and the same forces. */
Test(bw, pinned_particles)
{
    cl_model *m = ALL_BW("cloth.n=4", "pins.at=0,0 0,-1 2,1");
    const cl_cloth *c = cl_model_cloth(m);
    const cl_system *sys = cl_model_system(m);
    size_t n = fd_n(m), nf = 3 * c->nfree;
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n), *Jx = fd_vec(n * n),
           *Jv = fd_vec(n * n), *xf = fd_vec(nf), *vf = fd_vec(nf),
           *ff = fd_vec(nf), *bx = fd_vec(9 * sys->pattern->nnzb),
           *bv = fd_vec(9 * sys->pattern->nnzb);
    fd_rng r = {401};
    fd_deform(m, NULL, 0.1, 0.3, &r, x);
    fd_random_vec(&r, 1.0, v, n);
    for (size_t k = 0; k < c->npin; k++) /* fixed pins: at rest */
        for (int i = 0; i < 3; i++) {
            size_t p = (size_t)c->pins[k].p;
            x[3 * p + i] = c->X0[3 * p + i];
            v[3 * p + i] = 0.0;
        }
    fd_eval(m, x, v, f);
    fd_jacobian(m, x, v, Jx, Jv);
    cl_cloth_gather(c, x, xf);
    cl_cloth_gather(c, v, vf);
    cr_assert_eq(sys->jacobian(sys->data, 0.0, xf, vf, ff, bx, bv), CL_OK);
    const cl_bpattern *pat = sys->pattern;
    double dev = 0.0, scale = fmax(fd_maxabs(Jx, n * n), fd_maxabs(Jv, n * n));
    for (size_t bi = 0; bi < pat->nb; bi++) {
        size_t pi = (size_t)c->free_p[bi];
        for (int i = 0; i < 3; i++)
            dev = fmax(dev, fabs(ff[3 * bi + i] - f[3 * pi + i]) /
                                fd_maxabs(f, n));
        for (size_t k = pat->rowptr[bi]; k < pat->rowptr[bi + 1]; k++) {
            size_t pj = (size_t)c->free_p[pat->col[k]];
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    size_t rc = (3 * pi + a) * n + 3 * pj + b;
                    dev = fmax(dev, fabs(bx[9 * k + 3 * a + b] - Jx[rc]) /
                                        scale);
                    dev = fmax(dev, fabs(bv[9 * k + 3 * a + b] - Jv[rc]) /
                                        scale);
                }
        }
    }
    cr_assert_lt(dev, 1e-14, "system vs full Jacobian / force: %g", dev);
    free(x);
    free(v);
    free(f);
    free(Jx);
    free(Jv);
    free(xf);
    free(vf);
    free(ff);
    free(bx);
    free(bv);
    cl_model_free(m);
}

/* The three potentials are energy columns of their own; the three damping
 * powers add up in power_diss; nothing else mixes. */
Test(bw, energy_and_power_bookkeeping)
{
    cl_model *all = ALL_BW("cloth.n=4");
    size_t n = fd_n(all);
    double *x = fd_vec(n), *v = fd_vec(n), *f = fd_vec(n);
    fd_rng r = {402};
    fd_deform(all, NULL, 0.1, 0.3, &r, x);
    fd_random_vec(&r, 1.0, v, n);
    cl_energy e = fd_eval(all, x, v, f);
    cr_assert_eq(e.nterm, 3);
    double pot = 0.0;
    for (size_t k = 0; k < 3; k++)
        pot += fd_term_energy(&e, bw_terms[2 * k]);
    cr_assert(fabs(pot - e.potential) <= 1e-15 * pot);
    double power = 0.0;
    for (size_t k = 0; k < 3; k++) {
        /* one damping part at a time: every potential off, two kd zero */
        const char *zero[3] = {"bw-stretch.kd=0", "bw-shear.kd=0",
                               "bw-bend.kd=0"};
        const char *keep[3] = {"bw-stretch.kd=20", "bw-shear.kd=10",
                               "bw-bend.kd=1e-3"};
        zero[k] = keep[k];
        cl_model *m = ALL_BW("cloth.n=4", "bw-stretch.ku=0",
                             "bw-stretch.kv=0", "bw-shear.k=0", "bw-bend.k=0",
                             zero[0], zero[1], zero[2]);
        cr_assert(fd_has_term(m, bw_terms[2 * k + 1]));
        cl_energy d = fd_eval(m, x, v, f);
        cr_assert_eq(d.nterm, 0);
        cr_assert_lt(d.power_diss, 0.0);
        power += d.power_diss;
        cl_model_free(m);
    }
    cr_assert(fabs(power - e.power_diss) <= 1e-13 * fabs(power),
              "%.17g vs %.17g", e.power_diss, power);
    free(x);
    free(v);
    free(f);
    cl_model_free(all);
}

/* problems/bw-hang.ini: every key known, the six Baraff-Witkin terms and
 * gravity on, the Choi-Ko terms off; at rest only gravity acts. */
Test(bw, bw_hang_problem)
{
    cl_config *cfg = cl_config_alloc();
    cl_model *m = NULL;
    cl_error err;
    cr_assert_eq(cl_config_load(cfg, "problems/bw-hang.ini", &err), CL_OK,
                 "%s", err.msg);
    cl_config_ignore_section(cfg, "run");
    cr_assert_eq(cl_model_create(cfg, &m, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_config_check_unused(cfg, &err), CL_OK, "%s", err.msg);
    for (size_t k = 0; k < NTERMS; k++)
        cr_assert(fd_has_term(m, bw_terms[k]), "%s is off", bw_terms[k]);
    cr_assert(fd_has_term(m, "gravity"));
    cr_assert(!fd_has_term(m, "type1") && !fd_has_term(m, "type2") &&
              !fd_has_term(m, "damping"));
    const cl_cloth *c = cl_model_cloth(m);
    size_t n = fd_n(m);
    double *v = fd_vec(n), *f = fd_vec(n);
    fd_eval(m, c->X0, v, f);
    for (size_t p = 0; p < c->np; p++)
        cr_assert(f[3 * p] == 0.0 && f[3 * p + 2] == 0.0 &&
                  fabs(f[3 * p + 1] + 9.81 * c->mass[p]) <= 1e-15);
    free(v);
    free(f);
    cl_model_free(m);
    cl_config_free(cfg);
}
