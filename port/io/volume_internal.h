/* SPDX-License-Identifier: MIT */
/*
 * volume_internal.h: what the volume readers share (error text, checks, byte order, reading voxel data exactly).
 *
 * Names: vfp_ is the port's public prefix (volume.h); vfpi_ marks functions shared by the port's volume files
 * and no one else. Every vfpi_ function that can fail returns VFP_OK or VFP_ERR (status.h)
 * and fills err with one line that starts with the file name, as volume.h promises.
 */
#ifndef VFP_VOLUME_INTERNAL_H
#define VFP_VOLUME_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <sys/stat.h>

#include "volume.h"

/* Bytes the dispatcher looks at to recognise a file: a NIfTI-2 header (540; NIfTI-1's is 348) and its extension
 * flag (4). DICOM's "DICM" is at 128. */
#define VFPI_HEAD_BYTES 544

/* Largest spacing we accept: spacing_q16 must fit the core's uint32_t with room for sums of a few. */
#define VFPI_MAX_SPACING 32767.0

/* Where a file's voxel data is and how to get at it. Skips happen in this order: offset (file bytes), line_skip
 * (lines of the file as stored), byte_skip (bytes after decompression, as NRRD and gzip'd NIfTI need). */
typedef struct vfpi_source {
    const char *path;  /* the file to open (as messages name it) */
    const char *owner; /* NULL, or "header:LINE" that named this file: open failures name it first */
    const char *note;  /* NULL, or a hint appended in parentheses to size errors ("data file named by x:7") */
    uint64_t offset;
    uint32_t line_skip;
    int64_t byte_skip; /* -1: the data is the last bytes of the (uncompressed) file, NRRD's "byte skip: -1" */
    int gzip;          /* the data is gzip (or zlib) compressed; concatenated gzip members are one stream */
} vfpi_source_t;

/* A volume given as a pipe or FIFO (volfix-sim render <(zcat x.nhdr), /dev/stdin) gives its bytes once, and the
 * readers open their file more than once (recognising it, a header, then attached data): vfpi_spool_begin copies
 * such a stream, once and front to back, into an unnamed temporary file (at most VFPI_SPOOL_CAP bytes, docs/usage.md
 * "Input sizes"), and until vfpi_spool_end, vfpi_fopen and vfpi_stat give the copy for that path: messages keep
 * naming the path, and a detached data file stays beside it. A regular file or a device is left alone. A FIFO with
 * no writer waits, as cat does, until a signal ends the program. */
#define VFPI_SPOOL_CAP (1024ull << 20)
vfp_status_t vfpi_spool_begin(const char *path, char *err, size_t errlen);
void vfpi_spool_end(void);
FILE *vfpi_fopen(const char *path);
int vfpi_stat(const char *path, struct stat *st);

