/* SPDX-License-Identifier: MIT */
/*
 * volpack_peer.c: volfix's own client of VolPack's public API (Debian's libvolpack1-dev, VolPack 1.0b3), so
 * that `make bench-peers` can render volfix's benchmark scenes with VolPack in the same run and on the same
 * machine. Not part of volfix: it links VolPack, zlib and libpng and nothing of volfix's.
 *
 * It loads 8-bit voxels, classifies them once with VolPack's own classifier as its examples do
 * (vpVolumeNormals for the gradient and the encoded normals, vpSetClassifierTable on the scalar,
 * vpClassifyVolume), then renders the preclassified, run-length encoded volume with
 * vpRenderClassifiedVolume. Two shadings:
 *   phong  one luminance channel: a white material lit by one directional light through the shade table that
 *          vpShadeTable computes for each view (VolPack's own example's lighting);
 *   rgb    unshaded: three colour channels indexed by the scalar, straight from the transfer function.
 * The view: rotation A degrees about the volume's y axis (then --tilt about x), a parallel window of +-W,
 * which shows image_width / (2 W N) pixels per voxel, N the largest dimension (VolPack scales the volume to
 * a unit cube by N).
 *
 * Timing follows volfix-sim bench: each round renders a warm-up frame one step before the first view, then
 * the frames (CLOCK_MONOTONIC around each); the round's mean, and the median of the rounds' means. The work
 * of one view is peer_frame (the view, the Phong shade table, the render), so that callgrind can count it
 * alone: valgrind --tool=callgrind --toggle-collect=peer_frame --dump-after=peer_frame.
 */

/*********************
 *      INCLUDES
 *********************/
#include <errno.h>
#include <math.h>
#include <png.h>
#include <malloc.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <volpack.h>
#include <zlib.h>

/*********************
 *      DEFINES
 *********************/
/* volfix's early termination (core/render.h, VFI_OPAQUE_Q15): a ray stops at an opacity of 1 - 2^-10. */
#define VOLFIX_OPAQUE (1.0 - 1.0 / 1024.0)
#define MAX_DIM 4096
#define MAX_TF_POINTS 64
#define MAX_ROUNDS 1000
#define SCALAR_MAX 255

/* The voxel: a 16-bit shading index, the scalar, its gradient magnitude (VolPack's example layout). Only the
 * shading field goes into the classified volume, with the opacity. VolPack's lookup shader takes a 16-bit
 * index only: the encoded normal for phong, a copy of the scalar for rgb. */
typedef struct voxel {
    uint16_t shade;
    uint8_t scalar, gradient;
} voxel_t;
enum { FIELD_SHADE, FIELD_SCALAR, FIELD_GRADIENT, FIELD_COUNT };

/* VolPack's example classification (its examples/volume.h): opacity = density ramp x gradient-magnitude ramp. */
static const int check_density_x[] = {0, 24, 255};
static const float check_density_y[] = {0.0f, 1.0f, 1.0f};
static const int check_gradient_x[] = {0, 5, 20, 221};
static const float check_gradient_y[] = {0.0f, 0.0f, 1.0f, 1.0f};

/**********************
 *      TYPEDEFS
 **********************/
typedef enum { SHADE_PHONG, SHADE_RGB } shading_t;

typedef struct tf_point {
    double s, r, g, b, a;
} tf_point_t;

typedef struct options {
    const char *volume, *tf_file, *out, *save;
    const char *volfix_tf; /* --check: write volfix's transfer function of the example's classification here */
    int dims[3], have_dims;
    int check;            /* VolPack's example classification instead of a transfer function */
    shading_t shading;
    int width, height;
    double window;        /* parallel view window +-window */
    double angle, tilt;   /* first view: degrees about y, then about x */
    double step;          /* degrees from one frame to the next */
    int frames, rounds;
    double max_opacity, min_opacity;
    int depth_cue, json;
} options_t;

typedef struct peer {
    vpContext *vpc;
    shading_t shading;
    double tilt;
    int width, height, channels;
    unsigned char *image;
    voxel_t *voxels;      /* VolPack's raw voxel array (it classifies from it) */
    float *shade_table;   /* phong: one luminance per encoded normal, refilled per view by vpShadeTable */
    float *color_table;   /* rgb: three channels per scalar, 0..255, from the transfer function */
    float opacity_table[SCALAR_MAX + 1];
    float gradient_table[VP_GRAD_MAX + 1];
    size_t classified_bytes; /* what vpClassifyVolume kept on the heap: the three run-length encoded copies */
} peer_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static int usage_error(const char *option, const char *value, const char *expected);
static int parse_options(options_t *o, int argc, char **argv);
static unsigned char *load_volume(const options_t *o, int dims[3]);
static unsigned char *boxes(int dims[3]);
static int save_volume(const char *path, const unsigned char *voxels, const int dims[3]);
static int write_volfix_check(const char *path, const unsigned char *voxels, const int dims[3]);
static int load_tf(const char *path, tf_point_t *points, int *count);
static double tf_eval(const tf_point_t *p, int count, double s, int channel);
static int vp_check(vpResult result, const char *what);
static int setup(peer_t *p, const options_t *o, unsigned char *voxels, const int dims[3]);
static int write_png(const char *path, const peer_t *p);
static double now_ms(void);
static int by_value(const void *a, const void *b);
int peer_frame(peer_t *p, double angle);

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

