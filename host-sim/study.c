/* SPDX-License-Identifier: MIT */
/* study.c: running the precision study (see study.h). */
#include "study.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "io/pngio.h"

static vfp_status_t to_rgb(const vf_image_t *img, uint8_t **rgb)
{
    *rgb = malloc((size_t)img->width * img->height * 3);
    if (!*rgb)
        return VFP_ERR;
    vfp_image_to_rgb(img, *rgb);
    return VFP_OK;
}

vf_params_t study_default_params(void)
{
    vf_params_t p;
    vf_params_default(&p);
    return p;
}

/* The smaller tables first (the table dominates the memory), then the options that cost memory for accuracy. */
const study_mcu_candidate_t study_mcu_candidates[STUDY_MCU_CANDIDATES] = {
    {VF_MODE_PREINT1, 256, 16, 1, false}, {VF_MODE_PREINT1, 128, 16, 1, false}, {VF_MODE_PREINT1, 128, 8, 1, false},
    {VF_MODE_PREINT1, 64, 16, 1, false},  {VF_MODE_PREINT1, 64, 8, 1, false},   {VF_MODE_POINT, 256, 16, 1, false},
    {VF_MODE_PREINT1, 64, 16, 1, true},   {VF_MODE_PREINT1, 64, 16, 2, false},  {VF_MODE_PREINT1, 64, 8, 2, false},
    {VF_MODE_POINT, 256, 16, 2, false},
};

vf_params_t study_mcu_params(int k)
{
    vf_params_t p = study_default_params();
    const study_mcu_candidate_t *c = &study_mcu_candidates[k];
    p.mode = c->mode;
    p.table_size = c->table_size;
    p.table_bits = c->table_bits;
    p.rays = c->rays;
    p.partial_slabs = c->partial_slabs;
    return p;
}

int study_add_scene(study_t *st, const char *label, const char *volume, const char *preset, double azimuth,
                    double elevation, double zoom, uint32_t size, char *err, size_t errlen)
{
    if (st->scene_count >= STUDY_MAX_SCENES) {
        snprintf(err, errlen, "too many scenes (at most %d)", STUDY_MAX_SCENES);
        return -1;
    }
    study_scene_t *sc = &st->scenes[st->scene_count];
    memset(sc, 0, sizeof *sc);
    snprintf(sc->label, sizeof sc->label, "%s", label);
    snprintf(sc->volume, sizeof sc->volume, "%s", volume);
    snprintf(sc->preset, sizeof sc->preset, "%s", preset);
    sc->azimuth = azimuth;
    sc->elevation = elevation;
    sc->zoom = zoom;
    sc->size = size;
    char size_text[32];
    snprintf(size_text, sizeof size_text, "%ux%u", size, size);
    /* a preset name, or "file:PATH" for a transfer-function file */
    int is_file = strncmp(sc->preset, "file:", 5) == 0;
    /* unlit: the study measures the unlit algorithm, whatever a preset's own shading (study_lit.c lights its
     * scenes itself) */
    char *argv[] = {sc->volume, is_file ? "--tf" : "--preset", is_file ? sc->preset + 5 : sc->preset, "--size",
                    size_text, "--shade", "none"};
    sim_opts_t o;
    if (sim_parse(&o, 7, argv, SIM_OPT_SCENE, "")) {
        snprintf(err, errlen, "%s: bad scene", label);
        return -1;
    }
    o.azimuth = azimuth;
    o.elevation = elevation;
    o.zoom = zoom;
    o.threads = st->threads;
    if (sim_scene_load(&sc->scene, &o, err, errlen))
        return -1;
    return st->scene_count++;
}

const uint8_t *study_truth(study_t *st, int scene, char *err, size_t errlen)
{
    study_scene_t *sc = &st->scenes[scene];
    if (sc->truth)
        return sc->truth;
    vf_image_t img;
    double t0 = vfp_now_ms();
    if (sim_render_truth(&sc->scene, &img, err, errlen))
        return NULL;
    sc->truth_ms = vfp_now_ms() - t0;
    vfp_status_t status = to_rgb(&img, &sc->truth);
    sim_image_free(&img);
    if (status) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    return sc->truth;
}

/* The reference for the algorithm's options (mode, table size, lookup, correction, rays, partial slabs), at full
 * precision: the core's precision knobs, 8- to 12-bit tables included, are what the study measures against it. */
