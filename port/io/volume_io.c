/* SPDX-License-Identifier: MIT */
/* volume_io.c: the helpers the volume readers share: error text, checks, byte order, exact reads (plain or gzip). */
/*********************
 *      INCLUDES
 *********************/
#include "volume_internal.h"
#include "printable.h"
#include "render/memory.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

/*********************
 *      DEFINES
 *********************/
#define IN_BYTES (64 * 1024)      /* compressed bytes read at a time */
#define DISCARD_BYTES (64 * 1024) /* scratch for skipping and counting surplus bytes */
#define FIRST_BYTES (1 << 20)     /* gzip'd voxels: the buffer's first size; it doubles as the data keeps coming */

/**********************
 *      TYPES
 **********************/

/* A file read front to back, plain or through inflate. */
typedef struct stream {
    FILE *file;
    int gzip;
    int z_ready;      /* inflateInit2 succeeded: inflateEnd is owed */
    int member_ended; /* inflate reported the end of a gzip member; another may follow */
    int ended;        /* no more data: a member ended and the file has no bytes after it */
    z_stream z;
    unsigned char *in;
} stream_t;

/* What a volume's voxels may take: checked with vfp_memory_check before they are allocated, together with what the
 * renderer will need beside them, so that a volume too large for the machine is refused with its size named. */
typedef struct budget {
    const char *name;      /* the volume, as the user named it */
    const uint32_t *dims;
    uint64_t renderer;     /* bytes the renderer will take beside the voxels (default parameters) */
} budget_t;

/**********************
 *  STATIC PROTOTYPES
 **********************/
static vfp_status_t stream_open(stream_t *s, const vfpi_source_t *src, char *err, size_t errlen);
static void stream_close(stream_t *s);
static vfp_status_t stream_read(stream_t *s, const vfpi_source_t *src, unsigned char *out, size_t n, size_t *got,
                                char *err, size_t errlen);
static vfp_status_t stream_refill(stream_t *s, const vfpi_source_t *src, char *err, size_t errlen);
static vfp_status_t stream_skip(stream_t *s, const vfpi_source_t *src, uint64_t n, uint64_t *skipped, char *err,
                                size_t errlen);
static vfp_status_t skip_lines(FILE *file, const vfpi_source_t *src, char *err, size_t errlen);
static vfp_status_t read_plain(FILE *file, const vfpi_source_t *src, uint64_t file_bytes, size_t bytes,
                               const budget_t *budget, void **out, char *err, size_t errlen);
static vfp_status_t read_gzip(stream_t *s, const vfpi_source_t *src, size_t bytes, const budget_t *budget, void **out,
                              char *err, size_t errlen);
