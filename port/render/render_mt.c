/* SPDX-License-Identifier: MIT */
/* render_mt.c: the core renderer with malloc'd memory and pthreads (see render_mt.h). */
#include "render_mt.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define WARP_BAND 16

typedef enum stage { STAGE_TABLES, STAGE_COMPOSITE, STAGE_WARP } stage_t;

typedef struct band_work {
    vfp_render_t *r;
    const vf_image_t *image;
    atomic_uint next_band;
    uint32_t bands, rows;    /* bands (table parts) to share out; rows of the stage */
    stage_t stage;
    atomic_int status;       /* the first failure, VF_OK otherwise */
} band_work_t;

typedef struct worker {
    band_work_t *work;
    int index;
} worker_t;

static vfp_status_t create_core(vfp_render_t *r, size_t arena_bytes, char *err, size_t errlen);
static vfp_status_t apply(vfp_render_t *r, int window_changed, char *err, size_t errlen);
static void *run_bands(void *arg);
static vf_status_t spread(vfp_render_t *r, band_work_t *work);

double vfp_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

vfp_status_t vfp_render_open(vfp_render_t *r, const vf_params_t *params, const vf_volume_t *volume, int threads,
                             char *err, size_t errlen)
{
    memset(r, 0, sizeof *r);
    r->params = *params;
    r->volume = volume;
    r->threads = threads < 1 ? 1 : threads > VFP_MAX_THREADS ? VFP_MAX_THREADS : threads;
    /* Taller bands pay a slab's or slice's set-up fewer times a frame, so one thread takes 32 rows at a time;
     * shorter ones share the work out more evenly, so more threads take fewer: about ten bands a thread for a
     * 300-row intermediate image, never fewer than 8 rows. */
    r->band_rows = 32 / (uint32_t)r->threads < 8 ? 8 : 32 / (uint32_t)r->threads;
    size_t fixed;
    vf_status_t s = vf_renderer_bytes(params, volume, &fixed);
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot render this volume: %s", vf_status_text(s));
        return VFP_ERR;
    }
    /* The run lists come on top; a quarter of the fixed part is usually plenty, and set_tf grows it if not. */
    if (create_core(r, fixed + fixed / 4, err, errlen))
        return VFP_ERR;
    return VFP_OK;
}

vfp_status_t vfp_render_set_window(vfp_render_t *r, vf_window_t window, char *err, size_t errlen)
{
    r->window = window;
    r->have_window = 1;
    return apply(r, 1, err, errlen);
}

vfp_status_t vfp_render_set_tf(vfp_render_t *r, const vf_tf_point_t *points, uint32_t count, char *err, size_t errlen)
{
    if (count > VF_MAX_TF_POINTS) {
        snprintf(err, errlen, "transfer function has %u points (at most %d)", count, VF_MAX_TF_POINTS);
        return VFP_ERR;
    }
    memcpy(r->tf_points, points, sizeof *points * count);
    r->tf.points = r->tf_points;
    r->tf.count = count;
    r->have_tf = 1;
    return apply(r, 0, err, errlen);
}

vfp_status_t vfp_render_frame(vfp_render_t *r, const vf_view_t *view, const vf_image_t *image, char *err, size_t errlen)
{
    double t0 = vfp_now_ms();
    /* with threads, a table that went stale is built in a part a thread; on one, the bands (one after another)
     * build the diagonals they read */
    const vf_frame_t frame = {.view = *view, .width = image->width, .height = image->height,
                              .table_parts = r->threads > 1 ? (uint32_t)r->threads : 0, .one_thread = r->threads == 1};
    vf_status_t s = vf_renderer_begin(r->core, &frame);
    if (s == VF_OK && vf_renderer_table_parts(r->core)) {
        band_work_t tables = {.r = r, .image = image, .stage = STAGE_TABLES};
        tables.bands = vf_renderer_table_parts(r->core);
        s = spread(r, &tables);
    }
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot begin a frame: %s", vf_status_text(s));
        return VFP_ERR;
    }
    double t1 = vfp_now_ms();
    const vf_factor_t *f = vf_renderer_factor(r->core);
    band_work_t work = {.r = r, .image = image, .rows = f->int_h, .stage = STAGE_COMPOSITE};
    work.bands = (f->int_h + r->band_rows - 1) / r->band_rows;
    s = spread(r, &work);
    double t2 = vfp_now_ms();
    if (s == VF_OK) {
        band_work_t warp = {.r = r, .image = image, .rows = image->height, .stage = STAGE_WARP};
        warp.bands = (image->height + WARP_BAND - 1) / WARP_BAND;
        s = spread(r, &warp);
    }
    double t3 = vfp_now_ms();
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot render a frame: %s", vf_status_text(s));
        return VFP_ERR;
    }
    r->ms_tables = t1 - t0;
    r->ms_composite = t2 - t1;
    r->ms_warp = t3 - t2;
    return VFP_OK;
}

void vfp_render_close(vfp_render_t *r)
{
    for (int t = 0; t < VFP_MAX_THREADS; t++)
        free(r->scratch[t]);
    free(r->arena_buf);
    memset(r, 0, sizeof *r);
}

