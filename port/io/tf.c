/* SPDX-License-Identifier: MIT */
/* tf.c: transfer-function files, presets, and their conversion to the core's control points (see tf.h). */
#include "tf.h"
#include "numbers.h"
#include "readfile.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Mapped scalars (0..255 is the window) are kept within this far outside it: far enough that no output level
 * changes (an edge value interpolated across 1e12 moves by less than 1e-10), near enough that a difference of two
 * stays finite. A scalar of -1e308 in the file, times 255, is -inf, and the edge value between -inf and a point in
 * the window would be inf/inf, NaN, converted to uint16_t (undefined behaviour; tests/fuzz keeps such a file). */
#define FAR_SCALAR 1e12

typedef struct preset {
    const char *name;
    const char *about;
    int count;
    vfp_tf_point_t points[12];
    int shade; /* the preset's default shading (vfp_tf_look_t.shade: 1 phong, 0 none) */
} preset_t;

/* Normalised to the window. Opacity is per voxel: a slab of a few voxels at 0.3 is already mostly opaque. */
static const preset_t presets[] = {
    {"ramp", "opacity and grey level rise linearly from 0 to 1 over the window (the benchmark setting)", 2,
     {{0.0, 0, 0, 0, 0}, {1.0, 1, 1, 1, 1}}, 0},
    /* Narrow, but resolved: each peak is 0.04 of the range wide, ten entries of the default 256-entry table
     * (narrower peaks test the table's resolution more than the integration; see the precision study). */
    {"sharp", "three narrow opacity peaks (orange, green, white): the case pre-integration exists for", 10,
     {{0.0, 0, 0, 0, 0},
      {0.28, 1, 0.5, 0.1, 0}, {0.30, 1, 0.5, 0.1, 0.9}, {0.32, 1, 0.5, 0.1, 0},
      {0.53, 0.2, 1, 0.3, 0}, {0.55, 0.2, 1, 0.3, 0.9}, {0.57, 0.2, 1, 0.3, 0},
      {0.78, 1, 1, 1, 0}, {0.80, 1, 1, 1, 1}, {0.82, 1, 1, 1, 0}}, 0},
    /* CT, window-relative: with the default window (docs/defaults.md) air sits near 0, soft tissue of
     * uncalibrated CT (cthead) across the skin peak at 0.30-0.40 and bone from about 0.5 up; the skin layer is
     * the partial-volume ramp between air and tissue. */
    {"ct-bone", "CT: bone, ivory and opaque; soft tissue and air clear", 4,
     {{0.0, 1, 0.95, 0.85, 0}, {0.52, 1, 0.95, 0.85, 0}, {0.62, 1, 0.95, 0.85, 0.5}, {1.0, 1, 1, 1, 0.9}}, 1},
    {"ct-skin-bone", "CT: a thin translucent skin over opaque bone", 7,
     {{0.0, 0.9, 0.6, 0.45, 0}, {0.30, 0.9, 0.6, 0.45, 0}, {0.35, 0.9, 0.6, 0.45, 0.08},
      {0.40, 0.9, 0.6, 0.45, 0}, {0.52, 1, 0.95, 0.85, 0}, {0.62, 1, 0.95, 0.85, 0.5}, {1.0, 1, 1, 1, 0.9}}, 1},
    {"mr-brain", "MR: soft opacity ramp from dark red through orange to white", 5,
     {{0.0, 0.3, 0.05, 0.05, 0}, {0.15, 0.5, 0.1, 0.05, 0}, {0.4, 0.9, 0.45, 0.2, 0.04},
      {0.7, 1, 0.85, 0.6, 0.12}, {1.0, 1, 1, 1, 0.3}}, 0},
};

#define PRESET_COUNT (sizeof presets / sizeof presets[0])

const char *const vfp_tf_preset_names[] = {"ramp", "sharp", "ct-bone", "ct-skin-bone", "mr-brain", NULL};

