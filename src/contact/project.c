/* Projection response (project.h; docs/model.md, contact). */
#include "contact/project.h"

#include <math.h>

void cl_project_hit(const cl_response_params *r, const cl_contact_point *q,
                    double m, double x[3], double v[3], cl_project_tally *t)
{
    double w[3], wt[3], wn = 0.0, wt2 = 0.0;
    for (int i = 0; i < 3; i++) {
        x[i] += (r->offset - q->d) * q->n[i];
        w[i] = v[i] - q->u[i];
        wn += w[i] * q->n[i];
    }
    for (int i = 0; i < 3; i++) {
        wt[i] = w[i] - wn * q->n[i];
        wt2 += wt[i] * wt[i];
    }
    double dn = wn < 0.0 ? -wn : 0.0; /* normal speed removed */
    double keep = sqrt(wt2) > 0.0 ? fmax(0.0, 1.0 - r->mu * dn / sqrt(wt2))
                                  : 1.0;
    double keep_n = wn > 0.0 ? wn : 0.0;
    if (r->zero_velocity)
        keep = keep_n = 0.0;
    double dv2 = 0.0;
    for (int i = 0; i < 3; i++) {
        double wnew = keep_n * q->n[i] + keep * wt[i];
        dv2 += (wnew - w[i]) * (wnew - w[i]);
        v[i] = q->u[i] + wnew;
    }
    t->moved++;
    t->impulse += m * sqrt(dv2);
    t->friction_energy -= 0.5 * m * (1.0 - keep * keep) * wt2;
}

bool cl_project_particle(const cl_response_params *r,
                         const cl_contact_point *q, double m, double x[3],
                         double v[3], cl_project_tally *t)
{
    if (!(q->d < r->offset))
        return false;
    cl_project_hit(r, q, m, x, v, t);
    return true;
}
