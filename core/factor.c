/* SPDX-License-Identifier: MIT */
/*
 * factor.c: the shear-warp factorisation of a parallel view (docs/algorithm.md, section 3).
 *
 * Spaces, in Lacroute's names:
 *   object        voxel indices p = (x, y, z)
 *   world         w = Sr (p - c): relative spacing Sr = sp / min(sp), centred on the volume
 *   eye           e = R w: x right, y down, z into the screen
 *   standard      (i, j, k): object axes permuted so that k is the principal viewing axis, slice 0 in front
 *   intermediate  (u, v) = (i + ou_k, j + ov_k): the sheared slices, one pixel per voxel
 *   final         (px, py): the output image
 * The result (vf_factor_t) is all that compositing and warping use.
 *
 * Precision: the rotation is Q2.30; shears, translations and the warp map are Q32.32, because an error e in
 * a shear moves slice k by k*e voxels, and slice offsets must be right to far better than 2^-16 (where they are
 * snapped, as the reference snaps them) for the two renderers to cover the same pixels.
 */
#include "fixmath.h"
#include "shade.h"

#define ONE_Q32 (INT64_C(1) << 32)

/* A 3x3 matrix in Q2.30, wrapped so that const works on it in C99. */
typedef struct mat3 {
    int32_t m[3][3];
} mat3_t;

static void rotation(const vf_view_t *view, mat3_t *r);
static void matmul_q30(const mat3_t *a, const mat3_t *b, mat3_t *out);
static int principal_axis(const mat3_t *r, const uint32_t sp[3]);
static int64_t clamp_shear(int64_t s_q32);

void vfi_view_rotation(const vf_view_t *view, int32_t r_q30[3][3])
{
    mat3_t r;
    rotation(view, &r);
    for (int row = 0; row < 3; row++)
        for (int col = 0; col < 3; col++)
            r_q30[row][col] = r.m[row][col];
}

