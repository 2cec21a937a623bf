/* SPDX-License-Identifier: MIT */
/* test_volume_formats.c: NIfTI-1, VolPack .den, raw and phantom volumes, windows, and the option parsers. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/volume.h"
#include "volume_fixtures.h"

/* A NIfTI-1 header's fields, written in either byte order by nii_header. */
typedef struct nii {
    int big;
    int32_t sizeof_hdr;
    int16_t dim[8];
    int16_t datatype;
    float pixdim[4];
    float vox_offset, slope, inter;
    const char *magic; /* 4 bytes with the NUL */
} nii_t;

/* ---------------------------------------------------------------------------------------------------------- */
/* Helpers */

static void put16(unsigned char *p, uint16_t v, int big)
{
    p[big ? 0 : 1] = (unsigned char)(v >> 8);
    p[big ? 1 : 0] = (unsigned char)v;
}

static void put32(unsigned char *p, uint32_t v, int big)
{
    for (int i = 0; i < 4; i++)
        p[big ? 3 - i : i] = (unsigned char)(v >> (8 * i));
}

static void putf(unsigned char *p, float f, int big)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    put32(p, u, big);
}

/* The fixture as a 3x4x5 NIfTI-1 of the given type. */
static nii_t nii_fixture(vf_voxel_t type, int big)
{
    nii_t h = {.big = big, .sizeof_hdr = 348, .dim = {3, FX_X, FX_Y, FX_Z, 1, 1, 1, 1}, .pixdim = {1, 1, 1, 1},
               .vox_offset = 352, .slope = 0, .inter = 0, .magic = "n+1"};
    h.datatype = type == VF_VOXEL_U8 ? 2 : type == VF_VOXEL_I8 ? 256 : type == VF_VOXEL_I16 ? 4 : 512;
    return h;
}

/* Header, zero padding up to vox_offset, then the fixture's data (data_bytes of it, or all when < 0). */
static size_t nii_file(const nii_t *h, vf_voxel_t type, long data_bytes, unsigned char *out)
{
    size_t off = h->vox_offset > 352 && h->vox_offset < 4096 ? (size_t)h->vox_offset : 352;
    memset(out, 0, off);
    put32(out, (uint32_t)h->sizeof_hdr, h->big);
    for (int i = 0; i < 8; i++)
        put16(out + 40 + 2 * i, (uint16_t)h->dim[i], h->big);
    put16(out + 70, (uint16_t)h->datatype, h->big);
    for (int i = 0; i < 4; i++)
        putf(out + 76 + 4 * i, h->pixdim[i], h->big);
    putf(out + 108, h->vox_offset, h->big);
    putf(out + 112, h->slope, h->big);
    putf(out + 116, h->inter, h->big);
    memcpy(out + 344, h->magic, 4);
    size_t n = fx_bytes(type, h->big, out + off);
    return off + (data_bytes < 0 ? n : (size_t)data_bytes);
}

static const char *nii_write(const char *name, const nii_t *h, vf_voxel_t type, long data_bytes)
{
    unsigned char buf[8192];
    size_t n = nii_file(h, type, data_bytes, buf);
    size_t len = strlen(name);
    if (len > 3 && strcmp(name + len - 3, ".gz") == 0)
        return fx_write_gz(name, buf, n);
    return fx_write(name, NULL, buf, n);
}

/* A VolPack .den header for dims (x fastest), version and map_length as given. */
static size_t den_file(unsigned version, const uint16_t dims[3], uint32_t map_length, const unsigned char *data,
                       size_t n, unsigned char *out)
{
    memset(out, 0, 62);
    put16(out, (uint16_t)version, 0);
    for (int a = 0; a < 3; a++) {
        put16(out + 8 + 2 * a, (uint16_t)(dims[a] - 1), 0); /* orig_max */
        put16(out + 14 + 2 * a, dims[a], 0);                /* orig_len */
        put16(out + 32 + 2 * a, dims[a], 0);                /* extr_len */
        put16(out + 44 + 2 * a, (uint16_t)(dims[a] - 1), 0); /* map_max */
        put16(out + 50 + 2 * a, dims[a], 0);                /* map_len */
    }
    put32(out + 58, map_length, 0);
    memcpy(out + 62, data, n);
    return 62 + n;
}

/* ---------------------------------------------------------------------------------------------------------- */
/* NIfTI-1 */

