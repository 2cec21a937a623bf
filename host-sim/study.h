/* SPDX-License-Identifier: MIT */
/*
 * study.h: the fixed-point precision study: render scenes with many configurations of the core, measure each
 * against the double reference of the same algorithm (the fixed-point error alone) and against the ground
 * truth (the algorithm's own error), and record memory. study.c runs; study_report.c and the writers
 * study_report.h lists write CSV, plots, image strips, summary.json and report.md; cmd_study.c decides what to run.
 */
#ifndef SIM_STUDY_H
#define SIM_STUDY_H

#include <stdio.h>

#include "imgcmp.h"
#include "scene.h"

#define STUDY_MAX_SCENES 64
#define STUDY_MAX_RUNS 2048

/* Claim 1 with the errors point and preint1 share removed (docs/algorithm.md 4b and 4c): 16 x 16 rays per voxel
 * column, partial slabs at the side faces, 1024 table entries; the sweeps' factor "rays_partial_1024". */
#define STUDY_CLAIM_RAYS 16u
#define STUDY_CLAIM_TABLE 1024u

/* The modes the study ranks: vf_mode_t's first three, point, preint1 and preclass. preint2 renders in every
 * command but is not in the study's sweeps: it refuses partial slabs, which the rays sweep and its strips take, and
 * its ranking needs a smooth truth beside the trilinear one (docs/algorithm.md, section 8). */
#define STUDY_MODES 3

/* One scene: volume, transfer function, view and size; its truth image is rendered once. */
typedef struct study_scene {
    char label[64];        /* "ml41-sharp" */
    char volume[512];      /* file or phantom spec */
    char preset[1200];     /* a preset name, or "file:PATH" */
    double azimuth, elevation, zoom;
    uint32_t size;         /* square images */
    sim_scene_t scene;     /* loaded */
    uint8_t *truth;        /* size * size * 3, or NULL until rendered */
    double truth_ms;
} study_scene_t;

/* One run: a scene, a configuration, which factor it varies (for the plots), and what was measured. */
typedef struct study_run {
    int scene;
    vf_params_t params;
    char factor[32];       /* "table_bits", "order", ... or "default" */
    char value[32];        /* the factor's value as text */
    sim_diff_t vs_reference, vs_truth; /* vs_truth.pixels is 0 when the run had no truth */
    vf_memory_t memory;
    size_t band_bytes;     /* buffer slices and skip links for one thread (8-row bands) */
    double ms;             /* one core frame on this machine, informative only */
    /* With study_t.time_frames: that many more frames, each 2 degrees further round the vertical axis (so the
     * tables are rebuilt for each, as when a knob turns the view): the median CPU time of a frame (one thread) and
     * the median wall-clock time of its table rebuild. This machine: informative, not a benchmark (make bench is).
     * 0 when not timed. */
    int frames_timed;
    double frame_ms, frame_tables_ms;
    uint8_t *rgb;          /* the core's image, kept when study_t.keep_images was set for the run, else NULL */
    /* With study_t.count_instructions: instructions per frame under callgrind (study_instructions), 0 if not
     * counted. They do not depend on how busy the machine is, and they carry over to other processors better
     * than a time does. */
    uint64_t instructions;
} study_run_t;

/* Reference images depend on the scene and the algorithm's options (mode, table size, lookup, correction, rays,
 * partial slabs), not on the core's precision: each is rendered once. */
typedef struct study_reference {
    int scene;
    vf_mode_t mode;
    uint32_t table_size;
    vf_lookup_t lookup;
    vf_correction_t correction;
    uint32_t rays;
    bool partial_slabs;
    uint8_t *rgb;
} study_reference_t;

#define STUDY_MAX_REFERENCES 512

/* Where one scene's distance from the truth comes from (study_floor.c): the floor, exact ray integrals at the
 * intermediate pixels warped, against the truth; per mode (point, preint1, preclass, as ref_mode_t) and side-face
 * rule ([0] section 4's whole slabs, [1] partial slabs) the double reference's intermediate image against those
 * exact integrals (the integration alone) and its final image against the truth. PSNR in dB. The intermediate
 * image has the rays per voxel column study_floor is given (or the scene's, sim_scene_t.params.rays). */
#define STUDY_FLOOR_MODES 3
#define STUDY_RAYS_STEPS 5 /* R = 1, 2, 4, 8, 16 */
typedef struct study_floor {
    int done, scene;
    int rays;              /* R: R x R intermediate pixels per voxel */
    int table_size;        /* N of the reference's tables */
    int int_w, int_h;      /* the intermediate image, R (int_w - 1) + 1 by R (int_h - 1) + 1 of section 3 */
    double exact_db;
    double integration_db[STUDY_FLOOR_MODES][2];
    double truth_db[STUDY_FLOOR_MODES][2];
} study_floor_t;

