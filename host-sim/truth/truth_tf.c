/* SPDX-License-Identifier: MIT */
/* truth_tf.c: the continuous transfer function, and the exact integration of a linear scalar segment through it,
 * lit or not. */
#include "truth/truth.h"

#include <math.h>
#include <string.h>

#define FAR 1.0e6 /* the first and last pieces reach this far: scalars live in 0..255 */

static void add_seg(truth_tf_t *tf, double s0, double s1, const double v0[4], const double v1[4]);
static void split_at(truth_tf_t *tf, double s0, double s1, const double v0[4], const double v1[4], double level);
static int seg_up(const truth_tf_t *tf, double s);
static int seg_down(const truth_tf_t *tf, double s);
static double seg_a(const truth_seg_t *g, double s);
static void seg_c(const truth_seg_t *g, double s, double c[3]);
static double mean_log_g(double a0, double a1);
static double unit_steepness(const truth_tf_t *tf, int m);
static void composite_piece(double a0, double a1, const double c0[3], const double c1[3], double L, truth_acc_t *acc);
static void composite_graded(double a0, double a1, const double c0[3], const double c1[3], double L,
                             truth_acc_t *acc);
static void composite(const truth_tf_t *tf, double sa, double sb, double L, const ref_shade_t *shade,
                      truth_acc_t *acc);

int truth_tf_init(truth_tf_t *tf, const ref_tf_point_t *p, int n)
{
    if (!tf || !p || n < 1 || n > REF_MAX_TF_POINTS)
        return -1;
    for (int i = 0; i < n; i++)
        if (!isfinite(p[i].s) || !isfinite(p[i].r) || !isfinite(p[i].g) || !isfinite(p[i].b) || !isfinite(p[i].a) ||
            (i > 0 && p[i].s < p[i - 1].s))
            return -1;
    tf->nseg = 0;
    double first[4] = {p[0].r, p[0].g, p[0].b, p[0].a};
    double last[4] = {p[n - 1].r, p[n - 1].g, p[n - 1].b, p[n - 1].a};
    split_at(tf, -FAR, p[0].s, first, first, 0);
    /* a step (points sharing a scalar) has no piece of its own: the next piece starts at the last of them,
     * which makes the function right-continuous as ref_tf_eval is */
    for (int i = 0; i + 1 < n; i++)
        if (p[i].s < p[i + 1].s) {
            double v0[4] = {p[i].r, p[i].g, p[i].b, p[i].a}, v1[4] = {p[i + 1].r, p[i + 1].g, p[i + 1].b, p[i + 1].a};
            split_at(tf, p[i].s, p[i + 1].s, v0, v1, 0);
        }
    split_at(tf, p[n - 1].s, FAR, last, last, 0);

    /* what the cell skipping asks: opacity at each integer scalar and anywhere on each unit interval */
    memset(tf->visible_units, 0, sizeof tf->visible_units);
    for (int s = 0; s < 256; s++) {
        const truth_seg_t *g = &tf->seg[seg_up(tf, s)];
        tf->visible_at[s] = seg_a(g, s) > 0;
        int any = 0;
        for (int i = seg_up(tf, s); s < 255 && i <= seg_down(tf, s + 1); i++) {
            double lo = fmax(tf->seg[i].s0, s), hi = fmin(tf->seg[i].s1, s + 1.0);
            if (hi > lo && (seg_a(&tf->seg[i], lo) > 0 || seg_a(&tf->seg[i], hi) > 0))
                any = 1;
        }
        tf->visible_units[s + 1] = tf->visible_units[s] + any;
        if (s < 255)
            tf->steep[s] = unit_steepness(tf, s);
    }
    return 0;
}

double truth_tf_steepness(const truth_tf_t *tf, int lo, int hi)
{
    double most = 0;
    for (int m = lo; m < hi; m++)
        most = fmax(most, tf->steep[m]);
    return most;
}

int truth_tf_clear(const truth_tf_t *tf, int lo, int hi)
{
    if (lo == hi)
        return !tf->visible_at[lo];
    /* the units cover every value strictly inside and the one-sided limits at both ends; the value at hi
     * itself (right-continuous) is the only one left */
    return tf->visible_units[hi] == tf->visible_units[lo] && !tf->visible_at[hi];
}

double truth_depth(double a0, double a1, double L)
{
    return -L * mean_log_g(a0, a1);
}

void truth_tf_composite(const truth_tf_t *tf, double sa, double sb, double L, truth_acc_t *acc)
{
    composite(tf, sa, sb, L, NULL, acc);
}

/* The extinction times g over L is the extinction over g L: optical depth and emission depend on L only through
 * L tau. */
void truth_tf_composite_lit(const truth_tf_t *tf, double sa, double sb, double L, ref_shade_t shade,
                            truth_acc_t *acc)
{
    if (shade.g > 0)
        composite(tf, sa, sb, L * shade.g, &shade, acc);
}

