/* Penalty response with damping and smoothed friction, and its exact
 * Jacobians (penalty.h; docs/model.md, contact). */
#include "contact/penalty.h"

#include "core/vec3.h"

#include <math.h>
#include <string.h>

/* M += s a b^T */
static void add_outer(double M[9], double s, const double a[3],
                      const double b[3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            M[3 * i + j] += s * a[i] * b[j];
}

/* C = A B (3x3, row-major) */
static void mul33(const double A[9], const double B[9], double C[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] +
                           A[3 * i + 2] * B[6 + j];
}

/* Derivatives of the relative velocity's parts: dwn/dx = -n^T W + w^T G
 * (a row), dvt/dx = -W - n dwn/dx - w_n G, dvt/dv = I - n n^T. */
static void relative_velocity_jacobians(const cl_contact_point *q,
                                        const double w[3], double wn,
                                        double dwn_dx[3], double dvt_dx[9],
                                        double dvt_dv[9])
{
    for (int j = 0; j < 3; j++) {
        dwn_dx[j] = 0.0;
        for (int i = 0; i < 3; i++)
            dwn_dx[j] += -q->n[i] * q->W[3 * i + j] + w[i] * q->G[3 * i + j];
    }
    for (int k = 0; k < 9; k++) {
        dvt_dx[k] = -q->W[k] - wn * q->G[k];
        dvt_dv[k] = (k % 4 == 0) - q->n[k / 3] * q->n[k % 3];
    }
    add_outer(dvt_dx, -1.0, q->n, dwn_dx);
}

/* The Hunt-Crossley factor of the normal force, max(0, 1 - a w_n): a
 * particle leaving faster than 1/a is not pulled back (docs/model.md,
 * eq. C4). */
static inline double hunt_crossley(const cl_response_params *r, double wn)
{
    return fmax(0.0, 1.0 - r->damping * wn);
}

/* f_n = fe max(0, 1 - a w_n) n (docs/model.md, eq. C7, C8); where the
 * factor is 0 the normal force and its derivatives are. */
static void penalty_jacobians(const cl_response_params *r,
                              const cl_contact_point *q, const double w[3],
                              double wn, double fe, const double g[3],
                              double s, cl_penalty_out *o)
{
    double dwn_dx[3], dvt_dx[9], dvt_dv[9], A[9], Ax[9], Av[9];
    double hc = hunt_crossley(r, wn), a = hc > 0.0 ? r->damping : 0.0;
    relative_velocity_jacobians(q, w, wn, dwn_dx, dvt_dx, dvt_dv);
    for (int k = 0; k < 9; k++) {
        o->dfdx[k] = fe * hc * q->G[k];
        o->dfdv[k] = 0.0;
    }
    add_outer(o->dfdx, -r->k * hc, q->n, q->n);
    add_outer(o->dfdx, -a * fe, q->n, dwn_dx);
    add_outer(o->dfdv, -a * fe, q->n, q->n);
    if (r->mu == 0.0)
        return;
    for (int k = 0; k < 9; k++)
        A[k] = ((k % 4 == 0) - g[k / 3] * g[k % 3]) / s; /* dg/dvt */
    mul33(A, dvt_dx, Ax);
    mul33(A, dvt_dv, Av);
    add_outer(o->dfdx, r->mu * r->k, g, q->n);
    for (int k = 0; k < 9; k++) {
        o->dfdx[k] -= r->mu * fe * Ax[k];
        o->dfdv[k] -= r->mu * fe * Av[k];
    }
}

/* The law at distance d, normal n and obstacle velocity u: the force,
 * energy and powers into o; w = v - u, w_n, fe = k (eps - d), g and s
 * for the Jacobians. */
static inline void law(const cl_response_params *r, double d,
                       const double n[3],
                       const double u[3], const double v[3], double w[3],
                       double *wn, double *fe, double g[3], double *s,
                       cl_penalty_out *o)
{
    double vt[3];
    cl_v3_sub(v, u, w);
    *fe = r->k * (r->eps - d);
    *wn = cl_v3_dot(w, n);
    double hc = hunt_crossley(r, *wn);
    cl_v3_scale(*fe * hc, n, o->f);
    o->energy = 0.5 * r->k * (r->eps - d) * (r->eps - d);
    o->friction_power = 0.0;
    g[0] = g[1] = g[2] = *s = 0.0;
    if (r->mu != 0.0) { /* without friction, g is not needed */
        cl_v3_axpy(w, -*wn, n, vt);   /* w - w_n n */
        *s = sqrt(cl_v3_dot(vt, vt) + r->v_smooth * r->v_smooth);
        g[0] = vt[0] / *s;
        g[1] = vt[1] / *s;
        g[2] = vt[2] / *s;
        cl_v3_axpy(o->f, -(r->mu * *fe), g, o->f);
        o->friction_power = -r->mu * *fe * cl_v3_dot(g, vt);
    }
    /* the normal force beyond the spring's, fe (hc - 1), against w_n */
    double damp = hc > 0.0 ? -r->damping * *fe * *wn * *wn : -*fe * *wn;
    o->power = damp + o->friction_power;
}

bool cl_penalty_eval(const cl_response_params *r, const cl_contact_point *q,
                     const double v[3], bool jac, cl_penalty_out *o)
{
    if (!(q->d < r->eps))
        return false;
    double w[3], g[3], wn, fe, s;
    law(r, q->d, q->n, q->u, v, w, &wn, &fe, g, &s, o);
    if (jac)
        penalty_jacobians(r, q, w, wn, fe, g, s, o);
    return true;
}

void cl_penalty_forces(const cl_response_params *r, const cl_contact_slim *q,
                       const size_t *near, size_t n, const double *v,
                       double *f, double *energy, double *power)
{
    for (size_t i = 0; i < n; i++) {
        const double *vi = v + 3 * near[i];
        double w[3], g[3], wn, fe, s;
        cl_penalty_out o;
        if (!(q[i].d < r->eps))
            continue;
        law(r, q[i].d, q[i].n, q[i].u, vi, w, &wn, &fe, g, &s, &o);
        if (f)
            cl_v3_add(f + 3 * near[i], o.f, f + 3 * near[i]);
        *energy += o.energy;
        *power += o.power;
    }
}
