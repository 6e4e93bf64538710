/* Mass-spring network and the `springs` term (Zischg, Chea and Aigner,
 * sec. 3, eq. 4; the Verlet-and-PBD report, "Spring or Physical constraint"
 * and "Level of Constraint"; docs/model.md 2, 3.1, 3.4).  Pair sets, the
 * levels rule and the INI keys: springs.h.
 *
 * Every spring is linear in tension and compression alike:
 *     s(d) = k (d - L),   E(d) = k (d - L)^2 / 2,
 * on the central-pair machinery of docs/model.md 3.1 (forces/pairterm.h):
 * force on a is s(d) u, u = (x_b - x_a)/d (the Verlet-and-PBD report:
 * f_a = k (|P_b - P_a| - l) d^; Zischg, Chea and Aigner's eq. 4 is the same
 * force written for x_1 - x_2), Jacobian blocks
 * K = k u u^T + (s/d)(I - u u^T).  k is per pair (structural, shear, bend
 * or level); the rest length L is the rest distance, so d == L at rest. */
#include "forces/springs.h"

#include <math.h>
#include <stdlib.h>

#include "forces/pairdamp.h"
#include "model/cloth_read.h"

#define SEC "springs"

typedef struct {
    double ks, kshear, kbend; /* structural, shear, bend (N/m) */
    long levels;              /* 0: named sets; else levels 1..levels */
    bool inverse;             /* level_stiffness = inverse */
} spring_opts;

/* Keys that only one of the two modes uses must not be set in the other. */
static cl_status check_mode_keys(cl_config *cfg, const spring_opts *o,
                                 cl_error *err)
{
    static const char *const named_only[] = {"k_shear", "k_bend", NULL};
    static const char *const levels_only[] = {"level_stiffness", NULL};
    const char *const *keys = o->levels ? named_only : levels_only;
    char where[256];
    for (size_t k = 0; keys[k]; k++)
        if (cl_config_string(cfg, SEC, keys[k], NULL))
            return cl_error_set(
                err, CL_EINVAL,
                "%s: [springs] %s has no effect with levels = %ld: levels "
                ">= 1 replaces structural/shear/bend by levels 1..k, "
                "level_stiffness applies only to them",
                cl_config_origin(cfg, SEC, keys[k], where, sizeof where),
                keys[k], o->levels);
    return CL_OK;
}

static cl_status read_opts(cl_config *cfg, spring_opts *o, cl_error *err)
{
    static const char *const scaling[] = {"same", "inverse", NULL};
    int sk;
    cl_status rc;
    if ((rc = cl_config_double(cfg, SEC, "k_structural", 200.0, 0.0,
                               INFINITY, &o->ks, err)) ||
        (rc = cl_config_double(cfg, SEC, "k_shear", o->ks, 0.0, INFINITY,
                               &o->kshear, err)) ||
        (rc = cl_config_double(cfg, SEC, "k_bend", o->ks / 8.0, 0.0,
                               INFINITY, &o->kbend, err)) ||
        (rc = cl_config_long(cfg, SEC, "levels", 0, 0, 1000, &o->levels,
                             err)) ||
        (rc = cl_config_choice(cfg, SEC, "level_stiffness", scaling, 0, &sk,
                               err)))
        return rc;
    o->inverse = sk == 1;
    return check_mode_keys(cfg, o, err);
}

/* Stiffness of the spring at grid offset (di, dj). */
static double offset_stiffness(const spring_opts *o, int di, int dj)
{
    di = abs(di);
    dj = abs(dj);
    if (o->levels) {
        int l = di > dj ? di : dj;
        return o->inverse ? o->ks / l : o->ks;
    }
    if (di + dj == 1)
        return o->ks;
    return di == 1 && dj == 1 ? o->kshear : o->kbend;
}

/* Append the axis offsets (0, l), (l, 0) or the diagonal ones (l, l),
 * (l, -l). */
static size_t add_offsets(int (*off)[2], size_t n, int l, bool diagonal)
{
    off[n][0] = diagonal ? l : 0;
    off[n][1] = l;
    off[n + 1][0] = l;
    off[n + 1][1] = diagonal ? -l : 0;
    return n + 2;
}

/* Generating offsets (di > 0, or di == 0 and dj > 0) of the sets in use;
 * off has room for max(6, 4 levels) rows. */
static size_t spring_offsets(const spring_opts *o, long levels,
                             int (*off)[2])
{
    size_t n = 0;
    if (o->levels)
        return o->ks > 0 ? cl_level_offsets(levels, off) : 0;
    if (o->ks > 0)
        n = add_offsets(off, n, 1, false);
    if (o->kshear > 0)
        n = add_offsets(off, n, 1, true);
    if (o->kbend > 0)
        n = add_offsets(off, n, 2, false);
    return n;
}

