/* Shared piece of the libFuzzer harnesses (README "Fuzzing"): the readers
 * take a path, so each input is handed over as an in-memory file
 * (memfd_create), named /proc/self/fd/N. */
#ifndef CL_FUZZ_H
#define CL_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

/* The harness's entry: libFuzzer's, or another name where a test feeds
 * the inputs that once crashed (tests/test_config.c). */
#ifndef CL_FUZZ_ENTRY
#define CL_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

/* A fresh in-memory file holding data[0..size); its name goes to path.
 * Returns its descriptor (close it when done). */
static inline int fuzz_file(const uint8_t *data, size_t size, char *path,
                            size_t len)
{
    int fd = memfd_create("clothode-fuzz", 0);
    if (fd < 0) {
        perror("memfd_create");
        abort();
    }
    for (size_t done = 0; done < size;) {
        ssize_t n = write(fd, data + done, size - done);
        if (n <= 0) {
            perror("write");
            abort();
        }
        done += (size_t)n;
    }
    snprintf(path, len, "/proc/self/fd/%d", fd);
    return fd;
}

/* Hand data[0..size) to read() as a file. */
static inline int fuzz_read(const uint8_t *data, size_t size,
                            void (*read)(const char *path))
{
    char path[64];
    int fd = fuzz_file(data, size, path, sizeof path);
    read(path);
    close(fd);
    return 0;
}

#endif
