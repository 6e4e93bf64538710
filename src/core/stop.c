/* The stop flag of core/stop.h. */
#include "core/stop.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/time.h>
#include <time.h>

static volatile sig_atomic_t stop_signal;
static struct timespec first_signal_at; /* of the first SIGINT or SIGTERM */

/* The budget timers cl_stop_after armed (by cl_stop_clock), and the signal
 * actions their handler replaced: a host program's own SIGALRM and
 * SIGPROF handling comes back when they are disarmed. */
static volatile sig_atomic_t armed[2];
static struct sigaction replaced[2];
static const int timer_signal[2] = {SIGPROF, SIGALRM};
static const int timer_which[2] = {ITIMER_PROF, ITIMER_REAL};

/* The first reason to stop is the one reported (a budget that runs out
 * after a Ctrl-C does not turn the run's end into "budget"), except that
 * a signal (SIGINT, SIGTERM) replaces a budget's timer (SIGPROF,
 * SIGALRM), so that forgetting the budget's stop (cl_stop_clear) does
 * not forget a Ctrl-C that came after it. */
static bool budget_timer(int sig)
{
    return sig == SIGPROF || sig == SIGALRM;
}

/* A second SIGINT or SIGTERM ends the program at once (its default
 * action), unless it comes within CL_STOP_REPEAT_S of the first: then it
 * is the same request sent twice (timeout(1) signals the process, then
 * its process group).  clock_gettime, sigaction and raise are
 * async-signal-safe. */
static void on_signal(int sig)
{
    /* a timer's signal delivered after it was disarmed (generated just
     * before) stops nothing: the budget was an earlier run's */
    if (budget_timer(sig) && !armed[sig == SIGALRM])
        return;
    if (!budget_timer(sig)) {
        struct timespec now;
        clock_gettime(CLOCK_MONOTONIC, &now);
        if (stop_signal && !budget_timer(stop_signal)) {
            double since = (double)(now.tv_sec - first_signal_at.tv_sec) +
                           1e-9 * (double)(now.tv_nsec -
                                           first_signal_at.tv_nsec);
            if (since >= CL_STOP_REPEAT_S) {
                struct sigaction dfl;
                memset(&dfl, 0, sizeof dfl);
                dfl.sa_handler = SIG_DFL;
                sigaction(sig, &dfl, NULL);
                raise(sig); /* delivered when this handler returns */
            }
            return;
        }
        first_signal_at = now;
    }
    if (!stop_signal || (budget_timer(stop_signal) && !budget_timer(sig)))
        stop_signal = sig;
}

void cl_stop_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask); /* one handler at a time: first_signal_at */
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGTERM);
    /* system calls carry on (a repeat does not cut a write short); the
     * flag stops the run, a second signal the program (on_signal) */
    sa.sa_flags = SA_RESTART;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
}

int cl_stop_requested(void)
{
    return (int)stop_signal;
}

cl_status cl_stop_status(cl_status st)
{
    return st != CL_OK && stop_signal ? CL_EINTR : st;
}

bool cl_stop_interrupted(void)
{
    return stop_signal && !budget_timer(stop_signal);
}

/* A one-shot timer's value for `seconds`. */
static struct itimerval one_shot(double seconds)
{
    struct itimerval it;
    memset(&it, 0, sizeof it);
    double whole = floor(seconds);
    it.it_value.tv_sec = (time_t)whole;
    it.it_value.tv_usec = (suseconds_t)((seconds - whole) * 1e6);
    if (it.it_value.tv_sec == 0 && it.it_value.tv_usec == 0)
        it.it_value.tv_usec = 1; /* zero would disarm it */
    return it;
}

cl_status cl_stop_after(cl_stop_clock clock, double seconds, cl_error *err)
{
    bool cpu = clock == CL_STOP_CPU;
    if (!(seconds > 0.0) || !isfinite(seconds))
        return cl_error_set(err, CL_EINVAL, "%s budget %g s: must be a "
                            "finite number > 0", cpu ? "CPU" : "wall-time",
                            seconds);
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART; /* system calls carry on; the flag stops */
    struct itimerval it = one_shot(seconds);
    if (sigaction(timer_signal[clock], &sa,
                  armed[clock] ? NULL : &replaced[clock]) != 0)
        return cl_error_set(err, CL_EIO, "cannot set a %s timer: %s",
                            cpu ? "CPU-time" : "wall-time", strerror(errno));
    armed[clock] = true;
    if (setitimer(timer_which[clock], &it, NULL) != 0)
        return cl_error_set(err, CL_EIO, "cannot set a %s timer: %s",
                            cpu ? "CPU-time" : "wall-time", strerror(errno));
    return CL_OK;
}

void cl_stop_disarm(void)
{
    struct itimerval off;
    memset(&off, 0, sizeof off);
    for (int c = 0; c < 2; c++)
        if (armed[c]) {
            setitimer(timer_which[c], &off, NULL);
            /* a host's own handler comes back; the default action (the
             * command line's) does not: a signal of the timer generated
             * just before it was disarmed, delivered after, would end
             * the process */
            if (replaced[c].sa_handler != SIG_DFL)
                sigaction(timer_signal[c], &replaced[c], NULL);
            armed[c] = false;
        }
}

void cl_stop_clear(void)
{
    cl_stop_disarm();
    if (budget_timer(stop_signal))
        stop_signal = 0;
}

const char *cl_stop_signal_name(int sig)
{
    static char other[32];
    if (sig == SIGINT)
        return "SIGINT";
    if (sig == SIGTERM)
        return "SIGTERM";
    if (sig == SIGPROF)
        return "its CPU budget";
    if (sig == SIGALRM)
        return "its wall-time budget";
    snprintf(other, sizeof other, "signal %d", sig);
    return other;
}

cl_status cl_stop_error(cl_error *err, double t_reached, double t_to)
{
    const char *name = cl_stop_signal_name(cl_stop_requested());
    if (isnan(t_to))
        return cl_error_set(err, CL_EINTR, "interrupted by %s at t = %.10g",
                            name, t_reached);
    return cl_error_set(err, CL_EINTR, "interrupted by %s at t = %.10g "
                        "(during the advance to t = %g)", name, t_reached,
                        t_to);
}
