/* auto: picks the linear solver for the reduced matrix
 * (docs/model.md, 1; docs/integrators.md, 5)
 *
 *     A = M - a df/dv - b df/dx
 *
 * setup by setup, by cost:
 *
 *   pcg       (3x3 block-Jacobi, linsol_pcg.c) by default.  At CVODE's and
 *             IDA's small steps A is close to M and a solve costs one or two
 *             block products (1.0-1.2 iterations per solve on hang at n =
 *             16..64 with the integrator's tolerance);
 *   amg       (GAMG-preconditioned CG, linsol_amg.c, on PETSc's plug-in)
 *             in pcg's place for the rest of the run once a pcg setup's
 *             solves took more than CL_AUTO_AMG_ITERS iterations each.  The
 *             multigrid cycle costs about CL_AUTO_AMG_ITER_COST products
 *             per iteration but keeps the iterations nearly flat in the
 *             size, so it pays where block Jacobi's iterations have grown
 *             (paper/findings.md "Algebraic multigrid", semi-bdf2 per
 *             step: 1.2-2.0x pcg wherever pcg took 190-930 iterations a
 *             solve, on hang at n = 64-256 and bw-hang at n = 128; a tie,
 *             0.94-1.10x, at 69-117); without the plug-in pcg stays;
 *   cholmod   (linsol_cholmod.c, which itself hands a setup whose A is not
 *             symmetric positive definite to klu) for the next
 *             CL_AUTO_DIRECT setups when the last pcg setup cost more than
 *             a factorisation and the same number of direct solves would
 *             have; then pcg is tried again.
 *
 * Costs are counted in products with A (18 flops per stored block): a pcg
 * iteration CL_AUTO_ITER_COST products (the product, the preconditioner and
 * SUNDIALS' vector operations; an amg one CL_AUTO_AMG_ITER_COST); a CHOLMOD factorisation and solve their
 * flops from the analysis (cl_linsol_type.cost) times CL_AUTO_FLOP_RATIO,
 * CHOLMOD's flop rate with Debian's reference BLAS being about a quarter of
 * the block product's (measured on hang: factorisation 0.7-1.4 GFlop/s,
 * solves 1.0, products 4.4).  The comparison (pcg's iterations of the last
 * setup against factorisation + as many direct solves as that setup had)
 * is made once the last setup needed more than CL_AUTO_PROBE iterations per
 * solve; CHOLMOD's analysis is run then, once.  On hang at n = 16 the
 * break-even is ~34 iterations per solve with 20 solves per setup (CVODE at
 * large steps) and ~350 with one solve per setup (semi-be).
 *
 * A pcg (or amg) setup or solve that fails (A not positive definite, no
 * convergence within lin_maxit) is not an error: the same A is factorised by
 * cholmod (or klu) and the solve repeated, and the next CL_AUTO_DIRECT
 * setups go direct too; such fallbacks are counted in
 * cl_stats.lin_fallbacks.  For this, dfdx and dfdv must keep their values
 * from a setup to the last solve of that setup (every integrator here only
 * re-evaluates them before a setup).  The choice depends on counts only,
 * never on timings, so runs are reproducible.
 *
 * The solvers are created when first needed (pcg at create, cholmod at the
 * first direct setup or cost comparison: one allocation and one symbolic
 * analysis in the life of the solver) and kept.  Statistics are the sum of
 * theirs; linsol says what auto used: "auto:pcg", "auto:pcg+cholmod",
 * "auto:pcg+amg", "auto:pcg+cholmod+klu" (in the order pcg, amg, cholmod,
 * klu). */
#include "linalg/linsol.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CL_AUTO_PROBE 20        /* iterations per solve: compare costs */
#define CL_AUTO_ITER_COST 1.3   /* products with A per pcg iteration */
#define CL_AUTO_FLOP_RATIO 4.0  /* CHOLMOD's flops cost this many of ours */
#define CL_AUTO_DIRECT 16       /* direct setups before pcg is tried again */
#define CL_AUTO_AMG_ITERS 150   /* pcg iterations per solve: go to amg */
/* products with A per amg iteration: 3.4-4.8 pcg iterations, its setup
 * share included (semi-bdf2 on hang, n = 64-256, paper/findings.md,
 * "Algebraic multigrid", workload 10), times CL_AUTO_ITER_COST */
#define CL_AUTO_AMG_ITER_COST 6.0

extern const cl_linsol_type cl_linsol_pcg;
extern const cl_linsol_type cl_linsol_amg;
extern const cl_linsol_type cl_linsol_cholmod;