int main(int argc, char **argv)
{
    options_t o;
    int status = parse_options(&o, argc, argv);
    if (status)
        return status == 1 ? 0 : status;
    int dims[3];
    unsigned char *voxels = load_volume(&o, dims);
    if (!voxels)
        return 2;
    if ((o.save && save_volume(o.save, voxels, dims)) ||
        (o.volfix_tf && write_volfix_check(o.volfix_tf, voxels, dims))) {
        free(voxels);
        return 2;
    }
    peer_t p;
    double t0 = now_ms();
    status = setup(&p, &o, voxels, dims);
    double classify_ms = now_ms() - t0;
    free(voxels); /* VolPack's voxel array holds its own copy of the scalars */
    if (status)
        return status;

    if (o.out) {
        status = peer_frame(&p, o.angle) || write_png(o.out, &p) ? 2 : 0;
    } else {
        double *mean = calloc((size_t)o.rounds, sizeof *mean);
        double *frame_ms = calloc((size_t)o.rounds * o.frames, sizeof *frame_ms);
        if (!mean || !frame_ms) {
            fprintf(stderr, "volpack_peer: out of memory for %d rounds of %d frames\n", o.rounds, o.frames);
            return 2;
        }
        for (int r = 0; r < o.rounds && status == 0; r++) {
            status = peer_frame(&p, o.angle - o.step); /* warm-up: every timed frame is a new view */
            double sum = 0;
            for (int f = 0; f < o.frames && status == 0; f++) {
                double start = now_ms();
                status = peer_frame(&p, o.angle + o.step * f);
                frame_ms[(size_t)r * o.frames + f] = now_ms() - start;
                sum += frame_ms[(size_t)r * o.frames + f];
            }
            mean[r] = sum / o.frames;
        }
        if (status == 0) {
            double *sorted = malloc(sizeof *sorted * (size_t)o.rounds);
            if (!sorted)
                return 2;
            memcpy(sorted, mean, sizeof *sorted * (size_t)o.rounds);
            qsort(sorted, (size_t)o.rounds, sizeof *sorted, by_value);
            int n = o.rounds;
            double median = n % 2 ? sorted[n / 2] : (sorted[n / 2 - 1] + sorted[n / 2]) / 2;
            qsort(frame_ms, (size_t)n * o.frames, sizeof *frame_ms, by_value);
            size_t nf = (size_t)n * o.frames;
            double median_frame = nf % 2 ? frame_ms[nf / 2] : (frame_ms[nf / 2 - 1] + frame_ms[nf / 2]) / 2;
            const char *shading = o.shading == SHADE_PHONG ? "phong" : "rgb";
            if (o.json) {
                printf("{\"renderer\": \"volpack\", \"shading\": \"%s\", \"volume\": \"%s\", \"dims\": [%d, %d, %d], "
                       "\"size\": [%d, %d], \"window\": %.4f, \"angle\": %.2f, \"step\": %.2f, \"frames\": %d, "
                       "\"rounds\": %d, \"max_ray_opacity\": %.10f, \"ms_per_frame\": %.3f, "
                       "\"ms_per_frame_rounds\": [",
                       shading, o.volume, dims[0], dims[1], dims[2], o.width, o.height, o.window, o.angle, o.step,
                       o.frames, o.rounds, o.max_opacity, median);
                for (int r = 0; r < n; r++)
                    printf("%s%.3f", r ? ", " : "", mean[r]);
                printf("], \"median_ms\": %.3f, \"classify_ms\": %.1f, \"classified_bytes\": %zu}\n", median_frame,
                       classify_ms, p.classified_bytes);
            } else {
                printf("VolPack %s, %s %dx%dx%d, %dx%d, window +-%.4f, %d frames from %.1f deg in steps of %.1f, "
                       "%d round%s: %.2f ms per frame (median of the rounds' means), median frame %.2f ms; "
                       "classification %.0f ms, %zu bytes\n",
                       shading, o.volume, dims[0], dims[1], dims[2], o.width, o.height, o.window, o.frames, o.angle,
                       o.step, n, n > 1 ? "s" : "", median, median_frame, classify_ms, p.classified_bytes);
            }
            free(sorted);
        }
        free(mean);
        free(frame_ms);
    }
    vpDestroyContext(p.vpc);
    free(p.image);
    free(p.voxels);
    free(p.shade_table);
    free(p.color_table);
    return status;
}

/* One view: the model matrix, the shade table for it (phong), the render. Not static and not inlined, so
 * that callgrind can name it; 0, or 2 with VolPack's message on stderr. */