static uint64_t renderer_bytes(const uint32_t dims[3], vf_voxel_t type);
static vfp_status_t src_fail(char *err, size_t errlen, const vfpi_source_t *src, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/**********************
 *   GLOBAL FUNCTIONS
 **********************/

vfp_status_t vfpi_fail(char *err, size_t errlen, const char *name, unsigned line, const char *fmt, ...)
{
    if (!err || errlen == 0)
        return VFP_ERR;
    int n = line ? snprintf(err, errlen, "%s:%u: ", name, line) : snprintf(err, errlen, "%s: ", name);
    if (n >= 0 && (size_t)n < errlen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err + n, errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    vfp_printable(err); /* a file name or a quoted header value could carry a newline or binary junk */
    return VFP_ERR;
}

/* The stream copied by vfpi_spool_begin, and the path it came from (one at a time: volumes load one by one). */
static FILE *spool_file;
static char *spool_path;

vfp_status_t vfpi_spool_begin(const char *path, char *err, size_t errlen)
{
    struct stat st;
    if (stat(path, &st) != 0 || !(S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode)))
        return VFP_OK; /* a regular file, a device or a missing path: the readers say what it is */
    FILE *in = fopen(path, "rb");
    if (!in)
        return vfpi_fail(err, errlen, path, 0, "cannot open: %s", strerror(errno));
    FILE *copy = tmpfile();
    char *name = strdup(path);
    unsigned char *buf = malloc(IN_BYTES);
    vfp_status_t rc = VFP_OK;
    if (!copy || !name || !buf)
        rc = vfpi_fail(err, errlen, path, 0, "cannot make a temporary copy of the stream: %s", strerror(errno));
    uint64_t total = 0;
    while (rc == VFP_OK) {
        size_t got = fread(buf, 1, IN_BYTES, in);
        if (got == 0) {
            if (ferror(in))
                rc = vfpi_fail(err, errlen, path, 0, "cannot read: %s", strerror(errno));
            break;
        }
        total += got;
        if (total > VFPI_SPOOL_CAP)
            rc = vfpi_fail(err, errlen, path, 0, "a stream longer than %llu MiB, the cap on a volume read from a "
                           "pipe (give it as a regular file)", VFPI_SPOOL_CAP >> 20);
        else if (fwrite(buf, 1, got, copy) != got)
            rc = vfpi_fail(err, errlen, path, 0, "cannot copy the stream to a temporary file: %s", strerror(errno));
    }
    fclose(in);
    free(buf);
    if (rc == VFP_OK && fflush(copy) != 0)
        rc = vfpi_fail(err, errlen, path, 0, "cannot copy the stream to a temporary file: %s", strerror(errno));
    if (rc) {
        if (copy)
            fclose(copy);
        free(name);
        return VFP_ERR;
    }
    vfpi_spool_end();
    spool_file = copy;
    spool_path = name;
    return VFP_OK;
}

void vfpi_spool_end(void)
{
    if (spool_file)
        fclose(spool_file);
    free(spool_path);
    spool_file = NULL;
    spool_path = NULL;
}

FILE *vfpi_fopen(const char *path)
{
    if (!spool_file || strcmp(path, spool_path) != 0)
        return fopen(path, "rb");
    /* a file of its own (its own offset) onto the copy, which stays open until vfpi_spool_end */
    char proc[64];
    snprintf(proc, sizeof proc, "/proc/self/fd/%d", fileno(spool_file));
    return fopen(proc, "rb");
}

int vfpi_stat(const char *path, struct stat *st)
{
    if (spool_file && strcmp(path, spool_path) == 0)
        return fstat(fileno(spool_file), st);
    return stat(path, st);
}

vfp_status_t vfpi_read_head(const char *path, int gzip, unsigned char *buf, size_t cap, size_t *got, char *err,
                            size_t errlen)
{
    vfpi_source_t src = {.path = path, .gzip = gzip};
    stream_t s;
    *got = 0;
    if (stream_open(&s, &src, err, errlen))
        return VFP_ERR;
    char scratch[VFP_ERR_LEN];
    /* A damaged stream still yields the bytes before the damage; the reader that follows says what is wrong. */
    stream_read(&s, &src, buf, cap, got, scratch, sizeof scratch);
    stream_close(&s);
    return VFP_OK;
}

vfp_status_t vfpi_read_voxels(vfp_volume_t *vol, const uint32_t dims[3], vf_voxel_t type, const vfpi_source_t *src,
                              size_t *bytes, char *err, size_t errlen)
{
    /* dims are at most VF_MAX_DIM (2^12) each: the product fits 64 bits, but may not fit a 32-bit size_t. */
    uint64_t n = (uint64_t)dims[0] * dims[1] * dims[2] * vfpi_type_bytes(type);
    if (n > (uint64_t)SIZE_MAX)
        return src_fail(err, errlen, src, "volume of %llu bytes is too large for this machine", (unsigned long long)n);
    stream_t s;
    if (stream_open(&s, src, err, errlen))
        return VFP_ERR;
    budget_t budget = {vol->name[0] ? vol->name : src->path, dims, renderer_bytes(dims, type)};
    void *data = NULL;
    vfp_status_t rc;
    if (src->offset && fseeko(s.file, (off_t)src->offset, SEEK_SET) != 0)
        rc = src_fail(err, errlen, src, "cannot seek to byte %llu: %s", (unsigned long long)src->offset,
                      strerror(errno));
    else if ((rc = skip_lines(s.file, src, err, errlen)) != VFP_OK)
        ;
    else if (src->gzip) {
        if (src->byte_skip < 0)
            rc = src_fail(err, errlen, src, "byte skip -1 works only for uncompressed data");
        else
            rc = read_gzip(&s, src, (size_t)n, &budget, &data, err, errlen);
    } else {
        struct stat st;
        if (fstat(fileno(s.file), &st) != 0 || !S_ISREG(st.st_mode))
            rc = src_fail(err, errlen, src, "not a regular file (uncompressed data is read from regular files)");
        else
            rc = read_plain(s.file, src, (uint64_t)st.st_size, (size_t)n, &budget, &data, err, errlen);
    }
    stream_close(&s);
    if (rc)
        return rc;
    vol->data = data;
    for (int a = 0; a < 3; a++)
        vol->core.dims[a] = dims[a];
    vol->core.type = type;
    *bytes = (size_t)n;
    return VFP_OK;
}

vfp_status_t vfpi_check_dims(const uint64_t dims[3], const char *name, unsigned line, char *err, size_t errlen)
{
    static const char axis_names[3] = {'x', 'y', 'z'};
    for (int a = 0; a < 3; a++) {
        if (dims[a] >= 2 && dims[a] <= VF_MAX_DIM)
            continue;
        return vfpi_fail(err, errlen, name, line, "size %llu along %c is out of range (expected 2..%d%s)",
                         (unsigned long long)dims[a], axis_names[a], VF_MAX_DIM,
                         dims[a] == 1 ? "; a volume 1 voxel thick cannot be rendered" : "");
    }
    return VFP_OK;
}

vfp_status_t vfpi_check_spacing(double spacing, int axis, const char *name, unsigned line, char *err, size_t errlen)
{
    static const char axis_names[3] = {'x', 'y', 'z'};
    char c = axis_names[axis < 0 || axis > 2 ? 0 : axis];
    if (!isfinite(spacing) || spacing <= 0.0 || spacing > VFPI_MAX_SPACING)
        return vfpi_fail(err, errlen, name, line, "bad spacing %g along %c (expected a number > 0 and <= %g)",
                         spacing, c, VFPI_MAX_SPACING);
    if (lround(spacing * 65536.0) < 1)
        return vfpi_fail(err, errlen, name, line,
                         "spacing %g along %c is too small (expected at least %g: spacings are kept in "
                         "Q16.16)",
                         spacing, c, 0.5 / 65536.0);
    return VFP_OK;
}

vfp_status_t vfpi_alloc_voxels(vfp_volume_t *vol, const uint32_t dims[3], vf_voxel_t type, size_t *bytes,
                               const char *name, char *err, size_t errlen)
{
    /* dims are at most VF_MAX_DIM (2^12) each: the product fits 64 bits, but may not fit a 32-bit size_t. */
    uint64_t n = (uint64_t)dims[0] * dims[1] * dims[2] * vfpi_type_bytes(type);
    if (n > (uint64_t)SIZE_MAX)
        return vfpi_fail(err, errlen, name, 0, "volume of %llu bytes is too large for this machine",
                         (unsigned long long)n);
    if (vfp_memory_check(name, dims, n + renderer_bytes(dims, type), err, errlen)) {
        vfp_printable(err);
        return VFP_ERR;
    }
    vol->data = malloc((size_t)n);
    if (!vol->data)
        return vfpi_fail(err, errlen, name, 0, "out of memory for %llu bytes of voxels", (unsigned long long)n);
    for (int a = 0; a < 3; a++)
        vol->core.dims[a] = dims[a];
    vol->core.type = type;
    *bytes = (size_t)n;
    return VFP_OK;
}

void vfpi_to_native16(void *data, size_t count, int big_endian)
{
    const uint16_t probe = 1;
    unsigned char first;
    memcpy(&first, &probe, 1);
    int host_big = first == 0;
    if (host_big == (big_endian != 0))
        return;
    unsigned char *p = data;
    for (size_t i = 0; i < count; i++, p += 2) {
        unsigned char t = p[0];
        p[0] = p[1];
        p[1] = t;
    }
}

unsigned vfpi_type_bytes(vf_voxel_t type)
{
    return type == VF_VOXEL_U16 || type == VF_VOXEL_I16 ? 2u : 1u;
}

int vfpi_has_suffix(const char *text, const char *suffix)
{
    size_t n = strlen(text), m = strlen(suffix);
    return n >= m && strcasecmp(text + n - m, suffix) == 0;
}

uint16_t vfpi_load16(const unsigned char *p, int big_endian)
{
    return big_endian ? (uint16_t)(p[0] << 8 | p[1]) : (uint16_t)(p[1] << 8 | p[0]);
}

uint32_t vfpi_load32(const unsigned char *p, int big_endian)
{
    if (big_endian)
        return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
    return (uint32_t)p[3] << 24 | (uint32_t)p[2] << 16 | (uint32_t)p[1] << 8 | p[0];
}

/**********************
 *   STATIC FUNCTIONS
 **********************/

/* "path: message (note)", the shape of every data error. */
static vfp_status_t src_fail(char *err, size_t errlen, const vfpi_source_t *src, const char *fmt, ...)
{
    char msg[VFP_ERR_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (src->note)
        return vfpi_fail(err, errlen, src->path, 0, "%s (%s)", msg, src->note);
    return vfpi_fail(err, errlen, src->path, 0, "%s", msg);
}

static vfp_status_t stream_open(stream_t *s, const vfpi_source_t *src, char *err, size_t errlen)
{
    memset(s, 0, sizeof *s);
    s->gzip = src->gzip;
    s->file = vfpi_fopen(src->path);
    if (!s->file) {
        const char *why = strerror(errno);
        if (src->owner)
            return vfpi_fail(err, errlen, src->owner, 0, "cannot open data file %s: %s", src->path, why);
        return vfpi_fail(err, errlen, src->path, 0, "cannot open: %s", why);
    }
    if (!s->gzip)
        return VFP_OK;
    s->in = malloc(IN_BYTES);
    /* 15 + 32: a window of 2^15 and automatic gzip or zlib header detection. */
    if (!s->in || inflateInit2(&s->z, 15 + 32) != Z_OK) {
        stream_close(s);
        return src_fail(err, errlen, src, "out of memory for gzip decompression");
    }
    s->z_ready = 1;
    return VFP_OK;
}

static void stream_close(stream_t *s)
{
    if (s->z_ready)
        inflateEnd(&s->z);
    free(s->in);
    if (s->file)
        fclose(s->file);
    memset(s, 0, sizeof *s);
}

/* Moves unread input to the front and reads more of the file after it. Returns VFP_ERR on a read error. */
static vfp_status_t stream_refill(stream_t *s, const vfpi_source_t *src, char *err, size_t errlen)
{
    if (s->z.avail_in && s->z.next_in != s->in)
        memmove(s->in, s->z.next_in, s->z.avail_in);
    s->z.next_in = s->in;
    size_t r = fread(s->in + s->z.avail_in, 1, IN_BYTES - s->z.avail_in, s->file);
    if (r == 0 && ferror(s->file))
        return src_fail(err, errlen, src, "read error: %s", strerror(errno));
    s->z.avail_in += (uInt)r;
    return VFP_OK;
}

/* Reads up to n bytes; *got < n only at the end of the data. Returns VFP_ERR on a read or gzip error. */
static vfp_status_t stream_read(stream_t *s, const vfpi_source_t *src, unsigned char *out, size_t n, size_t *got,
                                char *err, size_t errlen)
{
    *got = 0;
    if (!s->gzip) {
        *got = fread(out, 1, n, s->file);
        if (*got < n && ferror(s->file))
            return src_fail(err, errlen, src, "read error: %s", strerror(errno));
        return VFP_OK;
    }
    while (*got < n && !s->ended) {
        if (s->member_ended) {
            /* Concatenated gzip members make one stream (as gzip -d reads them); anything else after the end
             * of the compressed data means the file is not what its header says. */
            if (s->z.avail_in < 2 && stream_refill(s, src, err, errlen))
                return VFP_ERR;
            if (s->z.avail_in == 0) {
                s->ended = 1;
                break;
            }
            if (s->z.avail_in < 2 || s->z.next_in[0] != 0x1f || s->z.next_in[1] != 0x8b)
                return src_fail(err, errlen, src, "gzip error: unexpected bytes after the end of the compressed data");
            inflateReset(&s->z);
            s->member_ended = 0;
        }
        if (s->z.avail_in == 0) {
            if (stream_refill(s, src, err, errlen))
                return VFP_ERR;
            if (s->z.avail_in == 0)
                return src_fail(err, errlen, src, "gzip error: unexpected end of file (the compressed data is "
                                                  "truncated)");
        }
        size_t room = n - *got;
        s->z.next_out = out + *got;
        s->z.avail_out = room > UINT_MAX ? UINT_MAX : (uInt)room;
        uInt before = s->z.avail_out;
        int rc = inflate(&s->z, Z_NO_FLUSH);
        *got += before - s->z.avail_out;
        if (rc == Z_STREAM_END)
            s->member_ended = 1;
        else if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT)
            return src_fail(err, errlen, src, "gzip error: %s", s->z.msg ? s->z.msg : "corrupt data");
        else if (rc == Z_MEM_ERROR)
            return src_fail(err, errlen, src, "gzip error: out of memory");
        /* Z_OK and Z_BUF_ERROR: more input or more room is needed, which the loop provides. */
    }
    return VFP_OK;
}

/* Reads and drops n bytes (or fewer at the end of the data: *skipped says how many). */
static vfp_status_t stream_skip(stream_t *s, const vfpi_source_t *src, uint64_t n, uint64_t *skipped, char *err,
                                size_t errlen)
{
    unsigned char *scratch = malloc(DISCARD_BYTES);
    if (!scratch)
        return src_fail(err, errlen, src, "out of memory");
    *skipped = 0;
    vfp_status_t rc = VFP_OK;
    while (*skipped < n) {
        uint64_t want = n - *skipped;
        size_t got;
        rc = stream_read(s, src, scratch, want > DISCARD_BYTES ? DISCARD_BYTES : (size_t)want, &got, err, errlen);
        *skipped += got;
        if (rc || got == 0)
            break;
    }
    free(scratch);
    return rc;
}

/* NRRD's line skip: lines of the file as stored, before any decompression. */
static vfp_status_t skip_lines(FILE *file, const vfpi_source_t *src, char *err, size_t errlen)
{
    for (uint32_t line = 0; line < src->line_skip; line++) {
        int c;
        while ((c = getc(file)) != EOF && c != '\n')
            ;
        if (c == EOF)
            return src_fail(err, errlen, src, "truncated: line skip %u passes the end of the file after %u lines",
                            src->line_skip, line);
    }
    return VFP_OK;
}

/* The renderer's bytes beside a volume's voxels, at the default parameters (the programs check again with their
 * own once the options are known). */
static uint64_t renderer_bytes(const uint32_t dims[3], vf_voxel_t type)
{
    vf_params_t params;
    vf_params_default(&params);
    return vfp_memory_renderer(&params, dims, type);
}

static vfp_status_t over_budget(const budget_t *b, uint64_t voxel_bytes, char *err, size_t errlen)
{
    if (vfp_memory_check(b->name, b->dims, voxel_bytes + b->renderer, err, errlen) == VFP_OK)
        return VFP_OK;
    vfp_printable(err);
    return VFP_ERR;
}

/* Checks that the file holds exactly `bytes` bytes of data (after the skips), and that the machine has room for
 * them, before it allocates them: a header that claims a huge volume costs nothing when the data is not there. */
static vfp_status_t read_plain(FILE *file, const vfpi_source_t *src, uint64_t file_bytes, size_t bytes,
                               const budget_t *budget, void **out, char *err, size_t errlen)
{
    off_t here = ftello(file);
    if (here < 0)
        return src_fail(err, errlen, src, "cannot tell the file position: %s", strerror(errno));
    uint64_t start = (uint64_t)here, avail;
    if (src->byte_skip < 0) {
        /* byte skip -1: the data is the last `bytes` bytes of the file, whatever precedes it. */
        avail = file_bytes > start ? file_bytes - start : 0;
        if (avail < bytes)
            return src_fail(err, errlen, src, "truncated: expected %zu bytes of voxel data, found %llu", bytes,
                            (unsigned long long)avail);
        start = file_bytes - bytes;
    } else {
        start += (uint64_t)src->byte_skip;
        if (start > file_bytes)
            return src_fail(err, errlen, src, "truncated: the data should start at byte %llu, but the file has only "
                            "%llu bytes", (unsigned long long)start, (unsigned long long)file_bytes);
        avail = file_bytes - start;
        if (avail < bytes)
            return src_fail(err, errlen, src, "truncated: expected %zu bytes of voxel data, found %llu", bytes,
                            (unsigned long long)avail);
        if (avail > bytes)
            return src_fail(err, errlen, src, "expected %zu bytes of voxel data, found %llu%s", bytes,
                            (unsigned long long)avail, src->note ? "" : " (more than the sizes and type say)");
    }
    if (fseeko(file, (off_t)start, SEEK_SET) != 0)
        return src_fail(err, errlen, src, "cannot seek to byte %llu: %s", (unsigned long long)start, strerror(errno));
    if (over_budget(budget, bytes, err, errlen))
        return VFP_ERR;
    void *dst = malloc(bytes);
    if (!dst)
        return src_fail(err, errlen, src, "out of memory for %zu bytes of voxels", bytes);
    size_t got = fread(dst, 1, bytes, file);
    if (got != bytes) {
        vfp_status_t rc = src_fail(err, errlen, src, "read error after %zu of %zu bytes: %s", got, bytes,
                                   ferror(file) ? strerror(errno) : "the file shrank while it was read");
        free(dst);
        return rc;
    }
    *out = dst;
    return VFP_OK;
}

/* The decompressed size is known only by decompressing, so the buffer grows with the data (doubling, up to
 * `bytes`): a small file that claims a huge volume is found short after allocating about what it holds. */
static vfp_status_t read_gzip(stream_t *s, const vfpi_source_t *src, size_t bytes, const budget_t *budget, void **out,
                              char *err, size_t errlen)
{
    uint64_t skipped;
    if (stream_skip(s, src, (uint64_t)src->byte_skip, &skipped, err, errlen))
        return VFP_ERR;
    if (skipped < (uint64_t)src->byte_skip)
        return src_fail(err, errlen, src, "truncated: the data should start at byte %lld after decompression, but "
                        "there are only %llu bytes", (long long)src->byte_skip, (unsigned long long)skipped);
    size_t cap = bytes < FIRST_BYTES ? bytes : FIRST_BYTES, got = 0;
    unsigned char *dst = malloc(cap);
    vfp_status_t rc = VFP_OK;
    for (;;) {
        size_t more;
        if (!dst) {
            rc = src_fail(err, errlen, src, "out of memory for %zu bytes of voxels", cap);
            break;
        }
        if ((rc = stream_read(s, src, dst + got, cap - got, &more, err, errlen)) != VFP_OK)
            break;
        got += more;
        if (got < cap || cap == bytes)
            break; /* the end of the data, or all of it */
        cap = cap > bytes / 2 ? bytes : cap * 2;
        /* the data has kept coming: before the buffer grows past what the machine has, the whole need is told */
        if (cap + budget->renderer > vfp_memory_available() && (rc = over_budget(budget, bytes, err, errlen)) != VFP_OK)
            break;
        unsigned char *grown = realloc(dst, cap);
        if (!grown)
            free(dst);
        dst = grown;
    }
    if (rc == VFP_OK && got < bytes)
        rc = src_fail(err, errlen, src, "truncated: expected %zu bytes of voxel data after decompression, found %zu",
                      bytes, got);
    /* One byte more than expected is enough to refuse the file: the rest of the surplus is never decompressed
     * (a small file can inflate to gigabytes). */
    uint64_t extra = 0;
    if (rc == VFP_OK)
        rc = stream_skip(s, src, 1, &extra, err, errlen);
    if (rc == VFP_OK && extra)
        rc = src_fail(err, errlen, src, "expected %zu bytes of voxel data after decompression, found at least %zu%s",
                      bytes, bytes + 1, src->note ? "" : " (more than the sizes and type say)");
    if (rc) {
        free(dst);
        return rc;
    }
    *out = dst;
    return VFP_OK;
}
