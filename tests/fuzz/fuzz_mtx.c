/* libFuzzer harness: the Matrix Market reader (io/mtx). */
#define _GNU_SOURCE
#include "io/mtx.h"
#include "fuzz.h"

static void read_mtx(const char *path)
{
    cl_error err;
    cl_triplets t;
    if (cl_mtx_read(path, &t, &err) == CL_OK)
        cl_triplets_free(&t);
}

int CL_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    return fuzz_read(data, size, read_mtx);
}
