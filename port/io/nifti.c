/* SPDX-License-Identifier: MIT */
/* nifti.c: the NIfTI-1 and NIfTI-2 reader (single-file .nii and .nii.gz, either byte order, 8- and 16-bit integer
 * voxels, the patient orientation from the sform or the qform). */

/*********************
 *      INCLUDES
 *********************/
#include "volume_internal.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/*********************
 *      DEFINES
 *********************/
/* Byte offsets of the header fields this reader uses: NIfTI-1 (nifti1.h, struct nifti_1_header: 16-bit dims, float
 * fields) and NIfTI-2 (nifti2.h, struct nifti_2_header: 64-bit dims, double fields, another order). */
#define N1_BYTES 348
#define N1_DIM 40          /* int16 dim[8] */
#define N1_DATATYPE 70     /* int16 */
#define N1_PIXDIM 76       /* float pixdim[8] */
#define N1_VOX_OFFSET 108  /* float */
#define N1_SCL_SLOPE 112   /* float */
#define N1_SCL_INTER 116   /* float */
#define N1_QFORM_CODE 252  /* int16 */
#define N1_SFORM_CODE 254  /* int16 */
#define N1_QUATERN 256     /* float quatern_b, c, d */
#define N1_SROW 280        /* float srow_x[4], srow_y[4], srow_z[4] */
#define N1_MAGIC 344       /* char magic[4]: "n+1" */

#define N2_BYTES 540
#define N2_MAGIC 4         /* char magic[8]: "n+2\0\r\n\032\n" */
#define N2_DATATYPE 12     /* int16 */
#define N2_DIM 16          /* int64 dim[8] */
#define N2_PIXDIM 104      /* double pixdim[8] */
#define N2_VOX_OFFSET 168  /* int64 */
#define N2_SCL_SLOPE 176   /* double */
#define N2_SCL_INTER 184   /* double */
#define N2_QFORM_CODE 344  /* int32 */
#define N2_SFORM_CODE 348  /* int32 */
#define N2_QUATERN 352     /* double quatern_b, c, d */
#define N2_SROW 400        /* double srow_x[4], srow_y[4], srow_z[4] */

/**********************
 *      TYPES
 **********************/

/* The fields of either version, widened. */
typedef struct header {
    int version;           /* 1 or 2 */
    int big;
    int64_t dim[8];
    int datatype;
    double pixdim[8];
    double vox_offset;
    double slope, inter;
    int qform_code, sform_code;
    double quatern[3];     /* b, c, d */
    double srow[3][4];
} header_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t read_header(header_t *h, const unsigned char *hdr, size_t n, const char *path, int gzip, char *err,
                                size_t errlen);
static vfp_status_t parse_header(vfp_volume_t *vol, header_t *h, const char *path, int gzip, uint32_t dims[3],
                                 vf_voxel_t *type, char *err, size_t errlen);
static vfp_status_t orientation(vfp_volume_t *vol, const header_t *h, const char *path, char *err, size_t errlen);
static int datatype_voxel(int datatype, vf_voxel_t *type);
static const char *datatype_name(int datatype);
static int16_t load_i16(const unsigned char *p, int big);
static int32_t load_i32(const unsigned char *p, int big);
static int64_t load_i64(const unsigned char *p, int big);
static float load_f32(const unsigned char *p, int big);
static double load_f64(const unsigned char *p, int big);

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

int vfpi_is_nifti(const unsigned char *head, size_t n)
{
    if (n >= N1_BYTES && (vfpi_load32(head, 0) == N1_BYTES || vfpi_load32(head, 1) == N1_BYTES) &&
        (memcmp(head + N1_MAGIC, "n+1", 4) == 0 || memcmp(head + N1_MAGIC, "ni1", 4) == 0))
        return 1;
    return n >= 8 && (vfpi_load32(head, 0) == N2_BYTES || vfpi_load32(head, 1) == N2_BYTES) &&
           (memcmp(head + N2_MAGIC, "n+2", 4) == 0 || memcmp(head + N2_MAGIC, "ni2", 4) == 0);
}

