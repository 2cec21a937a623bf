/* SPDX-License-Identifier: MIT */
/*
 * renderer.h: the renderer's private state, shared by the stage files (renderer.c, composite.c, warp.c).
 *
 * Everything lives in the caller's arena, in this order:
 *   [renderer | slices x3, bricks | classification | table scratch | tables | intermediate image] mark [run lists]
 * The part before the mark depends only on the volume's size and the parameters and is reserved once; the run
 * lists depend on the transfer function and are rebuilt after rewinding to the mark.
 */
#ifndef VF_RENDERER_H
#define VF_RENDERER_H

#include "classify.h"
#include "normals.h"
#include "preint2.h"
#include "runs.h"
#include "shade.h"
#include "slices.h"
#include "tables.h"
#include "volfix.h"

/* A pixel stops taking segments once its opacity reaches 1 - 2^-10 (docs/algorithm.md, section 4). */
#define VFI_OPAQUE_Q15 (VFI_ONE_Q15 - (VFI_ONE_Q15 >> 10))

struct vf_renderer {
    vf_params_t params;
    vf_volume_t volume;    /* the caller's description; its voxels are read again on a window change */
    vf_arena_t *arena;
    size_t runs_mark;      /* arena position where the run lists begin */
    size_t needed;         /* after VF_ERR_NOMEM: the arena size that would have been enough */

    vfi_layout_t layout[3];
    const uint8_t *slices[3];  /* the arena's (built_slices), or prebuilt read-only storage */
    uint8_t *built_slices[3];  /* what set_window writes; NULL over prebuilt storage */
    vfi_bricks_t bricks;       /* the slices' ranges a brick, for the run encoder; made with them */
    bool have_window;
    vf_window_t window;        /* the window of the slices */
    bool prebuilt;             /* made by vf_renderer_create_prebuilt: its slices, normals and run lists below */
    const vf_prebuilt_t *storage; /* the caller's, which outlives the renderer */

    vfi_classify_t cls;
    bool have_tf;
    bool tf_grey;
    bool general_loops;     /* vfi_renderer_general_loops: tests only */
    uint32_t tf_generation; /* counts transfer-function changes; the tables remember the one they were built for */

    vfi_runs_t runs[3];
    bool have_runs;
#if VF_MAX_ENCODE_PARTS >= 6
    /* An encoding left in parts by vf_renderer_set_tf_begin (runs_parts.c): the indices in place, a region of the
     * arena's free space a part, and what each part's pairs need (part_values, each written by its part alone),
     * all in the free space above the indices. */
    uint32_t encode_parts;  /* parts to run before vf_renderer_set_tf_end; 0: none */
    uint32_t encode_ranges; /* slab ranges per axis: encode_parts / 3 */
    uint32_t *part_index[3];
    uint16_t *part_pairs;   /* region q: part_pairs + q part_capacity */
    size_t part_capacity;   /* uint16 values a region holds */
    size_t *part_values;    /* [encode_parts], SIZE_MAX before the part has run */
#endif

    vfi_table_scratch_t table_scratch;
    void *table;            /* point table [N * 4] (point, preclass) or 2D table [N * N * 4] (preint1): r, g, b,
                             * a in Q1.15 (16 bits) or 8 bits */
    bool tables_valid;
    uint32_t tables_generation, tables_slab_q16;
    uint32_t frame_parts;   /* the parts the frame begun last was given (vf_frame_t.table_parts) */
    uint32_t table_parts;   /* of those, how many build the table; 0 when it was built in begin or was up to date */
    bool table_part_done[VF_MAX_TABLE_PARTS]; /* one flag a part, so that parts running side by side share none */
    uint16_t *lut_f;        /* lut correction knots, VFI_LUT_KNOTS each, when correction is lut */
    uint32_t *lut_g;
    uint32_t lut_slab_q16;  /* the slab length the lut was made for, 0 for none yet */
    uint16_t *view_table;   /* the table with the lut applied to every entry (vfi_view_table), which compositing
                             * then reads instead, when the lut would be applied to the entry alone: nearest lookup
                             * in a 16-bit table, not preclass (renderer.c, has_view_table) */
    uint32_t view_slab_q16; /* the slab length the view table was made for, 0 for none yet */
    bool parts_build;       /* the table's parts build its diagonals, not only their view-table entries */
#if VF_TABLE_ON_DEMAND
    bool table_unbuilt;     /* the 2D table has diagonals marked unbuilt, which compositing builds as it reads
                             * them, with demand (vf_frame_t.one_thread) */
    vfi_demand_t demand;
    bool thread_tables;     /* the frame's bands read their threads' copies of the table (vf_frame_t.thread_tables),
                             * each built as read; the shared one is stale */
#endif
    vfi_lookup_ctx_t lookup;

#if VF_LIGHTING
    /* Lighting (params.lighting): the normals, made at create; the lighting asked for; the shade table, remade
     * when the view's rotation or the lighting changes; the front-weighted table (and its view table) beside the
     * 2D table, built with it. */
    const uint16_t *codes[3];
    const uint8_t *magnitudes[3];
    const int32_t *unit;     /* [codes][3] unit normals, Q1.30 */
    uint32_t code_count;
    uint64_t *shade;         /* [code_count] L_d and L_s in lanes (shade.h) */
    uint16_t *ramp;          /* [256] gradient-opacity factors */
    void *lit_table;
    uint16_t *lit_view_table;
    bool lit;                /* frames are lit (vf_renderer_set_lighting), else as a renderer without lighting */
    vf_lighting_t lighting;
    uint32_t lighting_generation, shade_generation; /* the shade table is for lighting_generation ... */
    vf_view_t shade_view;                           /* ... and this view's rotation */
    bool shade_valid;
    bool lit_table_valid;    /* the front-weighted table is of the 2D table's transfer function and length */
    vfi_shading_t shading;   /* what the frame's bands read (its copy's arrays set per frame) */
#endif

#if VF_ORDER2
    /* preint2 (docs/algorithm.md, section 8): the 3D table, beside the 2D table (which holds the last slab's
     * entries when a volume has an odd number of slabs) and built with it, from its pieces; with lighting the 3D
     * table's front- and back-weighted values (eight an entry), built when a lit frame needs them. */
    void *table2;
    void *lit_table2;
    vfi_order2_pieces_t pieces;
    vfi_lookup2_t lookup2;
#endif

