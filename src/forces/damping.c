/* Choi-Ko pair damping (Jiao, eq. 14; docs/model.md 3.2) on every Type1
 * and Type2 pair:
 *     f_a = -kd (v_a - v_b),   f_b = -f_a,
 * so df_a/dv_a = df_b/dv_b = -kd I and df_a/dv_b = df_b/dv_a = kd I; no
 * position dependence.  Its power is -kd |v_a - v_b|^2 <= 0 per pair.
 * model = axial (an option) damps only the stretching rate,
 * f_a = kd (u . (v_b - v_a)) u (the Verlet-and-PBD report's "spring and
 * friction"); both laws and their Jacobians are in forces/pairdamp.h.
 *
 * where = engaged reproduces Jiao's own code, which damps a pair only
 * while its spring acts: a Type1 pair when d > L, a Type2 pair when d < L.
 * (The force then jumps where a pair engages; the Jacobian is that of the
 * current branch.)
 *
 * Tearing ([tear] cut > 0, forces/pairterm.h): a pair breaks when
 * d > cut L, the same test on the same d and L as its Type1 or Type2
 * spring, so a torn connection is no longer damped either.
 *
 * INI section [damping]: kd (N s/m, >= 0; 0 switches the term off),
 * where (always|engaged), model (linear|axial, default linear). */
#include <stdlib.h>

#include "forces/choiko.h"
#include "forces/pairdamp.h"
#include "model/cloth_read.h"

typedef struct {
    cl_pairdamp pd;     /* first member; its pairs: Type1 first, then Type2 */
    size_t ntype1;
    bool engaged_only;
} damping_state;

static bool engaged(const void *ctx, size_t k, const double *x)
{
    const damping_state *st = ctx;
    const cl_pair *pr = &st->pd.pt.set.pair[k];
    double d = cl_dist(x + 3 * pr->a, x + 3 * pr->b);
    return k < st->ntype1 ? d > pr->rest : d < pr->rest;
}

static void damping_eval(void *state, cl_eval *ev)
{
    damping_state *st = state;
    cl_pairdamp_eval(&st->pd, ev, st->engaged_only ? engaged : NULL, st);
}

bool cl_damping_fused(void *state, cl_pairterm *const *pt, size_t npt,
                      cl_eval *ev)
{
    damping_state *st = state;
    return !st->engaged_only && cl_pairdamp_fused(pt, npt, &st->pd, ev);
}

static void damping_free(void *state)
{
    damping_state *st = state;
    if (st)
        cl_pairdamp_free(&st->pd);
    free(st);
}

/* Type1 pairs followed by Type2 pairs (if Type2 is on); *ntype1 of them
 * Type1. */
static cl_status damping_pairs(cl_config *cfg, const cl_cloth *cloth,
                               cl_pairset *set, size_t *ntype1,
                               cl_error *err)
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
    *ntype1 = t1.n;
    if ((rc = cl_pairs_append(&t1, &t2, err))) {
        cl_pairs_free(&t1);
        return rc;
    }
    *set = t1;
    return CL_OK;
}

static cl_status damping_create(cl_config *cfg, const cl_cloth *cloth,
                                const cl_term_opts *opts, void **state,
                                cl_error *err)
{
    static const char *const where[] = {"always", "engaged", NULL};
    double kd;
    int wk;
    cl_damp_model model;
    cl_status rc;
    *state = NULL;
    if ((rc = cl_config_double(cfg, "damping", "kd", 0.0, 0.0, INFINITY, &kd,
                               err)) ||
        (rc = cl_config_choice(cfg, "damping", "where", where, 0, &wk,
                               err)) ||
        (rc = cl_pairdamp_read_model(cfg, "damping", CL_DAMP_LINEAR, &model,
                                     err)))
        return rc;
    if (kd == 0.0)
        return CL_OK;
    if ((rc = cl_cloth_grid_only(cfg, cloth, "damping", "kd",
                                 "Choi-Ko pair damping acts on the grid's "
                                 "Type1 and Type2 pairs; on a mesh cloth set "
                                 "[damping] kd = 0 (and use [spring-damping] "
                                 "or a Baraff-Witkin damping)", err)))
        return rc;
    damping_state *st = calloc(1, sizeof *st);
    if (!st)
        return cl_error_set(err, CL_ENOMEM, "out of memory (damping)");
    st->engaged_only = wk == 1;
    cl_pairset set;
    if ((rc = damping_pairs(cfg, cloth, &set, &st->ntype1, err)) ||
        (rc = cl_pairdamp_init(&st->pd, set, kd, model, err)) ||
        (rc = cl_pairterm_tear(&st->pd.pt, opts->tear_cut, err))) {
        damping_free(st);
        return rc;
    }
    *state = st;
    return CL_OK;
}

const cl_term_type cl_term_damping = {
    .name = "damping",
    .doc = "Choi-Ko pair damping on Type1 and Type2 pairs: linear "
           "-kd (v_i - v_j) (Jiao eq. 14) or axial",
    .conservative = false,
    .threads = cl_pairterm_threads,
    .create = damping_create,
    .couplings = cl_pairterm_couplings,
    .bind = cl_pairterm_bind,
    .eval = damping_eval,
    .step_done = cl_pairterm_step_done,
    .broken = cl_pairterm_broken,
    .free = damping_free,
};
