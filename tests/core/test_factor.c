/* SPDX-License-Identifier: MIT */
/*
 * test_factor.c: the shear-warp factorisation (core/factor.c) against docs/algorithm.md section 3 in double.
 *
 * (a) The 8 corners of the volume, projected directly (world, eye, final image with R from libm) and through
 *     the factorisation (standard coordinates, the snapped slice offsets, then the inverse of the warp map),
 *     land on the same final-image point: within 1e-3 pixel (measured: see corners_* cases).
 * (b) The principal axis is the largest |d_a|; an exact tie (45 degrees) goes to the lowest axis.
 * (c) Every slice's footprint lies inside the intermediate image, which is no larger than it must be.
 * (d) Shears, translations and slab length equal the spec's formulas.
 * (e) Every bad argument gives its documented status.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "check.h"
#include "volfix.h"

static uint64_t rng_state = 0x243F6A8885A308D3u;
static uint64_t rnd64(void)
{
    return check_rand64(&rng_state);
}

static const uint8_t dummy_voxel = 0;

static vf_volume_t volume(uint32_t nx, uint32_t ny, uint32_t nz, double spx, double spy, double spz)
{
    vf_volume_t v;
    v.dims[0] = nx;
    v.dims[1] = ny;
    v.dims[2] = nz;
    v.spacing_q16[0] = (uint32_t)lround(spx * 65536);
    v.spacing_q16[1] = (uint32_t)lround(spy * 65536);
    v.spacing_q16[2] = (uint32_t)lround(spz * 65536);
    v.type = VF_VOXEL_U8;
    v.voxels = &dummy_voxel; /* vf_factor never reads voxels */
    return v;
}

static vf_view_t view_deg(double az, double el, double roll, double zoom)
{
    vf_view_t v;
    v.azimuth = (int32_t)lround(az * 65536 / 360);
    v.elevation = (int32_t)lround(el * 65536 / 360);
    v.roll = (int32_t)lround(roll * 65536 / 360);
    v.zoom_q16 = (uint32_t)lround(zoom * 65536);
    return v;
}

/* The spec's camera in double, from the same BAU angles. */
typedef struct camera {
    double R[3][3];
    double sr[3];   /* relative spacing */
    double d[3];    /* viewing direction in object space */
    double scale;   /* final pixels per world unit */
    double cx, cy;  /* image centre */
    double c[3];    /* volume centre, object coordinates */
} camera_t;

static void matmul(const double a[3][3], const double b[3][3], double out[3][3])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            out[r][c] = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
}

static void camera(const vf_volume_t *vol, const vf_view_t *view, uint32_t w, uint32_t h, camera_t *cam)
{
    const double k = 2 * M_PI / 65536;
    double ta = view->azimuth * k, te = view->elevation * k, tr = view->roll * k;
    const double ry[3][3] = {{cos(ta), 0, sin(ta)}, {0, 1, 0}, {-sin(ta), 0, cos(ta)}};
    const double rx[3][3] = {{1, 0, 0}, {0, cos(te), -sin(te)}, {0, sin(te), cos(te)}};
    const double rz[3][3] = {{cos(tr), -sin(tr), 0}, {sin(tr), cos(tr), 0}, {0, 0, 1}};
    double rxy[3][3];
    matmul(rx, ry, rxy);
    matmul(rz, rxy, cam->R);
    double spmin = fmin(vol->spacing_q16[0], fmin(vol->spacing_q16[1], vol->spacing_q16[2]));
    double diag2 = 0;
    for (int a = 0; a < 3; a++) {
        cam->sr[a] = vol->spacing_q16[a] / spmin;
        cam->d[a] = cam->R[2][a] / cam->sr[a];
        cam->c[a] = (vol->dims[a] - 1) / 2.0;
        diag2 += pow(cam->sr[a] * (vol->dims[a] - 1), 2);
    }
    cam->scale = view->zoom_q16 / 65536.0 * (w < h ? w : h) / sqrt(diag2);
    cam->cx = (w - 1) / 2.0;
    cam->cy = (h - 1) / 2.0;
}