    vf_factor_t factor;
    bool have_frame;
    uint16_t *intermediate;  /* [int_w * int_h * 4] r, g, b, a in Q1.15 */
    size_t intermediate_max; /* pixels reserved */
    uint32_t max_int_w;      /* widest intermediate row of any view, for scratch sizing */
    uint16_t *row_extent;    /* [rows][2] of the frame's intermediate image: its first pixel with anything in it and
                              * one past its last (0, 0 for an empty row), written as each band finishes, so that
                              * the warp leaves empty space alone */
    uint32_t max_ni;         /* widest slice of any principal axis */

    vf_memory_t memory;
};

/* Whether compositing takes the plain loops (composite_order0.c, composite_order1.c): nearest lookup in a 16-bit
 * table with nothing corrected per segment (no lut, or a view table), samples and accumulators at full precision
 * (shifts 0), one ray per voxel column. composite.c asks it of a band's job, renderer.c of a frame's lookup. */
static inline bool vfi_plain_path(bool bilinear, const uint16_t *q15, const uint16_t *lut_f, uint32_t sample_shift,
                                  uint32_t inter_shift, uint32_t rays)
{
    return !bilinear && q15 && !lut_f && !sample_shift && !inter_shift && rays == 1;
}

/* Whether frames are lit (section 7 of docs/algorithm.md), which takes the general compositing loops. */
static inline bool vfi_lit(const vf_renderer_t *r)
{
#if VF_LIGHTING
    return r->lit;
#else
    (void)r;
    return false;
#endif
}

/* prebuilt.c: whether prebuilt storage fits these parameters and this volume (every array there and of its size,
 * the lighting's exactly when the parameters light, the run lists' when visible_from is given, each run list
 * whole; VF_ERR_NULL or VF_ERR_ARG); and, for a renderer over it with its transfer function classified, whether
 * the prebuilt run lists are of that visibility, then taken as its own. */
vf_status_t vfi_prebuilt_check(const vf_params_t *p, const vf_volume_t *vol, const vf_prebuilt_t *pre);
bool vfi_prebuilt_adopt_runs(vf_renderer_t *r);

/* renderer.c: the whole run-length encoding of set_tf and set_window (the indices, then each axis's pairs). */
vf_status_t vfi_encode_runs(vf_renderer_t *r);
/* runs_parts.c: the indices, and a region of the free space for each of 3 ranges parts; or, where that cannot be
 * (no room), the whole encoding. */
vf_status_t vfi_encode_parts_begin(vf_renderer_t *r, uint32_t ranges);

/* composite.c */
/* own: a thread's copy of the table built as read (vf_thread_table_t), or NULL for the shared table */
vf_status_t vfi_composite_band(const vf_renderer_t *r, uint32_t v0, uint32_t v1, void *scratch, size_t bytes,
                               const vfi_demand_t *own);
size_t vfi_band_scratch_bytes(const vf_renderer_t *r, uint32_t band_rows);

/* warp.c */
vf_status_t vfi_warp_band(const vf_renderer_t *r, const vf_image_t *image, uint32_t y0, uint32_t y1);

#endif
