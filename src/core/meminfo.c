/* Available memory from /proc/meminfo, sysinfo and getrlimit. */
#include "core/meminfo.h"

#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/sysinfo.h>

/* MemAvailable (kB) from /proc/meminfo; 0 if absent. */
static double meminfo_available(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    char line[256];
    unsigned long long kb = 0;
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1)
            break;
    if (f)
        fclose(f);
    return 1024.0 * (double)kb;
}

cl_status cl_mem_available(double *bytes, cl_error *err)
{
    double avail = meminfo_available();
    struct sysinfo si;
    if (avail <= 0 && sysinfo(&si) == 0)
        avail = ((double)si.freeram + (double)si.bufferram) * si.mem_unit;
    if (avail <= 0)
        return cl_error_set(err, CL_EIO, "cannot tell the available memory"
                            " (no MemAvailable in /proc/meminfo, no"
                            " sysinfo)");
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY &&
        (double)rl.rlim_cur < avail)
        avail = (double)rl.rlim_cur;
    *bytes = avail;
    return CL_OK;
}