static const uint8_t *reference_for(study_t *st, int scene, const vf_params_t *p, char *err, size_t errlen)
{
    for (int i = 0; i < st->reference_count; i++) {
        study_reference_t *r = &st->references[i];
        if (r->scene == scene && r->mode == p->mode && r->table_size == p->table_size && r->lookup == p->lookup &&
            r->correction == p->correction && r->rays == p->rays && r->partial_slabs == p->partial_slabs)
            return r->rgb;
    }
    if (st->reference_count == STUDY_MAX_REFERENCES) {
        snprintf(err, errlen, "too many reference images");
        return NULL;
    }
    sim_scene_t s = st->scenes[scene].scene; /* a copy: only the parameters change */
    s.params = study_default_params();
    s.params.mode = p->mode;
    s.params.table_size = p->table_size;
    s.params.lookup = p->lookup;
    s.params.correction = p->correction;
    s.params.rays = p->rays;
    s.params.partial_slabs = p->partial_slabs;
    vf_factor_t factor; /* one ray per voxel column: the reference takes its slice offsets, which are in voxels */
    vf_status_t fs = vf_factor(&factor, &s.vol.core, &s.view, s.width, s.height);
    if (fs != VF_OK) {
        snprintf(err, errlen, "cannot factor the view: %s", vf_status_text(fs));
        return NULL;
    }
    vf_image_t img;
    if (sim_render_reference(&s, &factor, &img, err, errlen))
        return NULL;
    study_reference_t *r = &st->references[st->reference_count];
    r->scene = scene;
    r->mode = p->mode;
    r->table_size = p->table_size;
    r->lookup = p->lookup;
    r->correction = p->correction;
    r->rays = p->rays;
    r->partial_slabs = p->partial_slabs;
    vfp_status_t status = to_rgb(&img, &r->rgb);
    sim_image_free(&img);
    if (status) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    st->reference_count++;
    return r->rgb;
}

static int compare_ms(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* CPU time of the calling thread, ms: a one-thread frame runs on it (render_mt.c), and unlike the wall clock it
 * does not count the time other work on a shared machine takes the processor away. */
static double thread_cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static double median(double *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, compare_ms);
    return n % 2 ? x[n / 2] : (x[n / 2 - 1] + x[n / 2]) / 2;
}

/* Time st->time_frames more frames, each 2 degrees further round the vertical axis than the last (a turning
 * knob: the slab length changes, so every frame rebuilds the tables), and keep in the run the median CPU time of
 * a frame and the median wall-clock time of its table rebuild. */
static vfp_status_t time_frames(study_t *st, vfp_render_t *r, const vf_view_t *view, vf_image_t *img, study_run_t *run,
                                char *err, size_t errlen)
{
    enum { MOST = 15 };
    double total[MOST], tables[MOST];
    int n = st->time_frames < MOST ? st->time_frames : MOST;
    for (int i = 0; i < n; i++) {
        vf_view_t v = *view;
        v.azimuth += sim_bau(2.0 * (i + 1));
        double t0 = thread_cpu_ms();
        if (vfp_render_frame(r, &v, img, err, errlen))
            return VFP_ERR;
        total[i] = thread_cpu_ms() - t0;
        tables[i] = r->ms_tables;
    }
    if (n > 0) {
        run->frames_timed = n;
        run->frame_ms = median(total, n);
        run->frame_tables_ms = median(tables, n);
    }
    return VFP_OK;
}

/* Render with the core; memory, band scratch and frame times too when asked. */
static vfp_status_t render_core(study_t *st, int scene, const vf_params_t *params, uint8_t *rgb, study_run_t *run,
                                char *err, size_t errlen)
{
    const sim_scene_t *s = &st->scenes[scene].scene;
    vf_image_t img;
    vfp_render_t r;
    if (sim_image_alloc(&img, s->width, s->height, VF_FORMAT_RGB888)) {
        snprintf(err, errlen, "out of memory");
        return VFP_ERR;
    }
    vfp_status_t status = vfp_render_open(&r, params, &s->vol.core, 1, err, errlen);
    if (status == VFP_OK)
        status = vfp_render_set_window(&r, s->window, err, errlen);
    if (status == VFP_OK)
        status = vfp_render_set_tf(&r, s->points, s->npoints, err, errlen);
    if (status == VFP_OK && params->lighting) { /* the scene's lighting (study_lit.c's scenes) */
        vf_status_t ls = vf_renderer_set_lighting(r.core, &s->lighting);
        if (ls != VF_OK) {
            snprintf(err, errlen, "cannot light the frames: %s", vf_status_text(ls));
            status = VFP_ERR;
        }
    }
    double t0 = vfp_now_ms();
    if (status == VFP_OK)
        status = vfp_render_frame(&r, &s->view, &img, err, errlen);
    if (status == VFP_OK) {
        vfp_image_to_rgb(&img, rgb);
        if (run) {
            run->ms = vfp_now_ms() - t0;
            vf_renderer_memory(r.core, &run->memory);
            run->band_bytes = vf_renderer_band_scratch_bytes(r.core, 8);
            status = time_frames(st, &r, &s->view, &img, run, err, errlen);
        }
    }
    vfp_render_close(&r);
    sim_image_free(&img);
    return status;
}

vfp_status_t study_render_core(study_t *st, int scene, const vf_params_t *params, uint8_t *rgb, char *err,
                               size_t errlen)
{
    return render_core(st, scene, params, rgb, NULL, err, errlen);
}

vfp_status_t study_render_core_memory(study_t *st, int scene, const vf_params_t *params, uint8_t *rgb,
                                      vf_memory_t *memory, char *err, size_t errlen)
{
    study_run_t run;
    memset(&run, 0, sizeof run);
    const int frames = st->time_frames;
    st->time_frames = 0;
    vfp_status_t status = render_core(st, scene, params, rgb, &run, err, errlen);
    st->time_frames = frames;
    *memory = run.memory;
    return status;
}

