/* SPDX-License-Identifier: MIT */
/*
 * preint.c: the pre-integrated table in O(N^2) by incremental subrange integration (Lum, Wilson and Ma 2004;
 * docs/algorithm.md section 2, tables.h), integer only. Its oracle is the brute force in tables.c.
 * This file holds the diagonals, their blocks and the table built as read; preint_runs.h the arithmetic below
 * (runs, moments, entries), preint_intervals.c the intervals' records and transmittances.
 *
 * Along a diagonal |b - f| = r every interval is crossed by a piece of length d / r. The window of intervals
 * f .. f+r-1 gives entry (f, f+r), composited front to back, and entry (f+r, f), back to front. The windows are
 * cut into blocks of r: a window is a suffix of its block (kept in scratch) joined with a prefix of the next
 * (grown one interval a window, in registers).
 *
 * A run of intervals is held with its transmittance t = 1 - opacity, the same seen from either end, and its
 * premultiplied colour seen from each end. An interval v (transmittance t_v, colour weight w, so colour
 * C_v = (1 - t_v) w: docs/algorithm.md) joins a run x
 *   at the end the colour is seen from:  C' = w + t_v (C - w)       (v in front of x)
 *   at the far end:                      C' = C + w (t - t')        (x lets t - t' of v's opacity through)
 * with t' = t t_v either way: one product a channel and direction, rounded once, and C_v is never formed. A join,
 * x in front of y, C = C_x + t_x C_y and t = t_x t_y, is kept exact in Q.60 until the entry is rounded.
 *
 * Where every interval of a block is visible (block_dense, the common case) the growing end's colour is carried
 * as C - w_next in Q.60 before its rounding, w_next the weight of the interval that comes next: then v in front is
 * one multiply-add with a per-table constant, (C' - w_next') 2^30 = t_v (C - w) 2^30 + (w - w_next') 2^30, and the
 * joins take the colour before that rounding. The same numbers as the first line above, but for the half LSB.
 *
 * The bound table_store.h needs: no value exceeds 1.0 by r LSB of Q.30 or more (r <= 1023). Call e = C + t - 1 a
 * run's excess, in LSB. The empty run (C = 0, t = 1) has e = 0. v at the seen end adds at most 1: C' + t' <=
 * t_v (C + t) + (1 - t_v) w + 1 <= 1 + e + 1 (two roundings, w <= 1; half of that before C' is rounded), and less
 * than 1 when x is empty (t' = t_v exactly). v at the far end adds nothing: w (t - t') rounds to at most the
 * integer t - t'. A join adds the two: C + t = C_x + t_x (C_y + t_y) <= 1 + e_x + e_y. A window's front colour
 * joins a suffix grown at its seen end with a prefix grown at its far end (e <= 0), its back colour the other way
 * round, so e < r. Both directions use the one t, which the bounds allow.
 *
 * The front-weighted (lit) outputs (docs/algorithm.md section 7: D_f = sum_k T_k C_k (1 - theta_k) per channel and S_f
 * = sum_k T_k alpha_k (1 - theta_k), theta_k = (k + t(x_k)) / r) are D_f = C - M / r and S_f = A - M_A / r, where M =
 * sum_k T_k C_k (k + t(x_k)) and M_A = sum_k T_k alpha_k (k + t(x_k)) are the emission-position moments seen from the
 * entry's front, positions in intervals. So each run carries, besides its colours, the moments seen from its front and
 * from its back (about the end that direction sees first), opacity's too, in Q.22 (they reach r < 2^10, so that a
 * product with a Q.30 factor stays below 2^64). With g_v = alpha_v t(x_v) of the diagonal's piece length (tables.h,
 * once per interval and diagonal beside t_v), v joins a run x
 *   at the end the moment is seen from:  M' = t_v (M + C) + w g_v        (x's emissions one interval deeper)
 *   at the far end, behind n intervals:  M' = M + w (n (t - t') + t g_v) (v's emission, x letting t - t' through)
 * and for M_A the same with w = 1 and C = A = 1 - t. Two runs join as colours do, the one behind taken the front one's
 * length deeper: M = M_x + t_x (M_y + n_x C_y). block_sparse's runs skip the intervals that change no bit (t = 1, and
 * then g = 0 too) but count them in the positions; where it copies a window's entries to the next, the lit values move:
 * the moments shift by one interval's worth of the window's colour instead. Each step rounds once to Q.22, so a moment
 * is off by about r 2^-22 at most and M / r by 2^-22, a 128th of an LSB of Q1.15 (tests/core/test_lit_tables.c measures
 * every lit value within 0.51 LSB of the exact one). The bound: D_f is C - M / r worked out on C's own unrounded value
 * (window_t) and clamped below at that form's 0, deliberately: M / r is below C exactly (positions k + t(x) < r) but
 * the roundings of a moment can take it a few LSB of Q.30 past a C of a few LSB. Then D_f <= C and S_f <= a hold in
 * every format, rounded the same way by monotonic conversions, and no lit value exceeds 1.0 by more than its entry
 * does.
 */
