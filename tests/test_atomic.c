/* Tests for atomic output files and cl_mkdir_p. */
#include <criterion/criterion.h>

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include "io/atomic.h"
#include "tmpdir.h"

static char dir[64];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "atomic");
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

TestSuite(atomic, .init = setup, .fini = teardown);

Test(atomic, commit_publishes_file)
{
    char path[256], buf[256];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    cl_afile af;
    cl_error err;
    cl_error_clear(&err);
    cr_assert_eq(cl_afile_open(&af, path, &err), CL_OK, "%s", err.msg);
    cr_assert_not_null(af.fp);
    cr_assert(strstr(af.tmp, "out.txt.tmp.") != NULL);
    /* Nothing at the final path yet, only the temporary file. */
    cr_assert_neq(access(path, F_OK), 0);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 1);
    cr_assert(fprintf(af.fp, "hello\n") > 0);
    cr_assert_eq(cl_afile_commit(&af, &err), CL_OK, "%s", err.msg);
    cr_assert_null(af.fp);
    tmp_slurp(path, buf, sizeof buf);
    cr_assert_str_eq(buf, "hello\n");
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 1);
    cl_afile_abort(&af);   /* no-op after commit */
    cr_assert_eq(access(path, F_OK), 0);
}

Test(atomic, commit_replaces_existing_file)
{
    char path[256], buf[256];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    tmp_put(path, "old contents\n");
    cl_afile af;
    cl_error err;
    cr_assert_eq(cl_afile_open(&af, path, &err), CL_OK);
    cr_assert(fprintf(af.fp, "new\n") > 0);
    /* Until commit the old file is untouched. */
    tmp_slurp(path, buf, sizeof buf);
    cr_assert_str_eq(buf, "old contents\n");
    cr_assert_eq(cl_afile_commit(&af, &err), CL_OK, "%s", err.msg);
    tmp_slurp(path, buf, sizeof buf);
    cr_assert_str_eq(buf, "new\n");
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 1);
}

Test(atomic, file_mode_follows_umask)
{
    char path[256];
    snprintf(path, sizeof path, "%s/mode.txt", dir);
    mode_t old = umask(022);
    cl_afile af;
    cl_error err;
    cr_assert_eq(cl_afile_open(&af, path, &err), CL_OK);
    cr_assert_eq(cl_afile_commit(&af, &err), CL_OK);
    umask(old);
    struct stat st;
    cr_assert_eq(stat(path, &st), 0);
    cr_assert_eq(st.st_mode & 0777, 0644, "mode %o", st.st_mode & 0777);
}

Test(atomic, abort_removes_temporary_and_keeps_old)
{
    char path[256], buf[256];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    tmp_put(path, "keep\n");
    cl_afile af;
    cl_error err;
    cr_assert_eq(cl_afile_open(&af, path, &err), CL_OK);
    cr_assert(fprintf(af.fp, "discard\n") > 0);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 2);
    cl_afile_abort(&af);
    cr_assert_null(af.fp);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 1);
    tmp_slurp(path, buf, sizeof buf);
    cr_assert_str_eq(buf, "keep\n");
    cl_afile_abort(&af);   /* second abort is harmless */
    cl_afile_abort(NULL);
}

Test(atomic, open_in_missing_directory)
{
    char path[256];
    snprintf(path, sizeof path, "%s/nodir/out.txt", dir);
    cl_afile af;
    cl_error err;
    cl_error_clear(&err);
    cr_assert_eq(cl_afile_open(&af, path, &err), CL_EIO);
    cr_assert_eq(err.code, CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, "No such file") != NULL, "%s", err.msg);
    cr_assert_null(af.fp);
    cl_afile_abort(&af);
}

Test(atomic, open_empty_name)
{
    cl_afile af;
    cl_error err;
    cr_assert_eq(cl_afile_open(&af, "", &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "empty") != NULL, "%s", err.msg);
}

Test(atomic, commit_failure_removes_temporary)
{
    /* A directory put in place of the output while it was being written:
     * the commit does not rename onto it and removes the temporary. */
    char path[256];
    snprintf(path, sizeof path, "%s/sub", dir);
    cl_afile af;
    cl_error err;
    cr_assert_eq(cl_afile_open(&af, path, &err), CL_OK);
    cr_assert_eq(mkdir(path, 0777), 0);
    cr_assert(fprintf(af.fp, "x\n") > 0);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 2);
    cr_assert_eq(cl_afile_commit(&af, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, "no longer a regular file") != NULL, "%s",
              err.msg);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 1);
    cr_assert_null(af.fp);
    cl_afile_abort(&af);
}

Test(atomic, commit_without_open)
{
    cl_afile af = {0};
    cl_error err;
    cr_assert_eq(cl_afile_commit(&af, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "not open") != NULL, "%s", err.msg);
}

