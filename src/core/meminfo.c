/* Available memory from /proc, the memory cgroups, sysinfo and getrlimit
 * (see meminfo.h). */
#include "core/meminfo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/sysinfo.h>

#define PATH_LEN 4096

/* The number after "key" at the start of a line of file dir/name, times
 * `unit`; NAN when the file or the key is absent. */
static double keyed_value(const char *dir, const char *name, const char *key,
                          double unit)
{
    char path[PATH_LEN], line[512];
    size_t len = strlen(key);
    double v = NAN;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "r");
    while (f && isnan(v) && fgets(line, sizeof line, f))
        if (!strncmp(line, key, len) && (line[len] == ' ' ||
                                         line[len] == ':' ||
                                         line[len] == '\t'))
            v = unit * strtod(line + len + 1, NULL);
    if (f)
        fclose(f);
    return v;
}

/* The number file dir/name holds; NAN when absent or "max" (no limit). */
static double file_value(const char *dir, const char *name)
{
    char path[PATH_LEN], text[64] = "";
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "r");
    char *end = text;
    double v = f && fgets(text, sizeof text, f) ? strtod(text, &end) : NAN;
    if (f)
        fclose(f);
    return end == text ? NAN : v;
}

/* Room left by the memory cgroup at dir (v2: memory.max, v1:
 * memory.limit_in_bytes; a v1 limit of 2^62 or more is none): the limit
 * less the use, plus the file pages the kernel reclaims first.  NAN
 * without a limit there. */
static double cgroup_room(const char *dir, bool v2)
{
    double max = file_value(dir, v2 ? "memory.max" : "memory.limit_in_bytes");
    double used = file_value(dir, v2 ? "memory.current"
                                     : "memory.usage_in_bytes");
    double file = keyed_value(dir, "memory.stat", v2 ? "file" : "total_cache",
                              1.0);
    /* tmpfs and shared memory count as file pages but are not reclaimed
     * without swap */
    double shmem = keyed_value(dir, "memory.stat",
                               v2 ? "shmem" : "total_shmem", 1.0);
    if (isnan(max) || max >= 0x1p62 || isnan(used))
        return NAN;
    return max - used + (isnan(file) ? 0.0 : file) -
           (isnan(shmem) ? 0.0 : shmem);
}

/* The least room left by the cgroup at `mount`/`path` and its ancestors. */
static double cgroup_path_room(const char *mount, const char *path, bool v2)
{
    char dir[PATH_LEN];
    double least = NAN;
    int n = snprintf(dir, sizeof dir, "%s%s", mount, path);
    if (n < 0 || (size_t)n >= sizeof dir)
        return NAN;
    for (size_t len = strlen(dir), root = strlen(mount);;) {
        while (len > root && dir[len - 1] == '/')
            dir[--len] = '\0';
        least = fmin(least, cgroup_room(dir, v2)); /* fmin skips a NAN */
        char *slash = strrchr(dir, '/');
        if (len <= root || !slash || (size_t)(slash - dir) < root)
            return least;
        len = (size_t)(slash - dir);
        dir[len] = '\0';
    }
}

/* Whether v1 controller list `list` ("cpu,memory") names memory. */
static bool names_memory(const char *list, size_t len)
{
    for (const char *p = list; p < list + len;) {
        size_t n = strcspn(p, ",:");
        if (n == 6 && !strncmp(p, "memory", 6))
            return true;
        p += n + 1;
    }
    return false;
}

/* The least room the process's memory cgroups leave (proc/self/cgroup:
 * "0::PATH" for v2, "N:...memory...:PATH" for v1); NAN if none limits. */
static double cgroups_room(const char *proc, const char *mount)
{
    char path[PATH_LEN], line[PATH_LEN], sub[PATH_LEN];
    double least = NAN;
    snprintf(path, sizeof path, "%s/self/cgroup", proc);
    FILE *f = fopen(path, "r");
    while (f && fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        char *ctl = strchr(line, ':'), *at = ctl ? strchr(ctl + 1, ':') : NULL;
        if (!at)
            continue;
        bool v2 = at == ctl + 1 && !strncmp(line, "0:", 2);
        double room = NAN;
        if (v2)
            room = cgroup_path_room(mount, at + 1, true);
        else if (names_memory(ctl + 1, (size_t)(at - ctl - 1)) &&
                 snprintf(sub, sizeof sub, "%s/memory", mount) <
                     (int)sizeof sub)
            room = cgroup_path_room(sub, at + 1, false);
        least = fmin(least, room);
    }
    if (f)
        fclose(f);
    return least;
}

