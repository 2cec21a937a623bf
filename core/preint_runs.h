/* SPDX-License-Identifier: MIT */
/*
 * preint_runs.h: the arithmetic of preint.c's runs of intervals, their emission-position moments and the entries
 * they round to (preint.c's header comment gives the formulas and their bounds). Included by preint.c alone and
 * static, so that the block loops inline every step.
 */
#ifndef VF_PREINT_RUNS_H
#define VF_PREINT_RUNS_H

#include "fixmath.h"
#include "preint.h"
#include "table_store.h"

/* One diagonal while it is built. */
typedef struct diagonal {
    const vfi_interval_t *iv; /* interval m at iv + m, m = -1 .. n - 1 (the first and last colourless) */
    const uint16_t *visible, *first_visible;
    vfi_suffix_t *suf;        /* a block's suffixes, by position in visible */
    uint32_t n, r;            /* entries a table axis; intervals a window */
    vfi_table_out_t out;
    vfi_suffix_lit_t *suf_lit; /* lit builds: the suffixes' moments, at the same positions */
    uint64_t recip;           /* lit builds: round(2^40 / r), so that M / r = M recip 2^-40 */
} diagonal_t;

/* A run's emission-position moments while it grows (lit builds), Q.22. */
typedef vfi_suffix_lit_t moments_t;

/* A run in Q.30 (block_sparse). */
typedef struct pair {
    uint32_t r, g, b, br, bg, bb, t;
} pair_t;

/* A run as block_dense grows it at one end: the colour seen from that end as x = (C - w_next) 2^30 + 2^29 in
 * Q.60, C before its rounding (so x >> 30 is C - w_next rounded); the colour seen from the other end exactly, as
 * c = C 2^30 + 2^29 in Q.60 (a sum of products w dt: so c >> 30 is C rounded). */
typedef struct run {
    int64_t xr, xg, xb;
    uint64_t cr, cg, cb;
    uint32_t t;
} run_t;

/* A window's two entries before rounding: colour seen from the front and from the back, and opacity, Q.60 with
 * half an LSB of Q1.15 added. */
typedef struct window {
    uint64_t r, g, b, br, bg, bb, a;
} window_t;

static void store_pair_q30(vfi_table_out_t out, size_t up, size_t down, uint32_t r, uint32_t g, uint32_t b,
                           uint32_t br, uint32_t bg, uint32_t bb, uint32_t a);

/* ---------------------------------------------------------------------------------------------------------- */
/* Runs of intervals (the header comment gives the arithmetic and its bound). */

static inline uint32_t mul_q30(uint32_t a, uint32_t b)
{
    return (uint32_t)(((uint64_t)a * b + HALF_Q30) >> 30);
}

/* Colour c with an interval of weight w behind it, of which the run lets dt of opacity through: c + w dt. */
static inline uint32_t in_front(uint32_t c, uint32_t w, uint32_t dt)
{
    return c + (uint32_t)(((uint64_t)w * dt + HALF_Q30) >> 30);
}

/* Colour c seen through an interval of transmittance t_v and weight w in front of it: w + t_v (c - w). Signed:
 * the shift is arithmetic, as vfi_sincos's products rely on too. */
static inline uint32_t behind(uint32_t t_v, uint32_t c, uint32_t w)
{
    return (uint32_t)((int64_t)w + (((int64_t)t_v * ((int64_t)c - (int64_t)w) + (int64_t)HALF_Q30) >> 30));
}

/* Interval v joins run x at its front (block_sparse). grey: the first channel alone (the others, never read, are
 * left as they were). */
static VF_ALWAYS_INLINE void pair_add_front(pair_t *x, const vfi_interval_t *v, bool grey)
{
    const uint32_t t = mul_q30(x->t, v->t), dt = x->t - t;
    x->r = behind(v->t, x->r, v->w[0]);
    x->br = in_front(x->br, v->w[0], dt);
    if (!grey) {
        x->g = behind(v->t, x->g, v->w[1]);
        x->b = behind(v->t, x->b, v->w[2]);
        x->bg = in_front(x->bg, v->w[1], dt);
        x->bb = in_front(x->bb, v->w[2], dt);
    }
    x->t = t;
}

