/* Clocks for timing runs: process CPU time and monotonic wall time, in
 * seconds from an arbitrary origin (differences only). */
#ifndef CL_CLOCK_H
#define CL_CLOCK_H

double cl_clock_cpu(void);
double cl_clock_wall(void);

#endif
