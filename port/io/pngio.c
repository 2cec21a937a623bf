/* SPDX-License-Identifier: MIT */
/* pngio.c: PNG files through libpng (see pngio.h). */
#include "pngio.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <png.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

void vfp_image_to_rgb(const vf_image_t *img, uint8_t *rgb)
{
    /* RGB565's 5- and 6-bit fields to 8 bits, rounded to nearest: from tables, with the format chosen once an
     * image rather than a pixel (the headless board converts every frame it shows) */
    uint8_t five[32], six[64];
    for (unsigned v = 0; v < 64; v++) {
        if (v < 32)
            five[v] = (uint8_t)((v * 255 + 15) / 31);
        six[v] = (uint8_t)((v * 255 + 31) / 63);
    }
    for (uint32_t y = 0; y < img->height; y++) {
        const uint8_t *src = (const uint8_t *)img->pixels + (size_t)y * img->stride;
        uint8_t *dst = rgb + (size_t)y * img->width * 3;
        if (img->format == VF_FORMAT_RGB888) {
            memcpy(dst, src, (size_t)img->width * 3);
        } else if (img->format == VF_FORMAT_RGB565) {
            for (uint32_t x = 0; x < img->width; x++, dst += 3) {
                const unsigned word = src[x * 2] | (unsigned)src[x * 2 + 1] << 8;
                dst[0] = five[word >> 11];
                dst[1] = six[(word >> 5) & 63];
                dst[2] = five[word & 31];
            }
        } else { /* XRGB8888: B, G, R, X */
            for (uint32_t x = 0; x < img->width; x++, dst += 3) {
                dst[0] = src[x * 4 + 2];
                dst[1] = src[x * 4 + 1];
                dst[2] = src[x * 4 + 0];
            }
        }
    }
}

vfp_status_t vfp_png_write(const char *path, const vf_image_t *img, char *err, size_t errlen)
{
    uint8_t *rgb = malloc((size_t)img->width * img->height * 3);
    if (!rgb) {
        snprintf(err, errlen, "%s: out of memory for a %ux%u image", path, img->width, img->height);
        return VFP_ERR;
    }
    vfp_image_to_rgb(img, rgb);
    vfp_status_t status = vfp_png_write_rgb(path, rgb, img->width, img->height, err, errlen);
    free(rgb);
    return status;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Writing: where the bytes go */

/* The PNG onto an open stream; VFP_OK only when every byte reached it. */
static vfp_status_t write_stream(FILE *f, const char *name, const uint8_t *rgb, uint32_t width, uint32_t height,
                                 char *err, size_t errlen)
{
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    image.width = width;
    image.height = height;
    image.format = PNG_FORMAT_RGB;
    /* Speed before size (libpng's filter and zlib level choices): the headless board writes a PNG per frame,
     * which with the defaults took about as many instructions as rendering the viewer's preview. */
#ifdef PNG_IMAGE_FLAG_FAST /* libpng 1.6.22 and later */
    image.flags = PNG_IMAGE_FLAG_FAST;
#endif
    errno = 0;
    if (!png_image_write_to_stdio(&image, f, 0, rgb, (png_int_32)(width * 3), NULL)) {
        snprintf(err, errlen, "%s: cannot write PNG: %s", name, image.message[0] ? image.message : strerror(errno));
        return VFP_ERR;
    }
    if (fflush(f) != 0 || ferror(f)) {
        snprintf(err, errlen, "%s: cannot write PNG: %s", name, strerror(errno ? errno : EIO));
        return VFP_ERR;
    }
    return VFP_OK;
}

/* The directory part of path ("." when it has none), into dir. */
static void dir_of(const char *path, char *dir, size_t len)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dir, len, ".");
    else if (slash == path)
        snprintf(dir, len, "/");
    else
        snprintf(dir, len, "%.*s", (int)(slash - path), path);
}

/* The file a path finally names, symlinks followed (a dangling one to the file it would create); VFP_ERR for a
 * loop or a name too long. */
static vfp_status_t follow_links(const char *path, char *target, size_t len, char *err, size_t errlen)
{
    snprintf(target, len, "%s", path);
    for (int hops = 0; hops < 40; hops++) {
        struct stat st;
        if (lstat(target, &st) != 0 || !S_ISLNK(st.st_mode))
            return VFP_OK;
        char link[PATH_MAX], dir[PATH_MAX];
        ssize_t n = readlink(target, link, sizeof link - 1);
        if (n < 0) {
            snprintf(err, errlen, "%s: cannot read the symbolic link: %s", path, strerror(errno));
            return VFP_ERR;
        }
        link[n] = 0;
        dir_of(target, dir, sizeof dir);
        int w = link[0] == '/' ? snprintf(target, len, "%s", link) : snprintf(target, len, "%s/%s", dir, link);
        if (w < 0 || (size_t)w >= len) {
            snprintf(err, errlen, "%s: the file it links to has too long a name", path);
            return VFP_ERR;
        }
    }
    snprintf(err, errlen, "%s: too many symbolic links (a loop?)", path);
    return VFP_ERR;
}

/* A regular file (or none yet) is replaced whole: the PNG goes to a temporary file beside it, which is renamed
 * over it once complete, so a failed write leaves the old file as it was and only the temporary file (which volfix
 * made) is removed. SIGINT, SIGTERM and SIGHUP wait while the temporary file exists, so that an interrupted run
 * leaves none behind; the write to a local file is short. */
