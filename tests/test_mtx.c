/* Tests for Matrix Market output of block matrices and the reader. */
#include <criterion/criterion.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/mtx.h"
#include "tmpdir.h"

static char dir[64];
static char path[256];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "mtx");
    snprintf(path, sizeof path, "%s/m.mtx", dir);
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

static void expect_read(const char *text, cl_status code, const char *sub1,
                        const char *sub2)
{
    tmp_put(path, text);
    cl_triplets t;
    cl_error err;
    cl_error_clear(&err);
    cl_status st = cl_mtx_read(path, &t, &err);
    cr_assert_eq(st, code, "status %d, message: %s", st, err.msg);
    cr_assert_null(t.row);
    cr_assert_eq(t.nnz, 0);
    if (sub1)
        cr_assert(strstr(err.msg, sub1) != NULL, "'%s' not in: %s", sub1,
                  err.msg);
    if (sub2)
        cr_assert(strstr(err.msg, sub2) != NULL, "'%s' not in: %s", sub2,
                  err.msg);
}

TestSuite(mtx, .init = setup, .fini = teardown);

/* Tridiagonal block pattern on 3 block rows, built by hand. */
static size_t rowptr[] = {0, 2, 5, 7};
static size_t col[] = {0, 1, 0, 1, 2, 1, 2};
static size_t diag[] = {0, 3, 6};
static const cl_bpattern pat = {3, 7, rowptr, col, diag};

static double value_of(size_t k, size_t m)
{
    return (double)(k + 1) / 3.0 + (double)m * 1e-7 - (m == 4 ? 1e300 : 0);
}

