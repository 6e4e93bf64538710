/* CSV fields (io/csv.c). */
#include <criterion/criterion.h>

#include <stdio.h>
#include <stdlib.h>

#include "io/csv.h"

static void expect_field(void (*write)(FILE *, const char *),
                         const char *in, const char *want)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&buf, &len);
    cr_assert_not_null(fp);
    write(fp, in);
    cr_assert_eq(fclose(fp), 0);
    cr_assert_str_eq(buf, want);
    free(buf);
}

Test(csv, quotes_doubled_inside_quotes)
{
    expect_field(cl_csv_quoted, "", "\"\"");
    expect_field(cl_csv_quoted, "a, b", "\"a, b\"");
    expect_field(cl_csv_quoted, "[s] k = \"x\": bad",
                 "\"[s] k = \"\"x\"\": bad\"");
}

Test(csv, text_quoted_only_when_it_must)
{
    expect_field(cl_csv_text, "plain text", "plain text");
    expect_field(cl_csv_text, "a,b", "\"a,b\"");
    expect_field(cl_csv_text, "say \"hi\"", "\"say \"\"hi\"\"\"");
    expect_field(cl_csv_text, "two\nlines", "\"two\nlines\"");
}
