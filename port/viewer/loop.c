/* SPDX-License-Identifier: MIT */
/* loop.c: the viewer's event loop (see viewer.h). */
#define _GNU_SOURCE /* ppoll, in glibc and musl */
#include "viewer.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include "display/overlay.h"

#define MAX_EVENTS 64
#define MAX_PENDING 4096        /* input events waiting for their frame, for the latency figures */
#define LATENCY_BINS 20000      /* the latency histogram: 0.1 ms bins up to 2 s, and one bin for longer */
#define LATENCY_BIN_MS 0.1
#define REOPEN_INTERVAL_MS 1000 /* how often a lost display is looked for */

typedef struct loop {
    viewer_t *v;
    vfp_display_t display;
    int display_open;
    uint64_t reopen_at;           /* when to look for a lost display again */
    vfp_input_t input;
    int input_open;
    vf_image_t clean, frame;      /* the last picture rendered, and it with the overlay */
    viewer_renderer_t fast;       /* the main thread's renderer: the preview volume (or the full one) */
    viewer_worker_t worker;
    int have_worker;
    uint64_t gen;                 /* bumped by every change of the controls */
    uint64_t shown_gen;           /* what the display shows */
    int shown_full;
    int clean_full;               /* clean holds a full-quality picture */
    double clean_ms;              /* and how long it took */
    uint64_t last_input;          /* when the controls last changed (0: never) */
    int need_fast, need_redraw, quitting;
    uint64_t pending[MAX_PENDING]; /* times of the changes not yet on the display */
    int npending;
    /* the session's figures */
    uint64_t started;
    unsigned frames, previews, fulls, dropped_fulls;
    /* Latency of every input event that changed something, kept in fixed memory (a board runs for days): a
     * histogram for the median and 95th percentile, and the exact worst. */
    uint32_t latency_bins[LATENCY_BINS + 1];
    uint64_t nlatency;
    double worst_latency;
} loop_t;

/* The one piece of process-wide state: what the SIGINT and SIGTERM handler leaves, the signal's number and a
 * byte in a pipe that wakes the loop's poll. */
static int signal_pipe[2] = {-1, -1};
static volatile sig_atomic_t signal_caught;

static void on_signal(int sig)
{
    int saved = errno;
    signal_caught = sig;
    char byte = 1;
    if (write(signal_pipe[1], &byte, 1) < 0) {
        /* a full pipe already holds a wake-up */
    }
    errno = saved;
}

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static void drain(int fd)
{
    char buf[64];
    while (read(fd, buf, sizeof buf) > 0)
        ;
}

static int set_nonblocking(int fd)
{
    int flags = fcntl(fd, F_GETFL);
    return flags < 0 ? -1 : fcntl(fd, F_SETFL, flags | O_NONBLOCK);
}

static const char *format_name(vf_format_t f)
{
    return f == VF_FORMAT_RGB565 ? "rgb565" : f == VF_FORMAT_XRGB8888 ? "xrgb8888" : "rgb888";
}

static double wrap360(double d)
{
    d = fmod(d, 360.0);
    return d < 0 ? d + 360.0 : d;
}

/* Resident memory now and at its peak so far, in KB (the long-run test reads them from the log); -1 where the
 * system does not say. */
static void memory_kb(long *rss, long *peak)
{
    *rss = *peak = -1;
    FILE *f = fopen("/proc/self/statm", "r");
    long pages_total, pages_resident;
    if (f && fscanf(f, "%ld %ld", &pages_total, &pages_resident) == 2)
        *rss = pages_resident * (sysconf(_SC_PAGESIZE) / 1024);
    if (f)
        fclose(f);
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) == 0)
        *peak = ru.ru_maxrss; /* KB on Linux */
}

/* One line of the log: the frame, and the volfix-sim render options that reproduce its pixels. Returns VFP_OK,
 * or VFP_ERR after printing an error when the line could not be written (a full disk ends the run: a log with
 * holes would not say what was shown). */
