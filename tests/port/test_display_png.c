/* SPDX-License-Identifier: MIT */
/* test_display_png.c: the PNG display: numbered frames, the pixels of each format, sub-rectangles, errors. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "display/display.h"
#include "display/display_backends.h" /* the png backend's table */
#include "fixtures.h"
#include "io/pngio.h"

static vfp_board_t board_for(const char *dir, uint32_t w, uint32_t h, vf_format_t format)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    snprintf(b.display, sizeof b.display, "png");
    snprintf(b.display_device, sizeof b.display_device, "%s", dir);
    b.width = w;
    b.height = h;
    b.format = format;
    return b;
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Reads DIR/frame-N.png as RGB into rgb (w*h*3); returns 0 on success. */
static int read_frame(const char *dir, unsigned n, uint8_t *rgb, uint32_t w, uint32_t h)
{
    char path[300], err[256];
    snprintf(path, sizeof path, "%s/frame-%05u.png", dir, n);
    uint8_t *got;
    uint32_t gw, gh;
    if (vfp_png_read_rgb(path, &got, &gw, &gh, err, sizeof err))
        return 1;
    int bad = gw != w || gh != h;
    if (!bad)
        memcpy(rgb, got, (size_t)w * h * 3);
    free(got);
    return bad;
}

/* A png display of w x h pixels in `format`, open, writing into the directory fx_path(name), copied to dir
 * (256 bytes); the case fails if it does not open with that mode. */
static void open_png(vfp_display_t *d, const char *name, uint32_t w, uint32_t h, vf_format_t format, char *dir)
{
    snprintf(dir, 256, "%s", fx_path(name));
    vfp_board_t b = board_for(dir, w, h, format);
    *d = (vfp_display_t){&vfp_display_png_ops, 0, 0, 0, NULL};
    char err[256] = "";
    CHECK_MSG(d->ops->open(d, &b, err, sizeof err) == VFP_OK, "%s", err);
    CHECK(d->width == w && d->height == h && d->format == format);
}

/* One whole frame (rows stride bytes apart) through a fresh display; the file it writes read back into rgb. */
static void show_frame(const char *name, uint32_t w, uint32_t h, vf_format_t format, const uint8_t *frame,
                       uint32_t stride, uint8_t *rgb)
{
    char dir[256], err[256] = "";
    vfp_display_t d;
    open_png(&d, name, w, h, format, dir);
    if (check_failed)
        return;
    CHECK_MSG(d.ops->present(&d, 0, 0, w, h, frame, stride, err, sizeof err) == VFP_OK, "%s", err);
    d.ops->close(&d);
    CHECK_EQ(read_frame(dir, 0, rgb, w, h), 0);
}

/* ---------------------------------------------------------------------------------------------------------- */

static void frames_numbered(void)
{
    char dir[256], err[256] = "";
    vfp_display_t d;
    open_png(&d, "numbered", 3, 2, VF_FORMAT_RGB888, dir);
    if (check_failed)
        return;
    uint8_t frame[3 * 2 * 3];
    for (int i = 0; i < 3; i++) {
        memset(frame, 40 * i, sizeof frame);
        CHECK_MSG(d.ops->present(&d, 0, 0, 3, 2, frame, 9, err, sizeof err) == VFP_OK, "%s", err);
    }
    d.ops->close(&d);
    CHECK(d.priv == NULL);
    char path[300];
    for (unsigned i = 0; i < 4; i++) {
        snprintf(path, sizeof path, "%s/frame-%05u.png", dir, i);
        CHECK_MSG(file_exists(path) == (i < 3), "%s", path);
    }
    uint8_t rgb[18];
    CHECK_EQ(read_frame(dir, 2, rgb, 3, 2), 0);
    CHECK_EQ(rgb[0], 80);
    CHECK_EQ(rgb[17], 80);
}

static void pixels_rgb888(void)
{
    /* rows 8 bytes apart: 6 of pixels, 2 of padding */
    const uint8_t frame[16] = {255, 0, 0, 0, 255, 0, 99, 99, 0, 0, 255, 10, 20, 30, 99, 99};
    const uint8_t expected[12] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30};
    uint8_t rgb[12];
    show_frame("rgb888", 2, 2, VF_FORMAT_RGB888, frame, 8, rgb);
    if (check_failed)
        return;
    CHECK(memcmp(rgb, expected, 12) == 0);
}

static void pixels_rgb565(void)
{
    /* little-endian words: red, green, blue / white, black, the middle of each channel */
    const uint8_t frame[12] = {0x00, 0xf8, 0xe0, 0x07, 0x1f, 0x00, 0xff, 0xff, 0x00, 0x00, 0x10, 0x84};
    /* 5 and 6 bits scaled to 0..255 with rounding: 16/31 -> 132, 32/63 -> 130 */
    const uint8_t expected[18] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0, 132, 130, 132};
    uint8_t rgb[18];
    show_frame("rgb565", 3, 2, VF_FORMAT_RGB565, frame, 6, rgb);
    if (check_failed)
        return;
    CHECK_MSG(memcmp(rgb, expected, 18) == 0, "last pixel %u %u %u", rgb[15], rgb[16], rgb[17]);
}

static void pixels_xrgb8888(void)
{
    /* bytes B, G, R, X */
    const uint8_t frame[8] = {0x30, 0x20, 0x10, 0xff, 0xcc, 0xbb, 0xaa, 0xff};
    const uint8_t expected[6] = {0x10, 0x20, 0x30, 0xaa, 0xbb, 0xcc};
    uint8_t rgb[6];
    show_frame("xrgb8888", 2, 1, VF_FORMAT_XRGB8888, frame, 8, rgb);
    if (check_failed)
        return;
    CHECK(memcmp(rgb, expected, 6) == 0);
}

