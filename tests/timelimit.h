/* Time limits for long tests.  Criterion's own (.timeout) is not used: in
 * Criterion 2.4.1, BoxFort's bxfi_cancel_timeout can unlink one cancelled
 * timeout request from the list that frees them while it cancels another,
 * so two tests with timeouts running at once (--jobs 2) may leak 48 bytes
 * in the runner, which LeakSanitizer reports under make SAN=1 test.
 *
 * The limit is on the test process's CPU time (RLIMIT_CPU: SIGXCPU), so
 * that a test on a loaded machine, which gets a fraction of a core, is not
 * ended for the others' work; a test blocked without using CPU (waiting
 * on a child that hangs) is ended by alarm() after four times as long of
 * wall time.  Either signal ends the test, and Criterion reports it as
 * crashed. */
#ifndef TIMELIMIT_H
#define TIMELIMIT_H

#include <sys/resource.h>
#include <unistd.h>

/* End this test's process after `seconds` of CPU time, or 4 `seconds` of
 * wall time.  Children started after the call inherit the CPU limit, each
 * for its own CPU time. */
static inline void time_limit(unsigned seconds)
{
    struct rlimit cpu = {.rlim_cur = seconds, .rlim_max = seconds + 10};
    setrlimit(RLIMIT_CPU, &cpu);
    alarm(4 * seconds);
}

#endif
