/* SPDX-License-Identifier: MIT */
/* ref_factor.c: the shear-warp factorisation of a parallel view and its warp map (section 3). */
#include "ref/ref.h"

#include <stddef.h>

#include <math.h>

#define PI 3.14159265358979323846
#define TIE_BAND (1.0 / 1048576.0) /* 2^-20: axes this close (relatively) to the largest |d_a| are tied */

/* The angle is reduced to a quarter turn in integers first, so multiples of 90 degrees are exact. */
void ref_sincos(int32_t bau, double *s, double *c)
{
    int64_t t = ((int64_t)bau % 65536 + 65536) % 65536;
    int quadrant = (int)(t >> 14);
    double x = (double)(t & 16383) * (PI / 32768.0);
    double s0 = sin(x), c0 = cos(x);
    switch (quadrant) {
    case 0: *s = s0; *c = c0; break;
    case 1: *s = c0; *c = -s0; break;
    case 2: *s = -s0; *c = -c0; break;
    default: *s = -c0; *c = s0; break;
    }
}

static void matmul(double a[3][3], double b[3][3], double out[3][3])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            out[r][c] = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
}

/* R = Rz(roll) Rx(elevation) Ry(azimuth), world -> eye. */
static void rotation(const ref_view_t *view, double R[3][3])
{
    double sa, ca, se, ce, sr, cr, tmp[3][3];
    ref_sincos(view->azimuth, &sa, &ca);
    ref_sincos(view->elevation, &se, &ce);
    ref_sincos(view->roll, &sr, &cr);
    double ry[3][3] = {{ca, 0, sa}, {0, 1, 0}, {-sa, 0, ca}};
    double rx[3][3] = {{1, 0, 0}, {0, ce, -se}, {0, se, ce}};
    double rz[3][3] = {{cr, -sr, 0}, {sr, cr, 0}, {0, 0, 1}};
    matmul(rx, ry, tmp);
    matmul(rz, tmp, R);
}

static double snap16(double x)
{
    return floor(x * 65536.0 + 0.5) / 65536.0;
}

void ref_factor_offset(const ref_factor_t *f, int k, double *ou, double *ov)
{
    if (f->given_offsets_q16) {
        *ou = f->given_offsets_q16[2 * k] / 65536.0;
        *ov = f->given_offsets_q16[2 * k + 1] / 65536.0;
        return;
    }
    *ou = snap16(f->ti + f->si * k);
    *ov = snap16(f->tj + f->sj * k);
}

int ref_factor_adopt_offsets(ref_factor_t *f, const int32_t *offsets_q16, int k_axis, int k_flip)
{
    if (!offsets_q16 || k_axis != f->k_axis || (k_flip != 0) != (f->k_flip != 0))
        return -2;
    const double step = 1.0 / 65536.0 + 1e-12;
    double umax = 0, vmax = 0;
    f->given_offsets_q16 = NULL;
    for (int k = 0; k < f->nk; k++) {
        double ou, ov, gu = offsets_q16[2 * k] / 65536.0, gv = offsets_q16[2 * k + 1] / 65536.0;
        ref_factor_offset(f, k, &ou, &ov);
        if (fabs(ou - gu) > step || fabs(ov - gv) > step || gu < 0 || gv < 0)
            return -2;
        umax = fmax(umax, gu);
        vmax = fmax(vmax, gv);
    }
    f->given_offsets_q16 = offsets_q16;
    f->int_w = (int)floor(umax) + f->ni;
    f->int_h = (int)floor(vmax) + f->nj;
    return 0;
}

/* u = u_c + e_x mu[0] + e_y mu[1] with mu[b] = R[b][i] / Sr_i + si sgn_k R[b][k] / Sr_k and
 * u_c = ti + c_i + si k_c (the centre in standard coordinates); v likewise with j, tj, sj. */
static void warp_terms(const ref_factor_t *f, double mu[2], double mv[2], double *uc, double *vc)
{
    double sgn = f->k_flip ? -1.0 : 1.0;
    int ia = f->i_axis, ja = f->j_axis, ka = f->k_axis;
    double kc = (f->nk - 1) / 2.0;
    for (int b = 0; b < 2; b++) {
        double along_k = sgn * f->R[b][ka] / f->Sr[ka];
        mu[b] = f->R[b][ia] / f->Sr[ia] + f->si * along_k;
        mv[b] = f->R[b][ja] / f->Sr[ja] + f->sj * along_k;
    }
    *uc = f->ti + ((f->ni - 1) / 2.0 + f->si * kc);
    *vc = f->tj + ((f->nj - 1) / 2.0 + f->sj * kc);
}

