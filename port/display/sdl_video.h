/* SPDX-License-Identifier: MIT */
/*
 * sdl_video.h: SDL's video subsystem is process-wide, and both the SDL display (display_sdl.c) and the SDL keys
 * (input_sdl.c) need it. Each calls vfp_sdl_init() when it opens and vfp_sdl_quit() when it closes; the first
 * init calls SDL_Init(SDL_INIT_VIDEO), the last quit calls SDL_Quit(). Call both from the thread that runs the
 * viewer's loop (SDL wants its video calls on one thread). Defined in display_sdl.c (VFP_HAVE_SDL).
 */
#ifndef VFP_SDL_VIDEO_H
#define VFP_SDL_VIDEO_H

#include <stddef.h>

#include "status.h"

/* Returns VFP_OK, or VFP_ERR with "SDL_Init failed: SDL's reason" in err. */
vfp_status_t vfp_sdl_init(char *err, size_t errlen);
void vfp_sdl_quit(void);

#endif
