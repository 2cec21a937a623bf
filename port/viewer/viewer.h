/* SPDX-License-Identifier: MIT */
/*
 * viewer.h: the knob-driven viewer (build/volfix), in four files:
 *   main.c    options, set-up and the closing summary
 *   scene.c   the volume (and its half-resolution preview), the transfer functions, and bringing a renderer up
 *             to date with the controls
 *   worker.c  a thread that renders the full-quality frame once the knobs rest, so that a slow table or
 *             run-length rebuild never holds up the knobs
 *   loop.c    the event loop: input, signals, previews, the display (lost and found again), overlay, log
 *
 * Frames come in two qualities. While a knob turns the main thread renders a preview from the downsampled
 * volume (an eighth of the voxels: reclassifying after a transfer-function move is eight times cheaper too);
 * once the knobs have rested for idle_ms the worker renders the full volume and the loop shows it if nothing
 * changed meanwhile. With the preview off (small volumes) every frame is full quality and the worker is idle.
 */
#ifndef VIEWER_H
#define VIEWER_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>

#include "board/board.h"
#include "input/controls.h"
#include "display/display.h"
#include "input/input.h"
#include "render/render_mt.h"
#include "render/sampling.h"
#include "io/lighting_opts.h"
#include "io/tf.h"
#include "io/volume.h"

#define VIEWER_MAX_TFS 16
#define VIEWER_ERR_LEN 512

/* What the frames are rendered from; read-only once set up, shared by the loop and the worker. */
typedef struct viewer_scene {
    vfp_volume_t full;
    vfp_volume_t preview;    /* the full volume downsampled preview_factor times (unused when factor 1) */
    int preview_factor;      /* 1: no preview */
    vf_window_t window;      /* raw values, of the full volume */
    vfp_tf_t tfs[VIEWER_MAX_TFS];
    char tf_args[VIEWER_MAX_TFS][VFP_PATH_LEN + 16]; /* how volfix-sim names each: "--preset ramp", "--tf FILE" */
    int tf_count;
    vf_params_t params;      /* the mode comes from the controls, lighting from the transfer function */
    uint32_t rays_given;     /* --rays, 0 when not given: the full volume's frames then take the spacing's
                              * (render/sampling.h); previews take one */
    /* How each transfer function is lit (the lighting options and its own shade and material lines): frames of
     * transfer function k are lit when lit[k], with lighting[k] */
    int lit[VIEWER_MAX_TFS];
    vf_lighting_t lighting[VIEWER_MAX_TFS];
    int threads;
} viewer_scene_t;

/* The rays of a frame of this volume (the full one or the preview), lit or not: --rays or the spacing's default
 * for the full volume, one for the preview. */
uint32_t viewer_rays(const viewer_scene_t *scene, const vfp_volume_t *volume, int lit);

/* A renderer and the controls it was last brought up to date with. */
typedef struct viewer_renderer {
    vfp_render_t r;
    int open;
    const vfp_volume_t *volume;
    vf_mode_t mode;
    int lit;                 /* made with params.lighting (for a lit transfer function) */
    vf_lighting_t lighting;  /* set last (when lit) */
    int preset;
    double tf_shift, tf_scale;
} viewer_renderer_t;

/* The lighting of c's frames: the transfer function's (the options' and its file's), shaded as c->shade says
 * (-1: as the transfer function says) and lit by c's light as the first light. Returns whether frames are lit
 * at all (shaded, or a gradient-opacity ramp): a renderer made with params.lighting. */
int viewer_lighting(const viewer_scene_t *scene, const vfp_controls_t *c, vf_lighting_t *lighting);

/* Bring vr up to date with c: a new renderer for a new mode or when the lighting is turned on or off (a lit
 * renderer keeps normals, which cost memory), a reclassification for a new transfer function, and the lighting
 * set again after it or when it changed. Returns VFP_OK, or VFP_ERR with err. */
vfp_status_t viewer_sync(viewer_renderer_t *vr, const viewer_scene_t *scene, const vfp_volume_t *volume,
                         const vfp_controls_t *c, char *err, size_t errlen);
/* Render a frame of c into image (after viewer_sync). */
vfp_status_t viewer_render(viewer_renderer_t *vr, const vfp_controls_t *c, int rotation, const vf_image_t *image,
                           char *err, size_t errlen);
void viewer_renderer_close(viewer_renderer_t *vr);

/* The full-quality renderer's thread. The loop hands it the controls of a generation; it renders and writes a
 * byte to wake_fd[1]. A request for an older generation than `latest` is dropped between stages. */
typedef struct viewer_worker {
    const viewer_scene_t *scene;
    viewer_renderer_t vr;
    int rotation;
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t cond;
    int wake_fd[2];
    atomic_uint_fast64_t latest; /* the loop's current generation */
    /* under lock */
    int stop;
    int busy;                /* a request is being worked on */
    int have_request;
    vfp_controls_t request;
    uint64_t request_gen;
    uint32_t request_width, request_height;
    vf_format_t request_format;
    int have_result;
    uint64_t result_gen;
    vf_image_t image;        /* the result, in the display's size and format */
    double result_ms;
    vfp_status_t result_status;
    char result_err[VIEWER_ERR_LEN];
} viewer_worker_t;

vfp_status_t viewer_worker_start(viewer_worker_t *w, const viewer_scene_t *scene, int rotation, char *err,
                                 size_t errlen);
/* Hand it a frame to render at this size and format; only while it is neither busy nor holding a result the
 * loop has not taken (the loop reads the result image under the lock, and nobody else writes it then). */
void viewer_worker_request(viewer_worker_t *w, const vfp_controls_t *c, uint64_t gen, uint32_t width,
                           uint32_t height, vf_format_t format);
void viewer_worker_stop(viewer_worker_t *w);

/* Everything the loop needs; main.c fills it. */
typedef struct viewer {
    vfp_board_t board;
    const char *script;      /* --script, or NULL */
    viewer_scene_t scene;
    vfp_controls_t controls, home;
    const vfp_display_ops_t *display_ops;
    const vfp_input_ops_t *input_ops;
    FILE *log;               /* --log, or NULL */
    const char *log_path;    /* its name, for messages */
    const char *volume_arg;  /* as given on the command line, for the log's volfix-sim lines */
    unsigned max_frames;     /* --frames N: leave after N frames (0: no limit) */
    int verbose;
} viewer_t;

/* SIGINT and SIGTERM, from the start of the program: the handler notes the signal and wakes the loop, and a read
 * that waits is interrupted (EINTR). viewer_signals_catch returns VFP_OK, or VFP_ERR with err;
 * viewer_signal_caught is the signal's number (0: none), for the exit status 128 + N; viewer_signals_release
 * puts the default handlers back. */
vfp_status_t viewer_signals_catch(char *err, size_t errlen);
int viewer_signal_caught(void);
void viewer_signals_release(void);

/* Run until quit (a quit button or the script's "quit": the full-quality frame is shown first), SIGINT or
 * SIGTERM (viewer_signal_caught then says which), or with --frames N, N frames or the end of a script without
 * "quit". Returns VFP_OK, or VFP_ERR after printing a one-line error. Prints the session's summary and gives the
 * display back in every case. */
vfp_status_t viewer_loop(viewer_t *v);

#endif
