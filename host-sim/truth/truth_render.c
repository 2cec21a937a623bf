/* SPDX-License-Identifier: MIT */
/* truth_render.c: rows of rays interleaved over threads (every ray is independent), and a whole truth image. */
#include "truth/truth.h"

#include <pthread.h>
#include <stdlib.h>

typedef struct job {
    const ref_volume_t *vol;
    const truth_tf_t *tf;
    const truth_camera_t *cam;
    const truth_opts_t *opts;
    const truth_lit_t *lit; /* NULL: unlit */
    const double *background;
    double *rgb;
} job_t;

typedef struct rows_job {
    void (*row)(const void *ctx, int y);
    const void *ctx;
    int rows, first_row, row_step;
} rows_job_t;

static void *run_rows(void *arg)
{
    const rows_job_t *j = arg;
    for (int y = j->first_row; y < j->rows; y += j->row_step)
        j->row(j->ctx, y);
    return NULL;
}

void truth_rows(int rows, int threads, void (*row)(const void *ctx, int y), const void *ctx)
{
    threads = threads < 1 ? 1 : threads > TRUTH_MAX_THREADS ? TRUTH_MAX_THREADS : threads;
    if (threads > rows)
        threads = rows > 0 ? rows : 1;
    rows_job_t jobs[TRUTH_MAX_THREADS];
    pthread_t ids[TRUTH_MAX_THREADS];
    int started = 1;
    for (int n = 0; n < threads; n++) {
        jobs[n] = (rows_job_t){row, ctx, rows, n, threads};
        if (n > 0 && started == n && pthread_create(&ids[n], NULL, run_rows, &jobs[n]) == 0)
            started = n + 1;
    }
    run_rows(&jobs[0]);
    for (int n = 1; n < started; n++)
        pthread_join(ids[n], NULL);
    for (int n = started; n < threads; n++) /* the rows of threads that could not start */
        run_rows(&jobs[n]);
}

static void render_row(const void *ctx, int py)
{
    const job_t *j = ctx;
    int w = j->cam->out_w;
    for (int px = 0; px < w; px++) {
        truth_acc_t acc;
        truth_trace_lit(j->vol, j->tf, j->cam, j->opts, j->lit, px, py, &acc);
        double *out = j->rgb + 3 * ((size_t)py * w + px);
        for (int c = 0; c < 3; c++)
            out[c] = acc.C[c] + acc.T * j->background[c];
    }
}

int truth_render_ex(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const double background[3],
                    const ref_view_t *view, int out_w, int out_h, int threads, const truth_opts_t *opts,
                    double *rgb)
{
    return truth_render_lit(vol, tf, npoints, background, view, out_w, out_h, threads, opts, NULL, rgb);
}

int truth_render_lit(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const double background[3],
                     const ref_view_t *view, int out_w, int out_h, int threads, const truth_opts_t *opts,
                     const ref_lighting_t *lighting, double *rgb)
{
    truth_opts_t defaults = TRUTH_OPTS_DEFAULT;
    truth_camera_t cam;
    truth_lit_t lit;
    if (!background || !rgb || threads < 1 || threads > TRUTH_MAX_THREADS ||
        (opts && !(opts->max_step > 0 && opts->scalar_tol > 0 && opts->steep >= 0)) ||
        truth_camera(vol, view, out_w, out_h, &cam) || (lighting && truth_lit_init(&lit, vol, &cam, lighting)) ||
        (lighting && opts && opts->field && opts->field->filter != TRUTH_FILTER_TRILINEAR) ||
        (opts && opts->field && opts->field->vol != vol))
        return -1;
    truth_tf_t *prepared = malloc(sizeof *prepared);
    if (!prepared || truth_tf_init(prepared, tf, npoints)) {
        free(prepared);
        return -1;
    }
    const job_t job = {vol, prepared, &cam, opts ? opts : &defaults, lighting ? &lit : NULL, background, rgb};
    truth_rows(out_h, threads, render_row, &job);
    free(prepared);
    return 0;
}

int truth_render(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const double background[3],
                 const ref_view_t *view, int out_w, int out_h, int threads, double *rgb)
{
    return truth_render_ex(vol, tf, npoints, background, view, out_w, out_h, threads, NULL, rgb);
}
