/* libFuzzer harness: the OBJ mesh reader (io/obj); a mesh it accepts is
 * placed as an obstacle's would be (scaled and moved). */
#define _GNU_SOURCE
#include "io/obj.h"
#include "fuzz.h"

static void read_obj(const char *path)
{
    cl_error err;
    cl_obj m;
    if (cl_obj_read(path, &m, &err) != CL_OK)
        return;
    cl_obj_place(&m, 2.5, (const double[3]){1.0, -2.0, 0.5});
    cl_obj_free(&m);
}

int CL_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    return fuzz_read(data, size, read_obj);
}