static vfp_status_t write_replacing(const char *path, const char *target, const uint8_t *rgb, uint32_t width,
                                    uint32_t height, char *err, size_t errlen)
{
    char dir[PATH_MAX], temp[PATH_MAX];
    dir_of(target, dir, sizeof dir);
    const char *base = strrchr(target, '/') ? strrchr(target, '/') + 1 : target;
    if (snprintf(temp, sizeof temp, "%s/.%s.XXXXXX", dir, base) >= (int)sizeof temp) {
        snprintf(err, errlen, "%s: name too long", path);
        return VFP_ERR;
    }
    struct stat st;
    int existed = stat(target, &st) == 0;
    mode_t mask = umask(0);
    umask(mask);
    mode_t mode = existed ? st.st_mode & 07777 : 0666 & ~mask;

    sigset_t block, saved;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &block, &saved);
    vfp_status_t status = VFP_ERR;
    int fd = mkstemp(temp);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot write: %s (a PNG is written to a temporary file in %s first)", path,
                 strerror(errno), dir);
    } else {
        FILE *f = fdopen(fd, "wb");
        if (!f) {
            snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
            close(fd);
        } else {
            status = write_stream(f, path, rgb, width, height, err, errlen);
            if (status == VFP_OK && fchmod(fd, mode) != 0)
                status = (snprintf(err, errlen, "%s: cannot set its mode: %s", path, strerror(errno)), VFP_ERR);
            if (fclose(f) != 0 && status == VFP_OK)
                status = (snprintf(err, errlen, "%s: cannot write PNG: %s", path, strerror(errno)), VFP_ERR);
        }
        if (status == VFP_OK && rename(temp, target) != 0)
            status = (snprintf(err, errlen, "%s: cannot replace it: %s", path, strerror(errno)), VFP_ERR);
        if (status != VFP_OK)
            unlink(temp); /* ours: nothing else is ever removed */
    }
    pthread_sigmask(SIG_SETMASK, &saved, NULL);
    return status;
}

vfp_status_t vfp_png_write_rgb(const char *path, const uint8_t *rgb, uint32_t width, uint32_t height, char *err,
                               size_t errlen)
{
    if (strcmp(path, "-") == 0)
        return write_stream(stdout, "(standard output)", rgb, width, height, err, errlen);
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        if (S_ISDIR(st.st_mode)) {
            snprintf(err, errlen, "%s: is a directory (expected a PNG file's name)", path);
            return VFP_ERR;
        }
        /* a device, a FIFO or a socket is written in place and never replaced or removed */
        int fd = open(path, O_WRONLY | O_CLOEXEC | O_NOCTTY);
        FILE *f = fd < 0 ? NULL : fdopen(fd, "wb");
        if (!f) {
            snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
            if (fd >= 0)
                close(fd);
            return VFP_ERR;
        }
        vfp_status_t status = write_stream(f, path, rgb, width, height, err, errlen);
        if (fclose(f) != 0 && status == VFP_OK) {
            snprintf(err, errlen, "%s: cannot write PNG: %s", path, strerror(errno));
            status = VFP_ERR;
        }
        return status;
    }
    char target[PATH_MAX];
    if (follow_links(path, target, sizeof target, err, errlen))
        return VFP_ERR;
    return write_replacing(path, target, rgb, width, height, err, errlen);
}

vfp_status_t vfp_png_check_output(const char *path, char *err, size_t errlen)
{
    if (!path || !*path) {
        snprintf(err, errlen, "'': an empty file name (expected a PNG file's name, or - for standard output)");
        return VFP_ERR;
    }
    if (strcmp(path, "-") == 0)
        return VFP_OK;
    struct stat st;
    if (stat(path, &st) == 0) {
        if (S_ISDIR(st.st_mode)) {
            snprintf(err, errlen, "%s: is a directory (expected a PNG file's name)", path);
            return VFP_ERR;
        }
        if (!S_ISREG(st.st_mode)) {
            if (access(path, W_OK) != 0) {
                snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
                return VFP_ERR;
            }
            return VFP_OK;
        }
    } else if (errno != ENOENT) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        return VFP_ERR;
    }
    char target[PATH_MAX], dir[PATH_MAX];
    if (follow_links(path, target, sizeof target, err, errlen))
        return VFP_ERR;
    dir_of(target, dir, sizeof dir);
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        snprintf(err, errlen, "%s: cannot write: %s is not a directory", path, dir);
        return VFP_ERR;
    }
    if (access(dir, W_OK) != 0) {
        snprintf(err, errlen, "%s: cannot write: %s (the PNG replaces it through a temporary file in %s)", path,
                 strerror(errno), dir);
        return VFP_ERR;
    }
    return VFP_OK;
}

vfp_status_t vfp_png_read_rgb(const char *path, uint8_t **rgb, uint32_t *width, uint32_t *height, char *err,
                              size_t errlen)
{
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    *rgb = NULL;
    if (!png_image_begin_read_from_file(&image, path)) {
        snprintf(err, errlen, "%s: cannot read PNG: %s", path, image.message);
        return VFP_ERR;
    }
    image.format = PNG_FORMAT_RGB;
    uint8_t *buf = malloc(PNG_IMAGE_SIZE(image));
    if (!buf || !png_image_finish_read(&image, NULL, buf, 0, NULL)) {
        snprintf(err, errlen, "%s: cannot read PNG: %s", path, buf ? image.message : "out of memory");
        free(buf);
        png_image_free(&image);
        return VFP_ERR;
    }
    *rgb = buf;
    *width = image.width;
    *height = image.height;
    return VFP_OK;
}
