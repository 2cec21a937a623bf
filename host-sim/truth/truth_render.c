/* truth_render.c: a whole truth image, its rows interleaved over threads (every pixel is independent). */
#include "truth/truth.h"

#include <pthread.h>
#include <stdlib.h>

#define MAX_THREADS 64

typedef struct job {
    const ref_volume_t *vol;
    const truth_tf_t *tf;
    const truth_camera_t *cam;
    const truth_opts_t *opts;
    const double *background;
    double *rgb;
    int first_row, row_step;
} job_t;

static void *render_rows(void *arg);

int truth_render_ex(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const double background[3],
                    const ref_view_t *view, int out_w, int out_h, int threads, const truth_opts_t *opts,
                    double *rgb)
{
    truth_opts_t defaults = TRUTH_OPTS_DEFAULT;
    truth_camera_t cam;
    if (!background || !rgb || threads < 1 || threads > MAX_THREADS ||
        (opts && !(opts->max_step > 0 && opts->scalar_tol > 0 && opts->steep >= 0)) ||
        truth_camera(vol, view, out_w, out_h, &cam))
        return -1;
    truth_tf_t *prepared = malloc(sizeof *prepared);
    if (!prepared || truth_tf_init(prepared, tf, npoints)) {
        free(prepared);
        return -1;
    }
    if (threads > out_h)
        threads = out_h;
    job_t jobs[MAX_THREADS];
    pthread_t ids[MAX_THREADS];
    int started = 0, status = 0;
    for (int n = 0; n < threads; n++) {
        /* interleaved rows: the expensive middle of the image is shared evenly */
        jobs[n] = (job_t){vol, prepared, &cam, opts ? opts : &defaults, background, rgb, n, threads};
        if (n > 0 && pthread_create(&ids[n], NULL, render_rows, &jobs[n]) != 0) {
            status = -1;
            break;
        }
        started = n + 1;
    }
    if (status == 0)
        render_rows(&jobs[0]);
    for (int n = 1; n < started; n++)
        pthread_join(ids[n], NULL);
    free(prepared);
    return status;
}

int truth_render(const ref_volume_t *vol, const ref_tf_point_t *tf, int npoints, const double background[3],
                 const ref_view_t *view, int out_w, int out_h, int threads, double *rgb)
{
    return truth_render_ex(vol, tf, npoints, background, view, out_w, out_h, threads, NULL, rgb);
}

static void *render_rows(void *arg)
{
    const job_t *j = arg;
    int w = j->cam->out_w;
    for (int py = j->first_row; py < j->cam->out_h; py += j->row_step)
        for (int px = 0; px < w; px++) {
            truth_acc_t acc;
            truth_trace(j->vol, j->tf, j->cam, j->opts, px, py, &acc);
            double *out = j->rgb + 3 * ((size_t)py * w + px);
            for (int c = 0; c < 3; c++)
                out[c] = acc.C[c] + acc.T * j->background[c];
        }
    return NULL;
}
