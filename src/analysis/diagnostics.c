/* Shape diagnostics of a cloth state. */
#include "analysis/diagnostics.h"

#include <math.h>

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

bool cl_offplane_applies(const cl_cloth *c)
{
    for (size_t p = 1; p < c->np; p++)
        if (c->X0[3 * p + 1] != c->X0[1])
            return false;
    return true;
}

long cl_wrinkles(const cl_cloth *c, const double *xfull)
{
    int j = c->nv / 2;
    double amp = 0.0;
    for (int i = 0; i < c->nu; i++) {
        size_t p = (size_t)cl_cloth_index(c, i, j);
        amp = fmax(amp, fabs(xfull[3 * p + 1] - c->X0[3 * p + 1]));
    }
    long changes = 0;
    int last = 0;
    for (int i = 0; i < c->nu; i++) {
        size_t p = (size_t)cl_cloth_index(c, i, j);
        double y = xfull[3 * p + 1] - c->X0[3 * p + 1];
        if (fabs(y) < 0.05 * amp || y == 0.0)
            continue;
        int sign = y > 0 ? 1 : -1;
        changes += last && sign != last;
        last = sign;
    }
    return changes;
}

double cl_max_distance(const double *a, const double *b, size_t np)
{
    double m = 0.0;
    for (size_t p = 0; p < np; p++) {
        double d0 = a[3 * p] - b[3 * p], d1 = a[3 * p + 1] - b[3 * p + 1];
        double d2 = a[3 * p + 2] - b[3 * p + 2];
        m = fmax(m, sqrt(d0 * d0 + d1 * d1 + d2 * d2));
    }
    return m;
}