static vfp_status_t log_frame(loop_t *L, int full, double ms, double present_ms, double latency_ms)
{
    viewer_t *v = L->v;
    if (!v->log)
        return VFP_OK;
    const viewer_scene_t *s = &v->scene;
    const vfp_controls_t *c = &v->controls;
    double slope = s->full.slope != 0 ? s->full.slope : 1, inter = s->full.inter;
    fprintf(v->log, "frame %u %s render %.2f ms present %.2f ms latency ", L->frames - 1, full ? "full" : "preview",
            ms, present_ms);
    if (latency_ms >= 0)
        fprintf(v->log, "%.2f ms", latency_ms);
    else
        fprintf(v->log, "-");
    long rss_kb, peak_kb;
    memory_kb(&rss_kb, &peak_kb);
    fprintf(v->log, " rss %ld KB peak %ld KB", rss_kb, peak_kb);
    char lighting[256]; /* the frame's lighting (the transfer function's, the light and shade controls'), as
                         * volfix-sim's options give it */
    vf_params_t p = s->params;
    vf_lighting_t l;
    p.lighting = viewer_lighting(s, c, &l) != 0;
    vfp_lighting_args(&p, &l, lighting, sizeof lighting);
    fprintf(v->log, ": --view %.17g,%.17g,%.17g --zoom %.17g --tf-move %.17g,%.17g %s --mode %s%s --window %.17g,%.17g "
                    "--size %ux%u --format %s",
            c->azimuth, c->elevation, wrap360(c->roll - v->board.rotation), c->zoom, c->tf_shift, c->tf_scale,
            s->tf_args[c->preset], vf_mode_name(c->mode), lighting, s->window.lo * slope + inter,
            s->window.hi * slope + inter, L->frame.width, L->frame.height, format_name(L->frame.format));
    if (!full && s->preview_factor > 1)
        fprintf(v->log, " --downsample %d", s->preview_factor);
    /* the rays this frame had, whenever volfix-sim's own default could differ */
    const vfp_volume_t *vol = !full && s->preview_factor > 1 ? &s->preview : &s->full;
    vfp_sampling_t sampling = vfp_sampling_choose(&s->full, s->rays_given, p.lighting);
    uint32_t rays = viewer_rays(s, vol, p.lighting);
    if (rays > 1 || sampling.anisotropy >= VFP_ANISOTROPY_THRESHOLD)
        fprintf(v->log, " --rays %u", rays);
    fputc('\n', v->log);
    if (fflush(v->log) != 0 || ferror(v->log)) {
        fprintf(stderr, "volfix: %s: cannot write the log: %s\n", v->log_path, strerror(errno ? errno : EIO));
        return VFP_ERR;
    }
    return VFP_OK;
}

static void record_latencies(loop_t *L, uint64_t now, double *worst)
{
    *worst = -1;
    for (int i = 0; i < L->npending; i++) {
        double ms = (double)(now - L->pending[i]) / 1e6;
        *worst = ms > *worst ? ms : *worst;
        L->worst_latency = ms > L->worst_latency ? ms : L->worst_latency;
        double bin = ms / LATENCY_BIN_MS;
        L->latency_bins[bin < LATENCY_BINS ? (size_t)bin : LATENCY_BINS]++;
        L->nlatency++;
    }
    L->npending = 0;
}

/* The latency below which `share` of the events fall, to the histogram's 0.1 ms (the bin's upper edge). */
static double latency_quantile(const loop_t *L, double share)
{
    uint64_t want = (uint64_t)ceil(share * (double)L->nlatency), seen = 0;
    for (size_t b = 0; b < LATENCY_BINS; b++) {
        seen += L->latency_bins[b];
        if (seen >= want && want > 0)
            return (double)(b + 1) * LATENCY_BIN_MS < L->worst_latency ? (double)(b + 1) * LATENCY_BIN_MS
                                                                        : L->worst_latency;
    }
    return L->worst_latency;
}

static void display_lost(loop_t *L, const char *why)
{
    fprintf(stderr, "volfix: display %s lost (%s): looking for it every %d ms\n", L->v->board.display, why,
            REOPEN_INTERVAL_MS);
    L->v->display_ops->close(&L->display);
    L->display_open = 0;
    L->reopen_at = now_ns() + (uint64_t)REOPEN_INTERVAL_MS * 1000000u;
}

