/* Tests for core/meminfo: the available memory is positive and no more
 * than the machine's (MemTotal) or the address-space limit; the memory
 * cgroups' limits (v1 and v2, on files laid out as /proc and
 * /sys/fs/cgroup lay them out) and the data limit lower it; the data cap
 * makes an allocation beyond it fail and is lifted again. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include "core/meminfo.h"
#include "tmpdir.h"

Test(meminfo, available_lies_between_zero_and_the_total)
{
    double avail = 0, total_kb = 0;
    cl_error err = {0};
    cr_assert_eq(cl_mem_available(&avail, NULL, &err), CL_OK, "%s", err.msg);
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

/* A file under the scratch tree, its directories made. */
static void put_under(const char *root, const char *rel, const char *text)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    for (char *p = path + strlen(root) + 1; (p = strchr(p, '/')); p++) {
        *p = '\0';
        mkdir(path, 0755);
        *p = '/';
    }
    tmp_put(path, text);
}

static double available_at(const char *root, const char **limit)
{
    char proc[600], cg[600];
    double avail = -1;
    cl_error err = {0};
    snprintf(proc, sizeof proc, "%s/proc", root);
    snprintf(cg, sizeof cg, "%s/cgroup", root);
    cr_assert_eq(cl_mem_available_at(proc, cg, &avail, limit, &err), CL_OK,
                 "%s", err.msg);
    return avail;
}

Test(meminfo, cgroup_limits_lower_the_available_memory)
{
    char root[512];
    const char *limit = NULL;
    tmp_mkdtemp(root, sizeof root, "meminfo");
    put_under(root, "proc/meminfo", "MemTotal: 9000 kB\nMemFree: 10 kB\n"
                                    "MemAvailable:    4000 kB\n");
    put_under(root, "proc/self/status", "Name: x\nVmSize: 1 kB\n");
    cr_assert_eq(available_at(root, &limit), 4096000.0);
    cr_assert_str_eq(limit, "MemAvailable");
    /* v2: the parent's memory.max binds (the job's), the cgroup's own is
     * "max"; its file pages count as room */
    put_under(root, "proc/self/cgroup", "0::/job/step\n");
    put_under(root, "cgroup/job/step/memory.max", "max\n");
    put_under(root, "cgroup/job/memory.max", "3000000\n");
    put_under(root, "cgroup/job/memory.current", "2500000\n");
    put_under(root, "cgroup/job/memory.stat", "anon 2000000\nfile 400000\n"
                                              "file_mapped 7\n");
    cr_assert_eq(available_at(root, &limit), 900000.0);
    cr_assert_str_eq(limit, "the memory cgroup's limit");
    /* v1: limit_in_bytes less usage plus total_cache, the ancestors'
     * unlimited 2^63 - 4096 ignored, the least of v1 and v2 */
    put_under(root, "proc/self/cgroup", "0::/job/step\n"
                                        "4:cpuacct,memory:/batch/7\n"
                                        "3:cpu:/other\n");
    put_under(root, "cgroup/memory/batch/7/memory.limit_in_bytes",
              "1000000\n");
    put_under(root, "cgroup/memory/batch/7/memory.usage_in_bytes",
              "800000\n");
    put_under(root, "cgroup/memory/batch/7/memory.stat",
              "cache 5\ntotal_cache 100000\n");
    put_under(root, "cgroup/memory/batch/memory.limit_in_bytes",
              "9223372036854771712\n");
    put_under(root, "cgroup/memory/memory.limit_in_bytes",
              "9223372036854771712\n");
    cr_assert_eq(available_at(root, &limit), 300000.0);
    /* a cgroup used up counts as nothing left */
    put_under(root, "cgroup/memory/batch/7/memory.usage_in_bytes",
              "1200000\n");
    cr_assert_eq(available_at(root, NULL), 0.0);
    tmp_rm_rf(root);
}

/* ulimit -d: the room left under RLIMIT_DATA (each test runs in its own
 * process, so the limit does not leak).  ASan reserves its shadow memory
 * as data, so the limit is set above what the process already has. */
Test(meminfo, data_limit_lowers_the_available_memory)
{
    double avail = 0, before = 0;
    const char *limit = NULL;
    cl_error err = {0};
    cr_assert_eq(cl_mem_available(&before, NULL, &err), CL_OK);
    cr_assert_gt(before, 64e6, "%g bytes available", before);
    struct rlimit rl;
    cr_assert_eq(getrlimit(RLIMIT_DATA, &rl), 0);
    if (rl.rlim_cur != RLIM_INFINITY)
        cr_skip_test("a data limit (ulimit -d) is set already");
    cl_mem_cap cap;
    cl_mem_cap_data(&cap);
    cr_assert(cap.lowered);
    cr_assert_eq(getrlimit(RLIMIT_DATA, &rl), 0);
    /* the cap is the data size plus what is available, free swap
     * included: at least what cl_mem_available said (other processes
     * allocate meanwhile) */
    cr_assert_eq(cl_mem_available(&avail, &limit, &err), CL_OK);
    cr_assert(avail > 0.8 * before - 64e6, "%g against %g", avail, before);
    /* an allocation beyond it fails instead of the kernel's OOM kill
     * (AddressSanitizer's allocator takes its memory from space reserved
     * at the start, and counted then) */
#if !defined(__SANITIZE_ADDRESS__)
    void *big = malloc((size_t)rl.rlim_cur);
    cr_assert_null(big);
#endif
    cl_mem_cap_release(&cap);
    struct rlimit after;
    cr_assert_eq(getrlimit(RLIMIT_DATA, &after), 0);
    cr_assert_eq(after.rlim_cur, cap.soft);
    cr_assert_neq(after.rlim_cur, rl.rlim_cur);
    /* a lower limit already set is kept: the data size and half of what
     * was available */
    double data_kb = 0;
    FILE *st = fopen("/proc/self/status", "r");
    char line[256];
    while (st && fgets(line, sizeof line, st))
        sscanf(line, "VmData: %lf kB", &data_kb);
    if (st)
        fclose(st);
    cr_assert_gt(data_kb, 0);
    rl.rlim_cur = (rlim_t)(1024 * data_kb + before / 2);
    cr_assert_eq(setrlimit(RLIMIT_DATA, &rl), 0);
    cl_mem_cap_data(&cap);
    cr_assert(!cap.lowered);
    cr_assert_eq(cl_mem_available(&avail, &limit, &err), CL_OK);
    cr_assert_str_eq(limit, "ulimit -d");
    cr_assert(avail < 0.8 * before, "%g against %g", avail, before);
}
