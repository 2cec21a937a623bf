/* SPDX-License-Identifier: MIT */
/* test_orientation.c: the readers added for the formats users have (MetaImage, NIfTI-2, NRRD's ascii and hex
 * encodings) and the patient frame on load (NRRD space directions and spaces, oblique directions), named views and
 * the letters at a view's edges; on small files written at test time. tests/port/orientation.sh renders one phantom
 * from every format. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "check.h"
#include "io/volume.h"
#include "volume_fixtures.h"

#define MHD_HEAD "ObjectType = Image\nNDims = 3\nDimSize = 3 4 5\nElementSpacing = 1 1 1\n"

/* ---------------------------------------------------------------------------------------------------------- */
/* Helpers */

/* The fixture's values as NRRD ascii text (one line per row) or hex (big-endian for 16 bits). */
static const char *nrrd_text(const char *name, const char *type, const char *encoding, vf_voxel_t vt)
{
    static char text[8192];
    int n = snprintf(text, sizeof text, "NRRD0004\ntype: %s\ndimension: 3\nsizes: 3 4 5\nendian: big\nencoding: %s\n\n",
                     type, encoding);
    unsigned char bytes[FX_COUNT * 2];
    size_t nb = fx_bytes(vt, 1, bytes);
    if (strcmp(encoding, "hex") != 0) {
        for (int i = 0; i < FX_COUNT; i++)
            n += snprintf(text + n, sizeof text - (size_t)n, "%d%s", fx_value(vt, i), i % 3 == 2 ? "\n" : "  ");
    } else {
        for (size_t i = 0; i < nb; i++)
            n += snprintf(text + n, sizeof text - (size_t)n, "%02X%s", bytes[i], i % 16 == 15 ? "\n" : "");
    }
    return fx_write(name, text, NULL, 0);
}

/* A NIfTI-2 header (540 bytes, little-endian) and 4 bytes of extension flags, then the fixture. */
static const char *nifti2(const char *name, vf_voxel_t vt, int qform_code, const double quatern[3], double qfac)
{
    unsigned char buf[544 + FX_COUNT * 2];
    memset(buf, 0, sizeof buf);
    int32_t sizeof_hdr = 540;
    memcpy(buf, &sizeof_hdr, 4);
    memcpy(buf + 4, "n+2\0\r\n\032\n", 8);
    int16_t datatype = vt == VF_VOXEL_U8 ? 2 : vt == VF_VOXEL_I16 ? 4 : vt == VF_VOXEL_U16 ? 512 : 256;
    int16_t bitpix = vt == VF_VOXEL_U8 || vt == VF_VOXEL_I8 ? 8 : 16;
    memcpy(buf + 12, &datatype, 2);
    memcpy(buf + 14, &bitpix, 2);
    int64_t dim[8] = {3, FX_X, FX_Y, FX_Z, 1, 1, 1, 1};
    memcpy(buf + 16, dim, sizeof dim);
    double pixdim[8] = {qfac, 0.5, 0.75, 2, 1, 1, 1, 1};
    memcpy(buf + 104, pixdim, sizeof pixdim);
    int64_t vox_offset = 544;
    memcpy(buf + 168, &vox_offset, 8);
    memcpy(buf + 344, &qform_code, 4);
    if (quatern)
        memcpy(buf + 352, quatern, 3 * sizeof(double));
    size_t n = fx_bytes(vt, 0, buf + 544);
    return fx_write(name, NULL, buf, 544 + n);
}

