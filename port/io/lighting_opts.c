/* SPDX-License-Identifier: MIT */
/* lighting_opts.c: the lighting options of volfix-sim and volfix, and the lighting they make (see
 * lighting_opts.h). */
#include "lighting_opts.h"
#include "numbers.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char vfp_lighting_help[] = VFP_LIGHTING_HELP;

/* Degrees to binary angle units (65536 a turn), as the view's angles. */
static int32_t bau(double degrees)
{
    return (int32_t)lround(degrees * VF_BAU_PER_TURN / 360.0);
}

static double degrees(int32_t angle)
{
    return angle * 360.0 / VF_BAU_PER_TURN;
}

static uint16_t unorm16(double v)
{
    return (uint16_t)lround(v * 65535);
}

/* Exactly `count` finite numbers separated by commas, nothing else: the one numeric form these options take
 * (numbers.h, shared with every other option of both programs). */
static int number_list(const char *text, double *out, int count)
{
    return vfp_parse_list(text, out, count, count) == count ? 0 : -1;
}

static vfp_status_t expected(char *err, size_t errlen, const char *form)
{
    snprintf(err, errlen, "expected %s", form);
    return VFP_ERR;
}

void vfp_lighting_opts_init(vfp_lighting_opts_t *o)
{
    memset(o, 0, sizeof *o);
    o->shade = -1;
    o->shade_lookup = -1;
}

vfp_status_t vfp_parse_shade(const char *text, int *shade, char *err, size_t errlen)
{
    if (text && strcmp(text, "none") == 0)
        *shade = 0;
    else if (text && strcmp(text, "phong") == 0)
        *shade = 1;
    else
        return expected(err, errlen, "none or phong");
    return VFP_OK;
}

vfp_status_t vfp_parse_light(const char *text, double light[2], char *err, size_t errlen)
{
    double v[2];
    if (number_list(text, v, 2) || !(v[0] >= -360 && v[0] <= 360) || !(v[1] >= -90 && v[1] <= 90))
        return expected(err, errlen, "AZ,EL in degrees, azimuth -360..360 and elevation -90..90");
    light[0] = v[0], light[1] = v[1];
    return VFP_OK;
}

vfp_status_t vfp_parse_material(const char *text, double k[3], int *shininess, char *err, size_t errlen)
{
    double v[4];
    if (number_list(text, v, 4) || !(v[0] >= 0 && v[0] <= 1) || !(v[1] >= 0 && v[1] <= 1) ||
        !(v[2] >= 0 && v[2] <= 1) || !(v[3] >= 1 && v[3] <= 255) || v[3] != floor(v[3]))
        return expected(err, errlen, "KA,KD,KS,N: ambient, diffuse and specular in [0, 1], shininess an integer "
                                     "1..255");
    k[0] = v[0], k[1] = v[1], k[2] = v[2];
    *shininess = (int)v[3];
    return VFP_OK;
}

vfp_status_t vfp_parse_gradient_opacity(const char *text, int *lo, int *hi, char *err, size_t errlen)
{
    double v[2];
    if (number_list(text, v, 2) || v[0] != floor(v[0]) || v[1] != floor(v[1]) || !(v[0] >= 0 && v[1] <= 255) ||
        !(v[0] < v[1]))
        return expected(err, errlen, "LO,HI: 8-bit gradient magnitudes, integers with 0 <= LO < HI <= 255");
    *lo = (int)v[0], *hi = (int)v[1];
    return VFP_OK;
}

vfp_status_t vfp_parse_normal_bits(const char *text, int *bits, char *err, size_t errlen)
{
    double v;
    if (number_list(text, &v, 1) || !(v == 8 || v == 10 || v == 12 || v == 14 || v == 16))
        return expected(err, errlen, "8, 10, 12, 14 or 16");
    *bits = (int)v;
    return VFP_OK;
}

vfp_status_t vfp_parse_shade_lookup(const char *text, int *lookup, char *err, size_t errlen)
{
    if (text && strcmp(text, "nearest") == 0)
        *lookup = VF_LOOKUP_NEAREST;
    else if (text && strcmp(text, "bilinear") == 0)
        *lookup = VF_LOOKUP_BILINEAR;
    else
        return expected(err, errlen, "nearest or bilinear");
    return VFP_OK;
}

int vfp_lighting_option(vfp_lighting_opts_t *o, const char *program, const char *option, const char *value)
{
    char err[160];
    vfp_status_t status;
    if (strcmp(option, "--shade") == 0) {
        status = vfp_parse_shade(value, &o->shade, err, sizeof err);
    } else if (strcmp(option, "--light") == 0) {
        if (o->light_count == VF_MAX_LIGHTS) {
            fprintf(stderr, "%s: --light %s: at most %d lights\n", program, value ? value : "(missing)",
                    VF_MAX_LIGHTS);
            return -1;
        }
        status = vfp_parse_light(value, o->light[o->light_count], err, sizeof err);
        o->light_count += status == VFP_OK;
    } else if (strcmp(option, "--material") == 0) {
        double k[3];
        status = vfp_parse_material(value, k, &o->shininess, err, sizeof err);
        if (status == VFP_OK)
            o->have_material = 1, o->ka = k[0], o->kd = k[1], o->ks = k[2];
    } else if (strcmp(option, "--gradient-opacity") == 0) {
        status = vfp_parse_gradient_opacity(value, &o->gradient_lo, &o->gradient_hi, err, sizeof err);
    } else if (strcmp(option, "--normal-bits") == 0) {
        status = vfp_parse_normal_bits(value, &o->normal_bits, err, sizeof err);
    } else if (strcmp(option, "--shade-lookup") == 0) {
        status = vfp_parse_shade_lookup(value, &o->shade_lookup, err, sizeof err);
    } else {
        return 0;
    }
    if (status == VFP_OK)
        return 1;
    fprintf(stderr, "%s: %s %s: %s\n", program, option, value ? value : "(missing)", err);
    return -1;
}