void study_progress(study_t *st, const study_run_t *run)
{
    const study_scene_t *sc = &st->scenes[run->scene];
    double seconds = (vfp_now_ms() - st->started_ms) / 1000;
    char line[256];
    char truth[96] = "";
    if (run->vs_truth.pixels)
        snprintf(truth, sizeof truth, ", %.1f dB from the truth", run->vs_truth.psnr_db);
    if (run->instructions)
        snprintf(truth + strlen(truth), sizeof truth - strlen(truth), ", %.1f M instructions per frame",
                 run->instructions / 1e6);
    snprintf(line, sizeof line, "study: %d runs, %.0f s: %s %s %s = %s: %.1f dB from the reference%s", st->run_count,
             seconds, sc->label, vf_mode_name(run->params.mode), run->factor, run->value, run->vs_reference.psnr_db,
             truth);
    if (st->progress_tty)
        fprintf(stderr, "\r%-150.150s", line);
    else
        fprintf(stderr, "%s\n", line);
}

study_run_t *study_run(study_t *st, int scene, const vf_params_t *params, const char *factor, const char *value,
                       int with_truth, char *err, size_t errlen)
{
    if (st->run_count >= STUDY_MAX_RUNS) {
        snprintf(err, errlen, "too many runs");
        return NULL;
    }
    const study_scene_t *sc = &st->scenes[scene];
    const size_t pixels = (size_t)sc->size * sc->size;
    const uint8_t *truth = with_truth ? study_truth(st, scene, err, errlen) : NULL;
    if (with_truth && !truth)
        return NULL;
    const uint8_t *ref = reference_for(st, scene, params, err, errlen);
    if (!ref)
        return NULL;
    uint8_t *rgb = malloc(pixels * 3);
    if (!rgb) {
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    study_run_t *run = &st->runs[st->run_count];
    memset(run, 0, sizeof *run);
    run->scene = scene;
    run->params = *params;
    snprintf(run->factor, sizeof run->factor, "%s", factor);
    snprintf(run->value, sizeof run->value, "%s", value);
    if (render_core(st, scene, params, rgb, run, err, errlen)) {
        free(rgb);
        return NULL;
    }
    if (st->count_instructions)
        run->instructions = study_instructions(st, scene, params);
    sim_diff(rgb, ref, pixels, &run->vs_reference);
    if (truth)
        sim_diff(rgb, truth, pixels, &run->vs_truth);
    if (st->keep_images)
        run->rgb = rgb;
    else
        free(rgb);
    st->run_count++;
    study_progress(st, run);
    return run;
}

uint64_t study_instructions(study_t *st, int scene, const vf_params_t *p)
{
    if (st->have_valgrind < 0)
        st->have_valgrind = system("valgrind --version >/dev/null 2>&1") == 0;
    char self[1024];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (!st->have_valgrind || n <= 0)
        return 0;
    self[n] = 0;
    char out[] = "/tmp/volfix-study-callgrind-XXXXXX";
    int fd = mkstemp(out);
    if (fd < 0)
        return 0;
    close(fd);
    const study_scene_t *sc = &st->scenes[scene];
    const int is_file = strncmp(sc->preset, "file:", 5) == 0;
    char command[4096];
    snprintf(command, sizeof command,
             "valgrind --tool=callgrind --callgrind-out-file='%s' --toggle-collect=vfp_render_frame '%s' bench '%s' "
             "%s '%s' --view %g,%g --zoom %g --size %ux%u --mode %s --table-size %u --table-bits %u --lookup %s "
             "--correction %s --buffer %s --rays %u%s --frames 1 --rounds 1 >/dev/null 2>&1",
             out, self, sc->volume, is_file ? "--tf" : "--preset", is_file ? sc->preset + 5 : sc->preset, sc->azimuth,
             sc->elevation, sc->zoom, sc->size, sc->size, vf_mode_name(p->mode), p->table_size, p->table_bits,
             vf_lookup_name(p->lookup), vf_correction_name(p->correction), vf_buffer_name(p->buffer), p->rays,
             p->partial_slabs ? " --partial-slabs" : "");
    uint64_t total = 0;
    if (system(command) == 0) {
        FILE *f = fopen(out, "r");
        char line[512];
        unsigned long long summary = 0, totals = 0;
        while (f && fgets(line, sizeof line, f)) {
            if (sscanf(line, "summary: %llu", &summary) == 1)
                continue;
            sscanf(line, "totals: %llu", &totals);
        }
        if (f)
            fclose(f);
        total = (summary ? summary : totals) / 2;
    }
    unlink(out);
    return total;
}

void study_free(study_t *st)
{
    for (int i = 0; i < st->scene_count; i++) {
        free(st->scenes[i].truth);
        sim_scene_free(&st->scenes[i].scene);
    }
    for (int i = 0; i < st->reference_count; i++)
        free(st->references[i].rgb);
    for (int i = 0; i < st->run_count; i++)
        free(st->runs[i].rgb);
    st->reference_count = 0;
    st->scene_count = st->run_count = 0;
}
