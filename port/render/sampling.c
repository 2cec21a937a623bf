/* SPDX-License-Identifier: MIT */
/* sampling.c: rays per voxel column from a volume's spacing (see sampling.h). */
#include "sampling.h"

#include <stdio.h>

vfp_sampling_t vfp_sampling_choose(const vfp_volume_t *vol, uint32_t rays_given, int lit)
{
    double lo = vol->spacing[0], hi = vol->spacing[0];
    for (int a = 1; a < 3; a++) {
        lo = vol->spacing[a] < lo ? vol->spacing[a] : lo;
        hi = vol->spacing[a] > hi ? vol->spacing[a] : hi;
    }
    vfp_sampling_t s = {lo > 0 ? hi / lo : 1, rays_given, rays_given != 0, lit != 0};
    if (!rays_given)
        s.rays = s.anisotropy >= VFP_ANISOTROPY_THRESHOLD && !lit ? 2 : 1;
    return s;
}

void vfp_sampling_text(const vfp_sampling_t *s, char *out, size_t outlen)
{
    if (s->anisotropy < VFP_ANISOTROPY_THRESHOLD || s->rays_given)
        snprintf(out, outlen, "%s", "");
    else if (s->lit)
        snprintf(out, outlen, "; anisotropic spacing %.2fx: one ray, lit frames gain nothing from more",
                 s->anisotropy);
    else
        snprintf(out, outlen, "; anisotropic spacing %.2fx: rays %u by default (--rays 1: 3 to 7 times less work)",
                 s->anisotropy, s->rays);
}