/* Interval v joins run x at its back (block_sparse). */
static VF_ALWAYS_INLINE void pair_add_back(pair_t *x, const vfi_interval_t *v, bool grey)
{
    const uint32_t t = mul_q30(x->t, v->t), dt = x->t - t;
    x->r = in_front(x->r, v->w[0], dt);
    x->br = behind(v->t, x->br, v->w[0]);
    if (!grey) {
        x->g = in_front(x->g, v->w[1], dt);
        x->b = in_front(x->b, v->w[2], dt);
        x->bg = behind(v->t, x->bg, v->w[1]);
        x->bb = behind(v->t, x->bb, v->w[2]);
    }
    x->t = t;
}

static inline pair_t empty_pair(void)
{
    pair_t x;
    x.r = x.g = x.b = x.br = x.bg = x.bb = 0; /* field by field: a zero aggregate can compile to a memset call */
    x.t = ONE_Q30;
    return x;
}

/* The empty run, with interval v next: x = (0 - w) 2^30 + 2^29. */
static inline run_t empty_run(const vfi_interval_t *v)
{
    run_t x;
    x.xr = (int64_t)HALF_Q30 - ((int64_t)v->w[0] << 30);
    x.xg = (int64_t)HALF_Q30 - ((int64_t)v->w[1] << 30);
    x.xb = (int64_t)HALF_Q30 - ((int64_t)v->w[2] << 30);
    x.cr = x.cg = x.cb = HALF_Q30;
    x.t = ONE_Q30;
    return x;
}

/* Interval v joins run x at its front; v - 1 comes next: x' = t_v (x >> 30) + v->step, step = (w - w_before) 2^30
 * + 2^29 (vfi_preint_list_intervals). */
static VF_ALWAYS_INLINE void run_add_front(run_t *x, const vfi_interval_t *v, bool grey)
{
    const uint32_t t = mul_q30(x->t, v->t), dt = x->t - t;
    x->xr = (int64_t)v->t * (x->xr >> 30) + v->step[0];
    x->cr += (uint64_t)v->w[0] * dt;
    if (!grey) {
        x->xg = (int64_t)v->t * (x->xg >> 30) + v->step[1];
        x->xb = (int64_t)v->t * (x->xb >> 30) + v->step[2];
        x->cg += (uint64_t)v->w[1] * dt;
        x->cb += (uint64_t)v->w[2] * dt;
    }
    x->t = t;
}

/* Interval v joins run x at its back; v + 1 comes next: the constant is (w - w_after) 2^30 + 2^29, which is
 * 2^30 - v[1].step (added and subtracted in that order: gcc then adds an immediate and subtracts from memory, one
 * instruction fewer a channel than forming 2^30 - step first). */
