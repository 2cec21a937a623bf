/* SPDX-License-Identifier: MIT */
/* nrrd.c: the NRRD reader (NRRD0001..0005; attached or detached data; raw, gzip, ascii or hex; 8- and 16-bit scalars
 * in 3D; the patient orientation from space and space directions). */

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

/*********************
 *      DEFINES
 *********************/
#define MAX_LINE (64 * 1024) /* longer header lines are an error (a missing blank line before binary data) */
#define SHOWN 48             /* characters of a bad header line repeated in its message */
#define TYPES_EXPECTED "expected int8, uint8, int16 or uint16"

/**********************
 *      TYPES
 **********************/

/* The fields this reader uses; every other field NRRD defines is read and ignored (F_IGNORED). */
typedef enum field_id {
    F_TYPE,
    F_DIMENSION,
    F_SIZES,
    F_SPACINGS,
    F_DIRECTIONS,
    F_ENDIAN,
    F_ENCODING,
    F_LINE_SKIP,
    F_BYTE_SKIP,
    F_DATA_FILE,
    F_SPACE,
    F_USED,
    F_IGNORED = F_USED
} field_id_t;

/* How the voxel data is written. */
typedef enum encoding { ENC_RAW, ENC_GZIP, ENC_ASCII, ENC_HEX } encoding_t;

/* What read_line found. */
typedef enum line_result {
    LINE_READ,     /* a line, in the buffer */
    LINE_END,      /* the end of the file, nothing read */
    LINE_TOO_LONG, /* longer than the buffer */
    LINE_BINARY,   /* a NUL byte in it */
} line_result_t;

typedef struct header {
    const char *path;
    unsigned line;           /* the line being read, 1-based */
    unsigned seen[F_USED];   /* the line of each used field, 0 while absent */
    vf_voxel_t type;
    uint32_t sizes[3];
    double spacings[3];
    double directions[3];    /* lengths of the space direction vectors */
    double vectors[3][4];    /* the space direction vectors, in the space's coordinates */
    int vector_len[3];       /* components of each vector; 0 for "none" */
    int space;               /* a patient space (SPACE_*), or SPACE_NONE */
    encoding_t encoding;
    int big_endian;
    uint32_t line_skip;
    int64_t byte_skip;
    char *data_file;         /* as written in the header */
    int attached;            /* a blank line ended the header: data follows at data_offset */
    uint64_t data_offset;
} header_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t read_header(header_t *h, FILE *file, char *line, char *err, size_t errlen);
static line_result_t read_line(FILE *file, char *buf, size_t cap);
static vfp_status_t parse_line(header_t *h, char *line, char *err, size_t errlen);
static vfp_status_t parse_field(header_t *h, field_id_t id, const char *name, char *value, char *err, size_t errlen);
static vfp_status_t parse_type(header_t *h, const char *value, char *err, size_t errlen);
static vfp_status_t parse_sizes(header_t *h, const char *value, char *err, size_t errlen);
static vfp_status_t parse_doubles(header_t *h, const char *name, const char *value, double out[3], char *err,
                                  size_t errlen);
static vfp_status_t parse_directions(header_t *h, const char *value, char *err, size_t errlen);
static int parse_int(const char *value, long long min, long long max, long long *out);
static vfp_status_t check_header(header_t *h, vfp_volume_t *vol, char *err, size_t errlen);
static vfp_status_t read_voxels(header_t *h, vfp_volume_t *vol, char *err, size_t errlen);
static vfp_status_t read_text_voxels(header_t *h, const vfpi_source_t *src, vfp_volume_t *vol, char *err,
                                     size_t errlen);
static vfp_status_t parse_space(header_t *h, const char *value, char *err, size_t errlen);
static vfp_status_t orientation(header_t *h, vfp_volume_t *vol, char *err, size_t errlen);
static field_id_t field_lookup(const char *name, int *known);
static char *trim(char *s);

/**********************
 *  STATIC VARIABLES
 **********************/