/* A loaded volume's voxel at (x, y, z). */
static int32_t at(const vfp_volume_t *v, uint32_t x, uint32_t y, uint32_t z)
{
    return fx_voxel(v, ((size_t)z * v->core.dims[1] + y) * v->core.dims[0] + x);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* NRRD's text encodings, NIfTI-2 */

static void nrrd_ascii_and_hex(void)
{
    vfp_volume_t v;
    CHECK_EQ(fx_load(&v, nrrd_text("a8.nrrd", "uint8", "ascii", VF_VOXEL_U8), NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_U8);
    CHECK_EQ(fx_load(&v, nrrd_text("a16.nrrd", "int16", "text", VF_VOXEL_I16), NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_I16);
    CHECK_EQ(fx_load(&v, nrrd_text("h16.nrrd", "uint16", "hex", VF_VOXEL_U16), NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_U16);
    CHECK_EQ(fx_load(&v, nrrd_text("h8.nrrd", "int8", "hex", VF_VOXEL_I8), NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_I8);

    const char *head = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: ascii\n\n";
    const char *p = fx_write("big.nrrd", head, "300", 3);
    fx_expect_error(p, NULL, p, "ascii value 1 '300' is not a whole number in 0..255");
    p = fx_write("short.nrrd", head, "1 2 3", 5);
    fx_expect_error(p, NULL, p, "truncated: expected 60");
    p = fx_write("hexbad.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: hex\n\n", "0g", 2);
    fx_expect_error(p, NULL, p, "hex byte 1 is not two hexadecimal digits");
    /* bzip2 is refused with the way to convert it (tests/port/test_volume.c has every spelling) */
    p = fx_write("bz.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: bzip2\n\n", NULL, 0);
    fx_expect_error(p, NULL, p, ":5: unsupported encoding 'bzip2' (supported: raw, gzip, ascii, hex; convert with "
                                "'unu save -e gzip'");
}

static void nifti2_loads(void)
{
    vfp_volume_t v;
    CHECK_EQ(fx_load(&v, nifti2("n2.nii", VF_VOXEL_I16, 0, NULL, 1), NULL), 0);
    CHECK(strcmp(v.format, "nifti") == 0 && !v.oriented);
    CHECK(v.spacing[0] == 0.5 && v.spacing[1] == 0.75 && v.spacing[2] == 2);
    fx_check_fixture(&v, VF_VOXEL_I16);
    CHECK_EQ(fx_load(&v, nifti2("n2u8.nii", VF_VOXEL_U8, 0, NULL, 1), NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_U8);
    /* qform: quaternion (0, 0, 1) turns NIfTI's RAS 180 degrees about S, so stored x runs towards L and y towards
     * P, LPS as stored: the voxels stay as they are, and the volume is oriented by its qform */
    const double half_turn[3] = {0, 0, 1};
    CHECK_EQ(fx_load(&v, nifti2("n2q.nii", VF_VOXEL_U8, 1, half_turn, 1), NULL), 0);
    CHECK(v.oriented && strcmp(v.orient_from, "qform") == 0 && v.oblique_deg == 0);
    CHECK(!v.stored_flip[0] && !v.stored_flip[1] && !v.stored_flip[2]);
    fx_check_fixture(&v, VF_VOXEL_U8);
    /* the identity qform (RAS) reverses x and y on the way into LPS */
    const double none[3] = {0, 0, 0};
    CHECK_EQ(fx_load(&v, nifti2("n2id.nii", VF_VOXEL_U8, 1, none, 1), NULL), 0);
    CHECK(v.stored_flip[0] && v.stored_flip[1] && !v.stored_flip[2]);
    CHECK_EQ(at(&v, 0, 0, 0), fx_value(VF_VOXEL_U8, 2 + 3 * 3));
    vfp_volume_free(&v);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* MetaImage */

static void metaimage_good(void)
{
    unsigned char data[FX_COUNT * 2], packed[FX_COUNT * 4];
    vfp_volume_t v;
    size_t n = fx_bytes(VF_VOXEL_U8, 0, data);
    const char *p = fx_write("u8.mha", MHD_HEAD "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n", data, n);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    CHECK(strcmp(v.format, "metaimage") == 0 && !v.oriented);
    fx_check_fixture(&v, VF_VOXEL_U8);

    n = fx_bytes(VF_VOXEL_I8, 0, data);
    fx_write("i8.raw", NULL, data, n);
    p = fx_write("i8.mhd", MHD_HEAD "ElementType = MET_CHAR\nElementDataFile = i8.raw\n", NULL, 0);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_I8);

    n = fx_bytes(VF_VOXEL_I16, 1, data);
    fx_write("i16.raw", NULL, data, n);
    p = fx_write("i16.mhd", MHD_HEAD "ElementByteOrderMSB = True\nElementType = MET_SHORT\nElementDataFile = i16.raw\n",
                 NULL, 0);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_I16);

    /* HeaderSize bytes skipped in the data file; -1: the data is the file's last bytes */
    unsigned char skipped[FX_COUNT * 2 + 40];
    memset(skipped, 0xee, 40);
    n = fx_bytes(VF_VOXEL_U16, 0, skipped + 40);
    fx_write("u16.raw", NULL, skipped, 40 + n);
    p = fx_write("u16.mhd", MHD_HEAD "HeaderSize = 40\nBinaryDataByteOrderMSB = False\nElementType = MET_USHORT\n"
                 "ElementDataFile = u16.raw\n", NULL, 0);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_U16);
    p = fx_write("u16m.mhd", MHD_HEAD "HeaderSize = -1\nElementType = MET_USHORT\nElementDataFile = u16.raw\n", NULL, 0);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_U16);

    /* zlib, with and without CompressedDataSize */
    n = fx_bytes(VF_VOXEL_I16, 0, data);
    uLongf packed_n = sizeof packed;
    CHECK_EQ(compress2(packed, &packed_n, data, n, 9), Z_OK);
    char head[512];
    snprintf(head, sizeof head, MHD_HEAD "CompressedData = True\nCompressedDataSize = %lu\nElementType = MET_SHORT\n"
             "ElementDataFile = LOCAL\n", (unsigned long)packed_n);
    p = fx_write("z.mha", head, packed, packed_n);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_I16);
    fx_write("z.zraw", NULL, packed, packed_n);
    p = fx_write("z.mhd", MHD_HEAD "CompressedData = True\nElementType = MET_SHORT\nElementDataFile = z.zraw\n", NULL, 0);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    fx_check_fixture(&v, VF_VOXEL_I16);

    /* ElementSpacing, or ElementSize when there is no spacing */
    p = fx_write("sp.mha", "NDims = 3\nDimSize = 3 4 5\nElementSize = 0.5 0.5 1.25\nElementType = MET_UCHAR\n"
                 "ElementDataFile = LOCAL\n", data, FX_COUNT);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    CHECK(v.spacing[0] == 0.5 && v.spacing[2] == 1.25);
    vfp_volume_free(&v);
}

static void metaimage_errors(void)
{
    unsigned char data[FX_COUNT * 4] = {0};
    const char *p = fx_write("f.mha", MHD_HEAD "ElementType = MET_FLOAT\nElementDataFile = LOCAL\n", data, sizeof data);
    fx_expect_error(p, NULL, p, ":5: unsupported ElementType 'MET_FLOAT' (expected MET_UCHAR, MET_CHAR, MET_USHORT or "
                                "MET_SHORT");
    p = fx_write("d2.mha", "NDims = 2\nDimSize = 3 4\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n", data, 12);
    fx_expect_error(p, NULL, p, ":1: NDims 2 is not supported (expected 3: a 3D volume)");
    p = fx_write("nodim.mha", "NDims = 3\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n", data, FX_COUNT);
    fx_expect_error(p, NULL, p, "missing key 'DimSize'");
    p = fx_write("list.mhd", MHD_HEAD "ElementType = MET_UCHAR\nElementDataFile = LIST\na.raw\n", NULL, 0);
    fx_expect_error(p, NULL, p, ":6: ElementDataFile = LIST (one file per slice) is not supported");
    p = fx_write("short.mha", MHD_HEAD "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n", data, 10);
    fx_expect_error(p, NULL, p, "truncated: expected 60 bytes of voxel data, found 10");
    p = fx_write("nofile.mhd", MHD_HEAD "ElementType = MET_UCHAR\nElementDataFile = missing.raw\n", NULL, 0);
    fx_expect_error(p, NULL, p, ":6: cannot open data file");
    p = fx_write("zbig.mha", MHD_HEAD "CompressedData = True\nCompressedDataSize = 5000\nElementType = MET_UCHAR\n"
                 "ElementDataFile = LOCAL\n", data, 20);
    fx_expect_error(p, NULL, p, "truncated: CompressedDataSize is 5000 bytes, but the file holds 20 after the header");
    p = fx_write("text.mha", MHD_HEAD "BinaryData = False\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n", "1 2", 3);
    fx_expect_error(p, NULL, p, ":5: BinaryData = False (text voxels) is not supported");
    p = fx_write("chan.mha", MHD_HEAD "ElementNumberOfChannels = 3\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n",
                 data, sizeof data);
    fx_expect_error(p, NULL, p, ":5: ElementNumberOfChannels '3' is not supported");
    p = fx_write("flat.mha", MHD_HEAD "TransformMatrix = 1 0 0 1 0 0 0 0 1\nElementType = MET_UCHAR\n"
                 "ElementDataFile = LOCAL\n", data, FX_COUNT);
    fx_expect_error(p, NULL, p, "the axes' directions are (nearly) in one plane");
    p = fx_write("anat.mha", MHD_HEAD "AnatomicalOrientation = RRS\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n",
                 data, FX_COUNT);
    fx_expect_error(p, NULL, p, ":5: bad AnatomicalOrientation 'RRS'");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* The patient frame */

static void nrrd_axes_into_lps(void)
{
    /* stored x runs towards P, stored y towards R (so reversed into L), stored z towards S */
    unsigned char data[FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    const char *p = fx_write("perm.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 4 5\nspace: LPS\n"
                             "space directions: (0,0.5,0) (-2,0,0) (0,0,1)\nencoding: raw\n\n", data, FX_COUNT);
    vfp_volume_t v;
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    CHECK(v.oriented && strcmp(v.orient_from, "space directions") == 0 && v.oblique_deg == 0);
    CHECK(v.core.dims[0] == 4 && v.core.dims[1] == 3 && v.core.dims[2] == 5);
    CHECK(v.spacing[0] == 2 && v.spacing[1] == 0.5 && v.spacing[2] == 1);
    CHECK(v.stored_axis[0] == 1 && v.stored_flip[0] && v.stored_axis[1] == 0 && !v.stored_flip[1]);
    /* new (x, y, z) is stored (y, 3 - x, z) */
    int same = 1;
    for (uint32_t z = 0; z < 5; z++)
        for (uint32_t y = 0; y < 3; y++)
            for (uint32_t x = 0; x < 4; x++)
                same = same && at(&v, x, y, z) == fx_value(VF_VOXEL_U8, (int)((z * 4 + (3 - x)) * 3 + y));
    CHECK(same);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            CHECK_NEAR(v.direction[r][c], r == c, 1e-12);
    vfp_volume_free(&v);

    /* the same in RAS: x and y of the space turned round */
    p = fx_write("ras.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 4 5\nspace: right-anterior-superior\n"
                 "space directions: (0,-0.5,0) (2,0,0) (0,0,1)\nencoding: raw\n\n", data, FX_COUNT);
    vfp_volume_t w;
    CHECK_EQ(fx_load(&v, fx_path("perm.nrrd"), NULL), 0);
    CHECK_EQ(fx_load(&w, p, NULL), 0);
    CHECK(memcmp(v.data, w.data, FX_COUNT) == 0 && memcmp(v.core.dims, w.core.dims, sizeof v.core.dims) == 0);
    vfp_volume_free(&v);
    vfp_volume_free(&w);

    /* a scanner space says nothing about the patient: as stored */
    p = fx_write("scan.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 4 5\nspace: scanner-xyz\n"
                 "space directions: (0,0.5,0) (-2,0,0) (0,0,1)\nencoding: raw\n\n", data, FX_COUNT);
    CHECK_EQ(fx_load(&v, p, NULL), 0);
    CHECK(!v.oriented && v.core.dims[0] == 3 && v.stored_axis[0] == 0);
    vfp_volume_free(&v);

    p = fx_write("flat.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 4 5\nspace: LPS\n"
                 "space directions: (1,0,0) (1,0,0) (0,0,1)\nencoding: raw\n\n", data, FX_COUNT);
    fx_expect_error(p, NULL, p, "the axes' directions are (nearly) in one plane");
}

static void oblique_nearest_axes(void)
{
    /* axes turned 30 degrees about S, the first nearer P than L: shown in the nearest patient axes (a permutation
     * and signs), with what is left in direction and oblique_deg 30 */
    double c = cos(30 * 3.14159265358979323846 / 180), s = sin(30 * 3.14159265358979323846 / 180);
    char head[512];
    snprintf(head, sizeof head, "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 3 4 5\nspace: LPS\nspace directions: "
             "(%.17g,%.17g,0) (%.17g,%.17g,0) (0,0,1)\nencoding: raw\n\n", s, c, -c, s);
    unsigned char data[FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    vfp_volume_t v;
    CHECK_EQ(fx_load(&v, fx_write("obl.nrrd", head, data, FX_COUNT), NULL), 0);
    CHECK(v.oriented);
    CHECK_NEAR(v.oblique_deg, 30, 1e-9);
    CHECK(v.stored_axis[0] == 1 && v.stored_flip[0] && v.stored_axis[1] == 0 && !v.stored_flip[1]);
    CHECK_NEAR(v.direction[0][0], c, 1e-12);
    CHECK_NEAR(v.direction[1][1], c, 1e-12);
    CHECK_NEAR(v.direction[2][2], 1, 1e-12);
    vfp_volume_free(&v);
}

static void named_views_and_edges(void)
{
    static const struct {
        const char *name;
        const char *right, *left, *top, *bottom;
    } views[] = {
        {"anterior", "L", "R", "S", "I"}, {"posterior", "R", "L", "S", "I"}, {"left", "P", "A", "S", "I"},
        {"right", "A", "P", "S", "I"},    {"inferior", "L", "R", "A", "P"},  {"superior", "R", "L", "A", "P"},
    };
    for (size_t i = 0; i < sizeof views / sizeof views[0]; i++) {
        double view[3];
        char r[4], l[4], t[4], b[4];
        CHECK_EQ(vfp_view_named(views[i].name, view), VFP_OK);
        vfp_view_edges(view, r, l, t, b);
        CHECK_MSG(!strcmp(r, views[i].right) && !strcmp(l, views[i].left) && !strcmp(t, views[i].top) &&
                      !strcmp(b, views[i].bottom),
                  "%s: right %s left %s top %s bottom %s", views[i].name, r, l, t, b);
    }
    double view[3] = {7, 7, 7};
    CHECK_EQ(vfp_view_named("front", view), VFP_ERR);
    CHECK_EQ(vfp_view_named(NULL, view), VFP_ERR);
    CHECK_EQ(vfp_view_named("ANTERIOR", view), VFP_OK);
    /* an oblique view names two axes at an edge */
    char r[4], l[4], t[4], b[4];
    const double oblique[3] = {30, 20, 0};
    vfp_view_edges(oblique, r, l, t, b);
    CHECK_MSG(strlen(r) == 2 && r[0] == 'L', "30,20: right edge %s", r);
}

CHECK_CASES({"nrrd_ascii_and_hex", nrrd_ascii_and_hex}, {"nifti2_loads", nifti2_loads},
            {"metaimage_good", metaimage_good}, {"metaimage_errors", metaimage_errors},
            {"nrrd_axes_into_lps", nrrd_axes_into_lps}, {"oblique_nearest_axes", oblique_nearest_axes},
            {"named_views_and_edges", named_views_and_edges});
CHECK_RUN("orientation")
