/* SPDX-License-Identifier: MIT */
/*
 * tf.h: transfer functions as people write them (a small text format, or a built-in preset), and their
 * conversion to the core's control points for a volume and window.
 *
 * The text format, one control point a line:
 *
 *     # comments start with '#'
 *     units normalized          # optional: "normalized" (the default) or "data"
 *     0.00   0 0 0   0
 *     0.40   1 0.8 0.6   0.05   # scalar  red green blue  opacity-per-voxel
 *     1.00   1 1 1   0.9
 *
 * A file may also say how it is lit (docs/algorithm.md, section 7; the command line's --shade and --material win
 * over it):
 *
 *     shade phong               # or "shade none": unlit
 *     material 0.1 0.7 0.2 10   # ambient, diffuse, specular in [0, 1], shininess an integer 1..255
 *
 * Scalars are non-decreasing. With "units normalized" a scalar of 0 is the bottom of the window and 1 its top,
 * so the function moves with the window (CT window/level); with "units data" scalars are data values (after a
 * NIfTI slope and intercept), fixed to the data whatever the window. Colour and opacity are in [0, 1]; opacity
 * is per unit length (one voxel of the smallest spacing). Between points the function is linear; beyond the
 * first and last point it is constant; two points at one scalar make a step.
 */
#ifndef VFP_TF_H
#define VFP_TF_H

#include <stddef.h>

#include "volfix.h"
#include "volume.h"

typedef struct vfp_tf_point {
    double s, r, g, b, a;
} vfp_tf_point_t;

/* How a transfer function is meant to be lit, when it says (a file's shade and material lines; a preset's). */
typedef struct vfp_tf_look {
    int shade;             /* 1: phong, 0: none, -1: not said (the programs' default: none) */
    int have_material;     /* the material below was given */
    double ka, kd, ks;     /* ambient, diffuse, specular, [0, 1] */
    int shininess;         /* 1..255 */
} vfp_tf_look_t;

typedef struct vfp_tf {
    char name[64];
    int data_units; /* 0: scalars normalised to the window; 1: data units */
    int count;
    vfp_tf_point_t points[VF_MAX_TF_POINTS];
    vfp_tf_look_t look;
} vfp_tf_t;

/* Read a transfer-function file. Returns VFP_OK, or VFP_ERR with a one-line "FILE:LINE: ..." message in err. */
vfp_status_t vfp_tf_load(vfp_tf_t *tf, const char *path, char *err, size_t errlen);

/* A built-in preset by name. Returns VFP_OK, or VFP_ERR with err listing the names. */
vfp_status_t vfp_tf_preset(vfp_tf_t *tf, const char *name, char *err, size_t errlen);

/* The preset names, NULL-terminated, and a one-line description of each. */
extern const char *const vfp_tf_preset_names[];
const char *vfp_tf_preset_about(const char *name);

/* Move and stretch a transfer function as a window/level control does, keeping the data's window (so the
 * renderer reclassifies but does not rebuild its slices). In the window's normalised units u (0 at its bottom,
 * 1 at its top) a point at u moves to 0.5 + shift + (u - 0.5) * scale: shift 0.1 moves the function up by a
 * tenth of the window, scale 2 makes it twice as wide about the window's centre. A function in data units moves
 * by the same amounts of the window (converted with the volume's slope and intercept). scale must be > 0. */
void vfp_tf_move(vfp_tf_t *tf, const vfp_volume_t *vol, vf_window_t window, double shift, double scale);

/* Control points for the core: scalars mapped through the window to 0..255 (clipped there, with points added
 * at the window's edges so that the shape inside is kept), values to unorm16. out holds VF_MAX_TF_POINTS.
 * Returns the number of points (at least 1). */
uint32_t vfp_tf_to_core(const vfp_tf_t *tf, const vfp_volume_t *vol, vf_window_t window, vf_tf_point_t *out);

#endif
