/* SPDX-License-Identifier: MIT */
/* study_results.c: the study's results looked up for its writers: runs by scene, factor and value, what a run
 * cost, the scenes' magnification, and the numbers the claims rest on (see study_report.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "study_report.h"

FILE *study_open_file(const study_t *st, const char *name, char *err, size_t errlen)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", st->dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        snprintf(err, errlen, "%s: cannot write", path);
    return f;
}

const study_run_t *study_find(const study_t *st, const char *scene, const char *factor, const char *value)
{
    for (int i = 0; i < st->run_count; i++) {
        const study_run_t *r = &st->runs[i];
        if (strcmp(st->scenes[r->scene].label, scene) == 0 && strcmp(r->factor, factor) == 0 &&
            strcmp(r->value, value) == 0)
            return r;
    }
    return NULL;
}

const study_run_t *study_find_mode(const study_t *st, const char *scene, const char *factor, const char *value,
                                   vf_mode_t mode)
{
    for (int i = 0; i < st->run_count; i++) {
        const study_run_t *r = &st->runs[i];
        if (r->params.mode == mode && strcmp(st->scenes[r->scene].label, scene) == 0 &&
            strcmp(r->factor, factor) == 0 && strcmp(r->value, value) == 0)
            return r;
    }
    return NULL;
}

const study_run_t *study_find_rays(const study_t *st, const char *scene, int partial, unsigned table_size,
                                   unsigned rays, vf_mode_t mode)
{
    char factor[32], value[16];
    snprintf(factor, sizeof factor, "rays_%s_%u", partial ? "partial" : "whole", table_size);
    snprintf(value, sizeof value, "%u", rays);
    return study_find_mode(st, scene, factor, value, mode);
}

double study_run_kb(const study_run_t *r)
{
    return (r->memory.total + r->band_bytes) / 1024.0;
}

double study_frame_ms(const study_run_t *r)
{
    return r->frames_timed ? r->frame_ms : r->ms;
}

const char *study_minstr(const study_run_t *r, char *text, size_t len)
{
    if (r && r->instructions)
        snprintf(text, len, "%.1f", r->instructions / 1e6);
    else
        snprintf(text, len, "-");
    return text;
}

int study_is_rays_factor(const char *factor)
{
    return strncmp(factor, "rays_", 5) == 0;
}

double study_pixels_per_voxel(const study_scene_t *sc)
{
    const vf_volume_t *v = &sc->scene.vol.core;
    double least = v->spacing_q16[0], diag = 0;
    for (int a = 1; a < 3; a++)
        least = v->spacing_q16[a] < least ? v->spacing_q16[a] : least;
    for (int a = 0; a < 3; a++) {
        double side = (v->dims[a] - 1) * (v->spacing_q16[a] / least);
        diag += side * side;
    }
    return sc->zoom * sc->size / sqrt(diag);
}

int study_scene_index(const study_t *st, const char *label)
{
    for (int s = 0; s < st->scene_count; s++)
        if (strcmp(st->scenes[s].label, label) == 0)
            return s;
    return -1;
}

int study_scenes_with(const study_t *st, const char *factor, int *which, int most)
{
    int count = 0;
    for (int s = 0; s < st->scene_count && count < most; s++)
        for (int i = 0; i < st->run_count; i++)
            if (st->runs[i].scene == s && strcmp(st->runs[i].factor, factor) == 0) {
                which[count++] = s;
                break;
            }
    return count;
}

study_claims_t study_claims(const study_t *st)
{
    study_claims_t c;
    memset(&c, 0, sizeof c);
    c.fixed_min_psnr = 99;
    const study_run_t *cube = study_find(st, "cube24", "order", "preint1");
    c.cube_db = cube ? cube->vs_truth.psnr_db : 0;
    const study_run_t *pre = study_find(st, "ml41-sharp", "order", "preint1");
    const study_run_t *pt = study_find(st, "ml41-sharp", "order", "point");
    if (pre && pt) {
        c.preint1_truth_db = pre->vs_truth.psnr_db;
        c.point_truth_db = pt->vs_truth.psnr_db;
        c.gain_db = c.preint1_truth_db - c.point_truth_db;
    }
    pre = study_find(st, "ml41-sharp-interior", "order", "preint1");
    pt = study_find(st, "ml41-sharp-interior", "order", "point");
    if (pre && pt) {
        c.inside_preint1_db = pre->vs_truth.psnr_db;
        c.inside_point_db = pt->vs_truth.psnr_db;
        c.inside_gain_db = c.inside_preint1_db - c.inside_point_db;
    }
    const study_run_t *cp = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, STUDY_CLAIM_RAYS, VF_MODE_POINT);
    const study_run_t *c1 = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, STUDY_CLAIM_RAYS, VF_MODE_PREINT1);
    const study_run_t *cc = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, STUDY_CLAIM_RAYS, VF_MODE_PRECLASS);
    if (cp && c1) {
        c.have_claim = 1;
        c.claim_point_db = cp->vs_truth.psnr_db;
        c.claim_preint1_db = c1->vs_truth.psnr_db;
        c.claim_preclass_db = cc ? cc->vs_truth.psnr_db : 0;
        c.claim_gain_db = c.claim_preint1_db - c.claim_point_db;
        c.claim_max_ref = cp->vs_reference.max_abs[3] > c1->vs_reference.max_abs[3] ? cp->vs_reference.max_abs[3]
                                                                                   : c1->vs_reference.max_abs[3];
    }
    cp = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, 8, VF_MODE_POINT);
    c1 = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, 8, VF_MODE_PREINT1);
    if (cp && c1) {
        c.have_r8 = 1;
        c.r8_point_db = cp->vs_truth.psnr_db;
        c.r8_preint1_db = c1->vs_truth.psnr_db;
        c.r8_gain_db = c.r8_preint1_db - c.r8_point_db;
    }
    c.rays_min_psnr = 99;
    for (int i = 0; i < st->run_count; i++) {
        const study_run_t *r = &st->runs[i];
        if (!study_is_rays_factor(r->factor) || strcmp(st->scenes[r->scene].label, "ml41-sharp") != 0)
            continue;
        c.rays_runs++;
        c.rays_max_ref = r->vs_reference.max_abs[3] > c.rays_max_ref ? r->vs_reference.max_abs[3] : c.rays_max_ref;
        c.rays_min_psnr = r->vs_reference.psnr_db < c.rays_min_psnr ? r->vs_reference.psnr_db : c.rays_min_psnr;
    }
    for (int i = 0; i < st->run_count; i++) {
        const study_run_t *r = &st->runs[i];
        if (strcmp(r->factor, "fixed_point") != 0)
            continue;
        c.fixed_cases++;
        c.fixed_max = r->vs_reference.max_abs[3] > c.fixed_max ? r->vs_reference.max_abs[3] : c.fixed_max;
        c.fixed_min_psnr = r->vs_reference.psnr_db < c.fixed_min_psnr ? r->vs_reference.psnr_db : c.fixed_min_psnr;
    }
    return c;
}
