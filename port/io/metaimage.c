/* SPDX-License-Identifier: MIT */
/* metaimage.c: the MetaImage reader (ITK/VTK's .mhd with its data file, or .mha with the data inside; raw or zlib;
 * 8- and 16-bit scalars in 3D; the patient orientation from TransformMatrix or AnatomicalOrientation). */

/*********************
 *      INCLUDES
 *********************/
#include "volume_internal.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

/*********************
 *      DEFINES
 *********************/
#define MAX_LINE 4096        /* longer header lines are an error (binary data without ElementDataFile before it) */
#define MAX_HEADER_LINES 256 /* a header has a few dozen lines; more means this is not one */
#define SHOWN 48             /* characters of a bad header value repeated in its message */
#define TYPES_EXPECTED "expected MET_UCHAR, MET_CHAR, MET_USHORT or MET_SHORT"

/**********************
 *      TYPES
 **********************/

typedef enum key_id {
    K_OBJECT_TYPE,
    K_NDIMS,
    K_DIM_SIZE,
    K_SPACING,
    K_ELEMENT_SIZE,
    K_TYPE,
    K_MSB,
    K_CHANNELS,
    K_BINARY,
    K_DATA_FILE,
    K_HEADER_SIZE,
    K_COMPRESSED,
    K_COMPRESSED_SIZE,
    K_MATRIX,
    K_ANATOMICAL,
    K_USED,
    K_IGNORED = K_USED
} key_id_t;

typedef struct header {
    const char *path;
    unsigned line;
    unsigned seen[K_USED];
    uint32_t dims[3];
    double spacing[3], element_size[3];
    vf_voxel_t type;
    int big_endian, compressed;
    int64_t header_size;      /* HeaderSize: bytes before the data; -1: the data is the end of the file */
    uint64_t compressed_size; /* CompressedDataSize, 0 when absent */
    double matrix[9];
    char anatomical[4];
    char data_file[1024];     /* ElementDataFile as written */
    uint64_t data_offset;     /* LOCAL: where the data starts in the header's file */
} header_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t read_header(header_t *h, FILE *file, char *err, size_t errlen);
static vfp_status_t parse_key(header_t *h, key_id_t id, const char *key, const char *value, char *err, size_t errlen);
static int parse_numbers(const char *value, double *out, int count);
static int parse_bool(const char *value, int *out);
static vfp_status_t check_header(header_t *h, vfp_volume_t *vol, char *err, size_t errlen);
static vfp_status_t read_data(header_t *h, vfp_volume_t *vol, char *err, size_t errlen);
static key_id_t key_lookup(const char *key);
static char *trim(char *s);

/**********************
 *  STATIC VARIABLES
 **********************/

/* Keys as MetaIO (ITK's metaImage.cxx, metaObject.cxx) writes them, compared without case; synonyms ITK reads too.
 * A key this reader does not know is a field some writer added: MetaIO keeps those as user fields, and so they are
 * read and ignored here. */
static const struct {
    const char *name;
    key_id_t id;
} keys[] = {
    {"ObjectType", K_OBJECT_TYPE}, {"NDims", K_NDIMS}, {"DimSize", K_DIM_SIZE}, {"ElementSpacing", K_SPACING},
    {"ElementSize", K_ELEMENT_SIZE}, {"ElementType", K_TYPE}, {"ElementByteOrderMSB", K_MSB},
    {"BinaryDataByteOrderMSB", K_MSB}, {"ElementNumberOfChannels", K_CHANNELS}, {"BinaryData", K_BINARY},
    {"ElementDataFile", K_DATA_FILE}, {"HeaderSize", K_HEADER_SIZE}, {"CompressedData", K_COMPRESSED},
    {"CompressedDataSize", K_COMPRESSED_SIZE}, {"TransformMatrix", K_MATRIX}, {"Rotation", K_MATRIX},
    {"Orientation", K_MATRIX}, {"AnatomicalOrientation", K_ANATOMICAL},
    /* read and ignored: where the volume is, and what it is */
    {"Offset", K_IGNORED}, {"Origin", K_IGNORED}, {"Position", K_IGNORED}, {"CenterOfRotation", K_IGNORED},
    {"Comment", K_IGNORED}, {"ObjectSubType", K_IGNORED}, {"Name", K_IGNORED}, {"ID", K_IGNORED},
    {"ParentID", K_IGNORED}, {"Color", K_IGNORED}, {"Modality", K_IGNORED}, {"ElementMin", K_IGNORED},
    {"ElementMax", K_IGNORED}, {"ElementOrigin", K_IGNORED}, {"SequenceID", K_IGNORED},
    {"AcquisitionDate", K_IGNORED}, {"FormTypeName", K_IGNORED}, {"ElementToIntensityFunctionSlope", K_IGNORED},
    {"ElementToIntensityFunctionOffset", K_IGNORED},
};

