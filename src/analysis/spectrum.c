/* Spectra of the linearised cloth and predicted explicit step limits (see
 * spectrum.h). */
#include "analysis/spectrum.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_blas.h>
#include <gsl/gsl_complex_math.h>
#include <gsl/gsl_eigen.h>
#include <gsl/gsl_poly.h>
#include <gsl/gsl_sort.h>

#include "core/stop.h"
#include "integrators/integrator.h"
#include "linalg/firstorder.h"

/* Growth rates below this fraction of the largest |lambda| are round-off
 * (a zero-stiffness mode's double eigenvalue 0 splits into +-sqrt(eps)). */
#define EIG_TOL 1e-6

typedef struct {
    size_t n, nval;
    double *dfdx, *dfdv, *f, *inv_mass, *A;
} spec_work;

static void work_free(spec_work *w)
{
    free(w->dfdx);
    free(w->dfdv);
    free(w->f);
    free(w->inv_mass);
    free(w->A);
}

/* The Jacobian blocks at (t, x, v) and a dense (2n)^2 scratch. */
static cl_status work_fill(cl_model *m, double t, const double *x,
                           const double *v, spec_work *w, cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    w->n = sys->n;
    w->nval = 9 * sys->pattern->nnzb;
    w->dfdx = malloc((w->nval + 1) * sizeof *w->dfdx);
    w->dfdv = malloc((w->nval + 1) * sizeof *w->dfdv);
    w->f = malloc(w->n * sizeof *w->f);
    w->inv_mass = malloc(w->n * sizeof *w->inv_mass);
    w->A = malloc(4 * w->n * w->n * sizeof *w->A);
    if (!w->dfdx || !w->dfdv || !w->f || !w->inv_mass || !w->A)
        return cl_error_set(err, CL_ENOMEM, "out of memory (spectrum of %zu "
                            "unknowns)", w->n);
    for (size_t i = 0; i < w->n; i++)
        w->inv_mass[i] = 1.0 / sys->mass[i];
    cl_status rc = sys->jacobian(sys->data, t, x, v, w->f, w->dfdx, w->dfdv);
    return rc ? cl_error_set(err, rc, "Jacobian at t = %g failed", t) : rc;
}

/* out = -M^-1/2 (B + B^T)/2 M^-1/2, B = df/dx or df/dv (blocks), dense
 * n x n. */
static void scaled_sym(const cl_bpattern *p, const spec_work *w,
                       const double *blocks, double *out)
{
    size_t n = w->n;
    memset(out, 0, n * n * sizeof *out);
    for (size_t bi = 0; bi < p->nb; bi++)
        for (size_t k = p->rowptr[bi]; k < p->rowptr[bi + 1]; k++)
            for (size_t r = 0; r < 3; r++)
                for (size_t c = 0; c < 3; c++) {
                    size_t i = 3 * bi + r, j = 3 * p->col[k] + c;
                    double a = -0.5 * blocks[9 * k + 3 * r + c] *
                               sqrt(w->inv_mass[i] * w->inv_mass[j]);
                    out[i * n + j] += a;
                    out[j * n + i] += a;
                }
}

/* A = -M^-1/2 sym(df/dx) M^-1/2 into w->A. */
static void stiffness_matrix(const cl_bpattern *p, const spec_work *w)
{
    scaled_sym(p, w, w->dfdx, w->A);
}

/* The modes' damping rates c_k = z_k^T D z_k, D = -M^-1/2 sym(df/dv)
 * M^-1/2, z_k the columns of Z (n x n, orthonormal): diag(Z^T D Z), with
 * D and D Z in the scratch after Z. */
static void modal_damping(const cl_bpattern *p, const spec_work *w,
                          const gsl_matrix *Z, double *c)
{
    size_t n = w->n;
    double *d = w->A + 2 * n * n, *dz = w->A + 3 * n * n;
    scaled_sym(p, w, w->dfdv, d);
    gsl_matrix_const_view D = gsl_matrix_const_view_array(d, n, n);
    gsl_matrix_view DZ = gsl_matrix_view_array(dz, n, n);
    gsl_blas_dgemm(CblasNoTrans, CblasNoTrans, 1.0, &D.matrix, Z, 0.0,
                   &DZ.matrix);
    for (size_t k = 0; k < n; k++) {
        double ck = 0.0;
        for (size_t i = 0; i < n; i++)
            ck += gsl_matrix_get(Z, i, k) * dz[i * n + k];
        c[k] = ck;
    }
}

