/* The clamped log barrier, its exact Hessian (projected or not) and lagged
 * smoothed friction (barrier.h; docs/model.md, contact). */
#include "contact/barrier.h"

#include <lapacke.h>
#include <math.h>
#include <string.h>

#include "core/vec3.h"

void cl_barrier_law(double d, double dhat, double *b, double *db,
                    double *d2b)
{
    if (d >= dhat) {
        *b = *db = *d2b = 0.0;
        return;
    }
    double e = d - dhat, l = log(d / dhat);
    *b = -e * e * l;
    *db = -2.0 * e * l - e * e / d;
    *d2b = -2.0 * l - 4.0 * e / d + e * e / (d * d);
}

double cl_barrier_lambda(const cl_response_params *r, double d)
{
    double b, db, d2b;
    if (!(d > 0.0) || d >= r->dhat)
        return 0.0;
    cl_barrier_law(d, r->dhat, &b, &db, &d2b);
    return -r->kappa * db;
}

void cl_barrier_project_psd(double H[9])
{
    double A[9], lam[3], work[64];
    memcpy(A, H, sizeof A);
    if (LAPACKE_dsyev_work(LAPACK_COL_MAJOR, 'V', 'U', 3, A, 3, lam, work,
                           64) != 0)
        return; /* dsyev did not converge: H is kept */
    memset(H, 0, 9 * sizeof *H);
    for (int k = 0; k < 3; k++) { /* column k of A: eigenvector k */
        if (lam[k] <= 0.0)
            continue;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                H[3 * i + j] += lam[k] * A[3 * k + i] * A[3 * k + j];
    }
}

void cl_barrier_friction(const cl_response_params *r, const double n[3],
                         double lambda, const double u[3], const double W[9],
                         const double v[3], bool jac, cl_barrier_out *o)
{
    double w[3], vt[3], A[9], P[9];
    for (int i = 0; i < 3; i++)
        w[i] = v[i] - u[i];
    double wn = cl_v3_dot(w, n);
    for (int i = 0; i < 3; i++)
        vt[i] = w[i] - wn * n[i];
    double y = cl_v3_norm(vt), ev = r->eps_v, c = r->mu * lambda;
    double phi = y < ev ? 2.0 / ev - y / (ev * ev) : 1.0 / y;
    double dphi_y = y == 0.0 ? 0.0 : y < ev ? -1.0 / (ev * ev * y)
                                            : -1.0 / (y * y * y);
    for (int i = 0; i < 3; i++)
        o->f[i] = -c * phi * vt[i];
    o->energy = 0.0;
    o->power = -c * phi * y * y;
    if (!jac)
        return;
    for (int k = 0; k < 9; k++) {
        A[k] = (k % 4 == 0) * phi + dphi_y * vt[k / 3] * vt[k % 3];
        P[k] = (k % 4 == 0) - n[k / 3] * n[k % 3];
    }
    for (int i = 0; i < 3; i++) /* dfdv = -c A P, dfdx = -dfdv W */
        for (int j = 0; j < 3; j++)
            o->dfdv[3 * i + j] = -c * (A[3 * i] * P[j] +
                                       A[3 * i + 1] * P[3 + j] +
                                       A[3 * i + 2] * P[6 + j]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            o->dfdx[3 * i + j] = -(o->dfdv[3 * i] * W[j] +
                                   o->dfdv[3 * i + 1] * W[3 + j] +
                                   o->dfdv[3 * i + 2] * W[6 + j]);
}

bool cl_barrier_eval(const cl_response_params *r, const cl_contact_point *q,
                     bool jac, cl_barrier_out *o)
{
    double b, db, d2b;
    if (!(q->d > 0.0) || q->d >= r->dhat)
        return false;
    cl_barrier_law(q->d, r->dhat, &b, &db, &d2b);
    o->energy = r->kappa * b;
    o->power = 0.0;
    for (int i = 0; i < 3; i++)
        o->f[i] = -r->kappa * db * q->n[i];
    if (!jac)
        return true;
    double H[9];
    for (int k = 0; k < 9; k++)
        H[k] = r->kappa * (d2b * q->n[k / 3] * q->n[k % 3] + db * q->G[k]);
    if (r->psd)
        cl_barrier_project_psd(H);
    for (int k = 0; k < 9; k++) {
        o->dfdx[k] = -H[k];
        o->dfdv[k] = 0.0;
    }
    return true;
}