__attribute__((noinline)) int peer_frame(peer_t *p, double angle)
{
    vpContext *vpc = p->vpc;
    if (vp_check(vpCurrentMatrix(vpc, VP_MODEL), "vpCurrentMatrix") ||
        vp_check(vpIdentityMatrix(vpc), "vpIdentityMatrix") ||
        vp_check(vpRotate(vpc, VP_Y_AXIS, angle), "vpRotate") ||
        (p->tilt != 0 && vp_check(vpRotate(vpc, VP_X_AXIS, p->tilt), "vpRotate")))
        return 2;
    if (p->shading == SHADE_PHONG && vp_check(vpShadeTable(vpc), "vpShadeTable"))
        return 2;
    return vp_check(vpRenderClassifiedVolume(vpc), "vpRenderClassifiedVolume");
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

static const char usage[] =
    "usage: volpack_peer VOLUME [--dims X,Y,Z] (--tf FILE | --check) [options] [-o OUT.png]\n"
    "Render VOLUME with VolPack (vpClassifyVolume, vpRenderClassifiedVolume) and time a turn about the\n"
    "vertical (y) axis, or write one view as PNG with -o.\n\n"
    "  VOLUME            a VolPack .den file, or raw 8-bit voxels (x fastest; gzip-compressed or not) with --dims,\n"
    "                    or 'boxes': a 128x128x84 phantom with no symmetry, for camera checks (a box of 120, a\n"
    "                    block of 255 on its +z face near -x, -y, a block of 200 on its +x face near +y, -z)\n"
    "  --save FILE       also write the voxels as raw 8-bit data (for volfix-sim --dims X,Y,Z --type uint8)\n"
    "  --tf FILE         volfix transfer-function file ('scalar r g b a' per line, scalars normalised to\n"
    "                    0..255); opacity per unit length, which VolPack corrects for each view's slab length\n"
    "  --check           VolPack's example classification instead (density ramp x gradient-magnitude ramp); sets\n"
    "                    its view too: window 0.5, 256x256, --angle 130 --tilt -15, max ray opacity 0.95, min\n"
    "                    voxel opacity 0.05 (later options override them)\n"
    "  --shading S       phong (default: luminance, white material, one light, shade table per view) or rgb\n"
    "                    (unshaded colour from the transfer function)\n"
    "  --size WxH        image size (default 512x512)\n"
    "  --window W        parallel view window +-W in VolPack's unit-cube coordinates (default 0.75)\n"
    "  --angle A         first view: A degrees about y (default 0)\n"
    "  --tilt X          then X degrees about x (default 0)\n"
    "  --frames N        frames to time (default 90), --step S degrees apart (default 2)\n"
    "  --rounds N        rounds of the turn, a warm-up frame before each (default 1)\n"
    "  --max-opacity X   VP_MAX_RAY_OPACITY, early ray termination (default 1 - 2^-10, volfix's)\n"
    "  --min-opacity X   VP_MIN_VOXEL_OPACITY (default 0)\n"
    "  --depth-cue       VolPack's example depth cueing (front factor 1.4, density 1.5)\n"
    "  --volfix-tf FILE  with --check: also write the example's classification for volfix (a .tf file of its\n"
    "                    density ramp, white, with its material) and print volfix's matching\n"
    "                    '--gradient-opacity LO,HI' (its ramp in volfix's 8-bit magnitudes of this volume)\n"
    "  -o FILE           render the view at --angle into an 8-bit RGB PNG instead of timing\n"
    "  --json            one JSON object\n";

static int usage_error(const char *option, const char *value, const char *expected)
{
    fprintf(stderr, "volpack_peer: %s %s: expected %s\n", option, value ? value : "(missing)", expected);
    return 2;
}

static int parse_number(const char *text, double *out)
{
    char *end;
    if (!text || !*text)
        return -1;
    errno = 0;
    *out = strtod(text, &end);
    return *end || errno || !isfinite(*out) ? -1 : 0;
}

/* 0, 1 for --help, or 2 with a message. */
static int parse_options(options_t *o, int argc, char **argv)
{
    memset(o, 0, sizeof *o);
    o->shading = SHADE_PHONG;
    o->width = o->height = 512;
    o->window = 0.75;
    o->step = 2;
    o->frames = 90;
    o->rounds = 1;
    o->max_opacity = VOLFIX_OPAQUE;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        double x;
        int takes = 1;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return 1;
        } else if (a[0] != '-' && !o->volume) {
            o->volume = a;
            takes = 0;
        } else if (strcmp(a, "--dims") == 0) {
            char extra;
            if (!v || sscanf(v, "%d,%d,%d%c", &o->dims[0], &o->dims[1], &o->dims[2], &extra) != 3 ||
                o->dims[0] < 2 || o->dims[1] < 2 || o->dims[2] < 2 || o->dims[0] > MAX_DIM ||
                o->dims[1] > MAX_DIM || o->dims[2] > MAX_DIM)
                return usage_error(a, v, "X,Y,Z, each 2..4096");
            o->have_dims = 1;
        } else if (strcmp(a, "--tf") == 0 && v) {
            o->tf_file = v;
        } else if (strcmp(a, "--check") == 0) {
            o->check = 1;
            o->window = 0.5;
            o->width = o->height = 256;
            o->angle = 130;
            o->tilt = -15;
            o->max_opacity = 0.95;
            o->min_opacity = 0.05;
            takes = 0;
        } else if (strcmp(a, "--shading") == 0) {
            if (v && strcmp(v, "phong") == 0)
                o->shading = SHADE_PHONG;
            else if (v && strcmp(v, "rgb") == 0)
                o->shading = SHADE_RGB;
            else
                return usage_error(a, v, "phong or rgb");
        } else if (strcmp(a, "--size") == 0) {
            char extra;
            if (!v || sscanf(v, "%dx%d%c", &o->width, &o->height, &extra) != 2 || o->width < 1 || o->height < 1 ||
                o->width > 8192 || o->height > 8192)
                return usage_error(a, v, "WxH, each 1..8192");
        } else if (strcmp(a, "--window") == 0) {
            if (parse_number(v, &o->window) || !(o->window > 0))
                return usage_error(a, v, "a half-width above 0");
        } else if (strcmp(a, "--angle") == 0) {
            if (parse_number(v, &o->angle))
                return usage_error(a, v, "an angle in degrees");
        } else if (strcmp(a, "--tilt") == 0) {
            if (parse_number(v, &o->tilt))
                return usage_error(a, v, "an angle in degrees");
        } else if (strcmp(a, "--step") == 0) {
            if (parse_number(v, &o->step))
                return usage_error(a, v, "an angle in degrees");
        } else if (strcmp(a, "--frames") == 0) {
            if (parse_number(v, &x) || x != (int)x || x < 1 || x > 100000)
                return usage_error(a, v, "a number of frames, 1..100000");
            o->frames = (int)x;
        } else if (strcmp(a, "--rounds") == 0) {
            if (parse_number(v, &x) || x != (int)x || x < 1 || x > MAX_ROUNDS)
                return usage_error(a, v, "a number of rounds, 1..1000");
            o->rounds = (int)x;
        } else if (strcmp(a, "--max-opacity") == 0) {
            if (parse_number(v, &o->max_opacity) || !(o->max_opacity > 0 && o->max_opacity <= 1))
                return usage_error(a, v, "an opacity above 0, at most 1");
        } else if (strcmp(a, "--min-opacity") == 0) {
            if (parse_number(v, &o->min_opacity) || !(o->min_opacity >= 0 && o->min_opacity < 1))
                return usage_error(a, v, "an opacity from 0, below 1");
        } else if (strcmp(a, "--depth-cue") == 0) {
            o->depth_cue = 1;
            takes = 0;
        } else if (strcmp(a, "-o") == 0 && v) {
            o->out = v;
        } else if (strcmp(a, "--save") == 0 && v) {
            o->save = v;
        } else if (strcmp(a, "--volfix-tf") == 0 && v) {
            o->volfix_tf = v;
        } else if (strcmp(a, "--json") == 0) {
            o->json = 1;
            takes = 0;
        } else {
            fprintf(stderr, "volpack_peer: %s: unknown option, or its value is missing (see --help)\n", a);
            return 2;
        }
        i += takes;
    }
    if (!o->volume) {
        fprintf(stderr, "volpack_peer: no volume given (see --help)\n");
        return 2;
    }
    if (!o->check == !o->tf_file) {
        fprintf(stderr, "volpack_peer: give --tf FILE or --check, one of them\n");
        return 2;
    }
    if (o->volfix_tf && !o->check) {
        fprintf(stderr, "volpack_peer: --volfix-tf %s: goes with --check (it writes the example's classification)\n",
                o->volfix_tf);
        return 2;
    }
    if (o->check && o->shading != SHADE_PHONG) {
        fprintf(stderr, "volpack_peer: --check goes with --shading phong: VolPack's example is lit\n");
        return 2;
    }
    return 0;
}