typedef struct {
    const cl_bpattern *pat;     /* borrowed */
    cl_linsol_opts opts;    /* copy (for the direct solver) */
    double *mass;               /* 3 nb */
    void *pcg, *direct;         /* direct: cholmod, NULL until needed */
    void *amg;                  /* NULL until pcg's solves grow long */
    const cl_linsol_type *it;   /* the iterative solver: pcg, then amg */
    void *its;                  /* its state (s->pcg or s->amg) */
    bool no_amg;                /* amg could not be created: keep pcg */
    bool use_iter;               /* the current setup is the iterative one's */
    bool ready;                 /* the current setup succeeded */
    bool used_pcg, used_amg, used_direct;
    /* the current setup, for a fallback from a failed pcg solve */
    double a, b;
    const double *dfdx, *dfdv;
    long direct_left;           /* setups still to go to the direct solver */
    long solves0, iters0;       /* s->it's counters at the current setup */
    long fallbacks;
} cl_auto;

static void auto_free(void *state)
{
    cl_auto *s = state;
    if (!s)
        return;
    if (s->pcg)
        cl_linsol_pcg.free(s->pcg);
    if (s->direct)
        cl_linsol_cholmod.free(s->direct);
    if (s->amg)
        cl_linsol_amg.free(s->amg);
    free(s->mass);
    free(s);
}

static cl_status auto_create(const cl_bpattern *pat, const double *mass,
                             const cl_linsol_opts *opts, void **state,
                             cl_error *err)
{
    *state = NULL;
    if (!pat || pat->nb == 0)
        return cl_error_set(err, CL_EINVAL, "auto: empty system (no free "
                            "particles)");
    cl_auto *s = calloc(1, sizeof *s);
    if (!s)
        return cl_error_set(err, CL_ENOMEM, "auto: out of memory");
    s->pat = pat;
    s->opts = *opts;
    s->mass = malloc(3 * pat->nb * sizeof *s->mass);
    cl_status st = s->mass ? cl_linsol_pcg.create(pat, mass, opts, &s->pcg,
                                                  err)
                           : cl_error_set(err, CL_ENOMEM, "auto: out of "
                                          "memory");
    if (st != CL_OK) {
        auto_free(s);
        return st;
    }
    memcpy(s->mass, mass, 3 * pat->nb * sizeof *s->mass);
    s->it = &cl_linsol_pcg;
    s->its = s->pcg;
    *state = s;
    return CL_OK;
}

static cl_status auto_make_direct(cl_auto *s, cl_error *err)
{
    if (s->direct)
        return CL_OK;
    return cl_linsol_cholmod.create(s->pat, s->mass, &s->opts, &s->direct,
                                    err);
}

/* Would the last pcg setup (solves solves, iters iterations) have been
 * cheaper direct?  Costs in products with A (see the header). */
static bool auto_direct_cheaper(const cl_auto *s, long solves, long iters)
{
    double fact, solve, product = 18.0 * (double)s->pat->nnzb;
    cl_linsol_cholmod.cost(s->direct, &fact, &solve);
    double direct = CL_AUTO_FLOP_RATIO * (fact + (double)solves * solve);
    double per_iter = s->it == &cl_linsol_amg ? CL_AUTO_AMG_ITER_COST
                                              : CL_AUTO_ITER_COST;
    return direct / product < per_iter * (double)iters;
}

/* From pcg to amg for the rest of the run (told of the current Jacobian,
 * the arrays of this setup); without PETSc's plug-in, pcg stays. */
static void auto_to_amg(cl_auto *s)
{
    cl_error ignored = {0};
    if (cl_linsol_amg.create(s->pat, s->mass, &s->opts, &s->amg,
                             &ignored) != CL_OK) {
        s->amg = NULL;
        s->no_amg = true;
        return;
    }
    cl_linsol_jacobian(&cl_linsol_amg, s->amg, s->dfdx, s->dfdv);
    s->it = &cl_linsol_amg;
    s->its = s->amg;
    s->solves0 = 0;
    s->iters0 = 0;
}

/* Close the books of the previous setup: if it was an iterative one whose
 * pcg solves took more than CL_AUTO_AMG_ITERS iterations each, amg takes
 * over; if a factorisation would have done it cheaper, the next
 * CL_AUTO_DIRECT setups go direct. */
static cl_status auto_review(cl_auto *s, cl_error *err)
{
    cl_stats p = {0};
    s->it->stats(s->its, &p);
    long solves = p.lin_solves - s->solves0, iters = p.lin_iters - s->iters0;
    s->solves0 = p.lin_solves;
    s->iters0 = p.lin_iters;
    if (!s->use_iter || solves == 0 || iters <= CL_AUTO_PROBE * solves)
        return CL_OK;
    if (s->it == &cl_linsol_pcg && !s->no_amg &&
        iters > CL_AUTO_AMG_ITERS * solves) {
        auto_to_amg(s);
        if (s->amg)
            return CL_OK;
    }
    cl_status st = auto_make_direct(s, err);
    if (st == CL_OK && auto_direct_cheaper(s, solves, iters))
        s->direct_left = CL_AUTO_DIRECT;
    return st;
}

