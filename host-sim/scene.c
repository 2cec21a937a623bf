/* SPDX-License-Identifier: MIT */
/* scene.c: load a scene and render it with the core or the reference (see scene.h). */
#include "scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "truth/truth.h"

int32_t sim_bau(double degrees)
{
    return (int32_t)lround(degrees * VF_BAU_PER_TURN / 360.0);
}

vf_view_t sim_view(double azimuth, double elevation, double roll, double zoom)
{
    vf_view_t v = {sim_bau(azimuth), sim_bau(elevation), sim_bau(roll), (uint32_t)lround(zoom * 65536)};
    return v;
}

vfp_status_t sim_scene_command(sim_opts_t *opts, sim_scene_t *scene, int argc, char **argv, unsigned groups,
                               const char *usage_head)
{
    char usage[8192], err[VFP_ERR_LEN];
    snprintf(usage, sizeof usage, "%s%s", usage_head, sim_scene_help);
    vfp_status_t status = sim_parse(opts, argc, argv, SIM_OPT_SCENE | groups, usage);
    if (status == VFP_OK)
        status = sim_check_options(opts, SIM_OPT_SCENE | groups);
    if (status == VFP_OK && (status = sim_scene_load(scene, opts, err, sizeof err)) != VFP_OK)
        fprintf(stderr, "volfix-sim: %s\n", err);
    return status;
}

vfp_status_t sim_scene_load(sim_scene_t *s, const sim_opts_t *o, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    /* the transfer function first: a mistake in it is found before a large volume is read */
    vfp_status_t status = o->tf_file ? vfp_tf_load(&s->tf, o->tf_file, err, errlen)
                                     : vfp_tf_preset(&s->tf, o->preset ? o->preset : "ramp", err, errlen);
    if (status)
        return VFP_ERR;
    if (vfp_volume_load(&s->vol, o->volume, &o->load, err, errlen))
        return VFP_ERR;
    s->window = vfp_default_window(&s->vol);
    if (o->window && vfp_parse_window(&s->vol, o->window, &s->window, err, errlen)) {
        vfp_volume_free(&s->vol);
        return VFP_ERR;
    }
    if (o->tf_shift != 0 || o->tf_scale != 1)
        vfp_tf_move(&s->tf, &s->vol, s->window, o->tf_shift, o->tf_scale);
    s->npoints = vfp_tf_to_core(&s->tf, &s->vol, s->window, s->points);
    s->params = o->params;
    /* with partial slabs the transfer function's own shading gives way (lighting does not go with them, and
     * options that ask for it were refused by sim_parse) */
    vfp_lighting_resolve(&o->lighting, o->params.partial_slabs ? NULL : &s->tf, &s->params, &s->lighting);
    s->sampling = vfp_sampling_choose(&s->vol, o->rays_given ? o->params.rays : 0, s->params.lighting);
    s->params.rays = s->sampling.rays;
    s->view = sim_view(o->azimuth, o->elevation, o->roll, o->zoom);
    s->width = o->width;
    s->height = o->height;
    s->format = o->format;
    s->threads = o->threads;
    s->truth_filter = o->truth_filter;
    return VFP_OK;
}

void sim_scene_free(sim_scene_t *s)
{
    vfp_volume_free(&s->vol);
    memset(s, 0, sizeof *s);
}

vfp_status_t sim_image_alloc(vf_image_t *img, uint32_t width, uint32_t height, vf_format_t format)
{
    return vfp_image_alloc(img, width, height, format);
}

void sim_image_free(vf_image_t *img)
{
    vfp_image_free(img);
}

vfp_status_t sim_core_lighting(const sim_scene_t *s, vf_renderer_t *core, char *err, size_t errlen)
{
    if (!s->params.lighting)
        return VFP_OK;
    vf_status_t status = vf_renderer_set_lighting(core, &s->lighting);
    if (status != VF_OK) {
        snprintf(err, errlen, "cannot light the frames: %s", vf_status_text(status));
        return VFP_ERR;
    }
    return VFP_OK;
}

