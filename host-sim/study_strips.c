/* SPDX-License-Identifier: MIT */
/* study_strips.c: the precision study's image strips (PNG): the same view in each order and the truth; below,
 * each order's difference from the truth. */
#include <stdlib.h>
#include <string.h>

#include "io/pngio.h"
#include "study_report.h"

/* A run of this scene whose core image was kept (study_t.keep_images) with these rays, side-face rule, table size
 * and mode, everything else at the default. */
static const uint8_t *kept_image(const study_t *st, int scene, const vf_params_t *p)
{
    const vf_params_t def = study_default_params();
    for (int i = 0; i < st->run_count; i++) {
        const vf_params_t *q = &st->runs[i].params;
        if (st->runs[i].scene == scene && st->runs[i].rgb && q->mode == p->mode && q->rays == p->rays &&
            q->partial_slabs == p->partial_slabs && q->table_size == p->table_size && q->lookup == def.lookup &&
            q->table_bits == def.table_bits && q->correction == def.correction && q->sample_bits == def.sample_bits &&
            q->intermediate_bits == def.intermediate_bits && q->warp_bits == def.warp_bits)
            return st->runs[i].rgb;
    }
    return NULL;
}

vfp_status_t study_write_strip(study_t *st, int scene, const vf_params_t *base, const char *suffix, char *name,
                               size_t namelen, char *err, size_t errlen)
{
    const study_scene_t *sc = &st->scenes[scene];
    const uint32_t w = sc->size, cols = STUDY_MODES + 1;
    const size_t pixels = (size_t)w * w;
    const uint8_t *truth = study_truth(st, scene, err, errlen);
    uint8_t *strip = calloc((size_t)cols * w * 2 * w, 3), *img = malloc(pixels * 3);
    if (!truth || !strip || !img) {
        free(strip);
        free(img);
        if (truth)
            snprintf(err, errlen, "out of memory");
        return VFP_ERR;
    }
    for (uint32_t col = 0; col < cols; col++) {
        if (col < STUDY_MODES) {
            vf_params_t p = study_default_params();
            if (base) {
                p.rays = base->rays;
                p.partial_slabs = base->partial_slabs;
                p.table_size = base->table_size;
            }
            p.mode = (vf_mode_t)col;
            const uint8_t *kept = kept_image(st, scene, &p);
            if (kept)
                memcpy(img, kept, pixels * 3);
            else if (study_render_core(st, scene, &p, img, err, errlen)) {
                free(strip);
                free(img);
                return VFP_ERR;
            }
        } else {
            memcpy(img, truth, pixels * 3);
        }
        for (uint32_t y = 0; y < w; y++)
            for (uint32_t x = 0; x < w; x++) {
                uint8_t *top = strip + (((size_t)y * cols * w) + col * w + x) * 3;
                uint8_t *bottom = strip + (((size_t)(y + w) * cols * w) + col * w + x) * 3;
                const uint8_t *a = img + ((size_t)y * w + x) * 3, *t = truth + ((size_t)y * w + x) * 3;
                for (int c = 0; c < 3; c++) {
                    top[c] = a[c];
                    int diff = abs((int)a[c] - (int)t[c]) * 4;
                    bottom[c] = (uint8_t)(col < STUDY_MODES ? (diff > 255 ? 255 : diff) : 0);
                }
            }
    }
    snprintf(name, namelen, "strip-%s%s%s.png", sc->label, suffix ? "-" : "", suffix ? suffix : "");
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", st->dir, name);
    vfp_status_t status = vfp_png_write_rgb(path, strip, cols * w, 2 * w, err, errlen);
    free(strip);
    free(img);
    return status;
}
