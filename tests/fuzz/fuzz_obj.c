/* libFuzzer harness: the OBJ mesh reader (io/obj). */
#define _GNU_SOURCE
#include "io/obj.h"
#include "fuzz.h"

int CL_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    char path[64];
    cl_error err;
    cl_obj m;
    int fd = fuzz_file(data, size, path, sizeof path);
    if (cl_obj_read(path, &m, &err) == CL_OK)
        cl_obj_free(&m);
    close(fd);
    return 0;
}
