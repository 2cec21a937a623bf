/* nifti.c: the NIfTI-1 reader (single-file .nii and .nii.gz, either byte order, 8- and 16-bit integer voxels). */

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
/* Byte offsets of the NIfTI-1 header fields this reader uses (nifti1.h, struct nifti_1_header). */
#define HDR_BYTES 348
#define OFF_DIM 40        /* int16 dim[8] */
#define OFF_DATATYPE 70   /* int16 */
#define OFF_PIXDIM 76     /* float pixdim[8] */
#define OFF_VOX_OFFSET 108 /* float */
#define OFF_SCL_SLOPE 112 /* float */
#define OFF_SCL_INTER 116 /* float */
#define OFF_MAGIC 344     /* char magic[4] */
#define NIFTI2_BYTES 540  /* sizeof_hdr of NIfTI-2, whose magic "n+2" is at byte 4 */

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t parse_header(vfp_volume_t *vol, const unsigned char *hdr, int big, const char *path, int gzip,
                                 uint32_t dims[3], vf_voxel_t *type, double *vox_offset, char *err, size_t errlen);
static int datatype_voxel(int datatype, vf_voxel_t *type);
static const char *datatype_name(int datatype);
static int16_t load_i16(const unsigned char *p, int big);
static float load_f32(const unsigned char *p, int big);

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

int vfpi_is_nifti(const unsigned char *head, size_t n)
{
    if (n >= HDR_BYTES && (vfpi_load32(head, 0) == HDR_BYTES || vfpi_load32(head, 1) == HDR_BYTES) &&
        (memcmp(head + OFF_MAGIC, "n+1", 4) == 0 || memcmp(head + OFF_MAGIC, "ni1", 4) == 0))
        return 1;
    /* NIfTI-2 is recognised only to say that it is not supported. */
    return n >= 8 && (vfpi_load32(head, 0) == NIFTI2_BYTES || vfpi_load32(head, 1) == NIFTI2_BYTES) &&
           memcmp(head + 4, "n+2", 4) == 0;
}

