/* libFuzzer harness: the state-file reader (io/state).  The first byte
 * picks the particle count (0..15); the rest is the file. */
#define _GNU_SOURCE
#include "io/state.h"
#include "fuzz.h"

int CL_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    size_t np = data[0] % 16;
    double x[48], v[48];
    char path[64];
    cl_error err;
    int fd = fuzz_file(data + 1, size - 1, path, sizeof path);
    cl_state_read(path, np, x, v, &err);
    close(fd);
    return 0;
}