/* Field names as NRRD0005 spells them (teem's readers also accept the spellings without spaces). */
static const struct {
    const char *name;
    field_id_t id;
} fields[] = {
    {"type", F_TYPE}, {"dimension", F_DIMENSION}, {"sizes", F_SIZES}, {"spacings", F_SPACINGS},
    {"space directions", F_DIRECTIONS}, {"spacedirections", F_DIRECTIONS}, {"endian", F_ENDIAN},
    {"encoding", F_ENCODING}, {"line skip", F_LINE_SKIP}, {"lineskip", F_LINE_SKIP}, {"byte skip", F_BYTE_SKIP},
    {"byteskip", F_BYTE_SKIP}, {"data file", F_DATA_FILE}, {"datafile", F_DATA_FILE}, {"space", F_SPACE},
    /* fields this renderer does not need, read and ignored */
    {"content", F_IGNORED}, {"number", F_IGNORED}, {"block size", F_IGNORED}, {"blocksize", F_IGNORED},
    {"thicknesses", F_IGNORED}, {"axis mins", F_IGNORED}, {"axismins", F_IGNORED}, {"axis maxs", F_IGNORED},
    {"axismaxs", F_IGNORED}, {"centers", F_IGNORED}, {"centerings", F_IGNORED}, {"kinds", F_IGNORED},
    {"labels", F_IGNORED}, {"units", F_IGNORED}, {"min", F_IGNORED}, {"max", F_IGNORED}, {"old min", F_IGNORED},
    {"oldmin", F_IGNORED}, {"old max", F_IGNORED}, {"oldmax", F_IGNORED}, {"sample units", F_IGNORED},
    {"sampleunits", F_IGNORED}, {"space dimension", F_IGNORED}, {"spacedimension", F_IGNORED},
    {"space units", F_IGNORED}, {"spaceunits", F_IGNORED}, {"space origin", F_IGNORED}, {"spaceorigin", F_IGNORED},
    {"measurement frame", F_IGNORED}, {"measurementframe", F_IGNORED},
};

/* Every type spelling NRRD defines; supported < 0 marks the types this renderer cannot use. */
static const struct {
    const char *name;
    int type; /* vf_voxel_t, or -1 */
} types[] = {
    {"signed char", VF_VOXEL_I8}, {"int8", VF_VOXEL_I8}, {"int8_t", VF_VOXEL_I8},
    {"uchar", VF_VOXEL_U8}, {"unsigned char", VF_VOXEL_U8}, {"uint8", VF_VOXEL_U8}, {"uint8_t", VF_VOXEL_U8},
    {"short", VF_VOXEL_I16}, {"short int", VF_VOXEL_I16}, {"signed short", VF_VOXEL_I16},
    {"signed short int", VF_VOXEL_I16}, {"int16", VF_VOXEL_I16}, {"int16_t", VF_VOXEL_I16},
    {"ushort", VF_VOXEL_U16}, {"unsigned short", VF_VOXEL_U16}, {"unsigned short int", VF_VOXEL_U16},
    {"uint16", VF_VOXEL_U16}, {"uint16_t", VF_VOXEL_U16},
    {"int", -1}, {"signed int", -1}, {"int32", -1}, {"int32_t", -1},
    {"uint", -1}, {"unsigned int", -1}, {"uint32", -1}, {"uint32_t", -1},
    {"longlong", -1}, {"long long", -1}, {"long long int", -1}, {"signed long long", -1},
    {"signed long long int", -1}, {"int64", -1}, {"int64_t", -1},
    {"ulonglong", -1}, {"unsigned long long", -1}, {"unsigned long long int", -1}, {"uint64", -1},
    {"uint64_t", -1}, {"float", -1}, {"double", -1}, {"block", -1},
};

/* The patient spaces NRRD names, and how each maps to LPS: the sign of each coordinate. The scanner and
 * handedness-only spaces ("scanner-xyz", "3D-right-handed") say nothing about the patient. */
enum { SPACE_NONE = -1 };
static const struct {
    const char *name;
    int dim;        /* components of a space direction */
    int sign[3];    /* LPS = sign * the space's coordinates */
} spaces[] = {
    {"left-posterior-superior", 3, {1, 1, 1}},   {"LPS", 3, {1, 1, 1}},
    {"right-anterior-superior", 3, {-1, -1, 1}}, {"RAS", 3, {-1, -1, 1}},
    {"left-anterior-superior", 3, {1, -1, 1}},   {"LAS", 3, {1, -1, 1}},
    {"left-posterior-superior-time", 4, {1, 1, 1}},   {"LPST", 4, {1, 1, 1}},
    {"right-anterior-superior-time", 4, {-1, -1, 1}}, {"RAST", 4, {-1, -1, 1}},
    {"left-anterior-superior-time", 4, {1, -1, 1}},   {"LAST", 4, {1, -1, 1}},
};
static const char *const other_spaces[] = {"scanner-xyz", "scanner-xyz-time", "3D-right-handed", "3D-left-handed",
                                           "3D-right-handed-time", "3D-left-handed-time"};

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

