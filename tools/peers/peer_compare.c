/* SPDX-License-Identifier: MIT */
/*
 * peer_compare.c: two renderings of one scene compared for `make bench-peers`: the silhouettes (pixels
 * brighter than a threshold against the black background) as intersection over union, for A as it is and
 * mirrored (left-right, up-down, both), so that a camera convention shows itself as the flip with the best
 * overlap; the best whole-pixel shift of A after that flip (--shift N), which shows an offset between the two
 * cameras' centres; then the luminance difference after the chosen flip, and a side-by-side picture:
 * A flipped | B | the silhouettes (white both, red A only, green B only).
 * Not part of volfix: it links libpng only.
 */

/*********************
 *      INCLUDES
 *********************/
#include <errno.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/*********************
 *      DEFINES
 *********************/
#define MAX_SIDE 8192

/**********************
 *      TYPEDEFS
 **********************/
typedef struct image {
    int width, height;
    unsigned char *rgb; /* rows packed, 3 bytes a pixel */
} image_t;

typedef enum { FLIP_NONE, FLIP_LR, FLIP_UD, FLIP_BOTH, FLIP_COUNT, FLIP_BEST = -1 } flip_t;

typedef struct overlap {
    long a, b, both; /* silhouette pixels of A, of B, of both */
    double iou;
} overlap_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static int read_image(const char *path, image_t *img);
static int read_pnm(const char *path, FILE *f, image_t *img);
static int read_png(const char *path, FILE *f, image_t *img);
static int write_png(const char *path, const image_t *img);
static const unsigned char *pixel(const image_t *img, int x, int y, flip_t flip);
static int lum(const unsigned char *p);
static int inside(const unsigned char *p, int threshold);
static overlap_t overlap(const image_t *a, const image_t *b, flip_t flip, int dx, int dy, int threshold);
static double psnr_of(const image_t *a, const image_t *b, flip_t flip, int dx, int dy);

static const char *const flip_names[FLIP_COUNT] = {"none", "lr", "ud", "both"};

static const char usage[] =
    "usage: peer_compare A B [--threshold T] [--flip none|lr|ud|both] [--shift N] [-o SIDE.png] [--pair] [--json]\n"
    "Compare two images of one size (PNG, or binary PGM/PPM): the silhouettes (pixels whose brightest channel\n"
    "is above T, default 0) as intersection over union for A unflipped and mirrored; then, after the flip\n"
    "given (default: the one with the best overlap), the luminance difference; -o writes A flipped, B and the\n"
    "silhouettes (white both, red A only, green B only) side by side. --shift N also reports the whole-pixel\n"
    "shift of A, up to N pixels each way, whose silhouette overlaps B's best (A's pixel x+dx,y+dy on B's x,y),\n"
    "and the shift with the best luminance PSNR. --pair: -o writes A and B only.\n";

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

