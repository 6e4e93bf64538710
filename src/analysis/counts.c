/* Connection counts: measured from the topology and from the formulas. */
#include "analysis/counts.h"

#include "model/mesh.h"
#include "model/pairs.h"

/* The Baraff-Witkin columns, from the grid's triangle mesh. */
static cl_status measure_bw(int n, cl_counts *c, cl_error *err)
{
    cl_mesh mesh;
    cl_status rc = cl_mesh_grid(n, n, CL_DIAGONAL_FIXED, &mesh, err);
    if (rc)
        return rc;
    long m = n;
    c->bw_tri = (long)mesh.ntri;
    c->bw_bend = (long)mesh.nedge;
    c->bw_edges = (long)(mesh.nedge + mesh.nboundary);
    c->bw = c->bw_tri + c->bw_bend;
    c->bw_tri_formula = 2 * (m - 1) * (m - 1);
    c->bw_bend_formula = (m - 1) * (3 * m - 5);
    c->bw_bend_seed = 2 * m * (m - 1) + (m - 1) * (m - 1);
    c->bw_formula = c->bw_tri_formula + c->bw_bend_formula;
    c->bw_seed = 5 * m * m - 8 * m + 3;
    cl_mesh_free(&mesh);
    return CL_OK;
}

cl_status cl_counts_measure(int n, cl_counts *c, cl_error *err)
{
    cl_cloth cloth;
    cl_pairset t1 = {0}, t2 = {0};
    cl_status rc = cl_cloth_grid(n, n, 1.0, 1.0, 1.0, &cloth, err);
    if (rc)
        return rc;
    if (!(rc = cl_pairs_type1(&cloth, &t1, err)) &&
        !(rc = cl_pairs_type2(&cloth, &t2, err))) {
        long m = n;
        c->n = n;
        c->type1 = (long)t1.n;
        c->type2 = (long)t2.n;
        c->ck = c->type1 + c->type2;
        c->type1_formula = 2 * (m - 1) * (2 * m - 1);
        c->type2_formula = 4 * (m - 1) * (m - 2);
        c->ck_formula = 8 * m * m - 18 * m + 10;
        rc = measure_bw(n, c, err);
    }
    cl_pairs_free(&t1);
    cl_pairs_free(&t2);
    cl_cloth_free(&cloth);
    return rc;
}
