/* Embedding clothode's cloth model in one's own SUNDIALS program.
 *
 * The model (a problem file: cloth, pins, force terms, obstacles) is
 * built by libclothode and seen through its cl_system: forces, Jacobian
 * blocks in a fixed block pattern, energy, masses.  The integration is
 * this program's own: CVODE BDF with a dense matrix, the first-order
 * Jacobian [[0, I], [M^-1 df/dx, M^-1 df/dv]] filled from the system's
 * blocks, as in SUNDIALS' own examples (a problem in user data, a
 * Jacobian function, every return value checked).
 *
 *   embed_cvode PROBLEM.ini T [section.key=value ...]
 *
 * prints CVODE's steps, the final time, and the kinetic and total
 * energies.  It integrates the forces alone: a problem that needs the
 * system's other hooks (position-based constraints, projection, barrier
 * or constraint contact, tearing: see system/system.h) is refused, as
 * this program would silently leave them out.  Build against an installed
 * clothode with
 *   cc embed_cvode.c $(pkg-config --cflags --libs clothode) -o embed_cvode
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "io/config.h"
#include "system/model.h"

typedef struct {
    const cl_system *sys;
    double *f, *dfdx, *dfdv; /* work arrays: n, and 9 blocks each */
} user_data;

/* y = (x, v): x' = v, v' = M^-1 f(t, x, v). */
static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void *data)
{
    user_data *u = data;
    size_t n = u->sys->n;
    const double *x = N_VGetArrayPointer(y);
    double *d = N_VGetArrayPointer(ydot);
    if (u->sys->force(u->sys->data, t, x, x + n, u->f) != CL_OK)
        return 1; /* recoverable: CVODE retries with a smaller step */
    for (size_t i = 0; i < n; i++) {
        d[i] = x[n + i];
        d[n + i] = u->f[i] / u->sys->mass[i];
    }
    return 0;
}

/* The dense first-order Jacobian from the system's 3x3 blocks. */
static int jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J,
               void *data, N_Vector t1, N_Vector t2, N_Vector t3)
{
    user_data *u = data;
    const cl_bpattern *p = u->sys->pattern;
    size_t n = u->sys->n;
    const double *x = N_VGetArrayPointer(y);
    (void)fy, (void)t1, (void)t2, (void)t3;
    if (u->sys->jacobian(u->sys->data, t, x, x + n, NULL, u->dfdx,
                         u->dfdv) != CL_OK)
        return 1;
    SUNMatZero(J);
    for (size_t i = 0; i < n; i++)
        SM_ELEMENT_D(J, i, n + i) = 1.0;
    for (size_t bi = 0; bi < p->nb; bi++)
        for (size_t k = p->rowptr[bi]; k < p->rowptr[bi + 1]; k++)
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    size_t r = 3 * bi + a, c = 3 * p->col[k] + b;
                    double m = u->sys->mass[r];
                    SM_ELEMENT_D(J, n + r, c) = u->dfdx[9 * k + 3 * a + b] / m;
                    SM_ELEMENT_D(J, n + r, n + c) =
                        u->dfdv[9 * k + 3 * a + b] / m;
                }
    return 0;
}

static int check(int flag, const char *fn)
{
    if (flag < 0)
        fprintf(stderr, "embed_cvode: %s failed with flag %d\n", fn, flag);
    return flag < 0;
}

/* Whether the system asks an integrator for more than its forces and
 * Jacobian (system/system.h). */
static int needs_hooks(const cl_system *sys)
{
    return sys->project || sys->projects || sys->step_done ||
           sys->step_fraction || sys->constrain;
}

/* The problem file with the assignments applied, as a model (the
 * configuration is kept alive beside it).  A key the model did not read
 * (a misspelt name) is refused, as clothode refuses it; [run], the
 * clothode command's own settings, is this program's to ignore. */
