/* SPDX-License-Identifier: MIT */
/*
 * test_display.c: finding a backend by name; fbdev through its seams (the kernel's fb ioctls cannot be made on a
 * regular file, so the format checks and the line_length copying run on screen information and memory the test
 * makes); the errors DRM gives on a machine without a card; the SDL window on SDL's dummy video driver.
 */
#include <errno.h>
#include <fcntl.h>
#include <linux/fb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "display/display.h"
#include "display/display_backends.h" /* the fbdev backend's table and seams */
#ifdef VFP_HAVE_SDL
#include <SDL.h>

#include "display/sdl_video.h"
#endif

static vfp_board_t board_named(const char *display, const char *device)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    snprintf(b.path, sizeof b.path, "boards/test.board");
    snprintf(b.display, sizeof b.display, "%s", display);
    snprintf(b.display_device, sizeof b.display_device, "%s", device);
    return b;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Finding backends */

static void find_known(void)
{
    vfp_board_t b = board_named("png", "");
    char err[256] = "";
    const char *always[] = {"png", "fbdev"};
    for (int i = 0; i < 2; i++) {
        const vfp_display_ops_t *ops = vfp_display_find(always[i], &b, err, sizeof err);
        CHECK_MSG(ops && strcmp(ops->name, always[i]) == 0, "%s: %s", always[i], err);
        CHECK(ops->open && ops->present && ops->close);
    }
    struct {
        const char *name, *package;
        int compiled;
    } optional[] = {
        {"drm", "libdrm-dev",
#ifdef VFP_HAVE_DRM
         1
#else
         0
#endif
        },
        {"gud", "libusb-1.0-0-dev",
#ifdef VFP_HAVE_GUD
         1
#else
         0
#endif
        },
        {"sdl", "libsdl2-dev",
#ifdef VFP_HAVE_SDL
         1
#else
         0
#endif
        },
    };
    for (int i = 0; i < 3; i++) {
        err[0] = 0;
        const vfp_display_ops_t *ops = vfp_display_find(optional[i].name, &b, err, sizeof err);
        if (optional[i].compiled) {
            CHECK_MSG(ops && strcmp(ops->name, optional[i].name) == 0, "%s: %s", optional[i].name, err);
        } else {
            char expected[200];
            snprintf(expected, sizeof expected, "boards/test.board: display '%s' is not compiled in: install %s "
                     "and rebuild", optional[i].name, optional[i].package);
            CHECK(ops == NULL);
            CHECK_MSG(strcmp(err, expected) == 0, "%s", err);
        }
    }
}

static void find_unknown(void)
{
    vfp_board_t b = board_named("vga", "");
    char err[256] = "";
    CHECK(vfp_display_find("vga", &b, err, sizeof err) == NULL);
    CHECK_MSG(strcmp(err, "boards/test.board: unknown display 'vga' (expected drm, fbdev, gud, sdl, png or none)") == 0,
              "%s", err);
    CHECK(vfp_display_find("", NULL, err, sizeof err) == NULL);
    CHECK_MSG(strcmp(err, "no display given (expected drm, fbdev, gud, sdl, png or none)") == 0, "%s", err);
    CHECK(vfp_display_find("PNG", NULL, err, sizeof err) == NULL); /* names are exact */
    char tiny[8];
    CHECK(vfp_display_find("vga", &b, tiny, sizeof tiny) == NULL); /* truncated, not overrun */
    CHECK(strlen(tiny) == 7);
}

static void table_terminated_and_unique(void)
{
    int n = 0;
    for (; vfp_displays[n]; n++) {
        CHECK(n < 6); /* drm, fbdev, gud, sdl, png, none */
        for (int k = 0; k < n; k++)
            CHECK(strcmp(vfp_displays[k]->name, vfp_displays[n]->name) != 0);
    }
    CHECK(n >= 3); /* fbdev, png and none are always there */
}

/* ---------------------------------------------------------------------------------------------------------- */
/* fbdev */

static void fb_info(struct fb_var_screeninfo *var, struct fb_fix_screeninfo *fix, uint32_t bpp, uint32_t w,
                    uint32_t h, uint32_t line_length)
{
    memset(var, 0, sizeof *var);
    memset(fix, 0, sizeof *fix);
    var->xres = var->xres_virtual = w;
    var->yres = var->yres_virtual = h;
    var->bits_per_pixel = bpp;
    if (bpp == 16) {
        var->red = (struct fb_bitfield){11, 5, 0};
        var->green = (struct fb_bitfield){5, 6, 0};
        var->blue = (struct fb_bitfield){0, 5, 0};
    } else {
        var->red = (struct fb_bitfield){16, 8, 0};
        var->green = (struct fb_bitfield){8, 8, 0};
        var->blue = (struct fb_bitfield){0, 8, 0};
        var->transp = (struct fb_bitfield){24, 8, 0};
    }
    fix->type = FB_TYPE_PACKED_PIXELS;
    fix->visual = FB_VISUAL_TRUECOLOR;
    fix->line_length = line_length;
    fix->smem_len = line_length * h;
}