/* The voxels (malloc'd), or NULL with a message. A .den file carries its dimensions in its 62-byte header
 * (little-endian: version 1, ..., map_len[3] at byte 50, map_length at 58); anything else is raw 8-bit data of
 * --dims, read through zlib, which passes a file that is not gzip-compressed through unchanged. */
static unsigned char *load_volume(const options_t *o, int dims[3])
{
    const char *path = o->volume;
    if (strcmp(path, "boxes") == 0)
        return boxes(dims);
    size_t len = strlen(path);
    int den = len > 4 && strcmp(path + len - 4, ".den") == 0;
    gzFile f = gzopen(path, "rb");
    if (!f) {
        fprintf(stderr, "volpack_peer: %s: cannot open: %s\n", path, strerror(errno));
        return NULL;
    }
    if (den) {
        unsigned char h[62];
        if (gzread(f, h, sizeof h) != (int)sizeof h) {
            fprintf(stderr, "volpack_peer: %s: too short for a .den header (62 bytes)\n", path);
            gzclose(f);
            return NULL;
        }
        unsigned long count = 1;
        for (int a = 0; a < 3; a++) {
            dims[a] = h[50 + 2 * a] | h[51 + 2 * a] << 8;
            count *= (unsigned long)dims[a];
        }
        unsigned long stated = h[58] | h[59] << 8 | (unsigned long)h[60] << 16 | (unsigned long)h[61] << 24;
        if ((h[0] | h[1] << 8) != 1 || count != stated || dims[0] < 2 || dims[1] < 2 || dims[2] < 2 ||
            dims[0] > MAX_DIM || dims[1] > MAX_DIM || dims[2] > MAX_DIM) {
            fprintf(stderr, "volpack_peer: %s: not a version-1 little-endian .den header with dimensions 2..4096\n",
                    path);
            gzclose(f);
            return NULL;
        }
    } else if (o->have_dims) {
        memcpy(dims, o->dims, sizeof o->dims);
    } else {
        fprintf(stderr, "volpack_peer: %s: not a .den file: give its --dims X,Y,Z (8-bit voxels, x fastest)\n",
                path);
        gzclose(f);
        return NULL;
    }
    size_t bytes = (size_t)dims[0] * dims[1] * dims[2];
    unsigned char *v = malloc(bytes);
    if (!v) {
        fprintf(stderr, "volpack_peer: %s: out of memory for %zu voxels\n", path, bytes);
        gzclose(f);
        return NULL;
    }
    size_t got = 0;
    while (got < bytes) {
        unsigned chunk = bytes - got > (1u << 30) ? 1u << 30 : (unsigned)(bytes - got);
        int n = gzread(f, v + got, chunk);
        if (n <= 0)
            break;
        got += (size_t)n;
    }
    unsigned char extra;
    int more = gzread(f, &extra, 1);
    gzclose(f);
    if (got != bytes || more != 0) {
        fprintf(stderr, "volpack_peer: %s: %s: expected %zu voxels of %dx%dx%d\n", path,
                got != bytes ? "too short" : "longer than its dimensions", bytes, dims[0], dims[1], dims[2]);
        free(v);
        return NULL;
    }
    return v;
}

