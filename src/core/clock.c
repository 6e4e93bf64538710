/* Process CPU and monotonic wall clocks (clock_gettime). */
#include "core/clock.h"

#include <time.h>

static double seconds(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double cl_clock_cpu(void)
{
    return seconds(CLOCK_PROCESS_CPUTIME_ID);
}

double cl_clock_wall(void)
{
    return seconds(CLOCK_MONOTONIC);
}
