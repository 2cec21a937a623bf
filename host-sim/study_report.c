/* SPDX-License-Identifier: MIT */
/*
 * study_report.c: what the precision study writes, and report.md. study_write_report writes results.csv
 * (study_csv.c), the plots (study_plots.c), image strips of the same view in each order with their differences
 * from the truth (study_strips.c) and summary.json (study_json.c), then report.md, which embeds them, states the
 * claims and derives recommended configurations (study_recommend.c).
 */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "render/render_mt.h"
#include "study_report.h"

/* The intermediate image's size for R rays per voxel column at the scene's view (section 3). */
static vfp_status_t intermediate_size(const study_t *st, int scene, uint32_t rays, uint32_t *w, uint32_t *h)
{
    const sim_scene_t *s = &st->scenes[scene].scene;
    vf_factor_t f;
    if (vf_factor(&f, &s->vol.core, &s->view, s->width, s->height) != VF_OK || vf_factor_rays(&f, rays) != VF_OK)
        return VFP_ERR;
    *w = f.int_w;
    *h = f.int_h;
    return VFP_OK;
}

/* Claim 1 restated: the same comparison with the errors both orders share taken away, and R = 8 beside it. */
static void claim_without_shared(FILE *f, const study_t *st, const study_claims_t *c, const char *strip)
{
    int ml = study_scene_index(st, "ml41-sharp");
    if (!c->have_claim || ml < 0) {
        fprintf(f, "   (The rays sweep did not run, so claim 1 without the shared errors was not measured.)\n\n");
        return;
    }
    const study_scene_t *sc = &st->scenes[ml];
    uint32_t w1 = 0, h1 = 0, w = 0, h = 0, w8 = 0, h8 = 0;
    intermediate_size(st, ml, 1, &w1, &h1);
    intermediate_size(st, ml, STUDY_CLAIM_RAYS, &w, &h);
    intermediate_size(st, ml, 8, &w8, &h8);
    const double mag = study_pixels_per_voxel(sc);
    const study_run_t *pt = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, STUDY_CLAIM_RAYS, VF_MODE_POINT);
    const study_run_t *pre = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, STUDY_CLAIM_RAYS, VF_MODE_PREINT1);
    fprintf(f, "   **Claim 1 without the errors both orders share.** Three of the renderer's options take them away, "
               "and the slab count stays the same (one slab per slice, as in the default): `--rays %u` (%u x %u rays "
               "per voxel column, docs/algorithm.md 4b: a %ux%u intermediate image instead of %ux%u, so the warp no "
               "longer spreads one ray over %.1f x %.1f output pixels; zoom 1 puts the volume's diagonal, %.0f voxels, "
               "across %u pixels) removes the intermediate image's resolution; `--partial-slabs` (section 4c: a ray "
               "that crosses a side face between two slices takes the part of the slab inside the box, not all of it "
               "or nothing) removes the staircase at the box's side faces, where Marschner-Lobb is visible; "
               "`--table-size %u` makes `sharp`'s peaks %u entries wide instead of 10. With all three, `preint1` is "
               "%.2f dB from the truth and `point` %.2f dB (`preclass` %.2f dB): **%.2f dB closer** (claim: at least 6 "
               "dB; %s). The core is within %d level of 255 of the reference at this configuration (PSNR %.1f dB for "
               "point, %.1f dB for preint1)",
            STUDY_CLAIM_RAYS, STUDY_CLAIM_RAYS, STUDY_CLAIM_RAYS, w, h, w1, h1, mag, mag, sc->size / mag, sc->size,
            STUDY_CLAIM_TABLE, STUDY_CLAIM_TABLE / 256 * 10, c->claim_preint1_db, c->claim_point_db,
            c->claim_preclass_db, c->claim_gain_db, c->claim_gain_db >= 6 ? "holds" : "does NOT hold", c->claim_max_ref,
            pt->vs_reference.psnr_db, pre->vs_reference.psnr_db);
    fprintf(f, ", and within %d over all %d renders of the rays sweep (lowest PSNR %.1f dB).", c->rays_max_ref,
            c->rays_runs, c->rays_min_psnr);
    if (c->have_r8)
        fprintf(f, " With 8 x 8 rays (%ux%u), about one ray per output pixel here (%.1f pixels per voxel), `preint1` "
                   "is %.2f dB and `point` %.2f dB: %.2f dB closer.",
                w8, h8, mag, c->r8_preint1_db, c->r8_point_db, c->r8_gain_db);
    /* where each order is closest to the truth with partial slabs and claim 1's table */
    static const unsigned rays[STUDY_RAYS_STEPS] = {1, 2, 4, 8, 16};
    unsigned best_r[2] = {0, 0};
    double best_db[2] = {0, 0}, one_db[2] = {0, 0};
    int all = 1;
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < STUDY_RAYS_STEPS; k++) {
            const study_run_t *r = study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, rays[k],
                                             m ? VF_MODE_PREINT1 : VF_MODE_POINT);
            if (!r) {
                all = 0;
                continue;
            }
            if (k == 0)
                one_db[m] = r->vs_truth.psnr_db;
            if (r->vs_truth.psnr_db > best_db[m]) {
                best_db[m] = r->vs_truth.psnr_db;
                best_r[m] = rays[k];
            }
        }
    if (all)
        fprintf(f, " Over R = 1 to 16 (the plot below): `preint1` comes closest to the truth at R = %u (%.2f dB, %.2f "
                   "dB above one ray; %.2f dB at R = 16) and `point` at R = %u (%.2f dB, %.2f dB above one ray; %.2f "
                   "dB at R = 16). Past that each ray's own error shows: with fewer rays the warp averaged "
                   "neighbouring rays' errors (a blur), with more each output pixel gets a ray of its own, and point "
                   "sampling's rays, which step over the narrow peaks, are the more wrong.",
                best_r[1], best_db[1], best_db[1] - one_db[1], c->claim_preint1_db, best_r[0], best_db[0],
                best_db[0] - one_db[0], c->claim_point_db);
    if (all && st->rays_floor[0].done && st->rays_floor[STUDY_RAYS_STEPS - 1].done)
        fprintf(f, " The floor rises from %.1f dB at one ray to %.1f dB at 16 (the rays section's second table), so "
                   "from R = 4 on what is left is the slab integration itself.",
                st->rays_floor[0].exact_db, st->rays_floor[STUDY_RAYS_STEPS - 1].exact_db);
    else
        fprintf(f, " (This quick run has R = 16 only; the full study has every R.)");
    fprintf(f, "\n\n");
    if (strip[0])
        fprintf(f, "   ![claim 1's configuration side by side](%s)\n\n   The same view with %u x %u rays per voxel "
                   "column, partial slabs and %u entries. Top, left to right: point, preint1, preclass, the truth; "
                   "bottom: each order's difference from the truth, times 4.\n\n",
                strip, STUDY_CLAIM_RAYS, STUDY_CLAIM_RAYS, STUDY_CLAIM_TABLE);
}

