/* Position-based distance constraints, the `pbd` term: equations, options
 * and sources in forces/pbd.h. */
#include "forces/pbd.h"

#include <math.h>
#include <stdlib.h>

#include "forces/pairterm.h"
#include "model/cloth_read.h"

#define SEC "pbd"

typedef struct {
    cl_pairterm pt;    /* first: pairs and tearing (no law, no Jacobian) */
    double stiffness;  /* K in (0, 1] */
    long iterations;   /* Gauss-Seidel sweeps per projection */
    double *w;         /* inverse mass per particle (np) */
} pbd_state;

/* One pair: move a and b along u in proportion to their inverse masses. */
static void pbd_pair(const pbd_state *st, const cl_pair *pr, double *x,
                     const int *dof)
{
    double wa = dof[pr->a] >= 0 ? st->w[pr->a] : 0.0;
    double wb = dof[pr->b] >= 0 ? st->w[pr->b] : 0.0;
    double *xa = x + 3 * pr->a, *xb = x + 3 * pr->b;
    double d = cl_dist(xa, xb);
    if (!(wa + wb > 0) || !(d > 0))
        return;
    /* s u = (x_a - x_b) K (d - L) / ((w_a + w_b) d) */
    double s = st->stiffness * (d - pr->rest) / ((wa + wb) * d);
    for (int i = 0; i < 3; i++) {
        double c = s * (xa[i] - xb[i]);
        xa[i] -= wa * c;
        xb[i] += wb * c;
    }
}

static void pbd_project(void *state, double *x, const int *dof)
{
    const pbd_state *st = state;
    for (long it = 0; it < st->iterations; it++)
        for (size_t k = 0; k < st->pt.set.n; k++)
            if (!cl_pairterm_is_torn(&st->pt, k))
                pbd_pair(st, &st->pt.set.pair[k], x, dof);
}

/* No force, no Jacobian, no energy (see the header). */
static void pbd_eval(void *state, cl_eval *ev)
{
    (void)state;
    if (ev->want_energy) {
        ev->energy = 0.0;
        ev->power = 0.0;
    }
}

/* The same pairs as hard distance constraints (XPBD with compliance 0);
 * K and the sweeps are the projection's own and are not passed on. */
static size_t pbd_distances(const void *state, const cl_pair **pair,
                            const double **k)
{
    const pbd_state *st = state;
    *pair = st->pt.set.pair;
    *k = NULL;
    return st->pt.set.n;
}

static size_t pbd_couplings(const void *state, const int (**pairs)[2])
{
    (void)state;
    *pairs = NULL;
    return 0;
}

static cl_status pbd_bind(void *state, const cl_bpattern *pat,
                          const int *dof, cl_error *err)
{
    (void)state, (void)pat, (void)dof, (void)err;
    return CL_OK;
}

static void pbd_free(void *state)
{
    pbd_state *st = state;
    if (!st)
        return;
    cl_pairterm_free(&st->pt);
    free(st->w);
    free(st);
}

/* The constraints of levels 1..levels: grid levels, or on a mesh the
 * triangle edges (level 1) and the bend pairs (level 2). */
static cl_status pbd_pairs(const cl_cloth *cloth, long levels,
                           cl_pairset *set, cl_error *err)
{
    cl_pairset bend;
    cl_status rc;
    if (cloth->kind == CL_CLOTH_GRID)
        return cl_pairs_levels(cloth, levels, set, err);
    if ((rc = cl_pairs_mesh_edges(cloth, set, err)) || levels < 2)
        return rc;
    if ((rc = cl_pairs_mesh_bend(cloth, &bend, err)) == CL_OK)
        rc = cl_pairs_append(set, &bend, err);
    return rc;
}

static cl_status pbd_setup(pbd_state *st, const cl_cloth *cloth, long levels,
                           double cut, cl_error *err)
{
    cl_pairset set = {0};
    cl_status rc;
    st->w = malloc(cloth->np * sizeof *st->w);
    if (!st->w)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pbd)");
    for (size_t p = 0; p < cloth->np; p++)
        st->w[p] = 1.0 / cloth->mass[p];
    if ((rc = pbd_pairs(cloth, levels, &set, err))) {
        cl_pairs_free(&set);
        return rc;
    }
    if ((rc = cl_pairterm_init(&st->pt, set, NULL, NULL, NULL, false, 1,
                                   err)))
        return rc;
    return cl_pairterm_tear(&st->pt, cut, err);
}

static cl_status pbd_create(cl_config *cfg, const cl_cloth *cloth,
                            const cl_term_opts *opts, void **state,
                            cl_error *err)
{
    bool enabled;
    long levels, iterations;
    double K;
    cl_status rc;
    *state = NULL;
    if ((rc = cl_config_bool(cfg, SEC, "enabled", false, &enabled, err)) ||
        (rc = cl_config_long(cfg, SEC, "levels", 1, 1, 1000, &levels,
                             err)) ||
        (rc = cl_config_double(cfg, SEC, "stiffness", 1.0, 1e-300, 1.0, &K,
                               err)) ||
        (rc = cl_config_long(cfg, SEC, "iterations", 10, 1, 1000000,
                             &iterations, err)) ||
        !enabled)
        return rc;
    if (levels > 2 &&
        (rc = cl_cloth_grid_only(cfg, cloth, SEC, "levels",
                                 "on a mesh cloth level 1 is the triangle "
                                 "edges and level 2 adds the bend pairs; "
                                 "levels beyond 2 are grid offsets", err)))
        return rc;
    pbd_state *st = calloc(1, sizeof *st);
    if (!st)
        return cl_error_set(err, CL_ENOMEM, "out of memory (pbd)");
    st->stiffness = K;
    st->iterations = iterations;
    if ((rc = pbd_setup(st, cloth, levels, opts->tear_cut, err))) {
        pbd_free(st);
        return rc;
    }
    *state = st;
    return CL_OK;
}

const cl_term_type cl_term_pbd = {
    .name = "pbd",
    .doc = "position-based distance constraints on levels 1..k, Gauss-Seidel "
           "projection (Verlet-and-PBD report; verlet-pbd projects, xpbd "
           "takes them as hard constraints, pd refuses them)",
    .conservative = false,
    .create = pbd_create,
    .couplings = pbd_couplings,
    .bind = pbd_bind,
    .eval = pbd_eval,
    .project = pbd_project,
    .distances = pbd_distances,
    .step_done = cl_pairterm_step_done,
    .broken = cl_pairterm_broken,
    .free = pbd_free,
};
