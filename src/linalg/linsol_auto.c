/* auto: picks the linear solver for the reduced matrix (SPEC 1, 5)
 *
 *     A = M - a df/dv - b df/dx
 *
 * at every setup from A's diagonal dominance
 *
 *     rho = max over scalar rows r of  sum_{c != r} |A_rc| / A_rr
 *
 * (one pass over the block values; rho = inf if a diagonal entry is not
 * positive):
 *
 *   rho <= 1   pcg (3x3 block-Jacobi, linsol_pcg.c).  A symmetric A with a
 *              positive diagonal that is diagonally dominant is positive
 *              definite, and the preconditioned system is well conditioned
 *              (kappa <= (1 + rho) / (1 - rho) for point Jacobi; block
 *              Jacobi does at least as well in practice): the small steps
 *              of an accuracy-limited CVODE or IDA run, where A is close to
 *              M and pcg needs one or two iterations per solve;
 *   otherwise  cholmod (linsol_cholmod.c), which itself hands a setup whose
 *              A is not symmetric positive definite to klu: the large steps
 *              of semi-implicit methods or stiff transients.
 *
 * A pcg setup or solve that fails (A not positive definite after all, no
 * convergence within lin_maxit) is not an error: the same A is factorised
 * by cholmod (or klu) and the solve repeated; such fallbacks are counted in
 * cl_stats.lin_fallbacks.  For this, dfdx and dfdv must keep their values
 * from a setup to the last solve of that setup (every integrator here only
 * re-evaluates them before a setup).
 *
 * The solvers are created when first needed (pcg at create, cholmod at the
 * first direct setup: one allocation and one symbolic analysis in the life
 * of the solver) and kept.  Statistics are the sum of theirs; linsol says
 * what auto picked: "auto:pcg", "auto:pcg+cholmod", "auto:cholmod+klu", ...
 * in the order pcg, cholmod, klu. */
#include "linalg/linsol.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CL_AUTO_RHO_PCG 1.0

extern const cl_linsol_type cl_linsol_pcg;
extern const cl_linsol_type cl_linsol_cholmod;

typedef struct {
    const cl_bpattern *pat;     /* borrowed */
    cl_integrator_opts opts;    /* copy (for the direct solver) */
    double *mass;               /* 3 nb */
    void *pcg, *direct;         /* direct: cholmod, NULL until needed */
    bool use_pcg;               /* the current setup is pcg's */
    bool ready;                 /* the current setup succeeded */
    bool used_pcg, used_direct;
    /* the current setup, for a fallback from a failed pcg solve */
    double a, b;
    const double *dfdx, *dfdv;
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
    free(s->mass);
    free(s);
}

static cl_status auto_create(const cl_bpattern *pat, const double *mass,
                             const cl_integrator_opts *opts, void **state,
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
    *state = s;
    return CL_OK;
}

/* rho of the header. */
static double auto_dominance(const cl_auto *s, double a, double b,
                             const double *dfdx, const double *dfdv)
{
    const cl_bpattern *p = s->pat;
    double rho = 0.0;
    for (size_t bi = 0; bi < p->nb; bi++) {
        double off[3] = {0, 0, 0}, dia[3] = {0, 0, 0};
        for (size_t k = p->rowptr[bi]; k < p->rowptr[bi + 1]; k++) {
            for (size_t q = 0; q < 9; q++) {
                double v = -a * dfdv[9 * k + q] - b * dfdx[9 * k + q];
                if (k == p->diag[bi] && q % 4 == 0)
                    dia[q / 4] = v + s->mass[3 * bi + q / 4];
                else
                    off[q / 3] += fabs(v);
            }
        }
        for (size_t r = 0; r < 3; r++)
            rho = dia[r] > 0.0 ? fmax(rho, off[r] / dia[r]) : INFINITY;
        if (!(rho <= CL_AUTO_RHO_PCG))
            return rho; /* decided */
    }
    return rho;
}

/* The current A goes to the direct solver. */
static cl_status auto_direct(cl_auto *s, cl_error *err)
{
    s->use_pcg = false;
    s->used_direct = true;
    if (!s->direct) {
        cl_status st = cl_linsol_cholmod.create(s->pat, s->mass, &s->opts,
                                                &s->direct, err);
        if (st != CL_OK)
            return st;
    }
    return cl_linsol_cholmod.setup(s->direct, s->a, s->b, s->dfdx, s->dfdv,
                                   err);
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
    cl_status st = CL_ESOLVER;
    if (auto_dominance(s, a, b, dfdx, dfdv) <= CL_AUTO_RHO_PCG) {
        st = cl_linsol_pcg.setup(s->pcg, a, b, dfdx, dfdv, err);
        if (st != CL_OK && st != CL_ESOLVER)
            return st;
        s->use_pcg = st == CL_OK;
        s->used_pcg |= s->use_pcg;
        s->fallbacks += st != CL_OK;
    }
    if (st != CL_OK)
        st = auto_direct(s, err);
    s->ready = st == CL_OK;
    return st;
}

/* A pcg solve (with w: to ||w .* r||_2 <= delta) falling back to the
 * direct solver if it fails. */
static cl_status auto_solve_any(cl_auto *s, const double *rhs, double *x,
                                const double *w, double delta, cl_error *err)
{
    if (!s->ready)
        return cl_error_set(err, CL_EINVAL, "auto: solve without a "
                            "successful setup");
    if (s->use_pcg) {
        cl_status st = w ? cl_linsol_pcg.solve_tol(s->pcg, rhs, x, w, delta,
                                                   err)
                         : cl_linsol_pcg.solve(s->pcg, rhs, x, err);
        if (st != CL_ESOLVER)
            return st;
        s->fallbacks++;
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
    if (s->direct)
        cl_linsol_cholmod.stats(s->direct, &d);
    out->lin_setups += d.lin_setups;
    out->lin_solves += d.lin_solves;
    out->symbolic_facts += d.symbolic_facts;
    out->lin_fallbacks += d.lin_fallbacks + s->fallbacks;
    snprintf(out->linsol, sizeof out->linsol, "auto:%s%s%.20s",
             s->used_pcg ? "pcg" : "",
             s->used_pcg && s->used_direct ? "+" : "",
             s->used_direct ? d.linsol : "");
}

const cl_linsol_type cl_linsol_auto = {
    .name = "auto",
    .doc = "pcg when A is diagonally dominant, else cholmod (klu if not "
           "SPD); falls back to direct when pcg fails",
    .create = auto_create,
    .setup = auto_setup,
    .solve = auto_solve,
    .solve_tol = auto_solve_tol,
    .stats = auto_stats,
    .free = auto_free,
};