vfp_status_t sim_render_core(const sim_scene_t *s, vf_image_t *img, vf_factor_t *factor, char *err, size_t errlen)
{
    vfp_render_t r;
    if (sim_image_alloc(img, s->width, s->height, s->format)) {
        snprintf(err, errlen, "out of memory for a %ux%u image", s->width, s->height);
        return VFP_ERR;
    }
    vfp_status_t status = vfp_render_open(&r, &s->params, &s->vol.core, s->threads, err, errlen);
    if (status == VFP_OK)
        status = vfp_render_set_window(&r, s->window, err, errlen);
    if (status == VFP_OK)
        status = vfp_render_set_tf(&r, s->points, s->npoints, err, errlen);
    if (status == VFP_OK)
        status = sim_core_lighting(s, r.core, err, errlen);
    if (status == VFP_OK)
        status = vfp_render_frame(&r, &s->view, img, err, errlen);
    if (status == VFP_OK && factor)
        *factor = *vf_renderer_factor(r.core);
    vfp_render_close(&r);
    if (status)
        sim_image_free(img);
    return status;
}

/* The reference and the truth get the same inputs the core gets: the spacing, view and transfer function as
 * quantised for the core, and they window the raw voxels themselves. */
vfp_status_t sim_ref_inputs(const sim_scene_t *s, sim_ref_inputs_t *in)
{
    const vf_volume_t *cv = &s->vol.core;
    int dims[3] = {(int)cv->dims[0], (int)cv->dims[1], (int)cv->dims[2]};
    in->scalars = malloc((size_t)dims[0] * dims[1] * dims[2]);
    if (!in->scalars)
        return VFP_ERR;
    ref_window(cv->voxels, (int)cv->type, dims, s->window.lo, s->window.hi, in->scalars);
    in->vol = (ref_volume_t){{dims[0], dims[1], dims[2]},
                             {cv->spacing_q16[0] / 65536.0, cv->spacing_q16[1] / 65536.0, cv->spacing_q16[2] / 65536.0},
                             in->scalars};
    for (uint32_t i = 0; i < s->npoints; i++)
        in->tf[i] = (ref_tf_point_t){s->points[i].scalar_q8 / 256.0, s->points[i].r / 65535.0,
                                     s->points[i].g / 65535.0, s->points[i].b / 65535.0, s->points[i].a / 65535.0};
    in->npoints = (int)s->npoints;
    in->view = (ref_view_t){s->view.azimuth, s->view.elevation, s->view.roll, s->view.zoom_q16 / 65536.0};
    for (int c = 0; c < 3; c++)
        in->background[c] = s->params.background[c] / 65535.0;
    return VFP_OK;
}

void sim_ref_inputs_free(sim_ref_inputs_t *in)
{
    free(in->scalars);
    in->scalars = NULL;
}

/* Colours in [0, 1] rounded into the output format as the core stores them. */
static void rgb_to_image(const sim_scene_t *s, const double *rgb, vf_image_t *img)
{
    for (uint32_t y = 0; y < s->height; y++)
        for (uint32_t x = 0; x < s->width; x++) {
            const double *c = rgb + ((size_t)y * s->width + x) * 3;
            uint8_t *p = (uint8_t *)img->pixels + (size_t)y * img->stride + (size_t)x * vf_format_bytes(s->format);
            long q[3];
            for (int n = 0; n < 3; n++) {
                double v = c[n] < 0 ? 0 : c[n] > 1 ? 1 : c[n];
                q[n] = lround(v * (s->format == VF_FORMAT_RGB565 ? (n == 1 ? 63 : 31) : 255));
            }
            if (s->format == VF_FORMAT_RGB888) {
                p[0] = (uint8_t)q[0], p[1] = (uint8_t)q[1], p[2] = (uint8_t)q[2];
            } else if (s->format == VF_FORMAT_RGB565) {
                unsigned word = (unsigned)(q[0] << 11 | q[1] << 5 | q[2]);
                p[0] = (uint8_t)(word & 0xFF), p[1] = (uint8_t)(word >> 8);
            } else {
                p[0] = (uint8_t)q[2], p[1] = (uint8_t)q[1], p[2] = (uint8_t)q[0], p[3] = 0xFF;
            }
        }
}

/* What the reference and the truth render from and into: their inputs, a frame of doubles, and the image it
 * becomes. VFP_ERR with "out of memory for WHO" in err, with nothing left to free. */
static vfp_status_t double_frame_begin(const sim_scene_t *s, const char *who, sim_ref_inputs_t *in, double **rgb,
                                       vf_image_t *img, char *err, size_t errlen)
{
    in->scalars = NULL;
    *rgb = malloc(sizeof(double) * 3 * s->width * s->height);
    if (!*rgb || sim_ref_inputs(s, in) || sim_image_alloc(img, s->width, s->height, s->format)) {
        free(*rgb);
        sim_ref_inputs_free(in);
        snprintf(err, errlen, "out of memory for %s", who);
        return VFP_ERR;
    }
    return VFP_OK;
}

