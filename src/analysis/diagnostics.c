/* Shape diagnostics of a cloth state. */
#include "analysis/diagnostics.h"

double cl_max_stretch(const cl_pairset *set, const double *xfull)
{
    double r = 0.0;
    for (size_t k = 0; k < set->n; k++) {
        const cl_pair *p = &set->pair[k];
        double q = cl_dist(xfull + 3 * p->a, xfull + 3 * p->b) / p->rest;
        if (q > r || q != q) /* a NaN propagates */
            r = q;
    }
    return r;
}

double cl_max_offplane(const cl_cloth *c, const double *xfull)
{
    double m = 0.0;
    for (size_t p = 0; p < c->np; p++) {
        double d = fabs(xfull[3 * p + 1] - c->X0[3 * p + 1]);
        if (d > m || d != d)
            m = d;
    }
    return m;
}
