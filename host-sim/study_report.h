/* SPDX-License-Identifier: MIT */
/*
 * study_report.h: what the precision study's writers share and no one else uses: the runs looked up by scene,
 * factor and value, what a run cost, the numbers the claims rest on, and the writers themselves, one file each
 * (study_write_report in study.h calls them in this order):
 *   study_csv.c        results.csv, every run
 *   study_plots.c      the plots: NAME.dat, NAME.gp and, through gnuplot, NAME.png
 *   study_strips.c     image strips (PNG), the same view in each order beside the truth
 *   study_json.c       summary.json, the numbers the claims rest on, for tests
 *   study_report.c     report.md, which embeds the others and states the claims
 *   study_recommend.c  report.md's recommended configurations
 * Writers that can fail return VFP_OK, or VFP_ERR with a one-line message in err.
 */
#ifndef SIM_STUDY_REPORT_H
#define SIM_STUDY_REPORT_H

#include <stdio.h>

#include "study.h"

/* The numbers the two claims rest on (study_claims), as summary.json and report.md give them. */
typedef struct study_claims {
    double preint1_truth_db, point_truth_db, gain_db; /* Marschner-Lobb 41^3, sharp, 512x512 */
    double inside_preint1_db, inside_point_db, inside_gain_db; /* the same, zoomed to the interior */
    double cube_db;                                            /* a uniform cube against the truth (preint1) */
    int fixed_max, fixed_cases;                       /* the default configuration against the reference */
    double fixed_min_psnr;
    /* Claim 1 without the errors point and preint1 share: STUDY_CLAIM_RAYS rays, partial slabs, STUDY_CLAIM_TABLE
     * entries (0 where not run), and at 8 rays (about one ray per output pixel on this scene) */
    int have_claim, have_r8;
    double claim_point_db, claim_preint1_db, claim_preclass_db, claim_gain_db;
    double r8_point_db, r8_preint1_db, r8_gain_db;
    int claim_max_ref;                                /* point and preint1 against the reference there */
    int rays_runs, rays_max_ref;                      /* every rays sweep run on ml41-sharp against the reference */
    double rays_min_psnr;
} study_claims_t;

/* ------------------------------------------------------------------------------------------------------- */
/* study_results.c: the results looked up */

study_claims_t study_claims(const study_t *st);

/* NAME in the study's directory, open for writing; NULL with "DIR/NAME: cannot write" in err. */
FILE *study_open_file(const study_t *st, const char *name, char *err, size_t errlen);

/* The run of a scene (by label) with this factor and value, or NULL. */
const study_run_t *study_find(const study_t *st, const char *scene, const char *factor, const char *value);
/* The same for one mode: the rays sweeps run every mode under one factor and value. */
const study_run_t *study_find_mode(const study_t *st, const char *scene, const char *factor, const char *value,
                                   vf_mode_t mode);
/* A run of the rays sweeps (cmd_study.c: factor rays_whole_N or rays_partial_N, value R). */
const study_run_t *study_find_rays(const study_t *st, const char *scene, int partial, unsigned table_size,
                                   unsigned rays, vf_mode_t mode);
/* A scene's index by label, or -1. */
int study_scene_index(const study_t *st, const char *label);
/* The scenes (at most `most`) that have runs of this factor, into which[]; returns how many. */
int study_scenes_with(const study_t *st, const char *factor, int *which, int most);
int study_is_rays_factor(const char *factor);

/* A run's renderer memory (arena and one thread's band scratch) in KB. */
double study_run_kb(const study_run_t *r);
/* Frame time of a run: the median of its timed frames (each rebuilding the tables), else its one frame. */
double study_frame_ms(const study_run_t *r);
/* Instructions per frame in millions, as text ("-" when not counted). */
const char *study_minstr(const study_run_t *r, char *text, size_t len);
/* Output pixels per voxel (of the smallest spacing) along a line: the warp's magnification, scale of section 3. */
double study_pixels_per_voxel(const study_scene_t *sc);

/* ------------------------------------------------------------------------------------------------------- */
/* The writers */

vfp_status_t study_write_csv(const study_t *st, char *err, size_t errlen);
vfp_status_t study_write_plots(const study_t *st, char *err, size_t errlen);
/* The strip of a scene with the default configuration (base NULL) or base's rays, side-face rule and table size
 * for every mode; named strip-LABEL.png, or strip-LABEL-SUFFIX.png (the name goes into name). */
vfp_status_t study_write_strip(study_t *st, int scene, const vf_params_t *base, const char *suffix, char *name,
                               size_t namelen, char *err, size_t errlen);
/* claim_strip: the strip of claim 1's configuration, "" when the rays sweep did not run it. */
vfp_status_t study_write_summary(const study_t *st, const study_claims_t *c, const char *claim_strip, char *err,
                                 size_t errlen);
/* report.md's "Recommendations" section. */
void study_recommend(FILE *f, const study_t *st);

#endif