/* ---- static functions ---------------------------------------------------------------------------------- */

/* The colour a shade makes of colour c: c L_d + L_s, at most 1 (no shade: c itself). */
static void lit_colour(const ref_shade_t *shade, double c[3])
{
    for (int n = 0; shade && n < 3; n++)
        c[n] = fmin(c[n] * shade->d + shade->s, 1.0);
}

static void composite(const truth_tf_t *tf, double sa, double sb, double L, const ref_shade_t *shade,
                      truth_acc_t *acc)
{
    double ca[3], cb[3];
    if (sa == sb) {
        const truth_seg_t *g = &tf->seg[seg_up(tf, sa)];
        double a = seg_a(g, sa);
        if (a > 0) {
            seg_c(g, sa, ca);
            lit_colour(shade, ca);
            composite_piece(a, a, ca, ca, L, acc);
        }
        return;
    }
    /* walk the pieces from sa towards sb; each gets the share of L its scalar range has */
    int up = sb > sa, i = up ? seg_up(tf, sa) : seg_down(tf, sa);
    double per_level = L / fabs(sb - sa), s = sa;
    for (;;) {
        const truth_seg_t *g = &tf->seg[i];
        double end = up ? fmin(sb, g->s1) : fmax(sb, g->s0);
        double a0 = seg_a(g, s), a1 = seg_a(g, end);
        if ((a0 > 0 || a1 > 0) && end != s) {
            seg_c(g, s, ca);
            seg_c(g, end, cb);
            lit_colour(shade, ca); /* linear between the two when the clamp holds at neither or both */
            lit_colour(shade, cb);
            composite_graded(a0, a1, ca, cb, per_level * fabs(end - s), acc);
        }
        if (end == sb || acc->T <= 1.0 - TRUTH_STOP_OPACITY)
            break;
        s = end;
        i += up ? 1 : -1;
    }
}

static void add_seg(truth_tf_t *tf, double s0, double s1, const double v0[4], const double v1[4])
{
    if (!(s1 > s0))
        return;
    truth_seg_t *g = &tf->seg[tf->nseg++];
    g->s0 = s0;
    g->s1 = s1;
    g->a0 = fmin(fmax(v0[3], 0.0), TRUTH_A0_MAX);
    g->a1 = fmin(fmax(v1[3], 0.0), TRUTH_A0_MAX);
    for (int c = 0; c < 3; c++) {
        g->c0[c] = v0[c];
        g->c1[c] = v1[c];
    }
}

/* Add a linear piece, split where its opacity crosses 0 or the clamp (level 0, then 1), so that the clamped
 * opacity is linear on each part. */
static void split_at(truth_tf_t *tf, double s0, double s1, const double v0[4], const double v1[4], double level)
{
    double bound = level == 0 ? 0.0 : TRUTH_A0_MAX;
    if (level > 1 || !((v0[3] - bound) * (v1[3] - bound) < 0)) {
        if (level > 1)
            add_seg(tf, s0, s1, v0, v1);
        else
            split_at(tf, s0, s1, v0, v1, level + 1);
        return;
    }
    double w = (bound - v0[3]) / (v1[3] - v0[3]), vm[4];
    for (int c = 0; c < 4; c++)
        vm[c] = v0[c] + w * (v1[c] - v0[c]);
    vm[3] = bound;
    double sm = s0 + w * (s1 - s0);
    split_at(tf, s0, sm, v0, vm, level + 1);
    split_at(tf, sm, s1, vm, v1, level + 1);
}