#include "arena.h"
#include "preint.h"
#include "preint_runs.h"

static VF_ALWAYS_INLINE void block_dense(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo);
static VF_ALWAYS_INLINE void block_dense_grey(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo);
static VF_ALWAYS_INLINE void block_sparse(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo, uint32_t k_hi);
static VF_ALWAYS_INLINE void block_sparse_grey(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo,
                                               uint32_t k_hi);
static VF_ALWAYS_INLINE void block_dense_lit(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo);
static VF_ALWAYS_INLINE void block_dense_grey_lit(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo);
static VF_ALWAYS_INLINE void block_sparse_lit(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo, uint32_t k_hi);
static VF_ALWAYS_INLINE void block_sparse_grey_lit(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo,
                                                   uint32_t k_hi);

size_t vfi_table_scratch_bytes(uint32_t n)
{
    return vfi_arena_block(sizeof(vfi_interval_t) * (n + 1)) + vfi_arena_block(sizeof(vfi_suffix_t) * (n - 1)) +
           vfi_arena_block(sizeof(uint16_t) * (n - 1)) + vfi_arena_block(sizeof(uint16_t) * n);
}

vf_status_t vfi_table_scratch_alloc(vfi_table_scratch_t *scratch, uint32_t n, vf_arena_t *arena)
{
    scratch->suffix_lit = NULL;
    scratch->interval = vfi_arena_alloc(arena, sizeof(vfi_interval_t) * (n + 1));
    scratch->suffix = vfi_arena_alloc(arena, sizeof(vfi_suffix_t) * (n - 1));
    scratch->visible = vfi_arena_alloc(arena, sizeof(uint16_t) * (n - 1));
    scratch->first_visible = vfi_arena_alloc(arena, sizeof(uint16_t) * n);
    return scratch->interval && scratch->suffix && scratch->visible && scratch->first_visible ? VF_OK
                                                                                            : VF_ERR_NOMEM;
}

/* The record of diagonal r (1 .. n - 1) once vfi_preint_list_intervals has run. */
static inline diagonal_t diagonal(const vfi_table_scratch_t *scratch, vfi_table_out_t out, uint32_t n, uint32_t r)
{
    diagonal_t d;
    d.iv = scratch->interval + 1;
    d.visible = scratch->visible;
    d.first_visible = scratch->first_visible;
    d.suf = scratch->suffix;
    d.n = n;
    d.out = out;
    d.r = r;
    return d;
}

/* The block of diagonal d's windows that start at s0 .. s0+r-1 (s0 a multiple of r, s0 + r <= count), both
 * triangles, once the transmittances of its intervals s0 .. block_end(d, s0) + r - 1 are in place. The windows
 * f .. f+r-1 start at f = 0 .. count - r; the block holds the starts s0 .. end, and its visible intervals are
 * listed at k_lo .. k_hi - 1. Blocks share nothing but the transmittances: any one can be built alone. */
