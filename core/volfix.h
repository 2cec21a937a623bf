/* SPDX-License-Identifier: MIT */
/*
 * volfix.h: the public interface of the volfix core.
 *
 * A fixed-point, pre-integrated shear-warp volume renderer in freestanding C99. The core owns no memory and
 * has no mutable globals: the caller hands in an arena (a buffer it owns), every fallible call returns a
 * vf_status_t, and nothing prints or aborts. docs/algorithm.md defines every pixel this code produces.
 *
 * A frame's path:
 *   vf_renderer_create          once per volume and parameter set (reserves all fixed-size memory)
 *   vf_renderer_set_window      when the window changes: the volume is resampled to 8-bit slices, one copy per axis
 *   vf_renderer_set_tf          when the transfer function changes: classification and run-length encoding
 *   vf_renderer_set_tf_begin    (threads only) the same with the encoding in parts, run side by side, then _end
 *   vf_renderer_begin           per frame: factor the view; bring the tables up to date for its slab length
 *   vf_renderer_build_table_part  (threads only) the parts of a stale pre-integrated table, side by side
 *   vf_renderer_thread_table_begin  (threads only) a thread's copy of a table built as read, before its bands
 *   vf_renderer_composite_band  per band of intermediate rows (threads may run bands at once; _in with a copy)
 *   vf_renderer_warp_band       per band of output rows (threads may run bands at once)
 * vf_renderer_draw runs a whole frame on the calling thread.
 */
#ifndef VOLFIX_H
#define VOLFIX_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "vf_config.h"

/* The library's version (CHANGELOG.md); vf_version() gives it as text, "MAJOR.MINOR.PATCH". */
#define VF_VERSION_MAJOR 0
#define VF_VERSION_MINOR 7
#define VF_VERSION_PATCH 0

