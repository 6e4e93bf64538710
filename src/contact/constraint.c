/* Baraff-Witkin constraint of one particle (constraint.h; docs/model.md,
 * eqs. C10-C13). */
#include "contact/constraint.h"

#include <math.h>
#include <string.h>

void cl_constraint_none(double S[9], double z[3], double y[3], double g[3])
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(S, I, sizeof I);
    for (int i = 0; i < 3; i++)
        z[i] = y[i] = g[i] = 0.0;
}

/* S = I - n n^T, z = -(w . n) n: the normal part of w removed. */
static void constrain_normal(const cl_constraint *c, double S[9],
                             double z[3])
{
    const double *n = c->n;
    double wn = c->w[0] * n[0] + c->w[1] * n[1] + c->w[2] * n[2];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            S[3 * i + j] = (i == j) - n[i] * n[j];
        z[i] = -wn * n[i];
    }
}

void cl_constraint_start(const cl_response_params *r,
                         const cl_contact_point *q, const double v[3],
                         cl_constraint *c, double S[9], double z[3],
                         double y[3], double g[3])
{
    c->mode = r->mu > 0.0 ? CL_CONSTRAINT_FULL : CL_CONSTRAINT_NORMAL;
    for (int i = 0; i < 3; i++) {
        c->n[i] = q->n[i];
        c->w[i] = v[i] - q->u[i];
        y[i] = (r->offset - q->d) * q->n[i];
        g[i] = 0.0;
    }
    if (c->mode == CL_CONSTRAINT_NORMAL) {
        constrain_normal(c, S, z);
        return;
    }
    for (int i = 0; i < 9; i++)
        S[i] = 0.0;
    for (int i = 0; i < 3; i++)
        z[i] = -c->w[i];
}

bool cl_constraint_release(double mu, const double imp[3], cl_constraint *c,
                           double S[9], double z[3], double y[3],
                           double g[3])
{
    if (c->mode == CL_CONSTRAINT_FREE)
        return false;
    const double *n = c->n;
    double rn = imp[0] * n[0] + imp[1] * n[1] + imp[2] * n[2];
    if (rn < 0.0) { /* the constraint pulls toward the obstacle */
        c->mode = CL_CONSTRAINT_FREE;
        cl_constraint_none(S, z, y, g);
        return true;
    }
    if (c->mode == CL_CONSTRAINT_NORMAL)
        return false;
    double rt[3], rt2 = 0.0;
    for (int i = 0; i < 3; i++) {
        rt[i] = imp[i] - rn * n[i];
        rt2 += rt[i] * rt[i];
    }
    if (!(sqrt(rt2) > mu * rn))
        return false; /* inside the friction cone: it sticks */
    c->mode = CL_CONSTRAINT_NORMAL;
    constrain_normal(c, S, z);
    for (int i = 0; i < 3; i++)
        g[i] = mu * rn * rt[i] / sqrt(rt2);
    return true;
}