/* Object point p to the final image, directly. */
static void project_direct(const camera_t *cam, const double p[3], double *px, double *py)
{
    double wv[3], e[2];
    for (int a = 0; a < 3; a++)
        wv[a] = cam->sr[a] * (p[a] - cam->c[a]);
    for (int b = 0; b < 2; b++)
        e[b] = cam->R[b][0] * wv[0] + cam->R[b][1] * wv[1] + cam->R[b][2] * wv[2];
    *px = cam->scale * e[0] + cam->cx;
    *py = cam->scale * e[1] + cam->cy;
}

/* Object voxel p (integer) to the final image through the core's factorisation. */
static void project_factor(const vf_factor_t *f, const uint32_t dims[3], const uint32_t p[3], double *px,
                           double *py)
{
    uint32_t i = p[f->i_axis], j = p[f->j_axis];
    uint32_t k = f->k_flip ? dims[f->k_axis] - 1 - p[f->k_axis] : p[f->k_axis];
    double u = i + vf_factor_offset_u(f, k) / 65536.0, v = j + vf_factor_offset_v(f, k) / 65536.0;
    /* u = u0 + x du/dx + y du/dy, v = v0 + x dv/dx + y dv/dy: solve for (x, y) */
    const double q = 4294967296.0;
    double a = f->du_dx_q32 / q, b = f->du_dy_q32 / q, c = f->dv_dx_q32 / q, d = f->dv_dy_q32 / q;
    double ru = u - f->u0_q32 / q, rv = v - f->v0_q32 / q, det = a * d - b * c;
    *px = (d * ru - b * rv) / det;
    *py = (a * rv - c * ru) / det;
}

/* Everything the spec says about one factorisation; returns the largest corner error in pixels, or -1 after a
 * failed check (the failure is recorded). */