/* The camera phantom: no mirror or half-turn maps it onto itself, and each small block shows only from its
 * side, so an image tells the view's direction and handedness. */
static unsigned char *boxes(int dims[3])
{
    static const int block[3][7] = { /* x0, x1, y0, y1, z0, z1 (voxel ranges, end excluded), value */
        {30, 91, 40, 101, 20, 61, 120},
        {35, 50, 45, 60, 62, 70, 255},
        {92, 100, 80, 95, 25, 35, 200},
    };
    dims[0] = 128, dims[1] = 128, dims[2] = 84;
    unsigned char *v = calloc((size_t)dims[0] * dims[1] * dims[2], 1);
    if (!v) {
        fprintf(stderr, "volpack_peer: boxes: out of memory\n");
        return NULL;
    }
    for (int b = 0; b < 3; b++)
        for (int z = block[b][4]; z < block[b][5]; z++)
            for (int y = block[b][2]; y < block[b][3]; y++)
                memset(v + ((size_t)z * dims[1] + y) * dims[0] + block[b][0], block[b][6],
                       (size_t)(block[b][1] - block[b][0]));
    return v;
}

/* VolPack's example classification for volfix (docs/peers.md, "VolPack's check image"): the density ramp as a
 * transfer function (white, its opacity per unit length as VolPack's voxel opacity is), lit with the example's
 * material; and its gradient ramp on stdout as volfix's --gradient-opacity LO,HI. volfix's 8-bit magnitude of a
 * voxel is round(255 m / M), m its central-difference gradient per voxel (one-sided on the volume's faces) and M
 * the volume's largest (core/normals.c); VolPack's is floor(m) on the inside and 0 on the faces. So VolPack's
 * ramp from 5 to 20 is volfix's from 255 * 5 / M to 255 * 20 / M, rounded. 0, or 2 with a message. */