/* pcg failed on the current A: count it, and go direct for a while. */
static void auto_fell_back(cl_auto *s)
{
    s->fallbacks++;
    s->direct_left = CL_AUTO_DIRECT;
}

/* The current A goes to the direct solver. */
static cl_status auto_direct(cl_auto *s, cl_error *err)
{
    s->use_iter = false;
    s->used_direct = true;
    cl_status st = auto_make_direct(s, err);
    if (st != CL_OK)
        return st;
    return cl_linsol_cholmod.setup(s->direct, s->a, s->b, s->dfdx, s->dfdv,
                                   err);
}

/* Only the iterative solver listens (the direct solvers do not exploit
 * symmetry). */
static void auto_jacobian(void *state, const double *dfdx, const double *dfdv)
{
    cl_auto *s = state;
    cl_linsol_jacobian(s->it, s->its, dfdx, dfdv);
}

static cl_status auto_setup(void *state, double a, double b,
                            const double *dfdx, const double *dfdv,
                            cl_error *err)
{
    cl_auto *s = state;
    s->a = a;
    s->b = b;
    s->dfdx = dfdx;
    s->dfdv = dfdv;
    s->ready = false;
    cl_status st = auto_review(s, err);
    if (st != CL_OK)
        return st;
    s->use_iter = false;
    st = CL_ESOLVER;
    if (s->direct_left > 0) {
        s->direct_left--;
    } else {
        st = s->it->setup(s->its, a, b, dfdx, dfdv, err);
        if (st != CL_OK && st != CL_ESOLVER)
            return st;
        s->use_iter = st == CL_OK;
        s->used_pcg |= s->use_iter && s->it == &cl_linsol_pcg;
        s->used_amg |= s->use_iter && s->it == &cl_linsol_amg;
        if (st != CL_OK)
            auto_fell_back(s);
    }
    if (st != CL_OK)
        st = auto_direct(s, err);
    s->ready = st == CL_OK;
    return st;
}

/* An iterative solve (with w: to ||w .* r||_2 <= delta) falling back to
 * the direct solver if it fails. */
static cl_status auto_solve_any(cl_auto *s, const double *rhs, double *x,
                                const double *w, double delta, cl_error *err)
{
    if (!s->ready)
        return cl_error_set(err, CL_EINVAL, "auto: solve without a "
                            "successful setup");
    if (s->use_iter) {
        cl_status st = w ? s->it->solve_tol(s->its, rhs, x, w, delta, err)
                         : s->it->solve(s->its, rhs, x, err);
        if (st != CL_ESOLVER)
            return st;
        auto_fell_back(s);
        if ((st = auto_direct(s, err)) != CL_OK) {
            s->ready = false;
            return st;
        }
    }
    return cl_linsol_cholmod.solve(s->direct, rhs, x, err);
}

static cl_status auto_solve(void *state, const double *rhs, double *x,
                            cl_error *err)
{
    return auto_solve_any(state, rhs, x, NULL, 0.0, err);
}

static cl_status auto_solve_tol(void *state, const double *rhs, double *x,
                                const double *w, double delta, cl_error *err)
{
    return auto_solve_any(state, rhs, x, w, delta, err);
}

static void auto_stats(const void *state, cl_stats *out)
{
    const cl_auto *s = state;
    cl_stats d = {0};
    cl_linsol_pcg.stats(s->pcg, out);
    if (s->amg)
        cl_linsol_amg.stats(s->amg, &d);
    if (s->direct)
        cl_linsol_cholmod.stats(s->direct, &d);
    out->lin_setups += d.lin_setups;
    out->lin_solves += d.lin_solves;
    out->lin_iters += d.lin_iters;
    out->symbolic_facts += d.symbolic_facts;
    out->lin_fallbacks += d.lin_fallbacks + s->fallbacks;
    out->lin_recoveries += d.lin_recoveries;
    snprintf(out->linsol, sizeof out->linsol, "auto:%s%s%s%s%.18s",
             s->used_pcg ? "pcg" : "",
             s->used_pcg && s->used_amg ? "+" : "",
             s->used_amg ? "amg" : "",
             (s->used_pcg || s->used_amg) && s->used_direct ? "+" : "",
             s->used_direct ? d.linsol : "");
}

const cl_linsol_type cl_linsol_auto = {
    .name = "auto",
    .factors = 2, /* cholmod, or klu when A is not SPD */
    .doc = "pcg (amg once pcg's solves grow long), or cholmod (klu if "
           "not SPD) while a factorisation is cheaper or after a failure",
    .create = auto_create,
    .jacobian = auto_jacobian,
    .setup = auto_setup,
    .solve = auto_solve,
    .solve_tol = auto_solve_tol,
    .stats = auto_stats,
    .free = auto_free,
};
