/* SPDX-License-Identifier: MIT */
/* phantom.c: synthetic uint8 volumes (Marschner-Lobb, 3D Shepp-Logan, a radial sphere, a uniform cube): a first run
 * needs no data. */

/*********************
 *      INCLUDES
 *********************/
#include "volume_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/*********************
 *      DEFINES
 *********************/
#define MIN_SIDE 2
#define MAX_SIDE 1024
#define NAMES "expected marschner-lobb, shepp-logan, sphere or cube"

/* Marschner and Lobb 1994, "An evaluation of reconstruction filters for volume rendering": the test signal
 * rho(x,y,z) = (1 - sin(pi z / 2) + alpha (1 + rho_r(sqrt(x^2 + y^2)))) / (2 (1 + alpha)) on [-1,1]^3, with
 * rho_r(r) = cos(2 pi f_M cos(pi r / 2)); its values lie in [0,1]. */
#define ML_FM 6.0
#define ML_ALPHA 0.25

#define SPHERE_RADIUS 0.45 /* of the side */

/**********************
 *      TYPES
 **********************/
typedef enum phantom { PH_MARSCHNER_LOBB, PH_SHEPP_LOGAN, PH_SPHERE, PH_CUBE } phantom_t;

/* An ellipsoid of the 3D Shepp-Logan head: value added inside, semi-axes, centre, Euler angles in degrees. */
typedef struct ellipsoid {
    double value, a, b, c, x0, y0, z0, phi, theta, psi;
} ellipsoid_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static void fill_marschner_lobb(uint8_t *v, uint32_t n);
static void fill_shepp_logan(uint8_t *v, uint32_t n, double *slice);
static void fill_sphere(uint8_t *v, uint32_t n);
static void fill_cube(uint8_t *v, uint32_t n);
static double coord(uint32_t i, uint32_t n);
static uint8_t to_u8(double unit);

/**********************
 *  STATIC VARIABLES
 **********************/
static const char *const phantom_names[] = {"marschner-lobb", "shepp-logan", "sphere", "cube"};

/* Kak and Slaney's 3D Shepp-Logan ellipsoids with Toft's "modified" intensities (higher contrast), as in
 * Schabel's phantom3d: values sum to 1 (skull), 0.2 (brain), 0 (ventricles) and 0.3 (small features). */
static const ellipsoid_t shepp_logan[] = {
    {1.0, 0.6900, 0.920, 0.810, 0.00, 0.0000, 0.00, 0, 0, 0},
    {-0.8, 0.6624, 0.874, 0.780, 0.00, -0.0184, 0.00, 0, 0, 0},
    {-0.2, 0.1100, 0.310, 0.220, 0.22, 0.0000, 0.00, -18, 0, 10},
    {-0.2, 0.1600, 0.410, 0.280, -0.22, 0.0000, 0.00, 18, 0, 10},
    {0.1, 0.2100, 0.250, 0.410, 0.00, 0.3500, -0.15, 0, 0, 0},
    {0.1, 0.0460, 0.046, 0.050, 0.00, 0.1000, 0.25, 0, 0, 0},
    {0.1, 0.0460, 0.046, 0.050, 0.00, -0.1000, 0.25, 0, 0, 0},
    {0.1, 0.0460, 0.023, 0.050, -0.08, -0.6050, 0.00, 0, 0, 0},
    {0.1, 0.0230, 0.023, 0.020, 0.00, -0.6060, 0.00, 0, 0, 0},
    {0.1, 0.0230, 0.046, 0.020, 0.06, -0.6050, 0.00, 0, 0, 0},
};

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