typedef struct study {
    study_scene_t scenes[STUDY_MAX_SCENES];
    int scene_count;
    study_run_t runs[STUDY_MAX_RUNS];
    int run_count;
    study_reference_t references[STUDY_MAX_REFERENCES];
    int reference_count;
    int threads;           /* for truth renders */
    int quick;
    int lighting_only;     /* --lighting-only: the lighting stages alone, and a report of them alone */
    int order2_only;       /* --order2-only: preint2's 3D table study alone (study_order2.c, its own files) */
    const char *dir;
    double started_ms;
    int progress_tty;      /* rewrite one progress line (a terminal) or print one per run (a log) */
    study_floor_t floor;   /* of the whole-view Marschner-Lobb scene, for the report's first claim */
    /* The same at R = 1, 2, 4, 8, 16 rays per voxel column (index log2 R; .done 0 where not measured: the quick
     * study measures R = 1 only, which is floor) */
    study_floor_t rays_floor[STUDY_RAYS_STEPS];
    int time_frames;       /* study_run: frames to time after the compared one (0: the compared frame only) */
    int keep_images;       /* study_run: keep the core's image in the run (for strips of non-default options) */
    int count_instructions; /* study_run: count instructions per frame (when valgrind is there) */
    int have_valgrind;     /* -1 not asked yet, 0 no, 1 yes */
} study_t;

/* Candidate configurations for a microcontroller with 256 KB of RAM (the report's recommendation (b)). cmd_study.c
 * runs each on the microcontroller's own scene (boards/mps2-an386: bucky at 64x64, "bucky-sharp-64"), factor
 * "mcu", value the candidate's index. */
typedef struct study_mcu_candidate {
    vf_mode_t mode;
    uint32_t table_size, table_bits, rays;
    bool partial_slabs;
} study_mcu_candidate_t;

#define STUDY_MCU_CANDIDATES 10
extern const study_mcu_candidate_t study_mcu_candidates[STUDY_MCU_CANDIDATES];

/* The default parameters with candidate k's options. */
vf_params_t study_mcu_params(int k);

/* Add a scene; returns its index, or -1 with err. The volume is loaded at once. */
int study_add_scene(study_t *st, const char *label, const char *volume, const char *preset, double azimuth,
                    double elevation, double zoom, uint32_t size, char *err, size_t errlen);

/* The study's default configuration: preint1, 256 entries, 16-bit, nearest, rebuild, full precision. */
vf_params_t study_default_params(void);

/* Run one configuration on a scene (rendering the truth, unless with_truth is 0, and the matching reference
 * first if they are not cached) and record it. Returns the run, or NULL with err. */
study_run_t *study_run(study_t *st, int scene, const vf_params_t *params, const char *factor, const char *value,
                       int with_truth, char *err, size_t errlen);

/* Instructions per frame of the core with these parameters on a scene, as tools/bench.sh counts them: callgrind
 * around vfp_render_frame of `volfix-sim bench SCENE --frames 1 --rounds 1` (a warm-up frame and one more, 2
 * degrees apart, tables rebuilt for each), halved. The precision knobs (sample, intermediate, warp bits) are not
 * passed: count only default-precision runs. 0 when valgrind is not installed or the count failed. */
uint64_t study_instructions(study_t *st, int scene, const vf_params_t *params);

/* Render a scene's core image for a configuration into rgb (size * size * 3). Returns VFP_OK, or VFP_ERR with
 * err. */
vfp_status_t study_render_core(study_t *st, int scene, const vf_params_t *params, uint8_t *rgb, char *err,
                               size_t errlen);

/* The same, and the renderer's memory. */
vfp_status_t study_render_core_memory(study_t *st, int scene, const vf_params_t *params, uint8_t *rgb,
                                      vf_memory_t *memory, char *err, size_t errlen);

/* One line of progress for a run just recorded. */
void study_progress(study_t *st, const study_run_t *run);

/* study_lit.c: the lighting stages (normal codes, shade table and lit table bits; the shade lookup in the full
 * study) on lit scenes, Marschner-Lobb 41^3 and, in the full study, the shared volumes under data. The lit
 * default: study_default_params with lighting. Returns VFP_OK, or VFP_ERR with err. */
vf_params_t study_lit_params(void);
vfp_status_t study_lit(study_t *st, const char *data, char *err, size_t errlen);

/* The scene's truth image (rendered on first use). NULL with err on failure. */
const uint8_t *study_truth(study_t *st, int scene, char *err, size_t errlen);

/* Measure a scene's floor and its integration errors (study_floor_t) into out, with R rays per voxel column and
 * N table entries (0: the scene's own). Returns VFP_OK, or VFP_ERR with err. */
vfp_status_t study_floor(study_t *st, int scene, int rays, int table_size, study_floor_t *out, char *err,
                         size_t errlen);

/* study_order2.c: preint2's 3D table, resolution 16..128 and entry bits 16..8, on Marschner-Lobb 41^3 and (full
 * study, with data) neghip, against the reference, both truths, with memory; DIR/order2.csv, .gp, .png, .md with
 * the size for 256 KB, 1 MB and 64 MB boards. Returns VFP_OK, or VFP_ERR with err. */
vfp_status_t study_order2(study_t *st, const char *data, char *err, size_t errlen);

void study_free(study_t *st);

/* study_report.c: CSV of every run, gnuplot plots, image strips, report.md and summary.json in st->dir.
 * Returns VFP_OK, or VFP_ERR with err. */
vfp_status_t study_write_report(study_t *st, char *err, size_t errlen);

#endif
