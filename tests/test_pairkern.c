/* The pair kernels (forces/pairkern.h): the vectorised, run-time dispatched
 * force and Jacobian paths of the pair terms against the scalar ones, on a
 * buckled state (positions moved by up to 5 % of a spacing, as in
 * clothode-bench's workload 4: a third of the Type2 pairs on the f_b
 * branch).  The scalar forces are those of the energy path (the law pair
 * by pair); the scalar Jacobian is assembled here from the scalar law and
 * cl_pair_block (central pairs), or by the pair damping's own scalar loop.
 * Agreement to 1e-13 relative to the largest entry (Type2's f_b comes
 * from Chebyshev pieces of t^2/D(t), forces/type2.c, within a few ulp of
 * the scalar law). */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fdcheck.h"
#include "forces/body.h"
#include "forces/choiko.h"
#include "forces/pairdamp.h"
#include "forces/springs.h"

typedef struct {
    cl_config *cfg;
    cl_model *m;
    void *state;
    const cl_term_type *type;
    cl_bpattern pat;
    int *dof;
    size_t n3, nv;
    double *x, *v;
} kcase;

/* One term of the model `sets` (no pins), bound to a full pattern, at a
 * buckled state. */
static void kcase_open(kcase *c, const cl_term_type *type,
                       const char *const *sets)
{
    cl_error err = {0};
    memset(c, 0, sizeof *c);
    c->cfg = cl_config_alloc();
    for (size_t k = 0; sets[k]; k++)
        cr_assert_eq(cl_config_set(c->cfg, sets[k], &err), CL_OK);
    cr_assert_eq(cl_model_create(c->cfg, &c->m, &err), CL_OK, "%s", err.msg);
    const cl_cloth *cloth = cl_model_cloth(c->m);
    cl_term_opts opts = {0};
    c->type = type;
    cr_assert_eq(type->create(c->cfg, cloth, &opts, &c->state, &err), CL_OK);
    cr_assert_not_null(c->state);
    const int(*pairs)[2];
    size_t np = cloth->np, npair = type->couplings(c->state, &pairs);
    c->dof = malloc(np * sizeof *c->dof);
    for (size_t p = 0; p < np; p++)
        c->dof[p] = (int)p;
    cr_assert_eq(cl_bpattern_build(np, c->dof, np, npair, pairs, &c->pat,
                                   &err), CL_OK);
    cr_assert_eq(type->bind(c->state, &c->pat, c->dof, &err), CL_OK);
    c->n3 = 3 * np;
    c->nv = 9 * c->pat.nnzb;
    c->x = fd_vec(c->n3);
    c->v = fd_vec(c->n3);
    fd_rng r = {2024};
    for (size_t k = 0; k < c->n3; k++) {
        c->x[k] = cloth->X0[k] + 0.05 * cloth->hu * fd_rand(&r);
        c->v[k] = 0.1 * fd_rand(&r);
    }
}

static void kcase_close(kcase *c)
{
    void *arr[] = {c->dof, c->x, c->v};
    c->type->free(c->state);
    cl_bpattern_free(&c->pat);
    cl_model_free(c->m);
    cl_config_free(c->cfg);
    for (size_t i = 0; i < sizeof arr / sizeof *arr; i++)
        free(arr[i]);
}

static double max_abs(const double *a, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(a[i]));
    return m;
}

static void assert_close(const double *a, const double *b, size_t n,
                         const char *what)
{
    double big = max_abs(b, n), worst = 0.0;
    cr_assert_gt(big, 0.0, "%s: all zero", what);
    for (size_t i = 0; i < n; i++)
        worst = fmax(worst, fabs(a[i] - b[i]));
    cr_assert_leq(worst, 1e-13 * big, "%s: %.3g of %.3g", what, worst, big);
}