static void fbdev_formats(void)
{
    struct fb_var_screeninfo var;
    struct fb_fix_screeninfo fix;
    vf_format_t format;
    char err[300] = "";
    fb_info(&var, &fix, 16, 320, 240, 640);
    CHECK_MSG(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(format, VF_FORMAT_RGB565);
    fb_info(&var, &fix, 32, 320, 240, 1280);
    CHECK_MSG(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(format, VF_FORMAT_XRGB8888);
    var.transp = (struct fb_bitfield){0, 0, 0}; /* no alpha field: still XRGB8888 */
    CHECK_EQ(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err), 0);

    /* BGR order in 32 bits: the message names the device and what it found */
    var.red.offset = 0, var.blue.offset = 16;
    CHECK_EQ(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err), 2);
    CHECK_MSG(strcmp(err, "/dev/fb1: unsupported pixel format: 32 bpp, red 0/8, green 8/8, blue 16/8 (expected 16 "
                     "bpp RGB565 or 32 bpp XRGB8888)") == 0, "%s", err);
    /* BGR565 */
    fb_info(&var, &fix, 16, 320, 240, 640);
    var.red.offset = 0, var.blue.offset = 11;
    CHECK_EQ(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err), 2);
    CHECK_MSG(strstr(err, "16 bpp, red 0/5, green 5/6, blue 11/5") != NULL, "%s", err);
    /* RGB555 */
    fb_info(&var, &fix, 16, 320, 240, 640);
    var.red.offset = 10, var.green.length = 5;
    CHECK_EQ(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err), 2);
    /* 24 bpp */
    fb_info(&var, &fix, 32, 320, 240, 960);
    var.bits_per_pixel = 24;
    CHECK_EQ(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err), 2);
    CHECK_MSG(strstr(err, ": 24 bpp,") != NULL, "%s", err);
    /* greyscale, and a palette visual */
    fb_info(&var, &fix, 16, 320, 240, 640);
    var.grayscale = 1;
    CHECK_EQ(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err), 2);
    CHECK_MSG(strstr(err, "greyscale") != NULL, "%s", err);
    fb_info(&var, &fix, 16, 320, 240, 640);
    fix.visual = FB_VISUAL_PSEUDOCOLOR;
    CHECK_EQ(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err), 2);
    CHECK_MSG(strstr(err, "/dev/fb1: unsupported framebuffer: type 0, visual 3") != NULL, "%s", err);
    fb_info(&var, &fix, 16, 320, 240, 640);
    fix.type = FB_TYPE_PLANES;
    CHECK_EQ(vfp_fbdev_check(&var, &fix, "/dev/fb1", &format, err, sizeof err), 2);
}

/* A 4x3 RGB565 panel whose rows are 14 bytes apart (8 of pixels, 6 of padding the driver keeps). */
static void fbdev_line_length(void)
{
    struct fb_var_screeninfo var;
    struct fb_fix_screeninfo fix;
    fb_info(&var, &fix, 16, 4, 3, 14);
    uint8_t mem[14 * 3];
    memset(mem, 0xaa, sizeof mem);
    vfp_display_t d = {&vfp_display_fbdev_ops, 0, 0, 0, NULL};
    char err[300] = "";
    CHECK_MSG(vfp_fbdev_attach(&d, &var, &fix, mem, sizeof mem, "/dev/fb1", err, sizeof err) == 0, "%s", err);
    CHECK_EQ(d.width, 4);
    CHECK_EQ(d.height, 3);
    CHECK_EQ(d.format, VF_FORMAT_RGB565);

    /* the viewer's frame, rows 10 bytes apart; pixel (x, y) = 0x1000 * y + x */
    uint8_t frame[10 * 3];
    memset(frame, 0x55, sizeof frame);
    for (int y = 0; y < 3; y++)
        for (int x = 0; x < 4; x++) {
            frame[y * 10 + x * 2] = (uint8_t)x;
            frame[y * 10 + x * 2 + 1] = (uint8_t)(0x10 * y);
        }
    CHECK_MSG(d.ops->present(&d, 1, 1, 2, 2, frame, 10, err, sizeof err) == 0, "%s", err);
    for (int y = 0; y < 3; y++)
        for (int i = 0; i < 14; i++) {
            int x = i / 2;
            int inside = y >= 1 && x >= 1 && x <= 2;
            uint8_t want = inside ? frame[y * 10 + i] : 0xaa;
            CHECK_MSG(mem[y * 14 + i] == want, "row %d byte %d: %02x, expected %02x", y, i, mem[y * 14 + i], want);
        }
    CHECK_MSG(d.ops->present(&d, 0, 0, 4, 3, frame, 10, err, sizeof err) == 0, "%s", err);
    for (int y = 0; y < 3; y++) {
        CHECK(memcmp(mem + y * 14, frame + y * 10, 8) == 0);
        CHECK(mem[y * 14 + 8] == 0xaa && mem[y * 14 + 13] == 0xaa);
    }
    CHECK_EQ(d.ops->present(&d, 3, 0, 2, 1, frame, 10, err, sizeof err), 2);
    CHECK_MSG(strstr(err, "/dev/fb1: rectangle 2x1 at (3,0)") != NULL, "%s", err);
    CHECK_EQ(d.ops->present(&d, 0, 0, 4, 1, frame, 6, err, sizeof err), 2); /* stride shorter than the rectangle */
    d.ops->close(&d);
    CHECK(d.priv == NULL);
}

