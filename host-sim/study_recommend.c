/* SPDX-License-Identifier: MIT */
/* study_recommend.c: report.md's recommendations, derived from the precision study's runs: the smallest safe
 * precision of each stage, (a) a Raspberry Pi class board, (b) a microcontroller with 256 KB of RAM. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/tf.h"
#include "study_report.h"

#define MCU_RAM (256u * 1024u)

/* The smallest setting of a stage at which every scene stays within PSNR 50 dB and 2 levels of the reference. */
static const char *smallest_safe(const study_t *st, const char *factor, char *out, size_t len)
{
    long best = -1;
    for (int i = 0; i < st->run_count; i++) {
        const study_run_t *r = &st->runs[i];
        if (strcmp(r->factor, factor) != 0)
            continue;
        long v = atol(r->value);
        int safe = 1;
        for (int j = 0; j < st->run_count; j++) { /* safe on every scene where it was tried */
            const study_run_t *q = &st->runs[j];
            if (strcmp(q->factor, factor) == 0 && atol(q->value) == v &&
                (q->vs_reference.psnr_db < 50 || q->vs_reference.max_abs[3] > 2))
                safe = 0;
        }
        if (safe && (best < 0 || v < best))
            best = v;
    }
    if (best < 0)
        snprintf(out, len, "none tried was safe");
    else
        snprintf(out, len, "%ld", best);
    return out;
}

/* Memory a configuration needs for the microcontroller scene (boards/mps2-an386): bucky, 32^3, and a 64x64
 * image, on one thread, measured by building the renderer (run lists depend on the data: a sphere phantom stands
 * in when $VOLFIX_DATA is unset or has no bucky). */
static size_t mcu_bytes(const vf_params_t *p)
{
    const char *data = getenv("VOLFIX_DATA");
    char path[1024], err[VFP_ERR_LEN];
    snprintf(path, sizeof path, "%s/bucky.nhdr", data && data[0] ? data : ".");
    vfp_volume_t vol;
    if ((!data || !data[0] || vfp_volume_load(&vol, path, NULL, err, sizeof err)) &&
        vfp_volume_load(&vol, "phantom:sphere:32", NULL, err, sizeof err))
        return 0;
    size_t fixed, total = 0;
    if (vf_renderer_bytes(p, &vol.core, &fixed) == VF_OK) {
        size_t size = fixed * 2;
        void *buf = malloc(size);
        vf_arena_t arena;
        vf_arena_init(&arena, buf, size);
        vf_renderer_t *r;
        vfp_tf_t tf;
        vf_tf_point_t pts[VF_MAX_TF_POINTS];
        vfp_tf_preset(&tf, "sharp", err, sizeof err);
        vf_tf_t core_tf = {pts, vfp_tf_to_core(&tf, &vol, vfp_default_window(&vol), pts)};
        if (buf && vf_renderer_create(&r, p, &vol.core, &arena) == VF_OK &&
            vf_renderer_set_window(r, vfp_default_window(&vol)) == VF_OK && vf_renderer_set_tf(r, &core_tf) == VF_OK)
            total = arena.used + vf_renderer_band_scratch_bytes(r, 8);
        free(buf);
    }
    vfp_volume_free(&vol);
    return total;
}

/* How many times a's frame costs b's: by instructions when both were counted (clears *by_instructions
 * otherwise), else by time. */
static double cost_ratio(const study_run_t *a, const study_run_t *b, int *by_instructions)
{
    if (a && b && a->instructions && b->instructions)
        return (double)a->instructions / (double)b->instructions;
    *by_instructions = 0;
    return a && b && study_frame_ms(b) > 0 ? study_frame_ms(a) / study_frame_ms(b) : 0;
}

/* Recommendation (a), continued: rays per voxel column, partial slabs and 1024 entries on a board with memory to
 * spare, from the rays sweeps (preint1, the scene's own table, whole slabs unless said). */
