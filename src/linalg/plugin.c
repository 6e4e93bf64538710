/* Plug-in loading (linalg/plugin.h): dlopen by name from the places the
 * header lists, each plug-in once per process. */
#include "linalg/plugin.h"

#include <dlfcn.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CL_PLUGIN_MAX 4

typedef struct {
    char name[32];
    void *handle;
} loaded_plugin;

static loaded_plugin plugins[CL_PLUGIN_MAX];

/* The folder of the running program, or "" if /proc does not tell. */
static void program_dir(char *dir, size_t len)
{
    char exe[PATH_MAX];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) {
        dir[0] = '\0';
        return;
    }
    exe[n] = '\0';
    snprintf(dir, len, "%s", dirname(exe));
}

/* Try one candidate; on failure append its path and dlerror to tried. */
static void *try_open(const char *path, char *tried, size_t len)
{
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        size_t used = strlen(tried);
        const char *why = dlerror();
        snprintf(tried + used, len - used, "%s%s (%s)", used ? "; " : "",
                 path, why ? why : "not loadable");
    }
    return h;
}

static cl_status open_plugin(const char *name, void **handle, cl_error *err)
{
    char file[64], dir[PATH_MAX], path[PATH_MAX + 96], tried[2048] = "";
    snprintf(file, sizeof file, "clothode-%s.so", name);
    const char *env = getenv("CLOTHODE_PLUGIN_DIR");
    if (env && *env) {
        snprintf(path, sizeof path, "%s/%s", env, file);
        if ((*handle = try_open(path, tried, sizeof tried)))
            return CL_OK;
    }
    program_dir(dir, sizeof dir);
    if (dir[0]) {
        snprintf(path, sizeof path, "%s/%s", dir, file);
        if ((*handle = try_open(path, tried, sizeof tried)))
            return CL_OK;
        snprintf(path, sizeof path, "%s/../lib/clothode/%s", dir, file);
        if ((*handle = try_open(path, tried, sizeof tried)))
            return CL_OK;
    }
    return cl_error_set(err, CL_EUNSUPPORTED,
                        "plug-in %s not found: tried %s; `make` builds it "
                        "beside the program, CLOTHODE_PLUGIN_DIR names "
                        "another folder", file, tried[0] ? tried : "nothing");
}

static cl_status find_plugin(const char *name, void **handle, cl_error *err)
{
    int i = 0;
    for (; i < CL_PLUGIN_MAX && plugins[i].handle; i++)
        if (strcmp(plugins[i].name, name) == 0) {
            *handle = plugins[i].handle;
            return CL_OK;
        }
    if (i == CL_PLUGIN_MAX || strlen(name) >= sizeof plugins[i].name)
        return cl_error_set(err, CL_EINVAL, "plug-in \"%s\": at most %d "
                            "plug-ins of names under %zu characters", name,
                            CL_PLUGIN_MAX, sizeof plugins[i].name);
    cl_status rc = open_plugin(name, handle, err);
    if (rc == CL_OK) {
        snprintf(plugins[i].name, sizeof plugins[i].name, "%s", name);
        plugins[i].handle = *handle;
    }
    return rc;
}

cl_status cl_plugin_symbol(const char *plugin, const char *symbol,
                           void **address, cl_error *err)
{
    void *handle = NULL;
    cl_status rc = find_plugin(plugin, &handle, err);
    if (rc != CL_OK)
        return rc;
    dlerror();
    *address = dlsym(handle, symbol);
    if (!*address)
        return cl_error_set(err, CL_EINVAL, "plug-in clothode-%s.so has no "
                            "entry point %s (built from another version?)",
                            plugin, symbol);
    return CL_OK;
}