/* The dense dim x dim matrix a scaled by a power of two (exactly) to a
 * largest entry in [1, 2), and its entries below DBL_EPSILON / dim of
 * that set to zero: a change of at most eps ||a||_2, within the
 * eigensolvers' own backward error, that keeps their iterations out of
 * subnormal numbers (in which GSL's symmetric QR iteration does not end:
 * a stiffness of 1e-300 beside 1).  The eigenvalues of the matrix given
 * are those of the result times the scale returned; the eigenvectors are
 * the same. */
static double eigen_ready(double *a, size_t dim)
{
    double big = 0.0;
    for (size_t k = 0; k < dim * dim; k++)
        big = fmax(big, fabs(a[k]));
    if (!(big > 0.0) || !isfinite(big))
        return 1.0;
    int e;
    frexp(big, &e);
    double scale = ldexp(1.0, e - 1), tiny = DBL_EPSILON / (double)dim;
    for (size_t k = 0; k < dim * dim; k++) {
        a[k] = ldexp(a[k], 1 - e);
        if (fabs(a[k]) < tiny)
            a[k] = 0.0;
    }
    return scale;
}

/* The stiffness eigenvalues mu (ascending) and, from their eigenvectors,
 * the modes' damping rates c. */
static cl_status stiffness_spectrum(const cl_bpattern *p, spec_work *w,
                                    cl_spectrum *s, cl_error *err)
{
    size_t n = w->n;
    stiffness_matrix(p, w);
    double scale = eigen_ready(w->A, n);
    gsl_matrix_view A = gsl_matrix_view_array(w->A, n, n);
    gsl_matrix_view Z = gsl_matrix_view_array(w->A + n * n, n, n);
    gsl_vector_view mu = gsl_vector_view_array(s->mu, n);
    gsl_eigen_symmv_workspace *ws = gsl_eigen_symmv_alloc(n);
    if (!ws)
        return cl_error_set(err, CL_ENOMEM, "out of memory (eigensolver)");
    int rc = gsl_eigen_symmv(&A.matrix, &mu.vector, &Z.matrix, ws);
    gsl_eigen_symmv_free(ws);
    if (rc)
        return cl_error_set(err, CL_ESOLVER, "symmetric eigensolver failed "
                            "(GSL %d)", rc);
    gsl_eigen_symmv_sort(&mu.vector, &Z.matrix, GSL_EIGEN_SORT_VAL_ASC);
    for (size_t i = 0; i < n; i++)
        s->mu[i] *= scale;
    modal_damping(p, w, &Z.matrix, s->c);
    s->w_max = sqrt(fmax(s->mu[w->n - 1], 0.0));
    /* the first-order tolerance squared: |lambda| = sqrt(|mu|) */
    double tol = EIG_TOL * EIG_TOL * fabs(s->mu[w->n - 1]);
    for (size_t i = 0; i < w->n; i++) {
        s->n_negative += s->mu[i] < -tol;
        s->n_zero += fabs(s->mu[i]) <= tol;
    }
    return CL_OK;
}

static int by_modulus_desc(const void *a, const void *b)
{
    double x = cabs(*(const double complex *)a);
    double y = cabs(*(const double complex *)b);
    return (x < y) - (x > y);
}

static cl_status first_order_spectrum(const cl_bpattern *p, spec_work *w,
                                      cl_spectrum *s, cl_error *err)
{
    size_t dim = 2 * w->n;
    cl_firstorder_dense(p, w->inv_mass, w->dfdx, w->dfdv, w->A);
    double scale = eigen_ready(w->A, dim);
    gsl_matrix_view J = gsl_matrix_view_array(w->A, dim, dim);
    gsl_vector_complex *ev = gsl_vector_complex_alloc(dim);
    gsl_eigen_nonsymm_workspace *ws = gsl_eigen_nonsymm_alloc(dim);
    int rc = ev && ws ? gsl_eigen_nonsymm(&J.matrix, ev, ws) : GSL_ENOMEM;
    if (!rc) {
        double complex *lam = (double complex *)ev->data; /* stride 1 */
        for (size_t j = 0; j < dim; j++)
            lam[j] *= scale;
        qsort(lam, dim, sizeof *lam, by_modulus_desc);
        s->lambda_max = cabs(lam[0]);
        double tol = EIG_TOL * s->lambda_max;
        for (size_t j = 0; j < dim; j++) {
            s->re[j] = creal(lam[j]);
            s->im[j] = cimag(lam[j]);
            if (s->re[j] > tol) {
                s->n_growing++;
                s->growth_max = fmax(s->growth_max, s->re[j]);
            }
        }
    }
    gsl_eigen_nonsymm_free(ws);
    gsl_vector_complex_free(ev);
    if (rc == GSL_ENOMEM)
        return cl_error_set(err, CL_ENOMEM, "out of memory (eigensolver)");
    return rc ? cl_error_set(err, CL_ESOLVER, "QR iteration of the "
                             "first-order Jacobian failed (GSL %d)", rc)
              : CL_OK;
}