vfp_status_t vfpi_load_phantom(vfp_volume_t *vol, const char *spec, char *err, size_t errlen)
{
    const char *name = strchr(spec, ':') + 1; /* volume.c chose this reader by the "phantom:" prefix */
    const char *colon = strchr(name, ':');
    if (!colon)
        return vfpi_fail(err, errlen, spec, 0, "expected phantom:NAME:N (NAME marschner-lobb, shepp-logan, sphere or "
                         "cube; N the size of each side, %d..%d)", MIN_SIDE, MAX_SIDE);
    size_t len = (size_t)(colon - name);
    int which = -1;
    for (int i = 0; i < 4; i++)
        if (strlen(phantom_names[i]) == len && strncmp(name, phantom_names[i], len) == 0)
            which = i;
    if (which < 0)
        return vfpi_fail(err, errlen, spec, 0, "unknown phantom '%.*s' (" NAMES ")", (int)(len > 64 ? 64 : len),
                         name);
    const char *num = colon + 1;
    size_t digits = strspn(num, "0123456789");
    if (digits == 0 || num[digits] != 0)
        return vfpi_fail(err, errlen, spec, 0, "bad size '%.16s' (expected a whole number %d..%d)", num, MIN_SIDE,
                         MAX_SIDE);
    long side = digits > 5 ? MAX_SIDE + 1 : strtol(num, NULL, 10);
    if (side < MIN_SIDE || side > MAX_SIDE)
        return vfpi_fail(err, errlen, spec, 0, "size %.16s is out of range (expected %d..%d)", num, MIN_SIDE,
                         MAX_SIDE);

    uint32_t n = (uint32_t)side, dims[3] = {n, n, n};
    size_t bytes;
    if (vfpi_alloc_voxels(vol, dims, VF_VOXEL_U8, &bytes, spec, err, errlen))
        return VFP_ERR;
    for (int a = 0; a < 3; a++)
        vol->spacing[a] = 1.0;
    switch ((phantom_t)which) {
    case PH_MARSCHNER_LOBB:
        fill_marschner_lobb(vol->data, n);
        break;
    case PH_SHEPP_LOGAN: {
        double *slice = malloc((size_t)n * n * sizeof *slice);
        if (!slice)
            return vfpi_fail(err, errlen, spec, 0, "out of memory");
        fill_shepp_logan(vol->data, n, slice);
        free(slice);
        break;
    }
    case PH_SPHERE:
        fill_sphere(vol->data, n);
        break;
    case PH_CUBE:
        fill_cube(vol->data, n);
        break;
    }
    return VFP_OK;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

/* Sample i of n on [-1,1], the first and last on the ends (41 samples put one on every 0.05, as in the paper). */
static double coord(uint32_t i, uint32_t n)
{
    return -1.0 + 2.0 * i / (n - 1);
}

static uint8_t to_u8(double unit)
{
    double v = nearbyint(255.0 * unit);
    return (uint8_t)(v < 0.0 ? 0.0 : v > 255.0 ? 255.0 : v);
}

/* The signal is a sum of a term in z and a term in r(x, y): each is computed once per row or column. */
static void fill_marschner_lobb(uint8_t *v, uint32_t n)
{
    const double pi = acos(-1.0);
    double norm = 2.0 * (1.0 + ML_ALPHA);
    for (uint32_t k = 0; k < n; k++) {
        double zterm = 1.0 - sin(pi * coord(k, n) / 2.0);
        uint8_t *out = v + (size_t)k * n * n;
        for (uint32_t j = 0; j < n; j++) {
            double y = coord(j, n);
            for (uint32_t i = 0; i < n; i++) {
                double x = coord(i, n), r = sqrt(x * x + y * y);
                double rho_r = cos(2.0 * pi * ML_FM * cos(pi * r / 2.0));
                out[(size_t)j * n + i] = to_u8((zterm + ML_ALPHA * (1.0 + rho_r)) / norm);
            }
        }
    }
}

/* Slice by slice: each ellipsoid adds its value to the samples inside it, visiting only its bounding box. A
 * sample p is inside when q = R (p - centre) has (q0/a)^2 + (q1/b)^2 + (q2/c)^2 <= 1, R from phantom3d's Euler
 * angles (the centre is subtracted before rotating, as in the 2D phantom). */
static void fill_shepp_logan(uint8_t *v, uint32_t n, double *slice)
{
    const double deg = acos(-1.0) / 180.0, half = (n - 1) / 2.0;
    size_t count = sizeof shepp_logan / sizeof shepp_logan[0];
    for (uint32_t k = 0; k < n; k++) {
        double z = coord(k, n);
        memset(slice, 0, (size_t)n * n * sizeof *slice);
        for (size_t e = 0; e < count; e++) {
            const ellipsoid_t *el = &shepp_logan[e];
            double cphi = cos(el->phi * deg), sphi = sin(el->phi * deg);
            double cth = cos(el->theta * deg), sth = sin(el->theta * deg);
            double cpsi = cos(el->psi * deg), spsi = sin(el->psi * deg);
            const double r[3][3] = {
                {cpsi * cphi - cth * sphi * spsi, cpsi * sphi + cth * cphi * spsi, spsi * sth},
                {-spsi * cphi - cth * sphi * cpsi, -spsi * sphi + cth * cphi * cpsi, cpsi * sth},
                {sth * sphi, -sth * cphi, cth},
            };
            const double axes[3] = {el->a, el->b, el->c}, centre[3] = {el->x0, el->y0, el->z0};
            double extent[3];
            for (int w = 0; w < 3; w++)
                extent[w] = sqrt(pow(r[0][w] * axes[0], 2) + pow(r[1][w] * axes[1], 2) + pow(r[2][w] * axes[2], 2));
            if (fabs(z - centre[2]) > extent[2])
                continue;
            long lo[2], hi[2];
            for (int w = 0; w < 2; w++) {
                lo[w] = (long)ceil((centre[w] - extent[w] + 1.0) * half);
                hi[w] = (long)floor((centre[w] + extent[w] + 1.0) * half);
                lo[w] = lo[w] < 0 ? 0 : lo[w];
                hi[w] = hi[w] > (long)n - 1 ? (long)n - 1 : hi[w];
            }
            for (long j = lo[1]; j <= hi[1]; j++) {
                for (long i = lo[0]; i <= hi[0]; i++) {
                    double p[3] = {coord((uint32_t)i, n) - centre[0], coord((uint32_t)j, n) - centre[1], z - centre[2]};
                    double sum = 0.0;
                    for (int row = 0; row < 3; row++) {
                        double q = (r[row][0] * p[0] + r[row][1] * p[1] + r[row][2] * p[2]) / axes[row];
                        sum += q * q;
                    }
                    if (sum <= 1.0)
                        slice[(size_t)j * n + (size_t)i] += el->value;
                }
            }
        }
        uint8_t *out = v + (size_t)k * n * n;
        for (size_t s = 0; s < (size_t)n * n; s++)
            out[s] = to_u8(slice[s]); /* to_u8 clamps the sum to [0,1] */
    }
}

/* A ball whose value falls linearly from 255 at the centre to 0 at the radius: every iso-value is a shell. */
static void fill_sphere(uint8_t *v, uint32_t n)
{
    double c = (n - 1) / 2.0, radius = SPHERE_RADIUS * n;
    for (uint32_t k = 0; k < n; k++)
        for (uint32_t j = 0; j < n; j++)
            for (uint32_t i = 0; i < n; i++) {
                double dx = i - c, dy = j - c, dz = k - c, r = sqrt(dx * dx + dy * dy + dz * dz);
                v[((size_t)k * n + j) * n + i] = r < radius ? to_u8(1.0 - r / radius) : 0;
            }
}

/* Every voxel 64 (a quarter of the range): a volume visible right up to its box, to measure how a renderer treats
 * the box's faces (a ray caster sees a clean cube; shear-warp adds a slab or nothing at the side faces). */
static void fill_cube(uint8_t *v, uint32_t n)
{
    for (size_t i = 0; i < (size_t)n * n * n; i++)
        v[i] = 64;
}