static VF_ALWAYS_INLINE void run_add_back(run_t *x, const vfi_interval_t *v, bool grey)
{
    const uint32_t t = mul_q30(x->t, v->t), dt = x->t - t;
    x->xr = (int64_t)v->t * (x->xr >> 30) + (int64_t)ONE_Q30 - v[1].step[0];
    x->cr += (uint64_t)v->w[0] * dt;
    if (!grey) {
        x->xg = (int64_t)v->t * (x->xg >> 30) + (int64_t)ONE_Q30 - v[1].step[1];
        x->xb = (int64_t)v->t * (x->xb >> 30) + (int64_t)ONE_Q30 - v[1].step[2];
        x->cg += (uint64_t)v->w[1] * dt;
        x->cb += (uint64_t)v->w[2] * dt;
    }
    x->t = t;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Emission-position moments (lit builds; the header comment gives the arithmetic and its bounds). */

#define HALF_Q22_IN_Q60 (UINT64_C(1) << 37)

static inline uint64_t q22_of_q30(uint64_t v)
{
    return (v + 128u) >> 8;
}

static inline moments_t no_moments(void)
{
    moments_t m;
    for (int c = 0; c < 4; c++) /* field by field, as empty_pair */
        m.front[c] = m.back[c] = 0;
    return m;
}

/* The colour block_dense's run is seen with from its growing end, from x = (C - w) 2^30 + 2^29 with w the weight
 * of the interval that joins next: C in Q.22. */
static inline uint64_t dense_colour_q22(int64_t x, uint32_t w)
{
    return ((uint64_t)(x + ((int64_t)w << 30)) + HALF_Q22_IN_Q60) >> 38;
}

/* Interval v (transmittance t_v, depth-weighted opacity g_v = alpha_v t(x_v)) joins a run, whose transmittance
 * goes from t0 to t, at the front (at_front) or at the back. The moments about the end v joins at take every
 * emission one interval deeper behind v, and v's own: m' = t_v (m + C) + w g_v, where shift[c] = gap C (C the
 * colour, shift[3] gap A the opacity, seen from that end before v joins, Q.22; gap 1 unless intervals that change
 * no bit lie between). The moments about the other end take v's emission behind the run's depth intervals,
 * T_x alpha_v w (depth + t(x_v)) = w h with h = depth (t0 - t) + t0 g_v, the same h for every channel. */
static VF_ALWAYS_INLINE void moments_add(moments_t *m, bool at_front, const uint64_t shift[4], uint32_t t0,
                                         uint32_t t, const vfi_interval_t *v, uint32_t depth, bool grey)
{
    uint64_t *near = at_front ? m->front : m->back, *far = at_front ? m->back : m->front;
    const uint64_t h = q22_of_q30((uint64_t)depth * (t0 - t) + (((uint64_t)t0 * v->g + HALF_Q30) >> 30));
    for (int c = 0; c < (grey ? 1 : 3); c++) {
        near[c] = (((near[c] + shift[c]) * v->t + HALF_Q30) >> 30) +
                  (((uint64_t)v->w[c] * v->g + HALF_Q22_IN_Q60) >> 38);
        far[c] += ((uint64_t)v->w[c] * h + HALF_Q30) >> 30;
    }
    near[3] = (((near[3] + shift[3]) * v->t + HALF_Q30) >> 30) + q22_of_q30(v->g);
    far[3] += h;
}

/* block_dense's run_add_front and run_add_back with the moments: gap 1, the colours from x before v joins. */
static VF_ALWAYS_INLINE void dense_add_lit(run_t *x, moments_t *m, const vfi_interval_t *v, uint32_t depth,
                                           bool at_front, bool grey)
{
    uint64_t shift[4];
    const uint32_t t0 = x->t;
    shift[0] = dense_colour_q22(x->xr, v->w[0]);
    if (!grey) {
        shift[1] = dense_colour_q22(x->xg, v->w[1]);
        shift[2] = dense_colour_q22(x->xb, v->w[2]);
    }
    shift[3] = q22_of_q30(ONE_Q30 - t0);
    at_front ? run_add_front(x, v, grey) : run_add_back(x, v, grey);
    moments_add(m, at_front, shift, t0, x->t, v, depth, grey);
}

/* block_sparse's pair_add_front and pair_add_back with the moments: v at interval m_v, *end the interval that
 * joined last at that end (the block's end when none has), depth the intervals from the run's other end. */
static VF_ALWAYS_INLINE void sparse_add_lit(pair_t *x, moments_t *m, const vfi_interval_t *iv, uint32_t m_v,
                                            uint32_t *end, uint32_t depth, bool at_front, bool grey)
{
    const vfi_interval_t *v = iv + m_v;
    const uint64_t gap = at_front ? *end - m_v : m_v - *end;
    const uint32_t t0 = x->t;
    uint64_t shift[4];
    shift[0] = gap * q22_of_q30(at_front ? x->r : x->br);
    if (!grey) {
        shift[1] = gap * q22_of_q30(at_front ? x->g : x->bg);
        shift[2] = gap * q22_of_q30(at_front ? x->b : x->bb);
    }
    shift[3] = gap * q22_of_q30(ONE_Q30 - t0);
    at_front ? pair_add_front(x, v, grey) : pair_add_back(x, v, grey);
    moments_add(m, at_front, shift, t0, x->t, v, depth, grey);
    *end = m_v;
}

/* C - M / r as window_t holds C (Q.60 with half an LSB of Q1.15 added), and at least that form's 0: never above
 * C, never below 0. M / r in Q.60 is (M_q22 round(2^40 / r)) >> 2. */
static inline uint64_t less_moment(uint64_t c, uint64_t m_q22, uint64_t recip)
{
    const uint64_t mr = (m_q22 * recip) >> 2;
    return c >= mr + HALF_Q15_IN_Q60 ? c - mr : HALF_Q15_IN_Q60;
}

/* store_lit_window's formats other than the default: through Q.30, as store_window rounds them. */
static VF_NOINLINE void store_lit_window_q30(vfi_table_out_t out, size_t up, size_t down, const uint64_t e[8])
{
    const uint64_t unhalf = HALF_Q15_IN_Q60 - HALF_Q30;
    uint32_t q[8];
    for (int c = 0; c < 8; c++)
        q[c] = (uint32_t)((e[c] - unhalf) >> 30);
    vfi_store_lit_q30(out, up, q[0], q[1], q[2], q[3]);
    vfi_store_lit_q30(out, down, q[4], q[5], q[6], q[7]);
}

/* Entries up and down's front-weighted values from e (up's r, g, b, a, then down's; window_t's form). The default
 * format inline, so that e stays in registers: once a window, about 60 instructions less out of line. */
static VF_ALWAYS_INLINE void store_lit_window(vfi_table_out_t out, size_t up, size_t down, const uint64_t e[8])
{
    if (out.lit_q15 && !out.grid_bits) {
        uint16_t *u = out.lit_q15 + up * 4, *w = out.lit_q15 + down * 4;
        for (int c = 0; c < 4; c++) {
            u[c] = (uint16_t)(e[c] >> 45);
            w[c] = (uint16_t)(e[4 + c] >> 45);
        }
    } else {
        store_lit_window_q30(out, up, down, e);
    }
}

/* Entries up and down's front-weighted values of a window of nothing seen: 0. */
static inline void store_nothing_seen(vfi_table_out_t out, size_t up, size_t down)
{
    const uint64_t zero = HALF_Q15_IN_Q60, e[8] = {zero, zero, zero, zero, zero, zero, zero, zero};
    store_lit_window(out, up, down, e);
}

/* A window's moments as joined, about its front (up[4]: the up entry's r, g, b, a) and its back (down[4]). */
typedef struct window_moments {
    uint64_t up[4], down[4];
} window_moments_t;

/* Window x's front-weighted values from its moments m, stored. */
static VF_ALWAYS_INLINE void store_lit_moments(const diagonal_t *d, const window_t *x, const window_moments_t *m,
                                               bool grey, size_t up, size_t down)
{
    const uint64_t recip = d->recip, cu[3] = {x->r, x->g, x->b}, cd[3] = {x->br, x->bg, x->bb};
    uint64_t e[8];
    for (int c = 0; c < (grey ? 1 : 3); c++) {
        e[c] = less_moment(cu[c], m->up[c], recip);
        e[4 + c] = less_moment(cd[c], m->down[c], recip);
    }
    if (grey) {
        e[1] = e[2] = e[0];
        e[5] = e[6] = e[4];
    }
    e[3] = less_moment(x->a, m->up[3], recip);
    e[7] = less_moment(x->a, m->down[3], recip);
    store_lit_window(d->out, up, down, e);
}

/* The front-weighted values of window x: the suffix in front of the prefix seen from the front (up), the prefix
 * in front of the suffix from the back (down). sf: the suffix's moments about its front (the window's front),
 * sb about its back; pf: the prefix's about its front, pb about its back (the window's back); s_cb, p_cf: the
 * suffix's colour seen from the back and the prefix's from the front (Q.30); ns, np their lengths. Joined, a run
 * behind the other has its moments taken np or ns intervals deeper and seen through the other's transmittance.
 * The moments into *m. */
static VF_ALWAYS_INLINE void lit_window(const diagonal_t *d, const window_t *x, const uint64_t sf[4],
                                        const uint64_t sb[4], const uint32_t s_cb[3], uint32_t st,
                                        const uint64_t pf[4], const uint64_t pb[4], const uint32_t p_cf[3],
                                        uint32_t pt, uint32_t ns, uint32_t np, bool grey, size_t up, size_t down,
                                        window_moments_t *m)
{
    const uint64_t st64 = st, pt64 = pt;
    for (int c = 0; c < (grey ? 1 : 3); c++) {
        m->up[c] = sf[c] + ((st64 * (pf[c] + ns * q22_of_q30(p_cf[c])) + HALF_Q30) >> 30);
        m->down[c] = pb[c] + ((pt64 * (sb[c] + np * q22_of_q30(s_cb[c])) + HALF_Q30) >> 30);
    }
    m->up[3] = sf[3] + ((st64 * (pf[3] + ns * q22_of_q30(ONE_Q30 - pt)) + HALF_Q30) >> 30);
    m->down[3] = pb[3] + ((pt64 * (sb[3] + np * q22_of_q30(ONE_Q30 - st)) + HALF_Q30) >> 30);
    store_lit_moments(d, x, m, grey, up, down);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Entries. */

/* The window that is suffix s in front of a prefix: s in front of it seen from the front, it in front of s seen
 * from the back. The prefix's colour seen from the front (Q.30) and from the back (Q.60 with the half added),
 * and its transmittance. */
static VF_ALWAYS_INLINE window_t join(const vfi_suffix_t *s, uint32_t pr, uint32_t pg, uint32_t pb, uint64_t pbr,
                                      uint64_t pbg, uint64_t pbb, uint32_t pt, bool grey)
{
    window_t x;
    const uint64_t st = s->t;
    x.r = s->front_q60[0] + st * pr;
    x.br = pbr + (uint64_t)pt * s->back[0];
    if (grey) { /* the other channels are the first's */
        x.g = x.b = x.r;
        x.bg = x.bb = x.br;
    } else {
        x.g = s->front_q60[1] + st * pg;
        x.b = s->front_q60[2] + st * pb;
        x.bg = pbg + (uint64_t)pt * s->back[1];
        x.bb = pbb + (uint64_t)pt * s->back[2];
    }
    x.a = ONE_Q60 + HALF_Q15_IN_Q60 - st * pt;
    return x;
}

/* Entries up = (f, f+r) and down = (f+r, f) of window x. q15: the default format (out.q15 without grid_bits),
 * rounded once from Q.60; the others go through Q.30, as the other builders round. */
static inline void store_window(vfi_table_out_t out, bool q15, size_t up, size_t down, const window_t *x)
{
    if (q15) {
        uint16_t *e = out.q15 + up * 4, *g = out.q15 + down * 4;
        const uint16_t a = (uint16_t)(x->a >> 45);
        e[0] = (uint16_t)(x->r >> 45);
        e[1] = (uint16_t)(x->g >> 45);
        e[2] = (uint16_t)(x->b >> 45);
        e[3] = a;
        g[0] = (uint16_t)(x->br >> 45);
        g[1] = (uint16_t)(x->bg >> 45);
        g[2] = (uint16_t)(x->bb >> 45);
        g[3] = a;
    } else {
        /* through Q.30: take the half of Q1.15 off (every value holds at least the half it had added, so this
         * cannot wrap) and put the half of Q.30 on */
        const uint64_t unhalf = HALF_Q15_IN_Q60 - HALF_Q30;
        store_pair_q30(out, up, down, (uint32_t)((x->r - unhalf) >> 30), (uint32_t)((x->g - unhalf) >> 30),
                       (uint32_t)((x->b - unhalf) >> 30), (uint32_t)((x->br - unhalf) >> 30),
                       (uint32_t)((x->bg - unhalf) >> 30), (uint32_t)((x->bb - unhalf) >> 30),
                       (uint32_t)((x->a - unhalf) >> 30));
    }
}
/* Out of line, so that store_window stays small enough to be inlined into the loops; the values one by one, so
 * that the window need not be in memory for the call. */
static void store_pair_q30(vfi_table_out_t out, size_t up, size_t down, uint32_t r, uint32_t g, uint32_t b,
                           uint32_t br, uint32_t bg, uint32_t bb, uint32_t a)
{
    vfi_store_q30(out, up, r, g, b, a);
    vfi_store_q30(out, down, br, bg, bb, a);
}

/* An entry's four values as one object, so that copying one is one move (C lets a struct with uint16_t or uint8_t
 * members access those values). */
typedef struct entry_q15 {
    uint16_t v[4];
} entry_q15_t;
typedef struct entry_u8 {
    uint8_t v[4];
} entry_u8_t;
typedef struct entry_q30 {
    uint32_t v[4];
} entry_q30_t;

/* Entries up and down from the entries distance before each: a window's entries equal to the previous one's. */
static inline void copy_pair(vfi_table_out_t out, size_t up, size_t down, size_t distance)
{
    if (out.q15) {
        entry_q15_t *e = (entry_q15_t *)out.q15;
        e[up] = e[up - distance];
        e[down] = e[down - distance];
    } else if (VF_ORDER2 && out.q30) {
        entry_q30_t *e = (entry_q30_t *)out.q30;
        e[up] = e[up - distance];
        e[down] = e[down - distance];
    } else {
        entry_u8_t *e = (entry_u8_t *)out.u8;
        e[up] = e[up - distance];
        e[down] = e[down - distance];
    }
}

#endif