static void nifti_int16_little_with_scaling(void)
{
    nii_t h = nii_fixture(VF_VOXEL_I16, 0);
    h.pixdim[1] = 0.5f;
    h.pixdim[2] = -2.0f; /* the sign of a pixdim is not the spacing's */
    h.pixdim[3] = 0.0f;  /* unknown: unit spacing */
    h.slope = 2.0f;
    h.inter = -10.0f;
    const char *p = nii_write("le16.nii", &h, VF_VOXEL_I16, -1);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK(strcmp(vol.format, "nifti") == 0);
    CHECK_NEAR(vol.spacing[0], 0.5, 0);
    CHECK_NEAR(vol.spacing[1], 2.0, 0);
    CHECK_NEAR(vol.spacing[2], 1.0, 0);
    CHECK_EQ(vol.core.spacing_q16[1], 262144); /* relative to the smallest, 0.5 */
    CHECK_NEAR(vol.slope, 2.0, 0);
    CHECK_NEAR(vol.inter, -10.0, 0);
    /* One unit: the default window in data units, given back as --window, is the same raw window. */
    vf_window_t w = vfp_default_window(&vol), back;
    double lo, hi;
    vfp_window_data(&vol, w, &lo, &hi);
    CHECK_NEAR(lo, w.lo * 2.0 - 10.0, 0);
    CHECK_NEAR(hi, w.hi * 2.0 - 10.0, 0);
    char text[64], err[VFP_ERR_LEN];
    snprintf(text, sizeof text, "%.10g,%.10g", lo, hi);
    CHECK_MSG(vfp_parse_window(&vol, text, &back, err, sizeof err) == VFP_OK, "%s", err);
    CHECK_EQ(back.lo, w.lo);
    CHECK_EQ(back.hi, w.hi);
    fx_check_fixture(&vol, VF_VOXEL_I16);
}

static void nifti_uint16_big(void)
{
    nii_t h = nii_fixture(VF_VOXEL_U16, 1);
    const char *p = nii_write("be16.nii", &h, VF_VOXEL_U16, -1);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK_NEAR(vol.slope, 1.0, 0); /* scl_slope 0: no scaling */
    CHECK_NEAR(vol.inter, 0.0, 0);
    fx_check_fixture(&vol, VF_VOXEL_U16);
}

static void nifti_gzip_uint8_4d(void)
{
    nii_t h = nii_fixture(VF_VOXEL_U8, 0);
    h.dim[0] = 4; /* a 4D file with one volume is a 3D volume */
    const char *p = nii_write("u8.nii.gz", &h, VF_VOXEL_U8, -1);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void nifti_int8_with_extension_bytes(void)
{
    nii_t h = nii_fixture(VF_VOXEL_I8, 1);
    h.vox_offset = 400; /* extensions between header and data */
    const char *p = nii_write("i8.nii", &h, VF_VOXEL_I8, -1);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_I8);
    p = nii_write("i8.nii.gz", &h, VF_VOXEL_I8, -1);
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_I8);
}

