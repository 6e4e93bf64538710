/* Tests for core/meminfo: the available memory is positive and no more
 * than the machine's (MemTotal) or the address-space limit. */
#include <criterion/criterion.h>

#include <stdio.h>
#include <sys/resource.h>

#include "core/meminfo.h"

Test(meminfo, available_lies_between_zero_and_the_total)
{
    double avail = 0, total_kb = 0;
    cl_error err = {0};
    cr_assert_eq(cl_mem_available(&avail, &err), CL_OK, "%s", err.msg);
    FILE *f = fopen("/proc/meminfo", "r");
    cr_assert_not_null(f);
    cr_assert_eq(fscanf(f, "MemTotal: %lf kB", &total_kb), 1);
    fclose(f);
    cr_assert(avail > 0 && avail <= 1024.0 * total_kb,
              "available %g bytes, total %g kB", avail, total_kb);
    struct rlimit rl;
    cr_assert_eq(getrlimit(RLIMIT_AS, &rl), 0);
    cr_assert(rl.rlim_cur == RLIM_INFINITY || avail <= (double)rl.rlim_cur);
}
