/* A write(2) that fails on purpose, for the reliability tests (LD_PRELOAD=libbhm_fault_inject.so).
 * Writes to any file whose path contains $BHM_FAULT_FILE fail with errno $BHM_FAULT_ERRNO
 * (default 28, ENOSPC: a full disk) once $BHM_FAULT_AFTER (default 0) such writes succeeded.
 * Every output of bhm goes through write(2) (engine/io/atomic_file.cpp), so this is a full disk or
 * a failing device as the program sees it, without needing one. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef ssize_t (*write_fn)(int, const void*, size_t);

static int matches(int fd) {
    const char* pattern = getenv("BHM_FAULT_FILE");
    if (!pattern || !*pattern || fd <= 2) return 0;
    char link[64], target[4096];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t n = readlink(link, target, sizeof target - 1);
    if (n <= 0) return 0;
    target[n] = '\0';
    return strstr(target, pattern) != NULL;
}

ssize_t write(int fd, const void* data, size_t bytes) {
    static write_fn real_write = NULL;
    static long allowed = -1;
    if (!real_write) real_write = (write_fn)dlsym(RTLD_NEXT, "write");
    if (matches(fd)) {
        if (allowed < 0) {
            const char* after = getenv("BHM_FAULT_AFTER");
            allowed = after ? atol(after) : 0;
        }
        if (allowed-- <= 0) {
            const char* code = getenv("BHM_FAULT_ERRNO");
            errno = code ? atoi(code) : ENOSPC;
            return -1;
        }
    }
    return real_write(fd, data, bytes);
}
