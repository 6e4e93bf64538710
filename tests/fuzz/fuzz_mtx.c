/* libFuzzer harness: the Matrix Market reader (io/mtx). */
#define _GNU_SOURCE
#include "io/mtx.h"
#include "fuzz.h"

int CL_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    char path[64];
    cl_error err;
    cl_triplets t;
    int fd = fuzz_file(data, size, path, sizeof path);
    if (cl_mtx_read(path, &t, &err) == CL_OK)
        cl_triplets_free(&t);
    close(fd);
    return 0;
}