int main(int argc, char **argv)
{
    const char *path_a = NULL, *path_b = NULL, *out = NULL;
    int threshold = 0, json = 0, shift = 0, pair = 0;
    flip_t flip = FLIP_BEST;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (strcmp(a, "--threshold") == 0) {
            char *end;
            long t = v ? strtol(v, &end, 10) : -1;
            if (!v || *end || t < 0 || t > 254) {
                fprintf(stderr, "peer_compare: --threshold %s: expected a level from 0 to 254\n", v ? v : "(missing)");
                return 2;
            }
            threshold = (int)t;
            i++;
        } else if (strcmp(a, "--flip") == 0) {
            flip = FLIP_COUNT;
            for (int f = 0; v && f < FLIP_COUNT; f++)
                if (strcmp(v, flip_names[f]) == 0)
                    flip = (flip_t)f;
            if (flip == FLIP_COUNT) {
                fprintf(stderr, "peer_compare: --flip %s: expected none, lr, ud or both\n", v ? v : "(missing)");
                return 2;
            }
            i++;
        } else if (strcmp(a, "--shift") == 0) {
            char *end;
            long n = v ? strtol(v, &end, 10) : -1;
            if (!v || *end || n < 0 || n > 64) {
                fprintf(stderr, "peer_compare: --shift %s: expected pixels from 0 to 64\n", v ? v : "(missing)");
                return 2;
            }
            shift = (int)n;
            i++;
        } else if (strcmp(a, "-o") == 0 && v) {
            out = v;
            i++;
        } else if (strcmp(a, "--pair") == 0) {
            pair = 1;
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
        } else if (a[0] != '-' && !path_a) {
            path_a = a;
        } else if (a[0] != '-' && !path_b) {
            path_b = a;
        } else {
            fprintf(stderr, "peer_compare: %s: unknown option or argument (see --help)\n", a);
            return 2;
        }
    }
    if (!path_b) {
        fprintf(stderr, "peer_compare: expected two images (see --help)\n");
        return 2;
    }
    image_t a, b;
    if (read_image(path_a, &a) || read_image(path_b, &b))
        return 2;
    if (a.width != b.width || a.height != b.height) {
        fprintf(stderr, "peer_compare: %s is %dx%d, %s is %dx%d: expected one size\n", path_a, a.width, a.height,
                path_b, b.width, b.height);
        return 2;
    }

    overlap_t ov[FLIP_COUNT];
    int best = 0;
    for (int f = 0; f < FLIP_COUNT; f++) {
        ov[f] = overlap(&a, &b, (flip_t)f, 0, 0, threshold);
        if (ov[f].iou > ov[best].iou)
            best = f;
    }
    flip_t used = flip == FLIP_BEST ? (flip_t)best : flip;
    overlap_t shifted = ov[used];
    int best_dx = 0, best_dy = 0;
    for (int dy = -shift; dy <= shift; dy++)
        for (int dx = -shift; dx <= shift; dx++) {
            overlap_t o = overlap(&a, &b, used, dx, dy, threshold);
            if (o.iou > shifted.iou) {
                shifted = o;
                best_dx = dx;
                best_dy = dy;
            }
        }

    long sum = 0, same = 0, n = (long)a.width * a.height;
    double sum2 = 0;
    int max = 0;
    for (int y = 0; y < a.height; y++)
        for (int x = 0; x < a.width; x++) {
            int d = abs(lum(pixel(&a, x, y, used)) - lum(pixel(&b, x, y, FLIP_NONE)));
            sum += d;
            sum2 += (double)d * d;
            same += d == 0;
            max = d > max ? d : max;
        }

    /* PSNR of the luminance, 8-bit peak; identical images have none (infinite): reported as 999 */
    const double psnr = sum2 > 0 ? 10 * log10(255.0 * 255.0 * n / sum2) : 999;
    /* the luminance's own best whole-pixel shift (it may differ from the silhouettes') */
    double psnr_shifted = psnr;
    int psnr_dx = 0, psnr_dy = 0;
    for (int dy = -shift; dy <= shift; dy++)
        for (int dx = -shift; dx <= shift; dx++) {
            const double p = psnr_of(&a, &b, used, dx, dy);
            if (p > psnr_shifted) {
                psnr_shifted = p;
                psnr_dx = dx;
                psnr_dy = dy;
            }
        }
    if (json) {
        printf("{\"a\": \"%s\", \"b\": \"%s\", \"width\": %d, \"height\": %d, \"threshold\": %d, \"iou\": {", path_a,
               path_b, a.width, a.height, threshold);
        for (int f = 0; f < FLIP_COUNT; f++)
            printf("%s\"%s\": %.4f", f ? ", " : "", flip_names[f], ov[f].iou);
        printf("}, \"best_flip\": \"%s\", \"flip\": \"%s\", \"pixels_a\": %ld, \"pixels_b\": %ld, \"pixels_both\": %ld, "
               "\"mean_abs\": %.3f, \"max_abs\": %d, \"identical\": %.4f, \"psnr\": %.2f",
               flip_names[best], flip_names[used], ov[used].a, ov[used].b, ov[used].both, (double)sum / n, max,
               (double)same / n, psnr);
        if (shift)
            printf(", \"best_shift\": [%d, %d], \"iou_shifted\": %.4f, \"psnr_shift\": [%d, %d], \"psnr_shifted\": %.2f",
                   best_dx, best_dy, shifted.iou, psnr_dx, psnr_dy, psnr_shifted);
        printf("}\n");
    } else {
        printf("peer_compare: %s against %s, %dx%d, silhouette = brightest channel above %d\n", path_a, path_b,
               a.width, a.height, threshold);
        for (int f = 0; f < FLIP_COUNT; f++)
            printf("  A flipped %-4s: IoU %.4f (A %ld px, B %ld px, both %ld)%s\n", flip_names[f], ov[f].iou, ov[f].a,
                   ov[f].b, ov[f].both, f == best ? "  <- best" : "");
        if (shift)
            printf("  after flip %s, the best shift within %d px: A's x%+d,y%+d on B's x,y, IoU %.4f; the luminance's\n"
                   "  best: x%+d,y%+d, PSNR %.2f dB\n",
                   flip_names[used], shift, best_dx, best_dy, shifted.iou, psnr_dx, psnr_dy, psnr_shifted);
        printf("  after flip %s: luminance |A - B| mean %.3f, max %d of 255, %.2f%% of pixels identical, PSNR %.2f dB\n",
               flip_names[used], (double)sum / n, max, 100.0 * same / n, psnr);
    }

    int status = 0;
    if (out) {
        const int panels = pair ? 2 : 3;
        image_t side = {panels * a.width, a.height, malloc((size_t)3 * panels * a.width * a.height)};
        if (!side.rgb) {
            fprintf(stderr, "peer_compare: out of memory\n");
            return 2;
        }
        for (int y = 0; y < a.height; y++)
            for (int x = 0; x < a.width; x++) {
                const unsigned char *pa = pixel(&a, x, y, used), *pb = pixel(&b, x, y, FLIP_NONE);
                unsigned char *row = side.rgb + (size_t)y * side.width * 3;
                int in_a = inside(pa, threshold), in_b = inside(pb, threshold);
                unsigned char mask[3] = {(unsigned char)(in_a ? 255 : 0), (unsigned char)(in_b ? 255 : 0),
                                         (unsigned char)(in_a && in_b ? 255 : 0)};
                memcpy(row + 3 * x, pa, 3);
                memcpy(row + 3 * (a.width + x), pb, 3);
                if (!pair)
                    memcpy(row + 3 * (2 * a.width + x), mask, 3);
            }
        status = write_png(out, &side);
        free(side.rgb);
    }
    free(a.rgb);
    free(b.rgb);
    return status;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

