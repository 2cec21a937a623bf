/* SPDX-License-Identifier: MIT */
/* study_csv.c: results.csv, one row per run of the precision study: its scene, configuration and measures. */
#include <stdio.h>
#include <string.h>

#include "study_report.h"

/* A text field of results.csv followed by its comma, quoted (RFC 4180) when it holds a comma or a quote, as
 * the fixed-point check's labels do ("fixed-engine-30,20"). */
static void csv_text(FILE *f, const char *s)
{
    if (!strpbrk(s, ",\"\n")) {
        fprintf(f, "%s,", s);
        return;
    }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', f);
        fputc(*s, f);
    }
    fputs("\",", f);
}

vfp_status_t study_write_csv(const study_t *st, char *err, size_t errlen)
{
    FILE *f = study_open_file(st, "results.csv", err, errlen);
    if (!f)
        return VFP_ERR;
    fprintf(f, "scene,volume,preset,view,size,factor,value,mode,table_size,table_bits,lookup,correction,buffer,rays,"
               "partial_slabs,sample_bits,intermediate_bits,warp_bits,ref_psnr_db,ref_max,ref_mean,ref_over1_pct,"
               "truth_psnr_db,truth_max,truth_mean,mem_slices,mem_runs,mem_tables,mem_intermediate,mem_band_scratch,"
               "mem_total,ms,frames_timed,frame_ms,frame_tables_ms,instructions\n");
    for (int i = 0; i < st->run_count; i++) {
        const study_run_t *r = &st->runs[i];
        const study_scene_t *sc = &st->scenes[r->scene];
        const vf_params_t *p = &r->params;
        csv_text(f, sc->label);
        csv_text(f, sc->volume);
        csv_text(f, sc->preset);
        fprintf(f, "\"%g,%g\",%u,", sc->azimuth, sc->elevation, sc->size);
        csv_text(f, r->factor);
        csv_text(f, r->value);
        fprintf(f, "%s,%u,%u,%s,%s,%s,%u,%d,%u,%u,%u,%.3f,%d,%.5f,%.5f,", vf_mode_name(p->mode),
                p->table_size, p->table_bits, vf_lookup_name(p->lookup), vf_correction_name(p->correction),
                vf_buffer_name(p->buffer), p->rays, p->partial_slabs ? 1 : 0, p->sample_bits, p->intermediate_bits,
                p->warp_bits, r->vs_reference.psnr_db, r->vs_reference.max_abs[3], r->vs_reference.mean_abs[3],
                r->vs_reference.over1_pct);
        if (r->vs_truth.pixels)
            fprintf(f, "%.3f,%d,%.5f,", r->vs_truth.psnr_db, r->vs_truth.max_abs[3], r->vs_truth.mean_abs[3]);
        else
            fprintf(f, ",,,");
        fprintf(f, "%zu,%zu,%zu,%zu,%zu,%zu,%.3f,%d,", r->memory.slices, r->memory.runs, r->memory.tables,
                r->memory.intermediate, r->band_bytes, r->memory.total + r->band_bytes, r->ms, r->frames_timed);
        if (r->frames_timed)
            fprintf(f, "%.3f,%.3f,", r->frame_ms, r->frame_tables_ms);
        else
            fprintf(f, ",,");
        if (r->instructions)
            fprintf(f, "%llu\n", (unsigned long long)r->instructions);
        else
            fprintf(f, "\n");
    }
    fclose(f);
    return VFP_OK;
}