static double check_factor(const vf_volume_t *vol, const vf_view_t *view, uint32_t w, uint32_t h, double tol)
{
    vf_factor_t f;
    vf_status_t s = vf_factor(&f, vol, view, w, h);
    if (s != VF_OK) {
        check_fail(__FILE__, __LINE__, "vf_factor: %s", vf_status_text(s));
        return -1;
    }
    camera_t cam;
    camera(vol, view, w, h, &cam);
    const uint32_t *n = vol->dims;
#define FAIL_IF(cond, ...) \
    do { \
        if (cond) { \
            check_fail(__FILE__, __LINE__, __VA_ARGS__); \
            return -1; \
        } \
    } while (0)

    /* (b) principal axis: the largest |d_a|, ties (relative 2^-20) to the lowest axis */
    double mag[3] = {fabs(cam.d[0]), fabs(cam.d[1]), fabs(cam.d[2])};
    double big = fmax(mag[0], fmax(mag[1], mag[2]));
    int ka = f.k_axis;
    FAIL_IF(ka > 2 || f.i_axis != (ka + 1) % 3 || f.j_axis != (ka + 2) % 3, "axes %d %d %d", ka, f.i_axis,
            f.j_axis);
    FAIL_IF(mag[ka] < big * (1 - 4e-6), "view %d %d %d: k_axis %d, |d| = %g %g %g", view->azimuth,
            view->elevation, view->roll, ka, mag[0], mag[1], mag[2]);
    for (int a = 0; a < ka; a++) /* a lower axis that clearly ties must have won */
        FAIL_IF(mag[a] >= big * (1 - 1e-8), "tie not given to the lowest axis: k %d, |d| = %.17g %.17g %.17g", ka,
                mag[0], mag[1], mag[2]);
    FAIL_IF(f.k_flip != (cam.d[ka] < 0), "k_flip %d with d_k %g", f.k_flip, cam.d[ka]);
    FAIL_IF(f.ni != n[f.i_axis] || f.nj != n[f.j_axis] || f.nk != n[ka], "dims");

    /* (d) shears, translations, slab length */
    const double q32 = 4294967296.0;
    double dk = fabs(cam.d[ka]);
    double si = -cam.d[f.i_axis] / dk, sj = -cam.d[f.j_axis] / dk;
    double si_c = f.si_q32 / q32, sj_c = f.sj_q32 / q32;
    /* R carries the sin/cos error (2.3e-9 per factor, three factors): eps = 1e-8 on each element of R, and
     * si = -R_i Sr_k / (|R_k| Sr_i) amplifies it by 1 / |R_k| (up to 64 sqrt 3 with anisotropic spacing) */
    double rk = fabs(cam.R[2][ka]), eps = 1e-8;
    double tol_i = eps * (cam.sr[ka] / cam.sr[f.i_axis] + fabs(si)) / rk;
    double tol_j = eps * (cam.sr[ka] / cam.sr[f.j_axis] + fabs(sj)) / rk;
    FAIL_IF(fabs(si_c - si) > tol_i || fabs(sj_c - sj) > tol_j, "shear %.12f %.12f vs %.12f %.12f", si_c, sj_c, si,
            sj);
    FAIL_IF(fabs(si_c) > 1 + 1e-6 || fabs(sj_c) > 1 + 1e-6, "shear beyond 1: %.12f %.12f", si_c, sj_c);
    /* ti = max(0, -si (n_k - 1)) exactly from the core's own shear */
    FAIL_IF(f.ti_q32 != (f.si_q32 < 0 ? -f.si_q32 * (int64_t)(f.nk - 1) : 0), "ti");
    FAIL_IF(f.tj_q32 != (f.sj_q32 < 0 ? -f.sj_q32 * (int64_t)(f.nk - 1) : 0), "tj");
    double slab = sqrt(pow(si * cam.sr[f.i_axis], 2) + pow(sj * cam.sr[f.j_axis], 2) + pow(cam.sr[ka], 2));
    FAIL_IF(fabs(f.slab_q16 / 65536.0 - slab) > 1.0 / 65536, "slab %.8f vs %.8f", f.slab_q16 / 65536.0, slab);

    /* (c) footprints: slice k covers pixel centres ceil(ou) .. floor(ou) + n_i - 1 */
    FAIL_IF(f.int_w > f.ni + f.nk - 1 || f.int_h > f.nj + f.nk - 1, "intermediate %ux%u too large", f.int_w,
            f.int_h);
    uint32_t reach_u = 0, reach_v = 0;
    for (uint32_t k = 0; k < f.nk; k++) {
        int32_t ou = vf_factor_offset_u(&f, k), ov = vf_factor_offset_v(&f, k);
        double ou_exact = (f.ti_q32 + (double)f.si_q32 * k) / q32 * 65536;
        FAIL_IF(fabs(ou - ou_exact) > 0.5 + 1e-6, "offset u of slice %u not snapped to nearest", k);
        FAIL_IF(ou < 0 || ov < 0, "slice %u offset negative", k);
        uint32_t last_u = (uint32_t)(ou >> 16) + f.ni - 1, last_v = (uint32_t)(ov >> 16) + f.nj - 1;
        FAIL_IF(last_u >= f.int_w || last_v >= f.int_h, "slice %u outside the intermediate image", k);
        reach_u = last_u + 1 > reach_u ? last_u + 1 : reach_u;
        reach_v = last_v + 1 > reach_v ? last_v + 1 : reach_v;
        /* the spec's offsets in double: ti + si k */
        double ti = fmax(0, -si * (f.nk - 1)), tj = fmax(0, -sj * (f.nk - 1));
        FAIL_IF(fabs(ou / 65536.0 - (ti + si * k)) > 1e-4 || fabs(ov / 65536.0 - (tj + sj * k)) > 1e-4,
                "slice %u offset (%.6f, %.6f) vs (%.6f, %.6f)", k, ou / 65536.0, ov / 65536.0, ti + si * k,
                tj + sj * k);
    }
    FAIL_IF(reach_u != f.int_w || reach_v != f.int_h, "intermediate %ux%u, slices reach %ux%u", f.int_w, f.int_h,
            reach_u, reach_v);
    FAIL_IF(f.out_w != w || f.out_h != h, "output size");

    /* (a) the 8 corners. The bound is tol pixels plus what the core's documented quantisation allows: the
     * slice offsets are snapped to 2^-16 (half a step, times the screen size of a voxel, Sr_i scale), 1 / scale and the
     * warp steps are Q32.32 (2^-33 intermediate pixel per step), and the diagonal D is computed in Q12 (relative 2^-13 / D; this last one is
     * not in docs/algorithm.md section 6 and is exposed on its own by scale_precision). Both relative terms act
     * on the distance from the image centre. */
    double diag = cam.scale > 0 ? (view->zoom_q16 / 65536.0) * (w < h ? w : h) / cam.scale : 1;
    double inv_scale = 1 / cam.scale;
    double sr_max = fmax(cam.sr[0], fmax(cam.sr[1], cam.sr[2]));
    /* du, dv: 2^-33 of an intermediate pixel each (times 1 + |G| <= 4), an intermediate pixel being up to
     * Sr_max world units, scale final pixels each */
    double rel = pow(2, -13) / diag + pow(2, -31) / inv_scale * sr_max;
    double worst = 0;
    for (int corner = 0; corner < 8; corner++) {
        uint32_t p[3];
        double pd[3];
        for (int a = 0; a < 3; a++) {
            p[a] = (corner >> a) & 1 ? n[a] - 1 : 0;
            pd[a] = p[a];
        }
        double x0, y0, x1, y1;
        project_direct(&cam, pd, &x0, &y0);
        project_factor(&f, n, p, &x1, &y1);
        double err = hypot(x1 - x0, y1 - y0);
        double bound = tol + cam.scale * pow(2, -17) * hypot(cam.sr[f.i_axis], cam.sr[f.j_axis]) +
                       rel * hypot(x0 - cam.cx, y0 - cam.cy);
        worst = fmax(worst, err / bound * tol);
        FAIL_IF(!(err <= bound),
                "volume %ux%ux%u sp %u:%u:%u, view (%d, %d, %d) zoom %u, %ux%u, corner %d: direct (%.5f, %.5f), "
                "factor (%.5f, %.5f), bound %.3g",
                n[0], n[1], n[2], vol->spacing_q16[0], vol->spacing_q16[1], vol->spacing_q16[2], view->azimuth,
                view->elevation, view->roll, view->zoom_q16, w, h, corner, x0, y0, x1, y1, bound);
    }

    /* The warp map against the spec's formula at the image's corners and centre: the intermediate point seen
     * by final pixel (px, py) is u = ti + sum_b e_b (R[b][i] / Sr_i + si sgn R[b][k] / Sr_k) + c_i + si k_c. */
    const double px_list[5][2] = {{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}, {(w - 1) / 2.0, (h - 1) / 2.0}};
    double sgn = f.k_flip ? -1 : 1, ti = fmax(0, -si * (f.nk - 1)), tj = fmax(0, -sj * (f.nk - 1));
    double kc = (f.nk - 1) / 2.0;
    for (int m = 0; m < 5; m++) {
        double e[2] = {(px_list[m][0] - cam.cx) / cam.scale, (px_list[m][1] - cam.cy) / cam.scale};
        double u = ti + (f.ni - 1) / 2.0 + si * kc, v = tj + (f.nj - 1) / 2.0 + sj * kc;
        for (int b2 = 0; b2 < 2; b2++) {
            u += e[b2] * (cam.R[b2][f.i_axis] / cam.sr[f.i_axis] + si * sgn * cam.R[b2][ka] / cam.sr[ka]);
            v += e[b2] * (cam.R[b2][f.j_axis] / cam.sr[f.j_axis] + sj * sgn * cam.R[b2][ka] / cam.sr[ka]);
        }
        double uc = (f.u0_q32 + px_list[m][0] * f.du_dx_q32 + px_list[m][1] * f.du_dy_q32) / q32;
        double vc = (f.v0_q32 + px_list[m][0] * f.dv_dx_q32 + px_list[m][1] * f.dv_dy_q32) / q32;
        /* in intermediate pixels: 1e-6 plus the shear error times k_c plus the scale error times |e| */
        double bound_uv = 1e-6 + (tol_i + tol_j) * kc + (rel + 1e-8) * 3 * hypot(e[0], e[1]);
        FAIL_IF(fabs(uc - u) > bound_uv || fabs(vc - v) > bound_uv,
                "warp at pixel (%g, %g): core (%.8f, %.8f), spec (%.8f, %.8f), bound %.3g", px_list[m][0],
                px_list[m][1], uc, vc, u, v, bound_uv);
    }
#undef FAIL_IF
    return worst;
}