vfp_status_t vfpi_load_nifti(vfp_volume_t *vol, const char *path, int gzip, char *err, size_t errlen)
{
    unsigned char hdr[VFPI_HEAD_BYTES];
    size_t n;
    if (vfpi_read_head(path, gzip, hdr, sizeof hdr, &n, err, errlen))
        return VFP_ERR;
    header_t h;
    if (read_header(&h, hdr, n, path, gzip, err, errlen))
        return VFP_ERR;
    uint32_t dims[3];
    vf_voxel_t type = VF_VOXEL_U8;
    if (parse_header(vol, &h, path, gzip, dims, &type, err, errlen) || orientation(vol, &h, path, err, errlen))
        return VFP_ERR;
    vfpi_source_t src = {.path = path, .byte_skip = (int64_t)h.vox_offset, .gzip = gzip};
    size_t bytes;
    if (vfpi_read_voxels(vol, dims, type, &src, &bytes, err, errlen))
        return VFP_ERR;
    if (vfpi_type_bytes(type) == 2)
        vfpi_to_native16(vol->data, bytes / 2, h.big);
    return VFP_OK;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

/* The version and byte order from sizeof_hdr (348 or 540 in the file's order), the magic, and the fields. */
static vfp_status_t read_header(header_t *h, const unsigned char *hdr, size_t n, const char *path, int gzip, char *err,
                                size_t errlen)
{
    memset(h, 0, sizeof *h);
    const char *after = gzip ? " after decompression" : "";
    if (n < 4)
        return vfpi_fail(err, errlen, path, 0, "too short for a NIfTI header: %zu bytes (expected at least %d)%s", n,
                         N1_BYTES, after);
    uint32_t le = vfpi_load32(hdr, 0), be = vfpi_load32(hdr, 1);
    if (le == N1_BYTES || be == N1_BYTES) {
        h->version = 1;
        h->big = le != N1_BYTES;
    } else if (le == N2_BYTES || be == N2_BYTES) {
        h->version = 2;
        h->big = le != N2_BYTES;
    } else {
        return vfpi_fail(err, errlen, path, 0, "bad sizeof_hdr %ld (expected 348 for NIfTI-1 or 540 for NIfTI-2, in "
                         "either byte order)", (long)(int32_t)le);
    }
    int big = h->big;
    if (h->version == 1) {
        if (n < N1_BYTES)
            return vfpi_fail(err, errlen, path, 0, "too short for a NIfTI-1 header: %zu bytes (expected at least "
                             "%d)%s", n, N1_BYTES, after);
        if (memcmp(hdr + N1_MAGIC, "ni1", 4) == 0)
            return vfpi_fail(err, errlen, path, 0, "magic 'ni1' means a .hdr/.img pair, which is not supported "
                             "(expected a single-file .nii, magic 'n+1')");
        if (memcmp(hdr + N1_MAGIC, "n+1", 4) != 0)
            return vfpi_fail(err, errlen, path, 0, "bad magic '%.3s' (expected 'n+1', a single-file NIfTI-1)",
                             (const char *)hdr + N1_MAGIC);
        for (int i = 0; i < 8; i++) {
            h->dim[i] = load_i16(hdr + N1_DIM + 2 * i, big);
            h->pixdim[i] = load_f32(hdr + N1_PIXDIM + 4 * i, big);
        }
        h->datatype = load_i16(hdr + N1_DATATYPE, big);
        h->vox_offset = load_f32(hdr + N1_VOX_OFFSET, big);
        h->slope = load_f32(hdr + N1_SCL_SLOPE, big);
        h->inter = load_f32(hdr + N1_SCL_INTER, big);
        h->qform_code = load_i16(hdr + N1_QFORM_CODE, big);
        h->sform_code = load_i16(hdr + N1_SFORM_CODE, big);
        for (int i = 0; i < 3; i++)
            h->quatern[i] = load_f32(hdr + N1_QUATERN + 4 * i, big);
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                h->srow[r][c] = load_f32(hdr + N1_SROW + 16 * r + 4 * c, big);
        return VFP_OK;
    }
    if (n < N2_BYTES)
        return vfpi_fail(err, errlen, path, 0, "too short for a NIfTI-2 header: %zu bytes (expected at least %d)%s",
                         n, N2_BYTES, after);
    static const unsigned char magic2[8] = {'n', '+', '2', 0, '\r', '\n', 0x1a, '\n'};
    if (memcmp(hdr + N2_MAGIC, "ni2", 4) == 0)
        return vfpi_fail(err, errlen, path, 0, "magic 'ni2' means a .hdr/.img pair, which is not supported "
                         "(expected a single-file .nii, magic 'n+2')");
    if (memcmp(hdr + N2_MAGIC, magic2, 4) != 0)
        return vfpi_fail(err, errlen, path, 0, "bad magic '%.3s' (expected 'n+2', a single-file NIfTI-2)",
                         (const char *)hdr + N2_MAGIC);
    if (memcmp(hdr + N2_MAGIC + 4, magic2 + 4, 4) != 0)
        return vfpi_fail(err, errlen, path, 0, "bad magic: the bytes after 'n+2' are not \\r\\n\\032\\n (was the file "
                         "copied as text?)");
    for (int i = 0; i < 8; i++) {
        h->dim[i] = load_i64(hdr + N2_DIM + 8 * i, big);
        h->pixdim[i] = load_f64(hdr + N2_PIXDIM + 8 * i, big);
    }
    h->datatype = load_i16(hdr + N2_DATATYPE, big);
    int64_t off = load_i64(hdr + N2_VOX_OFFSET, big);
    h->vox_offset = off < 0 ? -1.0 : (double)off;
    h->slope = load_f64(hdr + N2_SCL_SLOPE, big);
    h->inter = load_f64(hdr + N2_SCL_INTER, big);
    h->qform_code = load_i32(hdr + N2_QFORM_CODE, big);
    h->sform_code = load_i32(hdr + N2_SFORM_CODE, big);
    for (int i = 0; i < 3; i++)
        h->quatern[i] = load_f64(hdr + N2_QUATERN + 8 * i, big);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            h->srow[r][c] = load_f64(hdr + N2_SROW + 32 * r + 8 * c, big);
    return VFP_OK;
}

static vfp_status_t parse_header(vfp_volume_t *vol, header_t *h, const char *path, int gzip, uint32_t dims[3],
                                 vf_voxel_t *type, char *err, size_t errlen)
{
    const int64_t *dim = h->dim;
    if (dim[0] == 1 || dim[0] == 2)
        return vfpi_fail(err, errlen, path, 0, "dim[0] = %d: a %dD image, not a volume (expected 3)", (int)dim[0],
                         (int)dim[0]);
    if (dim[0] < 3 || dim[0] > 7)
        return vfpi_fail(err, errlen, path, 0, "bad dim[0] = %lld (expected 3)", (long long)dim[0]);
    /* A 4D..7D file whose extra axes all have size 1 is one 3D volume (dim[0] = 4 with dim[4] = 1 is common). */
    for (int i = 4; i <= dim[0]; i++)
        if (dim[i] != 1)
            return vfpi_fail(err, errlen, path, 0, "dim[0] = %d with dim[%d] = %lld: more than one volume is not "
                             "supported (expected a single 3D volume, dim[%d] = 1)", (int)dim[0], i,
                             (long long)dim[i], i);
    uint64_t d[3];
    for (int a = 0; a < 3; a++) {
        if (dim[a + 1] < 0)
            return vfpi_fail(err, errlen, path, 0, "bad dim[%d] = %lld (expected 2..%d)", a + 1, (long long)dim[a + 1],
                             VF_MAX_DIM);
        d[a] = (uint64_t)dim[a + 1];
    }
    if (vfpi_check_dims(d, path, 0, err, errlen))
        return VFP_ERR;
    for (int a = 0; a < 3; a++)
        dims[a] = (uint32_t)d[a];

    if (!datatype_voxel(h->datatype, type))
        return vfpi_fail(err, errlen, path, 0, "unsupported datatype %d%s (expected uint8, int8, int16 or uint16)",
                         h->datatype, datatype_name(h->datatype));

    /* pixdim: the sign carries no meaning for spacing (qfac lives in pixdim[0]); 0 means the writer did not know
     * the spacing, which several converters write for unknown units: a unit spacing, like nibabel's readers
     * assume. NaN or infinity is damage, not ignorance: an error. */
    for (int a = 0; a < 3; a++) {
        double s = h->pixdim[a + 1];
        if (!isfinite(s))
            return vfpi_fail(err, errlen, path, 0, "bad pixdim[%d] = %g (expected a finite voxel size)", a + 1, s);
        s = fabs(s);
        if (s == 0.0)
            s = 1.0;
        if (vfpi_check_spacing(s, a, path, 0, err, errlen))
            return VFP_ERR;
        vol->spacing[a] = s;
    }

    /* vox_offset below the header's size is read as "right after the header", as nifti1_io.c reads it. */
    double off = h->vox_offset;
    int hdr_bytes = h->version == 1 ? N1_BYTES : N2_BYTES;
    if (!isfinite(off) || off < 0.0 || off != floor(off) || off > 1e15)
        return vfpi_fail(err, errlen, path, 0, "bad vox_offset %g (expected a whole number of bytes, usually %d)",
                         off, hdr_bytes + 4);
    if (off < hdr_bytes)
        off = hdr_bytes;
    if (!gzip) {
        struct stat st;
        if (vfpi_stat(path, &st) == 0 && off > (double)st.st_size)
            return vfpi_fail(err, errlen, path, 0, "vox_offset %.0f is beyond the end of the file (%lld bytes)", off,
                             (long long)st.st_size);
    }
    h->vox_offset = off;

    /* scl_slope 0 means no scaling. A NaN or infinite slope is treated the same way (as nibabel does); the voxels
     * stay raw integers either way and the programs apply slope and intercept to what they show. */
    double slope = h->slope, inter = h->inter;
    if (slope == 0.0 || !isfinite(slope)) {
        slope = 1.0;
        inter = 0.0;
    } else if (!isfinite(inter)) {
        inter = 0.0;
    }
    vol->slope = slope;
    vol->inter = inter;
    return VFP_OK;
}

/* The patient directions of the axes, as nibabel chooses them: the sform when sform_code > 0, else the qform when
 * qform_code > 0, else none (the axes as stored). NIfTI's world is RAS: x and y are negated into LPS. The qform's
 * rotation comes from the quaternion (b, c, d; a = sqrt(1 - b^2 - c^2 - d^2)), its third axis reversed when qfac
 * (pixdim[0]) is -1 (nifti1.h, method 2). */
static vfp_status_t orientation(vfp_volume_t *vol, const header_t *h, const char *path, char *err, size_t errlen)
{
    double axes[3][3];
    const char *from;
    if (h->sform_code > 0) {
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++)
                axes[a][c] = h->srow[c][a];
        from = "sform";
    } else if (h->qform_code > 0) {
        double b = h->quatern[0], c = h->quatern[1], d = h->quatern[2];
        if (!isfinite(b) || !isfinite(c) || !isfinite(d))
            return vfpi_fail(err, errlen, path, 0, "qform: the quaternion (%g, %g, %g) is not finite", b, c, d);
        double aa = 1.0 - (b * b + c * c + d * d);
        double a;
        if (aa < 1e-7) {
            /* nifti1_io.c: a 180-degree rotation; (b, c, d) is renormalised */
            double len = sqrt(b * b + c * c + d * d);
            if (!(len > 0))
                return vfpi_fail(err, errlen, path, 0, "qform: the quaternion is zero");
            b /= len;
            c /= len;
            d /= len;
            a = 0;
        } else {
            a = sqrt(aa);
        }
        const double r[3][3] = {
            {a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
            {2 * (b * c + a * d), a * a + c * c - b * b - d * d, 2 * (c * d - a * b)},
            {2 * (b * d - a * c), 2 * (c * d + a * b), a * a + d * d - c * c - b * b},
        };
        double qfac = h->pixdim[0] < 0 ? -1.0 : 1.0;
        for (int ax = 0; ax < 3; ax++)
            for (int k = 0; k < 3; k++)
                axes[ax][k] = r[k][ax] * (ax == 2 ? qfac : 1.0);
        from = "qform";
    } else {
        return VFP_OK;
    }
    for (int a = 0; a < 3; a++) {
        axes[a][0] = -axes[a][0];
        axes[a][1] = -axes[a][1];
    }
    return vfpi_set_direction(vol, axes, from, path, 0, err, errlen);
}

static int datatype_voxel(int datatype, vf_voxel_t *type)
{
    switch (datatype) {
    case 2:
        *type = VF_VOXEL_U8;
        return 1;
    case 4:
        *type = VF_VOXEL_I16;
        return 1;
    case 256:
        *type = VF_VOXEL_I8;
        return 1;
    case 512:
        *type = VF_VOXEL_U16;
        return 1;
    default:
        return 0;
    }
}

/* " (float32)" for the message about an unsupported datatype; "" for a code NIfTI-1 does not define. */
static const char *datatype_name(int datatype)
{
    switch (datatype) {
    case 1: return " (binary)";
    case 8: return " (int32)";
    case 16: return " (float32)";
    case 32: return " (complex64)";
    case 64: return " (float64)";
    case 128: return " (rgb24)";
    case 768: return " (uint32)";
    case 1024: return " (int64)";
    case 1280: return " (uint64)";
    case 1536: return " (float128)";
    case 1792: return " (complex128)";
    case 2048: return " (complex256)";
    case 2304: return " (rgba32)";
    default: return "";
    }
}

static int16_t load_i16(const unsigned char *p, int big)
{
    uint16_t u = vfpi_load16(p, big);
    int16_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static int32_t load_i32(const unsigned char *p, int big)
{
    uint32_t u = vfpi_load32(p, big);
    int32_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static uint64_t load_u64(const unsigned char *p, int big)
{
    uint64_t lo = vfpi_load32(p + (big ? 4 : 0), big), hi = vfpi_load32(p + (big ? 0 : 4), big);
    return hi << 32 | lo;
}

static int64_t load_i64(const unsigned char *p, int big)
{
    uint64_t u = load_u64(p, big);
    int64_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

static double load_f64(const unsigned char *p, int big)
{
    uint64_t u = load_u64(p, big);
    double f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static float load_f32(const unsigned char *p, int big)
{
    uint32_t u = vfpi_load32(p, big);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}
