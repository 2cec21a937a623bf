/* SPDX-License-Identifier: MIT */
/*
 * display_backends.h: the display backends' ops tables and the seams their tests drive, for the registry
 * (display.c) and tests, not for applications: a program (the viewer) finds its backend with vfp_display_find()
 * (display.h, the contract shared with it), and nothing here is a promise to it.
 *
 * Each table lives in its backend's file (display_NAME.c); an optional backend's file defines it only when its
 * library is there (the Makefile's VFP_HAVE_DRM, VFP_HAVE_GUD, VFP_HAVE_SDL), so its declaration is conditional
 * too.
 */
#ifndef VFP_DISPLAY_BACKENDS_H
#define VFP_DISPLAY_BACKENDS_H

#include <stddef.h>

#include "display.h"
#include "volfix.h"

#ifdef VFP_HAVE_DRM
extern const vfp_display_ops_t vfp_display_drm_ops; /* display_drm.c */
#endif
extern const vfp_display_ops_t vfp_display_fbdev_ops; /* display_fbdev.c */
#ifdef VFP_HAVE_GUD
extern const vfp_display_ops_t vfp_display_gud_ops; /* display_gud.c */
#endif
#ifdef VFP_HAVE_SDL
extern const vfp_display_ops_t vfp_display_sdl_ops; /* display_sdl.c */
#endif
extern const vfp_display_ops_t vfp_display_png_ops; /* display_png.c */
extern const vfp_display_ops_t vfp_display_none_ops; /* display_none.c */

/* ---------------------------------------------------------------------------------------------------------- */
/* display_fbdev.c's seams: the kernel's fb ioctls cannot be made on a regular file, so tests open from a
 * descriptor, run the pure format check, and attach the display to screen information and memory they make. */

struct fb_var_screeninfo; /* <linux/fb.h> */
struct fb_fix_screeninfo;

/* Takes fd (closed on failure too): reads the screen information, checks the format, maps the memory. */
vfp_status_t vfp_fbdev_open_fd(vfp_display_t *d, int fd, const char *name, char *err, size_t errlen);
/* RGB565 or XRGB8888 in packed pixels, or VFP_ERR with a message naming the device and what it found. */
vfp_status_t vfp_fbdev_check(const struct fb_var_screeninfo *var, const struct fb_fix_screeninfo *fix, const char *name,
                             vf_format_t *format, char *err, size_t errlen);
/* The display over memory the caller maps (and keeps): checks the format and that the visible area fits. */
vfp_status_t vfp_fbdev_attach(vfp_display_t *d, const struct fb_var_screeninfo *var,
                              const struct fb_fix_screeninfo *fix, void *mem, size_t mem_len, const char *name,
                              char *err, size_t errlen);

#endif /* VFP_DISPLAY_BACKENDS_H */
