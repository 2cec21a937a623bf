/* SPDX-License-Identifier: MIT */
/*
 * sampling.h: rays per voxel column chosen from a volume's spacing.
 *
 * Shear-warp casts one ray per voxel column. On an isotropic volume that is the right default; where one spacing
 * is at least twice the smallest (thick-slice CT, headsq, cthead) the coarse axes draw stair-step outlines, and
 * 2 x 2 rays per voxel column bring unlit frames of such volumes 0.6 to 12 dB closer to the truth for about
 * three times the instructions (docs/defaults.md, "Anisotropic volumes"). Lit frames gained nothing measurable
 * (-0.3 to +0.6 dB: their distance from the truth is the shading's) and keep one ray; partial slabs gained
 * nothing either and stay off. Both programs take this default for their full-quality frames; --rays wins.
 */
#ifndef VFP_SAMPLING_H
#define VFP_SAMPLING_H

#include <stddef.h>

#include "io/volume.h"
#include "volfix.h"

/* Spacing ratio from which a volume is treated as anisotropic. */
#define VFP_ANISOTROPY_THRESHOLD 2.0

typedef struct vfp_sampling {
    double anisotropy; /* the largest spacing over the smallest (1 for isotropic volumes) */
    uint32_t rays;     /* rays per voxel column along each axis (vf_params_t.rays) */
    int rays_given;    /* --rays was given: it wins */
    int lit;           /* for a lit frame */
} vfp_sampling_t;

/* The rays for a frame of this volume: rays_given (--rays) when not 0, else what the spacing asks for: 2 for an
 * unlit frame from VFP_ANISOTROPY_THRESHOLD on, else 1. */
vfp_sampling_t vfp_sampling_choose(const vfp_volume_t *vol, uint32_t rays_given, int lit);

/* The summary line's words, "" for an isotropic volume or when --rays was given:
 * "; anisotropic spacing 2.13x: rays 2 by default (--rays 1: 3 to 7 times less work)". */
void vfp_sampling_text(const vfp_sampling_t *s, char *out, size_t outlen);

#endif
