/* Tests for the CSV time-series writer. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/series.h"
#include "tmpdir.h"

static char dir[64];
static char path[256];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "series");
    snprintf(path, sizeof path, "%s/energy.csv", dir);
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

static const char *const cols[] = {"t", "kinetic", "potential"};

TestSuite(series, .init = setup, .fini = teardown);

Test(series, rows_then_close)
{
    cl_series *s;
    cl_error err;
    cr_assert_eq(cl_series_open(path, 3, cols, &s, &err), CL_OK, "%s",
                 err.msg);
    double r1[] = {0, 1.0 / 3.0, -2.5e-12};
    double r2[] = {0.01, 123456789012.0, 4};
    cr_assert_eq(cl_series_row(s, r1, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_series_row(s, r2, &err), CL_OK, "%s", err.msg);

    /* Not published yet, but every row is already in the temporary file. */
    cr_assert_eq(access(path, F_OK), -1);
    char names[4][256], tmp[600], buf[1024];
    cr_assert_eq(tmp_list_dir(dir, names, 4), 1);
    cr_assert_eq(strncmp(names[0], "energy.csv.tmp.", 15), 0, "%s",
                 names[0]);
    snprintf(tmp, sizeof tmp, "%s/%s", dir, names[0]);
    const char *expect = "t,kinetic,potential\n"
                         "0,0.3333333333,-2.5e-12\n"
                         "0.01,1.23456789e+11,4\n";
    tmp_slurp(tmp, buf, sizeof buf);
    cr_assert_str_eq(buf, expect);

    cr_assert_eq(cl_series_close(s, &err), CL_OK, "%s", err.msg);
    tmp_slurp(path, buf, sizeof buf);
    cr_assert_str_eq(buf, expect);
    cr_assert_eq(tmp_list_dir(dir, names, 4), 1);
}

Test(series, header_only_and_non_finite)
{
    cl_series *s;
    cl_error err;
    cr_assert_eq(cl_series_open(path, 1, cols, &s, &err), CL_OK);
    cr_assert_eq(cl_series_close(s, &err), CL_OK);
    char buf[256];
    tmp_slurp(path, buf, sizeof buf);
    cr_assert_str_eq(buf, "t\n");

    /* A blow-up row is recorded, then the series is closed as on any
     * error path and replaces the previous file. */
    cr_assert_eq(cl_series_open(path, 3, cols, &s, &err), CL_OK);
    double r[] = {1, NAN, -INFINITY};
    cr_assert_eq(cl_series_row(s, r, &err), CL_OK);
    cr_assert_eq(cl_series_close(s, &err), CL_OK);
    tmp_slurp(path, buf, sizeof buf);
    cr_assert(strstr(buf, "t,kinetic,potential\n1,") == buf, "%s", buf);
    cr_assert(strstr(buf, "nan") != NULL, "%s", buf);
    cr_assert(strstr(buf, ",-inf\n") != NULL, "%s", buf);
}

Test(series, close_null_and_discard)
{
    cl_error err;
    cr_assert_eq(cl_series_close(NULL, &err), CL_OK);
    cl_series_discard(NULL);
    cl_series *s;
    cr_assert_eq(cl_series_open(path, 2, cols, &s, &err), CL_OK);
    char names[4][256];
    cr_assert_eq(tmp_list_dir(dir, names, 4), 1);
    cl_series_discard(s);
    cr_assert_eq(tmp_list_dir(dir, names, 4), 0);
}

Test(series, bad_columns)
{
    cl_series *s = (cl_series *)1;
    cl_error err;
    cr_assert_eq(cl_series_open(path, 0, cols, &s, &err), CL_EINVAL);
    cr_assert_null(s);
    cr_assert(strstr(err.msg, "at least one column") != NULL, "%s",
              err.msg);
    cr_assert_eq(cl_series_open(path, 2, NULL, &s, &err), CL_EINVAL);
    const char *const comma[] = {"t", "a,b"};
    cr_assert_eq(cl_series_open(path, 2, comma, &s, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "column 2 name \"a,b\"") != NULL, "%s",
              err.msg);
    const char *const empty[] = {""};
    cr_assert_eq(cl_series_open(path, 1, empty, &s, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "column 1") != NULL, "%s", err.msg);
    const char *const nl[] = {"x\n"};
    cr_assert_eq(cl_series_open(path, 1, nl, &s, &err), CL_EINVAL);
    const char *const null_name[] = {"t", NULL};
    cr_assert_eq(cl_series_open(path, 2, null_name, &s, &err), CL_EINVAL);
    char names[4][256];
    cr_assert_eq(tmp_list_dir(dir, names, 4), 0);
}

Test(series, open_in_missing_directory)
{
    char bad[300];
    snprintf(bad, sizeof bad, "%s/none/e.csv", dir);
    cl_series *s;
    cl_error err;
    cr_assert_eq(cl_series_open(bad, 3, cols, &s, &err), CL_EIO);
    cr_assert_null(s);
    cr_assert(strstr(err.msg, bad) != NULL, "%s", err.msg);
}

Test(series, row_without_values)
{
    cl_series *s;
    cl_error err;
    cr_assert_eq(cl_series_open(path, 3, cols, &s, &err), CL_OK);
    cr_assert_eq(cl_series_row(s, NULL, &err), CL_EINVAL);
    cr_assert_eq(cl_series_row(NULL, NULL, &err), CL_EINVAL);
    cr_assert_eq(cl_series_close(s, &err), CL_OK);
}

Test(series, close_failure_removes_temporary)
{
    /* A directory put in place of the final path while the series was
     * written: the close does not rename onto it. */
    cl_series *s;
    cl_error err;
    cr_assert_eq(cl_series_open(path, 3, cols, &s, &err), CL_OK);
    cr_assert_eq(mkdir(path, 0777), 0);
    double r[] = {1, 2, 3};
    cr_assert_eq(cl_series_row(s, r, &err), CL_OK);
    cr_assert_eq(cl_series_close(s, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    char names[4][256];
    cr_assert_eq(tmp_list_dir(dir, names, 4), 1);
    cr_assert_str_eq(names[0], "energy.csv");
}

Test(series, write_error_is_reported)
{
    /* Limit the file size: a row eventually fails with EFBIG (the signal
     * that would kill the process is ignored). */
    tmp_limit_file_size(200);

    cl_series *s;
    cl_error err;
    cr_assert_eq(cl_series_open(path, 3, cols, &s, &err), CL_OK);
    double r[] = {1.0 / 3.0, 2.0 / 3.0, 1.0 / 7.0};
    cl_status st = CL_OK;
    int rows = 0;
    while (st == CL_OK && rows < 100) {
        st = cl_series_row(s, r, &err);
        rows++;
    }
    cr_assert_eq(st, CL_EIO);
    cr_assert(rows > 1 && rows < 100, "rows %d", rows);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, "too large") != NULL, "%s", err.msg);
    /* A file known to be incomplete is not published. */
    cr_assert_eq(cl_series_close(s, &err), CL_EIO);
    cr_assert(strstr(err.msg, "write error") != NULL, "%s", err.msg);
    cr_assert_eq(access(path, F_OK), -1);
    char names[4][256];
    cr_assert_eq(tmp_list_dir(dir, names, 4), 0);
}
