/* The stability regions of the integrators (see region.h). */
#include "integrators/region.h"

const cl_region cl_region_taylor1 = {.kind = CL_REGION_TAYLOR, .degree = 1};
const cl_region cl_region_taylor4 = {.kind = CL_REGION_TAYLOR, .degree = 4};
const cl_region cl_region_symplectic = {.kind = CL_REGION_SYMPLECTIC};
const cl_region cl_region_a_stable = {.kind = CL_REGION_SECTOR,
                                      .alpha = 90.0};
const cl_region cl_region_bdf5 = {.kind = CL_REGION_SECTOR, .alpha = 51.84};
const cl_region cl_region_adaptive = {.kind = CL_REGION_ADAPTIVE};
const cl_region cl_region_projected = {.kind = CL_REGION_PROJECTED};
const cl_region cl_region_split = {.kind = CL_REGION_SPLIT};