/* The rays sweep on Marschner-Lobb, the floors at each R, and the sweeps on other scenes. */
static void rays_section(FILE *f, const study_t *st)
{
    static const unsigned rays[STUDY_RAYS_STEPS] = {1, 2, 4, 8, 16};
    const unsigned sizes[2] = {256, STUDY_CLAIM_TABLE};
    int ml = study_scene_index(st, "ml41-sharp");
    if (ml < 0)
        return;
    fprintf(f, "## Rays per voxel column and partial slabs\n\n![rays](rays.png)\n\n");
    fprintf(f, "Marschner-Lobb 41^3, `sharp`, 512x512, view 30,20 (%.1f output pixels per voxel): PSNR against the "
               "truth per mode, preint1's gain over point, the largest difference from the reference (levels of 255: "
               "point / preint1 / preclass), renderer memory (arena and one thread's band scratch) and the time per "
               "frame on one thread (%s), and instructions per frame (callgrind, as make bench counts them; where "
               "counted).\n\n",
            study_pixels_per_voxel(&st->scenes[ml]),
            st->quick ? "one frame, wall-clock, this machine"
                      : "median CPU time of 5 frames turning 2 degrees each, tables rebuilt every frame, this "
                        "machine; in brackets the table rebuild, wall-clock");
    fprintf(f, "| entries | slabs | R | intermediate image | point | preint1 | preclass | preint1 - point | max vs "
               "reference | memory (KB) point / preint1 | ms per frame point / preint1 | M instructions per frame "
               "point / preint1 |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (int n = 0; n < 2; n++)
        for (int partial = 0; partial < 2; partial++)
            for (int k = 0; k < STUDY_RAYS_STEPS; k++) {
                const study_run_t *r[3];
                int any = 0;
                for (int m = 0; m < 3; m++) {
                    r[m] = study_find_rays(st, "ml41-sharp", partial, sizes[n], rays[k], (vf_mode_t)m);
                    any |= r[m] != NULL;
                }
                if (!any)
                    continue;
                uint32_t w = 0, h = 0;
                intermediate_size(st, ml, rays[k], &w, &h);
                fprintf(f, "| %u | %s | %u | %ux%u |", sizes[n], partial ? "partial" : "whole", rays[k], w, h);
                for (int m = 0; m < 3; m++)
                    if (r[m])
                        fprintf(f, " %.2f |", r[m]->vs_truth.psnr_db);
                    else
                        fprintf(f, " - |");
                if (r[0] && r[1])
                    fprintf(f, " %.2f |", r[1]->vs_truth.psnr_db - r[0]->vs_truth.psnr_db);
                else
                    fprintf(f, " - |");
                for (int m = 0; m < 3; m++)
                    if (r[m])
                        fprintf(f, "%s%d", m ? " / " : " ", r[m]->vs_reference.max_abs[3]);
                    else
                        fprintf(f, "%s-", m ? " / " : " ");
                fprintf(f, " |");
                for (int m = 0; m < 2; m++)
                    if (r[m])
                        fprintf(f, "%s%.0f", m ? " / " : " ", study_run_kb(r[m]));
                    else
                        fprintf(f, "%s-", m ? " / " : " ");
                fprintf(f, " |");
                for (int m = 0; m < 2; m++) {
                    fprintf(f, "%s", m ? " / " : " ");
                    if (!r[m])
                        fprintf(f, "-");
                    else if (r[m]->frames_timed)
                        fprintf(f, "%.1f (%.1f)", r[m]->frame_ms, r[m]->frame_tables_ms);
                    else
                        fprintf(f, "%.1f", r[m]->ms);
                }
                char a[32], b[32];
                fprintf(f, " | %s / %s |\n", study_minstr(r[0], a, sizeof a), study_minstr(r[1], b, sizeof b));
            }
    fprintf(f, "\n");

    int floors = 0;
    for (int k = 0; k < STUDY_RAYS_STEPS; k++)
        floors += st->rays_floor[k].done;
    if (floors) {
        fprintf(f, "Where the rest comes from, at each R (the double reference, %d entries, as in the first claim's "
                   "table): the floor is the truth's exact integrals along the intermediate image's own rays, warped, "
                   "against the truth; the integration columns are the reference's intermediate image against those "
                   "exact integrals (the slab integration alone); the last two its final image against the truth. "
                   "PSNR in dB, partial slabs.\n\n"
                   "| R | intermediate image | floor | point, integration | preint1, integration | point vs truth | "
                   "preint1 vs truth |\n|---|---|---|---|---|---|---|\n",
                st->rays_floor[0].done ? st->rays_floor[0].table_size : (int)STUDY_CLAIM_TABLE);
        for (int k = 0; k < STUDY_RAYS_STEPS; k++) {
            const study_floor_t *fl = &st->rays_floor[k];
            if (!fl->done)
                continue;
            fprintf(f, "| %d | %dx%d | %.2f | %.2f | %.2f | %.2f | %.2f |\n", fl->rays, fl->int_w, fl->int_h,
                    fl->exact_db, fl->integration_db[REF_MODE_POINT][1], fl->integration_db[REF_MODE_PREINT1][1],
                    fl->truth_db[REF_MODE_POINT][1], fl->truth_db[REF_MODE_PREINT1][1]);
        }
        fprintf(f, "\n");
    }

    /* the other scenes that had a rays sweep */
    int header = 0;
    for (int s = 0; s < st->scene_count; s++) {
        if (s == ml)
            continue;
        const char *label = st->scenes[s].label;
        for (int partial = 0; partial < 2; partial++)
            for (int k = 0; k < STUDY_RAYS_STEPS; k++) {
                unsigned n = 0;
                const study_run_t *r[2] = {NULL, NULL};
                for (int i = 0; i < st->run_count && !n; i++)
                    if (st->runs[i].scene == s && study_is_rays_factor(st->runs[i].factor))
                        n = st->runs[i].params.table_size;
                for (int m = 0; m < 2 && n; m++)
                    r[m] = study_find_rays(st, label, partial, n, rays[k], (vf_mode_t)m);
                if (!r[0] && !r[1])
                    continue;
                if (!header) {
                    fprintf(f, "The same options elsewhere, each scene at its own size and table (pixels per "
                               "voxel: how much the warp magnifies the intermediate image at one ray; partial slabs "
                               "can change only what is visible at a volume's side faces):\n\n"
                               "| scene | size | pixels per voxel | entries | slabs | R | point | preint1 | memory "
                               "(KB) preint1 | ms per frame preint1 | M instructions per frame preint1 |\n"
                               "|---|---|---|---|---|---|---|---|---|---|---|\n");
                    header = 1;
                }
                fprintf(f, "| %s | %u | %.2f | %u | %s | %u |", label, st->scenes[s].size,
                        study_pixels_per_voxel(&st->scenes[s]), n, partial ? "partial" : "whole", rays[k]);
                for (int m = 0; m < 2; m++)
                    if (r[m])
                        fprintf(f, " %.2f |", r[m]->vs_truth.psnr_db);
                    else
                        fprintf(f, " - |");
                char text[32];
                if (r[1])
                    fprintf(f, " %.0f | %.1f | %s |\n", study_run_kb(r[1]), study_frame_ms(r[1]),
                            study_minstr(r[1], text, sizeof text));
                else
                    fprintf(f, " - | - | - |\n");
            }
    }
    if (header)
        fprintf(f, "\n");
}

/* Every run of a factor, one row each: its distance from the reference and the truth, and its memory. */
static void table_of(FILE *f, const study_t *st, const char *factor, const char *title)
{
    int which[STUDY_MAX_SCENES], n = study_scenes_with(st, factor, which, STUDY_MAX_SCENES);
    if (!n)
        return;
    fprintf(f, "%s\n\n| scene | value | PSNR vs reference | max | PSNR vs truth | memory (KB) |\n"
               "|---|---|---|---|---|---|\n",
            title);
    for (int k = 0; k < n; k++)
        for (int i = 0; i < st->run_count; i++) {
            const study_run_t *r = &st->runs[i];
            if (r->scene != which[k] || strcmp(r->factor, factor) != 0)
                continue;
            fprintf(f, "| %s | %s | %.1f | %d | ", st->scenes[r->scene].label, r->value, r->vs_reference.psnr_db,
                    r->vs_reference.max_abs[3]);
            if (r->vs_truth.pixels)
                fprintf(f, "%.1f | ", r->vs_truth.psnr_db);
            else
                fprintf(f, "- | ");
            fprintf(f, "%.0f |\n", (r->memory.total + r->band_bytes) / 1024.0);
        }
    fprintf(f, "\n");
}

/* The lighting stages (study_lit.c): a plot and a table each. */
static void lighting_section(FILE *f, const study_t *st)
{
    fprintf(f, "## Lighting\n\nLit `preint1` (docs/algorithm.md section 7: one headlight, material 0.1, 0.7, 0.2, "
               "10, bilinear shade lookup) on `sharp` scenes, each lighting stage on its own. The normal codes "
               "against the double reference with unquantised normals (section 7's gradients in double, "
               "normalised): the codes' error and the core's fixed point together; the shade table and the "
               "front-weighted table as the reference would have them with fewer bits, against the reference with "
               "them exact. *Against the truth* here is the lit truth (docs/algorithm.md, \"Lit truth\"), whose "
               "normals are the trilinear field's own gradients: most of that distance is how the normals are "
               "made, the same for every stage's setting.\n\n");
    fprintf(f, "![normal bits](normal_bits.png)\n\n");
    table_of(f, st, "normal_bits", "Normal codes (bits):");
    fprintf(f, "![shade table bits](shade_bits.png)\n\n");
    table_of(f, st, "shade_bits", "Shade table (fraction bits of L_d and L_s; the core keeps 14):");
    fprintf(f, "![lit table bits](lit_table_bits.png)\n\n");
    table_of(f, st, "lit_table_bits", "Front-weighted table (bits of D_f and S_f):");
    table_of(f, st, "shade_lookup", "A sample's shade, nearest or bilinear, against the lit truth (point and preint1):");
}

/* --lighting-only: results.csv, the lighting plots and a report of the lighting stages alone. */
static vfp_status_t lighting_report(study_t *st, char *err, size_t errlen)
{
    FILE *f = study_open_file(st, "report.md", err, errlen);
    if (!f)
        return VFP_ERR;
    fprintf(f, "# volfix precision study: the lighting stages%s\n\nWritten by `volfix-sim study --lighting-only%s -o "
               "%s`: %d runs on %d scenes in %.0f s; `results.csv` has every number.\n\n",
            st->quick ? " (quick)" : "", st->quick ? " --quick" : "", st->dir, st->run_count, st->scene_count,
            (vfp_now_ms() - st->started_ms) / 1000);
    lighting_section(f, st);
    fclose(f);
    return VFP_OK;
}

vfp_status_t study_write_report(study_t *st, char *err, size_t errlen)
{
    if (study_write_csv(st, err, errlen) || study_write_plots(st, err, errlen))
        return VFP_ERR;
    if (st->lighting_only)
        return lighting_report(st, err, errlen);
    char strips[5][128];
    int strip_count = 0;
    const char *strip_scenes[] = {"ml41-sharp", "ml41-sharp-interior", "ml41-ramp", "neghip-sharp"};
    for (size_t k = 0; k < 4; k++)
        for (int s = 0; s < st->scene_count; s++)
            if (strcmp(st->scenes[s].label, strip_scenes[k]) == 0 &&
                study_write_strip(st, s, NULL, NULL, strips[strip_count++], sizeof strips[0], err, errlen))
                return VFP_ERR;
    /* claim 1's configuration without the shared errors, when the rays sweep ran it */
    char claim_strip[128] = "";
    int ml = study_scene_index(st, "ml41-sharp");
    if (ml >= 0 && study_find_rays(st, "ml41-sharp", 1, STUDY_CLAIM_TABLE, STUDY_CLAIM_RAYS, VF_MODE_PREINT1)) {
        vf_params_t p = study_default_params();
        p.rays = STUDY_CLAIM_RAYS;
        p.partial_slabs = true;
        p.table_size = STUDY_CLAIM_TABLE;
        char suffix[64];
        snprintf(suffix, sizeof suffix, "rays%u-partial-%u", STUDY_CLAIM_RAYS, STUDY_CLAIM_TABLE);
        if (study_write_strip(st, ml, &p, suffix, claim_strip, sizeof claim_strip, err, errlen))
            return VFP_ERR;
    }

    study_claims_t c = study_claims(st);
    const study_floor_t *fl = &st->floor;
    if (study_write_summary(st, &c, claim_strip, err, errlen))
        return VFP_ERR;

    FILE *f = study_open_file(st, "report.md", err, errlen);
    if (!f)
        return VFP_ERR;
    time_t now = time(NULL);
    char when[64];
    strftime(when, sizeof when, "%Y-%m-%d %H:%M UTC", gmtime(&now));
    fprintf(f, "# volfix fixed-point precision study%s\n\n", st->quick ? " (quick)" : "");
    fprintf(f, "Written by `volfix-sim study%s -o %s` on %s: %d runs on %d scenes in %.0f s. Every number below "
               "was measured in this run; `results.csv` has all of them.\n\n",
            st->quick ? " --quick" : "", st->dir, when, st->run_count, st->scene_count,
            (vfp_now_ms() - st->started_ms) / 1000);
    fprintf(f, "- *Against the reference*: the core against the double-precision implementation of the same algorithm "
               "with the same algorithmic options (mode, table size, lookup, correction, rays, partial slabs) at full "
               "precision: the fixed-point error alone.\n"
               "- *Against the truth*: the core against a double ray caster through the same camera (trilinear "
               "reconstruction, steps of at most 1/16 voxel, exact integration of the piecewise-linear transfer "
               "function): the algorithm's own error.\n"
               "- PSNR over 8-bit RGB; max is the largest difference of any channel in levels of 255.\n\n");

    fprintf(f, "## The two claims\n\n");
    fprintf(f, "1. **Pre-integration against point sampling** on Marschner-Lobb 41^3, `sharp`, 512x512, view 30,20, "
               "the same slab spacing: `preint1` is %.2f dB from the truth, `point` %.2f dB: **%.2f dB closer** "
               "(claim: at least 6 dB; %s). Zoomed to the volume's interior (zoom 3, 256x256), where the rays' "
               "integration is all that differs: `preint1` %.2f dB, `point` %.2f dB, **%.2f dB closer** (%s).\n\n"
               "   Why the whole view gains less: shear-warp casts one ray per voxel column (the %dx%d intermediate "
               "image) and resamples it in the warp, and Marschner-Lobb with `sharp` has detail finer than a voxel. "
               "The truth's own exact integrals along those same rays, warped the same way, are **%.2f dB** from the "
               "truth: a floor, the same for both orders, that no slab integration passes on this view. The table "
               "below splits the double reference's distance (the core is within a level of it): against the exact "
               "integrals of its own rays, the integration alone, `preint1` is %.2f dB closer than `point` with whole "
               "slabs at the side faces and %.2f dB with partial slabs (the part of a slab inside the box where a ray "
               "crosses a side face); against the truth, after the warp, %.2f and %.2f dB. The side faces are the "
               "smaller part here; on the uniform cube `cube24`, where nothing else differs, the core renders %.1f dB "
               "from the truth. The peak-width plot below shows the rest: with peaks narrower than `sharp` the "
               "256-entry table limits both orders, with wider ones point sampling no longer misses them.\n\n"
               "   | double reference, PSNR in dB | point | preint1 | preclass |\n"
               "   |---|---|---|---|\n"
               "   | intermediate image against the exact integrals, whole slabs | %.2f | %.2f | %.2f |\n"
               "   | intermediate image against the exact integrals, partial slabs | %.2f | %.2f | %.2f |\n"
               "   | final image against the truth, whole slabs | %.2f | %.2f | %.2f |\n"
               "   | final image against the truth, partial slabs | %.2f | %.2f | %.2f |\n"
               "   | floor: the exact integrals, warped, against the truth | %.2f | %.2f | %.2f |\n\n"
               "   ![peak width](peaks.png)\n\n",
            c.preint1_truth_db, c.point_truth_db, c.gain_db, c.gain_db >= 6 ? "holds" : "does NOT hold",
            c.inside_preint1_db, c.inside_point_db, c.inside_gain_db,
            c.inside_gain_db >= 6 ? "at least 6 dB" : "less than 6 dB",
            fl->int_w, fl->int_h, fl->exact_db,
            fl->integration_db[REF_MODE_PREINT1][0] - fl->integration_db[REF_MODE_POINT][0],
            fl->integration_db[REF_MODE_PREINT1][1] - fl->integration_db[REF_MODE_POINT][1],
            fl->truth_db[REF_MODE_PREINT1][0] - fl->truth_db[REF_MODE_POINT][0],
            fl->truth_db[REF_MODE_PREINT1][1] - fl->truth_db[REF_MODE_POINT][1], c.cube_db,
            fl->integration_db[0][0], fl->integration_db[1][0], fl->integration_db[2][0],
            fl->integration_db[0][1], fl->integration_db[1][1], fl->integration_db[2][1],
            fl->truth_db[0][0], fl->truth_db[1][0], fl->truth_db[2][0],
            fl->truth_db[0][1], fl->truth_db[1][1], fl->truth_db[2][1],
            fl->exact_db, fl->exact_db, fl->exact_db);
    if (strip_count)
        fprintf(f, "   ![orders side by side](%s)\n\n   Top, left to right: %s, %s, %s, the truth; bottom: each "
                   "order's difference from the truth, times 4.\n\n",
                strips[0], vf_mode_name((vf_mode_t)0), vf_mode_name((vf_mode_t)1), vf_mode_name((vf_mode_t)2));
    claim_without_shared(f, st, &c, claim_strip);
    fprintf(f, "2. **The default configuration's fixed-point error** (`ramp`, the shared volumes at the views 0,0 "
               "30,20 45,0 60,-35 135,70, %s): at most **%d** level of 255 against the reference over %d renders "
               "(lowest PSNR %.1f dB; claim: at most 1; %s).\n\n",
            st->quick ? "brainsmall and neghip at 256x256 in this quick study" : "512x512", c.fixed_max, c.fixed_cases,
            c.fixed_min_psnr,
            c.fixed_cases && c.fixed_max <= 1 ? "holds" : c.fixed_cases ? "does NOT hold" : "no data");
    if (c.fixed_cases && c.fixed_max > 1)
        fprintf(f, "   The stages that round are the table entries (Q1.15), the accumulation (Q1.15 per slab) and "
                   "the warp (Q0.16 weights); the bits plots below show which of them it is.\n\n");

    fprintf(f, "## Bits per stage\n\n![bits](bits.png)\n\n");
    table_of(f, st, "table_bits", "Table entries:");
    table_of(f, st, "sample_bits", "Samples (fraction bits before the lookup; 32 is exact):");
    table_of(f, st, "intermediate_bits", "Intermediate image (bits after each slab):");
    table_of(f, st, "warp_bits", "Warp weights (fraction bits):");
    fprintf(f, "## Table size and lookup\n\n![table size](table_size.png)\n\n");
    table_of(f, st, "table_size_nearest", "Nearest lookup:");
    table_of(f, st, "table_size_bilinear", "Bilinear lookup:");
    fprintf(f, "## Orders, smooth and sharp\n\n![orders](orders.png)\n\n");
    table_of(f, st, "order", "Each order with the default tables:");
    table_of(f, st, "correction", "Opacity correction:");
    for (int k = 1; k < strip_count; k++)
        fprintf(f, "![%s](%s)\n\n", strips[k], strips[k]);
    rays_section(f, st);
    lighting_section(f, st);
    fprintf(f, "## Memory against error\n\n![memory](memory.png)\n\n");
    study_recommend(f, st);
    table_of(f, st, "fixed_point", "## The fixed-point check, every render\n");
    fclose(f);
    return VFP_OK;
}
