/* SPDX-License-Identifier: MIT */
/*
 * lighting_opts.h: the lighting options volfix-sim and volfix share (docs/usage.md, "Lighting"), parsed in one
 * place, and the renderer's lighting made of them and of the transfer function's own (tf.h, vfp_tf_look_t).
 *
 *   --shade none|phong        unlit, or Blinn-Phong (default: the transfer function's; the presets' are in
 *                             vfp_lighting_help)
 *   --light AZ,EL             a white directional light, degrees relative to the viewer; once or twice
 *   --material KA,KD,KS,N     ambient, diffuse, specular in [0, 1] and an integer shininess 1..255
 *   --gradient-opacity LO,HI  opacity times a ramp in the 8-bit gradient magnitude, integers 0 <= LO < HI <= 255
 *   --normal-bits B           bits of a normal code: 8, 10, 12, 14 or 16
 *   --shade-lookup L          a sample's shade: nearest (its nearest voxel's) or bilinear (its four voxels')
 *
 * Each option has its own small parser; every error is one line naming the option and the accepted form.
 */
#ifndef VFP_LIGHTING_OPTS_H
#define VFP_LIGHTING_OPTS_H

#include "status.h"
#include "tf.h"
#include "volfix.h"

typedef struct vfp_lighting_opts {
    int shade;                     /* 1 phong, 0 none, -1 not given */
    int light_count;               /* --light given this many times (0..VF_MAX_LIGHTS) */
    double light[VF_MAX_LIGHTS][2]; /* azimuth, elevation in degrees */
    int have_material;
    double ka, kd, ks;
    int shininess;
    int gradient_lo, gradient_hi;  /* both 0: not given */
    int normal_bits;               /* 0: not given */
    int shade_lookup;              /* a vf_lookup_t, or -1: not given */
} vfp_lighting_opts_t;

/* Nothing given. */
void vfp_lighting_opts_init(vfp_lighting_opts_t *o);

/* If option is one of the lighting options, parse its value into o: returns 1 (it took the value), or -1 after
 * printing "PROGRAM: OPTION VALUE: expected ..." to stderr. Returns 0 for any other option. */
int vfp_lighting_option(vfp_lighting_opts_t *o, const char *program, const char *option, const char *value);

/* The parsers one option each, for callers with their own loop: VFP_OK, or VFP_ERR with "expected ..." (the
 * accepted form, without the option's name) in err. */
vfp_status_t vfp_parse_shade(const char *text, int *shade, char *err, size_t errlen);
vfp_status_t vfp_parse_light(const char *text, double light[2], char *err, size_t errlen);
vfp_status_t vfp_parse_material(const char *text, double k[3], int *shininess, char *err, size_t errlen);
vfp_status_t vfp_parse_gradient_opacity(const char *text, int *lo, int *hi, char *err, size_t errlen);
vfp_status_t vfp_parse_normal_bits(const char *text, int *bits, char *err, size_t errlen);
vfp_status_t vfp_parse_shade_lookup(const char *text, int *lookup, char *err, size_t errlen);

/* Contradictions between the options, checked once all are read: VFP_OK, or VFP_ERR with a line in err. */
vfp_status_t vfp_lighting_check(const vfp_lighting_opts_t *o, char *err, size_t errlen);

/* The renderer's lighting for transfer function tf (NULL: none said) and the options: params->lighting,
 * normal_bits and shade_lookup, and *lighting, which vf_renderer_set_lighting takes when params->lighting.
 * The options win over the transfer function's shade and material; --light or --material without --shade mean
 * phong. Frames are lit (params->lighting) when shaded or with a gradient-opacity ramp. */
void vfp_lighting_resolve(const vfp_lighting_opts_t *o, const vfp_tf_t *tf, vf_params_t *params,
                          vf_lighting_t *lighting);

/* " phong light 0,0 material 0.1,0.7,0.2,10 normals 14 bits, bilinear shade": what a summary line adds for a lit
 * renderer ("" when unlit). */
void vfp_lighting_describe(const vf_params_t *params, const vf_lighting_t *lighting, char *text, size_t len);

/* The options that give this lighting to volfix-sim render (" --shade none", or " --shade phong --light ..."),
 * for logs that name the pixels. */
void vfp_lighting_args(const vf_params_t *params, const vf_lighting_t *lighting, char *text, size_t len);

/* The options' help lines, for both programs' --help: a string literal, so that a usage text can take it in. */
#define VFP_LIGHTING_HELP \
    "  --shade S            none or phong (Blinn-Phong lighting, docs/algorithm.md section 7). Default: the\n" \
    "                       transfer function's: phong for the ct-bone and ct-skin-bone presets, whose opaque\n" \
    "                       surfaces read as shapes only when lit, none for the others and for files without\n" \
    "                       a 'shade' line. --light or --material alone mean phong\n" \
    "  --light AZ,EL        a white light, degrees relative to the viewer (azimuth -360..360, positive from the\n" \
    "                       right; elevation -90..90, positive from above); give it twice for two lights\n" \
    "                       (default: one headlight, 0,0)\n" \
    "  --material KA,KD,KS,N  ambient, diffuse, specular in [0, 1] and shininess, an integer 1..255 (default:\n" \
    "                       the transfer function file's 'material' line, else 0.1,0.7,0.2,10)\n" \
    "  --gradient-opacity LO,HI  opacity times a ramp in the gradient magnitude, in 8-bit magnitudes (255 is the\n" \
    "                       volume's steepest voxel), integers 0 <= LO < HI <= 255: 0 up to LO, 1 from HI\n" \
    "                       (default: none); applies with --shade none too\n" \
    "  --normal-bits B      bits of a voxel's normal code: 8, 10, 12, 14 (default) or 16\n" \
    "  --shade-lookup L     a sample's shade: nearest (default: its nearest voxel's) or bilinear (its four\n" \
    "                       voxels' interpolated: a little closer to the truth, and slower)\n"
extern const char vfp_lighting_help[];

#endif