vfp_status_t vfp_lighting_check(const vfp_lighting_opts_t *o, char *err, size_t errlen)
{
    if (o->shade == 0 && (o->light_count || o->have_material)) {
        snprintf(err, errlen, "--%s goes with --shade phong, not --shade none", o->light_count ? "light" : "material");
        return VFP_ERR;
    }
    return VFP_OK;
}

void vfp_lighting_resolve(const vfp_lighting_opts_t *o, const vfp_tf_t *tf, vf_params_t *params,
                          vf_lighting_t *l)
{
    const vfp_tf_look_t *look = tf ? &tf->look : NULL;
    vf_lighting_default(l);
    int shade = o->shade >= 0                          ? o->shade
                : o->light_count || o->have_material  ? 1
                : look && look->shade >= 0            ? look->shade
                                                       : 0;
    l->shade = shade != 0;
    if (o->light_count) {
        l->light_count = (uint32_t)o->light_count;
        for (int k = 0; k < o->light_count; k++)
            l->lights[k] = (vf_light_t){bau(o->light[k][0]), bau(o->light[k][1])};
    }
    if (o->have_material) {
        l->ka = unorm16(o->ka), l->kd = unorm16(o->kd), l->ks = unorm16(o->ks);
        l->shininess = (uint16_t)o->shininess;
    } else if (look && look->have_material) {
        l->ka = unorm16(look->ka), l->kd = unorm16(look->kd), l->ks = unorm16(look->ks);
        l->shininess = (uint16_t)look->shininess;
    }
    l->gradient_lo = (uint8_t)o->gradient_lo;
    l->gradient_hi = (uint8_t)o->gradient_hi;
    params->lighting = l->shade || l->gradient_hi > l->gradient_lo;
    if (o->normal_bits)
        params->normal_bits = (uint32_t)o->normal_bits;
    if (o->shade_lookup >= 0)
        params->shade_lookup = (vf_lookup_t)o->shade_lookup;
}

/* an angle in degrees to two decimals (the angles are quantised to 1/65536 turn) */
static double two_places(int32_t angle)
{
    return round(degrees(angle) * 100) / 100;
}

void vfp_lighting_describe(const vf_params_t *p, const vf_lighting_t *l, char *text, size_t len)
{
    size_t at = 0;
    text[0] = 0;
    if (!p->lighting)
        return;
    if (l->shade) {
        at += (size_t)snprintf(text + at, len - at, " phong light");
        for (uint32_t k = 0; k < l->light_count && at < len; k++)
            at += (size_t)snprintf(text + at, len - at, "%s%g,%g", k ? "+" : " ", two_places(l->lights[k].azimuth),
                                   two_places(l->lights[k].elevation));
        if (at < len)
            at += (size_t)snprintf(text + at, len - at, " material %.3g,%.3g,%.3g,%u normals %u bits, %s shade",
                                   l->ka / 65535.0, l->kd / 65535.0, l->ks / 65535.0, l->shininess, p->normal_bits,
                                   vf_lookup_name(p->shade_lookup));
    } else {
        at += (size_t)snprintf(text + at, len - at, " unshaded");
    }
    if (at < len && l->gradient_hi > l->gradient_lo)
        snprintf(text + at, len - at, " gradient-opacity %u,%u", l->gradient_lo, l->gradient_hi);
}

void vfp_lighting_args(const vf_params_t *p, const vf_lighting_t *l, char *text, size_t len)
{
    size_t at = 0;
    if (!p->lighting || !l->shade)
        at += (size_t)snprintf(text, len, " --shade none");
    else {
        at += (size_t)snprintf(text, len, " --shade phong");
        for (uint32_t k = 0; k < l->light_count && at < len; k++)
            at += (size_t)snprintf(text + at, len - at, " --light %.17g,%.17g", degrees(l->lights[k].azimuth),
                                   degrees(l->lights[k].elevation));
        if (at < len)
            at += (size_t)snprintf(text + at, len - at, " --material %.17g,%.17g,%.17g,%u", l->ka / 65535.0,
                                   l->kd / 65535.0, l->ks / 65535.0, l->shininess);
    }
    if (at < len && p->lighting && l->gradient_hi > l->gradient_lo)
        at += (size_t)snprintf(text + at, len - at, " --gradient-opacity %u,%u", l->gradient_lo, l->gradient_hi);
    if (at < len && p->lighting)
        snprintf(text + at, len - at, " --normal-bits %u --shade-lookup %s", p->normal_bits,
                 vf_lookup_name(p->shade_lookup));
}
