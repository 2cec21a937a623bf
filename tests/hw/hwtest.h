/* SPDX-License-Identifier: MIT */
/*
 * hwtest.h: what the programs of make test-hw share (tests/hw/README.md): "ok - NAME" / "not ok - NAME: why"
 * lines with names made at run time (the libgpiod version, the gadget's configuration), small file helpers for
 * sysfs and configfs, and the monotonic clock. Header-only: each program is one .c file.
 */
#ifndef VFP_HWTEST_H
#define VFP_HWTEST_H

#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Messages are cut to their buffers on purpose: a long path in a test message is not worth a warning. */
#pragma GCC diagnostic ignored "-Wformat-truncation"
#pragma GCC diagnostic ignored "-Wunused-function"

static int hw_passed, hw_failed;

/* One result line. `name` is the whole test name; `why` (printf-style) only matters when !ok. */
static void hw_result(int ok, const char *name, const char *why_fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void hw_result(int ok, const char *name, const char *why_fmt, ...)
{
    if (ok) {
        printf("ok - %s\n", name);
        hw_passed++;
    } else {
        char why[1024];
        va_list ap;
        va_start(ap, why_fmt);
        vsnprintf(why, sizeof why, why_fmt, ap);
        va_end(ap);
        for (char *p = why; *p; p++)
            if (*p == '\n')
                *p = ' ';
        printf("not ok - %s: %s\n", name, why);
        hw_failed++;
    }
    fflush(stdout);
}

static uint64_t hw_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void hw_sleep_ms(unsigned ms)
{
    struct timespec ts = {ms / 1000, (long)(ms % 1000) * 1000000L};
    while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
    }
}

/* Write a string to a sysfs/configfs file. Returns 0, or -1 with a message in err. */
static int hw_write_file(const char *path, const char *text, char *err, size_t errlen)
{
    int fd = open(path, O_WRONLY);
    if (fd < 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    size_t len = strlen(text);
    ssize_t n = write(fd, text, len);
    int saved = errno;
    close(fd);
    if (n != (ssize_t)len) {
        snprintf(err, errlen, "write '%s' to %s: %s", text, path, n < 0 ? strerror(saved) : "short write");
        return -1;
    }
    return 0;
}

/* Read a small file, trailing newline removed. Returns 0, or -1 with a message in err. */
static int hw_read_file(const char *path, char *buf, size_t cap, char *err, size_t errlen)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return -1;
    }
    ssize_t n = read(fd, buf, cap - 1);
    int saved = errno;
    close(fd);
    if (n < 0) {
        snprintf(err, errlen, "%s: %s", path, strerror(saved));
        return -1;
    }
    buf[n] = 0;
    while (n > 0 && (buf[n - 1] == '\n' || buf[n - 1] == ' '))
        buf[--n] = 0;
    return 0;
}

#endif
