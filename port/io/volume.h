/* SPDX-License-Identifier: MIT */
/*
 * volume.h: reading volumes into memory for the core (NRRD, NIfTI-1 and -2, MetaImage, DICOM when built with GDCM,
 * VolPack .den, raw, synthetic phantoms), turning them into the patient frame, and choosing the window that maps
 * 16-bit data to the core's 8-bit scalar domain.
 *
 * The patient frame is DICOM's LPS: +x towards the patient's left, +y posterior, +z superior. A file that says how
 * its voxel axes lie in the patient (DICOM Image Orientation, NIfTI qform/sform, NRRD space directions, MetaImage
 * TransformMatrix or AnatomicalOrientation) is loaded with its axes reordered and reversed so that the volume's x,
 * y, z are L, P, S (docs/formats.md); the views then mean the same from every format (vfp_view_named).
 *
 * Every failure fills `err` with one line that names the file (and the header line when there is one) and says
 * what was wrong and what was expected, for example
 *   "data/x.nhdr:4: unknown type 'float32' (expected int8, uint8, int16 or uint16)"
 *   "data/x.raw: truncated: expected 1376256 bytes of voxel data, found 1000"
 * Programs print it and exit with status 2.
 */
#ifndef VFP_VOLUME_H
#define VFP_VOLUME_H

#include <stddef.h>
#include <stdint.h>

#include "status.h"
#include "volfix.h"

#define VFP_ERR_LEN 512

typedef struct vfp_volume {
    vf_volume_t core;     /* what the core reads; core.voxels points at data, native byte order */
    void *data;           /* voxel storage owned by this struct (malloc) */
    double spacing[3];    /* spacing as read (file units, usually mm) */
    double slope, inter;  /* data value = slope * raw + inter (NIfTI scl_slope/scl_inter; else 1 and 0) */
    int32_t raw_min, raw_max;
    char name[256];       /* the file name or phantom spec, for messages */
    char format[16];      /* "nrrd", "nifti", "metaimage", "dicom", "den", "raw", "phantom" */
    /* Orientation. oriented: the file said where its axes point in the patient; then the voxels have been reordered
     * so that x, y, z run towards L, P, S, and direction holds what is left: column a is the LPS unit vector of
     * axis a (the identity for axis-aligned data; oblique data is shown in the nearest patient axes, oblique_deg
     * says how far off). Not oriented (raw, .den, phantoms, files without a patient space): the axes as stored and
     * direction the identity. orient_from names the header field it came from ("qform", "space directions"). */
    int oriented;
    double direction[3][3];
    double oblique_deg;
    char orient_from[32];
    int stored_axis[3];   /* the file's axis that became x, y, z (0..2), and whether it was reversed */
    int stored_flip[3];
} vfp_volume_t;

/* Options for files that do not describe themselves (raw). */
typedef struct vfp_load_opts {
    int have_dims;        /* --dims X,Y,Z given */
    uint32_t dims[3];
    int have_type;        /* --type given */
    vf_voxel_t type;
    int big_endian;       /* --big-endian */
    int have_spacing;     /* --spacing X,Y,Z given (also overrides a file's own spacing) */
    double spacing[3];
    int downsample;       /* --downsample N: average N^3 blocks, spacing times N (0 or 1: as stored) */
    const char *series;   /* --series UID: the DICOM series to load from a folder holding several (NULL: largest) */
    int quiet;            /* no progress or series list on stderr (tests, fuzzing) */
} vfp_load_opts_t;

/* Load by name: a file path (format from its contents and extension: .nhdr/.nrrd, .nii/.nii.gz, .mhd/.mha, DICOM,
 * .den, else raw, which needs dims and type), a folder of DICOM files, or a synthetic volume "phantom:NAME:N" with NAME marschner-lobb, shepp-logan or
 * sphere or cube and N the size of each side (2..1024). Returns VFP_OK, or VFP_ERR with `err` filled. */
vfp_status_t vfp_volume_load(vfp_volume_t *vol, const char *spec, const vfp_load_opts_t *opts, char *err,
                             size_t errlen);
void vfp_volume_free(vfp_volume_t *vol);

/* A copy of src averaged over factor^3 blocks (factor 1..8), spacing times factor: what --downsample loads.
 * Returns VFP_OK, or VFP_ERR with err (dst then holds nothing to free). */
vfp_status_t vfp_volume_downsampled(vfp_volume_t *dst, const vfp_volume_t *src, int factor, char *err, size_t errlen);

/* The default window: the full range 0..255 for 8-bit data; otherwise from the 0.5 percentile of the raw values
 * to their 99.99 percentile, but at most twice as far as the 99.5 percentile (docs/defaults.md; never lo == hi). */
vf_window_t vfp_default_window(const vfp_volume_t *vol);

/* A raw-value window in data units (after slope/intercept), as every summary prints it and --window takes it
 * back: one unit everywhere, HU for calibrated CT. */
void vfp_window_data(const vfp_volume_t *vol, vf_window_t window, double *lo, double *hi);

/* Parse "LO,HI" in data units (after slope/intercept) into a raw-value window. Returns VFP_OK, or VFP_ERR with err. */
vfp_status_t vfp_parse_window(const vfp_volume_t *vol, const char *text, vf_window_t *window, char *err, size_t errlen);

/* Parse "X,Y,Z" (positive integers) and "uint8|int8|uint16|int16". Return VFP_OK, or VFP_ERR with err. */
vfp_status_t vfp_parse_dims(const char *text, uint32_t dims[3], char *err, size_t errlen);
vfp_status_t vfp_parse_type(const char *text, vf_voxel_t *type, char *err, size_t errlen);

/* Named views in the patient frame: anterior, posterior, left, right, superior, inferior. Each is the camera's
 * place (anterior: in front of the patient, looking at the face) with the head up (anterior, posterior, left,
 * right) or the face up (superior, inferior), and never mirrored: the patient's left is on the right of the
 * picture when the camera faces the patient, as a radiologist reads a frontal view. Sets view[] to the azimuth,
 * elevation and roll in degrees that --view AZ,EL,ROLL takes. Returns VFP_OK, or VFP_ERR for another name. */
vfp_status_t vfp_view_named(const char *name, double view[3]);
#define VFP_VIEW_NAMES "anterior, posterior, left, right, superior or inferior"

/* The patient directions of the picture's edges for a view (degrees, as --view): letters from L, R, A, P, S, I,
 * the largest component first, each component of at least a quarter (so 30,20 gives "LA" rather than "L"). Each
 * string holds up to three letters and a NUL. */
void vfp_view_edges(const double view[3], char right[4], char left[4], char top[4], char bottom[4]);

#endif /* VFP_VOLUME_H */