/* Per-pair stiffness from the grid offset of each pair. */
static void pair_stiffness(const cl_cloth *c, const spring_opts *o,
                           cl_springnet *net)
{
    for (size_t k = 0; k < net->set.n; k++) {
        const cl_pair *p = &net->set.pair[k];
        net->k[k] = offset_stiffness(o, p->b / c->nv - p->a / c->nv,
                                     p->b % c->nv - p->a % c->nv);
    }
}

/* The grid network: the offsets of the sets in use. */
static cl_status grid_network(const cl_cloth *c, const spring_opts *o,
                              cl_springnet *net, cl_error *err)
{
    /* Levels beyond the grid add no pair. */
    long span = c->nu > c->nv ? c->nu : c->nv;
    long levels = o->levels < span ? o->levels : span - 1;
    size_t room = levels > 1 ? 4 * (size_t)levels : 6;
    *net = (cl_springnet){.k = NULL};
    int(*off)[2] = malloc(room * sizeof *off);
    if (!off)
        return cl_error_set(err, CL_ENOMEM, "out of memory (springs)");
    size_t noff = spring_offsets(o, levels, off);
    cl_status rc = cl_pairs_from_offsets(c, noff, (const int(*)[2])off,
                                         &net->set, err);
    free(off);
    if (rc)
        return rc;
    net->k = malloc((net->set.n + 1) * sizeof *net->k);
    if (!net->k) {
        cl_springnet_free(net);
        return cl_error_set(err, CL_ENOMEM, "out of memory (springs)");
    }
    pair_stiffness(c, o, net);
    return CL_OK;
}

/* Pairs of *set get stiffness k from net->k[from] on, appended to net. */
static cl_status add_set(cl_springnet *net, cl_pairset *set, double k,
                         cl_error *err)
{
    size_t from = net->set.n;
    cl_status rc = cl_pairs_append(&net->set, set, err);
    double *kk = rc ? NULL
                    : realloc(net->k, (net->set.n + 1) * sizeof *net->k);
    if (!rc && !kk)
        rc = cl_error_set(err, CL_ENOMEM, "out of memory (springs)");
    if (rc)
        return rc;
    net->k = kk;
    for (size_t i = from; i < net->set.n; i++)
        net->k[i] = k;
    return CL_OK;
}

/* The mesh network: the triangle edges (k_structural) and the bend pairs
 * (k_bend), each left out when its stiffness is 0. */
static cl_status mesh_network(const cl_cloth *c, const spring_opts *o,
                              cl_springnet *net, cl_error *err)
{
    cl_pairset edges = {0}, bend = {0};
    cl_status rc = CL_OK;
    *net = (cl_springnet){.k = NULL};
    if (o->ks > 0 && !(rc = cl_pairs_mesh_edges(c, &edges, err)))
        rc = add_set(net, &edges, o->ks, err);
    if (!rc && o->kbend > 0 && !(rc = cl_pairs_mesh_bend(c, &bend, err)))
        rc = add_set(net, &bend, o->kbend, err);
    cl_pairs_free(&edges);
    cl_pairs_free(&bend);
    if (rc)
        cl_springnet_free(net);
    return rc;
}

/* On a mesh cloth the grid's levels and shear springs do not exist. */
static cl_status check_mesh_keys(cl_config *cfg, const cl_cloth *c,
                                 const spring_opts *o, cl_error *err)
{
    cl_status rc = CL_OK;
    if (o->levels)
        rc = cl_cloth_grid_only(cfg, c, SEC, "levels",
                                "levels are grid offsets; a mesh cloth has "
                                "structural springs on its triangle edges "
                                "and bend springs across them (levels = 0)",
                                err);
    if (!rc && o->kshear > 0 && cl_config_string(cfg, SEC, "k_shear", NULL))
        rc = cl_cloth_grid_only(cfg, c, SEC, "k_shear",
                                "a mesh cloth has no shear springs (its "
                                "triangle edges are the structural springs): "
                                "remove k_shear or set it to 0", err);
    return rc;
}

static cl_status build_network(cl_config *cfg, const cl_cloth *c,
                               const spring_opts *o, cl_springnet *net,
                               cl_error *err)
{
    if (c->kind == CL_CLOTH_GRID)
        return grid_network(c, o, net, err);
    cl_status rc = check_mesh_keys(cfg, c, o, err);
    return rc ? rc : mesh_network(c, o, net, err);
}

