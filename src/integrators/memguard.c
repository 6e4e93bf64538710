/* Memory estimate of an integrator's Jacobian and factors.
 *
 * With nnz = 9 nnzb the entries of one block Jacobian (df/dx or df/dv):
 *   both Jacobians        2 nnz x 8 bytes,
 *   the Newton matrix     nnz x 16 bytes (value and index, as CSC),
 *   its sparse factors    fill x nnz x 16 bytes per triangular factor kept
 *                         (KLU: L and U; CHOLMOD: L; PCG: none),
 *   a dense Newton matrix (2n)^2 x 8 bytes twice (the matrix and the saved
 *                         Jacobian CVODE and GSL keep beside its LU).
 * The fill of L + U over nnz, measured with CHOLMOD's symbolic analysis
 * (AMD ordering) on the hang grid, grows like log2 of the free particles
 * nb: 3.8 at nb = 256, 6.2 at 1024, 8.8 at 4096, 11.8 at 16384, as nested
 * dissection predicts for planar meshes (George, "Nested dissection of a
 * regular finite element mesh"); fill = 0.75 log2(nb) - 3.5 per factor
 * lies above every one of these. */
#include "integrators/memguard.h"

#include <math.h>

#include "core/meminfo.h"

/* Entries of one triangular factor per entry of the matrix. */
static double factor_fill(size_t nb)
{
    return fmax(1.0, 0.75 * log2((double)(nb ? nb : 1)) - 3.5);
}

/* Triangular factors the named solver keeps; unknown names (a method's
 * own, e.g. klu-full) count as the most any registered solver keeps. */
static int factors_of(const char *linsol)
{
    const cl_linsol_type *lt = cl_linsol_find(linsol);
    int most = 0;
    if (lt && linsol && *linsol)
        return lt->factors;
    for (const cl_linsol_type *const *r = cl_linsol_registry; *r; r++)
        most = (*r)->factors > most ? (*r)->factors : most;
    return most;
}

double cl_memguard_estimate(const cl_integrator_type *type,
                            const cl_system *sys, const char *linsol)
{
    double nnz = 9.0 * (double)sys->pattern->nnzb, m = 2.0 * (double)sys->n;
    double bytes = 2.0 * nnz * 8.0;
    if (type->dense_jacobian)
        return bytes + 2.0 * m * m * 8.0;
    if (type->takes_linsol)
        bytes += nnz * 16.0 * (1.0 + factors_of(linsol) *
                                         factor_fill(sys->n / 3));
    return bytes;
}

cl_status cl_memguard_check(const cl_integrator_type *type,
                            const cl_system *sys, const char *linsol,
                            cl_error *err)
{
    double need = cl_memguard_estimate(type, sys, linsol), avail;
    const char *limit;
    cl_status rc = cl_mem_available(&avail, &limit, err);
    if (rc || need <= avail)
        return rc;
    return cl_error_set(err, CL_ENOMEM,
                        "%s: the Jacobian and the factors of the Newton"
                        " matrix need about %.3g GB (%zu unknowns), more"
                        " than the %.3g GB available (%s); choose a smaller"
                        " cloth, %s, or --force to try anyway", type->name,
                        need / 1e9, sys->n, avail / 1e9, limit,
                        type->dense_jacobian ? "the sparse cvode-bdf"
                        : type->takes_linsol ? "--linsol pcg (no factors)"
                                             : "an explicit integrator");
}
