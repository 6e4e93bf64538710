/* Regular input files only (see input.h). */
#include "io/input.h"

#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/sha256.h"

/* The kinds of file, for messages: what it is, and the refusal of an
 * input that is not a regular one (literals: no buffer to share). */
static const struct {
    const char *kind, *refusal;
} kinds[] = {
    {"a regular file", NULL},
    {"a directory", "it is a directory, not a regular file"},
    {"a symbolic link", "it is a symbolic link, not a regular file"},
    {"a FIFO", "it is a FIFO, not a regular file"},
    {"a device", "it is a device, not a regular file"},
    {"a socket", "it is a socket, not a regular file"},
    {"of another kind", "it is not a regular file"},
};

static size_t kind_of(mode_t mode)
{
    return S_ISREG(mode)                    ? 0
           : S_ISDIR(mode)                  ? 1
           : S_ISLNK(mode)                  ? 2
           : S_ISFIFO(mode)                 ? 3
           : S_ISCHR(mode) || S_ISBLK(mode) ? 4
           : S_ISSOCK(mode)                 ? 5
                                            : 6;
}

const char *cl_file_kind(mode_t mode)
{
    return kinds[kind_of(mode)].kind;
}

bool cl_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 &&
           sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* Whether two readable files hold the same bytes (by SHA-256). */
static bool same_bytes(const char *a, const char *b)
{
    char ha[CL_SHA256_HEX], hb[CL_SHA256_HEX];
    cl_error ignored;
    return !cl_sha256_file(a, ha, &ignored) &&
           !cl_sha256_file(b, hb, &ignored) && !strcmp(ha, hb);
}

bool cl_same_input(const char *recorded, const char *mine)
{
    if (!strcmp(recorded, mine) || cl_same_file(recorded, mine))
        return true;
    if (access(recorded, R_OK) == 0)
        return same_bytes(recorded, mine);
    const char *ra = strrchr(recorded, '/'), *mb = strrchr(mine, '/');
    return !strcmp(ra ? ra + 1 : recorded, mb ? mb + 1 : mine);
}

FILE *cl_input_open(const char *path, const char *mode, const char **why)
{
    struct stat st;
    int fd = open(path, O_RDONLY | O_NONBLOCK);
    if (fd < 0) {
        *why = strerror(errno);
        return NULL;
    }
    int flags = fstat(fd, &st) == 0 ? fcntl(fd, F_GETFL) : -1;
    FILE *fp = NULL;
    if (flags < 0)
        *why = strerror(errno);
    else if (!S_ISREG(st.st_mode))
        *why = kinds[kind_of(st.st_mode)].refusal;
    else if (fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0 ||
             !(fp = fdopen(fd, mode)))
        *why = strerror(errno);
    if (!fp)
        (void)close(fd);
    return fp;
}

cl_status cl_input_line_ok(const char *line, ssize_t len, size_t max,
                           const char *path, size_t lineno, const char *kind,
                           const char *hint, cl_error *err)
{
    if (len == CL_INPUT_NOMEM)
        return cl_error_set(err, CL_ENOMEM, "%s:%zu: out of memory", path,
                            lineno);
    if (len == CL_INPUT_LONG)
        return cl_error_set(err, CL_EPARSE, "%s:%zu: a line longer than %zu "
                            "bytes%s", path, lineno, max, hint);
    if (memchr(line, '\0', (size_t)len))
        return cl_error_set(err, CL_EPARSE, "%s:%zu: NUL byte (%s is text)",
                            path, lineno, kind);
    return CL_OK;
}

ssize_t cl_input_line(FILE *fp, char **line, size_t *cap, size_t max)
{
    size_t n = 0;
    int ch = EOF;
    while ((ch = getc(fp)) != EOF) {
        if (n == max)
            return CL_INPUT_LONG;
        if (n + 2 > *cap) {
            size_t grown = *cap ? 2 * *cap : 128;
            grown = grown < max + 1 ? grown : max + 1;
            char *p = realloc(*line, grown);
            if (!p)
                return CL_INPUT_NOMEM;
            *line = p;
            *cap = grown;
        }
        (*line)[n++] = (char)ch;
        if (ch == '\n')
            break;
    }
    if (n == 0)
        return CL_INPUT_END;
    (*line)[n] = '\0';
    return (ssize_t)n;
}
