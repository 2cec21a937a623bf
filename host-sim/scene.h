/* SPDX-License-Identifier: MIT */
/*
 * scene.h: one scene (volume, window, transfer function, parameters, view, output size and format), rendered
 * by the fixed-point core, by the double-precision reference or by the ground-truth ray caster from the same
 * inputs.
 */
#ifndef SIM_SCENE_H
#define SIM_SCENE_H

#include "options.h"
#include "ref/ref.h"
#include "render/render_mt.h"
#include "render/sampling.h"
#include "io/tf.h"
#include "io/volume.h"

typedef struct sim_scene {
    vfp_volume_t vol;
    vf_window_t window;
    vfp_tf_t tf;
    vf_tf_point_t points[VF_MAX_TF_POINTS]; /* the transfer function as the core gets it */
    uint32_t npoints;
    vf_params_t params;
    vfp_sampling_t sampling; /* the rays the volume's spacing asks for (applied unless --rays was given) */
    vf_lighting_t lighting; /* section 7, for params.lighting: the options' and the transfer function's */
    /* The precision study's knobs of the reference's lighting (ref.h, ref_lighting_t; 0: section 7 as written) */
    int ref_exact_normals, ref_shade_bits, ref_lit_table_bits;
    vf_view_t view;
    uint32_t width, height;
    vf_format_t format;
    int threads;
    int truth_filter; /* the truth's reconstruction (truth.h's truth_filter_t; 0: trilinear) */
} sim_scene_t;

/* The start of a command that renders a scene: its options parsed (the usage is usage_head, then the scene options'
 * help) and the scene loaded. Returns VFP_OK with the scene loaded (free it), VFP_HELP_SHOWN after printing the
 * usage, or VFP_ERR after printing a one-line error. */
vfp_status_t sim_scene_command(sim_opts_t *opts, sim_scene_t *scene, int argc, char **argv, unsigned groups,
                               const char *usage_head);

/* Load the volume and transfer function the options name. Returns VFP_OK, or VFP_ERR with err. */
vfp_status_t sim_scene_load(sim_scene_t *scene, const sim_opts_t *opts, char *err, size_t errlen);
void sim_scene_free(sim_scene_t *scene);

/* Degrees to binary angle units, and a view from the options' angles and zoom. */
int32_t sim_bau(double degrees);
vf_view_t sim_view(double azimuth, double elevation, double roll, double zoom);

/* An image of the scene's size and format (pixels malloc'd; free with sim_image_free). */
vfp_status_t sim_image_alloc(vf_image_t *image, uint32_t width, uint32_t height, vf_format_t format);
void sim_image_free(vf_image_t *image);

/* Render with the core (threads from the scene) into an image of the scene's size and format; factor, if not
 * NULL, receives the frame's factorisation. Returns VFP_OK, or VFP_ERR with err. */
vfp_status_t sim_render_core(const sim_scene_t *scene, vf_image_t *image, vf_factor_t *factor, char *err,
                             size_t errlen);

/* Light a core renderer as the scene says (after every vfp_render_set_tf: a renderer made again for longer run
 * lists starts with the default lighting). VFP_OK, or VFP_ERR with err. */
vfp_status_t sim_core_lighting(const sim_scene_t *scene, vf_renderer_t *core, char *err, size_t errlen);

/* Render with the double reference. With core_factor (from sim_render_core), the reference checks the core's
 * slice offsets against its own and samples where the core does (ref.h explains why); without it the
 * reference works alone. Returns VFP_OK, or VFP_ERR with err (also when the factorisations disagree). */
vfp_status_t sim_render_reference(const sim_scene_t *scene, const vf_factor_t *core_factor, vf_image_t *image,
                                  char *err, size_t errlen);

/* The scene as the reference and the truth take it: the windowed 8-bit volume, the transfer-function points,
 * view and background as quantised for the core. sim_ref_inputs returns VFP_OK, or VFP_ERR when out of memory;
 * free the scalars with sim_ref_inputs_free. */
typedef struct sim_ref_inputs {
    ref_volume_t vol;
    uint8_t *scalars;
    ref_tf_point_t tf[VF_MAX_TF_POINTS];
    int npoints;
    ref_view_t view;
    double background[3];
} sim_ref_inputs_t;

vfp_status_t sim_ref_inputs(const sim_scene_t *scene, sim_ref_inputs_t *in);
void sim_ref_inputs_free(sim_ref_inputs_t *in);

/* The scene's lighting as the reference and the truth take it (the core's quantised lights and material, the raw
 * voxels), into *out; returns out, or NULL when the scene is unlit. */
const ref_lighting_t *sim_ref_lighting(const sim_scene_t *scene, ref_lighting_t *out);

/* Render with the ground-truth ray caster (host-sim/truth) from the inputs the reference gets: the windowed
 * volume, the quantised transfer-function points, view, size and background, and the lighting (the lit truth of
 * docs/algorithm.md); threads from the scene. The mode and table options do not apply. Returns VFP_OK, or
 * VFP_ERR with err. */
vfp_status_t sim_render_truth(const sim_scene_t *scene, vf_image_t *image, char *err, size_t errlen);

/* "engine.nhdr preint1 512x512 view 30,20 ramp window 0,255": what a line of output is about. */
void sim_scene_describe(const sim_scene_t *scene, char *text, size_t len);

#endif