/* Draw the overlay on a copy of the clean picture and show it. Returns VFP_OK, or VFP_ERR after printing an error. */
static vfp_status_t present(loop_t *L, int full, double ms)
{
    viewer_t *v = L->v;
    memcpy(L->frame.pixels, L->clean.pixels, (size_t)L->clean.stride * L->clean.height);
    if (v->controls.overlay) {
        int rot = v->board.rotation, upright_w = rot % 180 ? (int)L->frame.height : (int)L->frame.width;
        int scale = upright_w >= 480 ? 2 : 1;
        char line1[64], line2[96];
        snprintf(line1, sizeof line1, "%s %.1f MS", full ? "FULL" : "PREVIEW", ms);
        snprintf(line2, sizeof line2, "%s %s", vf_mode_name(v->controls.mode),
                 v->scene.tfs[v->controls.preset].name);
        vfp_overlay_text(&L->frame, rot, 2 * scale, 2 * scale, scale, line1);
        vfp_overlay_text(&L->frame, rot, 2 * scale, 2 * scale + vfp_overlay_height(scale), scale, line2);
        /* on a board whose knobs cycle, what they do now */
        char line3[96] = "";
        size_t at = 0;
        for (int n = 0; n < v->board.knob_count && at < sizeof line3; n++)
            if (v->board.knobs[n].cycle_count > 1) {
                double step;
                at += (size_t)snprintf(line3 + at, sizeof line3 - at, "%s%d %s", at ? " " : "KNOB ", n,
                                       vfp_action_name(vfp_controls_knob_action(&v->controls, &v->board, n, &step)));
            }
        if (line3[0])
            vfp_overlay_text(&L->frame, rot, 2 * scale, 2 * scale + 2 * vfp_overlay_height(scale), scale, line3);
        if (v->scene.full.oriented) { /* the patient's directions, when the file gave them */
            const double view[3] = {v->controls.azimuth, v->controls.elevation, v->controls.roll};
            char right[4], left[4], top[4], bottom[4];
            vfp_view_edges(view, right, left, top, bottom);
            vfp_overlay_directions(&L->frame, rot, scale, right, left, top, bottom);
        }
    }
    char err[VIEWER_ERR_LEN] = "";
    uint64_t t0 = now_ns();
    vfp_status_t rc = v->display_ops->present(&L->display, 0, 0, L->frame.width, L->frame.height, L->frame.pixels,
                                              L->frame.stride, err, sizeof err);
    if (rc == VFP_DISPLAY_LOST) {
        display_lost(L, err[0] ? err : "gone");
        return VFP_OK;
    }
    if (rc) {
        fprintf(stderr, "volfix: %s\n", err);
        return VFP_ERR;
    }
    uint64_t now = now_ns();
    double worst;
    record_latencies(L, now, &worst);
    L->frames++;
    full ? L->fulls++ : L->previews++;
    L->shown_gen = L->gen;
    L->shown_full = full;
    return log_frame(L, full, ms, (double)(now - t0) / 1e6, worst);
}

/* Open the display and size the pictures to it. Returns VFP_OK, or VFP_ERR with err. */
static vfp_status_t open_display(loop_t *L, char *err, size_t errlen)
{
    viewer_t *v = L->v;
    memset(&L->display, 0, sizeof L->display);
    L->display.ops = v->display_ops;
    if (v->display_ops->open(&L->display, &v->board, err, errlen))
        return VFP_ERR;
    L->display_open = 1;
    if (L->display.width > VF_MAX_IMAGE || L->display.height > VF_MAX_IMAGE) {
        /* a display's own mode (drm, fbdev, gud) larger than the renderer draws: said now, not at the first frame */
        snprintf(err, errlen, "%s: display %s has a %ux%u mode; the renderer draws at most %dx%d", v->board.path,
                 v->board.display, L->display.width, L->display.height, VF_MAX_IMAGE, VF_MAX_IMAGE);
        v->display_ops->close(&L->display);
        L->display_open = 0;
        return VFP_ERR;
    }
    if (L->frame.pixels && L->frame.width == L->display.width && L->frame.height == L->display.height &&
        L->frame.format == L->display.format)
        return VFP_OK;
    vfp_image_free(&L->clean);
    vfp_image_free(&L->frame);
    if (vfp_image_alloc(&L->clean, L->display.width, L->display.height, L->display.format) ||
        vfp_image_alloc(&L->frame, L->display.width, L->display.height, L->display.format)) {
        snprintf(err, errlen, "out of memory for %ux%u frames", L->display.width, L->display.height);
        return VFP_ERR;
    }
    return VFP_OK;
}