void ref_factor_warp(const ref_factor_t *f, double px, double py, double *u, double *v)
{
    double mu[2], mv[2], uc, vc;
    warp_terms(f, mu, mv, &uc, &vc);
    double ex = (px - (f->out_w - 1) / 2.0) / f->scale, ey = (py - (f->out_h - 1) / 2.0) / f->scale;
    *u = uc + ex * mu[0] + ey * mu[1];
    *v = vc + ex * mv[0] + ey * mv[1];
}

int ref_volume_check(const ref_volume_t *vol, double *spmin)
{
    double smallest = INFINITY, largest = 0;
    for (int a = 0; a < 3; a++) {
        if (vol->dims[a] < 2 || vol->dims[a] > REF_MAX_DIM || !(vol->spacing[a] > 0) || !isfinite(vol->spacing[a]))
            return -1;
        smallest = fmin(smallest, vol->spacing[a]);
        largest = fmax(largest, vol->spacing[a]);
    }
    if (largest > REF_MAX_ANISOTROPY * smallest)
        return -1;
    *spmin = smallest;
    return 0;
}

int ref_factor(const ref_volume_t *vol, const ref_view_t *view, int out_w, int out_h, ref_factor_t *f)
{
    double spmin;
    if (!vol || !view || !f || out_w < 1 || out_h < 1 || !(view->zoom > 0) || !isfinite(view->zoom) ||
        ref_volume_check(vol, &spmin))
        return -1;
    *f = (ref_factor_t){0}; /* given_offsets_q16 NULL: the reference's own offsets until some are adopted */
    f->out_w = out_w;
    f->out_h = out_h;
    double diag2 = 0;
    for (int a = 0; a < 3; a++) {
        f->Sr[a] = vol->spacing[a] / spmin;
        diag2 += (f->Sr[a] * (vol->dims[a] - 1)) * (f->Sr[a] * (vol->dims[a] - 1));
    }
    f->scale = view->zoom * (out_w < out_h ? out_w : out_h) / sqrt(diag2);
    rotation(view, f->R);

    /* Principal axis: largest |d_a|, ties within a relative 2^-20 to the lowest axis. */
    double dmax = 0;
    for (int a = 0; a < 3; a++) {
        f->dir[a] = f->R[2][a] / f->Sr[a];
        dmax = fmax(dmax, fabs(f->dir[a]));
    }
    int k = 0;
    while (fabs(f->dir[k]) < dmax * (1.0 - TIE_BAND))
        k++;
    f->k_axis = k;
    f->i_axis = (k + 1) % 3;
    f->j_axis = (k + 2) % 3;
    f->k_flip = f->dir[k] < 0;
    f->ni = vol->dims[f->i_axis];
    f->nj = vol->dims[f->j_axis];
    f->nk = vol->dims[k];

    double dk = fabs(f->dir[k]);
    f->si = fmax(-1.0, fmin(1.0, -f->dir[f->i_axis] / dk)); /* a tie can give 1 + 2^-20: clamped (spec) */
    f->sj = fmax(-1.0, fmin(1.0, -f->dir[f->j_axis] / dk));
    f->ti = fmax(0.0, -f->si * (f->nk - 1));
    f->tj = fmax(0.0, -f->sj * (f->nk - 1));
    double ri = f->si * f->Sr[f->i_axis], rj = f->sj * f->Sr[f->j_axis], rk = f->Sr[k];
    f->slab = sqrt(ri * ri + rj * rj + rk * rk);

    /* Slice k covers the pixels ceil(ou_k) .. floor(ou_k + n_i - 1); the offsets are >= 0 after snapping. */
    double umax = 0, vmax = 0;
    for (int s = 0; s < f->nk; s++) {
        double ou, ov;
        ref_factor_offset(f, s, &ou, &ov);
        umax = fmax(umax, ou);
        vmax = fmax(vmax, ov);
    }
    f->int_w = (int)floor(umax) + f->ni;
    f->int_h = (int)floor(vmax) + f->nj;

    double mu[2], mv[2], uc, vc, cx = (out_w - 1) / 2.0, cy = (out_h - 1) / 2.0;
    warp_terms(f, mu, mv, &uc, &vc);
    f->du_dx = mu[0] / f->scale;
    f->du_dy = mu[1] / f->scale;
    f->dv_dx = mv[0] / f->scale;
    f->dv_dy = mv[1] / f->scale;
    f->u0 = uc - cx * f->du_dx - cy * f->du_dy;
    f->v0 = vc - cx * f->dv_dx - cy * f->dv_dy;
    return 0;
}
