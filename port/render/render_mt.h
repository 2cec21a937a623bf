/* SPDX-License-Identifier: MIT */
/*
 * render_mt.h: the core renderer with its memory and threads provided: an arena from malloc sized by the
 * core's own queries (grown when a transfer function needs longer run lists), a stale pre-integrated table
 * built in a part a thread, and compositing and warping spread over threads in bands. The same pixels for any
 * thread count: each table entry is built by one part, each pixel computed by one band.
 *
 * Where one thread would build the 2D table as compositing reads it, a diagonal at a time, threads do the same in
 * a copy each, and a thread that needs a diagonal another has built copies it instead of building it again.
 *
 * A transfer function's run-length encoding is shared out too: each principal axis's slabs in ranges, a part a
 * range, joined by the core into the run lists one thread would make (vf_renderer_set_tf_begin).
 *
 * The threads live as long as the renderer: vfp_render_open starts threads - 1 workers, each frame wakes them
 * once, and the calling thread works beside them; vfp_render_close joins them. A renderer is used by one thread
 * at a time (its caller).
 */
#ifndef VFP_RENDER_MT_H
#define VFP_RENDER_MT_H

#include <stddef.h>

#include "image.h"
#include "status.h"
#include "volfix.h"

#define VFP_MAX_THREADS 16

struct vfp_pool; /* render_mt.c: the workers and what a frame gives them */

typedef struct vfp_render {
    vf_params_t params;
    const vf_volume_t *volume;
    vf_renderer_t *core;
    unsigned char *arena_buf;
    vf_arena_t arena;
    int have_window, have_tf;
    int core_fresh;                   /* the core has not had the window and transfer function yet */
    vf_window_t window;
    vf_tf_point_t tf_points[VF_MAX_TF_POINTS];
    vf_tf_t tf;
    int threads;
    uint32_t band_rows;               /* intermediate rows per compositing band */
    size_t scratch_bytes;
    void *scratch[VFP_MAX_THREADS];
    size_t table_copy_bytes;          /* with threads: each thread's copy of a table built as read (0: none) */
    void *table_copy[VFP_MAX_THREADS];
    struct vfp_pool *pool;            /* the workers, NULL with one thread */
    double ms_tables, ms_composite, ms_warp; /* the last frame's stages (begin includes table rebuilds) */
    double ms_classify;                      /* the last window or transfer-function change */
    uint32_t tf_parts;                /* the parts the last transfer function's run-length encoding was shared out
                                       * in (0: encoded whole on the calling thread) */
} vfp_render_t;

/* All return VFP_OK, or VFP_ERR with a one-line message in err. */
vfp_status_t vfp_render_open(vfp_render_t *r, const vf_params_t *params, const vf_volume_t *volume, int threads,
                             char *err, size_t errlen);
vfp_status_t vfp_render_set_window(vfp_render_t *r, vf_window_t window, char *err, size_t errlen);
vfp_status_t vfp_render_set_tf(vfp_render_t *r, const vf_tf_point_t *points, uint32_t count, char *err, size_t errlen);
vfp_status_t vfp_render_frame(vfp_render_t *r, const vf_view_t *view, const vf_image_t *image, char *err,
                              size_t errlen);
void vfp_render_close(vfp_render_t *r);

/* Milliseconds on the monotonic clock. */
double vfp_now_ms(void);

#endif