vf_status_t vf_factor(vf_factor_t *f, const vf_volume_t *vol, const vf_view_t *view, uint32_t out_w,
                      uint32_t out_h)
{
    if (!f || !vol || !view)
        return VF_ERR_NULL;
    uint32_t sp_min = UINT32_MAX, sp_max = 0;
    for (int a = 0; a < 3; a++) {
        if (vol->dims[a] < 2 || vol->dims[a] > VF_MAX_DIM)
            return VF_ERR_DIMS;
        if (vol->spacing_q16[a] == 0)
            return VF_ERR_SPACING;
        sp_min = vol->spacing_q16[a] < sp_min ? vol->spacing_q16[a] : sp_min;
        sp_max = vol->spacing_q16[a] > sp_max ? vol->spacing_q16[a] : sp_max;
    }
    if ((uint64_t)sp_max > (uint64_t)sp_min * VF_MAX_ANISOTROPY)
        return VF_ERR_SPACING;
    if (out_w == 0 || out_h == 0 || out_w > VF_MAX_IMAGE || out_h > VF_MAX_IMAGE)
        return VF_ERR_IMAGE;
    if (view->zoom_q16 < 256 || view->zoom_q16 > (UINT32_C(256) << 16))
        return VF_ERR_ARG; /* zoom in [1/256, 256] */

    const uint32_t *sp = vol->spacing_q16;
    mat3_t rot;
    rotation(view, &rot);
    int32_t(*r)[3] = rot.m;

    /* Standard object axes. The viewing direction in object space is d_a = R[2][a] / Sr_a. */
    int ka = principal_axis(&rot, sp);
    int ia = (ka + 1) % 3, ja = (ka + 2) % 3;
    int sgn = r[2][ka] > 0 ? 1 : -1;
    f->k_axis = (uint8_t)ka;
    f->i_axis = (uint8_t)ia;
    f->j_axis = (uint8_t)ja;
    f->k_flip = sgn < 0;
    f->ni = vol->dims[ia];
    f->nj = vol->dims[ja];
    f->nk = vol->dims[ka];

    /* Shear si = -d_i / |d_k| = -(R[2][i] sp_k) / (|R[2][k]| sp_i); the spacings' common unit cancels. */
    int64_t dk = (int64_t)(r[2][ka] < 0 ? -r[2][ka] : r[2][ka]);
    f->si_q32 = clamp_shear(-vfi_ratio_q32((int64_t)r[2][ia] * sp[ka], dk * sp[ia]));
    f->sj_q32 = clamp_shear(-vfi_ratio_q32((int64_t)r[2][ja] * sp[ka], dk * sp[ja]));
    int64_t last = (int64_t)f->nk - 1;
    f->ti_q32 = f->si_q32 < 0 ? -f->si_q32 * last : 0;
    f->tj_q32 = f->sj_q32 < 0 ? -f->sj_q32 * last : 0;

    /* The intermediate image holds every slice: slice k covers u in [ou_k, ou_k + n_i - 1]. */
    int32_t ou_max = vf_factor_offset_u(f, 0), ov_max = vf_factor_offset_v(f, 0);
    int32_t ou_last = vf_factor_offset_u(f, (uint32_t)last), ov_last = vf_factor_offset_v(f, (uint32_t)last);
    ou_max = ou_last > ou_max ? ou_last : ou_max;
    ov_max = ov_last > ov_max ? ov_last : ov_max;
    f->rays = 1;
    f->int_w = (uint32_t)(ou_max >> 16) + f->ni;
    f->int_h = (uint32_t)(ov_max >> 16) + f->nj;

    /* Relative spacing Sr_a = sp_a / sp_min, Q32.32 (at most 64). */
    int64_t sr[3];
    for (int a = 0; a < 3; a++)
        sr[a] = vfi_ratio_q32(sp[a], sp_min);

    /* Slab length |(si Sr_i, sj Sr_j, Sr_k)| in units of d_ref: components in Q24 keep the squares in 64 bits. */
    int64_t ci = vfi_mul_shift_round(f->si_q32, sr[ia], 40);
    int64_t cj = vfi_mul_shift_round(f->sj_q32, sr[ja], 40);
    int64_t ck = sr[ka] >> 8;
    uint32_t slab_q24 = vfi_sqrt64_round((uint64_t)(ci * ci) + (uint64_t)(cj * cj) + (uint64_t)(ck * ck));
    f->slab_q16 = (slab_q24 + 128) >> 8;

    /* scale = zoom * min(W, H) / D, D = |Sr (n - 1)| the diagonal; the warp needs 1 / scale. D to 1e-9 relative:
     * the lengths are Q32.32 (up to 2^50), so the square root is taken of their ratios to the longest. */
    int64_t len[3], longest = 0;
    for (int a = 0; a < 3; a++) {
        len[a] = sr[a] * ((int64_t)vol->dims[a] - 1);
        longest = len[a] > longest ? len[a] : longest;
    }
    uint64_t sum_q60 = 0;
    for (int a = 0; a < 3; a++) {
        int64_t ratio_q30 = vfi_ratio_q32(len[a], longest) >> 2;
        sum_q60 += (uint64_t)(ratio_q30 * ratio_q30);
    }
    int64_t diag_q32 = vfi_mul_shift_round(longest, vfi_sqrt64_round(sum_q60), 30);
    uint32_t min_side = out_w < out_h ? out_w : out_h;
    int64_t inv_scale_q32 = vfi_ratio_q32(diag_q32, ((int64_t)view->zoom_q16 * min_side) << 16);
    if (inv_scale_q32 > (INT64_C(1) << 40))
        return VF_ERR_ARG; /* over 256 voxels per output pixel: the image would be a dot */

    /* Final pixel (px, py) sees u = u_c + G_x e_x + G_y e_y with e = ((px, py) - centre) / scale and
     * G_b = R[b][i] / Sr_i + si sgn R[b][k] / Sr_k (the e_z terms cancel: that is the shear). */
    int64_t du[2], dv[2];
    for (int b = 0; b < 2; b++) {
        int64_t ri = vfi_ratio_q32((int64_t)r[b][ia] * sp_min, (int64_t)sp[ia] << 30);
        int64_t rj = vfi_ratio_q32((int64_t)r[b][ja] * sp_min, (int64_t)sp[ja] << 30);
        int64_t rk = sgn * vfi_ratio_q32((int64_t)r[b][ka] * sp_min, (int64_t)sp[ka] << 30);
        int64_t gu = ri + vfi_mul_shift_round(f->si_q32, rk, 32);
        int64_t gv = rj + vfi_mul_shift_round(f->sj_q32, rk, 32);
        du[b] = vfi_mul_shift_round(gu, inv_scale_q32, 32);
        dv[b] = vfi_mul_shift_round(gv, inv_scale_q32, 32);
    }
    f->out_w = out_w;
    f->out_h = out_h;
    f->du_dx_q32 = du[0];
    f->du_dy_q32 = du[1];
    f->dv_dx_q32 = dv[0];
    f->dv_dy_q32 = dv[1];
    /* Centre: (n_i - 1)/2 + ti + si (n_k - 1)/2, then back from the image centre ((W - 1)/2, (H - 1)/2). */
    int64_t uc = (((int64_t)f->ni - 1) << 31) + f->ti_q32 + f->si_q32 * last / 2;
    int64_t vc = (((int64_t)f->nj - 1) << 31) + f->tj_q32 + f->sj_q32 * last / 2;
    f->u0_q32 = uc - du[0] * ((int64_t)out_w - 1) / 2 - du[1] * ((int64_t)out_h - 1) / 2;
    f->v0_q32 = vc - dv[0] * ((int64_t)out_w - 1) / 2 - dv[1] * ((int64_t)out_h - 1) / 2;
    return VF_OK;
}