static const double special[][3] = {
    {0, 0, 0},     {30, 20, 0},   {45, 0, 0},     {60, -35, 0},   {135, 70, 0},  {90, 0, 0},   {180, 0, 0},
    {0, 90, 0},    {0, -90, 0},   {270, 0, 0},    {-90, 0, 0},    {0, 45, 0},    {45, 45, 0},  {0, 0, 30},
    {0, 0, 90},    {0, 0, 180},   {30, 20, 45},   {135, 70, -60}, {225, -45, 10}, {315, 30, 200}, {10, 80, 0},
    {-30, -20, 0}, {89.9, 0.1, 0}, {1, 1, 1},    {179, -89, 33}, {360, 0, 0},   {720, 450, -360},
};

static const double volumes[][6] = {
    {16, 16, 16, 1, 1, 1},    {16, 16, 16, 3.2, 3.2, 1.5}, {16, 16, 16, 1, 1, 2}, {7, 12, 20, 1, 1, 1},
    {20, 12, 7, 1, 2, 1},     {2, 2, 2, 1, 1, 1},          {32, 5, 9, 0.5, 0.7, 3}, {64, 64, 3, 1, 1, 1},
    {4096, 2, 300, 1, 1, 1},  {4096, 4096, 4096, 1, 1, 1}, {9, 9, 9, 64, 1, 1},   {100, 3, 50, 1, 64, 20},
};

