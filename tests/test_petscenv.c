/* Tests for PETSc's start through its plug-in (linalg/petscenv.h). */
#include <criterion/criterion.h>

#include <signal.h>

#include "linalg/petscenv.h"

/* Started twice it is started once; PETSc leaves SIGINT to the program
 * (core/stop.h), so the handler installed before is still there. */
static void mark(int sig)
{
    (void)sig;
}

Test(petscenv, starts_once_and_keeps_the_signal_handlers)
{
    cl_error err;
    struct sigaction before = {.sa_handler = mark}, after;
    sigemptyset(&before.sa_mask);
    cr_assert_eq(sigaction(SIGINT, &before, NULL), 0);
    cr_assert_eq(cl_petsc_start(&err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_petsc_start(&err), CL_OK, "%s", err.msg);
    cr_assert_eq(sigaction(SIGINT, NULL, &after), 0);
    cr_assert_eq((void *)after.sa_handler, (void *)mark);
}
