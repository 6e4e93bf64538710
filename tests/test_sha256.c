/* Tests for io/sha256: the digests of FIPS 180-4's examples. */
#include <criterion/criterion.h>

#include <stdio.h>
#include <string.h>

#include "io/sha256.h"
#include "tmpdir.h"

static char dir[64];

static void setup(void)
{
    tmp_mkdtemp(dir, sizeof dir, "sha256");
}

static void teardown(void)
{
    tmp_rm_rf(dir);
}

TestSuite(sha256, .init = setup, .fini = teardown);

static void digest_of(const char *text, const char *want)
{
    char path[256], hex[CL_SHA256_HEX];
    cl_error err = {0};
    snprintf(path, sizeof path, "%s/f", dir);
    tmp_put(path, text);
    cr_assert_eq(cl_sha256_file(path, hex, &err), CL_OK, "%s", err.msg);
    cr_assert_str_eq(hex, want, "\"%s\"", text);
}

Test(sha256, known_answers)
{
    digest_of("", "e3b0c44298fc1c149afbf4c8996fb924"
                  "27ae41e4649b934ca495991b7852b855");
    digest_of("abc", "ba7816bf8f01cfea414140de5dae2223"
                     "b00361a396177a9cb410ff61f20015ad");
    digest_of("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq",
              "248d6a61d20638b8e5c026930c3e6039"
              "a33ce45964ff2167f6ecedd419db06c1");
}

/* A file longer than the read buffer: a million 'a's (FIPS 180-4's third
 * example). */
Test(sha256, long_file)
{
    char path[256], hex[CL_SHA256_HEX];
    cl_error err = {0};
    snprintf(path, sizeof path, "%s/long", dir);
    FILE *fp = fopen(path, "w");
    cr_assert_not_null(fp);
    for (int k = 0; k < 1000000; k++)
        fputc('a', fp);
    cr_assert_eq(fclose(fp), 0);
    cr_assert_eq(cl_sha256_file(path, hex, &err), CL_OK, "%s", err.msg);
    cr_assert_str_eq(hex, "cdc76e5c9914fb9281a1c7e284d73e67"
                          "f1809a48a497200e046d39ccc7112cd0");
}

Test(sha256, missing_file_names_the_path)
{
    char path[256], hex[CL_SHA256_HEX];
    cl_error err = {0};
    snprintf(path, sizeof path, "%s/none", dir);
    cr_assert_eq(cl_sha256_file(path, hex, &err), CL_EIO);
    cr_assert(strstr(err.msg, path), "%s", err.msg);
}