vfp_status_t vfpi_load_nifti(vfp_volume_t *vol, const char *path, int gzip, char *err, size_t errlen)
{
    unsigned char hdr[VFPI_HEAD_BYTES];
    size_t n;
    if (vfpi_read_head(path, gzip, hdr, sizeof hdr, &n, err, errlen))
        return VFP_ERR;
    if (n >= 8 && (vfpi_load32(hdr, 0) == NIFTI2_BYTES || vfpi_load32(hdr, 1) == NIFTI2_BYTES))
        return vfpi_fail(err, errlen, path, 0, "NIfTI-2 is not supported (expected NIfTI-1, sizeof_hdr 348)");
    if (n < HDR_BYTES)
        return vfpi_fail(err, errlen, path, 0, "too short for a NIfTI-1 header: %zu bytes (expected at least %d)%s",
                         n, HDR_BYTES, gzip ? " after decompression" : "");
    /* The byte order of the whole file is the one in which sizeof_hdr reads 348. */
    int big;
    if (vfpi_load32(hdr, 0) == HDR_BYTES)
        big = 0;
    else if (vfpi_load32(hdr, 1) == HDR_BYTES)
        big = 1;
    else
        return vfpi_fail(err, errlen, path, 0, "bad sizeof_hdr %ld (expected 348 for NIfTI-1, in either byte order)",
                         (long)(int32_t)vfpi_load32(hdr, 0));
    if (memcmp(hdr + OFF_MAGIC, "ni1", 4) == 0)
        return vfpi_fail(err, errlen, path, 0, "magic 'ni1' means a .hdr/.img pair, which is not supported "
                         "(expected a single-file .nii, magic 'n+1')");
    if (memcmp(hdr + OFF_MAGIC, "n+1", 4) != 0)
        return vfpi_fail(err, errlen, path, 0, "bad magic '%.3s' (expected 'n+1', a single-file NIfTI-1)",
                         (const char *)hdr + OFF_MAGIC);

    uint32_t dims[3];
    vf_voxel_t type = VF_VOXEL_U8;
    double vox_offset = 0.0;
    if (parse_header(vol, hdr, big, path, gzip, dims, &type, &vox_offset, err, errlen))
        return VFP_ERR;
    vfpi_source_t src = {.path = path, .byte_skip = (int64_t)vox_offset, .gzip = gzip};
    size_t bytes;
    if (vfpi_read_voxels(vol, dims, type, &src, &bytes, err, errlen))
        return VFP_ERR;
    if (vfpi_type_bytes(type) == 2)
        vfpi_to_native16(vol->data, bytes / 2, big);
    return VFP_OK;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

static vfp_status_t parse_header(vfp_volume_t *vol, const unsigned char *hdr, int big, const char *path, int gzip,
                                 uint32_t dims[3], vf_voxel_t *type, double *vox_offset, char *err, size_t errlen)
{
    int dim[8];
    for (int i = 0; i < 8; i++)
        dim[i] = load_i16(hdr + OFF_DIM + 2 * i, big);
    if (dim[0] == 1 || dim[0] == 2)
        return vfpi_fail(err, errlen, path, 0, "dim[0] = %d: a %dD image, not a volume (expected 3)", dim[0], dim[0]);
    if (dim[0] < 3 || dim[0] > 7)
        return vfpi_fail(err, errlen, path, 0, "bad dim[0] = %d (expected 3)", dim[0]);
    /* A 4D..7D file whose extra axes all have size 1 is one 3D volume (dim[0] = 4 with dim[4] = 1 is common). */
    for (int i = 4; i <= dim[0]; i++)
        if (dim[i] != 1)
            return vfpi_fail(err, errlen, path, 0, "dim[0] = %d with dim[%d] = %d: more than one volume is not "
                             "supported (expected a single 3D volume, dim[%d] = 1)", dim[0], i, dim[i], i);
    uint64_t d[3];
    for (int a = 0; a < 3; a++) {
        if (dim[a + 1] < 0)
            return vfpi_fail(err, errlen, path, 0, "bad dim[%d] = %d (expected 2..%d)", a + 1, dim[a + 1], VF_MAX_DIM);
        d[a] = (uint64_t)dim[a + 1];
    }
    if (vfpi_check_dims(d, path, 0, err, errlen))
        return VFP_ERR;
    for (int a = 0; a < 3; a++)
        dims[a] = (uint32_t)d[a];

    int datatype = load_i16(hdr + OFF_DATATYPE, big);
    if (!datatype_voxel(datatype, type))
        return vfpi_fail(err, errlen, path, 0, "unsupported datatype %d%s (expected uint8, int8, int16 or uint16)",
                         datatype, datatype_name(datatype));

    /* pixdim: the sign carries no meaning for spacing (qfac lives in pixdim[0]); 0 means the writer did not know
     * the spacing, which several converters write for unknown units: a unit spacing, like nibabel's readers
     * assume. NaN or infinity is damage, not ignorance: an error. */
    for (int a = 0; a < 3; a++) {
        double s = load_f32(hdr + OFF_PIXDIM + 4 * (a + 1), big);
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
    double off = load_f32(hdr + OFF_VOX_OFFSET, big);
    if (!isfinite(off) || off < 0.0 || off != floor(off) || off > 1e15)
        return vfpi_fail(err, errlen, path, 0, "bad vox_offset %g (expected a whole number of bytes, usually 352)",
                         off);
    if (off < HDR_BYTES)
        off = HDR_BYTES;
    if (!gzip) {
        struct stat st;
        if (vfpi_stat(path, &st) == 0 && off > (double)st.st_size)
            return vfpi_fail(err, errlen, path, 0, "vox_offset %.0f is beyond the end of the file (%lld bytes)", off,
                             (long long)st.st_size);
    }
    *vox_offset = off;

    /* NIfTI-1: scl_slope 0 means no scaling. A NaN or infinite slope is treated the same way (as nibabel does);
     * the voxels stay raw integers either way and the programs apply slope and intercept to what they show. */
    double slope = load_f32(hdr + OFF_SCL_SLOPE, big), inter = load_f32(hdr + OFF_SCL_INTER, big);
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

static float load_f32(const unsigned char *p, int big)
{
    uint32_t u = vfpi_load32(p, big);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}