/* A rectangle updates the kept frame, and the whole frame is written. */
static void sub_rectangle(void)
{
    char dir[256], err[256] = "";
    vfp_display_t d;
    open_png(&d, "sub", 4, 3, VF_FORMAT_RGB888, dir);
    if (check_failed)
        return;
    uint8_t first[4 * 3 * 3], second[4 * 3 * 3];
    memset(first, 7, sizeof first);
    memset(second, 200, sizeof second);
    CHECK_MSG(d.ops->present(&d, 0, 0, 4, 3, first, 12, err, sizeof err) == VFP_OK, "%s", err);
    /* only the 2x1 rectangle at (1,1) of the second image */
    CHECK_MSG(d.ops->present(&d, 1, 1, 2, 1, second, 12, err, sizeof err) == VFP_OK, "%s", err);
    /* a zero-sized rectangle still writes a frame */
    CHECK_MSG(d.ops->present(&d, 4, 3, 0, 0, second, 12, err, sizeof err) == VFP_OK, "%s", err);
    d.ops->close(&d);
    uint8_t rgb[36];
    CHECK_EQ(read_frame(dir, 1, rgb, 4, 3), 0);
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 4; x++) {
            int inside = y == 1 && (x == 1 || x == 2);
            CHECK_MSG(rgb[(y * 4 + x) * 3] == (inside ? 200 : 7), "pixel (%d,%d) is %u", x, y, rgb[(y * 4 + x) * 3]);
        }
    uint8_t again[36];
    CHECK_EQ(read_frame(dir, 2, again, 4, 3), 0);
    CHECK(memcmp(rgb, again, 36) == 0);
}

/* With no directory, out/frames under the working directory, made with its parents. */
static void default_directory(void)
{
    char cwd[512];
    CHECK(getcwd(cwd, sizeof cwd) != NULL);
    const char *base = fx_path("default");
    CHECK(mkdir(base, 0777) == 0);
    CHECK(chdir(base) == 0);
    vfp_board_t b = board_for("", 1, 1, VF_FORMAT_RGB565);
    vfp_display_t d = {&vfp_display_png_ops, 0, 0, 0, NULL};
    char err[256] = "";
    int opened = d.ops->open(&d, &b, err, sizeof err);
    uint8_t px[2] = {0, 0};
    int presented = opened == VFP_OK ? d.ops->present(&d, 0, 0, 1, 1, px, 2, err, sizeof err) : VFP_ERR;
    d.ops->close(&d);
    int exists = file_exists("out/frames/frame-00000.png");
    CHECK(chdir(cwd) == 0);
    CHECK_MSG(opened == VFP_OK && presented == VFP_OK, "%s", err);
    CHECK(exists);
}

static void bad_directory(void)
{
    char file[256];
    snprintf(file, sizeof file, "%s", fx_path("plain-file"));
    FILE *f = fopen(file, "w");
    CHECK(f != NULL);
    fclose(f);
    vfp_display_t d = {&vfp_display_png_ops, 0, 0, 0, NULL};
    char err[512] = "";

    vfp_board_t b = board_for(file, 4, 4, VF_FORMAT_RGB888);
    CHECK_EQ(d.ops->open(&d, &b, err, sizeof err), VFP_ERR);
    CHECK(d.priv == NULL);
    CHECK_MSG(strstr(err, "plain-file: not a directory") != NULL, "%s", err);

    char under[300];
    snprintf(under, sizeof under, "%s/frames", file);
    b = board_for(under, 4, 4, VF_FORMAT_RGB888);
    CHECK_EQ(d.ops->open(&d, &b, err, sizeof err), VFP_ERR);
    CHECK_MSG(strstr(err, "plain-file/frames: cannot create directory: Not a directory") != NULL, "%s", err);

    b = board_for(fx_path("nosize"), 0, 4, VF_FORMAT_RGB888);
    CHECK_EQ(d.ops->open(&d, &b, err, sizeof err), VFP_ERR);
    CHECK_MSG(strstr(err, "needs a size") != NULL, "%s", err);
    d.ops->close(&d); /* safe on a display that never opened */
}

static void bad_rectangle(void)
{
    char dir[256], err[512] = "";
    vfp_display_t d;
    open_png(&d, "rect", 4, 4, VF_FORMAT_RGB565, dir);
    if (check_failed)
        return;
    uint8_t frame[4 * 4 * 2] = {0};
    CHECK_EQ(d.ops->present(&d, 3, 0, 2, 1, frame, 8, err, sizeof err), VFP_ERR);
    CHECK_MSG(strstr(err, "does not fit the 4x4 display") != NULL, "%s", err);
    CHECK_EQ(d.ops->present(&d, 0, 0, 4, 4, frame, 6, err, sizeof err), VFP_ERR); /* stride shorter than a row */
    CHECK_EQ(d.ops->present(&d, 0, 0xffffffffu, 1, 2, frame, 8, err, sizeof err), VFP_ERR);
    d.ops->close(&d);
    d.ops->close(&d);
}

CHECK_CASES({"frames_numbered", frames_numbered}, {"pixels_rgb888", pixels_rgb888},
            {"pixels_rgb565", pixels_rgb565}, {"pixels_xrgb8888", pixels_xrgb8888},
            {"sub_rectangle", sub_rectangle}, {"default_directory", default_directory},
            {"bad_directory", bad_directory}, {"bad_rectangle", bad_rectangle});

CHECK_RUN("display_png")
