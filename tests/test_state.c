/* Tests for the cloth state CSV reader and writer. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/state.h"
#include "tmpdir.h"

static char dir[64];
static char path[256];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "state");
    snprintf(path, sizeof path, "%s/state.csv", dir);
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

/* Read `text` as a state of np particles; expect `code` and, if given, a
 * message containing each of the substrings. */
static void expect_read(const char *text, size_t np, cl_status code,
                        const char *sub1, const char *sub2)
{
    tmp_put(path, text);
    double x[30], v[30];
    cl_error err;
    cl_error_clear(&err);
    cl_status st = cl_state_read(path, np, x, v, &err);
    cr_assert_eq(st, code, "status %d, message: %s", st, err.msg);
    if (code == CL_OK)
        return;
    cr_assert_eq(err.code, code);
    if (sub1)
        cr_assert(strstr(err.msg, sub1) != NULL, "'%s' not in: %s", sub1,
                  err.msg);
    if (sub2)
        cr_assert(strstr(err.msg, sub2) != NULL, "'%s' not in: %s", sub2,
                  err.msg);
}

TestSuite(state, .init = setup, .fini = teardown);

Test(state, round_trip_is_exact)
{
    enum { NP = 6 };
    double x[3 * NP], v[3 * NP], x2[3 * NP], v2[3 * NP];
    for (int k = 0; k < 3 * NP; k++) {
        x[k] = 0.1 * k + 1.0 / 3.0;
        v[k] = -1e-300 * (k + 1) + (k % 2 ? 2.718281828459045e10 : 0.0);
    }
    x[4] = -0.0;
    v[7] = 1.7976931348623157e308;
    cl_error err;
    cr_assert_eq(cl_state_write(path, NP, x, v, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(cl_state_read(path, NP, x2, v2, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(memcmp(x, x2, sizeof x), 0);
    cr_assert_eq(memcmp(v, v2, sizeof v), 0);
    /* The first line is the header, exactly; no temporary left behind. */
    FILE *fp = fopen(path, "r");
    char line[128];
    cr_assert_not_null(fgets(line, sizeof line, fp));
    cr_assert_str_eq(line, "p,x,y,z,vx,vy,vz\n");
    fclose(fp);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 1);
}

Test(state, rows_in_any_order)
{
    tmp_put(path, "p,x,y,z,vx,vy,vz\r\n"
                  "2,7,8,9,-7,-8,-9\r\n"
                  "\r\n"
                  "0, 1 ,2,3,-1,-2,-3\r\n"
                  "1,4,5,6e0,-4,-5,-6\r\n");
    double x[9], v[9];
    cl_error err;
    cr_assert_eq(cl_state_read(path, 3, x, v, &err), CL_OK, "%s", err.msg);
    for (int k = 0; k < 9; k++) {
        cr_assert_eq(x[k], k + 1);
        cr_assert_eq(v[k], -(k + 1));
    }
}

Test(state, zero_particles)
{
    cl_error err;
    cr_assert_eq(cl_state_write(path, 0, NULL, NULL, &err), CL_OK);
    cr_assert_eq(cl_state_read(path, 0, NULL, NULL, &err), CL_OK, "%s",
                 err.msg);
}

Test(state, missing_file)
{
    double x[3], v[3];
    cl_error err;
    cr_assert_eq(cl_state_read(path, 1, x, v, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, "No such file") != NULL, "%s", err.msg);
}

Test(state, write_into_missing_directory)
{
    double x[3] = {0}, v[3] = {0};
    char bad[300];
    snprintf(bad, sizeof bad, "%s/no/state.csv", dir);
    cl_error err;
    cr_assert_eq(cl_state_write(bad, 1, x, v, &err), CL_EIO);
    cr_assert(strstr(err.msg, bad) != NULL, "%s", err.msg);
}

Test(state, empty_file)
{
    expect_read("", 1, CL_EPARSE, ":1:", "missing header");
}

Test(state, wrong_header)
{
    expect_read("p,x,y,z,vx,vy\n0,1,2,3,4,5,6\n", 1, CL_EPARSE, ":1:",
                "expected header");
    expect_read("0,1,2,3,4,5,6\n", 1, CL_EPARSE, "state.csv:1:",
                "expected header");
    expect_read(" p,x,y,z,vx,vy,vz\n", 0, CL_EPARSE, ":1:",
                "expected header");
}

/* A line longer than 4096 bytes is refused as it is read, before the
 * rest of it (a file of one huge line would fill the memory); one of
 * 4095 bytes and its newline is read. */
Test(state, overlong_line)
{
    static char text[3 * 4096];
    size_t n = (size_t)sprintf(text, "p,x,y,z,vx,vy,vz\n0,1,2,3,4,5,6");
    memset(text + n, ' ', 4200);
    strcpy(text + n + 4200, "\n");
    expect_read(text, 1, CL_EPARSE, ":2:", "a line longer than 4096 bytes");
    n = (size_t)sprintf(text, "p,x,y,z,vx,vy,vz\n0,1,2,3,4,5,6");
    memset(text + n, ' ', 4095 - 13); /* the row's 13 bytes and blanks */
    strcpy(text + n + 4095 - 13, "\n");
    expect_read(text, 1, CL_OK, "", "");
}

Test(state, wrong_field_count)
{
    expect_read("p,x,y,z,vx,vy,vz\n0,1,2,3,4,5\n", 1, CL_EPARSE,
                ":2:", "expected 7 fields (p,x,y,z,vx,vy,vz), found 6");
    expect_read("p,x,y,z,vx,vy,vz\n0,1,2,3,4,5,6\n1,1,2,3,4,5,6,7\n", 2,
                CL_EPARSE, ":3:", "found 8");
    expect_read("p,x,y,z,vx,vy,vz\n0\n", 1, CL_EPARSE, ":2:", "found 1");
}

Test(state, non_numeric_value)
{
    expect_read("p,x,y,z,vx,vy,vz\n0,1,abc,3,4,5,6\n", 1, CL_EPARSE,
                ":2:", "y = \"abc\" is not a number");
    expect_read("p,x,y,z,vx,vy,vz\n0,1,2,3,4,5,\n", 1, CL_EPARSE, ":2:",
                "vz = \"\" is not a number");
    expect_read("p,x,y,z,vx,vy,vz\n0,1,2,3,4x,5,6\n", 1, CL_EPARSE, ":2:",
                "vx = \"4x\"");
}

Test(state, non_finite_value)
{
    expect_read("p,x,y,z,vx,vy,vz\n0,nan,2,3,4,5,6\n", 1, CL_EPARSE, ":2:",
                "x = \"nan\" is not finite");
    expect_read("p,x,y,z,vx,vy,vz\n0,1,2,3,4,-inf,6\n", 1, CL_EPARSE,
                ":2:", "vy = \"-inf\" is not finite");
    expect_read("p,x,y,z,vx,vy,vz\n0,1,2,1e999,4,5,6\n", 1, CL_EPARSE,
                ":2:", "z = \"1e999\" is not finite");
}

Test(state, bad_particle_index)
{
    expect_read("p,x,y,z,vx,vy,vz\n1.5,1,2,3,4,5,6\n", 2, CL_EPARSE, ":2:",
                "not an integer");
    expect_read("p,x,y,z,vx,vy,vz\nq,1,2,3,4,5,6\n", 2, CL_EPARSE, ":2:",
                "not an integer");
    expect_read("p,x,y,z,vx,vy,vz\n2,1,2,3,4,5,6\n", 2, CL_EPARSE, ":2:",
                "particle index 2 out of range 0..1");
    expect_read("p,x,y,z,vx,vy,vz\n0,1,2,3,4,5,6\n-1,1,2,3,4,5,6\n", 2,
                CL_EPARSE, ":3:", "particle index -1 out of range");
}

Test(state, duplicate_particle)
{
    expect_read("p,x,y,z,vx,vy,vz\n"
                "1,1,2,3,4,5,6\n"
                "0,1,2,3,4,5,6\n"
                "1,1,2,3,4,5,6\n", 3, CL_EPARSE, "state.csv:4:",
                "duplicate particle 1 (first on line 2)");
}

Test(state, missing_particle)
{
    expect_read("p,x,y,z,vx,vy,vz\n"
                "0,1,2,3,4,5,6\n"
                "3,1,2,3,4,5,6\n", 4, CL_EPARSE, "particle 1 missing",
                "2 of 4");
    expect_read("p,x,y,z,vx,vy,vz\n", 2, CL_EPARSE, "particle 0 missing",
                "state.csv");
}

Test(state, write_error)
{
    enum { NP = 100 };
    double x[3 * NP] = {0}, v[3 * NP] = {0};
    x[0] = 1.0 / 3.0;
    tmp_limit_file_size(1000);
    cl_error err;
    cr_assert_eq(cl_state_write(path, NP, x, v, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert_eq(access(path, F_OK), -1);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 0);
}