static const unsigned char *pixel(const image_t *img, int x, int y, flip_t flip)
{
    if (flip == FLIP_LR || flip == FLIP_BOTH)
        x = img->width - 1 - x;
    if (flip == FLIP_UD || flip == FLIP_BOTH)
        y = img->height - 1 - y;
    return img->rgb + ((size_t)y * img->width + x) * 3;
}

/* The luminance PSNR (8-bit peak) of A flipped, its pixel x+dx,y+dy taken for B's x,y (outside A: black), against
 * B; 999 for identical images. */
static double psnr_of(const image_t *a, const image_t *b, flip_t flip, int dx, int dy)
{
    double sum2 = 0;
    for (int y = 0; y < b->height; y++)
        for (int x = 0; x < b->width; x++) {
            int xa = x + dx, ya = y + dy;
            int la = xa >= 0 && xa < a->width && ya >= 0 && ya < a->height ? lum(pixel(a, xa, ya, flip)) : 0;
            double d = la - lum(pixel(b, x, y, FLIP_NONE));
            sum2 += d * d;
        }
    return sum2 > 0 ? 10 * log10(255.0 * 255.0 * b->width * b->height / sum2) : 999;
}

/* Silhouettes of A (flipped, then its pixel x+dx,y+dy taken for B's x,y; outside A is background) and B. */
static overlap_t overlap(const image_t *a, const image_t *b, flip_t flip, int dx, int dy, int threshold)
{
    overlap_t o = {0, 0, 0, 0};
    for (int y = 0; y < b->height; y++)
        for (int x = 0; x < b->width; x++) {
            int xa = x + dx, ya = y + dy;
            int in_a = xa >= 0 && xa < a->width && ya >= 0 && ya < a->height &&
                       inside(pixel(a, xa, ya, flip), threshold);
            int in_b = inside(pixel(b, x, y, FLIP_NONE), threshold);
            o.a += in_a;
            o.b += in_b;
            o.both += in_a && in_b;
        }
    long either = o.a + o.b - o.both;
    o.iou = either ? (double)o.both / either : 1.0;
    return o;
}

