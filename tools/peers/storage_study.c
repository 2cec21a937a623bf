/* SPDX-License-Identifier: MIT */
/*
 * storage_study.c: how many bytes volfix's per-axis storage would take if it kept only what a transfer function
 * leaves visible, against what it keeps today. For `make bench-peers`'s grey transfer functions (opacity 0 up to
 * a threshold T, positive above it) a cell (the 2x2x2 voxels a slab segment reads) is visible exactly when its
 * largest scalar is above T, and the voxels a frame reads are the corners of the visible cells. Per principal
 * axis it counts the voxel places four ways of storing them would hold:
 *   full        today's copies: every voxel, with the padding column and row (core/slices.h)
 *   slice rows  per slice, the rows from the first to the last that hold a needed voxel, whole
 *   row span    per row, from its first to its last needed voxel (and a 4-byte offset a row)
 *   exact       the needed voxels only (and the run lists that find them: 2 bytes a run, 2 a gap)
 * and VolPack's count: the voxels above T, which its classified copies hold. A lower bound for the three
 * shrunk forms: a segment's front sample also reads up to one voxel beyond its cell, which they leave out.
 *
 * usage: storage_study VOLUME --dims X,Y,Z --threshold T   (8-bit voxels, raw or gzip)
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

typedef struct count {
    uint64_t full, slice_rows, row_span, rows, exact, runs;
} count_t;

static int dims[3];
static const uint8_t *needed; /* per voxel: a corner of a visible cell */

static int need(int x, int y, int z) { return needed[((size_t)z * dims[1] + y) * dims[0] + x]; }

/* The counts for principal axis k, i and j the two others in volfix's standard order (i = k + 1, j = k + 2). */
static void count_axis(int k, count_t *c)
{
    const int ia = (k + 1) % 3, ja = (k + 2) % 3, ni = dims[ia], nj = dims[ja];
    for (int s = 0; s < dims[k]; s++) {
        int j0 = -1, j1 = -1;
        for (int j = 0; j < nj; j++) {
            int i0 = -1, i1 = -1, inside = 0;
            for (int i = 0; i < ni; i++) {
                int p[3];
                p[k] = s, p[ia] = i, p[ja] = j;
                if (need(p[0], p[1], p[2])) {
                    if (!inside)
                        c->runs++;
                    inside = 1;
                    i1 = i, c->exact++;
                    if (i0 < 0)
                        i0 = i;
                } else {
                    inside = 0;
                }
            }
            c->full += (uint64_t)ni + 1;
            c->rows++;
            if (i0 >= 0) {
                c->row_span += (uint64_t)(i1 - i0 + 1);
                if (j0 < 0)
                    j0 = j;
                j1 = j;
            }
        }
        c->full += (uint64_t)ni + 1; /* the padding row */
        if (j0 >= 0)
            c->slice_rows += (uint64_t)(j1 - j0 + 1) * ((uint64_t)ni + 1);
    }
}

int main(int argc, char **argv)
{
    const char *path = NULL;
    int threshold = -1;
    for (int a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--dims") == 0 && a + 1 < argc) {
            if (sscanf(argv[++a], "%d,%d,%d", &dims[0], &dims[1], &dims[2]) != 3) {
                fprintf(stderr, "storage_study: --dims %s: expected X,Y,Z\n", argv[a]);
                return 2;
            }
        } else if (strcmp(argv[a], "--threshold") == 0 && a + 1 < argc) {
            char *end;
            long t = strtol(argv[++a], &end, 10);
            if (*end || t < 0 || t > 255) {
                fprintf(stderr, "storage_study: --threshold %s: expected a whole number 0..255\n", argv[a]);
                return 2;
            }
            threshold = (int)t;
        } else if (argv[a][0] != '-' && !path) {
            path = argv[a];
        } else {
            fprintf(stderr, "usage: storage_study VOLUME --dims X,Y,Z --threshold T\n");
            return 2;
        }
    }
    if (!path || threshold < 0 || dims[0] < 2 || dims[1] < 2 || dims[2] < 2 || dims[0] > 4096 || dims[1] > 4096 ||
        dims[2] > 4096) {
        fprintf(stderr, "usage: storage_study VOLUME --dims X,Y,Z (each 2..4096) --threshold T\n");
        return 2;
    }
    const size_t n = (size_t)dims[0] * dims[1] * dims[2];
    uint8_t *v = malloc(n), *nd = calloc(n, 1);
    gzFile f = gzopen(path, "rb");
    if (!v || !nd || !f) {
        fprintf(stderr, "storage_study: %s: %s\n", path, !f ? "cannot open" : "out of memory");
        return 2;
    }
    size_t got = 0;
    for (int r; got < n && (r = gzread(f, v + got, (unsigned)(n - got > (1u << 30) ? 1u << 30 : n - got))) > 0;)
        got += (size_t)r;
    gzclose(f);
    if (got != n) {
        fprintf(stderr, "storage_study: %s: %zu bytes, expected %zu for %dx%dx%d\n", path, got, n, dims[0], dims[1],
                dims[2]);
        return 2;
    }

    uint64_t above = 0;
    for (size_t i = 0; i < n; i++)
        above += v[i] > threshold;
    const size_t sx = 1, sy = (size_t)dims[0], sz = (size_t)dims[0] * dims[1];
    for (int z = 0; z + 1 < dims[2]; z++)
        for (int y = 0; y + 1 < dims[1]; y++)
            for (int x = 0; x + 1 < dims[0]; x++) {
                const size_t o = z * sz + y * sy + x * sx;
                int hi = 0;
                for (int c = 0; c < 8; c++) {
                    int s = v[o + (c & 1 ? sx : 0) + (c & 2 ? sy : 0) + (c & 4 ? sz : 0)];
                    hi = s > hi ? s : hi;
                }
                if (hi > threshold)
                    for (int c = 0; c < 8; c++)
                        nd[o + (c & 1 ? sx : 0) + (c & 2 ? sy : 0) + (c & 4 ? sz : 0)] = 1;
            }
    needed = nd;
    count_t c = {0};
    for (int k = 0; k < 3; k++)
        count_axis(k, &c);
    /* JSON: voxel places summed over the three axes; bytes for a voxel place of b bytes are b times these, plus
     * the row offsets (row span) or the run lists (exact) */
    printf("{\"volume\": \"%s\", \"threshold\": %d, \"voxels\": %zu, \"above\": %llu, \"full\": %llu, "
           "\"slice_rows\": %llu, \"row_span\": %llu, \"row_offsets_bytes\": %llu, \"exact\": %llu, "
           "\"run_bytes\": %llu}\n",
           path, threshold, n, (unsigned long long)above, (unsigned long long)c.full,
           (unsigned long long)c.slice_rows, (unsigned long long)c.row_span, (unsigned long long)(4 * c.rows),
           (unsigned long long)c.exact, (unsigned long long)(4 * c.runs));
    free(v);
    free(nd);
    return 0;
}
