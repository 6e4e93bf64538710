/* Input files (io/input.c): a regular file (or a link to one) opens; a
 * FIFO with no writer, a directory and /dev/null are refused at once,
 * saying what they are, and a missing file with the system's reason. */
#include <criterion/criterion.h>

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/input.h"
#include "timelimit.h"
#include "tmpdir.h"

Test(input, only_regular_files_are_read)
{
    char dir[512], file[600], link[600], fifo[600], line[16];
    const char *why = NULL;
    time_limit(10); /* a FIFO opened for reading blocks without a writer */
    tmp_mkdtemp(dir, sizeof dir, "input");
    snprintf(file, sizeof file, "%s/a.ini", dir);
    snprintf(link, sizeof link, "%s/b.ini", dir);
    snprintf(fifo, sizeof fifo, "%s/f.ini", dir);
    FILE *fp = fopen(file, "w");
    cr_assert_not_null(fp);
    fputs("text\n", fp);
    fclose(fp);
    cr_assert_eq(symlink(file, link), 0);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    const char *ok[] = {file, link};
    for (int k = 0; k < 2; k++) {
        fp = cl_input_open(ok[k], "r", &why);
        cr_assert_not_null(fp, "%s: %s", ok[k], why);
        cr_assert_str_eq(fgets(line, sizeof line, fp), "text\n");
        fclose(fp);
    }
    const struct {
        const char *path, *why;
    } refused[] = {{fifo, "it is a FIFO, not a regular file"},
                   {dir, "it is a directory, not a regular file"},
                   {"/dev/null", "it is a device, not a regular file"}};
    for (int k = 0; k < 3; k++) {
        cr_assert_null(cl_input_open(refused[k].path, "r", &why));
        cr_assert_str_eq(why, refused[k].why, "%s", refused[k].path);
    }
    cr_assert_null(cl_input_open("/nonexistent/x.ini", "r", &why));
    cr_assert_str_eq(why, strerror(ENOENT));
    tmp_rm_rf(dir);
}

/* A path written down elsewhere names an input file when it is that file,
 * or it is readable here with the same bytes, or, not here (planned on
 * another machine), it has the same file name. */
Test(input, same_input_by_file_bytes_or_name)
{
    char dir[512], a[600], b[600], c[600], gone[600], other[600];
    tmp_mkdtemp(dir, sizeof dir, "sameinput");
    snprintf(a, sizeof a, "%s/hang.ini", dir);
    snprintf(b, sizeof b, "%s/copy.ini", dir);
    snprintf(c, sizeof c, "%s/edited.ini", dir);
    snprintf(gone, sizeof gone, "/nonexistent/cluster/hang.ini");
    snprintf(other, sizeof other, "/nonexistent/cluster/spring2.ini");
    tmp_put(a, "[type1]\nks = 200\n");
    tmp_put(b, "[type1]\nks = 200\n");
    tmp_put(c, "[type1]\nks = 300\n");
    cr_assert(cl_same_input(a, a));
    cr_assert(cl_same_input(b, a));
    cr_assert(!cl_same_input(c, a));
    cr_assert(cl_same_input(gone, a));
    cr_assert(!cl_same_input(other, a));
    tmp_rm_rf(dir);
}
