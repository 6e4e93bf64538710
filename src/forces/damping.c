/* Choi-Ko linear damping (seed 000, eq. 14; SPEC 3.2) on every Type1 and
 * Type2 pair:
 *     f_a = -kd (v_a - v_b),   f_b = -f_a,
 * so df_a/dv_a = df_b/dv_b = -kd I and df_a/dv_b = df_b/dv_a = kd I; no
 * position dependence.  Its power is -kd |v_a - v_b|^2 <= 0 per pair.
 *
 * where = engaged reproduces the seed author's code, which damps a pair only
 * while its spring acts: a Type1 pair when d > L, a Type2 pair when d < L.
 * (The force then jumps where a pair engages; the Jacobian is that of the
 * current branch.)
 *
 * INI section [damping]: kd (N s/m, >= 0; 0 switches the term off),
 * where (always|engaged). */
#include <stdlib.h>
#include <string.h>

#include "forces/choiko.h"
#include "forces/pairterm.h"

typedef struct {
    cl_pairset set;     /* Type1 pairs first, then Type2 pairs */
    size_t ntype1;
    int (*couple)[2];
    long *slot;
    double kd;
    bool engaged_only;
} damping_state;

static bool engaged(const damping_state *st, size_t k, const double *x)
{
    const cl_pair *pr = &st->set.pair[k];
    double d = cl_dist(x + 3 * pr->a, x + 3 * pr->b);
    return k < st->ntype1 ? d > pr->rest : d < pr->rest;
}

static void damping_eval(void *state, cl_eval *ev)
{
    damping_state *st = state;
    static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    double power = 0.0;
    for (size_t k = 0; k < st->set.n; k++) {
        if (st->engaged_only && !engaged(st, k, ev->x))
            continue;
        const cl_pair *pr = &st->set.pair[k];
        const double *va = ev->v + 3 * pr->a, *vb = ev->v + 3 * pr->b;
        for (int i = 0; i < 3; i++) {
            double fa = -st->kd * (va[i] - vb[i]);
            if (ev->f) {
                ev->f[3 * pr->a + i] += fa;
                ev->f[3 * pr->b + i] -= fa;
            }
            power += fa * (va[i] - vb[i]);
        }
        if (ev->dfdv) {
            const long *s = st->slot + 4 * k;
            cl_block_add(ev->dfdv, s[0], -st->kd, I3);
            cl_block_add(ev->dfdv, s[1], -st->kd, I3);
            cl_block_add(ev->dfdv, s[2], st->kd, I3);
            cl_block_add(ev->dfdv, s[3], st->kd, I3);
        }
    }
    if (ev->want_energy) {
        ev->energy = 0.0;
        ev->power = power;
    }
}

static size_t damping_couplings(const void *state, const int (**pairs)[2])
{
    const damping_state *st = state;
    *pairs = (const int (*)[2])st->couple;
    return st->set.n;
}

static cl_status damping_bind(void *state, const cl_bpattern *pat,
                              const int *dof, cl_error *err)
{
    damping_state *st = state;
    return cl_pair_slots(&st->set, pat, dof, &st->slot, err);
}

static void damping_free(void *state)
{
    damping_state *st = state;
    if (!st)
        return;
    cl_pairs_free(&st->set);
    free(st->couple);
    free(st->slot);
    free(st);
}

/* Type1 pairs followed by Type2 pairs (if Type2 is on). */
static cl_status damping_pairs(cl_config *cfg, const cl_cloth *cloth,
                               damping_state *st, cl_error *err)
{
    bool type2;
    cl_pairset t1 = {0}, t2 = {0};
    cl_status rc;
    if ((rc = cl_choiko_type2_enabled(cfg, &type2, err)) ||
        (rc = cl_pairs_type1(cloth, &t1, err)) ||
        (type2 && (rc = cl_pairs_type2(cloth, &t2, err)))) {
        cl_pairs_free(&t1);
        return rc;
    }
    st->ntype1 = t1.n;
    st->set.n = t1.n + t2.n;
    st->set.pair = realloc(t1.pair, (st->set.n + 1) * sizeof *t1.pair);
    st->couple = malloc((st->set.n + 1) * sizeof *st->couple);
    if (!st->set.pair || !st->couple) {
        if (!st->set.pair)
            free(t1.pair);
        cl_pairs_free(&t2);
        return cl_error_set(err, CL_ENOMEM, "out of memory (damping)");
    }
    if (t2.n)
        memcpy(st->set.pair + t1.n, t2.pair, t2.n * sizeof *t2.pair);
    cl_pairs_free(&t2);
    for (size_t k = 0; k < st->set.n; k++) {
        st->couple[k][0] = st->set.pair[k].a;
        st->couple[k][1] = st->set.pair[k].b;
    }
    return CL_OK;
}

static cl_status damping_create(cl_config *cfg, const cl_cloth *cloth,
                                const cl_term_opts *opts, void **state,
                                cl_error *err)
{
    static const char *const where[] = {"always", "engaged", NULL};
    double kd;
    int wk;
    cl_status rc;
    (void)opts;
    *state = NULL;
    if ((rc = cl_config_double(cfg, "damping", "kd", 0.0, 0.0, INFINITY, &kd,
                               err)) ||
        (rc = cl_config_choice(cfg, "damping", "where", where, 0, &wk, err)))
        return rc;
    if (kd == 0.0)
        return CL_OK;
    damping_state *st = calloc(1, sizeof *st);
    if (!st)
        return cl_error_set(err, CL_ENOMEM, "out of memory (damping)");
    st->kd = kd;
    st->engaged_only = wk == 1;
    if ((rc = damping_pairs(cfg, cloth, st, err))) {
        damping_free(st);
        return rc;
    }
    *state = st;
    return CL_OK;
}

const cl_term_type cl_term_damping = {
    .name = "damping",
    .doc = "Choi-Ko linear pair damping -kd (v_i - v_j) on Type1 and Type2 "
           "pairs (seed eq. 14)",
    .conservative = false,
    .create = damping_create,
    .couplings = damping_couplings,
    .bind = damping_bind,
    .eval = damping_eval,
    .free = damping_free,
};
