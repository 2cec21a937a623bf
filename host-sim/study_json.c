/* SPDX-License-Identifier: MIT */
/* study_json.c: summary.json, one object with the numbers the precision study's claims rest on, for tests and
 * scripts. */
#include <stdio.h>

#include "render/render_mt.h"
#include "study_report.h"

vfp_status_t study_write_summary(const study_t *st, const study_claims_t *c, const char *claim_strip, char *err,
                                 size_t errlen)
{
    const study_floor_t *fl = &st->floor;
    FILE *j = study_open_file(st, "summary.json", err, errlen);
    if (!j)
        return VFP_ERR;
    fprintf(j, "{\"quick\": %d, \"runs\": %d, \"scenes\": %d, \"seconds\": %.1f, "
               "\"ml41_sharp_preint1_truth_psnr_db\": %.3f, \"ml41_sharp_point_truth_psnr_db\": %.3f, "
               "\"preint1_gain_db\": %.3f, \"interior_preint1_truth_psnr_db\": %.3f, "
               "\"interior_point_truth_psnr_db\": %.3f, \"interior_preint1_gain_db\": %.3f, "
               "\"default_fixed_point_max_abs\": %d, \"default_fixed_point_min_psnr_db\": %.3f, "
               "\"default_fixed_point_cases\": %d, \"cube_truth_psnr_db\": %.3f, \"ml41_sharp_floor_db\": %.3f, "
               "\"integration_point_db\": [%.3f, %.3f], \"integration_preint1_db\": [%.3f, %.3f], "
               "\"reference_point_truth_db\": [%.3f, %.3f], \"reference_preint1_truth_db\": [%.3f, %.3f]",
            st->quick, st->run_count, st->scene_count, (vfp_now_ms() - st->started_ms) / 1000, c->preint1_truth_db,
            c->point_truth_db, c->gain_db, c->inside_preint1_db, c->inside_point_db, c->inside_gain_db, c->fixed_max,
            c->fixed_min_psnr, c->fixed_cases, c->cube_db, fl->exact_db, fl->integration_db[REF_MODE_POINT][0],
            fl->integration_db[REF_MODE_POINT][1], fl->integration_db[REF_MODE_PREINT1][0],
            fl->integration_db[REF_MODE_PREINT1][1], fl->truth_db[REF_MODE_POINT][0], fl->truth_db[REF_MODE_POINT][1],
            fl->truth_db[REF_MODE_PREINT1][0], fl->truth_db[REF_MODE_PREINT1][1]);
    /* claim 1 without the shared errors */
    fprintf(j, ", \"claim_rays\": %u, \"claim_partial_slabs\": 1, \"claim_table_size\": %u, \"claim_measured\": %d, "
               "\"claim_point_truth_psnr_db\": %.3f, \"claim_preint1_truth_psnr_db\": %.3f, "
               "\"claim_preclass_truth_psnr_db\": %.3f, \"claim_gain_db\": %.3f, \"claim_max_abs_vs_reference\": %d, "
               "\"rays8_point_truth_psnr_db\": %.3f, \"rays8_preint1_truth_psnr_db\": %.3f, \"rays8_gain_db\": %.3f, "
               "\"rays_runs\": %d, \"rays_max_abs_vs_reference\": %d, \"rays_min_psnr_vs_reference_db\": %.3f, "
               "\"claim_strip\": \"%s\"}\n",
            STUDY_CLAIM_RAYS, STUDY_CLAIM_TABLE, c->have_claim, c->claim_point_db, c->claim_preint1_db,
            c->claim_preclass_db, c->claim_gain_db, c->claim_max_ref, c->r8_point_db, c->r8_preint1_db, c->r8_gain_db,
            c->rays_runs, c->rays_max_ref, c->rays_min_psnr, claim_strip);
    fclose(j);
    return VFP_OK;
}
