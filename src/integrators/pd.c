/* pd: projective dynamics (Bouaziz, Martin, Liu, Kavan and Pauly,
 * "Projective dynamics: fusing constraint projections for fast
 * simulation", SIGGRAPH 2014) on the distance constraints of the system
 * (system/system.h, cl_distances); docs/integrators.md, 9.
 *
 * A substep of h (constraint_common.h: predictor with the other forces,
 * inertial target y, anchors at t + h) minimises
 *
 *   g(x) = |x - y|_M^2 / (2 h^2) + sum_j k_j |x_a - x_b - p_j|^2 / 2
 *
 * over x and the projections p_j onto |p| = L_j (their eqs. 9-14): the
 * spring energy k (d - L)^2 / 2 is min_p of the second sum, so the
 * minimiser in x is backward Euler of the springs with the other forces
 * explicit.  K alternations of
 *
 *   local   p_j = L_j (x_a - x_b) / |x_a - x_b|
 *   global  (M / h^2 + sum_j k_j A_j^T A_j) x = M y / h^2 + sum_j k_j A_j^T p_j,
 *
 * A_j x = x_a - x_b, an anchored end's known position moved to the right-
 * hand side (pins eliminated).  The matrix acts on each coordinate alike,
 * so it is one nfree x nfree SPD matrix, constant for a fixed h: factored
 * once by CHOLMOD (supernodal Cholesky) at create, each global step one
 * solve with three right-hand sides into storage kept from the first.
 * Hard constraints (the pbd term) have no finite weight and are refused.
 * Default K = 10. */
#include "integrators/constraint_common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>

typedef struct {
    cholmod_common c;
    bool started;
    cholmod_factor *L;
    cholmod_dense *B, *X, *Y, *E; /* nfree x 3 right-hand side, solution,
                                   * and solve2's workspace */
} pd_state;

static void pd_free(void *own)
{
    pd_state *p = own;
    if (p->started) {
        cholmod_l_free_factor(&p->L, &p->c);
        cholmod_l_free_dense(&p->B, &p->c);
        cholmod_l_free_dense(&p->X, &p->c);
        cholmod_l_free_dense(&p->Y, &p->c);
        cholmod_l_free_dense(&p->E, &p->c);
        cholmod_l_finish(&p->c);
    }
    free(p);
}

static cl_status pd_fail(pd_state *p, const char *fn, cl_error *err)
{
    return cl_error_set(err, CL_ESOLVER, "pd: %s failed (CHOLMOD status "
                        "%d)", fn, p->c.status);
}

/* Entry (i, j) of the upper triangle, value v, into the triplet T. */
static void add_entry(cholmod_triplet *T, int i, int j, double v)
{
    SuiteSparse_long *ti = T->i, *tj = T->j;
    double *tx = T->x;
    ti[T->nnz] = i < j ? i : j;
    tj[T->nnz] = i < j ? j : i;
    tx[T->nnz++] = v;
}

/* The global matrix M / h^2 + sum_j k_j A_j^T A_j over the free particles
 * (duplicates summed by the conversion to a sparse matrix). */
static cholmod_sparse *pd_matrix(pd_state *p, const cl_cdyn *s)
{
    const cl_distances *dc = s->dc;
    size_t nf = s->n / 3;
    cholmod_triplet *T = cholmod_l_allocate_triplet(
        nf, nf, nf + 3 * dc->n, 1, CHOLMOD_REAL, &p->c);
    if (!T)
        return NULL;
    for (size_t i = 0; i < nf; i++)
        add_entry(T, (int)i, (int)i, s->sys->mass[3 * i] / (s->h * s->h));
    for (size_t j = 0; j < dc->n; j++) {
        int a = dc->end[j][0], b = dc->end[j][1];
        double k = dc->stiffness[j];
        if (a >= 0)
            add_entry(T, a, a, k);
        if (b >= 0)
            add_entry(T, b, b, k);
        if (a >= 0 && b >= 0)
            add_entry(T, a, b, -k);
    }
    cholmod_sparse *A = cholmod_l_triplet_to_sparse(T, 0, &p->c);
    cholmod_l_free_triplet(&T, &p->c);
    return A;
}

