/* SPDX-License-Identifier: MIT */
/* replay.c: main() for a fuzz harness built without libFuzzer (`make test`): feeds each file named on the command
 * line to LLVMFuzzerTestOneInput once, as the fuzzer would. tests/fuzz/replay.sh runs the seeds and the
 * regression inputs through every harness this way, in the normal and the sanitizer (SAN=1) builds. A finding
 * crashes (or, with sanitizers, reports and exits non-zero) after naming the file on stderr.
 *
 * Memory: no input of a few kilobytes needs a large allocation, so one means a reader believed what a header
 * claims before it found the data missing. The fuzzer aborts on any single allocation above -malloc_limit_mb
 * (tools/fuzz.sh); so does the replay, through the wrappers below, which the Makefile links in place of malloc,
 * calloc and realloc for every object of the program (ld --wrap). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#define LIMIT_BYTES ((size_t)256 << 20) /* tools/fuzz.sh's -malloc_limit_mb */

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
void *__real_malloc(size_t size);
void *__real_calloc(size_t count, size_t size);
void *__real_realloc(void *p, size_t size);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t count, size_t size);
void *__wrap_realloc(void *p, size_t size);

static void check_size(const char *what, size_t count, size_t size)
{
    if (size && count > LIMIT_BYTES / size) {
        fprintf(stderr, "replay: %s of %zu x %zu bytes, more than the %zu MB an input may need\n", what, count, size,
                LIMIT_BYTES >> 20);
        abort();
    }
}

void *__wrap_malloc(size_t size)
{
    check_size("malloc", 1, size);
    return __real_malloc(size);
}

void *__wrap_calloc(size_t count, size_t size)
{
    check_size("calloc", count, size);
    return __real_calloc(count, size);
}

void *__wrap_realloc(void *p, size_t size)
{
    check_size("realloc", 1, size);
    return __real_realloc(p, size);
}

static unsigned char *read_all(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, n = 0;
    unsigned char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n, f);
        if (n < cap)
            break;
        unsigned char *grown = realloc(buf, cap * 2);
        if (!grown)
            free(buf);
        buf = grown;
        cap *= 2;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return NULL;
    }
    *size = n;
    return buf;
}

int main(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        size_t size;
        unsigned char *data = read_all(argv[i], &size);
        if (!data) {
            fprintf(stderr, "replay: cannot read %s\n", argv[i]);
            return 2;
        }
        fprintf(stderr, "replay: %s\n", argv[i]);
        LLVMFuzzerTestOneInput(data, size);
        free(data);
    }
    return 0;
}
