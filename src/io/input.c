/* Regular input files only (see input.h). */
#include "io/input.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char *cl_file_kind(mode_t mode)
{
    return S_ISREG(mode)                    ? "a regular file"
           : S_ISDIR(mode)                  ? "a directory"
           : S_ISLNK(mode)                  ? "a symbolic link"
           : S_ISFIFO(mode)                 ? "a FIFO"
           : S_ISCHR(mode) || S_ISBLK(mode) ? "a device"
           : S_ISSOCK(mode)                 ? "a socket"
                                            : "of another kind";
}

bool cl_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 &&
           sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

/* "it is KIND, not a regular file" for a file that is not one. */
static const char *not_regular(mode_t mode)
{
    return S_ISDIR(mode)    ? "it is a directory, not a regular file"
           : S_ISFIFO(mode) ? "it is a FIFO, not a regular file"
           : S_ISCHR(mode) || S_ISBLK(mode)
               ? "it is a device, not a regular file"
           : S_ISSOCK(mode) ? "it is a socket, not a regular file"
                            : "it is not a regular file";
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
        *why = not_regular(st.st_mode);
    else if (fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0 ||
             !(fp = fdopen(fd, mode)))
        *why = strerror(errno);
    if (!fp)
        (void)close(fd);
    return fp;
}
