/* SPDX-License-Identifier: MIT */
/*
 * renderer.c: the renderer's life (create, window, transfer function) and a frame's script: check, factor,
 * bring the tables up to date, composite, warp. Memory layout and invariants are in renderer.h.
 */
#include "arena.h"
#include "renderer.h"
#include "volfix_internal.h"

static vf_status_t check_params(const vf_params_t *p);
static vf_status_t check_volume(const vf_volume_t *v);
static size_t intermediate_pixels(const uint32_t dims[3], uint32_t rays, uint32_t *max_w, uint32_t *max_ni);
static size_t extent_bytes(const uint32_t dims[3], uint32_t rays);
static size_t table_value_bytes(const vf_params_t *p);
static size_t table_entries(const vf_params_t *p);
static size_t table_bytes(const vf_params_t *p);
static bool has_view_table(const vf_params_t *p);
static void update_tables(vf_renderer_t *r, uint32_t parts, bool one_thread, bool thread_tables);
#if VF_TABLE_ON_DEMAND
static bool on_demand(const vf_renderer_t *r);
#endif
static bool tables_complete(const vf_renderer_t *r);
static inline vfi_table_out_t table_out(const vf_renderer_t *r);

/* Whether lit frames take the general loops though the path is plain: gradient opacity (composite.c). */
static inline bool lit_general(const vf_renderer_t *r)
{
#if VF_LIGHTING
    return r->lit && r->lighting.gradient_hi;
#else
    (void)r;
    return false;
#endif
}
#if VF_ORDER2
static inline vfi_table_out_t table2_out(const vf_renderer_t *r);
#endif
static size_t normals_bytes(const vf_params_t *p, const vf_volume_t *vol, bool prebuilt);
static size_t reserved_intermediate(const vf_volume_t *vol, uint32_t rays, const vf_prebuilt_t *pre, uint32_t *max_w,
                                    uint32_t *max_ni);
static size_t order2_bytes(const vf_params_t *p);

/* Whether the renderer is over prebuilt storage (constant false in builds without VF_PREBUILT). */
static inline bool is_prebuilt(const vf_renderer_t *r)
{
    return VF_PREBUILT && r->prebuilt;
}

/* The modes with a 2D table: preint1, and preint2 (its last slab when the slab count is odd, and its pieces). */
static bool has_2d_table(const vf_params_t *p)
{
    return p->mode == VF_MODE_PREINT1 || p->mode == VF_MODE_PREINT2;
}

/* The table builders' scratch: with lighting, the 2D table's builder also builds the front-weighted table, which
 * needs more. */
static size_t scratch_bytes(const vf_params_t *p)
{
    return VF_LIT_TABLES && p->lighting && has_2d_table(p) ? vfi_table_scratch_lit_bytes(p->table_size)
                                                           : vfi_table_scratch_bytes(p->table_size);
}

static vf_status_t scratch_alloc(const vf_params_t *p, vfi_table_scratch_t *scratch, vf_arena_t *arena)
{
    return VF_LIT_TABLES && p->lighting && has_2d_table(p) ? vfi_table_scratch_alloc_lit(scratch, p->table_size, arena)
                                                           : vfi_table_scratch_alloc(scratch, p->table_size, arena);
}
static size_t lit_table_bytes(const vf_params_t *p);
#if VF_LIGHTING
static bool lighting_alloc(vf_renderer_t *r, vf_arena_t *arena);
static void update_shading(vf_renderer_t *r, const vf_view_t *view);
#endif

void vf_params_default(vf_params_t *p)
{
    if (!p)
        return;
    p->mode = VF_MODE_PREINT1;
    p->table_size = VF_DEFAULT_TABLE;
    p->table_bits = 16;
    p->lookup = VF_LOOKUP_NEAREST;
    p->correction = VF_CORRECTION_REBUILD;
    p->buffer = VF_BUFFER_SLICE;
    p->rays = 1;
    p->partial_slabs = false;
    p->sample_bits = 0;
    p->intermediate_bits = 16;
    p->warp_bits = 16;
    p->background[0] = p->background[1] = p->background[2] = 0;
    p->lighting = false;
    p->normal_bits = 14;
    p->shade_lookup = VF_LOOKUP_NEAREST; /* docs/usage.md: what bilinear costs and what it buys */
    p->table2_size = VF_DEFAULT_TABLE2;
}

void vf_lighting_default(vf_lighting_t *l)
{
    if (!l)
        return;
    vfi_zero(l, sizeof *l);
    l->shade = true;
    l->light_count = 1; /* a headlight: azimuth and elevation 0 */
    l->ka = 6554;       /* 0.1 */
    l->kd = 45875;      /* 0.7 */
    l->ks = 13107;      /* 0.2 */
    l->shininess = 10;
}

/* The arena bytes of a renderer, over prebuilt storage (pre) or not (NULL): what create reserves. */
static vf_status_t renderer_bytes(const vf_params_t *p, const vf_volume_t *vol, const vf_prebuilt_t *pre,
                                  size_t *bytes)
{
    if (!p || !vol || !bytes)
        return VF_ERR_NULL;
    vf_status_t s = check_params(p);
    if (s == VF_OK)
        s = check_volume(vol);
    if (s == VF_OK && (pre ? !VF_PREBUILT : !VF_BUILD_SLICES))
        s = VF_ERR_UNSUPPORTED;
    if (VF_PREBUILT && s == VF_OK && pre)
        s = vfi_prebuilt_check(p, vol, pre);
    if (s != VF_OK)
        return s;
    uint32_t w, ni;
    if (intermediate_pixels(vol->dims, p->rays, &w, &ni) == 0)
        return VF_ERR_INTERMEDIATE;
    const uint32_t n = p->table_size;
    size_t total = VFI_ALIGN + vfi_arena_block(sizeof(vf_renderer_t));
    for (int a = 0; a < 3 && !pre; a++)
        total += vfi_arena_block(vfi_slices_bytes(vol->dims, a));
    total += VF_RUN_BRICKS ? vfi_bricks_bytes(vol->dims) : 0;
    total += vfi_classify_bytes(n) + table_bytes(p) + lit_table_bytes(p) + normals_bytes(p, vol, pre != NULL) +
             order2_bytes(p);
    total += vfi_arena_block(sizeof(uint16_t) * 4 * reserved_intermediate(vol, p->rays, pre, &w, &ni)) +
             extent_bytes(vol->dims, p->rays);
    *bytes = total;
    return VF_OK;
}

vf_status_t vf_renderer_bytes(const vf_params_t *p, const vf_volume_t *vol, size_t *bytes)
{
    return renderer_bytes(p, vol, NULL, bytes);
}

