/* Clocks for timing runs: process CPU time and monotonic wall time, in
 * seconds from an arbitrary origin (differences only). */
#ifndef CL_CLOCK_H
#define CL_CLOCK_H

#include "core/decls.h"

CL_BEGIN_DECLS

double cl_clock_cpu(void);
double cl_clock_wall(void);

CL_END_DECLS

#endif