static double eval(const vfp_tf_point_t *p, int count, double x, int channel);
static double channel(const vfp_tf_point_t *p, int c);

vfp_status_t vfp_tf_preset(vfp_tf_t *tf, const char *name, char *err, size_t errlen)
{
    for (size_t i = 0; i < PRESET_COUNT; i++)
        if (strcmp(presets[i].name, name) == 0) {
            memset(tf, 0, sizeof *tf);
            snprintf(tf->name, sizeof tf->name, "%s", name);
            tf->count = presets[i].count;
            memcpy(tf->points, presets[i].points, sizeof(vfp_tf_point_t) * (size_t)presets[i].count);
            tf->look.shade = presets[i].shade; /* the default material: the programs' (vf_lighting_default) */
            return VFP_OK;
        }
    snprintf(err, errlen, "unknown preset '%s' (expected ramp, sharp, ct-bone, ct-skin-bone or mr-brain)", name);
    return VFP_ERR;
}

const char *vfp_tf_preset_about(const char *name)
{
    for (size_t i = 0; i < PRESET_COUNT; i++)
        if (strcmp(presets[i].name, name) == 0)
            return presets[i].about;
    return NULL;
}

/* A "shade" or "material" line (the word already read) into look. Returns VFP_OK, or VFP_ERR with what was
 * expected in err (the caller adds the file and line). */
static vfp_status_t look_line(const char *word, const char *line, vfp_tf_look_t *look, char *err, size_t errlen)
{
    char rest[32], extra[2];
    if (strcmp(word, "shade") == 0) {
        if (sscanf(line, " shade %31s %1s", rest, extra) == 1 && strcmp(rest, "phong") == 0)
            look->shade = 1;
        else if (sscanf(line, " shade %31s %1s", rest, extra) == 1 && strcmp(rest, "none") == 0)
            look->shade = 0;
        else {
            snprintf(err, errlen, "expected 'shade phong' or 'shade none'");
            return VFP_ERR;
        }
        return VFP_OK;
    }
    double k[4];
    if (sscanf(line, " material %lf %lf %lf %lf %1s", &k[0], &k[1], &k[2], &k[3], extra) != 4 ||
        !(k[0] >= 0 && k[0] <= 1 && k[1] >= 0 && k[1] <= 1 && k[2] >= 0 && k[2] <= 1) ||
        !(k[3] >= 1 && k[3] <= 255 && k[3] == floor(k[3]))) {
        snprintf(err, errlen, "expected 'material KA KD KS N': ambient, diffuse and specular in [0, 1] and an "
                              "integer shininess from 1 to 255");
        return VFP_ERR;
    }
    look->have_material = 1;
    look->ka = k[0], look->kd = k[1], look->ks = k[2];
    look->shininess = (int)k[3];
    return VFP_OK;
}

/* A control point's line: exactly five numbers separated by blanks, each read by the options' strict parser
 * (decimal and finite: "0x10", "nan" and "1junk" are not numbers here either). Returns 1 with *p filled, else 0. */
static int point_line(char *line, vfp_tf_point_t *p)
{
    double v[5];
    int n = 0;
    char *save = NULL;
    for (char *word = strtok_r(line, " \t\r", &save); word; word = strtok_r(NULL, " \t\r", &save)) {
        if (n == 5 || !vfp_parse_number(word, -DBL_MAX, DBL_MAX, &v[n]))
            return 0;
        n++;
    }
    if (n != 5)
        return 0;
    p->s = v[0], p->r = v[1], p->g = v[2], p->b = v[3], p->a = v[4];
    return 1;
}