static void nifti_recognised_by_content(void)
{
    nii_t h = nii_fixture(VF_VOXEL_U8, 0);
    const char *p = nii_write("nifti.vol", &h, VF_VOXEL_U8, -1);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK(strcmp(vol.format, "nifti") == 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
    unsigned char buf[1024];
    size_t n = nii_file(&h, VF_VOXEL_U8, -1, buf);
    p = fx_write_gz("nifti-gz.bin", buf, n);
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK(strcmp(vol.format, "nifti") == 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void nifti_errors(void)
{
    nii_t h = nii_fixture(VF_VOXEL_U8, 0);
    h.sizeof_hdr = 350;
    const char *p = nii_write("size.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": bad sizeof_hdr 350 (expected 348 for NIfTI-1");

    h = nii_fixture(VF_VOXEL_U8, 0);
    h.magic = "abc";
    p = nii_write("magic.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": bad magic 'abc' (expected 'n+1'");
    h.magic = "ni1";
    p = nii_write("pair.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": magic 'ni1' means a .hdr/.img pair, which is not supported");

    h = nii_fixture(VF_VOXEL_U8, 0);
    h.datatype = 16;
    p = nii_write("float.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": unsupported datatype 16 (float32) (expected uint8, int8, int16 or uint16)");
    h.datatype = 99;
    p = nii_write("dt99.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": unsupported datatype 99 (expected uint8, int8, int16 or uint16)");

    h = nii_fixture(VF_VOXEL_U8, 1);
    h.dim[0] = 2;
    p = nii_write("2d.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": dim[0] = 2: a 2D image, not a volume (expected 3)");
    h.dim[0] = 4;
    h.dim[4] = 3;
    p = nii_write("4d.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": dim[0] = 4 with dim[4] = 3: more than one volume is not supported");
    h.dim[0] = 9;
    p = nii_write("9d.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": bad dim[0] = 9 (expected 3)");
    h = nii_fixture(VF_VOXEL_U8, 0);
    h.dim[2] = 1;
    p = nii_write("thin.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": size 1 along y is out of range (expected 2..4096; a volume 1 voxel thick");
    h.dim[2] = -4;
    p = nii_write("neg.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": bad dim[2] = -4");

    h = nii_fixture(VF_VOXEL_U8, 0);
    h.pixdim[3] = NAN;
    p = nii_write("nan.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": bad pixdim[3] = nan (expected a finite voxel size)");
    h.pixdim[3] = 1e6f;
    p = nii_write("big.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": bad spacing 1e+06 along z");

    h = nii_fixture(VF_VOXEL_U8, 0);
    h.vox_offset = 5000;
    p = nii_write("beyond.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": vox_offset 5000 is beyond the end of the file (412 bytes)");
    p = nii_write("beyond.nii.gz", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": truncated: the data should start at byte 5000 after decompression, but there are "
                                "only 412 bytes");
    h.vox_offset = 352.5f;
    p = nii_write("half.nii", &h, VF_VOXEL_U8, -1);
    fx_expect_error(p, NULL, p, ": bad vox_offset 352.5 (expected a whole number of bytes");

    h = nii_fixture(VF_VOXEL_U16, 0);
    p = nii_write("short.nii", &h, VF_VOXEL_U16, 100);
    fx_expect_error(p, NULL, p, ": truncated: expected 120 bytes of voxel data, found 100");
    p = nii_write("long.nii", &h, VF_VOXEL_U16, 121);
    fx_expect_error(p, NULL, p, ": expected 120 bytes of voxel data, found 121");
    p = nii_write("short.nii.gz", &h, VF_VOXEL_U16, 100);
    fx_expect_error(p, NULL, p, ": truncated: expected 120 bytes of voxel data after decompression, found 100");

    unsigned char tiny[100] = {0x5c, 0x01};
    p = fx_write("tiny.nii", NULL, tiny, sizeof tiny);
    fx_expect_error(p, NULL, p, ": too short for a NIfTI-1 header: 100 bytes (expected at least 348)");
    unsigned char two[600] = {0x1c, 0x02, 0, 0, 'n', '+', '2', 0}; /* NIfTI-2 whose magic lost its \r\n\032\n */
    p = fx_write("two.nii", NULL, two, sizeof two);
    fx_expect_error(p, NULL, p, ": bad magic: the bytes after 'n+2' are not \\r\\n\\032\\n");
    p = fx_write("two-short.nii", NULL, two, 400);
    fx_expect_error(p, NULL, p, ": too short for a NIfTI-2 header: 400 bytes (expected at least 540)");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* VolPack .den */

static void den_good(void)
{
    unsigned char data[FX_COUNT], file[62 + FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    const uint16_t dims[3] = {FX_X, FX_Y, FX_Z};
    size_t n = den_file(1, dims, FX_COUNT, data, sizeof data, file);
    const char *p = fx_write("a.den", NULL, file, n);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK(strcmp(vol.format, "den") == 0);
    CHECK_NEAR(vol.spacing[2], 1.0, 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
    /* Recognised by content too: a valid header whose map_length matches the file's size. */
    p = fx_write("den.vol", NULL, file, n);
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK(strcmp(vol.format, "den") == 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void den_errors(void)
{
    unsigned char data[FX_COUNT + 1], file[64 + FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    const uint16_t dims[3] = {FX_X, FX_Y, FX_Z};
    size_t n = den_file(2, dims, FX_COUNT, data, FX_COUNT, file);
    const char *p = fx_write("v2.den", NULL, file, n);
    fx_expect_error(p, NULL, p, ": unsupported .den version 2 (expected 1)");
    n = den_file(256, dims, FX_COUNT, data, FX_COUNT, file);
    p = fx_write("swapped.den", NULL, file, n);
    fx_expect_error(p, NULL, p, "looks byte-swapped");
    n = den_file(1, dims, FX_COUNT + 1, data, FX_COUNT, file);
    p = fx_write("len.den", NULL, file, n);
    fx_expect_error(p, NULL, p, ": map_length 61 does not match map_len 3 x 4 x 5 = 60");
    n = den_file(1, dims, FX_COUNT, data, FX_COUNT - 10, file);
    p = fx_write("cut.den", NULL, file, n);
    fx_expect_error(p, NULL, p, ": truncated: expected 60 bytes of voxel data, found 50");
    n = den_file(1, dims, FX_COUNT, data, FX_COUNT + 1, file);
    p = fx_write("long.den", NULL, file, n);
    fx_expect_error(p, NULL, p, ": expected 60 bytes of voxel data, found 61");
    const uint16_t thin[3] = {FX_X, 1, FX_Z};
    n = den_file(1, thin, FX_X * FX_Z, data, FX_X * FX_Z, file);
    p = fx_write("thin.den", NULL, file, n);
    fx_expect_error(p, NULL, p, ": size 1 along y is out of range");
    p = fx_write("tiny.den", NULL, file, 20);
    fx_expect_error(p, NULL, p, ": too short for a VolPack .den header: 20 bytes (expected at least 62)");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Raw */

static void raw_good(void)
{
    unsigned char data[FX_COUNT * 2];
    size_t n = fx_bytes(VF_VOXEL_I16, 1, data);
    const char *p = fx_write("be.raw", NULL, data, n);
    vfp_load_opts_t opts = {.have_dims = 1, .dims = {FX_X, FX_Y, FX_Z}, .have_type = 1, .type = VF_VOXEL_I16,
                            .big_endian = 1, .have_spacing = 1, .spacing = {1, 2, 3}};
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, &opts), 0);
    CHECK(strcmp(vol.format, "raw") == 0);
    CHECK_NEAR(vol.spacing[2], 3.0, 0);
    CHECK_EQ(vol.core.spacing_q16[1], 131072); /* relative to the smallest, 1 */
    fx_check_fixture(&vol, VF_VOXEL_I16);

    n = fx_bytes(VF_VOXEL_U16, 0, data);
    p = fx_write_gz("le.raw.gz", data, n);
    opts = (vfp_load_opts_t){.have_dims = 1, .dims = {FX_X, FX_Y, FX_Z}, .have_type = 1, .type = VF_VOXEL_U16};
    CHECK_EQ(fx_load(&vol, p, &opts), 0);
    CHECK_NEAR(vol.spacing[0], 1.0, 0);
    fx_check_fixture(&vol, VF_VOXEL_U16);

    n = fx_bytes(VF_VOXEL_I8, 0, data);
    p = fx_write("i8.dat", NULL, data, n);
    opts.type = VF_VOXEL_I8;
    CHECK_EQ(fx_load(&vol, p, &opts), 0);
    fx_check_fixture(&vol, VF_VOXEL_I8);
}

static void raw_errors(void)
{
    unsigned char data[FX_COUNT * 2 + 1];
    memset(data, 1, sizeof data);
    const char *p = fx_write("x.raw", NULL, data, FX_COUNT);
    fx_expect_error(p, NULL, p, ": raw data needs --dims X,Y,Z and --type uint8|int8|uint16|int16");
    vfp_load_opts_t opts = {.have_dims = 1, .dims = {FX_X, FX_Y, FX_Z}};
    fx_expect_error(p, &opts, p, ": raw data needs --dims X,Y,Z and --type uint8|int8|uint16|int16 (--type is "
                                 "missing)");
    opts = (vfp_load_opts_t){.have_type = 1, .type = VF_VOXEL_U8};
    fx_expect_error(p, &opts, p, "(--dims is missing)");

    opts = (vfp_load_opts_t){.have_dims = 1, .dims = {FX_X, FX_Y, FX_Z}, .have_type = 1, .type = VF_VOXEL_U16};
    fx_expect_error(p, &opts, p, ": truncated: expected 120 bytes of voxel data, found 60 (for --dims 3,4,5 --type "
                                 "uint16)");
    p = fx_write("long.raw", NULL, data, FX_COUNT * 2 + 1);
    fx_expect_error(p, &opts, p, ": expected 120 bytes of voxel data, found 121 (for --dims 3,4,5 --type uint16)");
    p = fx_write_gz("short.raw.gz", data, FX_COUNT);
    fx_expect_error(p, &opts, p, ": truncated: expected 120 bytes of voxel data after decompression, found 60");
    p = fx_write("notgz.raw.gz", NULL, data, FX_COUNT * 2);
    fx_expect_error(p, &opts, p, ": gzip error: incorrect header check");
    opts.dims[2] = 1;
    fx_expect_error(p, &opts, p, ": --dims: size 1 along z is out of range");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Headers that claim more than the file holds (found by tests/fuzz): the size is checked against the file before
 * the voxels are allocated, and a gzip'd file's buffer grows with what it decompresses to, so a few bytes that
 * claim 128 GiB get the usual one-line "truncated" error, not an attempt to allocate it (which failed with "out
 * of memory", or aborted under the sanitizers). */

static void huge_claims_without_data(void)
{
    nii_t h = nii_fixture(VF_VOXEL_I16, 0);
    h.dim[1] = h.dim[2] = h.dim[3] = VF_MAX_DIM;
    const char *p = nii_write("huge.nii", &h, VF_VOXEL_I16, 100);
    fx_expect_error(p, NULL, p, FX_HUGE(": truncated: expected 137438953472 bytes of voxel data, found 100"));
    p = nii_write("huge.nii.gz", &h, VF_VOXEL_I16, 100);
    fx_expect_error(p, NULL, p,
                    FX_HUGE(": truncated: expected 137438953472 bytes of voxel data after decompression, found 100"));

    /* .den: map_length is 32 bits, so 1024^3 is about the most one can claim. */
    unsigned char data[FX_COUNT * 2], file[62 + FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    const uint16_t dims[3] = {1024, 1024, 1024};
    size_t n = den_file(1, dims, 1u << 30, data, FX_COUNT, file);
    p = fx_write("huge.den", NULL, file, n);
    fx_expect_error(p, NULL, p, ": truncated: expected 1073741824 bytes of voxel data, found 60");

    vfp_load_opts_t opts = {.have_dims = 1, .dims = {VF_MAX_DIM, VF_MAX_DIM, VF_MAX_DIM}, .have_type = 1,
                            .type = VF_VOXEL_U16};
    n = fx_bytes(VF_VOXEL_U16, 0, data);
    p = fx_write("huge.raw", NULL, data, n);
    fx_expect_error(p, &opts, p,
                    FX_HUGE(": truncated: expected 137438953472 bytes of voxel data, found 120 (for --dims "
                            "4096,4096,4096 --type uint16)"));
    p = fx_write_gz("huge.raw.gz", data, n);
    fx_expect_error(p, &opts, p,
                    FX_HUGE(": truncated: expected 137438953472 bytes of voxel data after decompression, found 120"));
}

/* More than the first buffer of gzip'd voxels (1 MiB): it grows as the data comes and holds every byte; one byte
 * fewer or more is still an error that says how many there are. */
static void gzip_larger_than_first_buffer(void)
{
    enum { X = 128, Y = 128, Z = 40 }; /* 1.25 MiB of uint16 */
    size_t bytes = (size_t)X * Y * Z * 2;
    unsigned char *data = malloc(bytes + 1);
    CHECK(data != NULL);
    for (size_t i = 0; i <= bytes; i++)
        data[i] = (unsigned char)(i * 7919u >> 3);
    vfp_load_opts_t opts = {.have_dims = 1, .dims = {X, Y, Z}, .have_type = 1, .type = VF_VOXEL_U16};
    const char *p = fx_write_gz("big.raw.gz", data, bytes), *shorter = fx_write_gz("big-1.raw.gz", data, bytes - 1),
               *longer = fx_write_gz("big+1.raw.gz", data, bytes + 1);
    vfp_volume_t vol;
    int rc = fx_load(&vol, p, &opts);
    int same = rc == 0 && memcmp(vol.data, data, bytes) == 0;
    free(data);
    CHECK_EQ(rc, 0);
    vfp_volume_free(&vol);
    CHECK(same);
    fx_expect_error(shorter, &opts, shorter, ": truncated: expected 1310720 bytes of voxel data after decompression, "
                                             "found 1310719");
    fx_expect_error(longer, &opts, longer, ": expected 1310720 bytes of voxel data after decompression, found at least 1310721");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Phantoms */

static uint8_t at(const vfp_volume_t *vol, uint32_t i, uint32_t j, uint32_t k)
{
    const uint8_t *v = vol->core.voxels;
    return v[((size_t)k * vol->core.dims[1] + j) * vol->core.dims[0] + i];
}

static void phantom_marschner_lobb(void)
{
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, "phantom:marschner-lobb:41", NULL), 0);
    CHECK(strcmp(vol.format, "phantom") == 0);
    CHECK(strcmp(vol.name, "phantom:marschner-lobb:41") == 0);
    CHECK_EQ(vol.core.dims[0], 41);
    CHECK_EQ(vol.core.dims[2], 41);
    CHECK_EQ(vol.core.type, VF_VOXEL_U8);
    CHECK_EQ(vol.core.spacing_q16[0], 65536);
    /* At the origin: (1 - sin 0 + 0.25 (1 + cos(12 pi))) / 2.5 = 0.6, so 153. */
    CHECK_EQ(at(&vol, 20, 20, 20), 153);
    /* At z = 1 the z term vanishes; at x = y = 0, rho_r = 1: (0 + 0.5) / 2.5 = 0.2, so 51. */
    CHECK_EQ(at(&vol, 20, 20, 40), 51);
    /* At z = -1 the z term is 2: (2 + 0.25 (1 + rho_r)) / 2.5, with rho_r(1) = cos(12 pi cos(pi/2)) = 1 at
     * (x, y) = (1, 0): 1.0, so 255. */
    CHECK_EQ(at(&vol, 40, 20, 0), 255);
    /* Rotational symmetry about z. */
    CHECK_EQ(at(&vol, 5, 12, 7), at(&vol, 12, 5, 7));
    CHECK_EQ(at(&vol, 5, 12, 7), at(&vol, 35, 28, 7));
    vfp_volume_free(&vol);
}

static void phantom_shepp_logan(void)
{
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, "phantom:shepp-logan:41", NULL), 0);
    CHECK_EQ(at(&vol, 20, 20, 20), 51);  /* brain: 1 - 0.8 */
    CHECK_EQ(at(&vol, 20, 38, 20), 255); /* skull at y = 0.9: inside the outer ellipsoid only */
    CHECK_EQ(at(&vol, 0, 0, 0), 0);      /* outside the head */
    CHECK_EQ(at(&vol, 20, 20, 0), 0);
    /* The left ventricle (-0.2 on brain, centre (-0.22, 0, 0)): 0. */
    CHECK_EQ(at(&vol, 16, 20, 20), 0);
    /* The ellipsoid at (0, 0.35, -0.15): brain + 0.1 = 0.3, 76.5 in 0..255 (either side of the rounding). */
    CHECK(at(&vol, 20, 27, 17) == 76 || at(&vol, 20, 27, 17) == 77);
    vfp_volume_free(&vol);
}

static void phantom_sphere(void)
{
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, "phantom:sphere:17", NULL), 0);
    /* Centre 8, radius 7.65: 255 at the centre, falling linearly, 0 outside. */
    CHECK_EQ(at(&vol, 8, 8, 8), 255);
    CHECK_EQ(at(&vol, 12, 8, 8), (int)nearbyint(255.0 * (1.0 - 4.0 / 7.65)));
    CHECK_EQ(at(&vol, 8, 8, 16), 0);
    CHECK_EQ(at(&vol, 0, 0, 0), 0);
    CHECK_EQ(at(&vol, 3, 5, 9), at(&vol, 9, 3, 5));
    CHECK_EQ(vol.raw_max, 255);
    CHECK_EQ(vol.raw_min, 0);
    vfp_volume_free(&vol);
    CHECK_EQ(fx_load(&vol, "phantom:sphere:2", NULL), 0);
    vfp_volume_free(&vol);
}

static void phantom_errors(void)
{
    fx_expect_error("phantom:foo:64", NULL, "phantom:foo:64",
                    ": unknown phantom 'foo' (expected marschner-lobb, shepp-logan, sphere or cube)");
    fx_expect_error("phantom:sphere", NULL, "phantom:sphere", ": expected phantom:NAME:N");
    fx_expect_error("phantom:", NULL, "phantom:", ": expected phantom:NAME:N");
    fx_expect_error("phantom:sphere:1", NULL, "phantom:sphere:1", ": size 1 is out of range (expected 2..1024)");
    fx_expect_error("phantom:sphere:1025", NULL, "phantom:sphere:1025", ": size 1025 is out of range");
    fx_expect_error("phantom:sphere:99999999999999", NULL, "phantom:sphere:", "is out of range");
    fx_expect_error("phantom:sphere:abc", NULL, "phantom:sphere:abc", ": bad size 'abc' (expected a whole number");
    fx_expect_error("phantom:sphere:-4", NULL, "phantom:sphere:-4", ": bad size '-4'");
    fx_expect_error("phantom:sphere:", NULL, "phantom:sphere:", ": bad size ''");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Windows */

/* A 10x10x10 volume of the given 16-bit type from values[]. */
static const char *raw16(const char *name, vf_voxel_t type, const int32_t *values, vfp_load_opts_t *opts)
{
    uint16_t data[1000];
    for (int i = 0; i < 1000; i++)
        data[i] = (uint16_t)values[i];
    *opts = (vfp_load_opts_t){.have_dims = 1, .dims = {10, 10, 10}, .have_type = 1, .type = type};
    const uint16_t probe = 1;
    opts->big_endian = *(const unsigned char *)&probe == 0;
    return fx_write(name, NULL, data, sizeof data);
}

static void window_default(void)
{
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, "phantom:sphere:8", NULL), 0);
    vf_window_t w = vfp_default_window(&vol);
    CHECK_EQ(w.lo, 0);
    CHECK_EQ(w.hi, 255);
    vfp_volume_free(&vol);

    unsigned char data[FX_COUNT];
    fx_bytes(VF_VOXEL_I8, 0, data);
    vfp_load_opts_t opts = {.have_dims = 1, .dims = {FX_X, FX_Y, FX_Z}, .have_type = 1, .type = VF_VOXEL_I8};
    CHECK_EQ(fx_load(&vol, fx_write("i8w.raw", NULL, data, sizeof data), &opts), 0);
    w = vfp_default_window(&vol);
    CHECK_EQ(w.lo, -128);
    CHECK_EQ(w.hi, 127);
    vfp_volume_free(&vol);

    /* 0..999 in a scrambled order: the 0.5 percentile is 4, the 99.99 percentile 999 (within twice the 99.5
     * percentile's 995 from lo, so it is the top). */
    int32_t values[1000];
    for (int i = 0; i < 1000; i++)
        values[i] = (i * 7919) % 1000;
    CHECK_EQ(fx_load(&vol, raw16("u16w.raw", VF_VOXEL_U16, values, &opts), &opts), 0);
    w = vfp_default_window(&vol);
    CHECK_EQ(w.lo, 4);
    CHECK_EQ(w.hi, 999);
    vfp_volume_free(&vol);
    for (int i = 0; i < 1000; i++)
        values[i] = (i * 7919) % 1000 - 2000;
    CHECK_EQ(fx_load(&vol, raw16("i16w.raw", VF_VOXEL_I16, values, &opts), &opts), 0);
    w = vfp_default_window(&vol);
    CHECK_EQ(w.lo, -1996);
    CHECK_EQ(w.hi, -1001);
    vfp_volume_free(&vol);

    /* A small object in empty space: both percentiles are 0, so the window is the whole range. */
    for (int i = 0; i < 1000; i++)
        values[i] = i < 3 ? 1000 + i : 0;
    CHECK_EQ(fx_load(&vol, raw16("sparse.raw", VF_VOXEL_I16, values, &opts), &opts), 0);
    w = vfp_default_window(&vol);
    CHECK_EQ(w.lo, 0);
    CHECK_EQ(w.hi, 1002);
    vfp_volume_free(&vol);

    /* Constant data still gets lo < hi, at the top of the range too. */
    for (int i = 0; i < 1000; i++)
        values[i] = -7;
    CHECK_EQ(fx_load(&vol, raw16("const.raw", VF_VOXEL_I16, values, &opts), &opts), 0);
    w = vfp_default_window(&vol);
    CHECK_EQ(w.lo, -7);
    CHECK_EQ(w.hi, -6);
    vfp_volume_free(&vol);
    for (int i = 0; i < 1000; i++)
        values[i] = 65535;
    CHECK_EQ(fx_load(&vol, raw16("top.raw", VF_VOXEL_U16, values, &opts), &opts), 0);
    w = vfp_default_window(&vol);
    CHECK_EQ(w.lo, 65534);
    CHECK_EQ(w.hi, 65535);
    vfp_volume_free(&vol);
}

static void window_parse(void)
{
    vfp_volume_t vol;
    memset(&vol, 0, sizeof vol);
    vol.slope = 2.0;
    vol.inter = -10.0;
    vf_window_t w;
    char err[VFP_ERR_LEN];
    CHECK_EQ(vfp_parse_window(&vol, "0,100", &w, err, sizeof err), 0);
    CHECK_EQ(w.lo, 5);
    CHECK_EQ(w.hi, 55);
    CHECK_EQ(vfp_parse_window(&vol, " -10 , 31 ", &w, err, sizeof err), 0);
    CHECK_EQ(w.lo, 0);
    CHECK_EQ(w.hi, 20); /* 20.5 rounds to even */
    CHECK_EQ(vfp_parse_window(&vol, "100,0", &w, err, sizeof err), 0);
    CHECK_EQ(w.lo, 55);
    CHECK_EQ(w.hi, 5);
    vol.slope = -1.0;
    vol.inter = 0.0;
    CHECK_EQ(vfp_parse_window(&vol, "-1000,2e3", &w, err, sizeof err), 0);
    CHECK_EQ(w.lo, 1000);
    CHECK_EQ(w.hi, -2000);
    vol.slope = 1.0;

    fx_expect_text(vfp_parse_window(&vol, "abc", &w, err, sizeof err), err, "--window 'abc'", "expected LO,HI");
    fx_expect_text(vfp_parse_window(&vol, "5", &w, err, sizeof err), err, "--window '5'", "expected LO,HI");
    fx_expect_text(vfp_parse_window(&vol, "1,2,3", &w, err, sizeof err), err, "--window '1,2,3'", "expected LO,HI");
    fx_expect_text(vfp_parse_window(&vol, "", &w, err, sizeof err), err, "--window ''", "expected LO,HI");
    fx_expect_text(vfp_parse_window(&vol, NULL, &w, err, sizeof err), err, "--window (missing)", "expected LO,HI");
    fx_expect_text(vfp_parse_window(&vol, "5,5", &w, err, sizeof err), err, "--window '5,5'", "LO and HI are equal");
    fx_expect_text(vfp_parse_window(&vol, "nan,1", &w, err, sizeof err), err, "--window 'nan,1'", "two finite numbers");
    fx_expect_text(vfp_parse_window(&vol, "0.1,0.2", &w, err, sizeof err), err, "--window '0.1,0.2'",
                   "both round to the raw value 0");
    fx_expect_text(vfp_parse_window(&vol, "0,1e12", &w, err, sizeof err), err, "--window '0,1e12'", "out of range");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Option parsers */

static void parse_dims_and_type(void)
{
    uint32_t d[3];
    char err[VFP_ERR_LEN];
    CHECK_EQ(vfp_parse_dims("3,4,5", d, err, sizeof err), 0);
    CHECK(d[0] == 3 && d[1] == 4 && d[2] == 5);
    CHECK_EQ(vfp_parse_dims("256x256x113", d, err, sizeof err), 0);
    CHECK(d[0] == 256 && d[2] == 113);
    CHECK_EQ(vfp_parse_dims(" 2, 4096 ,2 ", d, err, sizeof err), 0);
    CHECK_EQ(d[1], 4096);
    fx_expect_text(vfp_parse_dims("3,4", d, err, sizeof err), err, "--dims '3,4'", "expected X,Y,Z");
    fx_expect_text(vfp_parse_dims("a,b,c", d, err, sizeof err), err, "--dims 'a,b,c'", "expected X,Y,Z");
    fx_expect_text(vfp_parse_dims("-3,4,5", d, err, sizeof err), err, "--dims '-3,4,5'", "expected X,Y,Z");
    fx_expect_text(vfp_parse_dims("3,4,5,6", d, err, sizeof err), err, "--dims '3,4,5,6'", "unexpected ',6'");
    fx_expect_text(vfp_parse_dims("1,4,5", d, err, sizeof err), err, "--dims '1,4,5'",
                   "size 1 along x is out of range (expected 2..4096; a volume 1 voxel thick cannot be rendered)");
    fx_expect_text(vfp_parse_dims("2,2,5000", d, err, sizeof err), err, "--dims", "size 5000 along z is out of range");
    fx_expect_text(vfp_parse_dims(NULL, d, err, sizeof err), err, "--dims (missing)", "expected X,Y,Z");

    vf_voxel_t t;
    static const struct {
        const char *text;
        vf_voxel_t type;
    } types[] = {{"uint8", VF_VOXEL_U8}, {"int8", VF_VOXEL_I8}, {"uint16", VF_VOXEL_U16}, {"INT16", VF_VOXEL_I16}};
    for (size_t i = 0; i < 4; i++) {
        CHECK_EQ(vfp_parse_type(types[i].text, &t, err, sizeof err), 0);
        CHECK_EQ(t, types[i].type);
    }
    fx_expect_text(vfp_parse_type("float", &t, err, sizeof err), err, "--type 'float'",
                   "unknown type (expected uint8, int8, uint16 or int16)");
    fx_expect_text(vfp_parse_type(NULL, &t, err, sizeof err), err, "--type (missing)", "unknown type");
}

CHECK_CASES({"nifti_int16_little_with_scaling", nifti_int16_little_with_scaling},
            {"nifti_uint16_big", nifti_uint16_big},
            {"nifti_gzip_uint8_4d", nifti_gzip_uint8_4d},
            {"nifti_int8_with_extension_bytes", nifti_int8_with_extension_bytes},
            {"nifti_recognised_by_content", nifti_recognised_by_content},
            {"nifti_errors", nifti_errors},
            {"den_good", den_good},
            {"den_errors", den_errors},
            {"raw_good", raw_good},
            {"raw_errors", raw_errors},
            {"huge_claims_without_data", huge_claims_without_data},
            {"gzip_larger_than_first_buffer", gzip_larger_than_first_buffer},
            {"phantom_marschner_lobb", phantom_marschner_lobb},
            {"phantom_shepp_logan", phantom_shepp_logan},
            {"phantom_sphere", phantom_sphere},
            {"phantom_errors", phantom_errors},
            {"window_default", window_default},
            {"window_parse", window_parse},
            {"parse_dims_and_type", parse_dims_and_type});
CHECK_RUN("volume")