#ifdef __cplusplus
extern "C" {
#endif

/* The version this library was built as, "0.7.0": the macros above as text. */
const char *vf_version(void);

/* ---------------------------------------------------------------------------------------------------------- */
/* Status */

typedef enum vf_status {
    VF_OK = 0,
    VF_ERR_NULL,        /* a required pointer argument is NULL */
    VF_ERR_ARG,         /* an argument is out of its documented range */
    VF_ERR_DIMS,        /* volume dimensions outside 2..VF_MAX_DIM, or the volume is too large */
    VF_ERR_SPACING,     /* a spacing is zero, or the spacings differ by more than VF_MAX_ANISOTROPY */
    VF_ERR_WINDOW,      /* window with lo == hi */
    VF_ERR_TF,          /* transfer function with no points or with decreasing scalars */
    VF_ERR_NOMEM,       /* the arena (or band scratch) is too small; see vf_renderer_needed_bytes */
    VF_ERR_STATE,       /* called out of order (for example a frame before a window and transfer function) */
    VF_ERR_IMAGE,       /* output image: zero size, stride too small, unknown format, size differs from begin */
    VF_ERR_UNSUPPORTED, /* a valid request this build does not implement */
    VF_ERR_INTERMEDIATE, /* with this many rays the intermediate image would exceed VF_MAX_INTERMEDIATE a side */
    VF_STATUS_COUNT
} vf_status_t;

/* A one-line text for a status; never NULL. */
const char *vf_status_text(vf_status_t status);

/* ---------------------------------------------------------------------------------------------------------- */
/* Memory: an arena over a buffer the caller owns. Allocation only moves a cursor; nothing is freed singly. */

typedef struct vf_arena {
    unsigned char *base;
    size_t size;         /* bytes in the buffer */
    size_t used;         /* bytes handed out, including alignment padding */
    size_t peak;         /* high-water mark of used */
    uint32_t allocs;     /* allocations made */
    uint32_t reserved;   /* the core's own; vf_arena_init clears it */
} vf_arena_t;

void vf_arena_init(vf_arena_t *arena, void *buffer, size_t size);

/* ---------------------------------------------------------------------------------------------------------- */
/* Inputs */

typedef enum vf_voxel { VF_VOXEL_U8, VF_VOXEL_I8, VF_VOXEL_U16, VF_VOXEL_I16 } vf_voxel_t;

/* A volume the caller owns; it must outlive the renderer that uses it (window changes read it again). */
typedef struct vf_volume {
    uint32_t dims[3];        /* x, y, z voxels, each 2..VF_MAX_DIM */
    uint32_t spacing_q16[3]; /* voxel spacing, Q16.16 in any physical unit; only ratios matter */
    vf_voxel_t type;
    const void *voxels;      /* x fastest, then y, then z, native byte order */
} vf_volume_t;

/* Raw voxel values lo..hi map linearly to the scalar domain 0..255 (clamped); hi < lo maps descending. */
typedef struct vf_window {
    int32_t lo, hi;
} vf_window_t;

/* Transfer-function control point: scalar in the windowed domain, Q8.8 (0..255); colour and opacity per unit
 * length (one voxel of the smallest spacing) as unorm16 (65535 = 1.0). Piecewise linear between points. */
typedef struct vf_tf_point {
    uint16_t scalar_q8;
    uint16_t r, g, b, a;
} vf_tf_point_t;

typedef struct vf_tf {
    const vf_tf_point_t *points; /* scalar non-decreasing */
    uint32_t count;              /* 1..VF_MAX_TF_POINTS */
} vf_tf_t;

/* ---------------------------------------------------------------------------------------------------------- */
/* Parameters, fixed for the life of a renderer */

typedef enum vf_mode {
    VF_MODE_POINT,    /* order 0: point-sampled post-classification, one table entry per slice sample */
    VF_MODE_PREINT1,  /* order 1: pre-integrated slabs, one 2D table entry per (front, back) sample pair */
    VF_MODE_PRECLASS, /* order 0, pre-classified: voxels classified first, their RGBA interpolated (VolPack) */
    VF_MODE_PREINT2,  /* order 2: slabs of two slices, one 3D table entry per (front, middle, back) sample triple
                       * (El Hajjar et al. 2008; docs/algorithm.md, section 8), table2_size entries a side;
                       * VF_ERR_UNSUPPORTED in builds without VF_ORDER2, and with partial slabs */
    VF_MODE_COUNT
} vf_mode_t;

typedef enum vf_lookup {
    VF_LOOKUP_NEAREST,  /* the nearest table entry of each sample */
    VF_LOOKUP_BILINEAR, /* interpolate between entries (1D for point, 2D for preint1) */
    VF_LOOKUP_TRILINEAR, /* preint2 only: interpolate between the 8 entries around a sample triple in the 3D table
                          * (a last slab of one slice interpolates its 2D entries bilinearly) */
    VF_LOOKUP_COUNT
} vf_lookup_t;

typedef enum vf_correction {
    VF_CORRECTION_REBUILD, /* tables rebuilt for each view's exact slab length */
    VF_CORRECTION_LUT,     /* tables built once for length 1, each segment corrected through a lookup on its
                            * opacity a (Schulze et al.'s way: a' = 1 - (1 - a)^d, C' = C a' / a) */
    VF_CORRECTION_COUNT
} vf_correction_t;

typedef enum vf_buffer {
    VF_BUFFER_SLICE, /* two buffer slices the size of a voxel slice row (Schulze et al.'s slice-sized) */
    VF_BUFFER_IMAGE, /* one buffer the size of an intermediate row, updated in place (image-sized) */
    VF_BUFFER_COUNT
} vf_buffer_t;

typedef struct vf_params {
    vf_mode_t mode;             /* preint1 */
    uint32_t table_size;        /* N table entries over the scalar domain, VF_MIN_TABLE..VF_MAX_TABLE (256) */
    uint32_t table_bits;        /* 16 (Q1.15 entries), 8 (8-bit entries, half the memory), or 10 or 12 (values
                                 * on that grid, stored in 16 bits: for precision studies) */
    vf_lookup_t lookup;         /* nearest */
    vf_correction_t correction; /* rebuild */
    vf_buffer_t buffer;         /* slice */
    uint32_t rays;              /* 1, 2, 4, 8 or 16 (1): rays per voxel column along each of u and v, an
                                 * intermediate image of rays x rays pixels per voxel (docs/algorithm.md, 4b) */
    bool partial_slabs;         /* false: where a ray crosses a side face between two slices, a slab counts
                                 * whole or not at all (section 4); true: its part inside the box (4c) */
    uint16_t background[3];     /* unorm16 RGB behind the volume (black) */
    /* Lighting (docs/algorithm.md, section 7). true: the renderer keeps a normal code and an 8-bit gradient
     * magnitude per voxel (one copy per principal axis, like the slices: 3 (normal_bits / 8 rounded up) + 3
     * bytes a voxel), the front-weighted pre-integrated table and a shade table, and lights its frames with
     * vf_lighting_default until vf_renderer_set_lighting says otherwise. false (the default): none of that. */
    bool lighting;
    uint32_t normal_bits;       /* bits of a normal code, 8, 10, 12, 14 (14) or 16: 2^(B/2) - 1 levels a side of
                                 * the octahedron (section 7) */
    vf_lookup_t shade_lookup;   /* a sample's shade: its nearest voxel's (nearest, the default), or its four
                                 * voxels' interpolated (bilinear: a little closer to the truth, at more cost) */
    /* Precision of the core's own arithmetic, for studies of how many bits each stage needs (docs/algorithm.md,
     * section 6). The defaults are the full precision; the double reference ignores these. */
    uint32_t sample_bits;       /* 0: samples exact; 4..16: rounded to that many fraction bits before lookup */
    uint32_t intermediate_bits; /* 16: Q1.15 accumulation; 8 or 12: rounded to that many bits after each slab */
    uint32_t warp_bits;         /* 16: Q0.16 warp weights; 4..15: fractions rounded to that many bits */
    /* preint2 (docs/algorithm.md, section 8): entries a side of the 3D table, VF_MIN_TABLE2..VF_MAX_TABLE2 (64).
     * The table takes table2_size^3 entries of four values (16 or 8 bits, as table_bits: 10 and 12 bits are kept
     * in 16), with lighting three times that; it is built from first-order pieces kept in Q.30 (16 bytes an entry
     * of the table_size^2 2D table, twice that with lighting). Other modes ignore it. */
    uint32_t table2_size;
} vf_params_t;

void vf_params_default(vf_params_t *params);

/* How frames are lit (docs/algorithm.md, section 7), for a renderer created with params.lighting. */
#define VF_MAX_LIGHTS 2
typedef struct vf_light {
    int32_t azimuth, elevation; /* BAU, relative to the viewer: 0, 0 is a headlight; positive azimuth lights from
                                 * the right, positive elevation from above */
} vf_light_t;

typedef struct vf_lighting {
    bool shade;                       /* Blinn-Phong shading; false: unlit colours (gradient opacity still applies) */
    uint32_t light_count;             /* 1..VF_MAX_LIGHTS white directional lights */
    vf_light_t lights[VF_MAX_LIGHTS];
    uint16_t ka, kd, ks;              /* ambient, diffuse, specular, unorm16 (65535 = 1.0) */
    uint16_t shininess;               /* the specular exponent, 1..255 */
    uint8_t gradient_lo, gradient_hi; /* opacity times a ramp in the 8-bit gradient magnitude, from 0 at lo to 1 at
                                       * hi (lo < hi); 0, 0: no gradient opacity */
} vf_lighting_t;

/* Shading on, one headlight, ka 0.1, kd 0.7, ks 0.2, shininess 10 (VTK's defaults), no gradient opacity. */
void vf_lighting_default(vf_lighting_t *lighting);
const char *vf_mode_name(vf_mode_t mode);
const char *vf_lookup_name(vf_lookup_t lookup);
const char *vf_correction_name(vf_correction_t correction);
const char *vf_buffer_name(vf_buffer_t buffer);

/* ---------------------------------------------------------------------------------------------------------- */
/* View and output image */

#define VF_BAU_PER_TURN 65536 /* binary angle units: 65536 per full turn */

typedef struct vf_view {
    int32_t azimuth;   /* about the screen's vertical axis, BAU */
    int32_t elevation; /* about the screen's horizontal axis, BAU */
    int32_t roll;      /* about the viewing axis, BAU */
    uint32_t zoom_q16; /* 1.0 (65536) fits the volume's bounding sphere in the smaller image side */
} vf_view_t;

typedef enum vf_format {
    VF_FORMAT_RGB888,   /* bytes R, G, B */
    VF_FORMAT_RGB565,   /* little-endian 16-bit rrrrrggggggbbbbb */
    VF_FORMAT_XRGB8888, /* little-endian 32-bit 0xffRRGGBB (bytes B, G, R, 0xff), DRM's XRGB8888 */
    VF_FORMAT_COUNT
} vf_format_t;

typedef struct vf_image {
    void *pixels;
    uint32_t width, height;
    uint32_t stride;    /* bytes from one row to the next */
    vf_format_t format;
} vf_image_t;

uint32_t vf_format_bytes(vf_format_t format); /* bytes per pixel, 0 for an unknown format */

/* ---------------------------------------------------------------------------------------------------------- */
/* The shear-warp factorisation of a view (docs/algorithm.md, section 3): the only thing later stages use. */

typedef struct vf_factor {
    uint8_t k_axis, i_axis, j_axis; /* object axes (0 x, 1 y, 2 z) of the standard object axes k, i, j */
    bool k_flip;                    /* slice k of standard space is object slice n_k - 1 - k */
    uint32_t ni, nj, nk;            /* volume dimensions along i, j, k */
    int64_t si_q32, sj_q32;         /* shear: intermediate pixels per slice, Q32.32 */
    int64_t ti_q32, tj_q32;         /* translation of slice 0, Q32.32 */
    uint32_t rays;                  /* intermediate pixels per voxel along u and v (1 from vf_factor) */
    uint32_t int_w, int_h;          /* intermediate image size, pixels */
    uint32_t slab_q16;              /* distance between slices along a ray, units of d_ref, Q16.16 */
    uint32_t out_w, out_h;          /* final image size */
    int64_t u0_q32, v0_q32;         /* intermediate pixel seen by final pixel (0, 0), Q32.32 */
    int64_t du_dx_q32, dv_dx_q32;   /* change per final pixel to the right */
    int64_t du_dy_q32, dv_dy_q32;   /* change per final pixel down */
} vf_factor_t;

vf_status_t vf_factor(vf_factor_t *factor, const vf_volume_t *volume, const vf_view_t *view, uint32_t out_w,
                      uint32_t out_h);

/* The same factorisation with rays x rays intermediate pixels per voxel (a factorisation of one ray per voxel
 * column, rays 1, 2, 4, 8 or 16): int_w = rays (int_w - 1) + 1, likewise int_h, and the warp map in those
 * pixels. The slice offsets stay in voxels. VF_ERR_ARG for other values, VF_ERR_INTERMEDIATE when the image
 * would be wider or taller than VF_MAX_INTERMEDIATE. */
vf_status_t vf_factor_rays(vf_factor_t *factor, uint32_t rays);

/* Offset of slice k in the intermediate image in voxels, Q16.16 (snapped to the 2^-16 grid, docs/algorithm.md):
 * with rays R, pixel U samples slice k at U / R - offset. */
int32_t vf_factor_offset_u(const vf_factor_t *factor, uint32_t k);
int32_t vf_factor_offset_v(const vf_factor_t *factor, uint32_t k);

/* ---------------------------------------------------------------------------------------------------------- */
/* The renderer */

typedef struct vf_renderer vf_renderer_t; /* lives inside the caller's arena */

/* What the renderer holds, in bytes (for memory reports and sizing). */
typedef struct vf_memory {
    size_t renderer;     /* the renderer's own struct */
    size_t slices;       /* 8-bit scalar slices, one copy per principal axis */
    size_t runs;         /* run-length encoding of the visible cells, per principal axis */
    size_t classify;     /* per-entry extinction and colour, visibility prefix, the bricks' scalar ranges */
    size_t tables;       /* point table and (preint1) the 2D table, and with lighting its front-weighted table */
    size_t normals;      /* lighting: normal codes and gradient magnitudes, per principal axis; the shade table */
    size_t intermediate; /* the intermediate image at its largest */
    size_t total;        /* arena bytes in use, alignment included */
    size_t order2;       /* preint2: the 3D table (and with lighting its front- and back-weighted values) and the
                          * Q.30 pieces it is built from; 0 in the other modes */
} vf_memory_t;

/* Arena bytes that vf_renderer_create reserves for this volume and these parameters (everything but the run
 * lists, whose size depends on the transfer function: see vf_renderer_needed_bytes). */
vf_status_t vf_renderer_bytes(const vf_params_t *params, const vf_volume_t *volume, size_t *bytes);

vf_status_t vf_renderer_create(vf_renderer_t **renderer, const vf_params_t *params, const vf_volume_t *volume,
                               vf_arena_t *arena);
vf_status_t vf_renderer_set_window(vf_renderer_t *renderer, vf_window_t window);
vf_status_t vf_renderer_set_tf(vf_renderer_t *renderer, const vf_tf_t *tf);

/* vf_renderer_set_tf with the run-length encoding shared out, for callers with threads. Begin classifies (its
 * errors are set_tf's) and, with ranges 2 .. VF_MAX_ENCODE_PARTS / 3, leaves the encoding in parts: each principal
 * axis's slabs in that many ranges. vf_renderer_encode_parts then says how many parts there are (0 when begin
 * encoded the whole itself, as set_tf: ranges 0 or 1, no window yet, prebuilt storage, or too little free arena
 * for the parts' regions; begin's status is then set_tf's); run each part 0 .. parts - 1 once, on any threads,
 * each call on its own part (they share nothing else); then vf_renderer_set_tf_end joins them on one thread
 * (running any part left out) and returns what set_tf would have: the run lists are the same to the byte, and
 * so are VF_ERR_NOMEM and vf_renderer_needed_bytes (a part whose pairs outgrow its region of the free arena
 * makes end encode the whole instead). Until end, frames give VF_ERR_STATE. VF_ERR_ARG for ranges above
 * VF_MAX_ENCODE_PARTS / 3, or a part out of range. */
vf_status_t vf_renderer_set_tf_begin(vf_renderer_t *renderer, const vf_tf_t *tf, uint32_t ranges);
uint32_t vf_renderer_encode_parts(const vf_renderer_t *renderer);
vf_status_t vf_renderer_encode_part(vf_renderer_t *renderer, uint32_t part);
vf_status_t vf_renderer_set_tf_end(vf_renderer_t *renderer);

/* Light the frames that follow (the renderer must have been created with params.lighting: else
 * VF_ERR_UNSUPPORTED), or NULL: unlit, the pixels of a renderer without lighting to the bit. VF_ERR_ARG for a
 * light count, shininess or gradient ramp out of range. */
vf_status_t vf_renderer_set_lighting(vf_renderer_t *renderer, const vf_lighting_t *lighting);

/* After VF_ERR_NOMEM from vf_renderer_set_tf: the arena size that would have been enough for everything. */
size_t vf_renderer_needed_bytes(const vf_renderer_t *renderer);
void vf_renderer_memory(const vf_renderer_t *renderer, vf_memory_t *memory);
const vf_params_t *vf_renderer_params(const vf_renderer_t *renderer);

/* Prebuilt storage, for a device that keeps in read-only memory (flash) what the renderer would otherwise build in
 * its arena for one window and, optionally, one transfer function: the 8-bit slices of every principal axis, with
 * lighting the normals, and the run lists. vf_renderer_export describes a renderer's own (on a host, to write them
 * out); vf_renderer_create_prebuilt adopts them, read-only, and they (and the vf_prebuilt_t) must outlive the
 * renderer. Such a renderer:
 * - takes vf_renderer_set_window for the prebuilt window only (another: VF_ERR_UNSUPPORTED);
 * - adopts the run lists when vf_renderer_set_tf's transfer function has the visibility they were encoded for
 *   (visible_from, compared exactly), and otherwise encodes new ones in the arena as any renderer does (so a
 *   device that changes its transfer function needs the arena that vf_renderer_needed_bytes then reports);
 * - reserves an intermediate image of intermediate_pixels (0: the largest of any view), and vf_renderer_begin
 *   gives VF_ERR_NOMEM for a view whose intermediate image is larger.
 * Sizes are in elements; vf_renderer_create_prebuilt checks every size and every row of the run lists
 * (VF_ERR_ARG when one is wrong, VF_ERR_NULL for a missing array). */
typedef struct vf_prebuilt {
    vf_window_t window;            /* the window the slices (and the run lists) were made with */
    const uint8_t *slices[3];      /* per principal axis, the renderer's slice layout */
    size_t slice_count[3];
    const uint16_t *codes[3];      /* lighting only (else NULL): normal codes and gradient magnitudes per axis, as */
    const uint8_t *magnitudes[3];  /* many as the slices', and the unit normal of each code (3 values a code) */
    const int32_t *unit;
    size_t unit_count;
    const uint16_t *visible_from;  /* [256] the visibility the run lists were encoded for; NULL: no run lists */
    const uint32_t *row_start[3];  /* per axis, the run lists' row index and (skip, length) pairs */
    size_t row_count[3];
    const uint16_t *pairs[3];
    size_t pair_count[3];
    uint32_t intermediate_pixels;  /* the largest intermediate image of the views to come, 0: any view */
} vf_prebuilt_t;

/* What renderer holds after its window and transfer function (and with lighting its normals): pointers into its
 * arena, valid while it lives, with intermediate_pixels 0. VF_ERR_STATE before a window and transfer function. */
vf_status_t vf_renderer_export(const vf_renderer_t *renderer, vf_prebuilt_t *prebuilt);

/* vf_renderer_bytes and vf_renderer_create for a renderer over prebuilt storage: no slices, normals or (when they
 * are adopted) run lists in the arena. */
vf_status_t vf_renderer_prebuilt_bytes(const vf_params_t *params, const vf_volume_t *volume,
                                       const vf_prebuilt_t *prebuilt, size_t *bytes);
vf_status_t vf_renderer_create_prebuilt(vf_renderer_t **renderer, const vf_params_t *params,
                                        const vf_volume_t *volume, const vf_prebuilt_t *prebuilt, vf_arena_t *arena);

/* A frame: the view, the output size, and how the caller will run it. Zero-initialise and set view, width and
 * height for a frame on one thread; the other fields only matter to callers with threads. */
typedef struct vf_frame {
    vf_view_t view;
    uint32_t width, height; /* the output image's size */
    uint32_t table_parts;   /* 0 or 1: begin builds a stale pre-integrated table (a new transfer function or slab
                             * length; the one serial part of a preint1 frame, growing as N^2) itself.
                             * 2..VF_MAX_TABLE_PARTS: begin leaves it in that many parts, which the caller runs on
                             * threads with vf_renderer_build_table_part before compositing. The table is the
                             * same, to the bit, in any number of parts. */
    bool one_thread;        /* every band of this frame is composited on the calling thread, one after another:
                             * then a stale 2D table is built as compositing first reads each block of its
                             * diagonals, only the blocks the frame uses (the default preint1 path; otherwise, and in
                             * builds without VF_TABLE_ON_DEMAND, as begin would). The same pixels either way. */
    bool thread_tables;     /* bands run on threads, each thread with its own copy of the 2D table built as read
                             * (vf_thread_table_t): where one_thread would build the table as read, each copy is
                             * built as its thread's bands read it, so that no thread reads an entry another is
                             * writing; elsewhere as table_parts says. */
} vf_frame_t;

/* Factor the frame's view and bring the tables up to date. VF_ERR_ARG for table_parts above
 * VF_MAX_TABLE_PARTS or together with one_thread. */
vf_status_t vf_renderer_begin(vf_renderer_t *renderer, const vf_frame_t *frame);

/* The factorisation of the frame begun last; NULL before one. */
const vf_factor_t *vf_renderer_factor(const vf_renderer_t *renderer);

/* After a begin with table_parts > 1: how many parts of the table are to be built (0 when it was up to date), the
 * scratch each part needs, and the build of part 0 .. parts - 1, each once, on any threads, each with its own
 * scratch. vf_renderer_composite_band returns VF_ERR_STATE until every part has run. With the lut correction and
 * a view table (vf_config.h, VF_VIEW_TABLE) the parts also correct their entries of it for a new slab length. */
uint32_t vf_renderer_table_parts(const vf_renderer_t *renderer);
size_t vf_renderer_table_part_bytes(const vf_renderer_t *renderer);
vf_status_t vf_renderer_build_table_part(vf_renderer_t *renderer, uint32_t part, void *scratch, size_t scratch_bytes);

/* Bytes of scratch a band of band_rows intermediate rows needs (buffer slices and skip links). */
size_t vf_renderer_band_scratch_bytes(const vf_renderer_t *renderer, uint32_t band_rows);

/* Composite intermediate rows [v0, v1) (0 <= v0 < v1 <= factor->int_h). Bands may run concurrently on
 * different threads, each with its own scratch; every band must finish before any warp band starts. */
vf_status_t vf_renderer_composite_band(const vf_renderer_t *renderer, uint32_t v0, uint32_t v1, void *scratch,
                                       size_t scratch_bytes);

/* A thread's copy of the 2D table for frames begun with thread_tables: memory of vf_renderer_thread_table_bytes (0:
 * this renderer's frames never build their table as read), and what the core calls when one of the thread's bands
 * meets a diagonal its copy lacks: fill, which returns true when it has filled the diagonal itself (copied from
 * another thread's copy with vf_renderer_copy_diagonal) and false to have the core build it, then built once the
 * core has. Either may be NULL; both run on the band's thread. vf_renderer_thread_table_begin makes the copy ready
 * for the frame begun last (every diagonal but the main one unbuilt), on its thread before its first band, and
 * does nothing when that frame's table is shared. vf_renderer_composite_band_in is vf_renderer_composite_band
 * reading the thread's copy, or the shared table when the frame has one. Diagonal d: the entries (f, f + d) and
 * (f + d, f). */
typedef struct vf_thread_table {
    void *memory;
    size_t bytes;
    bool (*fill)(void *context, uint32_t diagonal);
    void (*built)(void *context, uint32_t diagonal);
    void *context;
} vf_thread_table_t;
size_t vf_renderer_thread_table_bytes(const vf_renderer_t *renderer);
vf_status_t vf_renderer_thread_table_begin(const vf_renderer_t *renderer, const vf_thread_table_t *table);
vf_status_t vf_renderer_composite_band_in(const vf_renderer_t *renderer, uint32_t v0, uint32_t v1, void *scratch,
                                          size_t scratch_bytes, const vf_thread_table_t *table);
vf_status_t vf_renderer_copy_diagonal(const vf_renderer_t *renderer, const vf_thread_table_t *from,
                                      const vf_thread_table_t *to, uint32_t diagonal);

/* Warp final rows [y0, y1) into image (whose size must equal the frame's width and height). */
vf_status_t vf_renderer_warp_band(const vf_renderer_t *renderer, const vf_image_t *image, uint32_t y0, uint32_t y1);

/* A whole frame on the calling thread: begin, composite all rows, warp all rows into image. */
vf_status_t vf_renderer_draw(vf_renderer_t *renderer, const vf_view_t *view, const vf_image_t *image, void *scratch,
                             size_t scratch_bytes);

/* ---------------------------------------------------------------------------------------------------------- */
/* Tables on their own, for tools (volfix-sim tables) and other renderers. An entry is Q1.15 r, g, b, a (colour premultiplied); the 2D table is
 * indexed [front * n + back]. scratch provides the classification and the builders' working memory
 * (vf_table_scratch_bytes); it is rewound afterwards. */

typedef enum vf_builder {
    VF_BUILDER_INCREMENTAL, /* O(N^2) incremental subrange integration (Lum et al. 2004): what renderers use */
    VF_BUILDER_BRUTEFORCE,  /* O(N^3), every entry composited interval by interval: the oracle (VF_ERR_UNSUPPORTED
                             * in builds without it, VF_TABLE_ORACLE) */
    VF_BUILDER_COUNT
} vf_builder_t;

size_t vf_table_scratch_bytes(uint32_t n);
vf_status_t vf_table_point(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_arena_t *scratch, uint16_t *out);
vf_status_t vf_table_preint(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_builder_t builder,
                            vf_arena_t *scratch, uint16_t *out);
/* The same 2D table into out and, into lit_out (n * n * 4 values, the same indices), its front-weighted values
 * for interpolated pre-integrated lighting (docs/algorithm.md section 7): D_f r, g, b (premultiplied) and S_f,
 * Q1.15, D_f at most the entry's C and S_f at most its a. out is the table vf_table_preint builds, to the bit.
 * vf_table_scratch_bytes covers it. */
vf_status_t vf_table_preint_lit(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_builder_t builder,
                                vf_arena_t *scratch, uint16_t *out, uint16_t *lit_out);

/* The order-2 table on its own (docs/algorithm.md, section 8) for a slab of 2 slab_q16 (slab_q16 is the distance
 * between slices, d): n2^3 entries of Q1.15 r, g, b, a indexed [(front * n2 + middle) * n2 + back], built from the
 * pieces of the n-entry 2D table. lit_out (NULL, or n2^3 * 8 values, the same indices): the entry's front- and
 * back-weighted values W_f r, g, b, S_f then W_b r, g, b, S_b for lighting (section 8). In parts for threads: part
 * (0 .. parts - 1) writes its share of the entries and no other, each part with its own scratch (the pieces are
 * built by every part); all parts give the whole table, to the bit. VF_ERR_UNSUPPORTED in builds without
 * VF_ORDER2 (or, for lit_out, without VF_LIT_TABLES). */
size_t vf_table2_scratch_bytes(uint32_t n, bool lit);
vf_status_t vf_table_order2(const vf_tf_t *tf, uint32_t n, uint32_t n2, uint32_t slab_q16, uint32_t part,
                            uint32_t parts, vf_arena_t *scratch, uint16_t *out, uint16_t *lit_out);

#ifdef __cplusplus
}
#endif

#endif /* VOLFIX_H */