vfp_status_t vfp_tf_load(vfp_tf_t *tf, const char *path, char *err, size_t errlen)
{
    memset(tf, 0, sizeof *tf);
    tf->look.shade = -1;
    char *text;
    size_t size;
    if (vfp_read_text(path, VFP_CAP_TF, "transfer function", &text, &size, err, errlen))
        return VFP_ERR;
    const char *base = strrchr(path, '/');
    snprintf(tf->name, sizeof tf->name, "%s", base ? base + 1 : path);
    int lineno = 0;
    vfp_status_t status = VFP_OK;
    unsigned nul = vfp_text_nul_line(text, size);
    char *cursor = text, *line;
    /* whole lines however long, each read once from the text in memory */
    while (status == VFP_OK && (line = vfp_text_next_line(&cursor)) != NULL) {
        lineno++;
        if ((unsigned)lineno == nul) {
            snprintf(err, errlen, "%s:%d: expected text, found a NUL byte", path, lineno);
            status = VFP_ERR;
            break;
        }
        char *hash = strchr(line, '#');
        if (hash)
            *hash = 0;
        char word[32];
        if (sscanf(line, " %31s", word) != 1)
            continue; /* blank or comment */
        if (strcmp(word, "units") == 0) {
            char units[32] = "";
            if (sscanf(line, " units %31s", units) == 1 && strcmp(units, "normalized") == 0) {
                tf->data_units = 0;
            } else if (strcmp(units, "data") == 0) {
                tf->data_units = 1;
            } else {
                snprintf(err, errlen, "%s:%d: expected 'units normalized' or 'units data'", path, lineno);
                status = VFP_ERR;
            }
            continue;
        }
        if (strcmp(word, "shade") == 0 || strcmp(word, "material") == 0) {
            char what[256];
            if (look_line(word, line, &tf->look, what, sizeof what)) {
                snprintf(err, errlen, "%s:%d: %s", path, lineno, what);
                status = VFP_ERR;
            }
            continue;
        }
        vfp_tf_point_t p;
        if (!point_line(line, &p)) {
            snprintf(err, errlen, "%s:%d: expected a control point 'scalar r g b a' (five numbers)", path, lineno);
            status = VFP_ERR;
        } else if (!isfinite(p.s)) {
            snprintf(err, errlen, "%s:%d: the scalar is not a finite number", path, lineno);
            status = VFP_ERR;
        } else if (!(p.r >= 0 && p.r <= 1 && p.g >= 0 && p.g <= 1 && p.b >= 0 && p.b <= 1 && p.a >= 0 && p.a <= 1)) {
            snprintf(err, errlen, "%s:%d: colour and opacity must be within [0, 1]", path, lineno);
            status = VFP_ERR;
        } else if (tf->count > 0 && p.s < tf->points[tf->count - 1].s) {
            snprintf(err, errlen, "%s:%d: scalar %g is below the previous point's %g (scalars must not decrease)",
                     path, lineno, p.s, tf->points[tf->count - 1].s);
            status = VFP_ERR;
        } else if (tf->count >= VF_MAX_TF_POINTS - 2) {
            snprintf(err, errlen, "%s:%d: more than %d control points", path, lineno, VF_MAX_TF_POINTS - 2);
            status = VFP_ERR;
        } else {
            tf->points[tf->count++] = p;
        }
    }
    free(text);
    if (status == VFP_OK && tf->count == 0) {
        snprintf(err, errlen, "%s: no control points (expected lines 'scalar r g b a')", path);
        status = VFP_ERR;
    }
    return status;
}