/* The visible area panned to (1, 2) of a larger virtual XRGB8888 framebuffer. */
static void fbdev_pan_offsets(void)
{
    struct fb_var_screeninfo var;
    struct fb_fix_screeninfo fix;
    fb_info(&var, &fix, 32, 2, 2, 16);
    var.xres_virtual = 4, var.yres_virtual = 4, var.xoffset = 1, var.yoffset = 2;
    uint32_t mem[16];
    memset(mem, 0, sizeof mem);
    vfp_display_t d = {&vfp_display_fbdev_ops, 0, 0, 0, NULL};
    char err[300] = "";
    CHECK_MSG(vfp_fbdev_attach(&d, &var, &fix, mem, sizeof mem, "/dev/fb0", err, sizeof err) == 0, "%s", err);
    CHECK_EQ(d.format, VF_FORMAT_XRGB8888);
    const uint32_t frame[4] = {0xff111111, 0xff222222, 0xff333333, 0xff444444};
    CHECK_MSG(d.ops->present(&d, 0, 0, 2, 2, frame, 8, err, sizeof err) == 0, "%s", err);
    CHECK(mem[2 * 4 + 1] == 0xff111111 && mem[2 * 4 + 2] == 0xff222222);
    CHECK(mem[3 * 4 + 1] == 0xff333333 && mem[3 * 4 + 2] == 0xff444444);
    CHECK(mem[0] == 0 && mem[2 * 4] == 0 && mem[2 * 4 + 3] == 0);
    d.ops->close(&d);

    /* memory too small for the panned area */
    CHECK_EQ(vfp_fbdev_attach(&d, &var, &fix, mem, 16 * 3, "/dev/fb0", err, sizeof err), 2);
    CHECK_MSG(strstr(err, "/dev/fb0: inconsistent framebuffer: 2x2 visible at (1,2), 16 bytes a line, 48 bytes")
              != NULL, "%s", err);
    CHECK(d.priv == NULL);
    fix.line_length = 8; /* shorter than xoffset + xres pixels */
    CHECK_EQ(vfp_fbdev_attach(&d, &var, &fix, mem, sizeof mem, "/dev/fb0", err, sizeof err), 2);
}