vf_status_t vf_renderer_prebuilt_bytes(const vf_params_t *p, const vf_volume_t *vol, const vf_prebuilt_t *pre,
                                       size_t *bytes)
{
    return pre ? renderer_bytes(p, vol, pre, bytes) : VF_ERR_NULL;
}

static vf_status_t renderer_create(vf_renderer_t **out, const vf_params_t *p, const vf_volume_t *vol,
                                   const vf_prebuilt_t *pre, vf_arena_t *arena)
{
    if (!out || !p || !vol || !arena)
        return VF_ERR_NULL;
    *out = NULL;
    size_t needed;
    vf_status_t s = renderer_bytes(p, vol, pre, &needed);
    if (s != VF_OK)
        return s;
    vf_renderer_t *r = vfi_arena_alloc(arena, sizeof *r);
    if (!r)
        return VF_ERR_NOMEM;
    /* Every field harmless before anything can fail (as Lua's preinit): NULL pointers, nothing valid yet. */
    vfi_zero(r, sizeof *r);
    r->params = *p;
    r->volume = *vol;
    r->arena = arena;
    r->needed = needed;
    r->prebuilt = VF_PREBUILT && pre != NULL;
    r->storage = pre;

    for (int a = 0; a < 3; a++) {
        vfi_layout(vol->dims, a, &r->layout[a]);
        r->built_slices[a] = pre ? NULL : vfi_arena_alloc(arena, vfi_slices_bytes(vol->dims, a));
        r->slices[a] = pre ? pre->slices[a] : r->built_slices[a];
    }
    uint8_t *brick_range = NULL;
    if (VF_RUN_BRICKS) {
        brick_range = vfi_arena_alloc(arena, vfi_bricks_bytes(vol->dims));
        vfi_bricks_init(&r->bricks, vol->dims, brick_range);
    }
    const uint32_t n = p->table_size;
    const bool lut = p->correction == VF_CORRECTION_LUT;
    /* a trilinear lookup's last slab, of one slice, looks its 2D entries up bilinearly */
    s = vfi_classify_alloc(&r->cls, n, p->lookup == VF_LOOKUP_TRILINEAR ? VF_LOOKUP_BILINEAR : p->lookup, arena);
    if (s == VF_OK)
        s = scratch_alloc(p, &r->table_scratch, arena);
    r->table = vfi_arena_alloc(arena, table_entries(p) * 4 * table_value_bytes(p));
    if (lut) {
        r->lut_f = vfi_arena_alloc(arena, sizeof(uint16_t) * VFI_LUT_KNOTS);
        r->lut_g = vfi_arena_alloc(arena, sizeof(uint32_t) * VFI_LUT_KNOTS);
    }
    if (has_view_table(p))
        r->view_table = vfi_arena_alloc(arena, table_entries(p) * 4 * sizeof(uint16_t));
    r->intermediate_max = reserved_intermediate(vol, p->rays, pre, &r->max_int_w, &r->max_ni);
    r->intermediate = vfi_arena_alloc(arena, sizeof(uint16_t) * 4 * r->intermediate_max);
    r->row_extent = VF_SPECIAL_LOOPS ? vfi_arena_alloc(arena, extent_bytes(vol->dims, p->rays)) : NULL;
    if (s != VF_OK || (VF_SPECIAL_LOOPS && !r->row_extent) || !r->slices[0] || !r->slices[1] || !r->slices[2] ||
        (VF_RUN_BRICKS && !brick_range) || !r->table ||
        (lut && (!r->lut_f || !r->lut_g)) || (has_view_table(p) && !r->view_table) || !r->intermediate)
        return VF_ERR_NOMEM; /* the caller's arena is theirs to reset; *out stays NULL */
#if VF_LIGHTING
    if (p->lighting && !lighting_alloc(r, arena))
        return VF_ERR_NOMEM;
#endif
#if VF_ORDER2
    if (p->mode == VF_MODE_PREINT2) {
        const size_t values = (size_t)p->table2_size * p->table2_size * p->table2_size * 4 * table_value_bytes(p);
        vfi_order2_scalar_entries(&r->cls, p->table2_size, p->lookup == VF_LOOKUP_TRILINEAR);
        r->table2 = vfi_arena_alloc(arena, values);
        if (p->lighting)
            r->lit_table2 = vfi_arena_alloc(arena, 2 * values);
        if (!r->table2 || (p->lighting && !r->lit_table2) ||
            vfi_order2_pieces_alloc(&r->pieces, n, p->lighting, arena) != VF_OK)
            return VF_ERR_NOMEM;
    }
#endif
    r->runs_mark = arena->used;

    r->memory.renderer = vfi_arena_block(sizeof *r);
    for (int a = 0; a < 3 && !pre; a++)
        r->memory.slices += vfi_arena_block(vfi_slices_bytes(vol->dims, a));
    /* the bricks' ranges serve classification (which bricks a transfer function hides), so they count there */
    r->memory.classify = vfi_classify_bytes(n) + (VF_RUN_BRICKS ? vfi_bricks_bytes(vol->dims) : 0);
    r->memory.tables = table_bytes(p);
    r->memory.intermediate = vfi_arena_block(sizeof(uint16_t) * 4 * r->intermediate_max) +
                             extent_bytes(vol->dims, p->rays);
    r->memory.tables += lit_table_bytes(p);
    r->memory.normals = normals_bytes(p, vol, pre != NULL);
    r->memory.order2 = order2_bytes(p);
    *out = r;
    return VF_OK;
}

vf_status_t vf_renderer_create(vf_renderer_t **out, const vf_params_t *p, const vf_volume_t *vol, vf_arena_t *arena)
{
    return renderer_create(out, p, vol, NULL, arena);
}

vf_status_t vf_renderer_create_prebuilt(vf_renderer_t **out, const vf_params_t *p, const vf_volume_t *vol,
                                        const vf_prebuilt_t *pre, vf_arena_t *arena)
{
    if (out)
        *out = NULL;
    return pre ? renderer_create(out, p, vol, pre, arena) : VF_ERR_NULL;
}

vf_status_t vf_renderer_set_window(vf_renderer_t *r, vf_window_t window)
{
    if (!r)
        return VF_ERR_NULL;
    if (window.lo == window.hi)
        return VF_ERR_WINDOW;
    if (is_prebuilt(r) && (window.lo != r->storage->window.lo || window.hi != r->storage->window.hi))
        return VF_ERR_UNSUPPORTED; /* read-only slices of another window: the renderer's slices stand */
    r->have_frame = false; /* a frame begun before must not composite half old, half new data */
    if (VF_BUILD_SLICES && !is_prebuilt(r))
        vfi_slices_build(&r->volume, window, r->built_slices);
    r->window = window;
    if (VF_RUN_BRICKS)
        vfi_bricks_build(&r->bricks, r->slices[2], r->volume.dims);
    r->have_window = true;
    return r->have_tf ? vfi_encode_runs(r) : VF_OK;
}

