/* SPDX-License-Identifier: MIT */
/*
 * fixtures.h: files a test writes while it runs, in a private temporary directory that is removed, with all that
 * was made in it (by the test or by the code under test), when the test program exits. Header-only and static
 * inline, as check.h is, so that each test program stays one file and one that does not use a helper gets no
 * warning. Failures to make a fixture end the test program: they are the machine's, not the code's.
 */
#ifndef FIXTURES_H
#define FIXTURES_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char fx_dir[64];

/* Removes path and, for a directory, everything below it (a symbolic link is removed, not followed). */
static inline void fx_remove_tree(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return;
    if (!S_ISDIR(st.st_mode)) {
        unlink(path);
        return;
    }
    DIR *d = opendir(path);
    struct dirent *de;
    while (d && (de = readdir(d))) {
        if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0)
            continue;
        char *child = malloc(strlen(path) + strlen(de->d_name) + 2);
        if (!child)
            break;
        sprintf(child, "%s/%s", path, de->d_name);
        fx_remove_tree(child);
        free(child);
    }
    if (d)
        closedir(d);
    rmdir(path);
}

static inline void fx_cleanup(void)
{
    if (fx_dir[0])
        fx_remove_tree(fx_dir);
}

/* The temporary directory, made on first use. */
static inline const char *fx_tmpdir(void)
{
    if (!fx_dir[0]) {
        snprintf(fx_dir, sizeof fx_dir, "/tmp/volfix-test-XXXXXX");
        if (!mkdtemp(fx_dir)) {
            perror("mkdtemp");
            exit(1);
        }
        atexit(fx_cleanup);
    }
    return fx_dir;
}

/* A path inside the temporary directory (nothing made there); eight rotating buffers, so a few can be alive at
 * once. */
static inline const char *fx_path(const char *name)
{
    static char bufs[8][512];
    static int next;
    char *b = bufs[next++ % 8];
    snprintf(b, sizeof bufs[0], "%s/%s", fx_tmpdir(), name);
    return b;
}

static inline const char *fx_mkdir(const char *name)
{
    const char *p = fx_path(name);
    mkdir(p, 0700);
    return p;
}

/* Writes text (may be NULL) followed by n bytes of data; returns the file's path. */
static inline const char *fx_write(const char *name, const char *text, const void *data, size_t n)
{
    const char *p = fx_path(name);
    FILE *f = fopen(p, "wb");
    if (!f) {
        perror(p);
        exit(1);
    }
    if (text)
        fputs(text, f);
    if (n)
        fwrite(data, 1, n, f);
    fclose(f);
    return p;
}

#endif
