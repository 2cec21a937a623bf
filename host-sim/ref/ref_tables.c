/* SPDX-License-Identifier: MIT */
/* ref_tables.c: transfer function, classification, point table and brute-force pre-integrated table (section 2),
 * and the front-weighted table of lit slabs (section 7). */
#include "ref/ref.h"

#include <math.h>
#include <stdlib.h>

#define A0_MAX (1.0 - 1.0 / 65536.0) /* opacity per d_ref is clamped here, so tau stays finite (<= 16 ln 2) */

static int tf_valid(const ref_tf_point_t *tf, int npoints)
{
    if (!tf || npoints < 1 || npoints > REF_MAX_TF_POINTS)
        return 0;
    for (int p = 0; p < npoints; p++) {
        if (!isfinite(tf[p].s) || !isfinite(tf[p].r) || !isfinite(tf[p].g) || !isfinite(tf[p].b) ||
            !isfinite(tf[p].a))
            return 0;
        if (p > 0 && tf[p].s < tf[p - 1].s)
            return 0;
    }
    return 1;
}

void ref_tf_eval(const ref_tf_point_t *tf, int npoints, double s, double rgba[4])
{
    /* p: the last point with s_p <= s (so a later point sharing a scalar wins at and to the right of it) */
    int p = -1;
    while (p + 1 < npoints && tf[p + 1].s <= s)
        p++;
    const ref_tf_point_t *lo = &tf[p < 0 ? 0 : p], *hi = lo;
    double w = 0;
    if (p >= 0 && p + 1 < npoints) {
        hi = &tf[p + 1]; /* s_p <= s < s_{p+1}: a proper segment */
        w = (s - lo->s) / (hi->s - lo->s);
    }
    rgba[0] = lo->r + w * (hi->r - lo->r);
    rgba[1] = lo->g + w * (hi->g - lo->g);
    rgba[2] = lo->b + w * (hi->b - lo->b);
    rgba[3] = lo->a + w * (hi->a - lo->a);
}

int ref_classify(const ref_tf_point_t *tf, int npoints, int N, double *tau, double *rgb)
{
    if (!tf_valid(tf, npoints) || N < REF_MIN_TABLE || N > REF_MAX_TABLE || !tau || !rgb)
        return -1;
    for (int i = 0; i < N; i++) {
        double v[4];
        ref_tf_eval(tf, npoints, i * 255.0 / (N - 1), v); /* s_i = i * 255 / (N - 1) */
        double a0 = v[3] < 0 ? 0 : v[3] > A0_MAX ? A0_MAX : v[3];
        tau[i] = -log1p(-a0); /* -ln(1 - a0), accurate for small a0; +0 for a0 = 0 */
        for (int c = 0; c < 3; c++)
            rgb[3 * i + c] = v[c];
    }
    return 0;
}

int ref_table_index(double s, int N)
{
    return (int)floor(s * (N - 1) / 255.0 + 0.5);
}

/* Point entry i: a = 1 - exp(-tau_i d), C = c_i a. */
static void point_entry(const double *tau, const double *rgb, int i, double d, double out[4])
{
    double a = -expm1(-tau[i] * d); /* 1 - exp(-tau d) without cancellation */
    out[0] = a;
    for (int c = 0; c < 3; c++)
        out[1 + c] = rgb[3 * i + c] * a;
}

int ref_point_table(const ref_tf_point_t *tf, int npoints, int N, double d, double *out)
{
    if (!out || !(d > 0) || !isfinite(d))
        return -1;
    double *tau = malloc(sizeof(double) * 4 * (size_t)N);
    if (!tau)
        return -1;
    double *rgb = tau + N;
    int rc = ref_classify(tf, npoints, N, tau, rgb);
    for (int i = 0; rc == 0 && i < N; i++)
        point_entry(tau, rgb, i, d, out + 4 * i);
    free(tau);
    return rc;
}

/* Extinction-weighted mean colour w_m of interval m (between entries m and m + 1). */
static void interval_weight(const double *tau, const double *rgb, int m, double w[3])
{
    double t0 = tau[m], t1 = tau[m + 1];
    for (int c = 0; c < 3; c++) {
        double c0 = rgb[3 * m + c], c1 = rgb[3 * (m + 1) + c];
        if (t0 + t1 == 0)
            w[c] = (c0 + c1) / 2;
        else
            w[c] = (2 * t0 * c0 + t0 * c1 + t1 * c0 + 2 * t1 * c1) / (3 * (t0 + t1));
    }
}

/* Entries (f, b) with |b - f| = r cross r intervals of length L = d / r each. For every r the N - 1 interval
 * values alpha_m(L), C_m(L) are computed once (seg), then each entry composites its r intervals in order from
 * f towards b, front to back. */