/* The frame becomes the image when the renderer succeeded (0), else the image is freed; the inputs and the frame
 * are freed either way. */
static vfp_status_t double_frame_end(const sim_scene_t *s, int rendered, sim_ref_inputs_t *in, double *rgb,
                                     vf_image_t *img)
{
    if (rendered == 0)
        rgb_to_image(s, rgb, img);
    else
        sim_image_free(img);
    sim_ref_inputs_free(in);
    free(rgb);
    return rendered == 0 ? VFP_OK : VFP_ERR;
}

const ref_lighting_t *sim_ref_lighting(const sim_scene_t *s, ref_lighting_t *out)
{
    if (!s->params.lighting)
        return NULL;
    const vf_lighting_t *l = &s->lighting;
    memset(out, 0, sizeof *out);
    out->shade = l->shade;
    out->light_count = (int)l->light_count;
    for (uint32_t k = 0; k < l->light_count && k < REF_MAX_LIGHTS; k++) {
        out->light_azimuth[k] = l->lights[k].azimuth;
        out->light_elevation[k] = l->lights[k].elevation;
    }
    out->ka = l->ka / 65535.0, out->kd = l->kd / 65535.0, out->ks = l->ks / 65535.0;
    out->shininess = l->shininess;
    out->gradient_lo = l->gradient_lo, out->gradient_hi = l->gradient_hi;
    out->normal_bits = (int)s->params.normal_bits;
    out->shade_lookup = s->params.shade_lookup == VF_LOOKUP_NEAREST ? REF_LOOKUP_NEAREST : REF_LOOKUP_BILINEAR;
    out->raw = s->vol.core.voxels;
    out->raw_type = (int)s->vol.core.type; /* vf_voxel_t and REF_VOXEL_* list the types in the same order */
    out->exact_normals = s->ref_exact_normals;
    out->shade_bits = s->ref_shade_bits;
    out->lit_table_bits = s->ref_lit_table_bits;
    return out;
}

vfp_status_t sim_render_reference(const sim_scene_t *s, const vf_factor_t *core_factor, vf_image_t *img, char *err,
                                  size_t errlen)
{
    sim_ref_inputs_t in;
    double *rgb;
    if (double_frame_begin(s, "the reference", &in, &rgb, img, err, errlen))
        return VFP_ERR;
    ref_params_t params = {0};
    params.mode = s->params.mode == VF_MODE_POINT     ? REF_MODE_POINT
                  : s->params.mode == VF_MODE_PRECLASS ? REF_MODE_PRECLASS
                  : s->params.mode == VF_MODE_PREINT2  ? REF_MODE_PREINT2
                                                       : REF_MODE_PREINT1;
    params.table2_size = (int)s->params.table2_size;
    params.table_size = (int)s->params.table_size;
    for (int c = 0; c < 3; c++)
        params.background[c] = in.background[c];
    params.lookup = s->params.lookup == VF_LOOKUP_BILINEAR    ? REF_LOOKUP_BILINEAR
                    : s->params.lookup == VF_LOOKUP_TRILINEAR ? REF_LOOKUP_TRILINEAR
                                                              : REF_LOOKUP_NEAREST;
    params.table_bits = (int)s->params.table_bits;
    params.correction = s->params.correction == VF_CORRECTION_LUT ? REF_CORRECTION_LUT : REF_CORRECTION_REBUILD;
    params.partial_slabs = s->params.partial_slabs;
    params.rays = (int)s->params.rays;
    ref_lighting_t lighting;
    params.lighting = sim_ref_lighting(s, &lighting);
    int32_t *offsets = NULL;
    if (core_factor) {
        offsets = malloc(sizeof(int32_t) * 2 * core_factor->nk);
        for (uint32_t k = 0; offsets && k < core_factor->nk; k++) {
            offsets[2 * k] = vf_factor_offset_u(core_factor, k);
            offsets[2 * k + 1] = vf_factor_offset_v(core_factor, k);
        }
        params.slice_offsets_q16 = offsets;
        params.slice_k_axis = core_factor->k_axis;
        params.slice_k_flip = core_factor->k_flip;
    }
    int status = ref_render(&in.vol, in.tf, in.npoints, &params, &in.view, (int)s->width, (int)s->height, rgb,
                            NULL);
    free(offsets);
    if (status)
        snprintf(err, errlen, status == -2 ? "the core's factorisation disagrees with the reference's (principal axis, "
                                             "flip or a slice offset more than 2^-16 apart)"
                                           : "the reference renderer failed (status %d)",
                 status);
    return double_frame_end(s, status, &in, rgb, img);
}

