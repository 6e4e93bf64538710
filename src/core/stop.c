/* The stop flag of core/stop.h. */
#include "core/stop.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

static volatile sig_atomic_t stop_signal;

static void on_signal(int sig)
{
    stop_signal = sig;
}

void cl_stop_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND; /* a second signal ends the program */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

int cl_stop_requested(void)
{
    return (int)stop_signal;
}

const char *cl_stop_signal_name(int sig)
{
    static char other[32];
    if (sig == SIGINT)
        return "SIGINT";
    if (sig == SIGTERM)
        return "SIGTERM";
    snprintf(other, sizeof other, "signal %d", sig);
    return other;
}

cl_status cl_stop_error(cl_error *err, double t_reached, double t_to)
{
    const char *name = cl_stop_signal_name(cl_stop_requested());
    if (isnan(t_to))
        return cl_error_set(err, CL_EINTR, "interrupted by %s at t = %g",
                            name, t_reached);
    return cl_error_set(err, CL_EINTR, "interrupted by %s at t = %g (during "
                        "the advance to t = %g)", name, t_reached, t_to);
}