/* Classify the transfer function; the run lists are then stale (have_runs stays as it was until they are made). */
static vf_status_t classify_tf(vf_renderer_t *r, const vf_tf_t *tf)
{
    vf_status_t s = vfi_classify(&r->cls, tf);
    if (s != VF_OK)
        return s; /* checked before anything was written: the previous transfer function stands */
    r->have_frame = false; /* the frame begun before has tables for the old function: begin again */
    r->have_tf = true;
    r->tf_grey = true; /* every point grey: so is every entry, lit or not (composite_order1.c's grey loops) */
    for (uint32_t i = 0; i < tf->count; i++)
        r->tf_grey = r->tf_grey && tf->points[i].r == tf->points[i].g && tf->points[i].g == tf->points[i].b;
    r->tf_generation++;
    return VF_OK;
}

vf_status_t vf_renderer_set_tf(vf_renderer_t *r, const vf_tf_t *tf)
{
    if (!r)
        return VF_ERR_NULL;
    vf_status_t s = classify_tf(r, tf);
    if (s != VF_OK)
        return s;
    return r->have_window ? vfi_encode_runs(r) : VF_OK;
}

vf_status_t vf_renderer_set_tf_begin(vf_renderer_t *r, const vf_tf_t *tf, uint32_t ranges)
{
    if (r && ranges > VF_MAX_ENCODE_PARTS / 3 && ranges > 1)
        return VF_ERR_ARG;
#if VF_MAX_ENCODE_PARTS >= 6
    /* prebuilt run lists may be adopted: then there is nothing to share out */
    if (r && ranges > 1 && !is_prebuilt(r)) {
        vf_status_t s = classify_tf(r, tf);
        if (s != VF_OK || !r->have_window)
            return s;
        return vfi_encode_parts_begin(r, ranges);
    }
#endif
    return vf_renderer_set_tf(r, tf); /* one range, or prebuilt storage: the whole encoding */
}

vf_status_t vf_renderer_set_lighting(vf_renderer_t *r, const vf_lighting_t *l)
{
    if (!r)
        return VF_ERR_NULL;
#if VF_LIGHTING
    if (!r->params.lighting)
        return VF_ERR_UNSUPPORTED;
    if (l && (l->light_count < 1 || l->light_count > VF_MAX_LIGHTS || l->shininess < 1 || l->shininess > 255 ||
              (l->gradient_hi <= l->gradient_lo && (l->gradient_lo || l->gradient_hi))))
        return VF_ERR_ARG;
    r->have_frame = false; /* a frame begun before has the old shade table */
    r->lit = l != NULL;
    if (l) {
        r->lighting = *l;
        vfi_gradient_ramp(l->gradient_lo, l->gradient_hi, r->ramp);
    }
    r->lighting_generation++;
    return VF_OK;
#else
    (void)l;
    return VF_ERR_UNSUPPORTED;
#endif
}

size_t vf_renderer_needed_bytes(const vf_renderer_t *r)
{
    return r ? r->needed : 0;
}

void vf_renderer_memory(const vf_renderer_t *r, vf_memory_t *m)
{
    if (!r || !m)
        return;
    *m = r->memory;
    m->total = r->arena->used;
}

const vf_params_t *vf_renderer_params(const vf_renderer_t *r)
{
    return r ? &r->params : NULL;
}

vf_status_t vf_renderer_begin(vf_renderer_t *r, const vf_frame_t *frame)
{
    if (!r || !frame)
        return VF_ERR_NULL;
    r->have_frame = false;
    const uint32_t parts = frame->table_parts ? frame->table_parts : 1;
    if (parts > VF_MAX_TABLE_PARTS || (parts > 1 && frame->one_thread))
        return VF_ERR_ARG;
    if (!r->have_window || !r->have_tf || !r->have_runs)
        return VF_ERR_STATE;
    vf_status_t s = vf_factor(&r->factor, &r->volume, &frame->view, frame->width, frame->height);
    if (s == VF_OK)
        s = vf_factor_rays(&r->factor, r->params.rays); /* fits: checked against the largest view at create */
    if (s != VF_OK)
        return s;
    if ((size_t)r->factor.int_w * r->factor.int_h > r->intermediate_max)
        return VF_ERR_NOMEM; /* an intermediate image reserved for smaller views (vf_prebuilt_t) */
    update_tables(r, parts, frame->one_thread, frame->thread_tables);
#if VF_LIGHTING
    if (r->lit)
        update_shading(r, &frame->view);
#endif
    if (VF_MAX_TABLE_PARTS > 1)
        r->frame_parts = parts;
    r->have_frame = true;
    return VF_OK;
}

uint32_t vf_renderer_table_parts(const vf_renderer_t *r)
{
    return r && r->have_frame && !tables_complete(r) ? r->table_parts : 0;
}

size_t vf_renderer_table_part_bytes(const vf_renderer_t *r)
{
    return r ? VFI_ALIGN + scratch_bytes(&r->params) : 0;
}

vf_status_t vf_renderer_build_table_part(vf_renderer_t *r, uint32_t part, void *scratch, size_t bytes)
{
    if (!r || !scratch)
        return VF_ERR_NULL;
    if (!r->have_frame)
        return VF_ERR_STATE;
#if VF_MAX_TABLE_PARTS == 1
    (void)bytes; /* a build for one core has no parts: begin built the table */
    return part == 0 ? VF_OK : VF_ERR_ARG;
#else
    if (part >= r->frame_parts)
        return VF_ERR_ARG;
    if (part >= r->table_parts || r->table_part_done[part])
        return VF_OK; /* nothing to build: the table was up to date, or this part has run */
    if (bytes < vf_renderer_table_part_bytes(r))
        return VF_ERR_NOMEM; /* the promised size, whatever the buffer's alignment */
    const vfi_table_out_t out = table_out(r);
#if VF_ORDER2
    if (r->params.mode == VF_MODE_PREINT2) { /* the 3D table's part; begin built its pieces */
        vfi_order2_table_part(&r->pieces, r->params.table2_size, table2_out(r), part, r->table_parts);
        r->table_part_done[part] = true;
        return VF_OK;
    }
#endif
    if (r->parts_build) {
        vf_arena_t arena;
        vfi_table_scratch_t ts;
        vf_arena_init(&arena, scratch, bytes);
        if (scratch_alloc(&r->params, &ts, &arena) != VF_OK)
            return VF_ERR_NOMEM;
        vfi_preint_table_part(&r->cls, r->tables_slab_q16, &ts, out, part, r->table_parts);
    }
    if (r->view_table) /* the entries this part built, or would have: the lut of this view on each */
        vfi_view_table_part(r->lut_f, r->lut_g, out.q15, r->view_table, r->params.table_size, part, r->table_parts);
    r->table_part_done[part] = true;
    return VF_OK;
#endif
}

