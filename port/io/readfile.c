/* SPDX-License-Identifier: MIT */
/* readfile.c: whole text inputs read once with a cap (see readfile.h). */
#include "readfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define FIRST_BYTES 4096 /* the buffer's first size; it doubles up to the cap */

vfp_status_t vfp_read_text(const char *path, size_t cap, const char *what, char **text, size_t *len, char *err,
                           size_t errlen)
{
    *text = NULL;
    *len = 0;
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return VFP_ERR;
    }
    size_t size = cap < FIRST_BYTES ? cap + 1 : FIRST_BYTES, used = 0;
    char *buf = malloc(size + 1);
    vfp_status_t status = VFP_OK;
    for (;;) {
        if (!buf) {
            snprintf(err, errlen, "%s: out of memory", path);
            status = VFP_ERR;
            break;
        }
        if (used == size) {
            if (used > cap) { /* one byte past the cap says enough: the rest is never read */
                snprintf(err, errlen, "%s: larger than %zu bytes, the cap on a %s", path, cap, what);
                status = VFP_ERR;
                break;
            }
            size_t grown = size * 2 > cap + 1 ? cap + 1 : size * 2;
            char *more = realloc(buf, grown + 1);
            if (!more)
                free(buf);
            buf = more;
            size = grown;
            continue;
        }
        ssize_t got = read(fd, buf + used, size - used);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0) {
            snprintf(err, errlen, "%s: cannot read: %s", path, strerror(errno));
            status = VFP_ERR;
            break;
        }
        if (got == 0)
            break;
        used += (size_t)got;
    }
    close(fd);
    if (status != VFP_OK) {
        free(buf);
        return status;
    }
    buf[used] = 0;
    *text = buf;
    *len = used;
    return VFP_OK;
}

unsigned vfp_text_nul_line(const char *text, size_t len)
{
    const char *nul = memchr(text, 0, len);
    if (!nul)
        return 0;
    unsigned line = 1;
    for (const char *p = text; p < nul; p++)
        line += *p == '\n';
    return line;
}

char *vfp_text_next_line(char **cursor)
{
    char *line = *cursor;
    if (!line || !*line) {
        *cursor = NULL;
        return NULL;
    }
    char *eol = strchr(line, '\n');
    if (eol) {
        *eol = 0;
        *cursor = eol + 1;
    } else {
        *cursor = NULL;
    }
    return line;
}
