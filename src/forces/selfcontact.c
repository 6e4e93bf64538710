/* Self-contact (docs/model.md 3.5; equations and keys in
 * forces/selfcontact.h). */
#include "forces/selfcontact.h"

#include <math.h>
#include <stdlib.h>

#include "forces/logbarrier.h"
#include "forces/pairterm.h"
#include "forces/sphash.h"
#include "model/ring.h"

#define SEC "selfcontact"

typedef enum { SC_PENALTY, SC_BARRIER } sc_law;

typedef struct {
    const cl_cloth *cloth;
    double h, k;           /* thickness (m), stiffness (N/m) */
    sc_law law;
    cl_ring ring;
    cl_sphash hash;
    long *diag;            /* np: slot of each particle's diagonal block,
                            * -1 if it carries no unknowns */
} sc_state;

/* One pass over the close pairs: what it adds and where. */
typedef struct {
    const sc_state *st;
    const double *x;
    double *f;             /* forces, or NULL */
    double *dfdx;          /* pattern values (diagonal blocks), or NULL */
    double *dense;         /* dense exact Jacobian, or NULL */
    double energy;         /* sum of E */
    double closest;        /* smallest d */
} sc_pass;

/* The scalar law at distance d < h_s: E(d), s(d) = E'(d) (the force on a
 * is s u) and s'(d): the penalty (3.4)-(3.5) or k_s times the barrier
 * (3.7). */
static void pair_law(const sc_state *st, double d, double *e, double *s,
                     double *ds)
{
    if (st->law == SC_BARRIER) {
        cl_logbarrier b = cl_logbarrier_eval(d, st->h);
        *e = st->k * b.b;
        *s = st->k * b.db;
        *ds = st->k * b.d2b;
        return;
    }
    double gap = st->h - d;
    *e = 0.5 * st->k * gap * gap;
    *s = -st->k * gap;
    *ds = st->k;
}

/* The block K of pair (a, b) at distance d > 0, direction u: exact, or
 * (lumped) its normal part s'(d) u u^T alone (docs/model.md 3.5). */
static void pair_block(const double u[3], double d, double s, double ds,
                       bool normal_only, double K[9])
{
    cl_pair_block(u, d, normal_only ? 0.0 : s, ds, false, K);
}

/* Add sign * K into the dense n x n matrix at block (a, b). */
static void dense_add(double *J, size_t n, int a, int b, double sign,
                      const double K[9])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            J[(3 * (size_t)a + r) * n + 3 * (size_t)b + c] +=
                sign * K[3 * r + c];
}

static void add_blocks(sc_pass *p, int a, int b, const double u[3],
                       double d, double s, double ds)
{
    double K[9];
    if (p->dfdx) {
        pair_block(u, d, s, ds, true, K);
        cl_block_add(p->dfdx, p->st->diag[a], -1.0, K);
        cl_block_add(p->dfdx, p->st->diag[b], -1.0, K);
    }
    if (p->dense) {
        pair_block(u, d, s, ds, false, K);
        size_t n = 3 * p->st->cloth->np;
        dense_add(p->dense, n, a, a, -1.0, K);
        dense_add(p->dense, n, b, b, -1.0, K);
        dense_add(p->dense, n, a, b, 1.0, K);
        dense_add(p->dense, n, b, a, 1.0, K);
    }
}

/* cl_sphash_visit: one pair closer than the thickness.  Coincident
 * particles (d = 0) have no direction: no force and no blocks. */
static void visit(void *ctx, int a, int b, double d2)
{
    sc_pass *p = ctx;
    const sc_state *st = p->st;
    if (cl_ring_has(&st->ring, a, b))
        return;
    double d = sqrt(d2), e, s, ds;
    if (d < p->closest)
        p->closest = d;
    pair_law(st, d, &e, &s, &ds);
    p->energy += e;
    if (!(d > 0))
        return;
    const double *xa = p->x + 3 * (size_t)a, *xb = p->x + 3 * (size_t)b;
    double u[3] = {(xb[0] - xa[0]) / d, (xb[1] - xa[1]) / d,
                   (xb[2] - xa[2]) / d};
    if (p->f)
        cl_pair_scatter(p->f, &(cl_pair){.a = a, .b = b}, s * u[0],
                        s * u[1], s * u[2]);
    if (p->dfdx || p->dense)
        add_blocks(p, a, b, u, d, s, ds);
}

static sc_pass run_pass(sc_state *st, const double *x, double *f,
                        double *dfdx, double *dense)
{
    sc_pass p = {.st = st, .x = x, .f = f, .dfdx = dfdx, .dense = dense,
                 .closest = INFINITY};
    cl_sphash_build(&st->hash, x);
    cl_sphash_pairs(&st->hash, x, visit, &p);
    return p;
}