vfp_status_t vfpi_load_nrrd(vfp_volume_t *vol, const char *path, char *err, size_t errlen)
{
    header_t h;
    memset(&h, 0, sizeof h);
    h.path = path;
    char *line = malloc(MAX_LINE + 1);
    FILE *file = vfpi_fopen(path);
    vfp_status_t rc;
    if (!line)
        rc = vfpi_fail(err, errlen, path, 0, "out of memory");
    else if (!file)
        rc = vfpi_fail(err, errlen, path, 0, "cannot open: %s", strerror(errno));
    else
        rc = read_header(&h, file, line, err, errlen);
    if (file)
        fclose(file);
    free(line);
    if (rc == VFP_OK)
        rc = check_header(&h, vol, err, errlen);
    if (rc == VFP_OK)
        rc = orientation(&h, vol, err, errlen);
    if (rc == VFP_OK)
        rc = read_voxels(&h, vol, err, errlen);
    free(h.data_file);
    return rc;
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

/* The magic line, then fields until a blank line (attached data follows) or the end of the file (detached). */
static vfp_status_t read_header(header_t *h, FILE *file, char *line, char *err, size_t errlen)
{
    h->line = 1;
    line_result_t r = read_line(file, line, MAX_LINE + 1);
    if (r != LINE_READ || !line[0])
        return vfpi_fail(err, errlen, h->path, 1, "bad magic: not a text line (expected NRRD0001..NRRD0005)");
    if (strlen(line) != 8 || strncmp(line, "NRRD000", 7) != 0 || line[7] < '1' || line[7] > '5')
        return vfpi_fail(err, errlen, h->path, 1, "bad magic '%.*s' (expected NRRD0001..NRRD0005)", SHOWN, line);
    for (;;) {
        h->line++;
        r = read_line(file, line, MAX_LINE + 1);
        if (r == LINE_END)
            return VFP_OK;
        if (r == LINE_TOO_LONG)
            return vfpi_fail(err, errlen, h->path, h->line, "line longer than %d bytes (is the blank line "
                             "between header and data missing?)", MAX_LINE);
        if (r == LINE_BINARY)
            return vfpi_fail(err, errlen, h->path, h->line, "binary data in the header (is the blank line "
                             "between header and data missing?)");
        if (line[0] == 0) {
            off_t here = ftello(file);
            h->attached = 1;
            h->data_offset = here > 0 ? (uint64_t)here : 0;
            return VFP_OK;
        }
        if (line[0] == '#')
            continue;
        if (parse_line(h, line, err, errlen))
            return VFP_ERR;
    }
}

/* One line without its "\n" or "\r\n". */
static line_result_t read_line(FILE *file, char *buf, size_t cap)
{
    size_t n = 0;
    int c, any = 0, binary = 0;
    buf[0] = 0;
    while ((c = getc(file)) != EOF) {
        any = 1;
        if (c == '\n')
            break;
        if (c == 0)
            binary = 1;
        if (n + 1 >= cap)
            return LINE_TOO_LONG;
        buf[n++] = (char)c;
    }
    if (n && buf[n - 1] == '\r')
        n--;
    buf[n] = 0;
    if (binary)
        return LINE_BINARY;
    return any ? LINE_READ : LINE_END;
}

/* "field: value", or "key:=value" (ignored). */
static vfp_status_t parse_line(header_t *h, char *line, char *err, size_t errlen)
{
    char *colon = strchr(line, ':');
    if (!colon)
        return vfpi_fail(err, errlen, h->path, h->line, "expected 'field: value', found '%.*s'", SHOWN, line);
    if (colon[1] == '=')
        return VFP_OK;
    *colon = 0;
    char *name = trim(line), *value = trim(colon + 1);
    int known;
    field_id_t id = field_lookup(name, &known);
    if (!known)
        return vfpi_fail(err, errlen, h->path, h->line, "unknown field '%.*s'", SHOWN, name);
    if (id == F_IGNORED)
        return VFP_OK;
    if (h->seen[id])
        return vfpi_fail(err, errlen, h->path, h->line, "duplicate field '%s' (first on line %u)", name,
                         h->seen[id]);
    h->seen[id] = h->line;
    return parse_field(h, id, name, value, err, errlen);
}

static vfp_status_t parse_field(header_t *h, field_id_t id, const char *name, char *value, char *err, size_t errlen)
{
    long long v;
    switch (id) {
    case F_TYPE:
        return parse_type(h, value, err, errlen);
    case F_DIMENSION:
        if (!parse_int(value, 0, 1 << 20, &v))
            return vfpi_fail(err, errlen, h->path, h->line, "bad dimension '%.*s' (expected 3)", SHOWN, value);
        if (v != 3)
            return vfpi_fail(err, errlen, h->path, h->line, "dimension %lld is not supported (expected 3: a "
                             "scalar 3D volume)", v);
        return VFP_OK;
    case F_SIZES:
        return parse_sizes(h, value, err, errlen);
    case F_SPACINGS:
        return parse_doubles(h, name, value, h->spacings, err, errlen);
    case F_DIRECTIONS:
        return parse_directions(h, value, err, errlen);
    case F_ENDIAN:
        if (strcasecmp(value, "little") == 0 || strcasecmp(value, "big") == 0) {
            h->big_endian = strcasecmp(value, "big") == 0;
            return VFP_OK;
        }
        return vfpi_fail(err, errlen, h->path, h->line, "unknown endian '%.*s' (expected little or big)", SHOWN,
                         value);
    case F_ENCODING:
        if (strcasecmp(value, "raw") == 0)
            h->encoding = ENC_RAW;
        else if (strcasecmp(value, "gzip") == 0 || strcasecmp(value, "gz") == 0)
            h->encoding = ENC_GZIP;
        else if (strcasecmp(value, "ascii") == 0 || strcasecmp(value, "text") == 0 || strcasecmp(value, "txt") == 0)
            h->encoding = ENC_ASCII;
        else if (strcasecmp(value, "hex") == 0)
            h->encoding = ENC_HEX;
        else if (strcasecmp(value, "bzip2") == 0 || strcasecmp(value, "bz2") == 0)
            /* bzip2 would be a library for one rare encoding; the data converts losslessly in one command. */
            return vfpi_fail(err, errlen, h->path, h->line, "unsupported encoding '%s' (supported: raw, gzip, ascii, "
                             "hex; convert with 'unu save -e gzip', or bunzip2 the data file and say 'encoding: raw')",
                             value);
        else if (strcasecmp(value, "zrl") == 0)
            return vfpi_fail(err, errlen, h->path, h->line, "unsupported encoding '%s' (supported: raw, gzip, ascii, "
                             "hex)", value);
        else
            return vfpi_fail(err, errlen, h->path, h->line, "unknown encoding '%.*s' (supported: raw, gzip, ascii, "
                             "hex)", SHOWN, value);
        return VFP_OK;
    case F_SPACE:
        return parse_space(h, value, err, errlen);
    case F_LINE_SKIP:
        if (!parse_int(value, 0, UINT32_MAX, &v))
            return vfpi_fail(err, errlen, h->path, h->line, "bad line skip '%.*s' (expected a whole number >= 0)",
                             SHOWN, value);
        h->line_skip = (uint32_t)v;
        return VFP_OK;
    case F_BYTE_SKIP:
        if (!parse_int(value, -1, INT64_MAX, &v))
            return vfpi_fail(err, errlen, h->path, h->line, "bad byte skip '%.*s' (expected a whole number >= 0, "
                             "or -1 for data at the end of the file)", SHOWN, value);
        h->byte_skip = v;
        return VFP_OK;
    case F_DATA_FILE:
        /* One file only: the multi-file forms ("LIST", or a printf pattern with min max step) are not. */
        if (!value[0])
            return vfpi_fail(err, errlen, h->path, h->line, "empty data file name");
        if (strncmp(value, "LIST", 4) == 0 && (value[4] == 0 || isspace((unsigned char)value[4])))
            return vfpi_fail(err, errlen, h->path, h->line, "multi-file data ('data file: LIST') is not supported "
                             "(expected one data file)");
        if (strchr(value, '%') && strchr(value, ' '))
            return vfpi_fail(err, errlen, h->path, h->line, "multi-file data (a file name pattern) is not "
                             "supported (expected one data file)");
        h->data_file = strdup(value);
        if (!h->data_file)
            return vfpi_fail(err, errlen, h->path, h->line, "out of memory");
        return VFP_OK;
    default:
        return VFP_OK;
    }
}

static vfp_status_t parse_type(header_t *h, const char *value, char *err, size_t errlen)
{
    /* Compare with single spaces and in lower case: "unsigned  Char" is "unsigned char". */
    char norm[64];
    size_t n = 0;
    for (const char *p = value; *p && n + 1 < sizeof norm; p++) {
        if (isspace((unsigned char)*p)) {
            if (n && norm[n - 1] != ' ')
                norm[n++] = ' ';
        } else {
            norm[n++] = (char)tolower((unsigned char)*p);
        }
    }
    while (n && norm[n - 1] == ' ')
        n--;
    norm[n] = 0;
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++) {
        if (strcmp(norm, types[i].name) != 0)
            continue;
        if (types[i].type < 0)
            return vfpi_fail(err, errlen, h->path, h->line, "unsupported type '%s' (" TYPES_EXPECTED ")", value);
        h->type = (vf_voxel_t)types[i].type;
        return VFP_OK;
    }
    if (strcmp(norm, "char") == 0)
        return vfpi_fail(err, errlen, h->path, h->line, "type 'char' is ambiguous in NRRD (expected 'signed char' "
                         "or 'uchar')");
    return vfpi_fail(err, errlen, h->path, h->line, "unknown type '%.*s' (" TYPES_EXPECTED ")", SHOWN, value);
}

