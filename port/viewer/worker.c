/* SPDX-License-Identifier: MIT */
/* worker.c: the full-quality renderer's thread (see viewer.h). */
#include "viewer.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

/* The nice value of this thread, and so of the render pool it starts (threads inherit it): the full-quality
 * frame is background work, and where the board has no more cores than the preview's threads, a preview that
 * answers a knob while this renderer still works shares them with it. At 10 the kernel gives this thread about
 * a tenth of a core the preview wants (CFS weights 110 against 1024). */
#define BACKGROUND_NICE 10

static int outdated(viewer_worker_t *w, uint64_t gen)
{
    return atomic_load(&w->latest) != gen;
}

static vfp_status_t ensure_image(vf_image_t *img, uint32_t width, uint32_t height, vf_format_t format)
{
    if (img->pixels && img->width == width && img->height == height && img->format == format)
        return VFP_OK;
    vfp_image_free(img);
    return vfp_image_alloc(img, width, height, format);
}

static void *worker_main(void *arg)
{
    viewer_worker_t *w = arg;
    /* On Linux each thread has its own nice value, named by the thread's id; a failure leaves the full frame as
     * urgent as the preview: previews then answer more slowly, not wrongly */
    if (setpriority(PRIO_PROCESS, (id_t)syscall(SYS_gettid), BACKGROUND_NICE) != 0) {
        /* nothing to undo */
    }
    pthread_mutex_lock(&w->lock);
    for (;;) {
        while (!w->stop && !w->have_request)
            pthread_cond_wait(&w->cond, &w->lock);
        if (w->stop)
            break;
        vfp_controls_t c = w->request;
        uint64_t gen = w->request_gen;
        uint32_t width = w->request_width, height = w->request_height;
        vf_format_t format = w->request_format;
        w->have_request = 0;
        w->busy = 1;
        pthread_mutex_unlock(&w->lock);

        /* Work outside the lock; the image is ours until we post the result (the loop reads it only then). */
        char err[VIEWER_ERR_LEN] = "";
        double t0 = vfp_now_ms();
        vfp_status_t status = VFP_OK;
        int dropped = outdated(w, gen);
        if (!dropped)
            status = viewer_sync(&w->vr, w->scene, &w->scene->full, &c, err, sizeof err);
        dropped = dropped || outdated(w, gen); /* the classification stays: the next request may use it */
        if (!status && !dropped && ensure_image(&w->image, width, height, format)) {
            snprintf(err, sizeof err, "out of memory for a %ux%u frame", width, height);
            status = VFP_ERR;
        }
        if (!status && !dropped)
            status = viewer_render(&w->vr, &c, w->rotation, &w->image, err, sizeof err);

        pthread_mutex_lock(&w->lock);
        w->busy = 0;
        if (!dropped || status) {
            w->have_result = 1;
            w->result_gen = gen;
            w->result_ms = vfp_now_ms() - t0;
            w->result_status = status;
            memcpy(w->result_err, err, sizeof err);
        }
        /* Wake the loop either way: it may be waiting for the worker to be free. */
        char byte = 1;
        while (write(w->wake_fd[1], &byte, 1) < 0 && errno == EINTR)
            ;
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

vfp_status_t viewer_worker_start(viewer_worker_t *w, const viewer_scene_t *scene, int rotation, char *err,
                                 size_t errlen)
{
    memset(w, 0, sizeof *w);
    w->scene = scene;
    w->rotation = rotation;
    atomic_init(&w->latest, 0);
    if (pipe(w->wake_fd)) {
        snprintf(err, errlen, "cannot make a pipe for the renderer thread: %s", strerror(errno));
        return VFP_ERR;
    }
    pthread_mutex_init(&w->lock, NULL);
    pthread_cond_init(&w->cond, NULL);
    if (pthread_create(&w->thread, NULL, worker_main, w)) {
        snprintf(err, errlen, "cannot start the renderer thread");
        close(w->wake_fd[0]);
        close(w->wake_fd[1]);
        return VFP_ERR;
    }
    return VFP_OK;
}

void viewer_worker_request(viewer_worker_t *w, const vfp_controls_t *c, uint64_t gen, uint32_t width,
                           uint32_t height, vf_format_t format)
{
    pthread_mutex_lock(&w->lock);
    w->request = *c;
    w->request_gen = gen;
    w->request_width = width;
    w->request_height = height;
    w->request_format = format;
    w->have_result = 0; /* an older result is of no use now */
    w->have_request = 1;
    pthread_cond_signal(&w->cond);
    pthread_mutex_unlock(&w->lock);
}

void viewer_worker_stop(viewer_worker_t *w)
{
    pthread_mutex_lock(&w->lock);
    w->stop = 1;
    pthread_cond_signal(&w->cond);
    pthread_mutex_unlock(&w->lock);
    pthread_join(w->thread, NULL);
    viewer_renderer_close(&w->vr);
    vfp_image_free(&w->image);
    close(w->wake_fd[0]);
    close(w->wake_fd[1]);
    pthread_mutex_destroy(&w->lock);
    pthread_cond_destroy(&w->cond);
}
