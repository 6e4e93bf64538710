/* Names of the exit statuses (core/exit.h). */
#include "core/exit.h"

#include <stddef.h>

const char *cl_exit_name(int s)
{
    static const char *const name[CL_EXIT_CLASSES] = {
        "ok",     "other",  "input",       "solver",
        "blow-up", "budget", "interrupted", "io"};
    return s >= 0 && s < CL_EXIT_CLASSES ? name[s] : NULL;
}