static vfp_status_t parse_sizes(header_t *h, const char *value, char *err, size_t errlen)
{
    uint64_t d[3];
    int n = 0;
    const char *p = value;
    while (*p) {
        char *end;
        errno = 0;
        unsigned long long v = isdigit((unsigned char)*p) ? strtoull(p, &end, 10) : 0;
        if (!isdigit((unsigned char)*p) || (*end && !isspace((unsigned char)*end)))
            return vfpi_fail(err, errlen, h->path, h->line, "bad sizes '%.*s' (expected three whole numbers)",
                             SHOWN, value);
        if (n < 3)
            d[n] = errno == ERANGE ? UINT64_MAX : v;
        n++;
        for (p = end; isspace((unsigned char)*p); p++)
            ;
    }
    if (n != 3)
        return vfpi_fail(err, errlen, h->path, h->line, "sizes has %d value%s (expected 3, one per axis)", n,
                         n == 1 ? "" : "s");
    if (vfpi_check_dims(d, h->path, h->line, err, errlen))
        return VFP_ERR;
    for (int a = 0; a < 3; a++)
        h->sizes[a] = (uint32_t)d[a];
    return VFP_OK;
}

/* Three numbers (strtod's spellings, so "nan" parses and is then refused by the spacing check). */
static vfp_status_t parse_doubles(header_t *h, const char *name, const char *value, double out[3], char *err,
                                  size_t errlen)
{
    int n = 0;
    const char *p = value;
    while (*p) {
        char *end;
        double v = strtod(p, &end);
        if (end == p || (*end && !isspace((unsigned char)*end)))
            return vfpi_fail(err, errlen, h->path, h->line, "bad %s '%.*s' (expected three numbers)", name, SHOWN,
                             value);
        if (n < 3)
            out[n] = v;
        n++;
        for (p = end; isspace((unsigned char)*p); p++)
            ;
    }
    if (n != 3)
        return vfpi_fail(err, errlen, h->path, h->line, "%s has %d value%s (expected 3, one per axis)", name, n,
                         n == 1 ? "" : "s");
    return VFP_OK;
}