int ref_preint_table(const ref_tf_point_t *tf, int npoints, int N, double d, double *out)
{
    if (!out || !(d > 0) || !isfinite(d))
        return -1;
    double *tau = malloc(sizeof(double) * (7 * (size_t)N + 4 * (size_t)N));
    if (!tau)
        return -1;
    double *rgb = tau + N, *w = rgb + 3 * N, *seg = w + 3 * N;
    if (ref_classify(tf, npoints, N, tau, rgb) != 0) {
        free(tau);
        return -1;
    }
    for (int m = 0; m + 1 < N; m++)
        interval_weight(tau, rgb, m, w + 3 * m);
    for (int f = 0; f < N; f++)
        point_entry(tau, rgb, f, d, out + 4 * ((size_t)f * N + f));
    for (int r = 1; r < N; r++) {
        double L = d / r;
        for (int m = 0; m + 1 < N; m++) {
            double alpha = -expm1(-L * (tau[m] + tau[m + 1]) / 2);
            seg[4 * m] = alpha;
            for (int c = 0; c < 3; c++)
                seg[4 * m + 1 + c] = w[3 * m + c] * alpha;
        }
        for (int lo = 0; lo + r < N; lo++) {
            for (int dir = 0; dir < 2; dir++) {
                int f = dir == 0 ? lo : lo + r, b = dir == 0 ? lo + r : lo;
                double A = 0, C[3] = {0, 0, 0};
                for (int q = 0; q < r; q++) {
                    int m = f < b ? f + q : f - 1 - q; /* f, f+1, .., b-1  or  f-1, f-2, .., b */
                    const double *s = seg + 4 * m;
                    for (int c = 0; c < 3; c++)
                        C[c] += (1 - A) * s[1 + c];
                    A += (1 - A) * s[0];
                }
                double *e = out + 4 * ((size_t)f * N + b);
                e[0] = A;
                e[1] = C[0];
                e[2] = C[1];
                e[3] = C[2];
            }
        }
    }
    free(tau);
    return 0;
}

double ref_mean_depth(double x)
{
    if (x < 1e-3) /* 1/2 - x/12 + x^3/720: the closed form cancels here */
        return 0.5 - x / 12 + x * x * x / 720;
    return 1 / x - 1 / expm1(x); /* exp(-x) / (1 - exp(-x)) = 1 / (exp(x) - 1) */
}

/* One piece of opacity alpha (depth x, t = t(x)) and colour c (unpremultiplied) at piece k of `pieces`, behind
 * transmittance *T: its share of the front-weighted sums S and D, and the transmittance behind it. */
static void lit_piece(double alpha, double t, const double c[3], int k, int pieces, double *T, double *S, double D[3])
{
    const double weight = 1 - (k + t) / pieces;
    *S += *T * alpha * weight;
    for (int n = 0; n < 3; n++)
        D[n] += *T * c[n] * alpha * weight;
    *T *= 1 - alpha;
}

/* Section 7: entry (f, b) is r = |b - f| pieces (one of length d for r = 0), met in order; piece k of depth x_k,
 * opacity alpha_k, colour C_k and transmittance T_k in front of it sends its light out from its mean position
 * theta_k = (k + t(x_k)) / max(r, 1) along the slab, and the front-weighted sums weight it by 1 - theta_k.
 * Entries of one diagonal r share the interval depths x_m = (d / r) (tau_m + tau_{m+1}) / 2. */
int ref_lit_table(const ref_tf_point_t *tf, int npoints, int N, double d, double *out)
{
    if (!out || !(d > 0) || !isfinite(d))
        return -1;
    double *tau = malloc(sizeof(double) * 9 * (size_t)N);
    if (!tau)
        return -1;
    double *rgb = tau + N, *w = rgb + 3 * N, *alpha = w + 3 * N, *t = alpha + N;
    if (ref_classify(tf, npoints, N, tau, rgb) != 0) {
        free(tau);
        return -1;
    }
    for (int m = 0; m + 1 < N; m++)
        interval_weight(tau, rgb, m, w + 3 * m);
    for (int f = 0; f < N; f++) {
        double T = 1, S = 0, D[3] = {0, 0, 0};
        const double x = tau[f] * d;
        lit_piece(-expm1(-x), ref_mean_depth(x), rgb + 3 * f, 0, 1, &T, &S, D);
        double *e = out + 4 * ((size_t)f * N + f);
        e[0] = S, e[1] = D[0], e[2] = D[1], e[3] = D[2];
    }
    for (int r = 1; r < N; r++) {
        for (int m = 0; m + 1 < N; m++) {
            const double x = d / r * (tau[m] + tau[m + 1]) / 2;
            alpha[m] = -expm1(-x);
            t[m] = ref_mean_depth(x);
        }
        for (int lo = 0; lo + r < N; lo++)
            for (int dir = 0; dir < 2; dir++) {
                const int f = dir == 0 ? lo : lo + r, b = dir == 0 ? lo + r : lo;
                double T = 1, S = 0, D[3] = {0, 0, 0};
                for (int k = 0; k < r; k++) {
                    const int m = f < b ? f + k : f - 1 - k; /* f, f+1, .., b-1  or  f-1, f-2, .., b */
                    lit_piece(alpha[m], t[m], w + 3 * m, k, r, &T, &S, D);
                }
                double *e = out + 4 * ((size_t)f * N + b);
                e[0] = S, e[1] = D[0], e[2] = D[1], e[3] = D[2];
            }
    }
    free(tau);
    return 0;
}