/* Scalar Jacobian of a central pair term: law, cl_pair_block, blocks. */
static void central_scalar(const cl_pairterm *pt, const double *x,
                           double *vals)
{
    for (size_t k = 0; k < pt->set.n; k++) {
        const cl_pair *pr = &pt->set.pair[k];
        const double *xa = x + 3 * pr->a, *xb = x + 3 * pr->b;
        double d = cl_dist(xa, xb), K[9], u[3];
        cl_pairlaw law;
        pt->law(pt->params, k, d, pr->rest, false, true, &law);
        for (int i = 0; i < 3; i++)
            u[i] = (xb[i] - xa[i]) / d;
        cl_pair_block(u, d, law.s, law.ds, pt->clamp_transverse, K);
        const long *s = pt->slot + 4 * k;
        cl_block_add(vals, s[0], -1.0, K);
        cl_block_add(vals, s[1], -1.0, K);
        cl_block_add(vals, s[2], 1.0, K);
        cl_block_add(vals, s[3], 1.0, K);
    }
}

/* Kernel forces and Jacobian against the scalar ones; central: the term
 * is a cl_pairterm (else pair damping, whose energy path is scalar). */
static void compare_paths(const cl_term_type *type, bool central,
                          const char *const *sets)
{
    kcase c;
    kcase_open(&c, type, sets);
    double *fk = fd_vec(c.n3), *fs = fd_vec(c.n3), *fj = fd_vec(c.n3);
    double *jxk = fd_vec(c.nv), *jvk = fd_vec(c.nv);
    double *jxs = fd_vec(c.nv), *jvs = fd_vec(c.nv);
    cl_eval force = {.x = c.x, .v = c.v, .f = fk};
    type->eval(c.state, &force);
    cl_eval jac = {.x = c.x, .v = c.v, .f = fj, .dfdx = jxk, .dfdv = jvk};
    type->eval(c.state, &jac);
    cr_assert_eq(memcmp(fj, fk, c.n3 * sizeof *fk), 0,
                 "%s: the Jacobian's forces are the force path's",
                 type->name);
    cl_eval scalar = {.x = c.x, .v = c.v, .f = fs, .want_energy = true,
                      .dfdx = central ? NULL : jxs,
                      .dfdv = central ? NULL : jvs};
    type->eval(c.state, &scalar);
    if (central)
        central_scalar(c.state, c.x, jxs);
    assert_close(fk, fs, c.n3, "forces");
    assert_close(central ? jxk : jvk, central ? jxs : jvs, c.nv,
                 central ? "df/dx" : "df/dv");
    if (!central && max_abs(jxs, c.nv) > 0)
        assert_close(jxk, jxs, c.nv, "df/dx");
    double *arr[] = {fk, fs, fj, jxk, jvk, jxs, jvs};
    for (size_t i = 0; i < sizeof arr / sizeof *arr; i++)
        free(arr[i]);
    kcase_close(&c);
}

#define BUCKLED(...) FD_SETS("cloth.n=24", "pins.at=", "damping.kd=1e-3",   \
                            __VA_ARGS__)

Test(pairkern, type2_buckled_matches_scalar)
{
    compare_paths(&cl_term_type2, true, BUCKLED("type2.kb=5e-6"));
    compare_paths(&cl_term_type2, true, BUCKLED("type2.kb=0.1"));
    compare_paths(&cl_term_type2, true,
                  BUCKLED("type2.asinc=seed-poly", "type2.tension=none"));
}

Test(pairkern, type1_and_springs_match_scalar)
{
    compare_paths(&cl_term_type1, true, BUCKLED("type1.ks=200"));
    compare_paths(&cl_term_type1, true,
                  BUCKLED("type1.compression=spring",
                         "jacobian.transverse=clamp"));
    compare_paths(&cl_term_springs, true,
                  BUCKLED("springs.enabled=true", "type1.enabled=false",
                         "type2.enabled=false"));
}

Test(pairkern, damping_matches_scalar)
{
    compare_paths(&cl_term_damping, false, BUCKLED("damping.model=linear"));
    compare_paths(&cl_term_damping, false, BUCKLED("damping.model=axial"));
    compare_paths(&cl_term_spring_damping, false,
                  BUCKLED("springs.enabled=true", "type1.enabled=false",
                         "type2.enabled=false", "spring-damping.kd=0.02"));
}