/* CL_EINTR once SIGINT or SIGTERM asked to stop (core/stop.h). */
static cl_status stopped(cl_error *err)
{
    int sig = cl_stop_requested();
    return sig ? cl_error_set(err, CL_EINTR, "spectrum: interrupted by %s",
                              cl_stop_signal_name(sig))
               : CL_OK;
}

cl_status cl_spectrum_compute(cl_model *m, double t, const double *x,
                              const double *v, cl_spectrum *s, cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    spec_work w = {0};
    memset(s, 0, sizeof *s);
    if (sys->n > CL_SPECTRUM_MAX_N)
        return cl_error_set(err, CL_EUNSUPPORTED, "spectrum: %zu unknowns, "
                            "at most %d (dense eigensolvers; a 24 x 24 "
                            "cloth)", sys->n, CL_SPECTRUM_MAX_N);
    s->n = sys->n;
    s->mu = malloc(s->n * sizeof *s->mu);
    s->c = malloc(s->n * sizeof *s->c);
    s->re = malloc(2 * s->n * sizeof *s->re);
    s->im = malloc(2 * s->n * sizeof *s->im);
    cl_status rc = s->mu && s->c && s->re && s->im
                       ? work_fill(m, t, x, v, &w, err)
                       : cl_error_set(err, CL_ENOMEM, "out of memory");
    /* GSL's QR iterations cannot be cut short: a stop is seen between
     * them (the first-order one takes minutes at the largest sizes) */
    if (!rc && !(rc = stiffness_spectrum(sys->pattern, &w, s, err)) &&
        !(rc = stopped(err)) &&
        !(rc = first_order_spectrum(sys->pattern, &w, s, err)))
        rc = stopped(err);
    work_free(&w);
    if (rc)
        cl_spectrum_free(s);
    return rc;
}

cl_status cl_spectrum_modes(cl_model *m, double t, const double *x,
                            const double *v, double *mu, double *phi,
                            cl_error *err)
{
    const cl_system *sys = cl_model_system(m);
    spec_work w = {0};
    if (sys->n > CL_SPECTRUM_MAX_N)
        return cl_error_set(err, CL_EUNSUPPORTED, "modes: %zu unknowns, at "
                            "most %d (dense eigensolver)", sys->n,
                            CL_SPECTRUM_MAX_N);
    cl_status rc = work_fill(m, t, x, v, &w, err);
    gsl_eigen_symmv_workspace *ws = rc ? NULL : gsl_eigen_symmv_alloc(w.n);
    if (!rc && !ws)
        rc = cl_error_set(err, CL_ENOMEM, "out of memory (eigensolver)");
    if (!rc) {
        stiffness_matrix(sys->pattern, &w);
        gsl_matrix_view A = gsl_matrix_view_array(w.A, w.n, w.n);
        gsl_matrix_view Z = gsl_matrix_view_array(phi, w.n, w.n);
        gsl_vector_view ev = gsl_vector_view_array(mu, w.n);
        int grc = gsl_eigen_symmv(&A.matrix, &ev.vector, &Z.matrix, ws);
        if (grc)
            rc = cl_error_set(err, CL_ESOLVER, "symmetric eigensolver "
                              "failed (GSL %d)", grc);
        else
            gsl_eigen_symmv_sort(&ev.vector, &Z.matrix,
                                 GSL_EIGEN_SORT_VAL_ASC);
    }
    if (ws)
        gsl_eigen_symmv_free(ws);
    work_free(&w);
    return rc;
}