/* The piece holding s and the values just above it: s0 <= s < s1. */
static int seg_up(const truth_tf_t *tf, double s)
{
    int lo = 0, hi = tf->nseg - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (tf->seg[mid].s0 <= s)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/* The piece holding the values just below s: s0 < s <= s1. */
static int seg_down(const truth_tf_t *tf, double s)
{
    int lo = 0, hi = tf->nseg - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (tf->seg[mid].s0 < s)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

static double seg_a(const truth_seg_t *g, double s)
{
    if (g->a0 == g->a1)
        return g->a0;
    return g->a0 + (g->a1 - g->a0) * ((s - g->s0) / (g->s1 - g->s0));
}

static void seg_c(const truth_seg_t *g, double s, double c[3])
{
    double w = (s - g->s0) / (g->s1 - g->s0);
    for (int n = 0; n < 3; n++)
        c[n] = g->c0[n] == g->c1[n] ? g->c0[n] : g->c0[n] + (g->c1[n] - g->c0[n]) * w;
}

/* Steepness on [m, m + 1]: pieces meeting there with different values (a step) make it infinite. */
static double unit_steepness(const truth_tf_t *tf, int m)
{
    double most = 0;
    for (int i = seg_up(tf, m); i <= seg_down(tf, m + 1.0); i++) {
        const truth_seg_t *g = &tf->seg[i];
        double lo = fmax(g->s0, m), hi = fmin(g->s1, m + 1.0), width = g->s1 - g->s0;
        if (!(hi > lo))
            continue;
        double amax = fmax(seg_a(g, lo), seg_a(g, hi)), dc = 0;
        for (int n = 0; n < 3; n++)
            dc = fmax(dc, fabs(g->c1[n] - g->c0[n]));
        most = fmax(most, fmax(fabs(g->a1 - g->a0), amax * dc) / width);
        if (i + 1 < tf->nseg && g->s1 <= m + 1.0) {
            const truth_seg_t *next = &tf->seg[i + 1];
            int jump = g->a1 != next->a0;
            for (int n = 0; n < 3; n++)
                jump |= (g->a1 > 0 || next->a0 > 0) && g->c1[n] != next->c0[n];
            if (jump)
                return INFINITY;
        }
    }
    return most;
}

/* The mean of ln g over a piece where g = 1 - a goes linearly from g0 to g1:
 * (g1 ln g1 - g0 ln g0) / (g1 - g0) - 1 = ln g0 + h(x) with x = g1 / g0 - 1 = (a0 - a1) / (1 - a0) and
 * h(x) = (1 + x) ln(1 + x) / x - 1; h by its series near 0, where the closed form cancels. */
static double mean_log_g(double a0, double a1)
{
    double x = (a0 - a1) / (1.0 - a0), h;
    if (fabs(x) < 1e-3)
        h = x * (0.5 + x * (-1.0 / 6 + x * (1.0 / 12 + x * (-1.0 / 20 + x * (1.0 / 30)))));
    else
        h = (1.0 + x) * log1p(x) / x - 1.0;
    return log1p(-a0) + h;
}

/* Opacity varying a lot across a piece makes -ln(1 - a) steep near its opaque end; Gauss-Legendre then
 * converges slowly. Splitting where 1 - a halves keeps every part gentle (most pieces need no split). */
static void composite_graded(double a0, double a1, const double c0[3], const double c1[3], double L,
                             truth_acc_t *acc)
{
    double g0 = 1.0 - a0, g1 = 1.0 - a1, ratio = g0 > g1 ? g0 / g1 : g1 / g0;
    if (ratio <= 2.0) {
        composite_piece(a0, a1, c0, c1, L, acc);
        return;
    }
    int parts = (int)ceil(log2(ratio));
    double u_prev = 0, a_prev = a0, c_prev[3] = {c0[0], c0[1], c0[2]};
    for (int k = 1; k <= parts && acc->T > 1.0 - TRUTH_STOP_OPACITY; k++) {
        double a_k = k == parts ? a1 : 1.0 - g0 * pow(g1 / g0, (double)k / parts);
        double u_k = k == parts ? 1.0 : (a_k - a0) / (a1 - a0), c_k[3];
        for (int n = 0; n < 3; n++)
            c_k[n] = c0[n] + (c1[n] - c0[n]) * u_k;
        composite_piece(a_prev, a_k, c_prev, c_k, L * (u_k - u_prev), acc);
        u_prev = u_k;
        a_prev = a_k;
        memcpy(c_prev, c_k, sizeof c_prev);
    }
}

/* One piece: opacity a and colour c linear in position over world length L. Optical depth is exact. The
 * emission int_0^1 L tau(u) c(u) T(u) du, with T(u) = exp(-depth over [0, u]) and dT/du = -L tau T, is by
 * parts c1 (1 - T(1)) - (c1 - c0) int_0^1 (1 - T(u)) du: only the last integral needs quadrature (5-point
 * Gauss-Legendre, each node with its exact partial optical depth), and it vanishes where colour is constant. */
static void composite_piece(double a0, double a1, const double c0[3], const double c1[3], double L, truth_acc_t *acc)
{
    static const double node[5] = {0.046910077030668004, 0.23076534494715845, 0.5, 0.76923465505284155,
                                   0.95308992296933200};
    static const double weight[5] = {0.11846344252809454, 0.23931433524968324, 0.28444444444444444,
                                     0.23931433524968324, 0.11846344252809454};
    double opacity = -expm1(-truth_depth(a0, a1, L)), J = 0;
    if (c0[0] != c1[0] || c0[1] != c1[1] || c0[2] != c1[2])
        for (int j = 0; j < 5; j++) {
            double u = node[j];
            J += weight[j] * -expm1(-truth_depth(a0, a0 + (a1 - a0) * u, L * u));
        }
    for (int n = 0; n < 3; n++)
        acc->C[n] += acc->T * (c1[n] * opacity - (c1[n] - c0[n]) * J);
    acc->T *= 1.0 - opacity;
}
