/* SPDX-License-Identifier: MIT */
/* orientation.c: a volume turned into the patient frame (LPS) on load, named views and the letters at a view's edges. */

/*********************
 *      INCLUDES
 *********************/
#include "volume_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/*********************
 *      DEFINES
 *********************/
#define PI 3.14159265358979323846

/* Three axes whose unit vectors span less than this volume are not a frame (a repeated or flat direction). */
#define MIN_FRAME_DET 0.1

/* A view's edge names every patient axis with at least this share of the edge's direction. */
#define EDGE_LETTER_SHARE 0.25

/**********************
 *  STATIC PROTOTYPES
 **********************/
static void rotation(const double view[3], double r[3][3]);
static void edge_letters(const double v[3], char out[4]);

/**********************
 *  STATIC VARIABLES
 **********************/

/* The camera of each named view as --view angles (azimuth, elevation, roll in degrees). The core's eye frame is x
 * right, y down, z into the screen, and eye = Rz(roll) Rx(elevation) Ry(azimuth) world (core/factor.c), so a view
 * is the three rows of R: the world directions of the picture's right, of its bottom and of the line of sight.
 *   inferior   right L, bottom P, looking S  (R = I: axial slices as radiologists read them, from the feet)
 *   superior   right R, bottom P, looking I  (azimuth 180)
 *   anterior   right L, bottom I, looking P  (elevation 90: facing the patient, the patient's left on the right)
 *   posterior  right R, bottom I, looking A  (azimuth 180, elevation -90)
 *   left       right P, bottom I, looking R  (azimuth 90, roll -90: at the patient's left side, the face on the left)
 *   right      right A, bottom I, looking L  (azimuth -90, roll 90)
 * Each is a rotation (right x bottom = line of sight), never a reflection: nothing is mirrored. */
static const struct {
    const char *name;
    double view[3];
} named_views[] = {
    {"inferior", {0, 0, 0}},     {"superior", {180, 0, 0}}, {"anterior", {0, 90, 0}},
    {"posterior", {180, -90, 0}}, {"left", {90, 0, -90}},    {"right", {-90, 0, 90}},
};

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

vfp_status_t vfpi_set_direction(vfp_volume_t *vol, const double axes[3][3], const char *from, const char *name,
                                unsigned line, char *err, size_t errlen)
{
    static const char axis_names[3] = {'x', 'y', 'z'};
    double unit[3][3];
    for (int a = 0; a < 3; a++) {
        double len = 0;
        for (int c = 0; c < 3; c++) {
            if (!isfinite(axes[a][c]))
                return vfpi_fail(err, errlen, name, line, "%s: the %c axis's direction is not finite", from,
                                 axis_names[a]);
            len += axes[a][c] * axes[a][c];
        }
        len = sqrt(len);
        if (!(len > 1e-12))
            return vfpi_fail(err, errlen, name, line, "%s: the %c axis's direction is zero (expected a vector of "
                             "non-zero length)", from, axis_names[a]);
        for (int c = 0; c < 3; c++)
            unit[a][c] = axes[a][c] / len;
    }
    double det = unit[0][0] * (unit[1][1] * unit[2][2] - unit[1][2] * unit[2][1]) -
                 unit[0][1] * (unit[1][0] * unit[2][2] - unit[1][2] * unit[2][0]) +
                 unit[0][2] * (unit[1][0] * unit[2][1] - unit[1][1] * unit[2][0]);
    if (!(fabs(det) >= MIN_FRAME_DET))
        return vfpi_fail(err, errlen, name, line, "%s: the axes' directions are (nearly) in one plane (expected "
                         "three independent directions)", from);
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++)
            vol->direction[c][a] = unit[a][c];
    vol->oriented = 1;
    snprintf(vol->orient_from, sizeof vol->orient_from, "%s", from);
    return VFP_OK;
}

