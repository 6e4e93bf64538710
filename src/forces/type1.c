/* Choi-Ko Type1 interaction (Jiao, eqs. 1-3; docs/model.md 3.2): sequential
 * pairs (i+-1, j), (i, j+-1), (i+-1, j+-1), tension only:
 *     s(d) = ks (d - L)  for d >= L,   0 for d < L,
 *     E(d) = ks (d - L)^2 / 2 for d >= L, 0 otherwise.
 * Jiao's eq. (1) reads ">= L" in both cases; the second means d < L.
 * With compression = spring the law is ks (d - L) on both sides: a plain
 * linear spring without the kink at d = L (for convergence and energy
 * studies).
 *
 * INI section [type1]: enabled (true), ks (N/m, >= 0), compression
 * (none|spring). */
#include <stdlib.h>

#include "forces/choiko.h"
#include "forces/pairterm.h"
#include "model/cloth_read.h"

typedef struct {
    cl_pairterm pt; /* first member: the pairterm hooks use it */
    double ks;
    bool linear;    /* compression = spring */
} type1_state;

static void type1_law(const void *params, size_t k, double d, double L,
                      bool want_energy, bool want_ds,
                      cl_pairlaw *out)
{
    (void)want_ds; /* s' costs nothing here */
    (void)k;
    const type1_state *st = params;
    double stretch = d - L;
    if (stretch >= 0 || st->linear) {
        out->s = st->ks * stretch;
        out->ds = st->ks;
        out->e = want_energy ? 0.5 * st->ks * stretch * stretch : 0.0;
    } else {
        out->s = out->ds = out->e = 0.0;
    }
}

/* The law over pairs [k0, k0 + m) (cl_pairlaw_batch_fn). */
CL_PAIR_KERNEL
static void type1_batch(const void *params, size_t k0, size_t m,
                        const double *d, const double *L, double *s,
                        double *ds)
{
    const type1_state *st = params;
    const double *restrict LL = L + k0;
    double ks = st->ks;
    bool linear = st->linear;
#pragma omp simd
    for (size_t i = 0; i < m; i++) {
        double stretch = d[i] - LL[i], v = ks * stretch;
        bool on = stretch >= 0 || linear;
        s[i] = on ? v : 0.0;
        if (ds)
            ds[i] = on ? ks : 0.0;
    }
}

/* Type1, Type2 (when it follows) and the damping of their pairs in one
 * pass, for forces alone (forces/term.h, fuse). */
static size_t type1_fuse(void *state, const cl_term_type *const *next,
                         void *const *next_state, size_t nnext, cl_eval *ev)
{
    cl_pairterm *pt[2] = {state, NULL};
    size_t npt = 1;
    if (nnext >= 1 && next[0] == &cl_term_type2)
        pt[npt++] = next_state[0];
    if (nnext < npt || next[npt - 1] != &cl_term_damping)
        return 0;
    return cl_damping_fused(next_state[npt - 1], pt, npt, ev) ? npt : 0;
}

/* The law as k (d - L) for the fused pass (forces/pairterm.h,
 * k_linear): the one ks of every pair, nothing below L unless
 * compression = spring. */
static void linear_law(type1_state *st)
{
    st->pt.k_linear = &st->ks;
    st->pt.k_uniform = true;
    st->pt.k_tension_only = !st->linear;
}

static void type1_free(void *state)
{
    type1_state *st = state;
    if (st)
        cl_pairterm_free(&st->pt);
    free(st);
}

static cl_status type1_create(cl_config *cfg, const cl_cloth *cloth,
                              const cl_term_opts *opts, void **state,
                              cl_error *err)
{
    static const char *const compression[] = {"none", "spring", NULL};
    bool enabled;
    double ks;
    int ck;
    cl_status rc;
    *state = NULL;
    if ((rc = cl_choiko_type1_enabled(cfg, &enabled, err)) ||
        (rc = cl_choiko_ks(cfg, &ks, err)) ||
        (rc = cl_config_choice(cfg, "type1", "compression", compression, 0,
                               &ck, err)))
        return rc;
    if (!enabled)
        return CL_OK;
    if ((rc = cl_cloth_grid_only(cfg, cloth, "type1", "enabled",
                                 "Choi-Ko Type1 acts on the grid's sequential "
                                 "pairs; a mesh cloth needs [type1] enabled = "
                                 "false", err)))
        return rc;
    type1_state *st = calloc(1, sizeof *st);
    if (!st)
        return cl_error_set(err, CL_ENOMEM, "out of memory (type1)");
    st->ks = ks;
    st->linear = ck == 1;
    cl_pairset set;
    if ((rc = cl_pairs_type1(cloth, &set, err)) ||
        (rc = cl_pairterm_init(&st->pt, set, type1_law, type1_batch, st,
                               opts->clamp_transverse, 1, err)) ||
        (rc = cl_pairterm_tear(&st->pt, opts->tear_cut, err))) {
        type1_free(st);
        return rc;
    }
    linear_law(st);
    *state = st;
    return CL_OK;
}

const cl_term_type cl_term_type1 = {
    .name = "type1",
    .doc = "Choi-Ko Type1: tension-only springs on sequential pairs "
           "(axis and diagonal neighbours)",
    .conservative = true,
    .threads = cl_pairterm_threads,
    .create = type1_create,
    .couplings = cl_pairterm_couplings,
    .bind = cl_pairterm_bind,
    .eval = cl_pairterm_eval,
    .step_done = cl_pairterm_step_done,
    .broken = cl_pairterm_broken,
    .fuse = type1_fuse,
    .free = type1_free,
};