static void corners_special_views(void)
{
    double worst = 0;
    for (size_t vi = 0; vi < sizeof volumes / sizeof volumes[0]; vi++) {
        const double *vd = volumes[vi];
        vf_volume_t vol = volume((uint32_t)vd[0], (uint32_t)vd[1], (uint32_t)vd[2], vd[3], vd[4], vd[5]);
        for (size_t n = 0; n < sizeof special / sizeof special[0]; n++) {
            vf_view_t view = view_deg(special[n][0], special[n][1], special[n][2], 1.0);
            double e = check_factor(&vol, &view, 64, 48, 1e-3);
            if (check_failed)
                return;
            worst = fmax(worst, e);
        }
    }
    CHECK(worst <= 1e-3);
}

static void corners_random_views(void)
{
    double worst = 0;
    for (size_t vi = 0; vi < sizeof volumes / sizeof volumes[0]; vi++) {
        const double *vd = volumes[vi];
        vf_volume_t vol = volume((uint32_t)vd[0], (uint32_t)vd[1], (uint32_t)vd[2], vd[3], vd[4], vd[5]);
        for (int n = 0; n < 300; n++) {
            vf_view_t view;
            view.azimuth = (int32_t)(rnd64() % 65536) - 32768;
            view.elevation = (int32_t)(rnd64() % 65536);
            view.roll = (int32_t)(rnd64() % 200000) - 100000;
            view.zoom_q16 = 16384 + (uint32_t)(rnd64() % (8 * 65536)); /* 0.25 .. 8.25 */
            uint32_t w = 1 + (uint32_t)(rnd64() % 400), h = 1 + (uint32_t)(rnd64() % 400);
            vf_factor_t f;
            if (vf_factor(&f, &vol, &view, w, h) == VF_ERR_ARG) {
                camera_t cam;
                camera(&vol, &view, w, h, &cam);
                CHECK_MSG(1 / cam.scale > 255.9, "VF_ERR_ARG at %g voxels per pixel", 1 / cam.scale);
                continue;
            }
            double e = check_factor(&vol, &view, w, h, 1e-3);
            if (check_failed)
                return;
            worst = fmax(worst, e);
        }
    }
    CHECK(worst <= 1e-3);
}

/* Extreme zoom and image sizes: the corner error scales with the zoom (the offsets are snapped to 2^-16 of an
 * intermediate pixel), so the bound is 1e-3 pixel plus 2^-15 of a voxel's size on the screen. */
