/* Atomic output files (temporary file + fsync + rename) and mkdir -p. */
#include "io/atomic.h"

#include "io/input.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

static void afile_reset(cl_afile *af)
{
    free(af->path);
    free(af->tmp);
    af->fp = NULL;
    af->path = NULL;
    af->tmp = NULL;
}

static char *dup_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d)
        memcpy(d, s, n);
    return d;
}

/* Undo an open that failed after mkstemp (errno says why): close fd,
 * remove the temporary file, reset; "cannot <verb> 'PATH': reason". */
static cl_status open_fail(cl_afile *af, int fd, const char *verb,
                           const char *path, cl_error *err)
{
    int e = errno;
    (void)close(fd);
    (void)unlink(af->tmp);
    afile_reset(af);
    return cl_error_set(err, CL_EIO, "cannot %s '%s': %s", verb, path,
                        strerror(e));
}

cl_status cl_output_check(const char *path, cl_error *err)
{
    struct stat st;
    if (!path || !*path)
        return cl_error_set(err, CL_EINVAL, "output file name is empty");
    if (lstat(path, &st) != 0 || S_ISREG(st.st_mode))
        return CL_OK;
    return cl_error_set(err, CL_EIO, "cannot write '%s': it is %s; an output "
                        "replaces only a regular file (choose another path)",
                        path, cl_file_kind(st.st_mode));
}

cl_status cl_afile_open(cl_afile *af, const char *path, cl_error *err)
{
    static const char suffix[] = ".tmp.XXXXXX";
    af->fp = NULL;
    af->path = NULL;
    af->tmp = NULL;
    cl_status rc = cl_output_check(path, err);
    if (rc)
        return rc;

    size_t n = strlen(path);
    af->path = dup_str(path);
    af->tmp = malloc(n + sizeof suffix);
    if (!af->path || !af->tmp) {
        afile_reset(af);
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", path);
    }
    memcpy(af->tmp, path, n);
    memcpy(af->tmp + n, suffix, sizeof suffix);

    int fd = mkstemp(af->tmp);
    if (fd < 0) {
        int e = errno;
        afile_reset(af);
        return cl_error_set(err, CL_EIO, "cannot create '%s': %s", path,
                            strerror(e));
    }
    /* mkstemp creates mode 0600; give the file the usual 0666 & ~umask.
     * (umask can only be read by setting it; the code is single-threaded
     * where files are written.) */
    mode_t mask = umask(077);
    umask(mask);
    if (fchmod(fd, (mode_t)(0666 & ~mask)) != 0)
        return open_fail(af, fd, "create", path, err);
    af->fp = fdopen(fd, "w");
    if (!af->fp)
        return open_fail(af, fd, "open", path, err);
    return CL_OK;
}

cl_status cl_afile_commit(cl_afile *af, cl_error *err)
{
    if (!af->fp || !af->tmp || !af->path) {
        afile_reset(af);
        return cl_error_set(err, CL_EINVAL,
                            "commit of an output file that is not open");
    }
    const char *what = NULL;
    int e = 0;
    if (ferror(af->fp)) {
        what = "write error";
        e = errno ? errno : EIO;
    } else if (fflush(af->fp) != 0) {
        what = "write error";
        e = errno;
    } else if (fsync(fileno(af->fp)) != 0) {
        what = "fsync failed";
        e = errno;
    }
    /* Close in every case; after fclose the stream is gone even on error. */
    int rc = fclose(af->fp);
    af->fp = NULL;
    if (!what && rc != 0) {
        what = "close failed";
        e = errno;
    }
    cl_error special;
    if (!what && cl_output_check(af->path, &special)) {
        what = "it is no longer a regular file";
        e = EEXIST;
    }
    if (!what && rename(af->tmp, af->path) != 0) {
        what = "cannot rename temporary file onto it";
        e = errno;
    }
    if (what) {
        (void)unlink(af->tmp);
        cl_status st = cl_error_set(err, CL_EIO, "cannot write '%s': %s: %s",
                                    af->path, what, strerror(e));
        afile_reset(af);
        return st;
    }
    afile_reset(af);
    return CL_OK;
}

void cl_afile_abort(cl_afile *af)
{
    if (!af)
        return;
    if (af->fp)
        (void)fclose(af->fp);
    if (af->tmp)
        (void)unlink(af->tmp);
    afile_reset(af);
}

/* One component: fine if it is a directory, else try to create it. */
static cl_status mkdir_one(const char *full, const char *part, cl_error *err)
{
    struct stat st;
    if (stat(part, &st) == 0) {
        if (S_ISDIR(st.st_mode))
            return CL_OK;
        return cl_error_set(err, CL_EIO,
                            "cannot create directory '%s': '%s' exists and "
                            "is not a directory", full, part);
    }
    if (mkdir(part, 0777) == 0)
        return CL_OK;
    int e = errno;
    /* Somebody may have created it in between. */
    if (e == EEXIST && stat(part, &st) == 0 && S_ISDIR(st.st_mode))
        return CL_OK;
    return cl_error_set(err, CL_EIO, "cannot create directory '%s': %s",
                        part, strerror(e));
}

cl_status cl_mkdir_p(const char *dir, cl_error *err)
{
    if (!dir || !*dir)
        return cl_error_set(err, CL_EINVAL, "directory name is empty");
    char *buf = dup_str(dir);
    if (!buf)
        return cl_error_set(err, CL_ENOMEM, "%s: out of memory", dir);

    cl_status st = CL_OK;
    /* Start after a leading '/', which always exists. */
    for (char *p = buf + 1; st == CL_OK; p++) {
        if (*p != '/' && *p != '\0')
            continue;
        char c = *p;
        if (p[-1] != '/') {     /* skip empty components ("a//b", "a/") */
            *p = '\0';
            st = mkdir_one(dir, buf, err);
            *p = c;
        }
        if (c == '\0')
            break;
    }
    free(buf);
    return st;
}

cl_status cl_afile_write_error(const cl_afile *af, cl_error *err)
{
    int e = errno;
    return cl_error_set(err, CL_EIO, "cannot write '%s': %s", af->path,
                        strerror(e ? e : EIO));
}

cl_status cl_afile_fail(cl_afile *af, cl_error *err)
{
    cl_status st = cl_afile_write_error(af, err);
    cl_afile_abort(af);
    return st;
}