void cl_spectrum_free(cl_spectrum *s)
{
    free(s->mu);
    free(s->c);
    free(s->re);
    free(s->im);
    memset(s, 0, sizeof *s);
}

/* ---- predicted limits -------------------------------------------------- */

/* Forward Euler, R = 1 + z: |1 + h lambda| <= 1 for h <= -2 Re / |l|^2
 * (0 for an undamped mode: every oscillation without damping grows). */
static double disc_limit(double complex l)
{
    return fmax(0.0, -2 * creal(l) / (creal(l) * creal(l) +
                                      cimag(l) * cimag(l)));
}

/* R(z) = sum_{k <= p} z^k / k!, nested as 1 + z (1 + z/2 (1 + z/3 ...)). */
static double complex r_taylor(int p, double complex z)
{
    double complex r = 1;
    for (int k = p; k >= 1; k--)
        r = 1 + z / k * r;
    return r;
}

/* What a step of size s = h |lambda| multiplies a mode by: the
 * amplification's modulus (or spectral radius) g(ctx, s). */
typedef double (*growth_fn)(const void *ctx, double s);

/* The largest s with g <= 1 from 0 up: scanned up to 4 in steps of 0.005
 * (the regions here end before: Taylor ones of degree <= 4 within |z| <
 * 4, region.h; a symplectic step at s = 2), then bisected; INFINITY if g
 * stays <= 1. */
static double scan_limit(growth_fn g, const void *ctx)
{
    double lo, hi = 0.0;
    for (double s = 0.005; s <= 4.0; s += 0.005)
        if (g(ctx, s) > 1 + 1e-12) {
            hi = s;
            break;
        }
    if (hi == 0.0)
        return INFINITY;
    lo = hi - 0.005;
    for (int k = 0; k < 60; k++) {
        double mid = 0.5 * (lo + hi);
        *(g(ctx, mid) > 1 + 1e-12 ? &hi : &lo) = mid;
    }
    return lo;
}

typedef struct {
    int p;             /* the Taylor degree */
    double complex d;  /* lambda / |lambda| */
} taylor_ray;

static double taylor_growth(const void *ctx, double s)
{
    const taylor_ray *r = ctx;
    return cabs(r_taylor(r->p, s * r->d));
}

/* The largest h with |R(h l)| <= 1 along the ray of l: for p = 1 the disc
 * |1 + z| <= 1 in closed form, else scanned. */
static double taylor_limit(int p, double complex l)
{
    if (p == 1)
        return disc_limit(l);
    double a = cabs(l);
    taylor_ray ray = {p, l / a};
    return scan_limit(taylor_growth, &ray) / a;
}

/* Eigenvalue j as it constrains a step, false if it does not: growing or
 * round-off-zero; a real part within the tolerance counts as 0
 * (undamped). */
static bool constraining(const cl_spectrum *s, size_t j, double complex *l)
{
    double tol = EIG_TOL * s->lambda_max;
    double re = fabs(s->re[j]) <= tol ? 0.0 : s->re[j];
    *l = re + I * s->im[j];
    return re <= 0 && cabs(*l) > tol;
}

/* Whether -l lies within alpha degrees of the positive real axis; an
 * undamped l (Re = 0) lies at 90 degrees. */
static bool in_sector(double complex l, double alpha)
{
    if (creal(l) == 0.0)
        return alpha >= 90.0;
    return atan2(fabs(cimag(l)), -creal(l)) <= alpha * M_PI / 180.0;
}

static double taylor_step(const cl_spectrum *s, int p)
{
    double h = INFINITY;
    double complex l;
    for (size_t j = 0; j < 2 * s->n; j++)
        if (constraining(s, j, &l))
            h = fmin(h, taylor_limit(p, l));
    return h;
}

static double sector_step(const cl_spectrum *s, double alpha)
{
    double complex l;
    for (size_t j = 0; j < 2 * s->n; j++)
        if (constraining(s, j, &l) && !in_sector(l, alpha))
            return NAN;
    return INFINITY;
}

/* A stiffness mode k as a damped oscillator x'' = -w2 x - c x': w2 =
 * mu_k, c = c_k (exact for proportional damping, whose modes are the
 * undamped cloth's; overdamped ones included). */
typedef struct {
    const cl_region *r;
    double scale;      /* max(w, c): h = s / scale */
    double w2, c;
} oscillator_mode;