Test(atomic, mkdir_p_creates_parents)
{
    char path[256];
    cl_error err;
    snprintf(path, sizeof path, "%s/a/b/c", dir);
    cr_assert_eq(cl_mkdir_p(path, &err), CL_OK, "%s", err.msg);
    struct stat st;
    cr_assert_eq(stat(path, &st), 0);
    cr_assert(S_ISDIR(st.st_mode));
    /* Existing directories are fine, trailing and doubled slashes too. */
    cr_assert_eq(cl_mkdir_p(path, &err), CL_OK, "%s", err.msg);
    snprintf(path, sizeof path, "%s/a//b/d/", dir);
    cr_assert_eq(cl_mkdir_p(path, &err), CL_OK, "%s", err.msg);
    snprintf(path, sizeof path, "%s/a/b/d", dir);
    cr_assert_eq(stat(path, &st), 0);
    cr_assert(S_ISDIR(st.st_mode));
    cr_assert_eq(cl_mkdir_p("/", &err), CL_OK);
}

Test(atomic, mkdir_p_relative)
{
    char cwd[1024];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    cr_assert_eq(chdir(dir), 0);
    cl_error err;
    cr_assert_eq(cl_mkdir_p("rel/x", &err), CL_OK, "%s", err.msg);
    struct stat st;
    cr_assert_eq(stat("rel/x", &st), 0);
    cr_assert(S_ISDIR(st.st_mode));
    cr_assert_eq(chdir(cwd), 0);
}

Test(atomic, mkdir_p_over_file)
{
    char file[256], path[300];
    cl_error err;
    snprintf(file, sizeof file, "%s/plain", dir);
    tmp_put(file, "x");
    cr_assert_eq(cl_mkdir_p(file, &err), CL_EIO);
    cr_assert(strstr(err.msg, "not a directory") != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, file) != NULL, "%s", err.msg);
    snprintf(path, sizeof path, "%s/sub/deeper", file);
    cr_assert_eq(cl_mkdir_p(path, &err), CL_EIO);
    cr_assert(strstr(err.msg, "not a directory") != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
}

Test(atomic, mkdir_p_empty)
{
    cl_error err;
    cr_assert_eq(cl_mkdir_p("", &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "empty") != NULL, "%s", err.msg);
}

Test(atomic, write_error_blocks_commit)
{
    char path[256];
    snprintf(path, sizeof path, "%s/big.txt", dir);
    cl_afile af;
    cl_error err;
    cr_assert_eq(cl_afile_open(&af, path, &err), CL_OK);
    tmp_limit_file_size(100);
    for (int k = 0; k < 1000; k++)
        if (fprintf(af.fp, "%d\n", k) < 0)
            break;
    cr_assert_eq(cl_afile_commit(&af, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, "write error") != NULL, "%s", err.msg);
    cr_assert_eq(access(path, F_OK), -1);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 0);
}

/* ---- outputs replace regular files only ------------------------------- */

/* mode, device and inode of path, to see that it was left alone */
static void stat_of(const char *path, struct stat *st)
{
    cr_assert_eq(lstat(path, st), 0, "lstat %s", path);
}

static void assert_same_node(const struct stat *a, const struct stat *b,
                             const char *path)
{
    cr_assert(a->st_mode == b->st_mode && a->st_ino == b->st_ino &&
                  a->st_rdev == b->st_rdev && a->st_dev == b->st_dev,
              "%s was replaced", path);
}

/* A device node of our own (a copy of /dev/null's, as root), so that
 * nothing else on the machine can change it during the test; /dev/null
 * itself otherwise. */
static const char *device_node(char *buf, size_t len)
{
    snprintf(buf, len, "%s/null", dir);
    return mknod(buf, S_IFCHR | 0666, makedev(1, 3)) == 0 ? buf
                                                           : "/dev/null";
}

Test(atomic, special_files_are_refused_and_untouched)
{
    char fifo[256], sub[256], node[256];
    snprintf(fifo, sizeof fifo, "%s/pipe", dir);
    snprintf(sub, sizeof sub, "%s/sub", dir);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    cr_assert_eq(mkdir(sub, 0700), 0);
    const char *dev = device_node(node, sizeof node);
    const char *paths[] = {fifo, sub, dev};
    const char *what[] = {"a FIFO", "a directory", "a device"};
    for (size_t k = 0; k < 3; k++) {
        struct stat before, after;
        cl_afile af;
        cl_error err = {0};
        stat_of(paths[k], &before);
        cr_assert_eq(cl_output_check(paths[k], &err), CL_EIO, "%s",
                     paths[k]);
        cr_assert(strstr(err.msg, what[k]) && strstr(err.msg, paths[k]),
                  "%s", err.msg);
        cr_assert_eq(cl_afile_open(&af, paths[k], &err), CL_EIO);
        cr_assert_null(af.fp);
        stat_of(paths[k], &after);
        assert_same_node(&before, &after, paths[k]);
    }
    /* only the FIFO, the directory and the node: no temporary was made */
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), dev == node ? 3u : 2u);
}

Test(atomic, symbolic_link_is_refused)
{
    char target[256], link[256];
    cl_error err = {0};
    snprintf(target, sizeof target, "%s/target", dir);
    snprintf(link, sizeof link, "%s/link", dir);
    tmp_put(target, "kept\n");
    cr_assert_eq(symlink(target, link), 0);
    cr_assert_eq(cl_output_check(link, &err), CL_EIO);
    cr_assert(strstr(err.msg, "symbolic link"), "%s", err.msg);
    cr_assert_eq(cl_output_check(target, &err), CL_OK);
}
