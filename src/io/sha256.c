/* SHA-256 of a file or a text (sha256.h). */
#include "io/sha256.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <nettle/sha2.h>

#include "io/input.h"

static void digest_hex(struct sha256_ctx *ctx, char hex[CL_SHA256_HEX])
{
    unsigned char digest[SHA256_DIGEST_SIZE];
    sha256_digest(ctx, SHA256_DIGEST_SIZE, digest);
    for (size_t k = 0; k < SHA256_DIGEST_SIZE; k++)
        snprintf(hex + 2 * k, 3, "%02x", digest[k]);
}

void cl_sha256_text(const char *text, char hex[CL_SHA256_HEX])
{
    struct sha256_ctx ctx;
    sha256_init(&ctx);
    sha256_update(&ctx, strlen(text), (const uint8_t *)text);
    digest_hex(&ctx, hex);
}

cl_status cl_sha256_file(const char *path, char hex[CL_SHA256_HEX],
                         cl_error *err)
{
    const char *why;
    FILE *fp = cl_input_open(path, "rb", &why);
    if (!fp)
        return cl_error_set(err, CL_EIO, "cannot read '%s': %s", path, why);
    struct sha256_ctx ctx;
    unsigned char buf[65536];
    size_t n;
    sha256_init(&ctx);
    while ((n = fread(buf, 1, sizeof buf, fp)) > 0)
        sha256_update(&ctx, n, buf);
    int bad = ferror(fp);
    int e = errno;
    fclose(fp);
    if (bad)
        return cl_error_set(err, CL_EIO, "cannot read '%s': %s", path,
                            strerror(e ? e : EIO));
    digest_hex(&ctx, hex);
    return CL_OK;
}
