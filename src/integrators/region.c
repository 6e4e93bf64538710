/* The stability regions of the integrators (see region.h). */
#include "integrators/region.h"

const cl_region cl_region_taylor1 = {.kind = CL_REGION_TAYLOR, .degree = 1};
const cl_region cl_region_taylor4 = {.kind = CL_REGION_TAYLOR, .degree = 4};
/* v first: v += h a(x, v), then x += h v (symplectic_euler.c). */
static void symplectic_euler_oscillator(double h, double w2, double c,
                                        double y[3])
{
    y[1] += h * (-w2 * y[0] - c * y[1]);
    y[0] += h * y[1];
    y[2] = 0.0;
}

/* Kick-drift-kick from the kept acceleration y[2], the damping at the
 * predictor (velocity_verlet.c). */
static void velocity_verlet_oscillator(double h, double w2, double c,
                                       double y[3])
{
    double vh = y[1] + 0.5 * h * y[2];
    double x1 = y[0] + h * vh;
    double a1 = -w2 * x1 - c * (vh + 0.5 * h * y[2]);
    y[0] = x1;
    y[1] = vh + 0.5 * h * a1;
    y[2] = a1;
}

const cl_region cl_region_symplectic = {
    .kind = CL_REGION_SYMPLECTIC, .oscillator = symplectic_euler_oscillator};
const cl_region cl_region_velocity_verlet = {
    .kind = CL_REGION_SYMPLECTIC, .oscillator = velocity_verlet_oscillator};
const cl_region cl_region_a_stable = {.kind = CL_REGION_SECTOR,
                                      .alpha = 90.0};
const cl_region cl_region_bdf5 = {.kind = CL_REGION_SECTOR, .alpha = 51.84};
const cl_region cl_region_adaptive = {.kind = CL_REGION_ADAPTIVE};
const cl_region cl_region_projected = {.kind = CL_REGION_PROJECTED};
const cl_region cl_region_split = {.kind = CL_REGION_SPLIT};
