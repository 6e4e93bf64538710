/* Plug-in loading (linalg/plugin.h): dlopen by name from the places the
 * header lists, each plug-in once per process, refused unless it was built
 * for this program's plug-in interface (CL_PLUGIN_ABI). */
#include "linalg/plugin.h"

#include <dlfcn.h>
#include <libgen.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "pluginabi.h"

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

/* The plug-in at path, just opened as h, against this program's interface
 * version: closed and refused unless its clp_plugin_abi is
 * CL_PLUGIN_ABI. */
static cl_status check_abi(void *h, const char *path, cl_error *err)
{
    const char *abi = dlsym(h, "clp_plugin_abi");
    if (abi && strncmp(abi, CL_PLUGIN_ABI, sizeof CL_PLUGIN_ABI) == 0)
        return CL_OK;
    cl_status rc =
        abi ? cl_error_set(err, CL_EUNSUPPORTED, "plug-in %s was built for "
                           "plug-in interface %.40s, this program for %s: "
                           "build both from the same sources (`make`)",
                           path, abi, CL_PLUGIN_ABI)
            : cl_error_set(err, CL_EUNSUPPORTED, "plug-in %s has no "
                           "plug-in interface version (clp_plugin_abi), "
                           "this program's is %s: build both from the same "
                           "sources (`make`)", path, CL_PLUGIN_ABI);
    dlclose(h);
    return rc;
}

/* The first of the places linalg/plugin.h lists that holds the plug-in,
 * into *handle if its interface version is this program's. */
static cl_status open_plugin(const char *name, void **handle, cl_error *err)
{
    char file[64], dir[PATH_MAX], path[PATH_MAX + 96], tried[2048] = "";
    snprintf(file, sizeof file, "clothode-%s.so", name);
    const char *env = getenv("CLOTHODE_PLUGIN_DIR");
    *handle = NULL;
    if (env && *env) {
        snprintf(path, sizeof path, "%s/%s", env, file);
        *handle = try_open(path, tried, sizeof tried);
    }
    program_dir(dir, sizeof dir);
    if (!*handle && dir[0]) {
        snprintf(path, sizeof path, "%s/%s", dir, file);
        *handle = try_open(path, tried, sizeof tried);
    }
    if (!*handle && dir[0]) {
        snprintf(path, sizeof path, "%s/../lib/clothode/%s", dir, file);
        *handle = try_open(path, tried, sizeof tried);
    }
#ifdef CL_PLUGIN_INSTALL_DIR
    if (!*handle) {
        snprintf(path, sizeof path, "%s/%s", CL_PLUGIN_INSTALL_DIR, file);
        *handle = try_open(path, tried, sizeof tried);
    }
#endif
    if (!*handle)
        return cl_error_set(err, CL_EUNSUPPORTED,
                            "plug-in %s not found: tried %s; `make` builds "
                            "it beside the program, `make install` into "
                            "PREFIX/lib/clothode, where the installed "
                            "library looks; CLOTHODE_PLUGIN_DIR names "
                            "another folder", file,
                            tried[0] ? tried : "nothing");
    cl_status rc = check_abi(*handle, path, err);
    if (rc != CL_OK)
        *handle = NULL;
    return rc;
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