static void corners_extreme_zoom(void)
{
    const uint32_t zooms[] = {256, 300, 65536, 256u << 16, 100u << 16};
    const uint32_t sizes[][2] = {{1, 1}, {8192, 8192}, {8192, 1}, {3, 8192}, {640, 480}};
    for (size_t vi = 0; vi < sizeof volumes / sizeof volumes[0]; vi++) {
        const double *vd = volumes[vi];
        vf_volume_t vol = volume((uint32_t)vd[0], (uint32_t)vd[1], (uint32_t)vd[2], vd[3], vd[4], vd[5]);
        for (size_t z = 0; z < sizeof zooms / sizeof zooms[0]; z++)
            for (size_t sz = 0; sz < sizeof sizes / sizeof sizes[0]; sz++) {
                vf_view_t view = view_deg(33, -21, 7, 1);
                view.zoom_q16 = zooms[z];
                vf_factor_t f;
                vf_status_t s = vf_factor(&f, &vol, &view, sizes[sz][0], sizes[sz][1]);
                camera_t cam;
                camera(&vol, &view, sizes[sz][0], sizes[sz][1], &cam);
                if (s == VF_ERR_ARG) {
                    /* only when a pixel would cover more than 256 voxels */
                    CHECK_MSG(1 / cam.scale > 255.9, "VF_ERR_ARG at %g voxels per pixel", 1 / cam.scale);
                    continue;
                }
                CHECK_EQ(s, VF_OK);
                check_factor(&vol, &view, sizes[sz][0], sizes[sz][1], 1e-3);
                if (check_failed)
                    return;
            }
    }
}

/* The tie rule at exactly 45 degrees (sin == cos exactly in the core): the lowest axis wins. */
static void principal_axis_ties(void)
{
    vf_volume_t cube = volume(8, 8, 8, 1, 1, 1);
    vf_factor_t f;
    struct {
        double az, el, roll;
        int k;
        bool flip;
    } cases[] = {
        {0, 0, 0, 2, false},    {180, 0, 0, 2, true},  {90, 0, 0, 0, true},   {-90, 0, 0, 0, false},
        {0, 90, 0, 1, false},   {0, -90, 0, 1, true},  {45, 0, 0, 0, true},   {-45, 0, 0, 0, false},
        {135, 0, 0, 0, true},   {0, 45, 0, 1, false},  {0, -45, 0, 1, true},  {180, 45, 0, 1, false},
        {0, 0, 77, 2, false},   {45, 0, 33, 0, true},  {30, 20, 0, 2, false}, {60, -35, 0, 0, true},
        {135, 70, 0, 1, false},
    };
    for (size_t n = 0; n < sizeof cases / sizeof cases[0]; n++) {
        vf_view_t v = view_deg(cases[n].az, cases[n].el, cases[n].roll, 1);
        CHECK_EQ(vf_factor(&f, &cube, &v, 32, 32), VF_OK);
        CHECK_MSG(f.k_axis == cases[n].k && f.k_flip == cases[n].flip, "view (%g, %g, %g): k %d flip %d, want %d %d",
                  cases[n].az, cases[n].el, cases[n].roll, f.k_axis, f.k_flip, cases[n].k, cases[n].flip);
    }
    /* at exactly 45 degrees the shear is exactly -+1 */
    vf_view_t v = view_deg(45, 0, 0, 1);
    CHECK_EQ(vf_factor(&f, &cube, &v, 32, 32), VF_OK);
    CHECK_EQ(f.k_axis, 0);
    CHECK(llabs(f.sj_q32) == (INT64_C(1) << 32)); /* j = z */
    CHECK_EQ(f.si_q32, 0);
    /* anisotropic spacing moves the boundary: with sp = (1, 1, 2), |d_x| = sin az and |d_z| = cos az / 2, which
     * meet at tan az = 1/2 (26.565 degrees) */
    vf_volume_t aniso = volume(8, 8, 8, 1, 1, 2);
    const struct {
        double az;
        int k;
    } an[] = {{0, 2}, {20, 2}, {25, 2}, {26.5, 2}, {26.7, 0}, {27, 0}, {45, 0}, {-26.5, 2}, {-26.7, 0}};
    for (size_t n = 0; n < sizeof an / sizeof an[0]; n++) {
        v = view_deg(an[n].az, 0, 0, 1);
        CHECK_EQ(vf_factor(&f, &aniso, &v, 32, 32), VF_OK);
        CHECK_MSG(f.k_axis == an[n].k, "az %g: k %d, want %d", an[n].az, f.k_axis, an[n].k);
    }
}