static void pi_rays(FILE *f, const study_t *st)
{
    static const unsigned rays[3] = {1, 2, 4};
    int scenes[STUDY_MAX_SCENES], count = 0;
    for (int s = 0; s < st->scene_count && count < STUDY_MAX_SCENES; s++)
        if (study_find_rays(st, st->scenes[s].label, 0, strcmp(st->scenes[s].label, "bucky-sharp-64") ? 256 : 64, 2,
                      VF_MODE_PREINT1))
            scenes[count++] = s;
    if (!count) {
        fprintf(f, "Rays per voxel column and partial slabs were not measured on enough scenes in this run to "
                   "recommend them (the full study does).\n\n");
        return;
    }
    fprintf(f, "Rays per voxel column and partial slabs, `preint1` on every scene with a rays sweep (its own size and "
               "table; whole slabs; partial slabs at the best R; time per frame %s):\n\n"
               "| scene | pixels per voxel | R = 1 | R = 2 | R = 4 | partial slabs | ms per frame R = 1 / 2 / 4 | "
               "M instructions per frame R = 1 / 2 / 4 | memory (MB) R = 1 / 2 / 4 |\n"
               "|---|---|---|---|---|---|---|---|---|\n",
            st->quick ? "one frame, wall-clock" : "median CPU time of 5 frames, one thread");
    double gain2_min = 1e9, gain2_max = -1e9, cost2_min = 1e9, cost2_max = 0, gain4_min = 1e9, gain4_max = -1e9;
    double cost4_min = 1e9, cost4_max = 0;
    double part_ml = 0, part_other = 0, minified_gain = -1e9, minified_ppv = 0;
    const char *gain2_min_at = "", *gain2_max_at = "", *minified_at = "", *cost2_min_at = "", *cost2_max_at = "";
    int part_ml_r = 0, by_instructions = 1;
    for (int i = 0; i < count; i++) {
        const study_scene_t *sc = &st->scenes[scenes[i]];
        const unsigned n = strcmp(sc->label, "bucky-sharp-64") ? 256 : 64;
        const double ppv = study_pixels_per_voxel(sc);
        const study_run_t *r[3], *p[3];
        for (int k = 0; k < 3; k++) {
            r[k] = study_find_rays(st, sc->label, 0, n, rays[k], VF_MODE_PREINT1);
            p[k] = study_find_rays(st, sc->label, 1, n, rays[k], VF_MODE_PREINT1);
        }
        if (!r[0] || !r[1])
            continue;
        int best = 0;
        for (int k = 1; k < 3; k++)
            if (r[k] && r[k]->vs_truth.psnr_db > r[best]->vs_truth.psnr_db)
                best = k;
        fprintf(f, "| %s (%u) | %.2f |", sc->label, sc->size, ppv);
        for (int k = 0; k < 3; k++)
            if (r[k])
                fprintf(f, " %.2f |", r[k]->vs_truth.psnr_db);
            else
                fprintf(f, " - |");
        double part = p[best] ? p[best]->vs_truth.psnr_db - r[best]->vs_truth.psnr_db : 0;
        if (p[best])
            fprintf(f, " %+.2f dB at R = %u |", part, rays[best]);
        else
            fprintf(f, " - |");
        for (int k = 0; k < 3; k++)
            fprintf(f, r[k] ? "%s%.1f" : "%s-", k ? " / " : " ", r[k] ? study_frame_ms(r[k]) : 0.0);
        fprintf(f, " |");
        for (int k = 0; k < 3; k++) {
            char text[32];
            fprintf(f, "%s%s", k ? " / " : " ", study_minstr(r[k], text, sizeof text));
        }
        fprintf(f, " |");
        for (int k = 0; k < 3; k++)
            fprintf(f, r[k] ? "%s%.1f" : "%s-", k ? " / " : " ", r[k] ? study_run_kb(r[k]) / 1024 : 0.0);
        fprintf(f, " |\n");
        double gain2 = r[1]->vs_truth.psnr_db - r[0]->vs_truth.psnr_db;
        double cost2 = cost_ratio(r[1], r[0], &by_instructions);
        if (gain2 < gain2_min)
            gain2_min = gain2, gain2_min_at = sc->label;
        if (gain2 > gain2_max)
            gain2_max = gain2, gain2_max_at = sc->label;
        if (cost2 < cost2_min)
            cost2_min = cost2, cost2_min_at = sc->label;
        if (cost2 > cost2_max)
            cost2_max = cost2, cost2_max_at = sc->label;
        if (ppv >= 2 && r[2]) {
            double gain4 = r[2]->vs_truth.psnr_db - r[1]->vs_truth.psnr_db;
            double cost4 = cost_ratio(r[2], r[1], &by_instructions);
            gain4_min = gain4 < gain4_min ? gain4 : gain4_min;
            gain4_max = gain4 > gain4_max ? gain4 : gain4_max;
            cost4_min = cost4 < cost4_min ? cost4 : cost4_min;
            cost4_max = cost4 > cost4_max ? cost4 : cost4_max;
        }
        if (ppv < 1 && gain2 > minified_gain)
            minified_gain = gain2, minified_ppv = ppv, minified_at = sc->label;
        if (strcmp(sc->label, "ml41-sharp") == 0)
            part_ml = part, part_ml_r = (int)rays[best];
        else if (fabs(part) > fabs(part_other))
            part_other = part;
    }
    fprintf(f, "\n");
    /* Marschner-Lobb at 512x512: where more rays stop paying, and what 1024 entries add */
    const study_run_t *m4 = study_find_rays(st, "ml41-sharp", 1, 256, 4, VF_MODE_PREINT1);
    const study_run_t *m4k = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, 4, VF_MODE_PREINT1);
    const study_run_t *m8k = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, 8, VF_MODE_PREINT1);
    const study_run_t *m16k = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, 16, VF_MODE_PREINT1);
    const study_run_t *m1 = study_find_rays(st, "ml41-sharp", 1, 256, 1, VF_MODE_PREINT1);
    const study_run_t *m1w = study_find_rays(st, "ml41-sharp", 0, 256, 1, VF_MODE_PREINT1);
    const study_run_t *m1k = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, 1, VF_MODE_PREINT1);
    int measured = 0;
    for (int i = 0; i < count; i++)
        measured += study_find_rays(st, st->scenes[scenes[i]].label, 0,
                                    strcmp(st->scenes[scenes[i]].label, "bucky-sharp-64") ? 256 : 64, 1,
                                    VF_MODE_PREINT1) != NULL;
    if (measured < 3) {
        fprintf(f, "This run measured rays on %d scene%s only, too few to recommend them (the full study has more): "
                   "2 x 2 rays came %.2f dB closer to the truth there for %.1f times the %s per frame.\n\n",
                measured, measured == 1 ? "" : "s", gain2_max, cost2_max, by_instructions ? "instructions" : "time");
        return;
    }
    fprintf(f, "Recommended for such a board, on top of the defaults: **2 x 2 rays per voxel column** (`rays = 2`) on "
               "any display, where the frame budget allows: every scene measured came %.2f (%s) to %.2f dB (%s) closer "
               "to the truth with it, for %.1f (%s) to %.1f times (%s) the %s per frame and about four times the "
               "intermediate image.",
            gain2_min, gain2_min_at, gain2_max, gain2_max_at, cost2_min, cost2_min_at, cost2_max, cost2_max_at,
            by_instructions ? "instructions" : "time");
    if (minified_gain > 1)
        fprintf(f, " Rays pay where a voxel covers less than an output pixel too (%s, %.2f pixels per voxel: %+.2f "
                   "dB): the warp interpolates between rays a voxel apart, which loses the detail inside a voxel "
                   "whatever the output size, while the truth has a ray of its own for every output pixel.",
                minified_at, minified_ppv, minified_gain);
    if (gain4_max > -1e9)
        fprintf(f, " **4 x 4** where a voxel covers two output pixels or more and the frame time allows: another %.2f "
                   "to %.2f dB over R = 2 there, for %.1f to %.1f times R = 2's %s%s.",
                gain4_min, gain4_max, cost4_min, cost4_max, by_instructions ? "instructions" : "time",
                minified_gain > -1e9 ? " (R = 4 was not measured on smaller magnifications)" : "");
    if (m4k && m8k && m16k) {
        int by = 1;
        double c8 = cost_ratio(m8k, m4k, &by), c16 = cost_ratio(m16k, m4k, &by);
        fprintf(f, " Not more: on Marschner-Lobb at 512x512 (7.4 pixels per voxel) R = 8 and 16 are %+.2f and %+.2f dB "
                   "from R = 4's distance to the truth (partial slabs, %u entries) for %.1f and %.1f times its %s.",
                m8k->vs_truth.psnr_db - m4k->vs_truth.psnr_db, m16k->vs_truth.psnr_db - m4k->vs_truth.psnr_db,
                STUDY_CLAIM_TABLE, c8, c16, by ? "instructions" : "time");
    }
    if (part_ml_r)
        fprintf(f, " **Partial slabs** where a volume is visible up to its box, as Marschner-Lobb is (%+.2f dB at R = "
                   "%d); on the other scenes they changed at most %+.2f dB. They cost no memory%s",
                part_ml, part_ml_r, part_other, m1 && m1w ? "" : ".");
    if (part_ml_r && m1 && m1w) {
        /* their cost at one ray on every scene, and on Marschner-Lobb at four */
        const study_run_t *m4w = study_find_rays(st, "ml41-sharp", 0, 256, 4, VF_MODE_PREINT1);
        int by = 1;
        double lo = 1e9, hi = 0, c4 = cost_ratio(m4, m4w, &by);
        const char *lo_at = "", *hi_at = "";
        for (int i = 0; i < count; i++) {
            const char *label = st->scenes[scenes[i]].label;
            const unsigned n = strcmp(label, "bucky-sharp-64") ? 256 : 64;
            double c = cost_ratio(study_find_rays(st, label, 1, n, 1, VF_MODE_PREINT1),
                                  study_find_rays(st, label, 0, n, 1, VF_MODE_PREINT1), &by);
            if (c > 0 && c < lo)
                lo = c, lo_at = label;
            if (c > hi)
                hi = c, hi_at = label;
        }
        fprintf(f, " and %.0f%% (%s) to %.0f%% (%s) more %s at one ray, %.0f%% on Marschner-Lobb at four: the core "
                   "composites the pixels along the faces exactly rather than fast (core/composite_partial.c), so they "
                   "are worth it only where a volume reaches its box.",
                100 * (lo - 1), lo_at, 100 * (hi - 1), hi_at, by ? "instructions" : "time", 100 * (c4 - 1));
    }
    if (m4 && m4k && m1 && m1k) {
        int by = 1;
        double extra = m1k->instructions && m1->instructions ? (m1k->instructions - (double)m1->instructions) / 1e6 : 0;
        fprintf(f, " **1024 table entries** only together with rays: on Marschner-Lobb `sharp` (peaks 10 entries wide "
                   "at 256) they gain %.2f dB at R = 4 with partial slabs (%.2f against %.2f dB) but %.2f dB at R = 1, "
                   "for %.1f MB more memory and",
                m4k->vs_truth.psnr_db - m4->vs_truth.psnr_db, m4k->vs_truth.psnr_db, m4->vs_truth.psnr_db,
                m1k->vs_truth.psnr_db - m1->vs_truth.psnr_db, (study_run_kb(m4k) - study_run_kb(m4)) / 1024);
        if (extra > 0)
            fprintf(f, " %.0f M more instructions per frame for the table that every view rebuilds (%.1f against "
                       "%.1f M at one ray).",
                    extra, m1k->instructions / 1e6, m1->instructions / 1e6);
        else
            fprintf(f, " %.1f times the time per frame at one ray.", cost_ratio(m1k, m1, &by));
    }
    fprintf(f, " The renderer's defaults stay as they are (one ray, whole slabs, 256 entries); a board file or the "
               "viewer would choose these, knowing its display and its frame budget.\n\n");
}

