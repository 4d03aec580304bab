/* LD_PRELOAD shim for tests/chaos/kill_at_write.py: counts the write calls a process makes to
 * the files a run writes as it goes (names ending .h5.partial or .checkpoint.partial) and
 * raises SIGKILL instead of making call number KILL_AT. A kill between any two of HDF5's writes
 * is a kill in the middle of a flush, which a signal sent from outside rarely meets. With
 * KILL_AT=0 it only counts, into the file GRANJET_WRITE_COUNT names, at exit. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <unistd.h>

static long writes = 0;

static int ends_with(const char* s, size_t n, const char* tail) {
  const size_t t = strlen(tail);
  return n >= t && memcmp(s + n - t, tail, t) == 0;
}

static void count(int fd) {
  char link[64], path[4096];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, path, sizeof path);
  if (n <= 0 || !(ends_with(path, (size_t)n, ".h5.partial") ||
                  ends_with(path, (size_t)n, ".checkpoint.partial")))
    return;
  const char* at = getenv("KILL_AT");
  if (++writes == (at ? atol(at) : -1)) raise(SIGKILL);
}

#define FORWARD(name, params, args)                                         \
  ssize_t name params {                                                     \
    static ssize_t(*real) params;                                           \
    if (!real) *(void**)&real = dlsym(RTLD_NEXT, #name);                   \
    count(fd);                                                              \
    return real args;                                                       \
  }

FORWARD(write, (int fd, const void* buf, size_t n), (fd, buf, n))
FORWARD(pwrite, (int fd, const void* buf, size_t n, off_t at), (fd, buf, n, at))
FORWARD(pwrite64, (int fd, const void* buf, size_t n, off_t at), (fd, buf, n, at))

/* Only a process that wrote reports: over MPI ranks, mpiexec and the ranks other than 0 also
 * load the shim and write none of the run's files. */
__attribute__((destructor)) static void report(void) {
  const char* file = getenv("GRANJET_WRITE_COUNT");
  FILE* out = file && writes > 0 ? fopen(file, "w") : NULL;
  if (out == NULL) return;
  fprintf(out, "%ld\n", writes);
  fclose(out);
}
