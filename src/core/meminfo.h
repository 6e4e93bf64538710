/* The memory this process may still take: the least of
 *   - the kernel's MemAvailable (/proc/meminfo; without it, free plus
 *     buffer memory from sysinfo),
 *   - the room its memory cgroups leave (cgroup v2: memory.max less
 *     memory.current, plus the cgroup's file pages but its shared memory,
 *     which the kernel reclaims before its OOM killer acts; v1:
 *     memory.limit_in_bytes less memory.usage_in_bytes, plus total_cache
 *     less total_shmem), for the process's cgroup
 *     and each of its ancestors -- a batch job's memory limit (Slurm's
 *     --mem) is one of these,
 *   - the room under the address-space and data limits (RLIMIT_AS less the
 *     process's VmSize, RLIMIT_DATA less its VmData; ulimit -v, -d),
 * and a cap on the data size that turns running out of it into failed
 * allocations (each one checked) instead of the kernel's OOM kill. */
#ifndef CL_MEMINFO_H
#define CL_MEMINFO_H

#include <stdbool.h>

#include "core/decls.h"
#include "core/error.h"

CL_BEGIN_DECLS

/* Bytes available, or CL_EIO if the system does not say.  *limit (may be
 * NULL) names the limit that gave the least: "MemAvailable", "the memory
 * cgroup's limit", "ulimit -v" or "ulimit -d". */
cl_status cl_mem_available(double *bytes, const char **limit,
                           cl_error *err);

/* The same with /proc and the cgroup file systems' mount point
 * (/sys/fs/cgroup) at other places: the files of a test. */
cl_status cl_mem_available_at(const char *proc, const char *cgroup,
                              double *bytes, const char **limit,
                              cl_error *err);

/* RLIMIT_DATA's soft limit before cl_mem_cap_data lowered it. */
typedef struct {
    bool lowered;
    unsigned long long soft;
    double available;  /* bytes the data may still grow by under the cap */
    const char *limit; /* and the limit that sets them ("MemAvailable
                        * and free swap", the cgroup's, "ulimit -v" or
                        * "ulimit -d"); NULL when not known: no cap */
} cl_mem_cap;

/* Lower RLIMIT_DATA's soft limit to the process's data size plus what
 * the machine or the job can still give (cl_mem_available with the free
 * swap beside MemAvailable: the point of the kernel's OOM kill, not of
 * swapping; RLIMIT_DATA itself left out), never raising it, so that
 * allocations beyond it fail; no cap when that is not known or cannot be
 * set.  cap tells what was
 * available, and cl_mem_cap_release restores the limit. */
void cl_mem_cap_data(cl_mem_cap *cap);
void cl_mem_cap_release(const cl_mem_cap *cap);

CL_END_DECLS

#endif