uint32_t vfp_tf_to_core(const vfp_tf_t *tf, const vfp_volume_t *vol, vf_window_t w, vf_tf_point_t *out)
{
    /* Each point's position in the scalar domain 0..255; a descending window reverses the order. */
    vfp_tf_point_t mapped[VF_MAX_TF_POINTS];
    int n = tf->count < VF_MAX_TF_POINTS - 2 ? tf->count : VF_MAX_TF_POINTS - 2;
    if (n <= 0) { /* an empty function is transparent everywhere */
        out[0] = (vf_tf_point_t){0, 0, 0, 0, 0};
        return 1;
    }
    double slope = vol && vol->slope != 0 ? vol->slope : 1, inter = vol ? vol->inter : 0;
    for (int i = 0; i < n; i++) {
        mapped[i] = tf->points[i];
        if (tf->data_units) {
            double raw = (tf->points[i].s - inter) / slope;
            mapped[i].s = (raw - w.lo) * 255.0 / ((double)w.hi - w.lo);
        } else {
            mapped[i].s = tf->points[i].s * 255.0;
        }
        mapped[i].s = mapped[i].s < -FAR_SCALAR ? -FAR_SCALAR : mapped[i].s > FAR_SCALAR ? FAR_SCALAR : mapped[i].s;
    }
    if (n > 1 && mapped[n - 1].s < mapped[0].s)
        for (int i = 0; i < n / 2; i++) {
            vfp_tf_point_t t = mapped[i];
            mapped[i] = mapped[n - 1 - i];
            mapped[n - 1 - i] = t;
        }

    /* Clip to [0, 255], adding edge points where the function continues outside. */
    vfp_tf_point_t kept[VF_MAX_TF_POINTS];
    int k = 0;
    if (mapped[0].s < 0) {
        kept[k] = (vfp_tf_point_t){0, eval(mapped, n, 0, 0), eval(mapped, n, 0, 1), eval(mapped, n, 0, 2),
                                   eval(mapped, n, 0, 3)};
        k++;
    }
    for (int i = 0; i < n; i++)
        if (mapped[i].s >= 0 && mapped[i].s <= 255)
            kept[k++] = mapped[i];
    if (mapped[n - 1].s > 255) {
        kept[k] = (vfp_tf_point_t){255, eval(mapped, n, 255, 0), eval(mapped, n, 255, 1), eval(mapped, n, 255, 2),
                                   eval(mapped, n, 255, 3)};
        k++;
    }
    if (k == 0) /* cannot happen (a point below 0 or above 255 adds an edge), but keep the core's contract */
        kept[k++] = (vfp_tf_point_t){0, 0, 0, 0, 0};

    for (int i = 0; i < k; i++) {
        double s = floor(kept[i].s * 256 + 0.5);
        out[i].scalar_q8 = (uint16_t)(s < 0 ? 0 : s > 65280 ? 65280 : s);
        out[i].r = (uint16_t)floor(kept[i].r * 65535 + 0.5);
        out[i].g = (uint16_t)floor(kept[i].g * 65535 + 0.5);
        out[i].b = (uint16_t)floor(kept[i].b * 65535 + 0.5);
        out[i].a = (uint16_t)floor(kept[i].a * 65535 + 0.5);
    }
    return (uint32_t)k;
}

void vfp_tf_move(vfp_tf_t *tf, const vfp_volume_t *vol, vf_window_t window, double shift, double scale)
{
    double centre = 0.5, width = 1;
    if (tf->data_units) {
        double slope = vol && vol->slope != 0 ? vol->slope : 1, inter = vol ? vol->inter : 0;
        double lo = window.lo * slope + inter, hi = window.hi * slope + inter;
        centre = (lo + hi) / 2;
        width = hi - lo;
    }
    for (int i = 0; i < tf->count; i++)
        tf->points[i].s = centre + shift * width + (tf->points[i].s - centre) * scale;
}

/* The function at x (right-continuous at steps), channel 0..3 = r, g, b, a. */
static double eval(const vfp_tf_point_t *p, int count, double x, int c)
{
    int i = -1;
    while (i + 1 < count && p[i + 1].s <= x)
        i++;
    if (i < 0)
        return channel(&p[0], c);
    if (i == count - 1)
        return channel(&p[i], c);
    double t = (x - p[i].s) / (p[i + 1].s - p[i].s);
    return channel(&p[i], c) + t * (channel(&p[i + 1], c) - channel(&p[i], c));
}

static double channel(const vfp_tf_point_t *p, int c)
{
    return c == 0 ? p->r : c == 1 ? p->g : c == 2 ? p->b : p->a;
}
