/* The reduced Newton matrix in the Krylov solvers' storage (amat.h). */
#include "linalg/amat.h"

#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "linalg/reduced.h"

cl_status cl_amat_init(cl_amat *m, const char *who, const cl_bpattern *pat,
                       const double *mass, int threads, cl_error *err)
{
    *m = (cl_amat){.pat = pat, .n = 3 * pat->nb, .threads = threads};
    cl_status st = cl_bsym_create(pat, &m->sym, err);
    if (st == CL_OK && threads > 1)
        st = cl_bsym_transpose(&m->sym, err);
    if (st != CL_OK)
        return st;
    m->mass = malloc(m->n * sizeof *m->mass);
    m->ablk = calloc(9 * pat->nnzb, sizeof *m->ablk);
    m->sdiag = malloc(9 * m->sym.nb * sizeof *m->sdiag);
    m->supper = malloc((9 * m->sym.ne + 1) * sizeof *m->supper);
    if (!m->mass || !m->ablk || !m->sdiag || !m->supper)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", who);
    st = cl_check_masses(mass, m->n, who, err);
    if (st == CL_OK)
        memcpy(m->mass, mass, m->n * sizeof *m->mass);
    return st;
}

void cl_amat_free(cl_amat *m)
{
    free(m->mass);
    free(m->ablk);
    free(m->sdiag);
    free(m->supper);
    cl_bsym_free(&m->sym);
}

void cl_amat_jacobian(cl_amat *m, const double *dfdx, const double *dfdv)
{
    m->jac_kind = cl_bsym_check_pair(&m->sym, dfdx, dfdv, CL_BSYM_TOL,
                                     m->threads);
}

void cl_amat_fill(cl_amat *m, double a, double b, const double *dfdx,
                  const double *dfdv)
{
    m->kind = m->jac_kind;
    if (m->kind != CL_BSYM_NONE)
        cl_bsym_pack_threads(&m->sym, m->kind, -a, dfdv, -b, dfdx, m->mass,
                             m->sdiag, m->supper, m->threads);
    else
        cl_reduced_blocks(m->pat, m->mass, a, b, dfdx, dfdv, m->ablk);
}

bool cl_amat_finite(const cl_amat *m)
{
    if (m->kind == CL_BSYM_NONE)
        return cl_all_finite_threads(m->ablk, 9 * m->pat->nnzb, m->threads);
    size_t w = m->kind == CL_BSYM_BLOCKS ? 6 : 9;
    return cl_all_finite_threads(m->sdiag, 9 * m->sym.nb, m->threads) &&
           cl_all_finite_threads(m->supper, w * m->sym.ne, m->threads);
}

const double *cl_amat_diag_block(const cl_amat *m, size_t i)
{
    return m->kind != CL_BSYM_NONE ? m->sdiag + 9 * i
                                   : m->ablk + 9 * m->pat->diag[i];
}

void cl_amat_mult(const cl_amat *m, const double *x, double *y)
{
    if (m->kind != CL_BSYM_NONE)
        cl_bsym_matvec_threads(&m->sym, m->kind, m->sdiag, m->supper, x, y,
                               m->threads);
    else
        cl_bmatvec_threads(m->pat, m->ablk, x, y, m->threads);
}