static void fbdev_not_a_framebuffer(void)
{
    char path[] = "/tmp/volfix-fb-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    unlink(path);
    vfp_display_t d = {&vfp_display_fbdev_ops, 0, 0, 0, NULL};
    char err[300] = "";
    CHECK_EQ(vfp_fbdev_open_fd(&d, fd, "/dev/fb7", err, sizeof err), 2);
    CHECK_MSG(strstr(err, "/dev/fb7: not a framebuffer device (FBIOGET_VSCREENINFO: ") != NULL, "%s", err);
    CHECK(d.priv == NULL);
    errno = 0;
    CHECK(fcntl(fd, F_GETFD) == -1 && errno == EBADF); /* the descriptor was taken, and closed */

    vfp_board_t b = board_named("fbdev", "/nonexistent/fb9");
    CHECK_EQ(d.ops->open(&d, &b, err, sizeof err), 2);
    CHECK_MSG(strcmp(err, "/nonexistent/fb9: cannot open: No such file or directory") == 0, "%s", err);
    d.ops->close(&d);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* DRM: only the errors can run here (no card on a build machine) */

static void drm_errors(void)
{
#ifdef VFP_HAVE_DRM
    const vfp_display_ops_t *ops = vfp_display_find("drm", NULL, NULL, 0);
    CHECK(ops != NULL);
    vfp_display_t d = {ops, 0, 0, 0, NULL};
    char err[300] = "";
    vfp_board_t b = board_named("drm", "/nonexistent/card9");
    CHECK_EQ(ops->open(&d, &b, err, sizeof err), 2);
    CHECK_MSG(strstr(err, "/nonexistent/card9: cannot open: No such file or directory") != NULL, "%s", err);
    CHECK(d.priv == NULL);

    char path[] = "/tmp/volfix-card-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    close(fd);
    b = board_named("drm", path);
    CHECK_EQ(ops->open(&d, &b, err, sizeof err), 2);
    unlink(path);
    CHECK_MSG(strstr(err, path) && strstr(err, "not a mode-setting device"), "%s", err);

    if (access("/dev/dri", F_OK) != 0) {
        b = board_named("drm", "");
        CHECK_EQ(ops->open(&d, &b, err, sizeof err), 2);
        CHECK_MSG(strcmp(err, "no DRM card found (/dev/dri/card0 to card15): is the KMS driver loaded?") == 0, "%s",
                  err);
    }
    ops->close(&d);
#endif
}

/* ---------------------------------------------------------------------------------------------------------- */
/* SDL, on the dummy video driver (no display needed) */

#ifdef VFP_HAVE_SDL
static SDL_Window *volfix_window(void)
{
    for (Uint32 id = 1; id < 64; id++) {
        SDL_Window *w = SDL_GetWindowFromID(id);
        if (w && strcmp(SDL_GetWindowTitle(w), "volfix") == 0)
            return w;
    }
    return NULL;
}
#endif

static void sdl_window(void)
{
#ifdef VFP_HAVE_SDL
    setenv("SDL_VIDEODRIVER", "dummy", 1);
    const vfp_display_ops_t *ops = vfp_display_find("sdl", NULL, NULL, 0);
    CHECK(ops != NULL);
    vfp_display_t d = {ops, 0, 0, 0, NULL};
    char err[300] = "";
    vfp_board_t b = board_named("sdl", "");
    b.width = 240, b.height = 135, b.format = VF_FORMAT_RGB565;
    CHECK_MSG(ops->open(&d, &b, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(d.width, 240);
    CHECK_EQ(d.height, 135);
    CHECK_EQ(d.format, VF_FORMAT_RGB565);
    SDL_Window *w = volfix_window();
    CHECK(w != NULL);
    int ww, wh;
    SDL_GetWindowSize(w, &ww, &wh);
    CHECK_EQ(ww, 480); /* under 320 on the longer side: twice as large */
    CHECK_EQ(wh, 270);
    static uint8_t frame[240 * 135 * 2];
    memset(frame, 0x5a, sizeof frame);
    CHECK_MSG(ops->present(&d, 0, 0, 240, 135, frame, 480, err, sizeof err) == 0, "%s", err);
    CHECK_MSG(ops->present(&d, 10, 20, 30, 40, frame, 480, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(ops->present(&d, 230, 0, 20, 1, frame, 480, err, sizeof err), 2);

    /* the video subsystem is shared: another user keeps it up after the display closes */
    CHECK_EQ(vfp_sdl_init(err, sizeof err), 0);
    ops->close(&d);
    CHECK(SDL_WasInit(SDL_INIT_VIDEO) != 0);
    vfp_sdl_quit();
    CHECK(SDL_WasInit(SDL_INIT_VIDEO) == 0);

    /* a large panel keeps its size; XRGB8888 and RGB888 textures */
    b.width = 480, b.height = 320, b.format = VF_FORMAT_XRGB8888;
    CHECK_MSG(ops->open(&d, &b, err, sizeof err) == 0, "%s", err);
    SDL_GetWindowSize(volfix_window(), &ww, &wh);
    CHECK(ww == 480 && wh == 320);
    static uint8_t big[480 * 320 * 4];
    CHECK_MSG(ops->present(&d, 0, 0, 480, 320, big, 480 * 4, err, sizeof err) == 0, "%s", err);
    ops->close(&d);
    b.format = VF_FORMAT_RGB888;
    CHECK_MSG(ops->open(&d, &b, err, sizeof err) == 0, "%s", err);
    CHECK_MSG(ops->present(&d, 1, 1, 10, 10, big, 480 * 3, err, sizeof err) == 0, "%s", err);
    ops->close(&d);
    ops->close(&d);
    CHECK(SDL_WasInit(SDL_INIT_VIDEO) == 0);

    b.width = 0;
    CHECK_EQ(ops->open(&d, &b, err, sizeof err), 2);
    CHECK_MSG(strstr(err, "display 'sdl' needs a size") != NULL, "%s", err);
#endif
}

CHECK_CASES({"find_known", find_known}, {"find_unknown", find_unknown},
            {"table_terminated_and_unique", table_terminated_and_unique}, {"fbdev_formats", fbdev_formats},
            {"fbdev_line_length", fbdev_line_length}, {"fbdev_pan_offsets", fbdev_pan_offsets},
            {"fbdev_not_a_framebuffer", fbdev_not_a_framebuffer}, {"drm_errors", drm_errors},
            {"sdl_window", sdl_window});
CHECK_RUN("display")