vf_status_t vf_factor_rays(vf_factor_t *f, uint32_t rays)
{
    if (!f)
        return VF_ERR_NULL;
    if (f->rays != 1 || (rays != 1 && rays != 2 && rays != 4 && rays != 8 && rays != 16))
        return VF_ERR_ARG;
    if (rays > VF_MAX_RAYS)
        return VF_ERR_UNSUPPORTED;
    if (rays == 1) /* nothing to scale; and a one-ray build (vf_config.h) keeps none of what follows */
        return VF_OK;
    if ((uint64_t)rays * (f->int_w - 1) + 1 > VF_MAX_INTERMEDIATE ||
        (uint64_t)rays * (f->int_h - 1) + 1 > VF_MAX_INTERMEDIATE)
        return VF_ERR_INTERMEDIATE;
    /* Pixel U is at u = U / rays: the image keeps the points 0..int_w - 1, and the warp's u scales by rays
     * (exactly: an integer times Q32.32). */
    f->rays = rays;
    f->int_w = rays * (f->int_w - 1) + 1;
    f->int_h = rays * (f->int_h - 1) + 1;
    f->u0_q32 *= rays;
    f->v0_q32 *= rays;
    f->du_dx_q32 *= rays;
    f->dv_dx_q32 *= rays;
    f->du_dy_q32 *= rays;
    f->dv_dy_q32 *= rays;
    return VF_OK;
}

int32_t vf_factor_offset_u(const vf_factor_t *f, uint32_t k)
{
    /* ti + si k >= 0 by the choice of ti, so the shift rounds to nearest */
    return (int32_t)((f->ti_q32 + f->si_q32 * (int64_t)k + (1 << 15)) >> 16);
}

int32_t vf_factor_offset_v(const vf_factor_t *f, uint32_t k)
{
    return (int32_t)((f->tj_q32 + f->sj_q32 * (int64_t)k + (1 << 15)) >> 16);
}

/* R = Rz(roll) Rx(elevation) Ry(azimuth), Q2.30. */
static void rotation(const vf_view_t *view, mat3_t *r)
{
    int32_t sa, ca, se, ce, sr, cr;
    vfi_sincos(view->azimuth, &sa, &ca);
    vfi_sincos(view->elevation, &se, &ce);
    vfi_sincos(view->roll, &sr, &cr);
    const int32_t one = VFI_ONE_Q30;
    const mat3_t ry = {{{ca, 0, sa}, {0, one, 0}, {-sa, 0, ca}}};
    const mat3_t rx = {{{one, 0, 0}, {0, ce, -se}, {0, se, ce}}};
    const mat3_t rz = {{{cr, -sr, 0}, {sr, cr, 0}, {0, 0, one}}};
    mat3_t rxy;
    matmul_q30(&rx, &ry, &rxy);
    matmul_q30(&rz, &rxy, r);
}

static void matmul_q30(const mat3_t *a, const mat3_t *b, mat3_t *out)
{
    for (int row = 0; row < 3; row++)
        for (int col = 0; col < 3; col++) {
            int64_t sum = 0;
            for (int n = 0; n < 3; n++)
                sum += (int64_t)a->m[row][n] * b->m[n][col];
            out->m[row][col] = (int32_t)((sum + (INT64_C(1) << 29)) >> 30);
        }
}

/* The axis with the largest |d_a| = |R[2][a]| / sp_a; axes within a relative 2^-20 of it tie, and a tie goes
 * to the lowest axis, so that the core and the reference agree at exactly 45 degrees. */
static int principal_axis(const mat3_t *r, const uint32_t sp[3])
{
    uint64_t mag[3];
    for (int a = 0; a < 3; a++)
        mag[a] = (uint64_t)(r->m[2][a] < 0 ? -(int64_t)r->m[2][a] : r->m[2][a]);
    int m = 0;
    for (int a = 1; a < 3; a++)
        if (mag[a] * sp[m] > mag[m] * sp[a]) /* |d_a| > |d_m| */
            m = a;
    for (int a = 0; a < m; a++) {
        uint64_t big = mag[m] * sp[a], small = mag[a] * sp[m]; /* |d_m|, |d_a| times sp_a sp_m */
        if (big - small <= big >> 20)
            return a;
    }
    return m;
}

/* A tie of the principal axis (within 2^-20) can make a shear 1 + 2^-20; clamped to [-1, 1] a slab's front and
 * back samples stay in cells that share a voxel, which the run-length skipping relies on (runs.h). The
 * projection moves by at most 2^-20 of the volume's depth. */
static int64_t clamp_shear(int64_t s_q32)
{
    return s_q32 > ONE_Q32 ? ONE_Q32 : s_q32 < -ONE_Q32 ? -ONE_Q32 : s_q32;
}