cl_status cl_springs_network(cl_config *cfg, const cl_cloth *cloth,
                             cl_springnet *net, cl_error *err)
{
    spring_opts o;
    *net = (cl_springnet){.k = NULL};
    cl_status rc = read_opts(cfg, &o, err);
    return rc ? rc : build_network(cfg, cloth, &o, net, err);
}

void cl_springnet_free(cl_springnet *net)
{
    cl_pairs_free(&net->set);
    free(net->k);
    net->k = NULL;
}

/* ---- the springs term ------------------------------------------------- */

typedef struct {
    cl_pairterm pt; /* first member: the pairterm hooks use it */
    double *k;      /* per pair, owned */
} springs_state;

static void springs_law(const void *params, size_t k, double d, double L,
                        bool want_energy, bool want_ds,
                        cl_pairlaw *out)
{
    (void)want_ds; /* s' costs nothing here */
    const springs_state *st = params;
    double stretch = d - L;
    out->s = st->k[k] * stretch;
    out->ds = st->k[k];
    out->e = want_energy ? 0.5 * st->k[k] * stretch * stretch : 0.0;
}

/* The law over pairs [k0, k0 + m) (cl_pairlaw_batch_fn). */
CL_PAIR_KERNEL
static void springs_batch(const void *params, size_t k0, size_t m,
                          const double *d, const double *L, double *s,
                          double *ds)
{
    const springs_state *st = params;
    const double *restrict kk = st->k + k0, *restrict LL = L + k0;
#pragma omp simd
    for (size_t i = 0; i < m; i++)
        s[i] = kk[i] * (d[i] - LL[i]);
    for (size_t i = 0; ds && i < m; i++)
        ds[i] = kk[i];
}

static void springs_free(void *state)
{
    springs_state *st = state;
    if (!st)
        return;
    cl_pairterm_free(&st->pt);
    free(st->k);
    free(st);
}

/* Every spring is the distance constraint of its pair with stiffness k
 * (compliance 1/k: XPBD, projective dynamics). */
static size_t springs_distances(const void *state, const cl_pair **pair,
                                const double **k)
{
    const springs_state *st = state;
    *pair = st->pt.set.pair;
    *k = st->k;
    return st->pt.set.n;
}

/* The springs and their dashpots (spring-damping, evaluated next) in one
 * pass over the pairs, for forces alone (forces/term.h, fuse). */
static size_t springs_fuse(void *state, const cl_term_type *const *next,
                           void *const *next_state, size_t nnext,
                           cl_eval *ev)
{
    cl_pairterm *pt = state;
    return nnext >= 1 && next[0] == &cl_term_spring_damping &&
                   cl_pairdamp_fused(&pt, 1, next_state[0], ev)
               ? 1 : 0;
}

static cl_status springs_create(cl_config *cfg, const cl_cloth *cloth,
                                const cl_term_opts *opts, void **state,
                                cl_error *err)
{
    bool enabled;
    spring_opts o;
    cl_status rc;
    *state = NULL;
    if ((rc = cl_config_bool(cfg, SEC, "enabled", false, &enabled, err)) ||
        (rc = read_opts(cfg, &o, err)) || !enabled)
        return rc;
    springs_state *st = calloc(1, sizeof *st);
    if (!st)
        return cl_error_set(err, CL_ENOMEM, "out of memory (springs)");
    cl_springnet net;
    if ((rc = build_network(cfg, cloth, &o, &net, err))) {
        free(st);
        return rc;
    }
    st->k = net.k;
    if ((rc = cl_pairterm_init(&st->pt, net.set, springs_law,
                               springs_batch, st, opts->clamp_transverse, 1,
                               err)) ||
        (rc = cl_pairterm_tear(&st->pt, opts->tear_cut, err))) {
        springs_free(st);
        return rc;
    }
    st->pt.k_linear = st->k;
    *state = st;
    return CL_OK;
}

const cl_term_type cl_term_springs = {
    .name = "springs",
    .doc = "mass-spring cloth: linear springs k (d - L) on structural, "
           "shear, bend pairs or levels 1..k (Zischg, Chea and Aigner; "
           "Verlet-and-PBD report)",
    .conservative = true,
    .threads = cl_pairterm_threads,
    .create = springs_create,
    .couplings = cl_pairterm_couplings,
    .bind = cl_pairterm_bind,
    .eval = cl_pairterm_eval,
    .distances = springs_distances,
    .step_done = cl_pairterm_step_done,
    .broken = cl_pairterm_broken,
    .fuse = springs_fuse,
    .free = springs_free,
};
