/* libFuzzer harness: the INI loader with --set overrides (io/config).
 *
 * Input: a problem file, optionally followed by a line "%%set" and one
 * --set assignment per line.  The loaded configuration is read through
 * every kind of getter, then written and read back: the written file must
 * load, and writing it again must give the same bytes (the saved
 * config.ini reads back to the same configuration). */
#define _GNU_SOURCE
#include <math.h>
#include <string.h>

#include "io/config.h"
#include "fuzz.h"

static const char *const choices[] = {"cvode-bdf", "fe", "rk4", NULL};

static void get_all(cl_config *cfg)
{
    cl_error err;
    double d, g[3];
    long l;
    bool b;
    int c;
    cl_config_double(cfg, "type1", "ks", 1, 0, INFINITY, &d, &err);
    cl_config_double(cfg, "run", "t_end", 1, 1e-9, INFINITY, &d, &err);
    cl_config_long(cfg, "cloth", "n", 16, 2, 4096, &l, &err);
    cl_config_bool(cfg, "springs", "enabled", false, &b, &err);
    cl_config_choice(cfg, "run", "integrator", choices, 0, &c, &err);
    cl_config_vector(cfg, "gravity", "g", 3, g, &err);
    cl_config_string(cfg, "pins", "at", "");
    cl_config_check_unused(cfg, &err);
}

/* The whole of the file at path, NUL-terminated; *len its size. */
static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "r");
    char *text = calloc(1, 1 << 16);
    if (!f || !text)
        abort();
    *len = fread(text, 1, (1 << 16) - 1, f);
    fclose(f);
    return text;
}

/* Write cfg, load the file again, write that: the same bytes.  The files
 * go to /dev/shm (tmpfs), where the writer's fsync costs nothing. */
static void round_trip(const cl_config *cfg)
{
    char a[64], b[64];
    cl_error err;
    snprintf(a, sizeof a, "/dev/shm/clothode-fuzz-%d-a.ini", (int)getpid());
    snprintf(b, sizeof b, "/dev/shm/clothode-fuzz-%d-b.ini", (int)getpid());
    if (cl_config_write(cfg, a, &err))
        abort();
    cl_config *back = cl_config_alloc();
    size_t la, lb;
    char *ta = slurp(a, &la);
    if (la > 0 && cl_config_load(back, a, &err)) {
        fprintf(stderr, "written config does not read back: %s\n%s\n",
                err.msg, ta);
        abort();
    }
    if (la > 0 && cl_config_write(back, b, &err))
        abort();
    char *tb = la > 0 ? slurp(b, &lb) : (lb = 0, calloc(1, 1));
    if (la != lb || memcmp(ta, tb, la)) {
        fprintf(stderr, "written twice, differs:\n%s\n---\n%s\n", ta, tb);
        abort();
    }
    free(ta);
    free(tb);
    cl_config_free(back);
    unlink(a);
    unlink(b);
}

int CL_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    static const char mark[] = "\n%%set\n";
    const uint8_t *sets = memmem(data, size, mark, sizeof mark - 1);
    size_t file_size = sets ? (size_t)(sets - data) + 1 : size;
    char path[64];
    cl_error err;
    int fd = fuzz_file(data, file_size, path, sizeof path);
    cl_config *cfg = cl_config_alloc();
    cl_status rc = cl_config_load(cfg, path, &err);
    close(fd);
    if (!rc && sets) {
        char *text = strndup((const char *)sets + sizeof mark - 1,
                             size - file_size - (sizeof mark - 2));
        for (char *save, *line = strtok_r(text, "\n", &save);
             !rc && line; line = strtok_r(NULL, "\n", &save))
            rc = cl_config_set_once(cfg, line, NULL, &err);
        free(text);
    }
    if (!rc) {
        get_all(cfg);
        round_trip(cfg);
    }
    cl_config_free(cfg);
    return 0;
}