/* "(x,y,z) (x,y,z) (x,y,z)", any vector may be "none"; a spacing is the length of its axis's vector. */
static vfp_status_t parse_directions(header_t *h, const char *value, char *err, size_t errlen)
{
    int n = 0;
    const char *p = value;
    while (*p) {
        double length = 1.0;
        int comps = 0;
        if (strncmp(p, "none", 4) == 0 && (p[4] == 0 || isspace((unsigned char)p[4]))) {
            p += 4;
        } else if (*p == '(') {
            double sum = 0.0;
            p++;
            for (;;) {
                char *end;
                double v = strtod(p, &end);
                if (end == p)
                    goto bad;
                sum += v * v;
                if (n < 3 && comps < 4)
                    h->vectors[n][comps] = v;
                comps++;
                for (p = end; isspace((unsigned char)*p); p++)
                    ;
                if (*p == ',') {
                    p++;
                } else if (*p == ')') {
                    p++;
                    break;
                } else {
                    goto bad;
                }
            }
            length = sqrt(sum);
        } else {
            goto bad;
        }
        if (n < 3) {
            h->directions[n] = length;
            h->vector_len[n] = comps;
        }
        n++;
        if (*p && !isspace((unsigned char)*p))
            goto bad;
        while (isspace((unsigned char)*p))
            p++;
    }
    if (n == 3)
        return VFP_OK;
bad:
    return vfpi_fail(err, errlen, h->path, h->line, "bad space directions '%.*s' (expected three vectors such as "
                     "(1,0,0) (0,1,0) (0,0,1))", SHOWN, value);
}