static inline uint32_t block_end(const diagonal_t *d, uint32_t s0)
{
    const uint32_t count = d->n - 1, r = d->r;
    return s0 + r - 1 < count - r ? s0 + r - 1 : count - r;
}

static VF_ALWAYS_INLINE void build_block(const diagonal_t *d, uint32_t s0, bool grey, bool lit)
{
    const uint32_t r = d->r, end = block_end(d, s0);
    const uint32_t k_lo = d->first_visible[s0], k_hi = d->first_visible[s0 + r];
    /* the prefixes add intervals s0+r .. end+r-1: when those and the block are all visible, no entry repeats the
     * last one and the suffix of f is listed at k_lo + f - s0 */
    const bool dense = k_hi - k_lo == r && d->first_visible[end + r] - k_hi == end - s0;
    if (!VF_LIT_TABLES || !lit) {
        if (dense)
            VF_SPECIAL_LOOPS && grey ? block_dense_grey(d, s0, end, k_lo) : block_dense(d, s0, end, k_lo);
        else
            VF_SPECIAL_LOOPS && grey ? block_sparse_grey(d, s0, end, k_lo, k_hi) : block_sparse(d, s0, end, k_lo, k_hi);
    } else {
        if (dense)
            VF_SPECIAL_LOOPS && grey ? block_dense_grey_lit(d, s0, end, k_lo) : block_dense_lit(d, s0, end, k_lo);
        else
            VF_SPECIAL_LOOPS && grey ? block_sparse_grey_lit(d, s0, end, k_lo, k_hi)
                                     : block_sparse_lit(d, s0, end, k_lo, k_hi);
    }
}

/* Diagonal r, both triangles: transmittances for pieces of d / r, then the blocks. */
static void build_diagonal(const vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch,
                           uint32_t visible_count, bool grey, vfi_table_out_t out, uint32_t r)
{
    const uint32_t count = cls->n - 1; /* count intervals */
    const diagonal_t d = diagonal(scratch, out, cls->n, r);
    vfi_preint_transmittances(scratch, visible_count, count, vfi_preint_piece_length_q28(slab_q16, r));
    for (uint32_t s0 = 0; s0 + r <= count; s0 += r)
        build_block(&d, s0, grey, false);
}

/* The same with the front-weighted outputs (lit builds): alpha t(x) beside each transmittance, the lit blocks.
 * Kept apart from build_diagonal, not a shared body with a flag: so inlined, the unlit builder's loop came out
 * 0.7 to 1.1% longer (callgrind, 256 entries, presets ct-skin-bone, mr-brain, ct-bone). */
static void build_diagonal_lit(const vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch,
                               uint32_t visible_count, bool grey, vfi_table_out_t out, uint32_t r)
{
    const uint32_t count = cls->n - 1;
    diagonal_t d = diagonal(scratch, out, cls->n, r);
    d.suf_lit = scratch->suffix_lit;
    d.recip = vfi_udiv64((UINT64_C(1) << 40) + r / 2, r);
    vfi_preint_transmittances_lit(scratch, visible_count, count, vfi_preint_piece_length_q28(slab_q16, r));
    for (uint32_t s0 = 0; s0 + r <= count; s0 += r)
        build_block(&d, s0, grey, true);
}

/* The diagonals share nothing but the classification, so parts can build them side by side: part p of P takes
 * the diagonal itself when p = 0 and the diagonals r = p + 1, p + 1 + P, ..., which spreads the long ones
 * (n - r entries) and the short ones alike. Each part lists the intervals in its own scratch. */