static cl_model *load(const char *path, int nset, char **sets,
                      cl_config **cfg)
{
    cl_error err = {0};
    cl_model *m = NULL;
    *cfg = cl_config_alloc();
    int bad = !*cfg || cl_config_load(*cfg, path, &err);
    for (int k = 0; !bad && k < nset; k++)
        bad = cl_config_set(*cfg, sets[k], &err) != CL_OK;
    if (!bad)
        bad = cl_model_create(*cfg, &m, &err) != CL_OK;
    if (!bad) {
        cl_config_ignore_section(*cfg, "run");
        bad = cl_config_check_unused(*cfg, &err) != CL_OK;
    }
    if (!bad && needs_hooks(cl_model_system(m))) {
        fprintf(stderr, "embed_cvode: %s: the problem needs more than "
                        "forces (projections, barriers, constraints or "
                        "tearing), which this program does not apply; "
                        "clothode's integrators do\n", path);
        cl_model_free(m);
        return NULL;
    }
    if (!bad)
        return m;
    fprintf(stderr, "embed_cvode: %s\n", err.msg);
    cl_model_free(m);
    return NULL;
}

static int integrate(const cl_system *sys, user_data *u, double T,
                     double *y0)
{
    size_t n = sys->n;
    SUNContext ctx;
    if (check(SUNContext_Create(NULL, &ctx), "SUNContext_Create"))
        return 1;
    N_Vector y = N_VMake_Serial((sunindextype)(2 * n), y0, ctx);
    SUNMatrix J = SUNDenseMatrix((sunindextype)(2 * n), (sunindextype)(2 * n),
                                 ctx);
    SUNLinearSolver ls = SUNLinSol_Dense(y, J, ctx);
    void *mem = CVodeCreate(CV_BDF, ctx);
    sunrealtype t = 0.0;
    int bad = !y || !J || !ls || !mem ||
              check(CVodeInit(mem, rhs, 0.0, y), "CVodeInit") ||
              check(CVodeSetUserData(mem, u), "CVodeSetUserData") ||
              check(CVodeSStolerances(mem, 1e-8, 1e-10), "CVodeSStolerances") ||
              check(CVodeSetLinearSolver(mem, ls, J), "CVodeSetLinearSolver") ||
              check(CVodeSetJacFn(mem, jac), "CVodeSetJacFn") ||
              check(CVodeSetMaxNumSteps(mem, 1000000), "CVodeSetMaxNumSteps") ||
              check(CVode(mem, T, y, &t, CV_NORMAL), "CVode");
    long steps = 0;
    if (!bad)
        CVodeGetNumSteps(mem, &steps);
    CVodeFree(&mem);
    SUNLinSolFree(ls);
    SUNMatDestroy(J);
    N_VDestroy(y);
    SUNContext_Free(&ctx);
    if (!bad)
        printf("steps %ld\n", steps);
    return bad;
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: embed_cvode PROBLEM.ini T "
                        "[section.key=value ...]\n");
        return 2;
    }
    char *end;
    double T = strtod(argv[2], &end);
    if (end == argv[2] || *end || !(T > 0) || !isfinite(T)) {
        fprintf(stderr, "embed_cvode: T = \"%s\": expected a finite "
                        "number of seconds > 0\n", argv[2]);
        return 2;
    }
    cl_config *cfg;
    cl_model *m = load(argv[1], argc - 3, argv + 3, &cfg);
    if (!m) {
        cl_config_free(cfg);
        return 1;
    }
    const cl_system *sys = cl_model_system(m);
    size_t n = sys->n, nval = 9 * sys->pattern->nnzb;
    user_data u = {sys, malloc(n * sizeof(double)),
                   malloc(nval * sizeof(double)),
                   malloc(nval * sizeof(double))};
    double *y0 = malloc(2 * n * sizeof *y0);
    int bad = !u.f || !u.dfdx || !u.dfdv || !y0 ||
              cl_model_initial_state(m, y0, y0 + n) != CL_OK ||
              integrate(sys, &u, T, y0);
    cl_energy e;
    if (!bad && sys->energy(sys->data, T, y0, y0 + n, &e) == CL_OK)
        printf("t %.17g\nkinetic %.17g\ntotal %.17g\n", T, e.kinetic,
               e.total);
    free(u.f);
    free(u.dfdx);
    free(u.dfdv);
    free(y0);
    cl_model_free(m);
    cl_config_free(cfg);
    return bad;
}
