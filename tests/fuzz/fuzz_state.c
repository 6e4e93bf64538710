/* libFuzzer harness: the state-file reader (io/state).  The first byte
 * picks the particle count (0..15); the rest is the file. */
#define _GNU_SOURCE
#include "io/state.h"
#include "fuzz.h"

static size_t np;

static void read_state(const char *path)
{
    double x[48], v[48];
    cl_error err;
    cl_state_read(path, np, x, v, &err);
}

int CL_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    np = data[0] % 16;
    return fuzz_read(data + 1, size - 1, read_state);
}