/* Room under a soft resource limit for a process using `used` bytes of
 * it; NAN without a limit. */
static double rlimit_room(int resource, double used)
{
    struct rlimit rl;
    if (getrlimit(resource, &rl) != 0 || rl.rlim_cur == RLIM_INFINITY ||
        isnan(used))
        return NAN;
    return (double)rl.rlim_cur - used;
}

/* Keep `room` as the least so far, with its name. */
static void keep_least(double room, const char *name, double *least,
                       const char **which)
{
    if (!isnan(room) && room < *least) {
        *least = room;
        *which = name;
    }
}

/* cl_mem_available_at; for the data cap (`cap`), with the free swap
 * beside MemAvailable (what can be given at all before the OOM killer
 * acts) and without RLIMIT_DATA, the limit the cap itself sets. */
static cl_status available_at(const char *proc, const char *cgroup,
                              bool cap, double *bytes, const char **limit,
                              cl_error *err)
{
    double avail = keyed_value(proc, "meminfo", "MemAvailable", 1024.0);
    double swap_free = keyed_value(proc, "meminfo", "SwapFree", 1024.0);
    const char *which = "MemAvailable";
    if (cap && avail > 0 && swap_free > 0) {
        avail += swap_free;
        which = "MemAvailable and free swap";
    }
    struct sysinfo si;
    if (!(avail > 0) && sysinfo(&si) == 0)
        avail = ((double)si.freeram + (double)si.bufferram) * si.mem_unit;
    if (!(avail > 0))
        return cl_error_set(err, CL_EIO, "cannot tell the available memory"
                            " (no MemAvailable in %s/meminfo, no sysinfo)",
                            proc);
    char self[PATH_LEN];
    snprintf(self, sizeof self, "%s/self", proc);
    keep_least(cgroups_room(proc, cgroup), "the memory cgroup's limit",
               &avail, &which);
    keep_least(rlimit_room(RLIMIT_AS,
                           keyed_value(self, "status", "VmSize", 1024.0)),
               "ulimit -v", &avail, &which);
    if (!cap)
        keep_least(rlimit_room(RLIMIT_DATA,
                               keyed_value(self, "status", "VmData", 1024.0)),
                   "ulimit -d", &avail, &which);
    *bytes = fmax(avail, 0.0);
    if (limit)
        *limit = which;
    return CL_OK;
}

cl_status cl_mem_available_at(const char *proc, const char *cgroup,
                              double *bytes, const char **limit,
                              cl_error *err)
{
    return available_at(proc, cgroup, false, bytes, limit, err);
}

cl_status cl_mem_available(double *bytes, const char **limit,
                           cl_error *err)
{
    return cl_mem_available_at("/proc", "/sys/fs/cgroup", bytes, limit,
                               err);
}

void cl_mem_cap_data(cl_mem_cap *cap)
{
    struct rlimit rl;
    double avail, data = keyed_value("/proc/self", "status", "VmData",
                                     1024.0);
    cl_error ignored;
    *cap = (cl_mem_cap){.lowered = false};
    if (isnan(data) ||
        available_at("/proc", "/sys/fs/cgroup", true, &avail, &cap->limit,
                     &ignored) ||
        getrlimit(RLIMIT_DATA, &rl) != 0) {
        cap->limit = NULL;
        return; /* nothing known to cap at */
    }
    double want = data + avail;
    cap->available = avail;
    if (rl.rlim_cur != RLIM_INFINITY && (double)rl.rlim_cur <= want) {
        cap->available = fmax((double)rl.rlim_cur - data, 0.0);
        cap->limit = "ulimit -d"; /* the limit already set binds */
        return;
    }
    cap->soft = (unsigned long long)rl.rlim_cur;
    rl.rlim_cur = (rlim_t)want;
    cap->lowered = setrlimit(RLIMIT_DATA, &rl) == 0; /* else no cap */
}

void cl_mem_cap_release(const cl_mem_cap *cap)
{
    struct rlimit rl;
    if (cap->lowered && getrlimit(RLIMIT_DATA, &rl) == 0) {
        rl.rlim_cur = (rlim_t)cap->soft;
        setrlimit(RLIMIT_DATA, &rl);
    }
}
