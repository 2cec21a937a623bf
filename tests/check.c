/* SPDX-License-Identifier: MIT */
/* check.c: see check.h. */
#include "check.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int check_failed;
static char check_message[1024];

void check_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    int n = snprintf(check_message, sizeof check_message, "%s:%d: ", file, line);
    va_start(ap, fmt);
    if (n > 0 && (size_t)n < sizeof check_message)
        vsnprintf(check_message + n, sizeof check_message - (size_t)n, fmt, ap);
    va_end(ap);
    check_failed = 1;
}

const char *check_data(const char *name, char *path, size_t len)
{
    const char *dir = getenv("VOLFIX_DATA");
    struct stat st;
    if (!dir || !dir[0]) {
        snprintf(path, len, "VOLFIX_DATA is not set: it names the folder of sample volumes with %s (make test sets it)",
                 name);
        return NULL;
    }
    snprintf(path, len, "%s/%s", dir, name);
    if (stat(path, &st) == 0)
        return path;
    snprintf(path, len, "no %s in VOLFIX_DATA=%s: set VOLFIX_DATA to the folder of sample volumes", name, dir);
    return NULL;
}

/* Runs every case, or only those named on the command line. Exit status 1 if any failed. */
int check_main(const char *suite, const check_case_t *cases, int count, int argc, char **argv)
{
    int failures = 0;
    for (int c = 0; c < count; c++) {
        if (argc > 1) {
            int wanted = 0;
            for (int a = 1; a < argc; a++)
                wanted |= strcmp(argv[a], cases[c].name) == 0;
            if (!wanted)
                continue;
        }
        check_failed = 0;
        check_message[0] = 0;
        cases[c].fn();
        if (check_failed) {
            printf("not ok - %s/%s: %s\n", suite, cases[c].name, check_message);
            failures++;
        } else {
            printf("ok - %s/%s\n", suite, cases[c].name);
        }
        fflush(stdout);
    }
    return failures ? 1 : 0;
}