static int parse_int(const char *value, long long min, long long max, long long *out)
{
    char *end;
    errno = 0;
    long long v = strtoll(value, &end, 10);
    if (end == value || *end || errno == ERANGE || v < min || v > max)
        return 0;
    *out = v;
    return 1;
}

/* Required fields, what depends on several fields, and the spacing that results. */
static vfp_status_t check_header(header_t *h, vfp_volume_t *vol, char *err, size_t errlen)
{
    static const struct {
        field_id_t id;
        const char *name;
    } required[] = {{F_TYPE, "type"}, {F_DIMENSION, "dimension"}, {F_SIZES, "sizes"}, {F_ENCODING, "encoding"}};
    for (size_t i = 0; i < sizeof required / sizeof required[0]; i++)
        if (!h->seen[required[i].id])
            return vfpi_fail(err, errlen, h->path, 0, "missing required field '%s'", required[i].name);
    if (vfpi_type_bytes(h->type) > 1 && !h->seen[F_ENDIAN] && h->encoding != ENC_ASCII)
        return vfpi_fail(err, errlen, h->path, 0, "missing field 'endian' (16-bit data needs 'endian: little' or "
                         "'endian: big')");
    if (h->byte_skip < 0 && h->encoding != ENC_RAW)
        return vfpi_fail(err, errlen, h->path, h->seen[F_BYTE_SKIP], "byte skip -1 works only with raw encoding");
    if (h->byte_skip > 0 && (h->encoding == ENC_ASCII || h->encoding == ENC_HEX))
        return vfpi_fail(err, errlen, h->path, h->seen[F_BYTE_SKIP], "byte skip works only with raw and gzip "
                         "encodings (text data skips lines: 'line skip')");
    if (!h->data_file && !h->attached)
        return vfpi_fail(err, errlen, h->path, 0, "no data: the header has no 'data file' field and no blank line "
                         "followed by data");
    for (int a = 0; a < 3; a++) {
        /* NRRD gives spacing either as "spacings" or as the lengths of "space directions"; without either,
         * samples are a unit apart. */
        double s = 1.0;
        unsigned line = 0;
        if (h->seen[F_SPACINGS]) {
            s = h->spacings[a];
            line = h->seen[F_SPACINGS];
        } else if (h->seen[F_DIRECTIONS]) {
            s = h->directions[a];
            line = h->seen[F_DIRECTIONS];
        }
        if (vfpi_check_spacing(s, a, h->path, line, err, errlen))
            return VFP_ERR;
        vol->spacing[a] = s;
    }
    return VFP_OK;
}

static vfp_status_t read_voxels(header_t *h, vfp_volume_t *vol, char *err, size_t errlen)
{
    vfpi_source_t src = {.path = h->path, .offset = h->data_offset, .line_skip = h->line_skip,
                         .byte_skip = h->byte_skip, .gzip = h->encoding == ENC_GZIP};
    char *data_path = NULL;
    char owner[VFP_ERR_LEN], note[VFP_ERR_LEN + 32];
    if (h->data_file) {
        /* A relative data file name is relative to the header's directory, not the working directory. */
        const char *slash = strrchr(h->path, '/');
        size_t dir = h->data_file[0] == '/' || !slash ? 0 : (size_t)(slash - h->path) + 1;
        data_path = malloc(dir + strlen(h->data_file) + 1);
        if (!data_path)
            return vfpi_fail(err, errlen, h->path, 0, "out of memory");
        memcpy(data_path, h->path, dir);
        strcpy(data_path + dir, h->data_file);
        snprintf(owner, sizeof owner, "%s:%u", h->path, h->seen[F_DATA_FILE]);
        snprintf(note, sizeof note, "data file named by %s", owner);
        src.path = data_path;
        src.owner = owner;
        src.note = note;
        src.offset = 0;
    }
    size_t bytes = 0;
    vfp_status_t rc;
    if (h->encoding == ENC_ASCII || h->encoding == ENC_HEX)
        rc = read_text_voxels(h, &src, vol, err, errlen);
    else
        rc = vfpi_read_voxels(vol, h->sizes, h->type, &src, &bytes, err, errlen);
    free(data_path);
    if (rc)
        return rc;
    if (h->encoding != ENC_ASCII && vfpi_type_bytes(h->type) == 2) /* ascii values are numbers, not bytes */
        vfpi_to_native16(vol->data, (size_t)h->sizes[0] * h->sizes[1] * h->sizes[2], h->big_endian);
    return VFP_OK;
}