static vfp_status_t render_fast(loop_t *L)
{
    viewer_t *v = L->v;
    const vfp_volume_t *vol = v->scene.preview_factor > 1 ? &v->scene.preview : &v->scene.full;
    char err[VIEWER_ERR_LEN];
    double t0 = vfp_now_ms();
    if (viewer_sync(&L->fast, &v->scene, vol, &v->controls, err, sizeof err) ||
        viewer_render(&L->fast, &v->controls, v->board.rotation, &L->clean, err, sizeof err)) {
        fprintf(stderr, "volfix: %s\n", err);
        return VFP_ERR;
    }
    L->clean_full = v->scene.preview_factor == 1;
    L->clean_ms = vfp_now_ms() - t0;
    L->need_fast = L->need_redraw = 0;
    return present(L, L->clean_full, L->clean_ms);
}

/* Take the worker's frame if it is of the current controls. Returns VFP_OK, or VFP_ERR after printing its error. */
static vfp_status_t take_full(loop_t *L)
{
    viewer_worker_t *w = &L->worker;
    vfp_status_t status = VFP_OK;
    int show = 0;
    double ms = 0;
    pthread_mutex_lock(&w->lock);
    if (w->have_result) {
        w->have_result = 0;
        if (w->result_status) {
            fprintf(stderr, "volfix: %s\n", w->result_err);
            status = VFP_ERR;
        } else if (w->result_gen == L->gen && L->display_open && w->image.width == L->clean.width &&
                   w->image.height == L->clean.height && w->image.format == L->clean.format) {
            memcpy(L->clean.pixels, w->image.pixels, (size_t)w->image.stride * w->image.height);
            ms = w->result_ms;
            show = 1;
        } else {
            L->dropped_fulls++;
        }
    }
    pthread_mutex_unlock(&w->lock);
    if (status || !show)
        return status;
    L->clean_full = 1;
    L->clean_ms = ms;
    return present(L, 1, ms);
}

static int worker_free(loop_t *L)
{
    pthread_mutex_lock(&L->worker.lock);
    int free_ = !L->worker.busy && !L->worker.have_request && !L->worker.have_result;
    pthread_mutex_unlock(&L->worker.lock);
    return free_;
}

/* Does the display still lack the full-quality picture of the current controls? */
static int full_wanted(const loop_t *L)
{
    return L->have_worker && L->display_open && !(L->shown_full && L->shown_gen == L->gen);
}

static void apply_events(loop_t *L, const vfp_event_t *ev, int n)
{
    viewer_t *v = L->v;
    for (int i = 0; i < n; i++) {
        unsigned changed = vfp_controls_apply(&v->controls, &v->home, &v->board, &ev[i]);
        vf_lighting_t lighting;
        viewer_lighting(&v->scene, &v->controls, &lighting);
        v->controls.shade_now = lighting.shade; /* what the next shade button press turns over */
        if (changed & VFP_CHANGED_QUIT) {
            L->quitting = 1;
            continue;
        }
        if (!changed)
            continue;
        if (changed & (VFP_CHANGED_VIEW | VFP_CHANGED_TF | VFP_CHANGED_MODE | VFP_CHANGED_LIGHT)) {
            L->gen++;
            atomic_store(&L->worker.latest, L->gen);
            L->need_fast = 1;
        }
        if (changed == VFP_CHANGED_KNOBS && !v->controls.overlay)
            continue; /* what the knobs do shows on the overlay only */
        L->need_redraw = 1; /* the overlay alone, or with the rest */
        L->last_input = now_ns();
        if (L->npending < MAX_PENDING)
            L->pending[L->npending++] = ev[i].time_ns ? ev[i].time_ns : L->last_input;
    }
}

static void summary(loop_t *L)
{
    double secs = (double)(now_ns() - L->started) / 1e9;
    printf("volfix: %u frames (%u previews, %u full quality) in %.2f s", L->frames, L->previews, L->fulls, secs);
    if (L->nlatency) {
        printf("; input-to-frame latency over %llu inputs: median %.1f ms, 95th percentile %.1f ms, worst %.1f ms",
               (unsigned long long)L->nlatency, latency_quantile(L, 0.5), latency_quantile(L, 0.95),
               L->worst_latency);
    }
    printf("\n");
}