vfp_status_t vfpi_orient(vfp_volume_t *vol, char *err, size_t errlen)
{
    for (int a = 0; a < 3; a++) {
        vol->stored_axis[a] = a;
        vol->stored_flip[a] = 0;
    }
    if (!vol->oriented) {
        memset(vol->direction, 0, sizeof vol->direction);
        for (int a = 0; a < 3; a++)
            vol->direction[a][a] = 1;
        vol->oblique_deg = 0;
        return VFP_OK;
    }
    /* The patient axis of each voxel axis: the largest component of all nine first, then the largest left among
     * the unused rows and columns, so that the choice is a permutation even for directions near 45 degrees. */
    int patient_of[3] = {-1, -1, -1}, used_row[3] = {0, 0, 0}, sign[3] = {1, 1, 1};
    for (int round = 0; round < 3; round++) {
        int best_r = -1, best_c = -1;
        double best = -1;
        for (int c = 0; c < 3; c++)
            for (int r = 0; r < 3; r++)
                if (patient_of[c] < 0 && !used_row[r] && fabs(vol->direction[r][c]) > best) {
                    best = fabs(vol->direction[r][c]);
                    best_r = r;
                    best_c = c;
                }
        patient_of[best_c] = best_r;
        used_row[best_r] = 1;
        sign[best_c] = vol->direction[best_r][best_c] < 0 ? -1 : 1;
    }
    /* What remains after the reordering: column p is the direction of the new axis p. */
    double rest[3][3];
    double worst_cos = 1;
    for (int c = 0; c < 3; c++) {
        int p = patient_of[c];
        for (int r = 0; r < 3; r++)
            rest[r][p] = sign[c] * vol->direction[r][c];
        vol->stored_axis[p] = c;
        vol->stored_flip[p] = sign[c] < 0;
    }
    for (int p = 0; p < 3; p++)
        worst_cos = rest[p][p] < worst_cos ? rest[p][p] : worst_cos;
    memcpy(vol->direction, rest, sizeof rest);
    vol->oblique_deg = acos(worst_cos > 1 ? 1 : worst_cos) * 180 / PI;
    if (vol->oblique_deg < 1e-6)
        vol->oblique_deg = 0;

    int identity = 1;
    for (int c = 0; c < 3; c++)
        identity = identity && patient_of[c] == c && sign[c] > 0;
    if (identity)
        return VFP_OK;

    /* The new voxel (X0, X1, X2) is stored voxel i_c = X_p (or n_c - 1 - X_p when reversed), p the patient axis of
     * stored axis c: walking the new volume is a walk through the old one with a fixed step per new axis. */
    const uint32_t *dims = vol->core.dims;
    uint32_t nd[3];
    int64_t step[3], base = 0, stride[3] = {1, (int64_t)dims[0], (int64_t)dims[0] * dims[1]};
    double spacing[3];
    for (int c = 0; c < 3; c++) {
        int p = patient_of[c];
        nd[p] = dims[c];
        spacing[p] = vol->spacing[c];
        step[p] = sign[c] * stride[c];
        if (sign[c] < 0)
            base += (int64_t)(dims[c] - 1) * stride[c];
    }
    unsigned bytes = vfpi_type_bytes(vol->core.type);
    size_t count = (size_t)dims[0] * dims[1] * dims[2];
    unsigned char *out = malloc(count * bytes);
    if (!out)
        return vfpi_fail(err, errlen, vol->name, 0, "out of memory for the volume in patient axes (%zu bytes)",
                         count * bytes);
    const unsigned char *in = vol->data;
    unsigned char *dst = out;
    for (uint32_t z = 0; z < nd[2]; z++)
        for (uint32_t y = 0; y < nd[1]; y++) {
            int64_t src = base + (int64_t)z * step[2] + (int64_t)y * step[1];
            if (bytes == 1) {
                for (uint32_t x = 0; x < nd[0]; x++, src += step[0])
                    *dst++ = in[src];
            } else {
                for (uint32_t x = 0; x < nd[0]; x++, src += step[0], dst += 2)
                    memcpy(dst, in + 2 * src, 2);
            }
        }
    free(vol->data);
    vol->data = out;
    for (int p = 0; p < 3; p++) {
        vol->core.dims[p] = nd[p];
        vol->spacing[p] = spacing[p];
    }
    return VFP_OK;
}

vfp_status_t vfp_view_named(const char *name, double view[3])
{
    for (size_t i = 0; name && i < sizeof named_views / sizeof named_views[0]; i++)
        if (strcasecmp(name, named_views[i].name) == 0) {
            memcpy(view, named_views[i].view, sizeof named_views[i].view);
            return VFP_OK;
        }
    return VFP_ERR;
}

void vfp_view_edges(const double view[3], char right[4], char left[4], char top[4], char bottom[4])
{
    double r[3][3], neg[3];
    rotation(view, r);
    edge_letters(r[0], right);
    edge_letters(r[1], bottom);
    for (int c = 0; c < 3; c++)
        neg[c] = -r[0][c];
    edge_letters(neg, left);
    for (int c = 0; c < 3; c++)
        neg[c] = -r[1][c];
    edge_letters(neg, top);
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

/* R = Rz(roll) Rx(elevation) Ry(azimuth), as the core's factorisation builds it (core/factor.c), in doubles. */
static void rotation(const double view[3], double r[3][3])
{
    double a = view[0] * PI / 180, e = view[1] * PI / 180, o = view[2] * PI / 180;
    double sa = sin(a), ca = cos(a), se = sin(e), ce = cos(e), so = sin(o), co = cos(o);
    const double rxy[3][3] = {{ca, 0, sa}, {se * sa, ce, -se * ca}, {-ce * sa, se, ce * ca}};
    for (int c = 0; c < 3; c++) {
        r[0][c] = co * rxy[0][c] - so * rxy[1][c];
        r[1][c] = so * rxy[0][c] + co * rxy[1][c];
        r[2][c] = rxy[2][c];
    }
}

/* "L", "LA", "PSR": the LPS components of v with at least EDGE_LETTER_SHARE of it, the largest first. */
static void edge_letters(const double v[3], char out[4])
{
    static const char plus[3] = {'L', 'P', 'S'}, minus[3] = {'R', 'A', 'I'};
    int order[3] = {0, 1, 2};
    for (int i = 0; i < 3; i++)
        for (int j = i + 1; j < 3; j++)
            if (fabs(v[order[j]]) > fabs(v[order[i]])) {
                int t = order[i];
                order[i] = order[j];
                order[j] = t;
            }
    int n = 0;
    for (int i = 0; i < 3; i++) {
        int c = order[i];
        if (fabs(v[c]) >= EDGE_LETTER_SHARE)
            out[n++] = v[c] > 0 ? plus[c] : minus[c];
    }
    out[n] = 0;
}
