/* Connection counts: measured from the topology and from the formulas. */
#include "analysis/counts.h"

#include "model/pairs.h"

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
    }
    cl_pairs_free(&t1);
    cl_pairs_free(&t2);
    cl_cloth_free(&cloth);
    return rc;
}