const vf_factor_t *vf_renderer_factor(const vf_renderer_t *r)
{
    return r && r->have_frame ? &r->factor : NULL;
}

size_t vf_renderer_band_scratch_bytes(const vf_renderer_t *r, uint32_t band_rows)
{
    return r ? vfi_band_scratch_bytes(r, band_rows) : 0;
}

vf_status_t vf_renderer_composite_band(const vf_renderer_t *r, uint32_t v0, uint32_t v1, void *scratch, size_t bytes)
{
    if (!r || !scratch)
        return VF_ERR_NULL;
    if (!r->have_frame)
        return VF_ERR_STATE;
    if (!tables_complete(r))
        return VF_ERR_STATE; /* a part of the table has not been built */
    if (v0 >= v1 || v1 > r->factor.int_h)
        return VF_ERR_ARG;
#if VF_TABLE_ON_DEMAND
    if (r->thread_tables)
        return VF_ERR_STATE; /* the frame's table is in the threads' copies: vf_renderer_composite_band_in */
#endif
    return vfi_composite_band(r, v0, v1, scratch, bytes, NULL);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Threads' copies of a table built as read (volfix.h, vf_thread_table_t). A copy's memory holds its state (the
 * demand, its scratch's description), the 2D table, the front-weighted table with lighting, and the scratch. */

typedef struct thread_head {
    vfi_demand_t demand;
    vfi_table_scratch_t scratch;
} thread_head_t;

#if VF_TABLE_ON_DEMAND
/* Diagonal d of an n x n table of four values an entry: entries (f, f + d) and (f + d, f), each copied as one
 * object (as preint.c's builder copies them), a move where four values were four. */
typedef struct entry4 {
    uint16_t v[4];
} entry4_t;

static void copy_diagonal(const uint16_t *from, uint16_t *to, uint32_t n, uint32_t d)
{
    const entry4_t *a = (const entry4_t *)from;
    entry4_t *b = (entry4_t *)to;
    for (size_t f = 0, up = d, down = (size_t)d * n; f < n - d; f++, up += n + 1, down += n + 1) {
        b[up] = a[up];
        b[down] = a[down];
    }
}
#endif

size_t vf_renderer_thread_table_bytes(const vf_renderer_t *r)
{
#if VF_TABLE_ON_DEMAND
    const vf_params_t *p = r ? &r->params : NULL;
    if (!p || p->mode != VF_MODE_PREINT1 || p->correction != VF_CORRECTION_REBUILD || p->table_bits == 8)
        return 0; /* never built as read (on_demand) */
    return VFI_ALIGN + vfi_arena_block(sizeof(thread_head_t)) + vfi_arena_block(table_entries(p) * 4 * 2) +
           lit_table_bytes(p) + scratch_bytes(p);
#else
    (void)r;
    return 0;
#endif
}

#if VF_TABLE_ON_DEMAND
/* The copy's state at the start of its memory (aligned as the arena aligns it), or NULL when it is too small. */
static thread_head_t *thread_head(const vf_renderer_t *r, const vf_thread_table_t *t)
{
    if (!t->memory || t->bytes < vf_renderer_thread_table_bytes(r))
        return NULL;
    vf_arena_t arena;
    vf_arena_init(&arena, t->memory, t->bytes);
    return vfi_arena_alloc(&arena, sizeof(thread_head_t));
}
#endif

vf_status_t vf_renderer_thread_table_begin(const vf_renderer_t *r, const vf_thread_table_t *t)
{
    if (!r || !t)
        return VF_ERR_NULL;
    if (!r->have_frame)
        return VF_ERR_STATE;
#if VF_TABLE_ON_DEMAND
    if (!r->thread_tables)
        return VF_OK; /* the frame reads the shared table */
    if (!t->memory)
        return VF_ERR_NULL;
    if (t->bytes < vf_renderer_thread_table_bytes(r))
        return VF_ERR_NOMEM;
    vf_arena_t arena;
    vf_arena_init(&arena, t->memory, t->bytes);
    thread_head_t *h = vfi_arena_alloc(&arena, sizeof *h);
    vfi_table_out_t out = table_out(r);
    out.q15 = vfi_arena_alloc(&arena, table_entries(&r->params) * 4 * 2);
    if (out.lit_q15)
        out.lit_q15 = vfi_arena_alloc(&arena, table_entries(&r->params) * 4 * 2);
    if (!h || !out.q15 || (table_out(r).lit_q15 && !out.lit_q15) || scratch_alloc(&r->params, &h->scratch, &arena) != VF_OK)
        return VF_ERR_NOMEM; /* not with the bytes promised */
    vfi_preint_demand_begin(&h->demand, &r->cls, r->factor.slab_q16, &h->scratch, out);
    h->demand.fill = t->fill;
    h->demand.built = t->built;
    h->demand.context = t->context;
#endif
    return VF_OK;
}

vf_status_t vf_renderer_composite_band_in(const vf_renderer_t *r, uint32_t v0, uint32_t v1, void *scratch,
                                          size_t bytes, const vf_thread_table_t *t)
{
    if (!r || !scratch || !t)
        return VF_ERR_NULL;
#if VF_TABLE_ON_DEMAND
    if (r->have_frame && r->thread_tables) {
        const thread_head_t *h = thread_head(r, t);
        if (!h)
            return VF_ERR_NOMEM;
        if (v0 >= v1 || v1 > r->factor.int_h)
            return VF_ERR_ARG;
        return vfi_composite_band(r, v0, v1, scratch, bytes, &h->demand);
    }
#endif
    return vf_renderer_composite_band(r, v0, v1, scratch, bytes);
}

vf_status_t vf_renderer_copy_diagonal(const vf_renderer_t *r, const vf_thread_table_t *from,
                                      const vf_thread_table_t *to, uint32_t d)
{
    if (!r || !from || !to)
        return VF_ERR_NULL;
#if VF_TABLE_ON_DEMAND
    if (!r->have_frame || !r->thread_tables)
        return VF_ERR_STATE;
    const thread_head_t *a = thread_head(r, from), *b = thread_head(r, to);
    const uint32_t n = r->params.table_size;
    if (!a || !b)
        return VF_ERR_NOMEM;
    if (d >= n)
        return VF_ERR_ARG;
    copy_diagonal(a->demand.out.q15, b->demand.out.q15, n, d);
    if (b->demand.out.lit_q15)
        copy_diagonal(a->demand.out.lit_q15, b->demand.out.lit_q15, n, d);
    return VF_OK;
#else
    (void)d;
    return VF_ERR_STATE;
#endif
}

vf_status_t vf_renderer_warp_band(const vf_renderer_t *r, const vf_image_t *image, uint32_t y0, uint32_t y1)
{
    if (!r || !image)
        return VF_ERR_NULL;
    if (!r->have_frame)
        return VF_ERR_STATE;
    return vfi_warp_band(r, image, y0, y1);
}

vf_status_t vf_renderer_draw(vf_renderer_t *r, const vf_view_t *view, const vf_image_t *image, void *scratch, size_t bytes)
{
    if (!image || !view)
        return VF_ERR_NULL;
    const vf_frame_t frame = {*view, image->width, image->height, 0, false, false};
    vf_status_t s = vf_renderer_begin(r, &frame);
    if (s == VF_OK)
        s = vf_renderer_composite_band(r, 0, r->factor.int_h, scratch, bytes);
    if (s == VF_OK)
        s = vf_renderer_warp_band(r, image, 0, image->height);
    return s;
}

void vfi_renderer_general_loops(vf_renderer_t *r, bool general)
{
    if (r)
        r->general_loops = general;
}

const uint16_t *vfi_renderer_intermediate(const vf_renderer_t *r)
{
    return r && r->have_frame ? r->intermediate : NULL;
}

const uint16_t *vfi_renderer_point_table(const vf_renderer_t *r)
{
    return r && r->tables_valid && tables_complete(r) && r->params.table_bits != 8 && !has_2d_table(&r->params)
               ? r->table
               : NULL;
}

const uint16_t *vfi_renderer_preint_table(const vf_renderer_t *r)
{
#if VF_TABLE_ON_DEMAND
    if (r && r->table_unbuilt)
        return NULL;
#endif
    return r && r->tables_valid && tables_complete(r) && r->params.table_bits != 8 && has_2d_table(&r->params)
               ? r->table
               : NULL;
}

const uint16_t *vfi_renderer_thread_table(const vf_renderer_t *r, const vf_thread_table_t *t)
{
#if VF_TABLE_ON_DEMAND
    const thread_head_t *h = r && t && r->have_frame && r->thread_tables ? thread_head(r, t) : NULL;
    return h ? h->demand.out.q15 : NULL;
#else
    (void)r;
    (void)t;
    return NULL;
#endif
}

const uint16_t *vfi_renderer_order2_table(const vf_renderer_t *r)
{
#if VF_ORDER2
    return r && r->tables_valid && tables_complete(r) && r->params.table_bits != 8 ? r->table2 : NULL;
#else
    (void)r;
    return NULL;
#endif
}

const uint16_t *vfi_renderer_order2_lit_table(const vf_renderer_t *r)
{
#if VF_ORDER2 && VF_LIGHTING
    return r && r->tables_valid && tables_complete(r) && r->params.table_bits != 8 && r->lit_table_valid
               ? r->lit_table2
               : NULL;
#else
    (void)r;
    return NULL;
#endif
}

static vf_status_t check_params(const vf_params_t *p)
{
    if ((unsigned)p->mode >= VF_MODE_COUNT || (unsigned)p->lookup >= VF_LOOKUP_COUNT ||
        (unsigned)p->correction >= VF_CORRECTION_COUNT || (unsigned)p->buffer >= VF_BUFFER_COUNT ||
        (p->table_bits != 8 && p->table_bits != 10 && p->table_bits != 12 && p->table_bits != 16) ||
        (p->rays != 1 && p->rays != 2 && p->rays != 4 && p->rays != 8 && p->rays != 16) ||
        (p->sample_bits != 0 && (p->sample_bits < 4 || p->sample_bits > 16)) ||
        (p->intermediate_bits != 8 && p->intermediate_bits != 12 && p->intermediate_bits != 16) ||
        p->warp_bits < 4 || p->warp_bits > 16)
        return VF_ERR_ARG;
    if (p->table_size < VF_MIN_TABLE || p->table_size > VF_MAX_TABLE)
        return VF_ERR_ARG;
    /* options this build leaves out (vf_config.h); and partial slabs not with the lut, whose Q1.15 knots leave
     * too few bits of a nearly opaque slab's transmittance for a part of it (docs/algorithm.md, section 4c) */
    if (p->rays > VF_MAX_RAYS || (p->partial_slabs && (!VF_PARTIAL_SLABS || p->correction == VF_CORRECTION_LUT)))
        return VF_ERR_UNSUPPORTED;
    /* preint2: a trilinear lookup (its own, and only its); its table's size; builds without it, and partial slabs,
     * which it does not shorten (docs/algorithm.md, section 8) */
    if ((p->lookup == VF_LOOKUP_TRILINEAR) != (p->mode == VF_MODE_PREINT2 && p->lookup != VF_LOOKUP_NEAREST) ||
        (p->mode == VF_MODE_PREINT2 && (p->table2_size < VF_MIN_TABLE2 || p->table2_size > VF_MAX_TABLE2)))
        return VF_ERR_ARG;
    if (p->mode == VF_MODE_PREINT2 && (!VF_ORDER2 || p->partial_slabs))
        return VF_ERR_UNSUPPORTED;
    if (p->normal_bits < 8 || p->normal_bits > 16 || p->normal_bits % 2 ||
        (unsigned)p->shade_lookup > VF_LOOKUP_BILINEAR) /* a shade is nearest or bilinear, never trilinear */
        return VF_ERR_ARG;
    /* lighting in builds without it, and lighting with partial slabs: docs/algorithm.md, section 7 */
    if (p->lighting && (!VF_LIGHTING || p->partial_slabs))
        return VF_ERR_UNSUPPORTED;
    return VF_OK;
}

static vf_status_t check_volume(const vf_volume_t *v)
{
    if (!v->voxels)
        return VF_ERR_NULL;
    if ((unsigned)v->type > VF_VOXEL_I16)
        return VF_ERR_ARG;
    uint32_t sp_min = UINT32_MAX, sp_max = 0;
    for (int a = 0; a < 3; a++) {
        if (v->dims[a] < 2 || v->dims[a] > VF_MAX_DIM)
            return VF_ERR_DIMS;
        if (v->spacing_q16[a] == 0)
            return VF_ERR_SPACING;
        sp_min = v->spacing_q16[a] < sp_min ? v->spacing_q16[a] : sp_min;
        sp_max = v->spacing_q16[a] > sp_max ? v->spacing_q16[a] : sp_max;
    }
    if ((uint64_t)sp_max > (uint64_t)sp_min * VF_MAX_ANISOTROPY)
        return VF_ERR_SPACING;
    /* three padded copies must be addressable */
    uint64_t voxels = (uint64_t)(v->dims[0] + 1) * (v->dims[1] + 1) * (v->dims[2] + 1);
    if (voxels > SIZE_MAX / 4)
        return VF_ERR_DIMS;
    return VF_OK;
}

/* The point table (point, preclass) or the 2D table (preint1), the builders' scratch, the lut. */
/* 8-bit tables are bytes; 10, 12 and 16 bits are kept in 16-bit words */
static size_t table_value_bytes(const vf_params_t *p)
{
    return p->table_bits == 8 ? 1 : 2;
}

static size_t table_entries(const vf_params_t *p)
{
    return has_2d_table(p) ? (size_t)p->table_size * p->table_size : p->table_size;
}

static size_t table_bytes(const vf_params_t *p)
{
    size_t bytes = scratch_bytes(p) + vfi_arena_block(table_entries(p) * 4 * table_value_bytes(p));
    if (p->correction == VF_CORRECTION_LUT)
        bytes += vfi_arena_block(sizeof(uint16_t) * VFI_LUT_KNOTS) + vfi_arena_block(sizeof(uint32_t) * VFI_LUT_KNOTS);
    if (has_view_table(p))
        bytes += vfi_arena_block(table_entries(p) * 4 * sizeof(uint16_t));
    return bytes;
}

/* The lut is applied to each table entry once a view rather than to each segment when a segment's correction
 * depends on its entry alone: nearest lookup, not preclass (which corrects the interpolation of four entries).
 * Not for 8-bit tables, which are asked for to save memory: a 16-bit view table would add twice theirs. Nor above
 * 512 entries, where correcting N^2 entries a view costs what correcting each segment does (engine at 512x512,
 * callgrind, instructions per frame: 1024 entries 207.9 M with a view table, 197.3 M without; 512: 113.3 M and
 * 152.2 M; 256: 85.4 M and 138.4 M). */
static bool has_view_table(const vf_params_t *p)
{
    return VF_VIEW_TABLE && p->correction == VF_CORRECTION_LUT && p->lookup == VF_LOOKUP_NEAREST &&
           p->mode != VF_MODE_PRECLASS && p->mode != VF_MODE_PREINT2 && p->table_bits != 8 && p->table_size <= 512 &&
           !p->lighting;
}

/* The front-weighted table beside the 2D table, in its format (docs/algorithm.md, section 7). */
static size_t lit_table_bytes(const vf_params_t *p)
{
    if (!VF_LIGHTING || !p->lighting || !has_2d_table(p))
        return 0;
    return vfi_arena_block(table_entries(p) * 4 * table_value_bytes(p));
}

/* preint2's 3D table (with lighting, its eight front- and back-weighted values an entry) and pieces. There is no
 * view table of it: the lut corrects each segment (a 3D view table would double the largest part of the memory). */
static size_t order2_bytes(const vf_params_t *p)
{
    if (!VF_ORDER2 || p->mode != VF_MODE_PREINT2)
        return 0;
    const size_t values = (size_t)p->table2_size * p->table2_size * p->table2_size * 4 * table_value_bytes(p);
#if VF_ORDER2
    return vfi_arena_block(values) + (p->lighting ? vfi_arena_block(2 * values) : 0) +
           vfi_order2_pieces_bytes(p->table_size, p->lighting);
#else
    return values;
#endif
}

/* Normal codes and magnitudes per copy and the codes' unit normals (unless prebuilt), the shade table and the
 * ramp. */
static size_t normals_bytes(const vf_params_t *p, const vf_volume_t *vol, bool prebuilt)
{
    if (!VF_LIGHTING || !p->lighting)
        return 0;
    const uint32_t codes = vfi_normal_code_count(vfi_normal_levels(p->normal_bits));
    size_t bytes = 0;
    for (int a = 0; a < 3 && !prebuilt; a++)
        bytes += vfi_arena_block(sizeof(uint16_t) * vfi_slices_bytes(vol->dims, a)) +
                 vfi_arena_block(vfi_slices_bytes(vol->dims, a));
    if (!prebuilt)
        bytes += vfi_arena_block(sizeof(int32_t) * 3 * codes);
    return bytes + vfi_arena_block(sizeof(uint64_t) * codes) + vfi_arena_block(sizeof(uint16_t) * 256);
}


#if VF_LIGHTING
/* The lighting's memory, the normals made from the volume, and the default lighting. False when short. */
static bool lighting_alloc(vf_renderer_t *r, vf_arena_t *arena)
{
    const vf_params_t *p = &r->params;
    const uint32_t levels = vfi_normal_levels(p->normal_bits);
    r->code_count = vfi_normal_code_count(levels);
    uint16_t *codes[3] = {NULL, NULL, NULL};
    uint8_t *magnitudes[3] = {NULL, NULL, NULL};
    for (int a = 0; a < 3 && !is_prebuilt(r); a++) {
        r->codes[a] = codes[a] = vfi_arena_alloc(arena, sizeof(uint16_t) * vfi_slices_bytes(r->volume.dims, a));
        r->magnitudes[a] = magnitudes[a] = vfi_arena_alloc(arena, vfi_slices_bytes(r->volume.dims, a));
        if (!codes[a] || !magnitudes[a])
            return false;
    }
    int32_t *unit = is_prebuilt(r) ? NULL : vfi_arena_alloc(arena, sizeof(int32_t) * 3 * r->code_count);
    if (is_prebuilt(r)) { /* made on a host, checked against these parameters at create */
        for (int a = 0; a < 3; a++) {
            r->codes[a] = r->storage->codes[a];
            r->magnitudes[a] = r->storage->magnitudes[a];
        }
        r->unit = r->storage->unit;
    } else {
        r->unit = unit;
    }
    r->shade = vfi_arena_alloc(arena, sizeof(uint64_t) * r->code_count);
    r->ramp = vfi_arena_alloc(arena, sizeof(uint16_t) * 256);
    if (has_2d_table(p))
        r->lit_table = vfi_arena_alloc(arena, table_entries(p) * 4 * table_value_bytes(p));
    if (!r->unit || !r->shade || !r->ramp || (has_2d_table(p) && !r->lit_table))
        return false;
    if (VF_BUILD_SLICES && !is_prebuilt(r)) {
        vfi_normals_build(&r->volume, levels, codes, magnitudes);
        vfi_normals_decode(levels, unit);
    }
    vf_lighting_t l;
    vf_lighting_default(&l);
    return vf_renderer_set_lighting(r, &l) == VF_OK;
}

/* The shade table for this view's rotation and the lighting, when either changed; and what the bands read. */
static void update_shading(vf_renderer_t *r, const vf_view_t *view)
{
    const bool same_view = r->shade_view.azimuth == view->azimuth && r->shade_view.elevation == view->elevation &&
                           r->shade_view.roll == view->roll;
    if (r->lighting.shade && (!r->shade_valid || !same_view || r->shade_generation != r->lighting_generation)) {
        int32_t rot[3][3];
        vfi_view_rotation(view, rot);
        vfi_shade_table(rot, &r->lighting, r->unit, r->code_count, r->shade);
        r->shade_view = *view;
        r->shade_generation = r->lighting_generation;
        r->shade_valid = true;
    }
    const int k = r->factor.k_axis;
    r->shading.shade = r->lighting.shade ? r->shade : NULL;
    r->shading.ramp = r->lighting.gradient_hi ? r->ramp : NULL;
    r->shading.slices = r->slices[k];
    r->shading.codes = r->codes[k];
    r->shading.magnitudes = r->magnitudes[k];
    r->shading.bilinear = r->params.shade_lookup == VF_LOOKUP_BILINEAR;
}
#endif

/* The intermediate image is at most (n_i + n_k - 1) x (n_j + n_k - 1) voxels for any view, as |shear| <= 1, and with
 * rays R per voxel R (n - 1) + 1 pixels a side (vf_factor_rays). 0 when a side would exceed VF_MAX_INTERMEDIATE. */
static size_t intermediate_pixels(const uint32_t dims[3], uint32_t rays, uint32_t *max_w, uint32_t *max_ni)
{
    size_t most = 0;
    *max_w = 0;
    *max_ni = 0;
    for (int k = 0; k < 3; k++) {
        vfi_layout_t l;
        vfi_layout(dims, k, &l);
        uint64_t w = (uint64_t)rays * (l.ni + l.nk - 2) + 1, h = (uint64_t)rays * (l.nj + l.nk - 2) + 1;
        if (w > VF_MAX_INTERMEDIATE || h > VF_MAX_INTERMEDIATE)
            return 0;
        most = w * h > most ? (size_t)(w * h) : most;
        *max_w = (uint32_t)w > *max_w ? (uint32_t)w : *max_w;
        *max_ni = l.ni > *max_ni ? l.ni : *max_ni;
    }
    return most;
}

/* The intermediate image's pixels that create reserves: the largest of any view, or of the views prebuilt storage
 * was made for. */
static size_t reserved_intermediate(const vf_volume_t *vol, uint32_t rays, const vf_prebuilt_t *pre, uint32_t *max_w,
                                    uint32_t *max_ni)
{
    const size_t most = intermediate_pixels(vol->dims, rays, max_w, max_ni);
    return pre && pre->intermediate_pixels && pre->intermediate_pixels < most ? pre->intermediate_pixels : most;
}

/* The row extents' bytes (renderer.h): two values for each row of the tallest intermediate image of any view, in
 * builds that have them (VF_SPECIAL_LOOPS). */
static size_t extent_bytes(const uint32_t dims[3], uint32_t rays)
{
    if (!VF_SPECIAL_LOOPS)
        return 0;
    uint32_t most = 0;
    for (int k = 0; k < 3; k++) {
        vfi_layout_t l;
        vfi_layout(dims, k, &l);
        const uint32_t h = rays * (l.nj + l.nk - 2) + 1; /* within VF_MAX_INTERMEDIATE: intermediate_pixels checks */
        most = h > most ? h : most;
    }
    return vfi_arena_block(sizeof(uint16_t) * 2 * most);
}

/* Rewind to the mark and run-length encode all three copies; on VF_ERR_NOMEM record what would have fitted. */
vf_status_t vfi_encode_runs(vf_renderer_t *r)
{
    vf_arena_t *arena = r->arena;
    r->have_runs = false;
#if VF_MAX_ENCODE_PARTS >= 6
    r->encode_parts = 0; /* parts of an encoding begun before are void */
#endif
    vfi_arena_rewind(arena, r->runs_mark);
    if (is_prebuilt(r) && vfi_prebuilt_adopt_runs(r)) { /* the prebuilt run lists are of this visibility */
        r->needed = r->runs_mark + VFI_ALIGN;
        r->memory.runs = 0;
        r->have_runs = true;
        return VF_OK;
    }
    /* The three indices first (their sizes are known, so that encodings in parts can write theirs in place), then
     * one pass per axis straight into the arena's free space; only when that is too small are the remaining
     * axes counted, to say how big an arena would do (vf_renderer_needed_bytes). */
    uint32_t *index[3];
    size_t total = 0;
    bool short_of_memory = !vfi_runs_indices(r->arena, r->layout, index, &total);
    for (int a = 0; a < 3; a++) {
        vfi_runs_t *runs = &r->runs[a];
        size_t free_bytes = 0, values;
        uint16_t *pairs = short_of_memory ? NULL : vfi_arena_top(arena, &free_bytes);
        values = vfi_runs_encode(r->slices[a], &r->layout[a], &r->cls, &r->bricks, short_of_memory ? NULL : index[a],
                                 pairs, free_bytes / sizeof(uint16_t));
        runs->row_start = index[a];
        runs->pairs = pairs;
        runs->nj = r->layout[a].nj;
        /* at least one value, so that an all-invisible volume still has a non-NULL array */
        size_t pair_bytes = vfi_arena_block(sizeof(uint16_t) * (values ? values : 1));
        total += pair_bytes;
        if (!runs->pairs || pair_bytes > free_bytes || !vfi_arena_alloc(arena, pair_bytes))
            short_of_memory = true;
    }
    r->needed = r->runs_mark + total + VFI_ALIGN;
    r->memory.runs = total;
    if (short_of_memory)
        return VF_ERR_NOMEM;
    r->have_runs = true;
    return VF_OK;
}

/* The tables depend on the transfer function and on the slab length, which changes with the view; with the
 * lut correction they are built for length 1 once per transfer function and the lut follows the view, applied to
 * every entry of a view table if there is one. A 2D table asked for in parts is left to vf_renderer_build_table_part
 * (its diagonals, or only their view-table entries), and counts as built once every part has run. */
static void update_tables(vf_renderer_t *r, uint32_t parts, bool one_thread, bool thread_tables)
{
    const uint32_t slab = r->factor.slab_q16;
    const bool lut = r->params.correction == VF_CORRECTION_LUT, view = VF_VIEW_TABLE && r->view_table;
    const uint32_t table_slab = lut ? UINT32_C(65536) : slab;
    const vfi_table_out_t out = table_out(r);
    /* compositing reads the view table if there is one, and then corrects nothing */
    r->lookup.q15 = view ? r->view_table : out.q15;
    r->lookup.u8 = out.u8;
    r->lookup.n = r->params.table_size;
    r->lookup.lit_q15 = out.lit_q15; /* set only for lit preint1 frames (table_out) */
    r->lookup.lit_u8 = out.lit_u8;
    r->lookup.lut_f = lut && !view ? r->lut_f : NULL;
    r->lookup.lut_g = lut && !view ? r->lut_g : NULL;
#if VF_ORDER2
    const bool order2 = r->params.mode == VF_MODE_PREINT2;
    if (order2) {
        const vfi_table_out_t out2 = table2_out(r);
        r->lookup2.q15 = out2.q15;
        r->lookup2.u8 = out2.u8;
        r->lookup2.lit_q15 = out2.lit_q15;
        r->lookup2.lit_u8 = out2.lit_u8;
        r->lookup2.n2 = r->params.table2_size;
    }
#else
    const bool order2 = false;
#endif
#if VF_TABLE_ON_DEMAND
    const bool demand = one_thread && on_demand(r);
    /* threads' copies built as read: the shared table is left as it is, stale, so that the next frame that reads
     * it builds it (the lut and view tables are never built as read: on_demand) */
    r->thread_tables = thread_tables && !one_thread && on_demand(r);
    if (r->thread_tables) {
        r->tables_valid = false;
        if (VF_MAX_TABLE_PARTS > 1)
            r->table_parts = 0;
        return;
    }
#else
    (void)one_thread;
    (void)thread_tables;
#endif
    bool build = !r->tables_valid || !tables_complete(r) || r->tables_generation != r->tf_generation ||
                 r->tables_slab_q16 != table_slab;
#if VF_LIGHTING
    /* a lit frame needs the front-weighted table too, which unlit frames leave as it was */
    const bool lit_table = out.lit_q15 || out.lit_u8;
    build = build || (lit_table && !r->lit_table_valid);
    if (build)
        r->lit_table_valid = lit_table;
#endif
#if VF_TABLE_ON_DEMAND
    build = build || (r->table_unbuilt && !demand); /* a frame that needs every entry after one built as read */
    if (build)
        r->table_unbuilt = demand;
#endif
    if (lut && r->lut_slab_q16 != slab) {
        vfi_correction_lut(slab, r->lut_f, r->lut_g); /* rho = d / 1 */
        r->lut_slab_q16 = slab;
    }
    const bool correct = view && (build || r->view_slab_q16 != slab);
    if (build || correct) {
        const bool preint = r->params.mode == VF_MODE_PREINT1;
        const uint32_t split = VF_MAX_TABLE_PARTS > 1 && (preint || order2) && parts > 1 ? parts : 0;
        if (VF_MAX_TABLE_PARTS > 1) { /* constant 0 in builds for one core, which never read them */
            r->table_parts = split;
            r->parts_build = build;
        }
        for (uint32_t p = 0; p < split; p++)
            r->table_part_done[p] = false;
#if VF_ORDER2
        /* preint2: the 2D table (the last slab's) and the 3D table's pieces here, one after the other in the one
         * scratch; the 3D table here too, or in its parts */
        if (order2 && build) {
            const bool lit = VF_LIT_TABLES && (out.lit_q15 || out.lit_u8);
            vfi_preint_table_incremental(&r->cls, table_slab, &r->table_scratch, out);
            vfi_order2_pieces_build(&r->pieces, &r->cls, table_slab, &r->table_scratch, lit);
            if (split == 0)
                vfi_order2_table_part(&r->pieces, r->params.table2_size, table2_out(r), 0, 1);
        } else
#endif
        if (split == 0 && build) {
#if VF_TABLE_ON_DEMAND
            if (demand)
                vfi_preint_demand_begin(&r->demand, &r->cls, table_slab, &r->table_scratch, out);
            else
#endif
            if (preint)
                vfi_preint_table_incremental(&r->cls, table_slab, &r->table_scratch, out);
            else
                vfi_point_table(&r->cls, table_slab, out);
        }
        if (split == 0 && correct)
            vfi_view_table(r->lut_f, r->lut_g, out.q15, r->view_table, table_entries(&r->params));
        r->tables_valid = true;
        r->tables_generation = r->tf_generation;
        r->tables_slab_q16 = table_slab;
        if (view)
            r->view_slab_q16 = slab;
    }
}

/* Whether a frame on one thread builds its 2D table as compositing reads it: when the loops that read the table
 * are composite_order1.c's span_plain or span_plain_lit (the plain path, after update_tables has set the lookup),
 * and without the lut, whose view table is made from every entry, or partial slabs, whose faces read the table
 * elsewhere. A lit frame's diagonals bring their front-weighted values with them. */
#if VF_TABLE_ON_DEMAND
static bool on_demand(const vf_renderer_t *r)
{
    const vf_params_t *p = &r->params;
    return p->mode == VF_MODE_PREINT1 && p->correction == VF_CORRECTION_REBUILD && !p->partial_slabs &&
           !r->general_loops && !lit_general(r) &&
           vfi_plain_path(p->lookup == VF_LOOKUP_BILINEAR, r->lookup.q15, r->lookup.lut_f, p->sample_bits,
                          16 - p->intermediate_bits, p->rays);
}
#endif

static bool tables_complete(const vf_renderer_t *r)
{
    if (VF_MAX_TABLE_PARTS == 1)
        return true; /* no parts: begin builds the whole table */
    for (uint32_t p = 0; p < r->table_parts; p++)
        if (!r->table_part_done[p])
            return false;
    return true;
}

#if VF_ORDER2
/* preint2's 3D table in the 2D table's format, with its lit values when frames are lit. */
static inline vfi_table_out_t table2_out(const vf_renderer_t *r)
{
    vfi_table_out_t out;
    vfi_zero(&out, sizeof out);
    const bool bits16 = r->params.table_bits != 8;
    out.q15 = bits16 ? r->table2 : NULL;
    out.u8 = bits16 ? NULL : r->table2;
    out.grid_bits = r->params.table_bits == 10 || r->params.table_bits == 12 ? r->params.table_bits : 0;
#if VF_LIGHTING
    if (r->lit && r->lit_table2) {
        out.lit_q15 = bits16 ? r->lit_table2 : NULL;
        out.lit_u8 = bits16 ? NULL : r->lit_table2;
    }
#endif
    return out;
}
#endif

static inline vfi_table_out_t table_out(const vf_renderer_t *r)
{
    vfi_table_out_t out;
    const bool bits16 = r->params.table_bits != 8; /* 10 and 12 bits are kept in 16-bit words */
    out.q15 = bits16 ? r->table : NULL;
    out.u8 = bits16 ? NULL : r->table;
    out.grid_bits = r->params.table_bits == 10 || r->params.table_bits == 12 ? r->params.table_bits : 0;
    out.lit_q15 = NULL, out.lit_u8 = NULL;
    out.q30 = NULL, out.lit_q30 = NULL;
#if VF_LIGHTING
    if (r->lit && r->lit_table) { /* preint1 or preint2 with lighting on */
        out.lit_q15 = bits16 ? r->lit_table : NULL;
        out.lit_u8 = bits16 ? NULL : r->lit_table;
    }
#endif
    return out;
}