/* A term and the terms after it (next[0..nnext)) in one pass
 * (forces/term.h, fuse) against the terms one after the other: the same
 * forces to 1e-13 relative (per-particle sums round differently from the
 * scatters); `expect` of them fused (0: not fused, nothing done); never
 * where Jacobians are asked for, or the following terms differ. */
static void compare_fused(const cl_term_type *lead,
                          const cl_term_type *const *next, size_t nnext,
                          size_t expect, const char *const *sets)
{
    kcase c;
    kcase_open(&c, lead, sets);
    void *st[4] = {NULL};
    cl_error err = {0};
    cl_term_opts opts = {0};
    for (size_t i = 0; i < nnext; i++) {
        cr_assert_eq(next[i]->create(c.cfg, cl_model_cloth(c.m), &opts,
                                     &st[i], &err), CL_OK, "%s", err.msg);
        cr_assert_not_null(st[i]);
    }
    double *fs = fd_vec(c.n3), *ff = fd_vec(c.n3), *jx = fd_vec(c.nv);
    cl_eval apart = {.x = c.x, .v = c.v, .f = fs};
    lead->eval(c.state, &apart);
    for (size_t i = 0; i < expect; i++)
        next[i]->eval(st[i], &apart);
    cl_eval one = {.x = c.x, .v = c.v, .f = ff};
    cr_assert_eq(lead->fuse(c.state, next, st, nnext, &one), expect);
    if (expect)
        assert_close(ff, fs, c.n3, "fused forces");
    cl_eval jac = {.x = c.x, .v = c.v, .f = ff, .dfdx = jx};
    cr_assert_eq(lead->fuse(c.state, next, st, nnext, &jac), 0);
    const cl_term_type *other[] = {&cl_term_gravity, &cl_term_gravity};
    cr_assert_eq(lead->fuse(c.state, other, st, nnext, &one), 0);
    for (size_t i = 0; i < nnext; i++)
        next[i]->free(st[i]);
    free(fs);
    free(ff);
    free(jx);
    kcase_close(&c);
}

static void compare_springs(const char *model)
{
    char set[64];
    snprintf(set, sizeof set, "spring-damping.model=%s", model);
    const cl_term_type *next[] = {&cl_term_spring_damping};
    compare_fused(&cl_term_springs, next, 1, 1,
                  BUCKLED("springs.enabled=true", "type1.enabled=false",
                          "type2.enabled=false", "spring-damping.kd=0.02",
                          set));
}

Test(pairkern, springs_and_dashpots_fused_match_two_passes)
{
    compare_springs("axial");
    compare_springs("linear");
}

/* Type1, Type2 (buckled: a third of its pairs on the f_b branch) and
 * their damping in one pass; Type1 and the damping alone without Type2;
 * not fused where the damping acts on engaged pairs only. */
Test(pairkern, choiko_fused_matches_three_passes)
{
    const cl_term_type *next[] = {&cl_term_type2, &cl_term_damping};
    const cl_term_type *damp[] = {&cl_term_damping};
    compare_fused(&cl_term_type1, next, 2, 2,
                  BUCKLED("damping.model=linear"));
    compare_fused(&cl_term_type1, next, 2, 2,
                  BUCKLED("damping.model=axial", "type2.kb=0.1"));
    compare_fused(&cl_term_type1, damp, 1, 1,
                  BUCKLED("type2.enabled=false"));
    compare_fused(&cl_term_type1, next, 2, 0,
                  BUCKLED("damping.where=engaged"));
}

/* The clone the kernels run is the one the CPU test picks. */
Test(pairkern, isa_is_the_resolvers_choice)
{
    const char *isa = cl_pairkern_isa();
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    __builtin_cpu_init();
    cr_assert_str_eq(isa, __builtin_cpu_supports("avx2") ? "avx2"
                                                         : "default");
#else
    cr_assert_str_eq(isa, "default");
#endif
}