static vfp_status_t create_core(vfp_render_t *r, size_t arena_bytes, char *err, size_t errlen)
{
    free(r->arena_buf); /* the core lived in it: gone with it, so that a failure below leaves nothing dangling */
    r->core = NULL;
    r->arena_buf = malloc(arena_bytes);
    if (!r->arena_buf) {
        snprintf(err, errlen, "out of memory: the renderer needs %zu MB", arena_bytes >> 20);
        return VFP_ERR;
    }
    vf_arena_init(&r->arena, r->arena_buf, arena_bytes);
    vf_status_t s = vf_renderer_create(&r->core, &r->params, r->volume, &r->arena);
    r->core_fresh = 1; /* it has neither window nor transfer function yet */
    if (s != VF_OK) {
        snprintf(err, errlen, "cannot create the renderer: %s", vf_status_text(s));
        return VFP_ERR;
    }
    /* Scratch for the tallest band or a table part, per thread; the core sizes it for any view of this volume. */
    r->scratch_bytes = vf_renderer_band_scratch_bytes(r->core, r->band_rows);
    if (r->threads > 1 && vf_renderer_table_part_bytes(r->core) > r->scratch_bytes)
        r->scratch_bytes = vf_renderer_table_part_bytes(r->core);
    for (int t = 0; t < r->threads; t++) {
        free(r->scratch[t]);
        r->scratch[t] = malloc(r->scratch_bytes);
        if (!r->scratch[t]) {
            snprintf(err, errlen, "out of memory for band scratch");
            return VFP_ERR;
        }
    }
    return VFP_OK;
}

/* Give the core what changed (the window, or the transfer function), growing the arena once if the run lists
 * need it; a new core gets both. Each core call re-encodes the runs, so a transfer-function change must not
 * set the window again: that would rebuild the slices and encode twice, which a turning level knob would feel. */
static vfp_status_t apply(vfp_render_t *r, int window_changed, char *err, size_t errlen)
{
    double t0 = vfp_now_ms();
    for (int attempt = 0; attempt < 2; attempt++) {
        vf_status_t s = VF_OK;
        if (r->have_window && (window_changed || r->core_fresh))
            s = vf_renderer_set_window(r->core, r->window);
        if (s == VF_OK && r->have_tf && (!window_changed || r->core_fresh))
            s = vf_renderer_set_tf(r->core, &r->tf);
        if (s == VF_OK) {
            r->core_fresh = 0;
            r->ms_classify = vfp_now_ms() - t0;
            return VFP_OK;
        }
        if (s != VF_ERR_NOMEM || attempt == 1) {
            snprintf(err, errlen, "%s: %s", r->have_tf ? "cannot apply the transfer function" : "cannot set the window",
                     vf_status_text(s));
            return VFP_ERR;
        }
        size_t needed = vf_renderer_needed_bytes(r->core);
        if (create_core(r, needed + needed / 8, err, errlen))
            return VFP_ERR;
    }
    return VFP_ERR;
}

static void *run_bands(void *arg)
{
    worker_t *w = arg;
    band_work_t *work = w->work;
    vfp_render_t *r = work->r;
    for (;;) {
        unsigned band = atomic_fetch_add(&work->next_band, 1);
        if (band >= work->bands || atomic_load(&work->status) != VF_OK)
            break;
        vf_status_t s;
        if (work->stage == STAGE_TABLES) {
            s = vf_renderer_build_table_part(r->core, band, r->scratch[w->index], r->scratch_bytes);
        } else if (work->stage == STAGE_WARP) {
            uint32_t y0 = band * WARP_BAND, y1 = y0 + WARP_BAND < work->rows ? y0 + WARP_BAND : work->rows;
            s = vf_renderer_warp_band(r->core, work->image, y0, y1);
        } else {
            uint32_t v0 = band * r->band_rows, v1 = v0 + r->band_rows < work->rows ? v0 + r->band_rows : work->rows;
            s = vf_renderer_composite_band(r->core, v0, v1, r->scratch[w->index], r->scratch_bytes);
        }
        if (s != VF_OK) {
            int expected = VF_OK;
            atomic_compare_exchange_strong(&work->status, &expected, (int)s);
        }
    }
    return NULL;
}

static vf_status_t spread(vfp_render_t *r, band_work_t *work)
{
    atomic_init(&work->next_band, 0);
    atomic_init(&work->status, VF_OK);
    worker_t workers[VFP_MAX_THREADS];
    pthread_t ids[VFP_MAX_THREADS];
    int started = 0;
    for (int t = 1; t < r->threads; t++) {
        workers[t] = (worker_t){work, t};
        if (pthread_create(&ids[t], NULL, run_bands, &workers[t]) != 0)
            break; /* fewer threads is slower, not wrong */
        started = t;
    }
    workers[0] = (worker_t){work, 0};
    run_bands(&workers[0]);
    for (int t = 1; t <= started; t++)
        pthread_join(ids[t], NULL);
    return (vf_status_t)atomic_load(&work->status);
}