vfp_status_t viewer_signals_catch(char *err, size_t errlen)
{
    if (pipe(signal_pipe) || set_nonblocking(signal_pipe[0]) || set_nonblocking(signal_pipe[1])) {
        snprintf(err, errlen, "cannot make a pipe for signals: %s", strerror(errno));
        return VFP_ERR;
    }
    /* no SA_RESTART: a read that waits (a FIFO with no writer yet) returns EINTR, and the caller stops */
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN); /* a display over a socket or pipe that went away is an error, not a death */
    return VFP_OK;
}

int viewer_signal_caught(void)
{
    return signal_caught;
}

void viewer_signals_release(void)
{
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    for (int i = 0; i < 2; i++)
        if (signal_pipe[i] >= 0) {
            close(signal_pipe[i]);
            signal_pipe[i] = -1;
        }
}

static vfp_status_t setup(loop_t *L, char *err, size_t errlen)
{
    viewer_t *v = L->v;
    L->input.ops = v->input_ops;
    if (v->input_ops->open(&L->input, &v->board, v->script, err, errlen))
        return VFP_ERR;
    L->input_open = 1;
    if (open_display(L, err, errlen))
        return VFP_ERR;
    if (v->scene.preview_factor > 1) {
        if (viewer_worker_start(&L->worker, &v->scene, v->board.rotation, err, errlen))
            return VFP_ERR;
        set_nonblocking(L->worker.wake_fd[0]);
        L->have_worker = 1;
    }
    return VFP_OK;
}

static void teardown(loop_t *L)
{
    viewer_t *v = L->v;
    if (L->have_worker)
        viewer_worker_stop(&L->worker);
    viewer_renderer_close(&L->fast);
    if (L->display_open)
        v->display_ops->close(&L->display); /* gives the display back: a DRM CRTC as it was found */
    if (L->input_open)
        v->input_ops->close(&L->input);
    vfp_image_free(&L->clean);
    vfp_image_free(&L->frame);
}

/* The earliest of the deadlines, as a ppoll timeout (NULL: none). To the nanosecond rather than poll's
 * millisecond, which rounded up would wake the loop up to 1 ms after a scripted event is due, and that wait
 * counts in its latency. */
static const struct timespec *timeout_at(uint64_t now, const uint64_t *deadlines, int n, struct timespec *ts)
{
    uint64_t first = 0;
    for (int i = 0; i < n; i++)
        if (deadlines[i] && (!first || deadlines[i] < first))
            first = deadlines[i];
    if (!first)
        return NULL;
    uint64_t wait = first <= now ? 0 : first - now;
    if (wait > UINT64_C(60000000000))
        wait = UINT64_C(60000000000);
    ts->tv_sec = (time_t)(wait / 1000000000u);
    ts->tv_nsec = (long)(wait % 1000000000u);
    return ts;
}