void vfi_preint_table_part(const vfi_classify_t *cls, uint32_t slab_q16, const vfi_table_scratch_t *scratch,
                           vfi_table_out_t out, uint32_t part, uint32_t parts)
{
    if (VF_MAX_TABLE_PARTS == 1) /* a build without parts: the code of one */
        part = 0, parts = 1;
    const uint32_t n = cls->n;
    if (part == 0)
        vfi_point_entries(cls, slab_q16, out, n + 1); /* the diagonal */
    bool grey;
    const uint32_t visible_count = vfi_preint_list_intervals(cls, scratch, &grey);
    if (vfi_table_out_lit(out))
        for (uint32_t r = part + 1; r < n; r += parts)
            build_diagonal_lit(cls, slab_q16, scratch, visible_count, grey, out, r);
    else
        for (uint32_t r = part + 1; r < n; r += parts)
            build_diagonal(cls, slab_q16, scratch, visible_count, grey, out, r);
}

void vfi_store_entry(const vfi_table_out_t *out, size_t entry, uint32_t r, uint32_t g, uint32_t b, uint32_t a)
{
    vfi_store_q30(*out, entry, r, g, b, a);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* A block of windows. */

/* Every interval of the block s0 .. s0+r-1 and of the prefixes visible: the suffix from f (kept at k_lo + f - s0)
 * for f down from the block's end, then window f = the suffix from f joined with the prefix s0+r .. f+r-1.
 * The suffixes from past end (the last block of a diagonal) start no window: composited, not kept. lit: the runs'
 * moments beside them (the suffixes' kept in d->suf_lit), and each window's front-weighted values. */
static VF_ALWAYS_INLINE void block_dense_body(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo,
                                             bool grey, bool lit)
{
    if (!VF_LIT_TABLES) /* a build without them: the unlit code alone */
        lit = false;
    const uint32_t n = d->n, r = d->r;
    const vfi_interval_t *v = d->iv + s0 + r - 1, *stop = d->iv + end; /* the block's last interval */
    run_t acc = empty_run(v);
    moments_t am, pm; /* lit: the suffix's and the prefix's moments */
    if (lit)
        am = pm = no_moments();
    uint32_t depth = 0; /* lit: intervals in acc */
    for (; v > stop; v--)
        lit ? dense_add_lit(&acc, &am, v, depth++, true, grey) : run_add_front(&acc, v, grey);
    vfi_suffix_t *s = d->suf + k_lo + (end - s0);
    for (stop = d->iv + s0; v >= stop; v--, s--) {
        lit ? dense_add_lit(&acc, &am, v, depth++, true, grey) : run_add_front(&acc, v, grey);
        /* C 2^30 + the half of Q1.15 = x + w_next 2^30 - 2^29 + the half, which is v[-1].w_q60 */
        s->front_q60[0] = (uint64_t)(acc.xr + (int64_t)v[-1].w_q60[0]);
        s->back[0] = (uint32_t)(acc.cr >> 30);
        if (!grey) {
            s->front_q60[1] = (uint64_t)(acc.xg + (int64_t)v[-1].w_q60[1]);
            s->front_q60[2] = (uint64_t)(acc.xb + (int64_t)v[-1].w_q60[2]);
            s->back[1] = (uint32_t)(acc.cg >> 30);
            s->back[2] = (uint32_t)(acc.cb >> 30);
        }
        s->t = acc.t;
        if (lit)
            d->suf_lit[s - d->suf] = am;
    }
    s++;

    const vfi_table_out_t out = d->out;
    const bool q15 = out.q15 && !out.grid_bits;
    const vfi_suffix_t *last = s + (end - s0);
    size_t up = (size_t)s0 * n + s0 + r, down = (size_t)(s0 + r) * n + s0;
    v = d->iv + s0 + r; /* the interval after the prefix */
    const vfi_interval_t *prefix = v; /* lit: v - prefix intervals are in the prefix */
    run_t pre = empty_run(v);
    for (;; s++, v++) {
        const window_t x = join(s, (uint32_t)(pre.cr >> 30), (uint32_t)(pre.cg >> 30), (uint32_t)(pre.cb >> 30),
                                (uint64_t)(pre.xr + (int64_t)v->w_q60[0]),
                                (uint64_t)(pre.xg + (int64_t)v->w_q60[1]), (uint64_t)(pre.xb + (int64_t)v->w_q60[2]),
                                pre.t, grey);
        store_window(out, q15, up, down, &x);
        if (lit) {
            const vfi_suffix_lit_t *sl = d->suf_lit + (s - d->suf);
            const uint32_t p_cf[3] = {(uint32_t)(pre.cr >> 30), (uint32_t)(pre.cg >> 30), (uint32_t)(pre.cb >> 30)};
            const uint32_t np = (uint32_t)(v - prefix);
            window_moments_t wm;
            lit_window(d, &x, sl->front, sl->back, s->back, s->t, pm.front, pm.back, p_cf, pre.t, r - np, np, grey,
                       up, down, &wm);
        }
        if (s == last)
            break;
        lit ? dense_add_lit(&pre, &pm, v, (uint32_t)(v - prefix), false, grey) : run_add_back(&pre, v, grey);
        up += n + 1;
        down += n + 1;
    }
}

static VF_ALWAYS_INLINE void block_dense(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo)
{
    block_dense_body(d, s0, end, k_lo, false, false);
}

/* A grey transfer function's block (every weight's three channels equal, vfi_preint_list_intervals): the three channels are
 * the same numbers, so one is worked out and stored three times; the table is the three-channel one to the bit
 * (tests/core/test_classify_tables.c); about 2% of engine's preint1 frame (docs/performance.md). Not in builds
 * without VF_SPECIAL_LOOPS. */
static VF_ALWAYS_INLINE void block_dense_grey(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo)
{
    block_dense_body(d, s0, end, k_lo, true, false);
}

static VF_ALWAYS_INLINE void block_dense_lit(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo)
{
    block_dense_body(d, s0, end, k_lo, false, true);
}

static VF_ALWAYS_INLINE void block_dense_grey_lit(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo)
{
    block_dense_body(d, s0, end, k_lo, true, true);
}

/* block_sparse's window f, front-weighted: the suffix from the first visible interval at or after f (listed at k,
 * none when k = k_hi) has its front moments taken from there to f; the prefix its back moments from the back of
 * the interval that joined it last (p_back) to the window's back. The positions count every interval, seen or
 * not: that is why no window's lit values repeat the last one's, where its main ones do. The moments into *m;
 * a window of nothing seen (both runs' transmittance 1, so every sum exactly 0) stores zeros and returns false.
 * grey: the first channel and opacity alone, as lit_window reads them. */
static VF_ALWAYS_INLINE bool sparse_lit_window(const diagonal_t *d, const window_t *x, uint32_t s0, uint32_t f,
                                               uint32_t k_hi, const pair_t *pre, const moments_t *pm,
                                               uint32_t p_back, size_t up, size_t down, window_moments_t *m, bool grey)
{
    static const uint32_t no_colour[3] = {0, 0, 0};
    const uint32_t r = d->r, k = d->first_visible[f];
    uint64_t sf[4], pb[4];
    const uint64_t *sb = sf;
    const uint32_t *s_cb = no_colour;
    uint32_t st = ONE_Q30;
    if (k < k_hi) {
        const vfi_suffix_t *s = &d->suf[k];
        st = s->t;
        if (st != ONE_Q30) {
            const vfi_suffix_lit_t *sl = &d->suf_lit[k];
            const uint64_t delta = d->visible[k] - f;
            for (int c = 0; c < (grey ? 1 : 3); c++) /* block_sparse keeps the colour as (C << 30) + the half */
                sf[c] = sl->front[c] + delta * q22_of_q30((s->front_q60[c] - HALF_Q15_IN_Q60) >> 30);
            sf[3] = sl->front[3] + delta * q22_of_q30(ONE_Q30 - st);
            sb = sl->back;
            s_cb = s->back;
        }
    }
    if (st == ONE_Q30) {
        if (pre->t == ONE_Q30) {
            store_nothing_seen(d->out, up, down);
            return false;
        }
        sf[0] = sf[1] = sf[2] = sf[3] = 0;
        sb = sf;
        s_cb = no_colour;
    }
    const uint64_t eps = f + r - 1 - p_back;
    pb[0] = pm->back[0] + eps * q22_of_q30(pre->br);
    if (!grey) {
        pb[1] = pm->back[1] + eps * q22_of_q30(pre->bg);
        pb[2] = pm->back[2] + eps * q22_of_q30(pre->bb);
    }
    pb[3] = pm->back[3] + eps * q22_of_q30(ONE_Q30 - pre->t);
    const uint32_t p_cf[3] = {pre->r, pre->g, pre->b};
    lit_window(d, x, sf, sb, s_cb, st, pm->front, pb, p_cf, pre->t, s0 + r - f, f - s0, grey, up, down, m);
    return true;
}

/* The next window of a run block_sparse copies (the interval it drops and the one it adds both seen through): every
 * emission one interval nearer its front and one farther from its back, m->up less the colours and opacity seen
 * from the front, m->down more those from the back (not below 0: the rounding of those may take a little more
 * than the moment holds, where all of it is next to the front). */
static VF_ALWAYS_INLINE void sparse_lit_next(const diagonal_t *d, const window_t *x, window_moments_t *m,
                                             size_t up, size_t down, bool grey)
{
    const uint64_t cu[4] = {x->r, x->g, x->b, x->a}, cd[4] = {x->br, x->bg, x->bb, x->a};
    for (int c = 0; c < 4; c++) {
        if (grey && (c == 1 || c == 2)) /* grey: the first channel and opacity */
            continue;
        const uint64_t u = (cu[c] - HALF_Q15_IN_Q60 + HALF_Q22_IN_Q60) >> 38; /* Q.60 with the half, to Q.22 */
        m->up[c] = m->up[c] > u ? m->up[c] - u : 0;
        m->down[c] += (cd[c] - HALF_Q15_IN_Q60 + HALF_Q22_IN_Q60) >> 38;
    }
    store_lit_moments(d, x, m, grey, up, down);
}

/* The same with invisible intervals (t = 1; any interval with t = 1 changes no bit of a composite, so skipping
 * it is exact, and for transfer functions with narrow peaks that is most of the work). Suffixes are kept for
 * the visible intervals only, k_lo .. k_hi - 1; the suffix from f is the one from the first visible interval at
 * or after f, or the empty run. While the interval a window drops and the one the next adds both have t = 1, the
 * next window's entries are this one's (but for their front-weighted values, which lit works out for each).
 * grey: as block_dense's, one channel worked out for three (the suffixes' and runs' others are never read). */
static VF_ALWAYS_INLINE void block_sparse_body(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo,
                                              uint32_t k_hi, bool grey, bool lit)
{
    if (!VF_LIT_TABLES) /* a build without them: the unlit code alone */
        lit = false;
    const uint32_t n = d->n, r = d->r;
    const vfi_interval_t *iv = d->iv;
    const uint16_t *visible = d->visible, *first_visible = d->first_visible;
    uint32_t k = k_hi, k_end = first_visible[end] + 1u; /* the suffixes from k_end on start no window */
    pair_t acc = empty_pair();
    moments_t am, pm; /* lit: the suffix's and the prefix's moments */
    if (lit)
        am = pm = no_moments();
    uint32_t s_front = s0 + r, p_back = s0 + r - 1; /* lit: the interval that joined each last */
    for (; k > k_end; k--)
        lit ? sparse_add_lit(&acc, &am, iv, visible[k - 1], &s_front, s0 + r - 1 - visible[k - 1], true, grey)
            : pair_add_front(&acc, iv + visible[k - 1], grey);
    for (; k > k_lo; k--) {
        lit ? sparse_add_lit(&acc, &am, iv, visible[k - 1], &s_front, s0 + r - 1 - visible[k - 1], true, grey)
            : pair_add_front(&acc, iv + visible[k - 1], grey);
        vfi_suffix_t *s = &d->suf[k - 1];
        s->front_q60[0] = ((uint64_t)acc.r << 30) + HALF_Q15_IN_Q60;
        s->back[0] = acc.br;
        if (!grey) {
            s->front_q60[1] = ((uint64_t)acc.g << 30) + HALF_Q15_IN_Q60;
            s->front_q60[2] = ((uint64_t)acc.b << 30) + HALF_Q15_IN_Q60;
            s->back[1] = acc.bg;
            s->back[2] = acc.bb;
        }
        s->t = acc.t;
        if (lit)
            d->suf_lit[k - 1] = am;
    }

    const vfi_table_out_t out = d->out;
    const bool q15 = out.q15 && !out.grid_bits;
    size_t up = (size_t)s0 * n + s0 + r, down = (size_t)(s0 + r) * n + s0;
    vfi_suffix_t none; /* the empty suffix */
    none.front_q60[0] = none.front_q60[1] = none.front_q60[2] = HALF_Q15_IN_Q60;
    none.back[0] = none.back[1] = none.back[2] = 0;
    none.t = ONE_Q30;
    pair_t pre = empty_pair();
    for (uint32_t f = s0;;) {
        k = first_visible[f];
        const window_t x = join(k < k_hi ? &d->suf[k] : &none, pre.r, pre.g, pre.b,
                                ((uint64_t)pre.br << 30) + HALF_Q15_IN_Q60, ((uint64_t)pre.bg << 30) + HALF_Q15_IN_Q60,
                                ((uint64_t)pre.bb << 30) + HALF_Q15_IN_Q60, pre.t, grey);
        store_window(out, q15, up, down, &x);
        window_moments_t wm;
        const bool seen = lit && sparse_lit_window(d, &x, s0, f, k_hi, &pre, &pm, p_back, up, down, &wm, grey);
        for (; f < end && iv[f].t == ONE_Q30 && iv[f + r].t == ONE_Q30; f++) {
            up += n + 1;
            down += n + 1;
            copy_pair(out, up, down, n + 1);
            if (seen)
                sparse_lit_next(d, &x, &wm, up, down, grey);
            else if (lit)
                store_nothing_seen(d->out, up, down);
        }
        if (f == end)
            break;
        if (iv[f + r].t != ONE_Q30)
            lit ? sparse_add_lit(&pre, &pm, iv, f + r, &p_back, f - s0, false, grey)
                : pair_add_back(&pre, iv + f + r, grey);
        f++;
        up += n + 1;
        down += n + 1;
    }
}

static VF_ALWAYS_INLINE void block_sparse(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo, uint32_t k_hi)
{
    block_sparse_body(d, s0, end, k_lo, k_hi, false, false);
}

/* A grey transfer function's sparse block (block_dense_grey's reasons; not in builds without VF_SPECIAL_LOOPS). */
static VF_ALWAYS_INLINE void block_sparse_grey(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo,
                                               uint32_t k_hi)
{
    block_sparse_body(d, s0, end, k_lo, k_hi, true, false);
}

static VF_ALWAYS_INLINE void block_sparse_lit(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo, uint32_t k_hi)
{
    block_sparse_body(d, s0, end, k_lo, k_hi, false, true);
}

static VF_ALWAYS_INLINE void block_sparse_grey_lit(const diagonal_t *d, uint32_t s0, uint32_t end, uint32_t k_lo,
                                                   uint32_t k_hi)
{
    block_sparse_body(d, s0, end, k_lo, k_hi, true, true);
}

#if VF_TABLE_ON_DEMAND
/* ---------------------------------------------------------------------------------------------------------- */
/* The table built as it is read (tables.h). Every entry is marked unbuilt as one object (entry_q15_t, as
 * copy_pair copies them), then the diagonal itself is built over the marks. */
void vfi_preint_demand_begin(vfi_demand_t *demand, const vfi_classify_t *cls, uint32_t slab_q16,
                             const vfi_table_scratch_t *scratch, vfi_table_out_t out)
{
    const uint32_t n = cls->n;
    entry_q15_t unbuilt, *e = (entry_q15_t *)out.q15;
    unbuilt.v[0] = unbuilt.v[1] = unbuilt.v[2] = VFI_UNBUILT_Q15;
    unbuilt.v[3] = 0;
    /* four entries a step: this runs over the whole table every frame */
    size_t k = 0;
    for (; k + 4 <= (size_t)n * n; k += 4) {
        e[k] = unbuilt;
        e[k + 1] = unbuilt;
        e[k + 2] = unbuilt;
        e[k + 3] = unbuilt;
    }
    for (; k < (size_t)n * n; k++)
        e[k] = unbuilt;
    vfi_point_entries(cls, slab_q16, out, n + 1);
    demand->cls = cls;
    demand->scratch = scratch;
    demand->out = out;
    demand->slab_q16 = slab_q16;
    demand->visible_count = vfi_preint_list_intervals(cls, scratch, &demand->grey);
    demand->fill = NULL;
    demand->built = NULL;
    demand->context = NULL;
}

/* Entry (f, b)'s block of its diagonal r = |b - f| (build_block): the window lo .. lo+r-1, lo = min(f, b), gives
 * both (lo, lo+r) and (lo+r, lo), and is in the block from s0 = lo - lo mod r. Only that block's intervals get
 * their transmittances for pieces of d / r, so a block costs O(r) however long its diagonal: a frame reads few
 * of a short diagonal's many blocks (docs/performance.md). */
void vfi_preint_demand_entry(const vfi_demand_t *demand, uint32_t f, uint32_t b)
{
    const uint32_t lo = f < b ? f : b, r = f < b ? b - f : f - b;
    if (r == 0) /* the diagonal itself: built at begin */
        return;
    if (demand->fill) { /* a thread's own copy: whole diagonals, which the other threads' copies can take */
        if (demand->fill(demand->context, r))
            return;
        if (vfi_table_out_lit(demand->out))
            build_diagonal_lit(demand->cls, demand->slab_q16, demand->scratch, demand->visible_count, demand->grey,
                               demand->out, r);
        else
            build_diagonal(demand->cls, demand->slab_q16, demand->scratch, demand->visible_count, demand->grey,
                           demand->out, r);
        if (demand->built)
            demand->built(demand->context, r);
        return;
    }
    const vfi_table_scratch_t *scratch = demand->scratch;
    diagonal_t d = diagonal(scratch, demand->out, demand->cls->n, r);
    const uint32_t s0 = lo - lo % r;
    const uint32_t k_lo = scratch->first_visible[s0], k_hi = scratch->first_visible[block_end(&d, s0) + r];
    const uint64_t length_q28 = vfi_preint_piece_length_q28(demand->slab_q16, r);
    if (VF_LIT_TABLES && vfi_table_out_lit(demand->out)) {
        vfi_preint_transmittances_listed(scratch, k_lo, k_hi, length_q28, true);
        d.suf_lit = scratch->suffix_lit;
        d.recip = vfi_udiv64((UINT64_C(1) << 40) + r / 2, r);
        build_block(&d, s0, demand->grey, true);
    } else {
        vfi_preint_transmittances_listed(scratch, k_lo, k_hi, length_q28, false);
        build_block(&d, s0, demand->grey, false);
    }
}
#endif