static cl_status pd_factor(pd_state *p, const cl_cdyn *s, cl_error *err)
{
    size_t nf = s->n / 3;
    cholmod_sparse *A = pd_matrix(p, s);
    if (!A)
        return pd_fail(p, "building the matrix", err);
    p->L = cholmod_l_analyze(A, &p->c);
    bool ok = p->L && cholmod_l_factorize(A, p->L, &p->c) &&
              p->c.status == CHOLMOD_OK;
    cholmod_l_free_sparse(&A, &p->c);
    if (!ok)
        return pd_fail(p, "cholmod_l_analyze/factorize", err);
    p->B = cholmod_l_zeros(nf, 3, CHOLMOD_REAL, &p->c);
    return p->B ? CL_OK : pd_fail(p, "cholmod_l_zeros", err);
}

static cl_status pd_setup(cl_cdyn *s, cl_error *err)
{
    for (size_t j = 0; j < s->dc->n; j++)
        if (!isfinite(s->dc->stiffness[j]))
            return cl_error_set(err, CL_EINVAL, "pd needs springs of finite "
                                "stiffness; the pbd term's constraints are "
                                "hard (set pbd.enabled = false)");
    pd_state *p = calloc(1, sizeof *p);
    if (!p)
        return cl_error_set(err, CL_ENOMEM, "pd: out of memory");
    s->own = p;
    if (!cholmod_l_start(&p->c))
        return pd_fail(p, "cholmod_l_start", err);
    p->started = true;
    p->c.print = 0;
    p->c.supernodal = CHOLMOD_SUPERNODAL;
    s->lin_setups = 1;
    return pd_factor(p, s, err);
}

/* Constraint j's term k_j A_j^T p_j of the right-hand side (B, nf x 3,
 * column-major), with p_j from the local step; an anchored end's position
 * moves to the right-hand side of the other end. */
static void pd_local(cl_cdyn *s, size_t j, double *B, size_t nf)
{
    const int *e = s->dc->end[j];
    const double *xa = cl_cdyn_pos(s, e[0]), *xb = cl_cdyn_pos(s, e[1]);
    double k = s->dc->stiffness[j];
    double dx[3] = {xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]};
    double d = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    double scale = d > 0 ? s->dc->rest[j] / d : 0.0;
    for (int i = 0; i < 3; i++) {
        double kp = k * scale * dx[i];
        if (e[0] >= 0)
            B[(size_t)e[0] + nf * i] += kp + (e[1] < 0 ? k * xb[i] : 0.0);
        if (e[1] >= 0)
            B[(size_t)e[1] + nf * i] += -kp + (e[0] < 0 ? k * xa[i] : 0.0);
    }
}

static cl_status pd_iteration(cl_cdyn *s, pd_state *p, cl_error *err)
{
    size_t nf = s->n / 3;
    double *B = p->B->x, c = 1.0 / (s->h * s->h);
    for (size_t q = 0; q < nf; q++)
        for (int i = 0; i < 3; i++)
            B[q + nf * i] = s->sys->mass[3 * q] * c * s->y[3 * q + i];
    for (size_t j = 0; j < s->dc->n; j++)
        pd_local(s, j, B, nf);
    if (!cholmod_l_solve2(CHOLMOD_A, p->L, p->B, NULL, &p->X, NULL, &p->Y,
                          &p->E, &p->c))
        return pd_fail(p, "cholmod_l_solve2", err);
    s->lin_solves++;
    const double *X = p->X->x;
    for (size_t q = 0; q < nf; q++)
        for (int i = 0; i < 3; i++)
            s->x[3 * q + i] = X[q + nf * i];
    return CL_OK;
}

static cl_status pd_solve(cl_cdyn *s, double t, double h, cl_error *err)
{
    (void)t, (void)h;
    cl_status st = CL_OK;
    for (long it = 0; st == CL_OK && it < s->iterations; it++)
        st = pd_iteration(s, s->own, err);
    return st;
}

static const cl_cdyn_method pd_method = {
    .name = "pd",
    .default_iterations = 10,
    .setup = pd_setup,
    .solve = pd_solve,
    .free = pd_free,
};

CL_CDYN_INTEGRATOR(cl_integrator_pd, pd_method, "pd",
                   "projective dynamics (Bouaziz et al.) on the springs: "
                   "global matrix factored once by CHOLMOD, iterations K, "
                   "substeps S, fixed step dt");
