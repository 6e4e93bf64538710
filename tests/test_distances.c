/* The distance constraints a model exposes (system/distances.c,
 * system/system.h cl_distances): the springs' pairs with their stiffness
 * and the pbd term's as hard constraints, ends numbered free or anchor,
 * anchors at their pins' positions; force_other is the force without the
 * springs; none without a spring network or with tearing. */
#include <criterion/criterion.h>

#include "cdyncheck.h"

Test(distances, spring_chain_numbering)
{
    pb_case c = pb_open(FD_MODEL(CD_CHAIN, "pins.velocity=0,2,0"));
    const cl_distances *d = c.sys->distances;
    cr_assert_not_null(d);
    cr_assert_eq(d->n, CD_N);
    cr_assert_eq(d->nanchor, 1);
    /* link 0 joins the pin (anchor 0) and free particle 0 */
    cr_assert_eq(d->end[0][0], -1);
    cr_assert_eq(d->end[0][1], 0);
    for (size_t j = 1; j < d->n; j++) {
        cr_assert_eq(d->end[j][0], (int)j - 1);
        cr_assert_eq(d->end[j][1], (int)j);
    }
    for (size_t j = 0; j < d->n; j++) {
        cr_assert_float_eq(d->rest[j], CD_L, 1e-15);
        cr_assert_eq(d->stiffness[j], CD_K);
    }
    double xa[3];
    c.sys->anchors(c.sys->data, 0.25, xa);
    cr_assert_eq(xa[0], 0.0);
    cr_assert_float_eq(xa[1], 0.5, 1e-15);
    cr_assert_eq(xa[2], 0.0);
    pb_close(&c);
}

Test(distances, pbd_constraints_are_hard)
{
    pb_case c = pb_open(FD_MODEL("cloth.n=3", "type1.enabled=false",
                                 "type2.enabled=false", "pbd.enabled=true"));
    const cl_distances *d = c.sys->distances;
    cr_assert_not_null(d);
    cr_assert_eq(d->n, 2 * 2 * 5); /* level 1 on 3 x 3: 2 (n-1)(2n-1) */
    for (size_t j = 0; j < d->n; j++)
        cr_assert(isinf(d->stiffness[j]));
    pb_close(&c);
}

Test(distances, none_without_springs_or_with_tearing)
{
    pb_case a = pb_open(FD_MODEL("cloth.n=3"));
    pb_case b = pb_open(FD_MODEL(CD_CHAIN, "tear.cut=2"));
    cr_assert_null(a.sys->distances);
    cr_assert_null(b.sys->distances);
    cr_assert_null(b.sys->force_other);
    pb_close(&a);
    pb_close(&b);
}

/* force_other at a random state equals the force of the same model
 * without its springs (gravity and spring damping remain). */
Test(distances, force_other_leaves_out_the_springs)
{
    const char *const with[] = {CD_CHAIN, "spring-damping.kd=0.01", NULL};
    const char *const without[] = {CD_CHAIN, "spring-damping.kd=0.01",
                                   "springs.enabled=false", NULL};
    pb_case a = pb_open(fd_model(with)), b = pb_open(fd_model(without));
    fd_rng r = {7};
    fd_random_vec(&r, 0.05, a.x, a.n);
    fd_random_vec(&r, 0.5, a.v, a.n);
    double fa[3 * CD_N], fb[3 * CD_N], ff[3 * CD_N];
    cr_assert_eq(a.sys->force_other(a.sys->data, 0.0, a.x, a.v, fa), CL_OK);
    cr_assert_eq(b.sys->force(b.sys->data, 0.0, a.x, a.v, fb), CL_OK);
    cr_assert_eq(a.sys->force(a.sys->data, 0.0, a.x, a.v, ff), CL_OK);
    double d = 0.0, s = 0.0;
    for (size_t i = 0; i < a.n; i++) {
        d = fmax(d, fabs(fa[i] - fb[i]));
        s = fmax(s, fabs(ff[i] - fb[i]));
    }
    cr_assert_lt(d, 1e-15, "%g", d);
    cr_assert_gt(s, 0.1, "the springs pull: %g", s);
    pb_close(&a);
    pb_close(&b);
}