/* Rec. 601 luma, 0..255. */
static int lum(const unsigned char *p)
{
    return (299 * p[0] + 587 * p[1] + 114 * p[2] + 500) / 1000;
}

static int inside(const unsigned char *p, int threshold)
{
    return p[0] > threshold || p[1] > threshold || p[2] > threshold;
}

/* 0, or 2 with a message naming the file. */
static int read_image(const char *path, image_t *img)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "peer_compare: %s: cannot open: %s\n", path, strerror(errno));
        return 2;
    }
    int c = getc(f);
    ungetc(c, f);
    int status = c == 'P' ? read_pnm(path, f, img) : read_png(path, f, img);
    fclose(f);
    return status;
}

/* Binary PGM (P5) or PPM (P6), 8-bit: VolPack's example writes its images so. */
static int read_pnm(const char *path, FILE *f, image_t *img)
{
    char magic[3] = {0};
    int maxval;
    if (fscanf(f, "%2s %d %d %d", magic, &img->width, &img->height, &maxval) != 4 ||
        (strcmp(magic, "P5") != 0 && strcmp(magic, "P6") != 0) || maxval != 255 || img->width < 1 ||
        img->height < 1 || img->width > MAX_SIDE || img->height > MAX_SIDE || getc(f) == EOF) {
        fprintf(stderr, "peer_compare: %s: expected a binary 8-bit PGM (P5) or PPM (P6) of at most %dx%d\n", path,
                MAX_SIDE, MAX_SIDE);
        return 2;
    }
    int channels = magic[1] == '5' ? 1 : 3;
    size_t n = (size_t)img->width * img->height;
    img->rgb = malloc(n * 3);
    if (!img->rgb || fread(img->rgb, (size_t)channels, n, f) != n) {
        fprintf(stderr, "peer_compare: %s: %s\n", path, img->rgb ? "shorter than its header says" : "out of memory");
        free(img->rgb);
        return 2;
    }
    for (size_t i = n; channels == 1 && i-- > 0;)
        img->rgb[3 * i] = img->rgb[3 * i + 1] = img->rgb[3 * i + 2] = img->rgb[i];
    return 0;
}

/* Any PNG, expanded or reduced to 8-bit RGB. */
static int read_png(const char *path, FILE *f, image_t *img)
{
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    unsigned char *volatile rgb = NULL;
    if (!info || setjmp(png_jmpbuf(png))) {
        fprintf(stderr, "peer_compare: %s: not a readable PNG (or binary PGM/PPM)\n", path);
        png_destroy_read_struct(&png, &info, NULL);
        free(rgb);
        return 2;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_strip_alpha(png);
    png_set_gray_to_rgb(png);
    png_read_update_info(png, info);
    png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
    if (w < 1 || h < 1 || w > MAX_SIDE || h > MAX_SIDE || png_get_rowbytes(png, info) != w * 3) {
        fprintf(stderr, "peer_compare: %s: expected an image of at most %dx%d\n", path, MAX_SIDE, MAX_SIDE);
        png_destroy_read_struct(&png, &info, NULL);
        return 2;
    }
    rgb = malloc((size_t)w * h * 3);
    if (!rgb)
        png_error(png, "out of memory");
    for (png_uint_32 y = 0; y < h; y++)
        png_read_row(png, rgb + (size_t)y * w * 3, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    img->width = (int)w;
    img->height = (int)h;
    img->rgb = rgb;
    return 0;
}

static int write_png(const char *path, const image_t *img)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "peer_compare: %s: cannot write: %s\n", path, strerror(errno));
        return 2;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info || setjmp(png_jmpbuf(png))) {
        fprintf(stderr, "peer_compare: %s: PNG write failed\n", path);
        png_destroy_write_struct(&png, &info);
        fclose(f);
        return 2;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)img->width, (png_uint_32)img->height, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < img->height; y++)
        png_write_row(png, img->rgb + (size_t)y * img->width * 3);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    if (fclose(f)) {
        fprintf(stderr, "peer_compare: %s: cannot write: %s\n", path, strerror(errno));
        return 2;
    }
    return 0;
}