/* AnatomicalOrientation's letters in pairs along L-R, P-A, S-I: index / 2 is the LPS axis, and an even index
 * (R, A, I: the side an axis comes from, as ITK writes them) runs towards +L, +P, +S. */
static const char anatomical_letters[] = "RLAPIS";

static const struct {
    const char *name;
    int type; /* vf_voxel_t, or -1: a MetaIO type this renderer cannot use */
} types[] = {
    {"MET_UCHAR", VF_VOXEL_U8}, {"MET_CHAR", VF_VOXEL_I8}, {"MET_USHORT", VF_VOXEL_U16}, {"MET_SHORT", VF_VOXEL_I16},
    {"MET_UINT", -1}, {"MET_INT", -1}, {"MET_ULONG", -1}, {"MET_LONG", -1}, {"MET_ULONG_LONG", -1},
    {"MET_LONG_LONG", -1}, {"MET_FLOAT", -1}, {"MET_DOUBLE", -1}, {"MET_STRING", -1},
    {"MET_UCHAR_ARRAY", -1}, {"MET_CHAR_ARRAY", -1}, {"MET_USHORT_ARRAY", -1}, {"MET_SHORT_ARRAY", -1},
    {"MET_FLOAT_ARRAY", -1}, {"MET_DOUBLE_ARRAY", -1},
};

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

int vfpi_is_metaimage(const unsigned char *head, size_t n)
{
    /* The first key of every MetaIO header ITK, VTK and MeVisLab write. */
    static const char *const first[] = {"ObjectType", "NDims"};
    for (size_t i = 0; i < 2; i++) {
        size_t k = strlen(first[i]);
        if (n > k && memcmp(head, first[i], k) == 0 && (head[k] == ' ' || head[k] == '='))
            return 1;
    }
    return 0;
}