/* The spectral radius of the region's step h = s / scale on the mode: of
 * its 3 x 3 matrix A (column k the step of the k-th unit state), the
 * largest root of det(z - A) = z^3 - tr z^2 + m2 z - det. */
static double oscillator_growth(const void *ctx, double s)
{
    const oscillator_mode *m = ctx;
    double h = s / m->scale, a[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int k = 0; k < 3; k++)
        m->r->oscillator(h, m->w2, m->c, a[k]); /* a[k]: column k */
    double tr = a[0][0] + a[1][1] + a[2][2];
    double m2 = a[0][0] * a[1][1] - a[1][0] * a[0][1] +
                a[0][0] * a[2][2] - a[2][0] * a[0][2] +
                a[1][1] * a[2][2] - a[2][1] * a[1][2];
    double det = a[0][0] * (a[1][1] * a[2][2] - a[2][1] * a[1][2]) -
                 a[1][0] * (a[0][1] * a[2][2] - a[2][1] * a[0][2]) +
                 a[2][0] * (a[0][1] * a[1][2] - a[1][1] * a[0][2]);
    gsl_complex z[3];
    gsl_poly_complex_solve_cubic(-tr, m2, -det, &z[0], &z[1], &z[2]);
    return fmax(gsl_complex_abs(z[0]),
                fmax(gsl_complex_abs(z[1]), gsl_complex_abs(z[2])));
}

/* The smallest limit over the stiffness modes: mu within the tolerance
 * of the first-order eigenvalues squared counts as 0, and a mode with
 * neither stiffness nor damping beyond it constrains nothing; a mode the
 * forces push away (mu < 0) grows for every step and is left out, as the
 * growing eigenvalues are. */
static double symplectic_step(const cl_spectrum *s, const cl_region *r)
{
    double h = INFINITY, tol = EIG_TOL * s->lambda_max;
    for (size_t k = 0; k < s->n; k++) {
        double w2 = fabs(s->mu[k]) <= tol * tol ? 0.0 : s->mu[k];
        double c = fabs(s->c[k]) <= tol ? 0.0 : s->c[k];
        double scale = fmax(sqrt(fmax(w2, 0.0)), fabs(c));
        if (w2 < 0 || c < 0 || scale == 0.0)
            continue;
        oscillator_mode m = {r, scale, w2, c};
        h = fmin(h, scan_limit(oscillator_growth, &m) / scale);
    }
    return h;
}

double cl_spectrum_step_limit(const cl_spectrum *s, const cl_region *r)
{
    switch (r->kind) {
    case CL_REGION_TAYLOR:
        return taylor_step(s, r->degree);
    case CL_REGION_SYMPLECTIC:
        return symplectic_step(s, r);
    case CL_REGION_SECTOR:
        return sector_step(s, r->alpha);
    default:
        return NAN;
    }
}

/* The registry's methods of region kind `kind` appended to out[*n...]
 * (those past cap counted only). */
static void limits_of_kind(const cl_spectrum *s, cl_region_kind kind,
                           const char *basis, cl_spectrum_limit *out,
                           size_t cap, size_t *n)
{
    for (size_t i = 0; cl_integrator_registry[i]; i++) {
        const cl_integrator_type *t = cl_integrator_registry[i];
        if (t->region->kind != kind)
            continue;
        if (*n < cap)
            out[*n] = (cl_spectrum_limit){
                t->name, basis, cl_spectrum_step_limit(s, t->region)};
        ++*n;
    }
}

size_t cl_spectrum_limits(const cl_spectrum *s, cl_spectrum_limit *out,
                          size_t cap)
{
    size_t n = 0;
    limits_of_kind(s, CL_REGION_TAYLOR, "|R(h lambda)| <= 1", out, cap, &n);
    limits_of_kind(s, CL_REGION_SYMPLECTIC, "step's radius <= 1 per mode",
                   out, cap, &n);
    return n;
}

void cl_spectrum_write(FILE *fp, const cl_spectrum *s)
{
    fprintf(fp, "kind,index,re,im\n");
    for (size_t i = 0; i < s->n; i++)
        fprintf(fp, "mu,%zu,%.17g,0\n", i, s->mu[i]);
    for (size_t j = 0; j < 2 * s->n; j++)
        fprintf(fp, "lambda,%zu,%.17g,%.17g\n", j, s->re[j], s->im[j]);
}