/* ascii: one number per voxel, separated by white space or commas, in the type's range. hex: two hexadecimal
 * digits per byte, white space anywhere, the bytes in the header's byte order. The text is read front to back and
 * the voxels buffer grows with it (doubling), so a header that claims a huge volume costs what the file holds. */
static vfp_status_t read_text_voxels(header_t *h, const vfpi_source_t *src, vfp_volume_t *vol, char *err,
                                     size_t errlen)
{
    static const long lo[] = {[VF_VOXEL_U8] = 0, [VF_VOXEL_I8] = -128, [VF_VOXEL_U16] = 0, [VF_VOXEL_I16] = -32768};
    static const long hi[] = {[VF_VOXEL_U8] = 255, [VF_VOXEL_I8] = 127, [VF_VOXEL_U16] = 65535, [VF_VOXEL_I16] = 32767};
    const char *what = h->encoding == ENC_ASCII ? "ascii" : "hex";
    unsigned tb = vfpi_type_bytes(h->type);
    size_t count = (size_t)h->sizes[0] * h->sizes[1] * h->sizes[2], bytes = count * tb;
    FILE *file = fopen(src->path, "rb");
    if (!file) {
        if (src->owner)
            return vfpi_fail(err, errlen, src->owner, 0, "cannot open data file %s: %s", src->path, strerror(errno));
        return vfpi_fail(err, errlen, src->path, 0, "cannot open: %s", strerror(errno));
    }
    vfp_status_t rc = VFP_OK;
    unsigned char *dst = NULL;
    size_t cap = 0, got = 0; /* bytes */
    if (src->offset && fseeko(file, (off_t)src->offset, SEEK_SET) != 0)
        rc = vfpi_fail(err, errlen, src->path, 0, "cannot seek to byte %llu", (unsigned long long)src->offset);
    for (uint32_t line = 0; rc == VFP_OK && line < h->line_skip; line++) {
        int c;
        while ((c = getc(file)) != EOF && c != '\n')
            ;
        if (c == EOF)
            rc = vfpi_fail(err, errlen, src->path, 0, "truncated: line skip %u passes the end of the file after %u "
                           "lines", h->line_skip, line);
    }
    int c = 0;
    while (rc == VFP_OK) {
        do
            c = getc(file);
        while (c != EOF && (isspace(c) || (h->encoding == ENC_ASCII && c == ',')));
        if (c == EOF)
            break;
        unsigned char value[2];
        size_t n;
        if (h->encoding == ENC_ASCII) {
            char num[32];
            size_t k = 0;
            while (c != EOF && !isspace(c) && c != ',' && k + 1 < sizeof num) {
                num[k++] = (char)c;
                c = getc(file);
            }
            num[k] = 0;
            char *end;
            errno = 0;
            long v = strtol(num, &end, 10);
            if (end == num || *end || errno == ERANGE || v < lo[h->type] || v > hi[h->type]) {
                rc = vfpi_fail(err, errlen, src->path, 0, "ascii value %zu '%.24s' is not a whole number in %ld..%ld "
                               "(%s data)%s%s", got / tb + 1, num, lo[h->type], hi[h->type], tb == 1 ? "8-bit" :
                               "16-bit", src->note ? "; " : "", src->note ? src->note : "");
                break;
            }
            uint16_t u = (uint16_t)v;
            if (tb == 1)
                value[0] = (unsigned char)u;
            else
                memcpy(value, &u, 2);
            n = tb;
        } else {
            int c2;
            do
                c2 = getc(file);
            while (c2 != EOF && isspace(c2));
            if (!isxdigit(c) || !isxdigit(c2)) {
                rc = vfpi_fail(err, errlen, src->path, 0, "hex byte %zu is not two hexadecimal digits%s%s", got + 1,
                               src->note ? "; " : "", src->note ? src->note : "");
                break;
            }
            char pair[3] = {(char)c, (char)c2, 0};
            value[0] = (unsigned char)strtoul(pair, NULL, 16);
            n = 1;
        }
        if (got + n > bytes) {
            rc = vfpi_fail(err, errlen, src->path, 0, "%s data holds more than the %zu values the sizes and type say",
                           what, count);
            break;
        }
        if (got + n > cap) {
            size_t grown_cap = cap ? (cap > bytes / 2 ? bytes : cap * 2) : (bytes < 4096 ? bytes : 4096);
            unsigned char *grown = realloc(dst, grown_cap);
            if (!grown) {
                rc = vfpi_fail(err, errlen, src->path, 0, "out of memory for %zu bytes of voxels", grown_cap);
                break;
            }
            dst = grown;
            cap = grown_cap;
        }
        memcpy(dst + got, value, n);
        got += n;
    }
    if (rc == VFP_OK && ferror(file))
        rc = vfpi_fail(err, errlen, src->path, 0, "read error: %s", strerror(errno));
    if (rc == VFP_OK && got < bytes)
        rc = vfpi_fail(err, errlen, src->path, 0, "truncated: expected %zu %s, found %zu", h->encoding == ENC_ASCII ?
                       count : bytes, h->encoding == ENC_ASCII ? "ascii values" : "hex bytes",
                       h->encoding == ENC_ASCII ? got / tb : got);
    fclose(file);
    if (rc) {
        free(dst);
        return rc;
    }
    vol->data = dst;
    for (int a = 0; a < 3; a++)
        vol->core.dims[a] = h->sizes[a];
    vol->core.type = h->type;
    return VFP_OK;
}

