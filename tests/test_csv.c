/* CSV fields (io/csv.c). */
#include <criterion/criterion.h>

#include <stdio.h>
#include <stdlib.h>

#include "io/csv.h"

static void expect_quoted(const char *in, const char *want)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&buf, &len);
    cr_assert_not_null(fp);
    cl_csv_quoted(fp, in);
    cr_assert_eq(fclose(fp), 0);
    cr_assert_str_eq(buf, want);
    free(buf);
}

Test(csv, quotes_doubled_inside_quotes)
{
    expect_quoted("", "\"\"");
    expect_quoted("a, b", "\"a, b\"");
    expect_quoted("[s] k = \"x\": bad", "\"[s] k = \"\"x\"\": bad\"");
}
