/* Input files (io/input.c): a regular file (or a link to one) opens; a
 * FIFO with no writer, a directory and /dev/null are refused at once,
 * saying what they are, and a missing file with the system's reason.
 * Lines are read up to a bound, telling a line too long and a buffer that
 * could not grow from the end of the file. */
#include <criterion/criterion.h>

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
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

/* Lines up to the bound, the newline kept; a longer one is refused
 * before the rest of it is read; the last line may lack its newline. */
Test(input, lines_are_read_up_to_the_bound)
{
    char text[] = "ab\n\nlonger than eight\nend";
    FILE *fp = fmemopen(text, strlen(text), "r");
    cr_assert_not_null(fp);
    char *line = NULL;
    size_t cap = 0;
    cr_assert_eq(cl_input_line(fp, &line, &cap, 8), 3);
    cr_assert_str_eq(line, "ab\n");
    cr_assert_eq(cl_input_line(fp, &line, &cap, 8), 1);
    cr_assert_str_eq(line, "\n");
    cr_assert_eq(cl_input_line(fp, &line, &cap, 8), CL_INPUT_LONG);
    cr_assert_leq(cap, 9, "the buffer stays within the bound");
    ssize_t len = cl_input_line(fp, &line, &cap, 64);
    cr_assert(len > 0 && len < 12 && strstr(line, "eight\n"),
              "the rest of the long line: %s", line);
    cr_assert_eq(cl_input_line(fp, &line, &cap, 8), 3);
    cr_assert_str_eq(line, "end");
    cr_assert_eq(cl_input_line(fp, &line, &cap, 8), CL_INPUT_END);
    free(line);
    fclose(fp);
}

/* A buffer that cannot grow (under a data limit a little above what the
 * process has) is told from the end of the file.  Not under
 * AddressSanitizer, whose allocator takes its memory from space reserved
 * at the start. */
#if !defined(__SANITIZE_ADDRESS__)
Test(input, a_buffer_that_cannot_grow_is_not_an_end)
{
    struct rlimit rl;
    cr_assert_eq(getrlimit(RLIMIT_DATA, &rl), 0);
    if (rl.rlim_cur != RLIM_INFINITY)
        cr_skip_test("a data limit (ulimit -d) is set already");
    size_t big = (size_t)64 << 20;
    char *text = malloc(big);
    cr_assert_not_null(text);
    memset(text, 'x', big);
    FILE *fp = fmemopen(text, big, "r");
    cr_assert_not_null(fp);
    long data_kb = 0;
    char status[128];
    FILE *st = fopen("/proc/self/status", "r");
    cr_assert_not_null(st);
    while (fgets(status, sizeof status, st))
        if (sscanf(status, "VmData: %ld kB", &data_kb) == 1)
            break;
    fclose(st);
    cr_assert_gt(data_kb, 0);
    rl.rlim_cur = (rlim_t)data_kb * 1024 + ((rlim_t)8 << 20);
    cr_assert_eq(setrlimit(RLIMIT_DATA, &rl), 0);
    char *line = NULL;
    size_t cap = 0;
    cr_assert_eq(cl_input_line(fp, &line, &cap, 2 * big), CL_INPUT_NOMEM);
    cr_assert_lt(cap, (size_t)16 << 20, "grown to %zu bytes", cap);
    free(line);
    fclose(fp);
    free(text);
}
#endif

/* What a text reader refuses of a line, with the file and line named. */
Test(input, line_refusals_name_file_and_line)
{
    cl_error err = {0};
    cr_assert_eq(cl_input_line_ok("1,2\n", 4, 64, "s.csv", 3, "a state file",
                                  "", &err), CL_OK);
    cr_assert_eq(cl_input_line_ok("a\0b\n", 4, 64, "s.csv", 3, "a state file",
                                  "", &err), CL_EPARSE);
    cr_assert_str_eq(err.msg, "s.csv:3: NUL byte (a state file is text)");
    cr_assert_eq(cl_input_line_ok("", CL_INPUT_LONG, 64, "s.csv", 4, "a state "
                                  "file", " (rows are short)", &err),
                 CL_EPARSE);
    cr_assert_str_eq(err.msg, "s.csv:4: a line longer than 64 bytes (rows "
                              "are short)");
    cr_assert_eq(cl_input_line_ok("", CL_INPUT_NOMEM, 64, "s.csv", 5, "a state "
                                  "file", "", &err), CL_ENOMEM);
    cr_assert_str_eq(err.msg, "s.csv:5: out of memory");
}