static int write_volfix_check(const char *path, const unsigned char *voxels, const int dims[3])
{
    const size_t sx = 1, sy = (size_t)dims[0], sz = (size_t)dims[0] * dims[1];
    double most2 = 0;
    for (int z = 0; z < dims[2]; z++)
        for (int y = 0; y < dims[1]; y++)
            for (int x = 0; x < dims[0]; x++) {
                const int at[3] = {x, y, z};
                const size_t stride[3] = {sx, sy, sz};
                const size_t i = x * sx + y * sy + z * sz;
                double m2 = 0;
                for (int a = 0; a < 3; a++) {
                    const int down = at[a] > 0, up = at[a] + 1 < dims[a];
                    const double d = ((double)voxels[i + (up ? stride[a] : 0)] - voxels[i - (down ? stride[a] : 0)]) /
                                     (down + up);
                    m2 += d * d;
                }
                most2 = m2 > most2 ? m2 : most2;
            }
    if (most2 == 0) {
        fprintf(stderr, "volpack_peer: --volfix-tf: the volume is constant: it has no gradient to ramp\n");
        return 2;
    }
    const double most = sqrt(most2);
    int lo = (int)lround(255.0 * check_gradient_x[1] / most), hi = (int)lround(255.0 * check_gradient_x[2] / most);
    hi = hi > 255 ? 255 : hi;
    lo = lo >= hi ? hi - 1 : lo;
    FILE *f = fopen(path, "w");
    if (!f) {
        fprintf(stderr, "volpack_peer: %s: cannot write: %s\n", path, strerror(errno));
        return 2;
    }
    fprintf(f, "# VolPack's example classification (its examples/volume.h), for volfix: white, opacity per unit\n"
               "# length 0 at 0 rising to 1 at %d of 255; with volfix-sim --gradient-opacity %d,%d (VolPack's gradient\n"
               "# ramp %d..%d of the largest gradient, %.3f per voxel)\n",
            check_density_x[1], lo, hi, check_gradient_x[1], check_gradient_x[2], most);
    fprintf(f, "shade phong\nmaterial 0.18 0.35 0.39 10\n0 1 1 1 0\n%.10f 1 1 1 1\n1 1 1 1 1\n",
            check_density_x[1] / 255.0);
    if (fclose(f) != 0) {
        fprintf(stderr, "volpack_peer: %s: cannot write: %s\n", path, strerror(errno));
        return 2;
    }
    printf("--gradient-opacity %d,%d\n", lo, hi);
    return 0;
}

/* 0, or 2 with a message. */
static int save_volume(const char *path, const unsigned char *voxels, const int dims[3])
{
    FILE *f = fopen(path, "wb");
    size_t n = (size_t)dims[0] * dims[1] * dims[2];
    int ok = f && fwrite(voxels, 1, n, f) == n;
    if (f && fclose(f))
        ok = 0;
    if (!ok)
        fprintf(stderr, "volpack_peer: %s: cannot write: %s\n", path, strerror(errno));
    return ok ? 0 : 2;
}

/* A volfix transfer-function file (port/io/tf.h): 'scalar r g b a' a line, '#' comments, an optional
 * "units normalized". 0, or 2 with a "FILE:LINE: ..." message. */
static int load_tf(const char *path, tf_point_t *points, int *count)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "volpack_peer: %s: cannot open: %s\n", path, strerror(errno));
        return 2;
    }
    char line[512];
    int n = 0, lineno = 0, status = 0;
    while (status == 0 && fgets(line, sizeof line, f)) {
        lineno++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = 0;
        char word[32], extra[2];
        tf_point_t q;
        if (sscanf(line, " %31s %1s", word, extra) < 1)
            continue;
        if (strcmp(word, "units") == 0) {
            if (sscanf(line, " units %31s %1s", word, extra) != 1 || strcmp(word, "normalized") != 0) {
                fprintf(stderr, "volpack_peer: %s:%d: expected 'units normalized' (data units are volfix's only)\n",
                        path, lineno);
                status = 2;
            }
        } else if (sscanf(line, " %lf %lf %lf %lf %lf %1s", &q.s, &q.r, &q.g, &q.b, &q.a, extra) != 5 ||
                   !(q.s >= 0 && q.s <= 1) || !(q.r >= 0 && q.r <= 1) || !(q.g >= 0 && q.g <= 1) ||
                   !(q.b >= 0 && q.b <= 1) || !(q.a >= 0 && q.a <= 1) || (n > 0 && q.s < points[n - 1].s)) {
            fprintf(stderr, "volpack_peer: %s:%d: expected 'scalar r g b a', five numbers in 0..1 with "
                            "non-decreasing scalars\n", path, lineno);
            status = 2;
        } else if (n == MAX_TF_POINTS) {
            fprintf(stderr, "volpack_peer: %s:%d: more than %d points\n", path, lineno, MAX_TF_POINTS);
            status = 2;
        } else {
            points[n++] = q;
        }
    }
    fclose(f);
    if (status == 0 && n == 0) {
        fprintf(stderr, "volpack_peer: %s: no control points (expected 'scalar r g b a' lines)\n", path);
        status = 2;
    }
    *count = n;
    return status;
}

/* Piecewise linear between points, constant beyond the ends; channel 0..3 = r, g, b, a. */
static double tf_eval(const tf_point_t *p, int count, double s, int channel)
{
#define CH(q) (channel == 0 ? (q).r : channel == 1 ? (q).g : channel == 2 ? (q).b : (q).a)
    if (s <= p[0].s)
        return CH(p[0]);
    for (int i = 1; i < count; i++)
        if (s <= p[i].s) {
            double w = p[i].s > p[i - 1].s ? (s - p[i - 1].s) / (p[i].s - p[i - 1].s) : 1;
            return CH(p[i - 1]) + w * (CH(p[i]) - CH(p[i - 1]));
        }
    return CH(p[count - 1]);
#undef CH
}

/* Bytes the heap holds for the program: small blocks plus those malloc maps on their own (VolPack's run-length
 * encoded copies of a large volume are mapped). VolPack has no call that says what its classified volume takes. */
static size_t heap_in_use(void)
{
    struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
}

