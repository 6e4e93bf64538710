/* The build and host descriptions of version.h.  The BLAS and LAPACK are
 * those the dynamic linker loaded (Debian's alternatives may point
 * libblas.so.3 at OpenBLAS, ATLAS or the reference BLAS), found by the
 * file that holds dgemm_ and dgetrf_ (dladdr). */
#define _GNU_SOURCE
#include "cli/version.h"

#include <dlfcn.h>
#include <elf.h>
#include <limits.h>
#include <link.h>
#include <stdlib.h>
#include <string.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <SuiteSparse_config.h>
#include <gsl/gsl_version.h>
#include <nettle/version.h>
#include <sundials/sundials_version.h>

#include "buildinfo.h"

/* The file (resolved through symbolic links) that holds `symbol`, or
 * "unknown". */
static json_t *library_of(const char *symbol)
{
    Dl_info info;
    char real[PATH_MAX];
    void *at = dlsym(RTLD_DEFAULT, symbol);
    if (!at || !dladdr(at, &info) || !info.dli_fname)
        return json_string("unknown");
    if (!realpath(info.dli_fname, real))
        return json_string(info.dli_fname);
    return json_string(real);
}

/* OpenBLAS's own description of its build, when the BLAS is OpenBLAS. */
static json_t *openblas_config(void)
{
    char *(*config)(void) = NULL;
    *(void **)&config = dlsym(RTLD_DEFAULT, "openblas_get_config");
    return config ? json_string(config()) : json_null();
}

/* The GNU build ID of a loaded object (the linker's hash of its contents,
 * a note among its program headers) in hexadecimal into hex (129 bytes),
 * left as it was if it has none. */
static void build_id_of(const struct dl_phdr_info *info, char *hex)
{
    for (int k = 0; k < info->dlpi_phnum; k++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[k];
        if (ph->p_type != PT_NOTE)
            continue;
        /* notes are padded to the segment's alignment, 4 or 8 */
        size_t pad = ph->p_align == 8 ? 7 : 3;
        const char *at = (const char *)(info->dlpi_addr + ph->p_vaddr);
        const char *end = at + ph->p_memsz;
        while ((size_t)(end - at) >= sizeof(ElfW(Nhdr))) {
            const ElfW(Nhdr) *nh = (const ElfW(Nhdr) *)(const void *)at;
            const char *name = at + sizeof *nh;
            size_t namesz = (nh->n_namesz + pad) & ~pad;
            size_t descsz = (nh->n_descsz + pad) & ~pad;
            if ((size_t)(end - name) < namesz ||
                (size_t)(end - name) - namesz < nh->n_descsz)
                break;
            const unsigned char *desc = (const unsigned char *)name + namesz;
            if (nh->n_type == NT_GNU_BUILD_ID && nh->n_namesz == 4 &&
                !memcmp(name, "GNU", 4) && nh->n_descsz <= 64) {
                for (unsigned i = 0; i < nh->n_descsz; i++)
                    sprintf(hex + 2 * i, "%02x", desc[i]);
                return;
            }
            if ((size_t)(end - (const char *)desc) < descsz)
                break;
            at = (const char *)desc + descsz;
        }
    }
}

/* The first object dl_iterate_phdr visits is the program. */
static int program_build_id(struct dl_phdr_info *info, size_t size,
                            void *hex)
{
    (void)size;
    build_id_of(info, hex);
    return 1;
}

static json_t *build_id_json(void)
{
    char hex[129] = "";
    dl_iterate_phdr(program_build_id, hex);
    return *hex ? json_string(hex) : json_null();
}

/* A loaded plug-in (clothode-NAME.so, linalg/plugin.h) appended to the
 * list as {"path", "build_id"}. */