vfp_status_t sim_render_truth(const sim_scene_t *s, vf_image_t *img, char *err, size_t errlen)
{
    sim_ref_inputs_t in;
    double *rgb;
    if (double_frame_begin(s, "the ground truth", &in, &rgb, img, err, errlen))
        return VFP_ERR;
    ref_lighting_t lighting;
    truth_field_t field;
    truth_opts_t opts = TRUTH_OPTS_DEFAULT;
    opts.field = &field;
    int status = truth_field_init(&field, &in.vol, (truth_filter_t)s->truth_filter,
                                  strcmp(s->vol.format, "phantom") == 0 ? s->vol.name : NULL, s->window.lo,
                                  s->window.hi);
    if (status == 0 && field.filter != TRUTH_FILTER_TRILINEAR && s->params.lighting)
        status = -3;
    if (status == -3)
        snprintf(err, errlen, "--truth-filter %s: the lit truth reconstructs trilinearly only (drop the lighting "
                 "or the filter)", truth_filter_name((truth_filter_t)s->truth_filter));
    else if (status == -2)
        snprintf(err, errlen, "--truth-filter analytic: %s has no analytic function (phantom:NAME:N with NAME "
                 "marschner-lobb, sphere or cube)", s->vol.name);
    else if (status)
        snprintf(err, errlen, "out of memory for the ground truth's filter");
    if (status == 0) {
        status = truth_render_lit(&in.vol, in.tf, in.npoints, in.background, &in.view, (int)s->width,
                                  (int)s->height, s->threads, &opts, sim_ref_lighting(s, &lighting), rgb);
        if (status)
            snprintf(err, errlen, "the ground-truth ray caster failed (status %d)", status);
    }
    truth_field_free(&field);
    return double_frame_end(s, status, &in, rgb, img);
}

void sim_scene_describe(const sim_scene_t *s, char *text, size_t len)
{
    const char *base = strrchr(s->vol.name, '/');
    char view[64];
    /* degrees to two decimals: the angles are quantised to 1/65536 turn, and 29.9982 would only distract */
    double az = round(s->view.azimuth * 36000.0 / VF_BAU_PER_TURN) / 100;
    double el = round(s->view.elevation * 36000.0 / VF_BAU_PER_TURN) / 100;
    double roll = round(s->view.roll * 36000.0 / VF_BAU_PER_TURN) / 100;
    if (s->view.roll)
        snprintf(view, sizeof view, "%g,%g,%g", az, el, roll);
    else
        snprintf(view, sizeof view, "%g,%g", az, el);
    const vf_params_t *p = &s->params;
    char options[128] = "";
    /* only what differs from the defaults, so that the common line stays short */
    if (p->table_size != VF_DEFAULT_TABLE || p->table_bits != 16 || p->lookup != VF_LOOKUP_NEAREST ||
        p->correction != VF_CORRECTION_REBUILD || p->buffer != VF_BUFFER_SLICE)
        snprintf(options, sizeof options, " (table %u x %u bits, %s, %s, %s buffer)", p->table_size, p->table_bits,
                 vf_lookup_name(p->lookup), vf_correction_name(p->correction), vf_buffer_name(p->buffer));
    if (p->mode == VF_MODE_PREINT2) /* its 3D table's size, always: the study has not settled its default */
        snprintf(options + strlen(options), sizeof options - strlen(options), " (table2 %u^3)", p->table2_size);
    char rays[48] = "", aniso[96];
    if (s->params.rays > 1)
        snprintf(rays, sizeof rays, " rays %u", s->params.rays);
    if (s->params.partial_slabs)
        snprintf(rays + strlen(rays), sizeof rays - strlen(rays), " partial slabs");
    vfp_sampling_text(&s->sampling, aniso, sizeof aniso);
    char lit[192];
    vfp_lighting_describe(p, &s->lighting, lit, sizeof lit);
    double lo, hi; /* in data units, as --window takes them */
    vfp_window_data(&s->vol, s->window, &lo, &hi);
    snprintf(text, len, "%s %s%s%s %ux%u view %s zoom %g %s window %.10g,%.10g%s%s", base ? base + 1 : s->vol.name,
             vf_mode_name(p->mode), options, rays, s->width, s->height, view, s->view.zoom_q16 / 65536.0, s->tf.name,
             lo, hi, lit, aniso);
}