vfp_status_t vfpi_load_metaimage(vfp_volume_t *vol, const char *path, char *err, size_t errlen)
{
    header_t h;
    memset(&h, 0, sizeof h);
    h.path = path;
    FILE *file = fopen(path, "rb");
    if (!file)
        return vfpi_fail(err, errlen, path, 0, "cannot open: %s", strerror(errno));
    vfp_status_t rc = read_header(&h, file, err, errlen);
    fclose(file);
    if (rc == VFP_OK)
        rc = check_header(&h, vol, err, errlen);
    if (rc == VFP_OK)
        rc = read_data(&h, vol, err, errlen);
    return rc;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

/* "Key = Value" lines up to ElementDataFile, which ends the header (the data of LOCAL follows its line). */
static vfp_status_t read_header(header_t *h, FILE *file, char *err, size_t errlen)
{
    char line[MAX_LINE + 2];
    for (h->line = 1; h->line <= MAX_HEADER_LINES; h->line++) {
        size_t n = 0;
        int c;
        while ((c = getc(file)) != EOF && c != '\n') {
            if (c == 0)
                return vfpi_fail(err, errlen, h->path, h->line, "binary data in the header (expected 'Key = Value' "
                                 "lines ending with ElementDataFile)");
            if (n >= MAX_LINE)
                return vfpi_fail(err, errlen, h->path, h->line, "line longer than %d bytes (expected 'Key = Value' "
                                 "lines ending with ElementDataFile)", MAX_LINE);
            line[n++] = (char)c;
        }
        if (c == EOF && n == 0)
            return vfpi_fail(err, errlen, h->path, 0, "the header ends without ElementDataFile (expected "
                             "'ElementDataFile = LOCAL' or a data file's name as the last line)");
        if (n && line[n - 1] == '\r')
            n--;
        line[n] = 0;
        char *text = trim(line);
        if (!text[0])
            continue;
        char *eq = strchr(text, '=');
        if (!eq)
            return vfpi_fail(err, errlen, h->path, h->line, "expected 'Key = Value', found '%.*s'", SHOWN, text);
        *eq = 0;
        char *key = trim(text), *value = trim(eq + 1);
        key_id_t id = key_lookup(key);
        if (id != K_IGNORED) {
            if (h->seen[id])
                return vfpi_fail(err, errlen, h->path, h->line, "duplicate key '%s' (first on line %u)", key,
                                 h->seen[id]);
            h->seen[id] = h->line;
            if (parse_key(h, id, key, value, err, errlen))
                return VFP_ERR;
        }
        if (id == K_DATA_FILE) {
            off_t here = ftello(file);
            h->data_offset = here > 0 ? (uint64_t)here : 0;
            return VFP_OK;
        }
    }
    return vfpi_fail(err, errlen, h->path, 0, "more than %d header lines without ElementDataFile (is this a "
                     "MetaImage header?)", MAX_HEADER_LINES);
}

static vfp_status_t parse_key(header_t *h, key_id_t id, const char *key, const char *value, char *err, size_t errlen)
{
    double v[9];
    int b;
    switch (id) {
    case K_OBJECT_TYPE:
        if (strcasecmp(value, "Image") != 0)
            return vfpi_fail(err, errlen, h->path, h->line, "ObjectType '%.*s' is not supported (expected Image)",
                             SHOWN, value);
        return VFP_OK;
    case K_NDIMS:
        if (parse_numbers(value, v, 1) != 1 || v[0] != floor(v[0]))
            return vfpi_fail(err, errlen, h->path, h->line, "bad NDims '%.*s' (expected 3)", SHOWN, value);
        if (v[0] != 3)
            return vfpi_fail(err, errlen, h->path, h->line, "NDims %g is not supported (expected 3: a 3D volume)",
                             v[0]);
        return VFP_OK;
    case K_DIM_SIZE: {
        if (!h->seen[K_NDIMS])
            return vfpi_fail(err, errlen, h->path, h->line, "DimSize before NDims (expected NDims = 3 first)");
        if (parse_numbers(value, v, 3) != 3)
            return vfpi_fail(err, errlen, h->path, h->line, "bad DimSize '%.*s' (expected three whole numbers)",
                             SHOWN, value);
        uint64_t d[3];
        for (int a = 0; a < 3; a++) {
            if (!(v[a] >= 0 && v[a] < 1e15) || v[a] != floor(v[a]))
                return vfpi_fail(err, errlen, h->path, h->line, "bad DimSize '%.*s' (expected three whole numbers)",
                                 SHOWN, value);
            d[a] = (uint64_t)v[a];
        }
        if (vfpi_check_dims(d, h->path, h->line, err, errlen))
            return VFP_ERR;
        for (int a = 0; a < 3; a++)
            h->dims[a] = (uint32_t)d[a];
        return VFP_OK;
    }
    case K_SPACING:
    case K_ELEMENT_SIZE: {
        double *out = id == K_SPACING ? h->spacing : h->element_size;
        if (parse_numbers(value, out, 3) != 3)
            return vfpi_fail(err, errlen, h->path, h->line, "bad %s '%.*s' (expected three numbers)", key, SHOWN,
                             value);
        for (int a = 0; a < 3; a++)
            if (vfpi_check_spacing(out[a], a, h->path, h->line, err, errlen))
                return VFP_ERR;
        return VFP_OK;
    }
    case K_TYPE:
        for (size_t i = 0; i < sizeof types / sizeof types[0]; i++) {
            if (strcasecmp(value, types[i].name) != 0)
                continue;
            if (types[i].type < 0)
                return vfpi_fail(err, errlen, h->path, h->line, "unsupported ElementType '%s' (" TYPES_EXPECTED ")",
                                 value);
            h->type = (vf_voxel_t)types[i].type;
            return VFP_OK;
        }
        return vfpi_fail(err, errlen, h->path, h->line, "unknown ElementType '%.*s' (" TYPES_EXPECTED ")", SHOWN,
                         value);
    case K_MSB:
        if (!parse_bool(value, &h->big_endian))
            return vfpi_fail(err, errlen, h->path, h->line, "bad %s '%.*s' (expected True or False)", key, SHOWN,
                             value);
        return VFP_OK;
    case K_CHANNELS:
        if (parse_numbers(value, v, 1) != 1 || v[0] != 1)
            return vfpi_fail(err, errlen, h->path, h->line, "ElementNumberOfChannels '%.*s' is not supported "
                             "(expected 1: scalar voxels)", SHOWN, value);
        return VFP_OK;
    case K_BINARY:
        if (!parse_bool(value, &b))
            return vfpi_fail(err, errlen, h->path, h->line, "bad BinaryData '%.*s' (expected True or False)", SHOWN,
                             value);
        if (!b)
            return vfpi_fail(err, errlen, h->path, h->line, "BinaryData = False (text voxels) is not supported "
                             "(expected binary data)");
        return VFP_OK;
    case K_DATA_FILE:
        if (!value[0])
            return vfpi_fail(err, errlen, h->path, h->line, "empty ElementDataFile (expected LOCAL or a file name)");
        if (strcasecmp(value, "LIST") == 0 || strncasecmp(value, "LIST ", 5) == 0)
            return vfpi_fail(err, errlen, h->path, h->line, "ElementDataFile = LIST (one file per slice) is not "
                             "supported (expected LOCAL or one data file)");
        if (strchr(value, '%') && strchr(value, ' '))
            return vfpi_fail(err, errlen, h->path, h->line, "a file name pattern in ElementDataFile (one file per "
                             "slice) is not supported (expected LOCAL or one data file)");
        if (strlen(value) >= sizeof h->data_file)
            return vfpi_fail(err, errlen, h->path, h->line, "ElementDataFile is longer than %zu characters",
                             sizeof h->data_file - 1);
        strcpy(h->data_file, value);
        return VFP_OK;
    case K_HEADER_SIZE:
        if (parse_numbers(value, v, 1) != 1 || v[0] != floor(v[0]) || v[0] < -1 || v[0] > 1e15)
            return vfpi_fail(err, errlen, h->path, h->line, "bad HeaderSize '%.*s' (expected a whole number of "
                             "bytes >= 0, or -1 for data at the end of the file)", SHOWN, value);
        h->header_size = (int64_t)v[0];
        return VFP_OK;
    case K_COMPRESSED:
        if (!parse_bool(value, &h->compressed))
            return vfpi_fail(err, errlen, h->path, h->line, "bad CompressedData '%.*s' (expected True or False)",
                             SHOWN, value);
        return VFP_OK;
    case K_COMPRESSED_SIZE:
        if (parse_numbers(value, v, 1) != 1 || v[0] != floor(v[0]) || v[0] < 1 || v[0] > 1e15)
            return vfpi_fail(err, errlen, h->path, h->line, "bad CompressedDataSize '%.*s' (expected a whole number "
                             "of bytes)", SHOWN, value);
        h->compressed_size = (uint64_t)v[0];
        return VFP_OK;
    case K_MATRIX:
        if (parse_numbers(value, h->matrix, 9) != 9)
            return vfpi_fail(err, errlen, h->path, h->line, "bad %s '%.*s' (expected nine numbers: three direction "
                             "vectors)", key, SHOWN, value);
        return VFP_OK;
    case K_ANATOMICAL: {
        /* Three letters, one of R/L, A/P, S/I each; '?' (unknown) leaves the volume as stored. */
        size_t n = strlen(value);
        int axes_seen = 0;
        for (size_t i = 0; i < n && n == 3; i++) {
            const char *p = value[i] ? strchr(anatomical_letters, toupper((unsigned char)value[i])) : NULL;
            if (!p)
                break;
            axes_seen |= 1 << ((p - anatomical_letters) / 2);
        }
        if (strchr(value, '?') && n == 3)
            return VFP_OK;
        if (n != 3 || axes_seen != 7)
            return vfpi_fail(err, errlen, h->path, h->line, "bad AnatomicalOrientation '%.*s' (expected three "
                             "letters, one of R or L, A or P, S or I each, such as RAI)", SHOWN, value);
        for (int i = 0; i < 3; i++)
            h->anatomical[i] = (char)toupper((unsigned char)value[i]);
        return VFP_OK;
    }
    default:
        return VFP_OK;
    }
}

/* Exactly `count` numbers separated by white space; returns how many there were (count + 1 if more). */
static int parse_numbers(const char *value, double *out, int count)
{
    int n = 0;
    const char *p = value;
    while (*p) {
        char *end;
        double v = strtod(p, &end);
        if (end == p || (*end && !isspace((unsigned char)*end)) || !isfinite(v))
            return -1;
        if (n == count)
            return count + 1;
        out[n++] = v;
        for (p = end; isspace((unsigned char)*p); p++)
            ;
    }
    return n;
}

static int parse_bool(const char *value, int *out)
{
    if (strcasecmp(value, "True") == 0 || strcmp(value, "1") == 0) {
        *out = 1;
        return 1;
    }
    if (strcasecmp(value, "False") == 0 || strcmp(value, "0") == 0) {
        *out = 0;
        return 1;
    }
    return 0;
}

static vfp_status_t check_header(header_t *h, vfp_volume_t *vol, char *err, size_t errlen)
{
    static const struct {
        key_id_t id;
        const char *name;
    } required[] = {{K_NDIMS, "NDims"}, {K_DIM_SIZE, "DimSize"}, {K_TYPE, "ElementType"}};
    for (size_t i = 0; i < sizeof required / sizeof required[0]; i++)
        if (!h->seen[required[i].id])
            return vfpi_fail(err, errlen, h->path, 0, "missing key '%s'", required[i].name);
    if (h->header_size < 0 && h->compressed)
        return vfpi_fail(err, errlen, h->path, h->seen[K_HEADER_SIZE], "HeaderSize -1 works only with uncompressed "
                         "data");
    for (int a = 0; a < 3; a++)
        vol->spacing[a] = h->seen[K_SPACING] ? h->spacing[a] : h->seen[K_ELEMENT_SIZE] ? h->element_size[a] : 1.0;

    /* TransformMatrix, as ITK reads it: row a is the LPS direction of axis a. Without it, AnatomicalOrientation
     * as ITK writes it: each letter the side an axis comes from, so RAI (ITK's name for the identity) runs x
     * towards L, y towards P, z towards S. */
    double axes[3][3];
    if (h->seen[K_MATRIX]) {
        for (int a = 0; a < 3; a++)
            for (int c = 0; c < 3; c++)
                axes[a][c] = h->matrix[3 * a + c];
        return vfpi_set_direction(vol, axes, "TransformMatrix", h->path, h->seen[K_MATRIX], err, errlen);
    }
    if (h->anatomical[0]) {
        for (int a = 0; a < 3; a++) {
            int index = (int)(strchr(anatomical_letters, h->anatomical[a]) - anatomical_letters), axis = index / 2;
            for (int c = 0; c < 3; c++)
                axes[a][c] = c == axis ? (index % 2 ? -1.0 : 1.0) : 0.0;
        }
        return vfpi_set_direction(vol, axes, "AnatomicalOrientation", h->path, h->seen[K_ANATOMICAL], err, errlen);
    }
    return VFP_OK;
}

static vfp_status_t read_data(header_t *h, vfp_volume_t *vol, char *err, size_t errlen)
{
    vfpi_source_t src = {.path = h->path, .byte_skip = h->header_size, .gzip = h->compressed};
    char *data_path = NULL;
    char owner[VFP_ERR_LEN], note[VFP_ERR_LEN + 32];
    if (strcasecmp(h->data_file, "LOCAL") == 0) {
        src.offset = h->data_offset;
    } else {
        /* A relative data file name is relative to the header's directory, not the working directory. */
        const char *slash = strrchr(h->path, '/');
        size_t dir = h->data_file[0] == '/' || !slash ? 0 : (size_t)(slash - h->path) + 1;
        data_path = malloc(dir + strlen(h->data_file) + 1);
        if (!data_path)
            return vfpi_fail(err, errlen, h->path, 0, "out of memory");
        memcpy(data_path, h->path, dir);
        strcpy(data_path + dir, h->data_file);
        snprintf(owner, sizeof owner, "%s:%u", h->path, h->seen[K_DATA_FILE]);
        snprintf(note, sizeof note, "data file named by %s", owner);
        src.path = data_path;
        src.owner = owner;
        src.note = note;
    }
    vfp_status_t rc = VFP_OK;
    if (h->compressed && h->compressed_size) {
        /* The compressed bytes the header promises must be there (the stream reader finds any surplus). */
        struct stat st;
        if (stat(src.path, &st) == 0 && S_ISREG(st.st_mode)) {
            uint64_t start = src.offset + (uint64_t)(h->header_size > 0 ? h->header_size : 0);
            uint64_t have = (uint64_t)st.st_size > start ? (uint64_t)st.st_size - start : 0;
            if (have < h->compressed_size)
                rc = vfpi_fail(err, errlen, h->path, h->seen[K_COMPRESSED_SIZE], "truncated: CompressedDataSize is "
                               "%llu bytes, but the file holds %llu after the header", 
                               (unsigned long long)h->compressed_size, (unsigned long long)have);
        }
    }
    if (rc == VFP_OK && h->compressed && h->header_size > 0) {
        /* HeaderSize skips bytes of the file, before the compressed data starts. */
        src.offset += (uint64_t)h->header_size;
        src.byte_skip = 0;
    }
    size_t bytes;
    if (rc == VFP_OK)
        rc = vfpi_read_voxels(vol, h->dims, h->type, &src, &bytes, err, errlen);
    free(data_path);
    if (rc)
        return rc;
    if (vfpi_type_bytes(h->type) == 2)
        vfpi_to_native16(vol->data, bytes / 2, h->big_endian);
    return VFP_OK;
}

static key_id_t key_lookup(const char *key)
{
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        if (strcasecmp(key, keys[i].name) == 0)
            return keys[i].id;
    return K_IGNORED;
}

/* Strips white space at both ends, in place. */
static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n && isspace((unsigned char)s[n - 1]))
        s[--n] = 0;
    return s;
}