/* A view straight down the z axis where the spec's scale is exactly 1 (the diagonal of 15x15x8 is |(14, 14, 7)|
 * = 21, the output 21x21, zoom 1): the warp is the identity plus a shift by 3 pixels (used by test_render too).
 * The lengths are in ratio 2:2:1, so the diagonal is exact in any binary fixed point. */
static void identity_warp(void)
{
    vf_volume_t vol = volume(15, 15, 8, 1, 1, 1);
    vf_view_t v = view_deg(0, 0, 0, 1);
    vf_factor_t f;
    CHECK_EQ(vf_factor(&f, &vol, &v, 21, 21), VF_OK);
    CHECK_EQ(f.k_axis, 2);
    CHECK_EQ(f.k_flip, 0);
    CHECK_EQ(f.si_q32, 0);
    CHECK_EQ(f.sj_q32, 0);
    CHECK_EQ(f.int_w, 15);
    CHECK_EQ(f.int_h, 15);
    CHECK_EQ(f.slab_q16, 65536);
    CHECK_EQ(f.du_dx_q32, INT64_C(1) << 32);
    CHECK_EQ(f.dv_dy_q32, INT64_C(1) << 32);
    CHECK_EQ(f.du_dy_q32, 0);
    CHECK_EQ(f.dv_dx_q32, 0);
    CHECK_EQ(f.u0_q32, -(INT64_C(3) << 32));
    CHECK_EQ(f.v0_q32, -(INT64_C(3) << 32));
    /* 180 degrees about the vertical axis: x mirrored, slices renumbered */
    v = view_deg(180, 0, 0, 1);
    CHECK_EQ(vf_factor(&f, &vol, &v, 21, 21), VF_OK);
    CHECK_EQ(f.k_flip, 1);
    CHECK_EQ(f.du_dx_q32, -(INT64_C(1) << 32));
    CHECK_EQ(f.dv_dy_q32, INT64_C(1) << 32);
    CHECK_EQ(f.u0_q32, INT64_C(17) << 32);
}

/* Straight down z with unit spacing, G is exactly 1, so du/dx is 1 / scale = D / (zoom min(W, H)) itself, which
 * Q32.32 could hold to 2^-33. CORE DOUBT (factor.c, the diagonal "len_q12 ... diag_q16 = sqrt << 4"): D is computed
 * in Q12 only, so 1 / scale is off by up to 2^-13 / D relative: 4.3e-5 for a 2x2x2 volume (1.7e-3 pixel at the
 * corners of a 64x48 image, 0.18 pixel at the edge of an 8192 image), 4.7e-6 for 16^3. docs/algorithm.md
 * section 6 does not list this quantisation, so the double reference's warp differs by that much. */
static void scale_precision(void)
{
    const uint32_t dims[][3] = {{2, 2, 2}, {3, 3, 3}, {16, 16, 16}, {7, 12, 20}, {256, 256, 128}};
    for (size_t n = 0; n < sizeof dims / sizeof dims[0]; n++) {
        vf_volume_t vol = volume(dims[n][0], dims[n][1], dims[n][2], 1, 1, 1);
        vf_view_t v = view_deg(0, 0, 0, 1);
        vf_factor_t f;
        CHECK_EQ(vf_factor(&f, &vol, &v, 64, 48), VF_OK);
        camera_t cam;
        camera(&vol, &v, 64, 48, &cam);
        double got = f.du_dx_q32 / 4294967296.0, want = 1 / cam.scale;
        CHECK_MSG(fabs(got / want - 1) <= 1e-7, "volume %ux%ux%u: 1 / scale %.12f, spec %.12f (relative %.3g)",
                  dims[n][0], dims[n][1], dims[n][2], got, want, got / want - 1);
    }
}

