/* SPDX-License-Identifier: MIT */
/*
 * display_sdl.c: an SDL2 window titled "volfix" on a desktop, board width x height (shown twice as large when the
 * longer side is under 320 pixels, so a small panel's layout stays readable). Frames go into a streaming texture
 * in the board's format and are rendered at once. Closing the window is an input event: input_sdl.c polls SDL's
 * events; this file only shares SDL's initialisation with it (sdl_video.h).
 */
#ifdef VFP_HAVE_SDL

/*********************
 *      INCLUDES
 *********************/
#include "display.h"
#include "display_backends.h"
#include "sdl_video.h"

#include <SDL.h>
#include <stdio.h>
#include <stdlib.h>

/*********************
 *      DEFINES
 *********************/
#define SMALL_SIDE 320 /* below this on the longer side, the window is scaled x2 */
#define MAX_SIDE 8192

/**********************
 *      TYPES
 **********************/
typedef struct sdl_display {
    SDL_Window *window;
    SDL_Renderer *renderer;
    SDL_Texture *texture;
    int initialised; /* holds a vfp_sdl_init() reference */
} sdl_display_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t sdl_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen);
static vfp_status_t sdl_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                uint32_t stride, char *err, size_t errlen);
static void sdl_close(vfp_display_t *d);
static Uint32 sdl_format(vf_format_t format);

/**********************
 *  STATIC VARIABLES
 **********************/
/* References to SDL's video subsystem (sdl_video.h). SDL's own state is process-wide, so this count is too;
 * it is only touched from the viewer's thread. */
static int sdl_users;

/**********************
 *  GLOBAL VARIABLES
 **********************/
const vfp_display_ops_t vfp_display_sdl_ops = {"sdl", sdl_open, sdl_present, sdl_close};

/**********************
 *   GLOBAL FUNCTIONS
 **********************/
vfp_status_t vfp_sdl_init(char *err, size_t errlen)
{
    if (sdl_users == 0 && SDL_Init(SDL_INIT_VIDEO) != 0) {
        snprintf(err, errlen, "SDL_Init failed: %s", SDL_GetError());
        return VFP_ERR;
    }
    sdl_users++;
    return VFP_OK;
}

void vfp_sdl_quit(void)
{
    if (sdl_users > 0 && --sdl_users == 0)
        SDL_Quit();
}

/**********************
 *   STATIC FUNCTIONS
 **********************/
static vfp_status_t sdl_open(vfp_display_t *d, const vfp_board_t *board, char *err, size_t errlen)
{
    d->priv = NULL;
    uint32_t w = board->width, h = board->height;
    if (w == 0 || h == 0 || w > MAX_SIDE || h > MAX_SIDE) {
        snprintf(err, errlen, "display 'sdl' needs a size from 1x1 to %dx%d (the board gives %ux%u)", MAX_SIDE,
                 MAX_SIDE, w, h);
        return VFP_ERR;
    }
    Uint32 format = sdl_format(board->format);
    if (format == SDL_PIXELFORMAT_UNKNOWN) {
        snprintf(err, errlen, "display 'sdl': unknown pixel format %d", (int)board->format);
        return VFP_ERR;
    }
    sdl_display_t *s = calloc(1, sizeof *s);
    if (!s) {
        snprintf(err, errlen, "display 'sdl': out of memory");
        return VFP_ERR;
    }
    if (vfp_sdl_init(err, errlen))
        goto fail;
    s->initialised = 1;
    int scale = (w > h ? w : h) < SMALL_SIDE ? 2 : 1;
    s->window = SDL_CreateWindow("volfix", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, (int)w * scale,
                                 (int)h * scale, 0);
    if (!s->window) {
        snprintf(err, errlen, "SDL_CreateWindow failed: %s", SDL_GetError());
        goto fail;
    }
    s->renderer = SDL_CreateRenderer(s->window, -1, 0);
    if (!s->renderer) {
        snprintf(err, errlen, "SDL_CreateRenderer failed: %s", SDL_GetError());
        goto fail;
    }
    s->texture = SDL_CreateTexture(s->renderer, format, SDL_TEXTUREACCESS_STREAMING, (int)w, (int)h);
    if (!s->texture) {
        snprintf(err, errlen, "SDL_CreateTexture failed: %s", SDL_GetError());
        goto fail;
    }
    SDL_SetRenderDrawColor(s->renderer, 0, 0, 0, 255);
    SDL_RenderClear(s->renderer);
    SDL_RenderPresent(s->renderer);
    d->priv = s;
    d->width = w;
    d->height = h;
    d->format = board->format;
    return VFP_OK;

fail:
    if (s->texture)
        SDL_DestroyTexture(s->texture);
    if (s->renderer)
        SDL_DestroyRenderer(s->renderer);
    if (s->window)
        SDL_DestroyWindow(s->window);
    if (s->initialised)
        vfp_sdl_quit();
    free(s);
    return VFP_ERR;
}

static vfp_status_t sdl_present(vfp_display_t *d, uint32_t x, uint32_t y, uint32_t w, uint32_t h, const void *pixels,
                                uint32_t stride, char *err, size_t errlen)
{
    sdl_display_t *s = d->priv;
    uint32_t bytes = vf_format_bytes(d->format);
    if (vfp_display_check_present(d, "sdl display", x, y, w, h, stride, err, errlen))
        return VFP_ERR;
    if (w == 0 || h == 0)
        return VFP_OK;
    SDL_Rect rect = {(int)x, (int)y, (int)w, (int)h};
    const uint8_t *first = (const uint8_t *)pixels + (size_t)y * stride + (size_t)x * bytes;
    if (SDL_UpdateTexture(s->texture, &rect, first, (int)stride) != 0 ||
        SDL_RenderCopy(s->renderer, s->texture, NULL, NULL) != 0) {
        snprintf(err, errlen, "sdl display: %s", SDL_GetError());
        return VFP_ERR;
    }
    SDL_RenderPresent(s->renderer);
    return VFP_OK;
}

static void sdl_close(vfp_display_t *d)
{
    sdl_display_t *s = d->priv;
    if (s) {
        SDL_DestroyTexture(s->texture);
        SDL_DestroyRenderer(s->renderer);
        SDL_DestroyWindow(s->window);
        vfp_sdl_quit();
        free(s);
    }
    d->priv = NULL;
}

/* The core's formats are little-endian words or bytes; SDL's packed formats are native words, the same on the
 * little-endian machines this runs on. */
static Uint32 sdl_format(vf_format_t format)
{
    switch (format) {
    case VF_FORMAT_RGB565:
        return SDL_PIXELFORMAT_RGB565;
    case VF_FORMAT_XRGB8888:
        return SDL_PIXELFORMAT_RGB888; /* SDL 2.0.14 and later also call it XRGB8888 */
    case VF_FORMAT_RGB888:
        return SDL_PIXELFORMAT_RGB24;
    default:
        return SDL_PIXELFORMAT_UNKNOWN;
    }
}

#else
/* Without SDL2 (VFP_HAVE_SDL) this backend is not compiled in; display.c says how to get it. */
typedef int vfp_display_sdl_unused_t;
#endif
