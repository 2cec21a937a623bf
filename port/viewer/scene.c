/* SPDX-License-Identifier: MIT */
/* scene.c: bringing a renderer up to date with the controls, and rendering a frame of them (see viewer.h). */
#include "viewer.h"

#include <stdio.h>
#include <string.h>

void viewer_renderer_close(viewer_renderer_t *vr)
{
    if (vr->open)
        vfp_render_close(&vr->r);
    vr->open = 0;
}

uint32_t viewer_rays(const viewer_scene_t *scene, const vfp_volume_t *volume, int lit)
{
    /* previews stay at one ray: they are for speed */
    return volume == &scene->full ? vfp_sampling_choose(volume, scene->rays_given, lit).rays : 1;
}

int viewer_lighting(const viewer_scene_t *scene, const vfp_controls_t *c, vf_lighting_t *l)
{
    *l = scene->lighting[c->preset];
    if (c->shade >= 0)
        l->shade = c->shade != 0;
    l->lights[0] = (vf_light_t){vfp_degrees_to_bau(c->light_azimuth), vfp_degrees_to_bau(c->light_elevation)};
    return l->shade || l->gradient_hi > l->gradient_lo;
}

static int same_lighting(const vf_lighting_t *a, const vf_lighting_t *b)
{
    if (a->shade != b->shade || a->light_count != b->light_count || a->ka != b->ka || a->kd != b->kd ||
        a->ks != b->ks || a->shininess != b->shininess || a->gradient_lo != b->gradient_lo ||
        a->gradient_hi != b->gradient_hi)
        return 0;
    for (uint32_t k = 0; k < a->light_count && k < VF_MAX_LIGHTS; k++)
        if (a->lights[k].azimuth != b->lights[k].azimuth || a->lights[k].elevation != b->lights[k].elevation)
            return 0;
    return 1;
}

vfp_status_t viewer_sync(viewer_renderer_t *vr, const viewer_scene_t *scene, const vfp_volume_t *volume,
                         const vfp_controls_t *c, char *err, size_t errlen)
{
    vf_lighting_t lighting;
    const int lit = viewer_lighting(scene, c, &lighting);
    if (vr->open && (vr->volume != volume || vr->mode != c->mode || vr->lit != lit))
        viewer_renderer_close(vr);
    int fresh = !vr->open;
    if (fresh) {
        vf_params_t params = scene->params;
        params.mode = c->mode;
        params.lighting = lit != 0;
        params.rays = viewer_rays(scene, volume, lit);
        /* preint2's 3D table takes about 22 ms to rebuild at 64^3 (docs/performance.md), too long to wait for at
         * every turn of a knob: it is built once for d0 and corrected through the opacity lookup */
        if (params.mode == VF_MODE_PREINT2)
            params.correction = VF_CORRECTION_LUT;
        if (vfp_render_open(&vr->r, &params, &volume->core, scene->threads, err, errlen))
            return VFP_ERR;
        vr->open = 1;
        vr->volume = volume;
        vr->mode = c->mode;
        vr->lit = lit;
        /* The window is fixed for the session (the level and width knobs move the transfer function instead):
         * the slices are built once per renderer. */
        if (vfp_render_set_window(&vr->r, scene->window, err, errlen)) {
            viewer_renderer_close(vr);
            return VFP_ERR;
        }
    }
    int relight = lit && !same_lighting(&vr->lighting, &lighting);
    if (fresh || vr->preset != c->preset || vr->tf_shift != c->tf_shift || vr->tf_scale != c->tf_scale) {
        vfp_tf_t tf = scene->tfs[c->preset];
        vfp_tf_move(&tf, &scene->full, scene->window, c->tf_shift, c->tf_scale);
        vf_tf_point_t points[VF_MAX_TF_POINTS];
        uint32_t n = vfp_tf_to_core(&tf, &scene->full, scene->window, points);
        if (vfp_render_set_tf(&vr->r, points, n, err, errlen)) {
            viewer_renderer_close(vr); /* half applied: start again next time */
            return VFP_ERR;
        }
        vr->preset = c->preset;
        vr->tf_shift = c->tf_shift;
        vr->tf_scale = c->tf_scale;
        relight = lit; /* after the transfer function: a renderer made again for longer run lists starts with the
                        * default lighting */
    }
    if (relight) {
        vf_status_t ls = vf_renderer_set_lighting(vr->r.core, &lighting);
        if (ls != VF_OK) {
            snprintf(err, errlen, "cannot light the frames: %s", vf_status_text(ls));
            viewer_renderer_close(vr);
            return VFP_ERR;
        }
        vr->lighting = lighting;
    }
    return VFP_OK;
}

vfp_status_t viewer_render(viewer_renderer_t *vr, const vfp_controls_t *c, int rotation, const vf_image_t *image,
                           char *err, size_t errlen)
{
    vf_view_t view = vfp_controls_view(c, rotation);
    return vfp_render_frame(&vr->r, &view, image, err, errlen);
}