/* 0 when VolPack said VP_OK, else 2 with its message. */
static int vp_check(vpResult result, const char *what)
{
    if (result == VP_OK)
        return 0;
    fprintf(stderr, "volpack_peer: %s: VolPack error: %s\n", what, vpGetErrorString(result));
    return 2;
}

/* Context, voxel layout, classification, shading, view window and image. 0, or 2 with a message. */
static int setup(peer_t *p, const options_t *o, unsigned char *voxels, const int dims[3])
{
    memset(p, 0, sizeof *p);
    p->shading = o->shading;
    p->tilt = o->tilt;
    p->width = o->width;
    p->height = o->height;
    p->channels = o->shading == SHADE_PHONG ? 1 : 3;
    p->image = malloc((size_t)o->width * o->height * p->channels);
    if (o->shading == SHADE_PHONG)
        p->shade_table = calloc(VP_NORM_MAX + 1, sizeof *p->shade_table);
    else
        p->color_table = calloc((SCALAR_MAX + 1) * 3, sizeof *p->color_table);
    p->vpc = vpCreateContext();
    if (!p->image || (!p->shade_table && !p->color_table) || !p->vpc) {
        fprintf(stderr, "volpack_peer: out of memory\n");
        return 2;
    }

    tf_point_t tf[MAX_TF_POINTS];
    int tf_count = 0;
    if (o->tf_file && load_tf(o->tf_file, tf, &tf_count))
        return 2;

    /* The examples' way (makevolume.c, classifyvolume.c): a raw voxel array, vpVolumeNormals for the scalar,
     * the gradient magnitude and (phong) the encoded normal, then vpClassifyVolume. */
    vpContext *vpc = p->vpc;
    size_t count = (size_t)dims[0] * dims[1] * dims[2];
    p->voxels = malloc(count * sizeof *p->voxels);
    if (!p->voxels) {
        fprintf(stderr, "volpack_peer: out of memory for %zu voxels\n", count);
        return 2;
    }
    if (vp_check(vpSetVolumeSize(vpc, dims[0], dims[1], dims[2]), "vpSetVolumeSize") ||
        vp_check(vpSetVoxelSize(vpc, sizeof(voxel_t), FIELD_COUNT, 1, o->check ? 2 : 1), "vpSetVoxelSize") ||
        vp_check(vpSetVoxelField(vpc, FIELD_SHADE, sizeof(uint16_t), offsetof(voxel_t, shade),
                                 o->shading == SHADE_PHONG ? VP_NORM_MAX : SCALAR_MAX), "vpSetVoxelField") ||
        vp_check(vpSetVoxelField(vpc, FIELD_SCALAR, 1, offsetof(voxel_t, scalar), SCALAR_MAX), "vpSetVoxelField") ||
        vp_check(vpSetVoxelField(vpc, FIELD_GRADIENT, 1, offsetof(voxel_t, gradient), VP_GRAD_MAX),
                 "vpSetVoxelField") ||
        vp_check(vpSetRawVoxels(vpc, p->voxels, (int)(count * sizeof *p->voxels), sizeof(voxel_t),
                                dims[0] * (int)sizeof(voxel_t), dims[0] * dims[1] * (int)sizeof(voxel_t)),
                 "vpSetRawVoxels") ||
        vp_check(vpVolumeNormals(vpc, voxels, (int)count, FIELD_SCALAR, FIELD_GRADIENT,
                                 o->shading == SHADE_PHONG ? FIELD_SHADE : VP_SKIP_FIELD), "vpVolumeNormals"))
        return 2;
    if (o->shading == SHADE_RGB)
        for (size_t i = 0; i < count; i++)
            p->voxels[i].shade = voxels[i];

    /* Classification: the transfer function's opacity per unit length as VolPack's per-voxel opacity (VolPack
     * corrects it for each view's slab length, as volfix does); or the example's two ramps. */
    if (o->check) {
        vpRamp(p->opacity_table, sizeof(float), 3, (int *)check_density_x, (float *)check_density_y);
        vpRamp(p->gradient_table, sizeof(float), 4, (int *)check_gradient_x, (float *)check_gradient_y);
        if (vp_check(vpSetClassifierTable(vpc, 1, FIELD_GRADIENT, p->gradient_table, sizeof p->gradient_table),
                     "vpSetClassifierTable"))
            return 2;
    } else {
        for (int i = 0; i <= SCALAR_MAX; i++)
            p->opacity_table[i] = (float)tf_eval(tf, tf_count, i / (double)SCALAR_MAX, 3);
    }
    if (vp_check(vpSetClassifierTable(vpc, 0, FIELD_SCALAR, p->opacity_table, sizeof p->opacity_table),
                 "vpSetClassifierTable") ||
        vp_check(vpSetd(vpc, VP_MIN_VOXEL_OPACITY, o->min_opacity), "vpSetd(VP_MIN_VOXEL_OPACITY)"))
        return 2;
    size_t before = heap_in_use();
    if (vp_check(vpClassifyVolume(vpc), "vpClassifyVolume"))
        return 2;
    p->classified_bytes = heap_in_use() - before;

    /* Shading. The light is set while the model matrix is the identity: VolPack transforms its direction by
     * the model matrix of that moment, so it stays fixed in eye space while the volume turns. */
    if (o->shading == SHADE_PHONG) {
        if (vp_check(vpSetLookupShader(vpc, 1, 1, FIELD_SHADE, p->shade_table,
                                       (VP_NORM_MAX + 1) * (int)sizeof(float), 0, NULL, 0), "vpSetLookupShader") ||
            vp_check(vpSetMaterial(vpc, VP_MATERIAL0, VP_AMBIENT, VP_BOTH_SIDES, 0.18, 0.18, 0.18), "vpSetMaterial") ||
            vp_check(vpSetMaterial(vpc, VP_MATERIAL0, VP_DIFFUSE, VP_BOTH_SIDES, 0.35, 0.35, 0.35), "vpSetMaterial") ||
            vp_check(vpSetMaterial(vpc, VP_MATERIAL0, VP_SPECULAR, VP_BOTH_SIDES, 0.39, 0.39, 0.39), "vpSetMaterial") ||
            vp_check(vpSetMaterial(vpc, VP_MATERIAL0, VP_SHINYNESS, VP_BOTH_SIDES, 10.0, 0.0, 0.0), "vpSetMaterial") ||
            vp_check(vpSetLight(vpc, VP_LIGHT0, VP_DIRECTION, 0.3, 0.3, 1.0), "vpSetLight") ||
            vp_check(vpSetLight(vpc, VP_LIGHT0, VP_COLOR, 1.0, 1.0, 1.0), "vpSetLight") ||
            vp_check(vpEnable(vpc, VP_LIGHT0, 1), "vpEnable(VP_LIGHT0)"))
            return 2;
    } else {
        for (int i = 0; i <= SCALAR_MAX; i++)
            for (int c = 0; c < 3; c++)
                p->color_table[3 * i + c] = (float)(255.0 * tf_eval(tf, tf_count, i / (double)SCALAR_MAX, c));
        if (vp_check(vpSetLookupShader(vpc, 3, 1, FIELD_SHADE, p->color_table,
                                       (SCALAR_MAX + 1) * 3 * (int)sizeof(float), 0, NULL, 0), "vpSetLookupShader"))
            return 2;
    }
    if (o->depth_cue && (vp_check(vpSetDepthCueing(vpc, 1.4, 1.5), "vpSetDepthCueing") ||
                         vp_check(vpEnable(vpc, VP_DEPTH_CUE, 1), "vpEnable(VP_DEPTH_CUE)")))
        return 2;

    /* A rotation about y, then x: each later rotation multiplies on the left (it turns the turned volume about
     * the eye's axes), as VolPack's example does. The window is a cube, as in the example: its depth sets only
     * the depth-cueing scale (VolPack clips nothing against near and far). */
    if (vp_check(vpSeti(vpc, VP_CONCAT_MODE, VP_CONCAT_LEFT), "vpSeti(VP_CONCAT_MODE)") ||
        vp_check(vpCurrentMatrix(vpc, VP_PROJECT), "vpCurrentMatrix") ||
        vp_check(vpIdentityMatrix(vpc), "vpIdentityMatrix") ||
        vp_check(vpWindow(vpc, VP_PARALLEL, -o->window, o->window, -o->window, o->window, -o->window,
                            o->window), "vpWindow") ||
        vp_check(vpCurrentMatrix(vpc, VP_MODEL), "vpCurrentMatrix") ||
        vp_check(vpSetImage(vpc, p->image, o->width, o->height, o->width * p->channels,
                            o->shading == SHADE_PHONG ? VP_LUMINANCE : VP_RGB), "vpSetImage") ||
        vp_check(vpSetd(vpc, VP_MAX_RAY_OPACITY, o->max_opacity), "vpSetd(VP_MAX_RAY_OPACITY)"))
        return 2;
    return 0;
}

/* The image as 8-bit RGB (luminance repeated), rows in VolPack's order. 0, or 2 with a message. */
static int write_png(const char *path, const peer_t *p)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "volpack_peer: %s: cannot write: %s\n", path, strerror(errno));
        return 2;
    }
    unsigned char *row = malloc((size_t)p->width * 3);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!row || !info || setjmp(png_jmpbuf(png))) {
        fprintf(stderr, "volpack_peer: %s: PNG write failed\n", path);
        png_destroy_write_struct(&png, &info);
        free(row);
        fclose(f);
        return 2;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)p->width, (png_uint_32)p->height, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < p->height; y++) {
        const unsigned char *src = p->image + (size_t)y * p->width * p->channels;
        for (int x = 0; x < p->width; x++)
            for (int c = 0; c < 3; c++)
                row[3 * x + c] = src[x * p->channels + (p->channels == 3 ? c : 0)];
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    if (fclose(f)) {
        fprintf(stderr, "volpack_peer: %s: cannot write: %s\n", path, strerror(errno));
        return 2;
    }
    return 0;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