Test(mtx, block_round_trip)
{
    double val[63];
    for (size_t k = 0; k < 7; k++)
        for (size_t m = 0; m < 9; m++)
            val[9 * k + m] = value_of(k, m);
    val[9 * 2 + 5] = 0.0;   /* explicit zeros are written too */
    cl_error err;
    cr_assert_eq(cl_mtx_write_blocks(path, &pat, val, &err), CL_OK, "%s",
                 err.msg);

    FILE *fp = fopen(path, "r");
    char line[256];
    cr_assert_not_null(fgets(line, sizeof line, fp));
    cr_assert_str_eq(line, "%%MatrixMarket matrix coordinate real general\n");
    fclose(fp);

    cl_triplets t;
    cr_assert_eq(cl_mtx_read(path, &t, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(t.nrows, 9);
    cr_assert_eq(t.ncols, 9);
    cr_assert_eq(t.nnz, 63);
    int seen[7][9] = {{0}};
    for (size_t e = 0; e < t.nnz; e++) {
        size_t bi = t.row[e] / 3, bj = t.col[e] / 3;
        size_t r = t.row[e] % 3, c = t.col[e] % 3;
        long k = -1;
        for (size_t q = rowptr[bi]; q < rowptr[bi + 1]; q++)
            if (col[q] == bj)
                k = (long)q;
        cr_assert(k >= 0, "entry (%zu, %zu) outside the pattern", t.row[e],
                  t.col[e]);
        cr_assert_eq(t.val[e], val[9 * k + 3 * r + c]);
        seen[k][3 * r + c]++;
        /* Sorted by row, then column. */
        if (e > 0)
            cr_assert(t.row[e] > t.row[e - 1] ||
                      (t.row[e] == t.row[e - 1] && t.col[e] > t.col[e - 1]));
    }
    for (size_t k = 0; k < 7; k++)
        for (size_t m = 0; m < 9; m++)
            cr_assert_eq(seen[k][m], 1);
    cl_triplets_free(&t);
    cl_triplets_free(&t);   /* harmless twice */
}

Test(mtx, empty_matrix)
{
    size_t rp[] = {0};
    cl_bpattern empty = {0, 0, rp, NULL, NULL};
    cl_error err;
    cr_assert_eq(cl_mtx_write_blocks(path, &empty, NULL, &err), CL_OK, "%s",
                 err.msg);
    cl_triplets t;
    cr_assert_eq(cl_mtx_read(path, &t, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(t.nrows, 0);
    cr_assert_eq(t.nnz, 0);
    cl_triplets_free(&t);
}

Test(mtx, write_errors)
{
    double val[63] = {0};
    char bad[300];
    snprintf(bad, sizeof bad, "%s/none/m.mtx", dir);
    cl_error err;
    cr_assert_eq(cl_mtx_write_blocks(bad, &pat, val, &err), CL_EIO);
    cr_assert(strstr(err.msg, bad) != NULL, "%s", err.msg);
    cr_assert_eq(cl_mtx_write_blocks(path, &pat, NULL, &err), CL_EINVAL);
    cr_assert(strstr(err.msg, "no matrix") != NULL, "%s", err.msg);
    cr_assert_eq(access(path, F_OK), -1);
}

Test(mtx, reader_accepts_comments_blanks_and_case)
{
    tmp_put(path, "%%MatrixMarket MATRIX Coordinate Real General\n"
                  "% a comment\n"
                  "\n"
                  "2 3 2\n"
                  "% between entries\n"
                  "1 3 -2.5\n"
                  "  2 1   4e-3  \n");
    cl_triplets t;
    cl_error err;
    cr_assert_eq(cl_mtx_read(path, &t, &err), CL_OK, "%s", err.msg);
    cr_assert_eq(t.nrows, 2);
    cr_assert_eq(t.ncols, 3);
    cr_assert_eq(t.nnz, 2);
    cr_assert_eq(t.row[0], 0);
    cr_assert_eq(t.col[0], 2);
    cr_assert_eq(t.val[0], -2.5);
    cr_assert_eq(t.row[1], 1);
    cr_assert_eq(t.col[1], 0);
    cr_assert_eq(t.val[1], 4e-3);
    cl_triplets_free(&t);
}

Test(mtx, reader_missing_file)
{
    cl_triplets t;
    cl_error err;
    cr_assert_eq(cl_mtx_read(path, &t, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert(strstr(err.msg, "No such file") != NULL, "%s", err.msg);
}

Test(mtx, reader_bad_banner)
{
    expect_read("", CL_EPARSE, "m.mtx:1:", "empty");
    expect_read("hello\n1 1 0\n", CL_EPARSE, "m.mtx:1:",
                "not a Matrix Market file");
    expect_read("%%MatrixMarket matrix coordinate real\n1 1 0\n", CL_EPARSE,
                ":1:", "not a Matrix Market file");
    expect_read("%%MatrixMarket matrix array real general\n1 1\n1\n",
                CL_EPARSE, ":1:", "unsupported Matrix Market type");
    expect_read("%%MatrixMarket matrix coordinate real symmetric\n1 1 0\n",
                CL_EPARSE, ":1:", "real symmetric");
}

Test(mtx, reader_bad_size_line)
{
    expect_read("%%MatrixMarket matrix coordinate real general\n% c\n",
                CL_EPARSE, "m.mtx:2:", "missing size line");
    expect_read("%%MatrixMarket matrix coordinate real general\n3 3\n",
                CL_EPARSE, ":2:", "expected size line");
    expect_read("%%MatrixMarket matrix coordinate real general\n3 -3 1\n",
                CL_EPARSE, ":2:", "expected size line");
    expect_read("%%MatrixMarket matrix coordinate real general\n3 3 1 4\n",
                CL_EPARSE, ":2:", "expected size line");
}

Test(mtx, reader_bad_entries)
{
    /* entries after the header of a 3 x 3 matrix with 2 entries, and what
     * the message must contain */
    static const struct {
        const char *entries, *sub1, *sub2;
    } bad[] = {
        {"1 1 1\n1 x 2\n", "m.mtx:4:", "expected entry"},
        {"1 1\n", ":3:", "expected entry"},
        {"1 1 1 1\n", ":3:", "expected entry"},
        {"1.5 1 1\n", ":3:", "expected entry"},
        {"0 1 1\n", ":3:", "entry (0, 1) outside the 3 x 3"},
        {"1 1 1\n2 4 1\n", ":4:", "entry (2, 4) outside"},
        {"1 1 nan\n", ":3:", "not finite"},
        {"1 1 1\n2 2 2\n3 3 3\n", ":5:", "more entries than the 2 announced"},
        {"1 1 1\n", "2 entries announced, 1 found", NULL},
    };
    char buf[256];
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        snprintf(buf, sizeof buf, "%%%%MatrixMarket matrix coordinate real "
                 "general\n3 3 2\n%s", bad[k].entries);
        expect_read(buf, CL_EPARSE, bad[k].sub1, bad[k].sub2);
    }
}

Test(mtx, write_error_leaves_nothing)
{
    double val[63];
    for (int k = 0; k < 63; k++)
        val[k] = 1.0 / (k + 3);
    tmp_limit_file_size(300);
    cl_error err;
    cr_assert_eq(cl_mtx_write_blocks(path, &pat, val, &err), CL_EIO);
    cr_assert(strstr(err.msg, path) != NULL, "%s", err.msg);
    cr_assert_eq(access(path, F_OK), -1);
    cr_assert_eq(tmp_list_dir(dir, NULL, 0), 0);
}
