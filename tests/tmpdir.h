/* Scratch directories and small file helpers for the tests that write
 * files (test_atomic, test_frames, test_mtx, test_series, test_state, and
 * the command-line tests through runcli.h).  Header-only: every function
 * is static inline and fails the calling test through Criterion's
 * assertions. */
#ifndef CL_TEST_TMPDIR_H
#define CL_TEST_TMPDIR_H

#include <criterion/criterion.h>

#include <dirent.h>
#include <errno.h>
#include <ftw.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>

/* A fresh directory "$TMPDIR/clothode-<tag>-XXXXXX", its name in buf
 * (/tmp when $TMPDIR is unset, empty, or too long for buf). */
static inline void tmp_mkdtemp(char *buf, size_t len, const char *tag)
{
    const char *tmp = getenv("TMPDIR");
    int n = snprintf(buf, len, "%s/clothode-%s-XXXXXX",
                     tmp && *tmp ? tmp : "/tmp", tag);
    if (n < 0 || (size_t)n >= len)
        n = snprintf(buf, len, "/tmp/clothode-%s-XXXXXX", tag);
    cr_assert(n > 0 && (size_t)n < len, "scratch directory name too long");
    cr_assert_not_null(mkdtemp(buf), "mkdtemp %s: %s", buf, strerror(errno));
}

static inline int tmp_rm_entry(const char *path, const struct stat *st,
                               int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    remove(path);
    return 0;
}

/* Remove path and, if it is a directory, everything below it (symbolic
 * links are removed, not followed). */
static inline void tmp_rm_rf(const char *path)
{
    if (path && *path)
        nftw(path, tmp_rm_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* The number of entries of dir other than "." and ".."; the names of the
 * first `max` of them go into names (NULL when max is 0). */
static inline size_t tmp_list_dir(const char *dir, char (*names)[256],
                                  size_t max)
{
    DIR *d = opendir(dir);
    cr_assert_not_null(d, "opendir %s: %s", dir, strerror(errno));
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        if (n < max)
            snprintf(names[n], 256, "%s", e->d_name);
        n++;
    }
    closedir(d);
    return n;
}

/* The file's content (at most len - 1 bytes), NUL-terminated. */
static inline void tmp_slurp(const char *path, char *buf, size_t len)
{
    FILE *fp = fopen(path, "r");
    cr_assert_not_null(fp, "cannot open %s", path);
    size_t n = fread(buf, 1, len - 1, fp);
    buf[n] = '\0';
    fclose(fp);
}

/* text written to path in `mode` ("w": replaced, "a": appended). */
static inline void tmp_write(const char *path, const char *mode,
                             const char *text)
{
    FILE *fp = fopen(path, mode);
    cr_assert_not_null(fp, "cannot write %s: %s", path, strerror(errno));
    cr_assert(fputs(text, fp) >= 0);
    cr_assert_eq(fclose(fp), 0);
}

/* Create or replace the file with `text`. */
static inline void tmp_put(const char *path, const char *text)
{
    tmp_write(path, "w", text);
}

/* Make writes beyond `bytes` fail with EFBIG (instead of SIGXFSZ); each
 * test runs in its own process, so the limit does not leak. */
static inline void tmp_limit_file_size(rlim_t bytes)
{
    cr_assert_neq(signal(SIGXFSZ, SIG_IGN), SIG_ERR);
    struct rlimit rl;
    cr_assert_eq(getrlimit(RLIMIT_FSIZE, &rl), 0);
    rl.rlim_cur = bytes;
    cr_assert_eq(setrlimit(RLIMIT_FSIZE, &rl), 0);
}

#endif