/* Formats "name:line: message" (line 0: "name: message") into err; returns VFP_ERR, so `return vfpi_fail(...)`. */
vfp_status_t vfpi_fail(char *err, size_t errlen, const char *name, unsigned line, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

/* Reads up to cap bytes from the start of a file (decompressed when gzip) for recognising it. Errors of a
 * damaged gzip stream are not reported here (the reader that follows reports them); a file that cannot be
 * opened is. */
vfp_status_t vfpi_read_head(const char *path, int gzip, unsigned char *buf, size_t cap, size_t *got, char *err,
                            size_t errlen);

/* Reads a file's voxels: sets vol->core.dims and type and mallocs vol->data for exactly dims x type bytes, which the
 * file must hold (after the skips): more or fewer is an error. Nothing is allocated before the data is known to be
 * there (uncompressed: the file's size; gzip: the buffer grows with the decompressed data), so a header that
 * claims a huge volume fails with "truncated: expected N bytes of voxel data, found M", not out of memory. *bytes
 * is the size read. On failure vol is untouched. */
vfp_status_t vfpi_read_voxels(vfp_volume_t *vol, const uint32_t dims[3], vf_voxel_t type, const vfpi_source_t *src,
                              size_t *bytes, char *err, size_t errlen);

/* Checks: each size 2..VF_MAX_DIM; a spacing finite, > 0, <= VFPI_MAX_SPACING and not 0 in Q16.16. */
vfp_status_t vfpi_check_dims(const uint64_t dims[3], const char *name, unsigned line, char *err, size_t errlen);
vfp_status_t vfpi_check_spacing(double spacing, int axis, const char *name, unsigned line, char *err, size_t errlen);

/* Sets vol->core.dims and type and mallocs vol->data for them (exactly, products checked for overflow): for volumes
 * made in memory (phantoms, downsampled copies); a file's voxels come through vfpi_read_voxels. */
vfp_status_t vfpi_alloc_voxels(vfp_volume_t *vol, const uint32_t dims[3], vf_voxel_t type, size_t *bytes,
                               const char *name, char *err, size_t errlen);

/* 16-bit values stored with the given byte order become native. */
void vfpi_to_native16(void *data, size_t count, int big_endian);

unsigned vfpi_type_bytes(vf_voxel_t type);
int vfpi_has_suffix(const char *text, const char *suffix); /* ASCII case-insensitive */

/* Little- and big-endian field loads from a byte buffer (no alignment needed). */
uint16_t vfpi_load16(const unsigned char *p, int big_endian);
uint32_t vfpi_load32(const unsigned char *p, int big_endian);

/* The readers. Each fills vol->data, core.dims, core.type, spacing, slope and inter (or fails with everything it
 * allocated freed); volume.c does the rest (spacing_q16, raw_min/max, voxels pointer). */
vfp_status_t vfpi_load_nrrd(vfp_volume_t *vol, const char *path, char *err, size_t errlen);
vfp_status_t vfpi_load_nifti(vfp_volume_t *vol, const char *path, int gzip, char *err, size_t errlen);
vfp_status_t vfpi_load_den(vfp_volume_t *vol, const char *path, char *err, size_t errlen);
vfp_status_t vfpi_load_raw(vfp_volume_t *vol, const char *path, const vfp_load_opts_t *opts, char *err, size_t errlen);
vfp_status_t vfpi_load_phantom(vfp_volume_t *vol, const char *spec, char *err, size_t errlen);
vfp_status_t vfpi_load_metaimage(vfp_volume_t *vol, const char *path, char *err, size_t errlen);

/* Orientation (orientation.c). A reader that knows where its voxel axes point in the patient calls
 * vfpi_set_direction with axes[a] the LPS vector of stored axis a (any length; readers convert RAS and other
 * patient spaces to LPS): it checks that the three make a frame (finite, non-zero, not in one plane; else an error
 * "NAME:LINE: FROM: ...") and sets vol->oriented, direction and orient_from. volume.c then calls vfpi_orient,
 * which reorders and reverses the voxels (and dims and spacing) so that x, y, z run towards L, P, S. */
vfp_status_t vfpi_set_direction(vfp_volume_t *vol, const double axes[3][3], const char *from, const char *name,
                                unsigned line, char *err, size_t errlen);
vfp_status_t vfpi_orient(vfp_volume_t *vol, char *err, size_t errlen);

/* Replace the volume by its box average over factor^3 blocks (1..VFPI_MAX_DOWNSAMPLE), spacing times factor
 * (volume_downsample.c). Before volume.c's finishing step, which derives spacing_q16 and the range. */
#define VFPI_MAX_DOWNSAMPLE 8
vfp_status_t vfpi_downsample(vfp_volume_t *vol, int factor, char *err, size_t errlen);

/* Recognisers for dispatch by content (head: the first bytes of the file, decompressed when gzip). */
int vfpi_is_nifti(const unsigned char *head, size_t n);
int vfpi_is_den(const unsigned char *head, size_t n, uint64_t file_bytes);
int vfpi_is_metaimage(const unsigned char *head, size_t n);

#endif /* VFP_VOLUME_INTERNAL_H */