void study_recommend(FILE *f, const study_t *st)
{
    char t[32], s[32], i[32], w[32];
    smallest_safe(st, "table_bits", t, sizeof t);
    smallest_safe(st, "sample_bits", s, sizeof s);
    smallest_safe(st, "intermediate_bits", i, sizeof i);
    smallest_safe(st, "warp_bits", w, sizeof w);
    fprintf(f, "## Recommendations\n\n");
    fprintf(f, "The smallest precision of each stage that kept every scene it was tried on within PSNR 50 dB and 2 "
               "levels of the reference (one stage reduced at a time): table entries %s bits, samples %s fraction "
               "bits (32 = exact), intermediate image %s bits, warp weights %s fraction bits.\n\n", t, s, i, w);

    const study_run_t *rows[STUDY_MODES];
    fprintf(f, "Orders on Marschner-Lobb, PSNR against the truth (sharp / smooth):");
    for (int m = 0; m < STUDY_MODES; m++) {
        rows[m] = study_find(st, "ml41-sharp", "order", vf_mode_name((vf_mode_t)m));
        const study_run_t *smooth = study_find(st, "ml41-ramp", "order", vf_mode_name((vf_mode_t)m));
        fprintf(f, " %s %.1f / %.1f dB%s", vf_mode_name((vf_mode_t)m), rows[m] ? rows[m]->vs_truth.psnr_db : 0,
                smooth ? smooth->vs_truth.psnr_db : 0, m + 1 < STUDY_MODES ? ";" : ".\n\n");
    }
    const study_run_t *n256 = study_find(st, "ml41-sharp", "table_size_nearest", "256");
    const study_run_t *b256 = study_find(st, "ml41-sharp", "table_size_bilinear", "256");
    const study_run_t *lut = study_find(st, "ml41-sharp", "correction", "lut");
    const study_run_t *reb = study_find(st, "ml41-sharp", "correction", "rebuild");

    double time_ratio = n256 && b256 && n256->ms > 0 ? b256->ms / n256->ms : 0;
    double lut_ratio = reb && lut && reb->ms > 0 ? lut->ms / reb->ms : 0;
    fprintf(f, "**(a) A Raspberry Pi class board** (hundreds of MB, 4 cores): `preint1`, 256 entries, 16-bit tables, "
               "nearest lookup, tables rebuilt for each view, exact samples, 16-bit accumulation and warp: the "
               "renderer's defaults. Evidence, from this run: pre-integration is the closest to the truth on the sharp "
               "transfer function above; at 256 entries bilinear lookups gain %.2f dB against the truth (%.1f vs "
               "%.1f dB) for %.1f times the frame time (one frame each, 512x512, this machine; make bench measures "
               "properly), so nearest; the lut correction is %.2f dB from rebuilding the tables (%.1f vs %.1f dB) "
               "for %.1f times the frame time; 256 entries give every 8-bit scalar its own entry. Full precision "
               "costs no memory worth counting on such a board, and every reduced stage above was measured "
               "against it.\n\n",
            n256 && b256 ? b256->vs_truth.psnr_db - n256->vs_truth.psnr_db : 0, b256 ? b256->vs_truth.psnr_db : 0,
            n256 ? n256->vs_truth.psnr_db : 0, time_ratio,
            reb && lut ? lut->vs_truth.psnr_db - reb->vs_truth.psnr_db : 0, lut ? lut->vs_truth.psnr_db : 0,
            reb ? reb->vs_truth.psnr_db : 0, lut_ratio);
    pi_rays(f, st);

    /* Microcontroller: measured memory of candidate configurations for the 32^3 scene. The voxels and the code
     * stay in flash; RAM holds the renderer, a 64x64 RGB565 frame (8 KB) and the stack: 32 KB are kept for those. */
    fprintf(f, "**(b) A microcontroller with 256 KB of RAM**, bucky (32^3) and a 64x64 image (the scene of "
               "boards/mps2-an386, %.2f output pixels per voxel), the `sharp` preset; the voxels and the code in "
               "flash, 32 KB of RAM kept for the frame and the stack. Renderer memory (arena and band scratch, one "
               "thread) measured by building each candidate; its accuracy measured on that scene itself "
               "(`bucky-sharp-64`, against its truth and the reference) and, where the sweeps above ran it, on "
               "Marschner-Lobb `sharp` at 512x512:\n\n",
            study_scene_index(st, "bucky-sharp-64") >= 0
                ? study_pixels_per_voxel(&st->scenes[study_scene_index(st, "bucky-sharp-64")])
                : 64 / (31 * sqrt(3.0)));
    fprintf(f, "| mode | entries | table bits | rays | slabs | memory (KB) | fits | bucky 64x64: PSNR vs truth | vs "
               "reference (max) | M instructions per frame (x86-64) | Marschner-Lobb: PSNR vs truth |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n");
    int chosen = -1;
    double chosen_truth = -1;
    double mcu_db[STUDY_MCU_CANDIDATES];
    size_t mcu_kb[STUDY_MCU_CANDIDATES];
    uint64_t mcu_instr[STUDY_MCU_CANDIDATES];
    for (int k = 0; k < STUDY_MCU_CANDIDATES; k++) {
        const study_mcu_candidate_t *cand = &study_mcu_candidates[k];
        vf_params_t p = study_mcu_params(k);
        size_t bytes = mcu_bytes(&p);
        int fits = bytes && bytes + 32 * 1024 <= MCU_RAM;
        char text[16];
        snprintf(text, sizeof text, "%d", k);
        const study_run_t *own = study_find_mode(st, "bucky-sharp-64", "mcu", text, p.mode);
        /* Marschner-Lobb: the table-size sweep (nearest, 16 bits, one ray, whole slabs), or the orders */
        const study_run_t *ml = NULL;
        snprintf(text, sizeof text, "%u", cand->table_size);
        if (cand->rays == 1 && !cand->partial_slabs && cand->table_bits == 16)
            ml = p.mode != VF_MODE_POINT    ? study_find(st, "ml41-sharp", "table_size_nearest", text)
                 : cand->table_size == 256 ? study_find(st, "ml41-sharp", "order", "point")
                                           : NULL;
        double truth = own ? own->vs_truth.psnr_db : ml ? ml->vs_truth.psnr_db : 0;
        mcu_db[k] = own ? own->vs_truth.psnr_db : -1;
        mcu_instr[k] = own ? own->instructions : 0;
        mcu_kb[k] = bytes;
        if (fits && truth > chosen_truth + 0.05) { /* a later (costlier) candidate must be measurably closer */
            chosen = k;
            chosen_truth = truth;
        }
        fprintf(f, "| %s | %u | %u | %u | %s | %.1f | %s |", vf_mode_name(p.mode), cand->table_size, cand->table_bits,
                cand->rays, cand->partial_slabs ? "partial" : "whole", bytes / 1024.0, fits ? "yes" : "no");
        char instr[32];
        if (own)
            fprintf(f, " %.2f | %.1f (%d) | %s |", own->vs_truth.psnr_db, own->vs_reference.psnr_db,
                    own->vs_reference.max_abs[3], study_minstr(own, instr, sizeof instr));
        else
            fprintf(f, " - | - | - |");
        if (ml)
            fprintf(f, " %.2f |\n", ml->vs_truth.psnr_db);
        else
            fprintf(f, " - |\n");
    }
    if (chosen >= 0) {
        const study_mcu_candidate_t *cand = &study_mcu_candidates[chosen];
        fprintf(f, "\nRecommended: `%s` with %u entries and %u-bit tables, %u ray%s per voxel column and %s slabs: the "
                   "candidate closest to the truth that fits (a costlier one only where it is more than 0.05 dB "
                   "closer); samples, accumulation and warp at full precision (they cost no memory). The three slice "
                   "copies (one per principal axis) are the largest part; a board that renders from one side only "
                   "would need one.",
                vf_mode_name(cand->mode), cand->table_size, cand->table_bits, cand->rays, cand->rays > 1 ? "s" : "",
                cand->partial_slabs ? "partial" : "whole");
        /* what the new options would give and cost here: 2 rays (candidate 7 against 3), partial slabs (6 against 3) */
        char ratio_text[64] = "";
        if (mcu_instr[6] && mcu_instr[3])
            snprintf(ratio_text, sizeof ratio_text, " and %.1f times the instructions per frame",
                     (double)mcu_instr[6] / (double)mcu_instr[3]);
        if (mcu_db[3] >= 0 && mcu_db[6] >= 0 && mcu_db[7] >= 0)
            fprintf(f, " Two rays per voxel column would bring this scene %.2f dB closer to the truth (%.2f against "
                       "%.2f dB with 64 entries, 16 bits), because even at %.2f output pixels per voxel one ray per "
                       "voxel column leaves the warp to interpolate between rays a voxel apart; but the intermediate "
                       "image grows four times and the renderer needs %.0f KB (%.0f KB with 8-bit tables), more than "
                       "the %u KB left beside the frame and the stack: a board with %.0f KB of RAM could have it. "
                       "Partial slabs change it by %.2f dB for %.1f KB more%s%s",
                    mcu_db[7] - mcu_db[3], mcu_db[7], mcu_db[3],
                    study_pixels_per_voxel(&st->scenes[study_scene_index(st, "bucky-sharp-64")]), mcu_kb[7] / 1024.0,
                    mcu_kb[8] / 1024.0, (MCU_RAM - 32 * 1024) / 1024, (mcu_kb[8] + 32 * 1024) / 1024.0,
                    mcu_db[6] - mcu_db[3], ((double)mcu_kb[6] - (double)mcu_kb[3]) / 1024.0, ratio_text,
                    fabs(mcu_db[6] - mcu_db[3]) < 0.2 ? ": nothing to gain on this scene, so off." : ".");
        fprintf(f, "\n\n");
    } else {
        fprintf(f, "\nNo candidate fits.\n\n");
    }
}
