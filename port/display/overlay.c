/* SPDX-License-Identifier: MIT */
/* overlay.c: a 5x7 bitmap font drawn into any of the core's pixel formats, and the patient directions at the
 * picture's edges (see overlay.h). */
#include "overlay.h"

#include <stdint.h>
#include <string.h>

#define GLYPH_W 5
#define GLYPH_H 7
#define ADVANCE 6 /* a column of space between characters */
#define MARGIN 1  /* box around the text, in font pixels */

/* Seven rows of five bits each, the leftmost pixel in bit 4. */
typedef struct glyph {
    char c;
    uint8_t rows[GLYPH_H];
} glyph_t;

static const glyph_t font[] = {
    {'0', {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}}, {'1', {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'2', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}}, {'3', {0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e}},
    {'4', {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}}, {'5', {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}},
    {'6', {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}}, {'7', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}}, {'9', {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c}},
    {'A', {0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}}, {'B', {0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e}},
    {'C', {0x0e, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0e}}, {'D', {0x1c, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1c}},
    {'E', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f}}, {'F', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x10}},
    {'G', {0x0e, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0f}}, {'H', {0x11, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}},
    {'I', {0x0e, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e}}, {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0c}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}}, {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f}},
    {'M', {0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11}}, {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}}, {'P', {0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10}},
    {'Q', {0x0e, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0d}}, {'R', {0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11}},
    {'S', {0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e}}, {'T', {0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}}, {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0a, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0a}}, {'X', {0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0a, 0x04, 0x04, 0x04}}, {'Z', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1f}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}}, {',', {0x00, 0x00, 0x00, 0x00, 0x0c, 0x04, 0x08}},
    {':', {0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00}}, {'-', {0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00}}, {'=', {0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}}, {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}}, {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
    {'?', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04}},
};

static const uint8_t *glyph_rows(char c)
{
    if (c >= 'a' && c <= 'z')
        c = (char)(c - 'a' + 'A');
    for (size_t i = 0; i < sizeof font / sizeof font[0]; i++)
        if (font[i].c == c)
            return font[i].rows;
    return NULL; /* a space, or a character the font lacks: left blank */
}

/* One pixel of the upright picture at (x, y), mapped into the panel's buffer. */
static void plot(const vf_image_t *img, int rotation, int x, int y, uint8_t grey)
{
    int w = (int)img->width, h = (int)img->height, px, py;
    switch (rotation) {
    /* The panel turned clockwise by `rotation` carries buffer pixel (px, py) to where the upright (x, y) is. */
    case 90: px = y; py = h - 1 - x; break; /* the upright picture is the panel's height wide */
    case 180: px = w - 1 - x; py = h - 1 - y; break;
    case 270: px = w - 1 - y; py = x; break;
    default: px = x; py = y; break;
    }
    if (px < 0 || py < 0 || px >= w || py >= h)
        return;
    uint8_t *p = (uint8_t *)img->pixels + (size_t)py * img->stride + (size_t)px * vf_format_bytes(img->format);
    switch (img->format) {
    case VF_FORMAT_RGB565: {
        uint16_t v = (uint16_t)(((grey >> 3) << 11) | ((grey >> 2) << 5) | (grey >> 3));
        p[0] = (uint8_t)v;
        p[1] = (uint8_t)(v >> 8);
        break;
    }
    case VF_FORMAT_XRGB8888: p[0] = p[1] = p[2] = grey; p[3] = 0xff; break;
    default: p[0] = p[1] = p[2] = grey; break;
    }
}

int vfp_overlay_width(const char *text, int scale)
{
    return ((int)strlen(text) * ADVANCE - 1 + 2 * MARGIN) * scale;
}

int vfp_overlay_height(int scale)
{
    return (GLYPH_H + 2 * MARGIN) * scale;
}

void vfp_overlay_text(const vf_image_t *img, int rotation, int x, int y, int scale, const char *text)
{
    if (!img || !img->pixels || !text || scale < 1)
        return;
    int n = (int)strlen(text);
    for (int row = 0; row < GLYPH_H + 2 * MARGIN; row++)
        for (int col = 0; col < n * ADVANCE - 1 + 2 * MARGIN; col++) {
            int i = (col - MARGIN) / ADVANCE, gx = (col - MARGIN) % ADVANCE, gy = row - MARGIN;
            const uint8_t *rows = col >= MARGIN && i < n && gx < GLYPH_W && gy >= 0 && gy < GLYPH_H
                                      ? glyph_rows(text[i]) : NULL;
            uint8_t grey = rows && (rows[gy] >> (GLYPH_W - 1 - gx)) & 1 ? 0xff : 0x20;
            for (int sy = 0; sy < scale; sy++)
                for (int sx = 0; sx < scale; sx++)
                    plot(img, rotation, x + col * scale + sx, y + row * scale + sy, grey);
        }
}

void vfp_overlay_directions(const vf_image_t *img, int rotation, int scale, const char *right, const char *left,
                            const char *top, const char *bottom)
{
    if (!img || !img->pixels || scale < 1)
        return;
    int w = rotation % 180 ? (int)img->height : (int)img->width;
    int h = rotation % 180 ? (int)img->width : (int)img->height;
    int th = vfp_overlay_height(scale), pad = scale;
    /* Each at the middle of its edge, as radiology viewers place them; the frame-time lines start at the top left,
     * clear of the top edge's middle. */
    if (top && top[0])
        vfp_overlay_text(img, rotation, (w - vfp_overlay_width(top, scale)) / 2, pad, scale, top);
    if (bottom && bottom[0])
        vfp_overlay_text(img, rotation, (w - vfp_overlay_width(bottom, scale)) / 2, h - th - pad, scale, bottom);
    if (left && left[0])
        vfp_overlay_text(img, rotation, pad, (h - th) / 2, scale, left);
    if (right && right[0])
        vfp_overlay_text(img, rotation, w - vfp_overlay_width(right, scale) - pad, (h - th) / 2, scale, right);
}