static void argument_checks(void)
{
    vf_volume_t vol = volume(8, 8, 8, 1, 1, 1);
    vf_view_t v = view_deg(10, 20, 30, 1);
    vf_factor_t f;
    CHECK_EQ(vf_factor(NULL, &vol, &v, 32, 32), VF_ERR_NULL);
    CHECK_EQ(vf_factor(&f, NULL, &v, 32, 32), VF_ERR_NULL);
    CHECK_EQ(vf_factor(&f, &vol, NULL, 32, 32), VF_ERR_NULL);
    CHECK_EQ(vf_factor(&f, &vol, &v, 32, 32), VF_OK);

    const uint32_t bad_dims[] = {0, 1, VF_MAX_DIM + 1, UINT32_MAX};
    for (int a = 0; a < 3; a++)
        for (size_t n = 0; n < 4; n++) {
            vf_volume_t b = vol;
            b.dims[a] = bad_dims[n];
            CHECK_EQ(vf_factor(&f, &b, &v, 32, 32), VF_ERR_DIMS);
        }
    vf_volume_t edge = volume(2, VF_MAX_DIM, 2, 1, 1, 1);
    CHECK_EQ(vf_factor(&f, &edge, &v, 32, 32), VF_OK);

    for (int a = 0; a < 3; a++) {
        vf_volume_t b = vol;
        b.spacing_q16[a] = 0;
        CHECK_EQ(vf_factor(&f, &b, &v, 32, 32), VF_ERR_SPACING);
        b = vol;
        b.spacing_q16[a] = 65536 * VF_MAX_ANISOTROPY; /* exactly the limit: allowed */
        CHECK_EQ(vf_factor(&f, &b, &v, 32, 32), VF_OK);
        b.spacing_q16[a] = 65536 * VF_MAX_ANISOTROPY + 1; /* just over */
        CHECK_EQ(vf_factor(&f, &b, &v, 32, 32), VF_ERR_SPACING);
        b = vol;
        b.spacing_q16[a] = 1023; /* 65536 / 1023 > 64 */
        CHECK_EQ(vf_factor(&f, &b, &v, 32, 32), VF_ERR_SPACING);
        b.spacing_q16[a] = 1024; /* 64 exactly */
        CHECK_EQ(vf_factor(&f, &b, &v, 32, 32), VF_OK);
    }
    /* huge spacings (only ratios matter) */
    vf_volume_t huge = vol;
    huge.spacing_q16[0] = huge.spacing_q16[1] = UINT32_MAX;
    huge.spacing_q16[2] = UINT32_MAX / 64 + 1;
    CHECK_EQ(check_factor(&huge, &v, 32, 32, 1e-3) >= 0, 1);

    CHECK_EQ(vf_factor(&f, &vol, &v, 0, 32), VF_ERR_IMAGE);
    CHECK_EQ(vf_factor(&f, &vol, &v, 32, 0), VF_ERR_IMAGE);
    CHECK_EQ(vf_factor(&f, &vol, &v, VF_MAX_IMAGE + 1, 32), VF_ERR_IMAGE);
    CHECK_EQ(vf_factor(&f, &vol, &v, 32, VF_MAX_IMAGE + 1), VF_ERR_IMAGE);
    CHECK_EQ(vf_factor(&f, &vol, &v, VF_MAX_IMAGE, VF_MAX_IMAGE), VF_OK);

    const uint32_t bad_zoom[] = {0, 1, 255, (256u << 16) + 1, UINT32_MAX};
    for (size_t n = 0; n < 5; n++) {
        vf_view_t z = v;
        z.zoom_q16 = bad_zoom[n];
        CHECK_EQ(vf_factor(&f, &vol, &z, 32, 32), VF_ERR_ARG);
    }
    vf_view_t z = v;
    z.zoom_q16 = 256; /* 1/256 */
    CHECK_EQ(vf_factor(&f, &vol, &z, 32, 32), VF_OK);
    z.zoom_q16 = 256u << 16; /* 256 */
    CHECK_EQ(vf_factor(&f, &vol, &z, 32, 32), VF_OK);
    /* a legal zoom that would put more than 256 voxels in a pixel is refused too */
    vf_volume_t big = volume(4096, 4096, 4096, 1, 1, 1);
    z.zoom_q16 = 256;
    CHECK_EQ(vf_factor(&f, &big, &z, 1, 1), VF_ERR_ARG);
}

CHECK_CASES(CHECK_CASE(corners_special_views), CHECK_CASE(corners_random_views), CHECK_CASE(corners_extreme_zoom),
            CHECK_CASE(principal_axis_ties), CHECK_CASE(identity_warp), CHECK_CASE(scale_precision),
            CHECK_CASE(argument_checks));
CHECK_RUN("core/factor")