vfp_status_t viewer_loop(viewer_t *v)
{
    loop_t L;
    memset(&L, 0, sizeof L);
    L.v = v;
    L.started = now_ns();
    L.need_fast = 1;
    L.gen = 1;
    char err[VIEWER_ERR_LEN] = "";
    vfp_status_t status = setup(&L, err, sizeof err);
    if (status) {
        fprintf(stderr, "volfix: %s\n", err);
        teardown(&L);
        return VFP_ERR;
    }
    const uint32_t *d = v->scene.full.core.dims;
    char aniso[96] = ""; /* lit frames keep one ray unless --rays says otherwise (render/sampling.h) */
    vfp_sampling_t sampling = vfp_sampling_choose(&v->scene.full, v->scene.rays_given, 0);
    if (sampling.anisotropy >= VFP_ANISOTROPY_THRESHOLD && !sampling.rays_given)
        snprintf(aniso, sizeof aniso, "; anisotropic spacing %.2fx: unlit full-quality frames at %u rays a side",
                 sampling.anisotropy, sampling.rays);
    printf("volfix: %s (%ux%ux%u) on %s: display %s %ux%u, input %s, %d threads, preview %s%s\n", v->volume_arg,
           d[0], d[1], d[2], v->board.name, v->board.display, L.display.width, L.display.height,
           v->script ? "script" : v->board.input, v->scene.threads, v->scene.preview_factor > 1 ? "on" : "off", aniso);
    fflush(stdout);
    atomic_store(&L.worker.latest, L.gen);
    uint64_t idle_ns = (uint64_t)v->board.idle_ms * 1000000u;
    int readable = 1, stop = signal_caught != 0;
    while (!stop && !status) {
        uint64_t now = now_ns();
        /* Input first, all of it: one frame answers every event that arrived meanwhile. */
        uint64_t input_deadline = v->input_ops->deadline_ns(&L.input);
        if (readable || (input_deadline && input_deadline <= now)) {
            vfp_event_t ev[MAX_EVENTS];
            int n;
            do {
                n = v->input_ops->read(&L.input, ev, MAX_EVENTS, now, err, sizeof err);
                if (n < 0) {
                    fprintf(stderr, "volfix: %s\n", err);
                    status = VFP_ERR;
                    break;
                }
                apply_events(&L, ev, n);
            } while (n == MAX_EVENTS && !signal_caught); /* a device that floods does not hold off a signal */
        }
        if (status)
            break;
        if (!L.display_open && now >= L.reopen_at) {
            if (open_display(&L, err, sizeof err) == VFP_OK) {
                fprintf(stderr, "volfix: display %s is back\n", v->board.display);
                L.need_fast = 1;
            } else {
                L.display_open = 0;
                L.reopen_at = now + (uint64_t)REOPEN_INTERVAL_MS * 1000000u;
            }
        }
        if (L.have_worker)
            status = take_full(&L);
        if (!status && L.display_open && L.need_fast)
            status = render_fast(&L);
        else if (!status && L.display_open && L.need_redraw)
            status = (L.need_redraw = 0, present(&L, L.clean_full, L.clean_ms));
        if (status)
            break;

        /* Full quality once the knobs rest (at once when quitting: the last picture is the best one). */
        now = now_ns();
        uint64_t full_at = 0;
        if (full_wanted(&L) && worker_free(&L)) {
            full_at = L.quitting || !L.last_input ? now : L.last_input + idle_ns;
            if (full_at <= now) {
                viewer_worker_request(&L.worker, &v->controls, L.gen, L.clean.width, L.clean.height, L.clean.format);
                full_at = 0;
            }
        }
        if (L.quitting && !(full_wanted(&L)))
            break;
        if (v->max_frames && L.frames >= v->max_frames)
            break;
        /* With --frames, an input that has nothing more to give (a script played to its end without "quit": no
         * fd to poll, no deadline) ends the run once its last picture is on the display at full quality, rather
         * than waiting for frames that will never come. */
        if (v->max_frames && v->input_ops->fd(&L.input) < 0 && !v->input_ops->deadline_ns(&L.input) &&
            L.display_open && !L.need_fast && !L.need_redraw && !full_wanted(&L) &&
            (!L.have_worker || worker_free(&L)))
            break;
        if (signal_caught)
            break;

        struct pollfd fds[3];
        int nfds = 0, in_fd = v->input_ops->fd(&L.input);
        fds[nfds++] = (struct pollfd){.fd = signal_pipe[0], .events = POLLIN};
        fds[nfds++] = (struct pollfd){.fd = L.have_worker ? L.worker.wake_fd[0] : -1, .events = POLLIN};
        fds[nfds++] = (struct pollfd){.fd = in_fd, .events = POLLIN};
        uint64_t deadlines[3] = {v->input_ops->deadline_ns(&L.input), full_at, L.display_open ? 0 : L.reopen_at};
        struct timespec ts;
        int rc = ppoll(fds, (nfds_t)nfds, timeout_at(now_ns(), deadlines, 3, &ts), NULL);
        if (rc < 0 && errno != EINTR) {
            fprintf(stderr, "volfix: poll: %s\n", strerror(errno));
            status = VFP_ERR;
            break;
        }
        if (rc > 0 && (fds[0].revents & POLLIN)) {
            drain(signal_pipe[0]);
            stop = 1; /* SIGINT or SIGTERM: leave now, giving the display back */
        }
        if (rc > 0 && (fds[1].revents & POLLIN))
            drain(L.worker.wake_fd[0]);
        readable = rc > 0 && (fds[2].revents & (POLLIN | POLLHUP | POLLERR));
    }
    summary(&L);
    teardown(&L);
    return status;
}