static void sc_eval(void *state, cl_eval *ev)
{
    sc_pass p = run_pass(state, ev->x, ev->f, ev->dfdx, NULL);
    if (ev->want_energy) {
        ev->energy = p.energy;
        ev->power = 0.0;
    }
}

double cl_selfcontact_closest(void *state, const double *x)
{
    return run_pass(state, x, NULL, NULL, NULL).closest;
}

void cl_selfcontact_dense(void *state, const double *x, double *J)
{
    run_pass(state, x, NULL, NULL, J);
}

/* The pairs change at every evaluation: none is fixed in the pattern. */
static size_t sc_couplings(const void *state, const int (**pairs)[2])
{
    (void)state;
    *pairs = NULL;
    return 0;
}

static cl_status sc_bind(void *state, const cl_bpattern *pat, const int *dof,
                         cl_error *err)
{
    sc_state *st = state;
    (void)err;
    for (size_t p = 0; p < st->cloth->np; p++)
        st->diag[p] = dof[p] >= 0 ? (long)pat->diag[dof[p]] : -1;
    return CL_OK;
}

static void sc_free(void *state)
{
    sc_state *st = state;
    if (!st)
        return;
    cl_ring_free(&st->ring);
    cl_sphash_free(&st->hash);
    free(st->diag);
    free(st);
}

/* At rest no pair outside the ring may be closer than the thickness. */
static cl_status check_rest(cl_config *cfg, sc_state *st, cl_error *err)
{
    double d = cl_selfcontact_closest(st, st->cloth->X0);
    if (isinf(d))
        return CL_OK;
    char where[256];
    return cl_error_set(err, CL_EINVAL,
                        "%s: [selfcontact] thickness = %g m: particles more "
                        "than ring = %d steps apart are %g m apart in the "
                        "rest shape; the thickness must be smaller (or ring "
                        "larger)",
                        cl_config_origin(cfg, SEC, "thickness", where,
                                         sizeof where),
                        st->h, st->ring.ring, d);
}

/* The keys are read (and so known) even when the term is off. */
static cl_status read_keys(cl_config *cfg, bool enabled, sc_state *st,
                           long *ring, cl_error *err)
{
    static const char *const laws[] = {"penalty", "barrier", NULL};
    int law;
    cl_status rc;
    if ((rc = cl_config_double(cfg, SEC, "thickness", NAN, 1e-300, INFINITY,
                               &st->h, err)) ||
        (rc = cl_config_double(cfg, SEC, "stiffness", NAN, 1e-300, INFINITY,
                               &st->k, err)) ||
        (rc = cl_config_long(cfg, SEC, "ring", 2, 1, 8, ring, err)) ||
        (rc = cl_config_choice(cfg, SEC, "law", laws, 0, &law, err)))
        return rc;
    st->law = law == 1 ? SC_BARRIER : SC_PENALTY;
    if (enabled && (isnan(st->h) || isnan(st->k)))
        return cl_error_set(err, CL_EINVAL, "[selfcontact] enabled = true "
                            "needs thickness (m, > 0) and stiffness (N/m, "
                            "> 0)");
    return CL_OK;
}

static cl_status sc_create(cl_config *cfg, const cl_cloth *cloth,
                           const cl_term_opts *opts, void **state,
                           cl_error *err)
{
    bool enabled;
    long ring;
    sc_state keys, *st;
    cl_status rc;
    *state = NULL;
    if ((rc = cl_config_bool(cfg, SEC, "enabled", false, &enabled, err)) ||
        (rc = read_keys(cfg, enabled, &keys, &ring, err)) || !enabled)
        return rc;
    if (!(st = calloc(1, sizeof *st)))
        return cl_error_set(err, CL_ENOMEM, "out of memory (self-contact)");
    st->cloth = cloth;
    st->h = keys.h;
    st->k = keys.k;
    st->law = keys.law;
    (void)opts; /* the lumped blocks drop the transverse part anyway */
    st->diag = malloc((cloth->np + 1) * sizeof *st->diag);
    if (!st->diag)
        rc = cl_error_set(err, CL_ENOMEM, "out of memory (self-contact)");
    if (rc || (rc = cl_ring_build(cloth, (int)ring, &st->ring, err)) ||
        (rc = cl_sphash_init(&st->hash, cloth->np, st->h, err)) ||
        (rc = check_rest(cfg, st, err))) {
        sc_free(st);
        return rc;
    }
    *state = st;
    return CL_OK;
}

const cl_term_type cl_term_selfcontact = {
    .name = "selfcontact",
    .doc = "self-contact: penalty k_s (h_s - d) or IPC's log barrier "
           "between particles more than `ring` steps apart and closer "
           "than h_s (spatial hash; lumped Jacobian)",
    .conservative = true,
    .create = sc_create,
    .couplings = sc_couplings,
    .bind = sc_bind,
    .eval = sc_eval,
    .free = sc_free,
};
