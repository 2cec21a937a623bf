/* SPDX-License-Identifier: MIT */
/* test_volume.c: the NRRD reader, format dispatch and their error messages, on small files written at test time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/volume.h"
#include "volume_fixtures.h"

/* The head of a valid 3x4x5 header; tests add or replace lines. */
#define HEAD "NRRD0004\n"
#define U8_FIELDS "type: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: raw\n"

/* A NRRD with attached data: header, blank line, the fixture's bytes. */
static const char *attached(const char *name, const char *header, vf_voxel_t type, int big)
{
    unsigned char data[FX_COUNT * 2];
    size_t n = fx_bytes(type, big, data);
    char text[4096];
    snprintf(text, sizeof text, "%s\n", header);
    return fx_write(name, text, data, n);
}

/* An attached NRRD whose data has `delta` bytes more (or fewer) than the header says. */
static const char *attached_sized(const char *name, const char *header, int delta)
{
    unsigned char data[FX_COUNT + 16];
    memset(data, 7, sizeof data);
    char text[4096];
    snprintf(text, sizeof text, "%s\n", header);
    return fx_write(name, text, data, (size_t)(FX_COUNT + delta));
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Good files */

static void nrrd_attached_uint8(void)
{
    const char *p = attached("a.nrrd", HEAD U8_FIELDS, VF_VOXEL_U8, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK(strcmp(vol.format, "nrrd") == 0);
    CHECK(strcmp(vol.name, p) == 0);
    for (int a = 0; a < 3; a++) {
        CHECK_NEAR(vol.spacing[a], 1.0, 0);
        CHECK_EQ(vol.core.spacing_q16[a], 65536);
    }
    CHECK_NEAR(vol.slope, 1.0, 0);
    CHECK_NEAR(vol.inter, 0.0, 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void nrrd_detached_int16_big(void)
{
    /* The data file name is relative to the header's directory, not to the working directory. */
    fx_mkdir("sub");
    unsigned char data[FX_COUNT * 2];
    size_t n = fx_bytes(VF_VOXEL_I16, 1, data);
    fx_write("sub/be.raw", NULL, data, n);
    const char *p = fx_write("sub/be.nhdr", HEAD "type: short\ndimension: 3\nsizes: 3 4 5\nspacings: 0.5 1 2.25\n"
                             "endian: big\nencoding: raw\ndata file: be.raw\n", NULL, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK_NEAR(vol.spacing[0], 0.5, 0);
    CHECK_NEAR(vol.spacing[2], 2.25, 0);
    /* the core gets spacings relative to the smallest, Q16.16 */
    CHECK_EQ(vol.core.spacing_q16[0], 65536);
    CHECK_EQ(vol.core.spacing_q16[1], 131072);
    CHECK_EQ(vol.core.spacing_q16[2], 294912);
    fx_check_fixture(&vol, VF_VOXEL_I16);
}

static void nrrd_detached_gzip_uint16_little(void)
{
    unsigned char data[FX_COUNT * 2];
    size_t n = fx_bytes(VF_VOXEL_U16, 0, data);
    fx_write_gz("le.raw.gz", data, n);
    /* NRRD0001-era spellings: "datafile", "gz", CRLF line ends. */
    const char *p = fx_write("le.nhdr", "NRRD0001\r\ntype: unsigned short\r\ndimension: 3\r\nsizes: 3 4 5\r\n"
                             "endian: little\r\nencoding: gz\r\ndatafile: le.raw.gz\r\n", NULL, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_U16);
}

static void nrrd_attached_gzip_int8(void)
{
    unsigned char data[FX_COUNT];
    size_t n = fx_bytes(VF_VOXEL_I8, 0, data), gz_n;
    unsigned char *gz = fx_gzip_bytes(data, n, &gz_n);
    const char *p = fx_write("gz8.nrrd", HEAD "type: int8\ndimension: 3\nsizes: 3 4 5\nencoding: gzip\n\n", gz, gz_n);
    free(gz);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_I8);
}

static void nrrd_gzip_two_members(void)
{
    /* Concatenated gzip members are one stream, as gzip -d reads them. */
    unsigned char data[FX_COUNT * 2];
    size_t n = fx_bytes(VF_VOXEL_I16, 0, data), n1, n2;
    unsigned char *g1 = fx_gzip_bytes(data, 50, &n1), *g2 = fx_gzip_bytes(data + 50, n - 50, &n2);
    unsigned char both[1024];
    memcpy(both, g1, n1);
    memcpy(both + n1, g2, n2);
    free(g1);
    free(g2);
    const char *p = fx_write("two.nrrd", HEAD "type: int16\ndimension: 3\nsizes: 3 4 5\nendian: little\n"
                             "encoding: gzip\n\n", both, n1 + n2);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_I16);
}

static void nrrd_type_spellings(void)
{
    static const struct {
        const char *spelling;
        vf_voxel_t type;
    } cases[] = {
        {"uchar", VF_VOXEL_U8}, {"unsigned char", VF_VOXEL_U8}, {"uint8", VF_VOXEL_U8}, {"uint8_t", VF_VOXEL_U8},
        {"signed char", VF_VOXEL_I8}, {"int8", VF_VOXEL_I8}, {"int8_t", VF_VOXEL_I8},
        {"short", VF_VOXEL_I16}, {"short int", VF_VOXEL_I16}, {"signed short", VF_VOXEL_I16},
        {"signed short int", VF_VOXEL_I16}, {"int16", VF_VOXEL_I16}, {"int16_t", VF_VOXEL_I16},
        {"ushort", VF_VOXEL_U16}, {"unsigned short", VF_VOXEL_U16}, {"unsigned short int", VF_VOXEL_U16},
        {"uint16", VF_VOXEL_U16}, {"uint16_t", VF_VOXEL_U16}, {"Unsigned  Short", VF_VOXEL_U16},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char header[512];
        snprintf(header, sizeof header, HEAD "type: %s\ndimension: 3\nsizes: 3 4 5\nendian: big\nencoding: raw\n",
                 cases[i].spelling);
        const char *p = attached("spell.nrrd", header, cases[i].type, 1);
        vfp_volume_t vol;
        CHECK_MSG(fx_load(&vol, p, NULL) == 0, "type '%s' did not load", cases[i].spelling);
        fx_check_fixture(&vol, cases[i].type);
        if (check_failed)
            return;
    }
}

static void nrrd_ignored_fields_and_directions(void)
{
    /* Every field NRRD defines that the renderer does not need, comments, key/value pairs, and spacing from the
     * lengths of the space direction vectors (in a scanner space, which says nothing about the patient: the voxels
     * stay as stored; test_orientation.c has the patient spaces). */
    const char *header = "NRRD0005\n# a comment\ntype: uint8\ndimension: 3\nspace: scanner-xyz\n"
                         "sizes: 3 4 5\nspace directions: (0.5,0,0) (0,0.6,0.8) (0,0, 3)\nkinds: domain domain domain\n"
                         "space origin: (1,2,3)\ncontent: test\nlabels: \"x\" \"y\" \"z\"\n"
                         "units: \"mm\" \"mm\" \"mm\"\n"
                         "space units: \"mm\" \"mm\" \"mm\"\ncenterings: cell cell cell\ncenters: cell cell cell\n"
                         "min: 0\nmax: 255\nold min: 0\nold max: 1\nsample units: HU\n"
                         "measurement frame: (1,0,0) (0,1,0) (0,0,1)\naxis mins: 0 0 0\naxis maxs: 1 1 1\n"
                         "thicknesses: 1 1 1\nspace dimension: 3\nnumber: 60\nmy key:=my: value\nencoding: raw\n";
    const char *p = attached("fields.nrrd", header, VF_VOXEL_U8, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK_NEAR(vol.spacing[0], 0.5, 1e-12);
    CHECK_NEAR(vol.spacing[1], 1.0, 1e-12);
    CHECK_NEAR(vol.spacing[2], 3.0, 1e-12);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void nrrd_spacings_win_over_directions(void)
{
    const char *p = attached("both.nrrd", HEAD U8_FIELDS "spacings: 2 3 4\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n",
                             VF_VOXEL_U8, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK_NEAR(vol.spacing[0], 2.0, 0);
    CHECK_NEAR(vol.spacing[2], 4.0, 0);
    vfp_volume_free(&vol);
}

static void nrrd_line_and_byte_skip(void)
{
    unsigned char data[FX_COUNT * 2 + 4];
    memcpy(data, "junk", 4);
    size_t n = fx_bytes(VF_VOXEL_U16, 1, data + 4);
    fx_write("skip.raw", "first line\nsecond line\n", data, n + 4);
    const char *p = fx_write("skip.nhdr", HEAD "type: uint16\ndimension: 3\nsizes: 3 4 5\nendian: big\n"
                             "encoding: raw\nline skip: 2\nbyte skip: 4\ndata file: skip.raw\n", NULL, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_U16);
}

static void nrrd_byte_skip_minus_one(void)
{
    /* byte skip -1: the data is the last bytes of the file, whatever comes before. */
    unsigned char data[FX_COUNT + 9];
    memcpy(data, "123456789", 9);
    fx_bytes(VF_VOXEL_U8, 0, data + 9);
    fx_write("tail.raw", NULL, data, sizeof data);
    const char *p = fx_write("tail.nhdr", HEAD U8_FIELDS "byte skip: -1\ndata file: tail.raw\n", NULL, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void nrrd_gzip_byte_skip_after_decompression(void)
{
    unsigned char data[FX_COUNT + 7];
    memcpy(data, "skipped", 7);
    fx_bytes(VF_VOXEL_U8, 0, data + 7);
    fx_write_gz("gskip.gz", data, sizeof data);
    const char *p = fx_write("gskip.nhdr", HEAD "type: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: gzip\n"
                             "byte skip: 7\ndata file: gskip.gz\n", NULL, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void nrrd_absolute_data_file(void)
{
    unsigned char data[FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    const char *raw = fx_write("abs.raw", NULL, data, sizeof data);
    char header[1024];
    snprintf(header, sizeof header, HEAD U8_FIELDS "data file: %s\n", raw);
    fx_mkdir("elsewhere");
    const char *p = fx_write("elsewhere/abs.nhdr", header, NULL, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void nrrd_recognised_by_content(void)
{
    const char *p = attached("volume.dat", HEAD U8_FIELDS, VF_VOXEL_U8, 0);
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, NULL), 0);
    CHECK(strcmp(vol.format, "nrrd") == 0);
    fx_check_fixture(&vol, VF_VOXEL_U8);
}

static void spacing_option_overrides_file(void)
{
    const char *p = attached("over.nrrd", HEAD U8_FIELDS "spacings: 9 9 9\n", VF_VOXEL_U8, 0);
    vfp_load_opts_t opts = {.have_spacing = 1, .spacing = {0.25, 1.5, 3}};
    vfp_volume_t vol;
    CHECK_EQ(fx_load(&vol, p, &opts), 0);
    CHECK_NEAR(vol.spacing[0], 0.25, 0);
    CHECK_EQ(vol.core.spacing_q16[0], 65536);
    CHECK_EQ(vol.core.spacing_q16[1], 393216);
    CHECK_EQ(vol.core.spacing_q16[2], 786432);
    vfp_volume_free(&vol);
    opts.spacing[1] = 0;
    fx_expect_error(p, &opts, p, ": --spacing: bad spacing 0 along y");
}

static void spacing_anisotropy_limit(void)
{
    /* the core renders spacings within 64x of each other; the loader says so, naming the file */
    const char *p = attached("flat.nrrd", HEAD U8_FIELDS "spacings: 0.1 0.1 7\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ": spacings 0.1, 0.1, 7 differ by more than 64x");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* Errors that come before any format */

static void error_nonexistent_file(void)
{
    const char *p = fx_path("no/such/file.nhdr");
    fx_expect_error(p, NULL, p, "cannot open: No such file or directory");
}

static void error_empty_file(void)
{
    const char *p = fx_write("empty.nrrd", NULL, NULL, 0);
    fx_expect_error(p, NULL, p, "empty file");
    p = fx_write("empty.bin", NULL, NULL, 0);
    fx_expect_error(p, NULL, p, "empty file");
}

static void error_directory(void)
{
    const char *p = fx_mkdir("adir.nrrd");
    fx_expect_error(p, NULL, p, "is a directory");
}

static void error_null_arguments(void)
{
    vfp_volume_t vol;
    char err[VFP_ERR_LEN];
    CHECK_EQ(vfp_volume_load(&vol, "", NULL, err, sizeof err), VFP_ERR);
    CHECK(strstr(err, "no volume file") != NULL);
    CHECK_EQ(vfp_volume_load(&vol, NULL, NULL, err, sizeof err), VFP_ERR);
    CHECK_EQ(vfp_volume_load(NULL, "x", NULL, err, sizeof err), VFP_ERR);
    CHECK_EQ(vfp_volume_load(&vol, "", NULL, NULL, 0), VFP_ERR); /* no err buffer: still no crash */
    vfp_volume_free(NULL);
}

/* ---------------------------------------------------------------------------------------------------------- */
/* NRRD header errors */

static void error_bad_magic(void)
{
    const char *p = attached("magic.nrrd", "NRRX0004\n" U8_FIELDS, VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":1: bad magic 'NRRX0004' (expected NRRD0001..NRRD0005)");
    p = attached("magic9.nhdr", "NRRD0009\n" U8_FIELDS, VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":1: bad magic 'NRRD0009'");
    unsigned char junk[4] = {0, 1, 2, 3};
    p = fx_write("binary.nrrd", NULL, junk, sizeof junk);
    fx_expect_error(p, NULL, p, ":1: bad magic: not a text line");
}

static void error_line_without_colon(void)
{
    const char *p = attached("nocolon.nrrd", HEAD "type: uint8\ndimension: 3\nsizes 3 4 5\nencoding: raw\n",
                             VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":4: expected 'field: value', found 'sizes 3 4 5'");
}

static void error_unknown_field(void)
{
    const char *p = attached("unknown.nrrd", HEAD U8_FIELDS "colour: red\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":6: unknown field 'colour'");
}

static void error_unparsable_values(void)
{
    const char *p = attached("badsizes.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: 3 four 5\nencoding: raw\n",
                             VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":4: bad sizes '3 four 5' (expected three whole numbers)");
    p = attached("count.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: 3 4\nencoding: raw\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":4: sizes has 2 values (expected 3, one per axis)");
    p = attached("baddim.nrrd", HEAD "type: uint8\ndimension: three\nsizes: 3 4 5\nencoding: raw\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":3: bad dimension 'three'");
    p = attached("badsp.nrrd", HEAD U8_FIELDS "spacings: 1 1\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":6: spacings has 2 values");
    p = attached("baddir.nrrd", HEAD U8_FIELDS "space directions: (1,0,0) (0,1 0) (0,0,1)\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":6: bad space directions");
    p = attached("badendian.nrrd", HEAD U8_FIELDS "endian: middle\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":6: unknown endian 'middle' (expected little or big)");
    p = attached("badskip.nrrd", HEAD U8_FIELDS "byte skip: -2\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":6: bad byte skip '-2'");
    p = attached("badlskip.nrrd", HEAD U8_FIELDS "line skip: x\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":6: bad line skip 'x'");
}

static void error_duplicate_field(void)
{
    const char *p = attached("dup.nrrd", HEAD U8_FIELDS "type: uint8\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":6: duplicate field 'type' (first on line 2)");
}

static void error_missing_required_fields(void)
{
    static const struct {
        const char *fields, *missing;
    } cases[] = {
        {"dimension: 3\nsizes: 3 4 5\nencoding: raw\n", "missing required field 'type'"},
        {"type: uint8\nsizes: 3 4 5\nencoding: raw\n", "missing required field 'dimension'"},
        {"type: uint8\ndimension: 3\nencoding: raw\n", "missing required field 'sizes'"},
        {"type: uint8\ndimension: 3\nsizes: 3 4 5\n", "missing required field 'encoding'"},
        {"type: int16\ndimension: 3\nsizes: 3 4 5\nencoding: raw\n", "missing field 'endian'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char header[512];
        snprintf(header, sizeof header, HEAD "%s", cases[i].fields);
        const char *p = attached("missing.nrrd", header, VF_VOXEL_U8, 0);
        fx_expect_error(p, NULL, p, cases[i].missing);
        if (check_failed)
            return;
    }
}

static void error_unsupported_type(void)
{
    static const char *const unsupported[] = {"float", "double", "int", "int32", "uint32_t", "long long", "block"};
    for (size_t i = 0; i < sizeof unsupported / sizeof unsupported[0]; i++) {
        char header[512], phrase[128];
        snprintf(header, sizeof header, HEAD "type: %s\ndimension: 3\nsizes: 3 4 5\nencoding: raw\n", unsupported[i]);
        snprintf(phrase, sizeof phrase, ":2: unsupported type '%s' (expected int8, uint8, int16 or uint16)",
                 unsupported[i]);
        const char *p = attached("float.nrrd", header, VF_VOXEL_U8, 0);
        fx_expect_error(p, NULL, p, phrase);
        if (check_failed)
            return;
    }
    const char *p = attached("f32.nrrd", HEAD "type: float32\ndimension: 3\nsizes: 3 4 5\nencoding: raw\n",
                             VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":2: unknown type 'float32' (expected int8, uint8, int16 or uint16)");
    p = attached("char.nrrd", HEAD "type: char\ndimension: 3\nsizes: 3 4 5\nencoding: raw\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":2: type 'char' is ambiguous");
}

static void error_unsupported_encoding(void)
{
    static const char *const encodings[] = {"bzip2", "bz2", "zrl"};
    for (size_t i = 0; i < sizeof encodings / sizeof encodings[0]; i++) {
        char header[512], phrase[128];
        snprintf(header, sizeof header, HEAD "type: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: %s\n", encodings[i]);
        snprintf(phrase, sizeof phrase, ":5: unsupported encoding '%s' (supported: raw, gzip, ascii, hex", encodings[i]);
        const char *p = attached("enc.nrrd", header, VF_VOXEL_U8, 0);
        fx_expect_error(p, NULL, p, phrase);
        if (check_failed)
            return;
    }
    const char *p = attached("enc2.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: lz4\n",
                             VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":5: unknown encoding 'lz4' (supported: raw, gzip, ascii, hex)");
}

static void error_wrong_dimension(void)
{
    const char *p = attached("dim4.nrrd", HEAD "type: uint8\ndimension: 4\nsizes: 1 3 4 5\nencoding: raw\n",
                             VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":3: dimension 4 is not supported (expected 3");
    p = attached("dim2.nrrd", HEAD "type: uint8\ndimension: 2\nsizes: 12 5\nencoding: raw\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":3: dimension 2 is not supported");
}

static void error_bad_sizes(void)
{
    const char *p = attached("thin.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: 3 1 20\nencoding: raw\n",
                             VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":4: size 1 along y is out of range (expected 2..4096; a volume 1 voxel thick cannot "
                                "be rendered)");
    p = attached("huge.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: 3 4 5000\nencoding: raw\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":4: size 5000 along z is out of range (expected 2..4096)");
    p = attached("zero.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: 0 4 5\nencoding: raw\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":4: size 0 along x");
    p = attached("neg.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: -3 4 5\nencoding: raw\n", VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":4: bad sizes");
    p = attached("over.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: 99999999999999999999999 4 5\nencoding: raw\n",
                 VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":4: size 18446744073709551615 along x is out of range");
}

static void error_bad_spacings(void)
{
    static const struct {
        const char *line, *phrase;
    } cases[] = {
        {"spacings: 1 0 1\n", ":6: bad spacing 0 along y (expected a number > 0 and <= 32767)"},
        {"spacings: -1 1 1\n", ":6: bad spacing -1 along x"},
        {"spacings: 1 1 nan\n", ":6: bad spacing nan along z"},
        {"spacings: inf 1 1\n", ":6: bad spacing inf along x"},
        {"spacings: 1 40000 1\n", ":6: bad spacing 40000 along y"},
        {"spacings: 1 1 1e-9\n", ":6: spacing 1e-09 along z is too small"},
        {"space directions: (0,0,0) (0,1,0) (0,0,1)\n", ":6: bad spacing 0 along x"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char header[512];
        snprintf(header, sizeof header, HEAD U8_FIELDS "%s", cases[i].line);
        const char *p = attached("spacing.nrrd", header, VF_VOXEL_U8, 0);
        fx_expect_error(p, NULL, p, cases[i].phrase);
        if (check_failed)
            return;
    }
}

static void error_header_runs_into_data(void)
{
    /* No blank line between header and binary data. */
    unsigned char data[FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    data[5] = 0;
    const char *p = fx_write("noblank.nrrd", HEAD U8_FIELDS, data, sizeof data);
    fx_expect_error(p, NULL, p, ":6: binary data in the header (is the blank line between header and data missing?)");
    char *text = malloc(70000 + 256);
    strcpy(text, HEAD "content: ");
    memset(text + strlen(text), 'a', 70000);
    strcpy(text + strlen(HEAD "content: ") + 70000, "\n" U8_FIELDS "\n");
    p = fx_write("longline.nrrd", text, data, sizeof data);
    free(text);
    fx_expect_error(p, NULL, p, ":2: line longer than 65536 bytes");
    p = fx_write("nodata.nrrd", HEAD U8_FIELDS, NULL, 0);
    fx_expect_error(p, NULL, p, "no data: the header has no 'data file' field and no blank line followed by data");
}

static void error_multi_file_data(void)
{
    const char *p = fx_write("list.nhdr", HEAD U8_FIELDS "data file: LIST\na.raw\nb.raw\n", NULL, 0);
    fx_expect_error(p, NULL, p, ":6: multi-file data ('data file: LIST') is not supported");
    p = fx_write("pattern.nhdr", HEAD U8_FIELDS "data file: slice%03d.raw 1 5 1\n", NULL, 0);
    fx_expect_error(p, NULL, p, ":6: multi-file data (a file name pattern) is not supported");
}

/* ---------------------------------------------------------------------------------------------------------- */
/* NRRD data errors */

static void error_size_mismatch(void)
{
    const char *p = attached_sized("more.nrrd", HEAD U8_FIELDS, +1);
    fx_expect_error(p, NULL, p, ": expected 60 bytes of voxel data, found 61");
    p = attached_sized("less.nrrd", HEAD U8_FIELDS, -1);
    fx_expect_error(p, NULL, p, ": truncated: expected 60 bytes of voxel data, found 59");
    p = attached_sized("none.nrrd", HEAD U8_FIELDS, -FX_COUNT);
    fx_expect_error(p, NULL, p, ": truncated: expected 60 bytes of voxel data, found 0");
    p = attached_sized("skipall.nrrd", HEAD U8_FIELDS "byte skip: 100\n", 0);
    fx_expect_error(p, NULL, p, "truncated: the data should start at byte");
}

/* A header that claims the largest volume (4096^3 int16, 128 GiB) over a few bytes of data: the data's size is
 * checked before the voxels are allocated (found by tests/fuzz; before, the reader allocated first and failed
 * "out of memory", or aborted under the sanitizers). Attached, detached and gzip'd. */
static void error_huge_sizes_without_data(void)
{
    const char *fields = HEAD "type: int16\ndimension: 3\nsizes: 4096 4096 4096\nendian: little\n";
    char header[256];
    snprintf(header, sizeof header, "%sencoding: raw\n", fields);
    const char *p = attached_sized("huge.nrrd", header, 0);
    fx_expect_error(p, NULL, p, FX_HUGE(": truncated: expected 137438953472 bytes of voxel data, found 60"));

    unsigned char data[FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    const char *raw = fx_write("huge.raw", NULL, data, FX_COUNT);
    snprintf(header, sizeof header, "%sencoding: raw\ndata file: huge.raw\n", fields);
    p = fx_write("huge.nhdr", header, NULL, 0);
    fx_expect_error(p, NULL, raw,
                    FX_HUGE(": truncated: expected 137438953472 bytes of voxel data, found 60 (data file named by"));

    size_t gz_n;
    unsigned char *gz = fx_gzip_bytes(data, FX_COUNT, &gz_n);
    snprintf(header, sizeof header, "%sencoding: gzip\n\n", fields);
    p = fx_write("huge-gz.nrrd", header, gz, gz_n);
    free(gz);
    fx_expect_error(p, NULL, p,
                    FX_HUGE(": truncated: expected 137438953472 bytes of voxel data after decompression, found 60"));
}

static void error_detached_data(void)
{
    const char *p = fx_write("lost.nhdr", HEAD U8_FIELDS "data file: missing.raw\n", NULL, 0);
    char both[600];
    snprintf(both, sizeof both, "lost.nhdr:6: cannot open data file %s: No such file or directory",
             fx_path("missing.raw"));
    fx_expect_error(p, NULL, p, both);

    unsigned char data[FX_COUNT];
    fx_bytes(VF_VOXEL_U8, 0, data);
    const char *raw = fx_write("short.raw", NULL, data, 50);
    p = fx_write("short.nhdr", HEAD U8_FIELDS "data file: short.raw\n", NULL, 0);
    fx_expect_error(p, NULL, raw, "truncated: expected 60 bytes of voxel data, found 50 (data file named by");
    fx_expect_error(p, NULL, "short.nhdr:6)", "truncated");

    p = fx_write("lines.nhdr", HEAD U8_FIELDS "line skip: 9\ndata file: short.raw\n", NULL, 0);
    fx_expect_error(p, NULL, raw, "truncated: line skip 9 passes the end of the file after 0 lines");
}

static void error_gzip(void)
{
    unsigned char data[FX_COUNT * 4];
    for (size_t i = 0; i < sizeof data; i++)
        data[i] = (unsigned char)(i * 37 + (i >> 3));
    size_t gz_n;
    unsigned char *gz = fx_gzip_bytes(data, FX_COUNT, &gz_n);
    const char *header = HEAD "type: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: gzip\n\n";

    const char *p = fx_write("cut.nrrd", header, gz, gz_n - 12);
    fx_expect_error(p, NULL, p, "gzip error: unexpected end of file (the compressed data is truncated)");
    unsigned char bad[1024];
    memcpy(bad, gz, gz_n);
    bad[gz_n - 5] ^= 0xff; /* the CRC in the gzip trailer */
    p = fx_write("crc.nrrd", header, bad, gz_n);
    fx_expect_error(p, NULL, p, "gzip error: ");
    memcpy(bad, gz, gz_n);
    bad[10] = 0xff; /* an invalid deflate block type */
    p = fx_write("corrupt.nrrd", header, bad, gz_n);
    fx_expect_error(p, NULL, p, "gzip error: invalid block type");
    memcpy(bad, gz, gz_n);
    memcpy(bad + gz_n, "garbage", 7);
    p = fx_write("trail.nrrd", header, bad, gz_n + 7);
    fx_expect_error(p, NULL, p, "gzip error: unexpected bytes after the end of the compressed data");
    p = fx_write("plain.nrrd", header, data, FX_COUNT);
    fx_expect_error(p, NULL, p, "gzip error: incorrect header check");
    free(gz);

    gz = fx_gzip_bytes(data, FX_COUNT - 10, &gz_n);
    p = fx_write("gzshort.nrrd", header, gz, gz_n);
    fx_expect_error(p, NULL, p, "truncated: expected 60 bytes of voxel data after decompression, found 50");
    free(gz);
    gz = fx_gzip_bytes(data, sizeof data, &gz_n);
    p = fx_write("gzlong.nrrd", header, gz, gz_n);
    fx_expect_error(p, NULL, p, "expected 60 bytes of voxel data after decompression, found at least 61");
    free(gz);

    p = attached("gzskip.nrrd", HEAD "type: uint8\ndimension: 3\nsizes: 3 4 5\nencoding: gzip\nbyte skip: -1\n",
                 VF_VOXEL_U8, 0);
    fx_expect_error(p, NULL, p, ":6: byte skip -1 works only with raw encoding");
}

CHECK_CASES({"nrrd_attached_uint8", nrrd_attached_uint8}, {"spacing_anisotropy_limit", spacing_anisotropy_limit},
            {"nrrd_detached_int16_big", nrrd_detached_int16_big},
            {"nrrd_detached_gzip_uint16_little", nrrd_detached_gzip_uint16_little},
            {"nrrd_attached_gzip_int8", nrrd_attached_gzip_int8},
            {"nrrd_gzip_two_members", nrrd_gzip_two_members},
            {"nrrd_type_spellings", nrrd_type_spellings},
            {"nrrd_ignored_fields_and_directions", nrrd_ignored_fields_and_directions},
            {"nrrd_spacings_win_over_directions", nrrd_spacings_win_over_directions},
            {"nrrd_line_and_byte_skip", nrrd_line_and_byte_skip},
            {"nrrd_byte_skip_minus_one", nrrd_byte_skip_minus_one},
            {"nrrd_gzip_byte_skip_after_decompression", nrrd_gzip_byte_skip_after_decompression},
            {"nrrd_absolute_data_file", nrrd_absolute_data_file},
            {"nrrd_recognised_by_content", nrrd_recognised_by_content},
            {"spacing_option_overrides_file", spacing_option_overrides_file},
            {"error_nonexistent_file", error_nonexistent_file},
            {"error_empty_file", error_empty_file},
            {"error_directory", error_directory},
            {"error_null_arguments", error_null_arguments},
            {"error_bad_magic", error_bad_magic},
            {"error_line_without_colon", error_line_without_colon},
            {"error_unknown_field", error_unknown_field},
            {"error_unparsable_values", error_unparsable_values},
            {"error_duplicate_field", error_duplicate_field},
            {"error_missing_required_fields", error_missing_required_fields},
            {"error_unsupported_type", error_unsupported_type},
            {"error_unsupported_encoding", error_unsupported_encoding},
            {"error_wrong_dimension", error_wrong_dimension},
            {"error_bad_sizes", error_bad_sizes},
            {"error_bad_spacings", error_bad_spacings},
            {"error_header_runs_into_data", error_header_runs_into_data},
            {"error_multi_file_data", error_multi_file_data},
            {"error_size_mismatch", error_size_mismatch},
            {"error_detached_data", error_detached_data},
            {"error_huge_sizes_without_data", error_huge_sizes_without_data},
            {"error_gzip", error_gzip});
CHECK_RUN("volume")