static vfp_status_t parse_space(header_t *h, const char *value, char *err, size_t errlen)
{
    h->space = SPACE_NONE;
    for (size_t i = 0; i < sizeof spaces / sizeof spaces[0]; i++)
        if (strcasecmp(value, spaces[i].name) == 0) {
            h->space = (int)i;
            return VFP_OK;
        }
    for (size_t i = 0; i < sizeof other_spaces / sizeof other_spaces[0]; i++)
        if (strcasecmp(value, other_spaces[i]) == 0)
            return VFP_OK;
    return vfpi_fail(err, errlen, h->path, h->line, "unknown space '%.*s' (expected a NRRD space such as "
                     "left-posterior-superior, right-anterior-superior or scanner-xyz)", SHOWN, value);
}

/* A patient space and a direction for every axis: the axes' LPS vectors. Anything less (no space, a scanner
 * space, an axis without a direction) leaves the volume as stored. */
static vfp_status_t orientation(header_t *h, vfp_volume_t *vol, char *err, size_t errlen)
{
    if (!h->seen[F_SPACE] || h->space == SPACE_NONE || !h->seen[F_DIRECTIONS])
        return VFP_OK;
    double axes[3][3];
    int dim = spaces[h->space].dim;
    for (int a = 0; a < 3; a++) {
        if (h->vector_len[a] == 0)
            return VFP_OK;
        if (h->vector_len[a] != dim)
            return vfpi_fail(err, errlen, h->path, h->seen[F_DIRECTIONS], "space directions: vector %d has %d "
                             "components (expected %d for space '%s')", a + 1, h->vector_len[a], dim,
                             spaces[h->space].name);
        for (int c = 0; c < 3; c++)
            axes[a][c] = spaces[h->space].sign[c] * h->vectors[a][c];
    }
    return vfpi_set_direction(vol, axes, "space directions", h->path, h->seen[F_DIRECTIONS], err, errlen);
}

static field_id_t field_lookup(const char *name, int *known)
{
    *known = 1;
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++)
        if (strcasecmp(name, fields[i].name) == 0)
            return fields[i].id;
    *known = 0;
    return F_IGNORED;
}

/* Strips spaces and tabs at both ends, in place. */
static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    size_t n = strlen(s);
    while (n && (s[n - 1] == ' ' || s[n - 1] == '\t'))
        s[--n] = 0;
    return s;
}