static int plugin_build_id(struct dl_phdr_info *info, size_t size,
                           void *list)
{
    (void)size;
    const char *base = strrchr(info->dlpi_name, '/');
    base = base ? base + 1 : info->dlpi_name;
    size_t n = strlen(base);
    if (n < 13 || strncmp(base, "clothode-", 9) || strcmp(base + n - 3, ".so"))
        return 0;
    char hex[129] = "", real[PATH_MAX];
    build_id_of(info, hex);
    json_array_append_new(list, json_pack(
        "{s:s, s:o}", "path",
        realpath(info->dlpi_name, real) ? real : info->dlpi_name, "build_id",
        *hex ? json_string(hex) : json_null()));
    return 0;
}

json_t *cl_cli_plugins_json(void)
{
    json_t *list = json_array();
    if (list)
        dl_iterate_phdr(plugin_build_id, list);
    return list;
}

static json_t *libraries_json(void)
{
    char sundials[64] = "unknown", text[64];
    int ss[3] = {0, 0, 0};
    SUNDIALSGetVersion(sundials, (int)sizeof sundials);
    SuiteSparse_version(ss);
    snprintf(text, sizeof text, "%d.%d.%d", ss[0], ss[1], ss[2]);
    json_t *o = json_object();
    json_object_set_new(o, "sundials", json_string(sundials));
    json_object_set_new(o, "suitesparse", json_string(text));
    json_object_set_new(o, "gsl", json_string(gsl_version));
    json_object_set_new(o, "blas", library_of("dgemm_"));
    json_object_set_new(o, "lapack", library_of("dgetrf_"));
    json_object_set_new(o, "openblas", openblas_config());
    json_object_set_new(o, "jansson", json_string(jansson_version_str()));
    snprintf(text, sizeof text, "%d.%d", nettle_version_major(),
             nettle_version_minor());
    json_object_set_new(o, "nettle", json_string(text));
    return o;
}

json_t *cl_cli_build_json(void)
{
    json_t *o = json_object();
    json_object_set_new(o, "version", json_string(CL_BUILD_VERSION));
    json_object_set_new(o, "commit", json_string(CL_BUILD_COMMIT));
    json_object_set_new(o, "compiler",
                        json_sprintf("%s (%s)", CL_BUILD_CC, __VERSION__));
    json_object_set_new(o, "flags", json_string(CL_BUILD_FLAGS));
    json_object_set_new(o, "build_id", build_id_json());
    json_object_set_new(o, "libraries", libraries_json());
    return o;
}

/* The first "model name" of /proc/cpuinfo, or "unknown". */
static json_t *cpu_model(void)
{
    FILE *fp = fopen("/proc/cpuinfo", "r");
    char line[512];
    json_t *name = NULL;
    while (fp && !name && fgets(line, sizeof line, fp)) {
        char *colon = strchr(line, ':');
        if (!strncmp(line, "model name", 10) && colon) {
            colon += 1 + (colon[1] == ' ');
            colon[strcspn(colon, "\n")] = '\0';
            name = json_string(colon);
        }
    }
    if (fp)
        fclose(fp);
    return name ? name : json_string("unknown");
}

json_t *cl_cli_host_json(void)
{
    struct utsname u;
    json_t *o = json_object();
    json_object_set_new(o, "cpu", cpu_model());
    json_object_set_new(o, "cores",
                        json_integer(sysconf(_SC_NPROCESSORS_ONLN)));
    if (uname(&u) == 0) {
        json_object_set_new(o, "system", json_sprintf("%s %s %s", u.sysname,
                                                      u.release, u.machine));
        json_object_set_new(o, "hostname", json_string(u.nodename));
    }
    return o;
}

static void print_object(FILE *fp, json_t *o)
{
    const char *key;
    json_t *value;
    json_object_foreach(o, key, value) {
        if (json_is_object(value))
            print_object(fp, value);
        else if (json_is_string(value))
            fprintf(fp, "%-12s %s\n", key, json_string_value(value));
    }
}

int cl_cli_version(FILE *fp)
{
    json_t *b = cl_cli_build_json();
    if (!b) {
        fprintf(stderr, "clothode: out of memory\n");
        return 1;
    }
    fprintf(fp, "clothode %s\n", CL_BUILD_VERSION);
    json_object_del(b, "version");
    print_object(fp, b);
    json_decref(b);
    return 0;
}
