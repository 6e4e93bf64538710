/* Time limits for long tests.  Criterion's own (.timeout) is not used: in
 * Criterion 2.4.1, BoxFort's bxfi_cancel_timeout can unlink one cancelled
 * timeout request from the list that frees them while it cancels another,
 * so two tests with timeouts running at once (--jobs 2) may leak 48 bytes
 * in the runner, which LeakSanitizer reports under make SAN=1 test.
 * alarm() in the test's own process does the same job: SIGALRM ends the
 * test, and Criterion reports it as crashed. */
#ifndef TIMELIMIT_H
#define TIMELIMIT_H

#include <unistd.h>

/* End this test's process after `seconds` of wall time. */
static inline void time_limit(unsigned seconds)
{
    alarm(seconds);
}

#endif
