/* JSON documents from regular files (io/jsonfile.c): a document reads; a
 * file that is not JSON says where, with no reason to open; one that
 * cannot be opened says why. */
#include <criterion/criterion.h>

#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "io/jsonfile.h"
#include "timelimit.h"
#include "tmpdir.h"

Test(jsonfile, documents_errors_and_refusals)
{
    char dir[512], good[600], bad[600], fifo[600];
    const char *why = "unset";
    json_error_t je;
    time_limit(10);
    tmp_mkdtemp(dir, sizeof dir, "jsonfile");
    snprintf(good, sizeof good, "%s/good.json", dir);
    snprintf(bad, sizeof bad, "%s/bad.json", dir);
    snprintf(fifo, sizeof fifo, "%s/fifo.json", dir);
    tmp_put(good, "{\"program\": \"clothode\"}\n");
    tmp_put(bad, "{\n\"program\": \n");
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    json_t *root = cl_json_read(good, &je, &why);
    cr_assert_not_null(root);
    cr_assert_null(why);
    cr_assert_str_eq(json_string_value(json_object_get(root, "program")),
                     "clothode");
    json_decref(root);
    why = "unset";
    cr_assert_null(cl_json_read(bad, &je, &why));
    cr_assert_null(why, "opened, not JSON");
    cr_assert_eq(je.line, 3, "%d: %s", je.line, je.text);
    cr_assert_null(cl_json_read(fifo, &je, &why));
    cr_assert_str_eq(why, "it is a FIFO, not a regular file");
    tmp_rm_rf(dir);
}
