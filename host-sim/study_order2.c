/* SPDX-License-Identifier: MIT */
/* study_order2.c: the precision study of preint2's 3D table (volfix-sim study --order2-only): its resolution N2
 * (16..128 a side) and entry bits (16, 12, 10, 8) against the double reference at full precision (the fixed-point
 * error), against the trilinear and the smooth truth (the algorithm's error), and the memory each takes; a plot,
 * and the size a board with 256 KB, 1 MB or 64 MB of RAM should use. Writes DIR/order2.csv, order2.gp,
 * order2.png (with gnuplot) and order2.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/pngio.h"
#include "study.h"
#include "truth/truth.h"

#define MAX_ROWS 256
#define NBITS 4

static const uint32_t sizes_full[] = {16, 24, 32, 48, 64, 96, 128};
static const uint32_t sizes_quick[] = {16, 32, 64};
static const uint32_t bits[NBITS] = {16, 12, 10, 8};

/* The boards: RAM, and the share of it the renderer may take (a bare-metal microcontroller gives it all, as the
 * study's MCU recommendation does; a Linux board keeps half for the system, the display and the volume file). */
static const struct board {
    const char *name;
    size_t ram;
    double share;
} boards[] = {{"256 KB microcontroller", 256 * 1024, 1.0}, {"1 MB board", 1024 * 1024, 0.5},
              {"64 MB board", 64u * 1024 * 1024, 0.5}};

typedef struct row {
    int scene;
    uint32_t n2, bits;         /* n2 0: the preint1 comparison row, table_size in bits' place */
    uint32_t table_size;
    sim_diff_t ref, tri, smooth;
    sim_diff_t conv;           /* against the reference with the largest 3D table studied (the table's own error) */
    size_t order2_bytes, total_bytes;
} row_t;

static vfp_status_t to_rgb(vf_image_t *img, uint8_t **rgb)
{
    *rgb = malloc((size_t)img->width * img->height * 3);
    if (*rgb)
        vfp_image_to_rgb(img, *rgb);
    sim_image_free(img);
    return *rgb ? VFP_OK : VFP_ERR;
}

/* The scene's truth with a filter (a copy of the scene with it), as 8-bit RGB. */
static uint8_t *truth_image(study_t *st, int scene, truth_filter_t filter, char *err, size_t errlen)
{
    sim_scene_t s = st->scenes[scene].scene;
    s.truth_filter = (int)filter;
    vf_image_t img;
    uint8_t *rgb = NULL;
    if (sim_render_truth(&s, &img, err, errlen) == VFP_OK && to_rgb(&img, &rgb))
        snprintf(err, errlen, "out of memory");
    return rgb;
}

/* The reference at full precision for preint2 at n2 (or preint1 at table_size when n2 is 0), on the core's
 * slice offsets. */
static uint8_t *reference_image(study_t *st, int scene, const vf_params_t *p, char *err, size_t errlen)
{
    sim_scene_t s = st->scenes[scene].scene;
    s.params = *p;
    s.params.table_bits = 16;
    vf_factor_t factor;
    vf_status_t fs = vf_factor(&factor, &s.vol.core, &s.view, s.width, s.height);
    if (fs != VF_OK) {
        snprintf(err, errlen, "cannot factor the view: %s", vf_status_text(fs));
        return NULL;
    }
    vf_image_t img;
    uint8_t *rgb = NULL;
    if (sim_render_reference(&s, &factor, &img, err, errlen) == VFP_OK && to_rgb(&img, &rgb))
        snprintf(err, errlen, "out of memory");
    return rgb;
}

static vfp_status_t measure(study_t *st, int scene, const vf_params_t *p, const uint8_t *ref, const uint8_t *conv,
                            const uint8_t *tri, const uint8_t *smooth, row_t *row, char *err, size_t errlen)
{
    const study_scene_t *sc = &st->scenes[scene];
    size_t pixels = (size_t)sc->size * sc->size;
    uint8_t *rgb = malloc(pixels * 3);
    vf_memory_t mem;
    if (!rgb) {
        snprintf(err, errlen, "out of memory");
        return VFP_ERR;
    }
    if (study_render_core_memory(st, scene, p, rgb, &mem, err, errlen)) {
        free(rgb);
        return VFP_ERR;
    }
    sim_diff(rgb, ref, pixels, &row->ref);
    sim_diff(rgb, conv, pixels, &row->conv);
    sim_diff(rgb, tri, pixels, &row->tri);
    sim_diff(rgb, smooth, pixels, &row->smooth);
    row->order2_bytes = mem.order2;
    row->total_bytes = mem.total;
    free(rgb);
    fprintf(stderr, "study order2: %s %s %u %u-bit: %.2f dB from the reference (max %d), %.2f / %.2f dB from the "
            "trilinear / smooth truth\n", sc->label, p->mode == VF_MODE_PREINT2 ? "preint2" : "preint1",
            p->mode == VF_MODE_PREINT2 ? p->table2_size : p->table_size, p->table_bits, row->ref.psnr_db,
            row->ref.max_abs[3], row->tri.psnr_db, row->smooth.psnr_db);
    return VFP_OK;
}

static int fits(const row_t *r)
{
    return r->ref.max_abs[3] <= 2 && r->ref.psnr_db >= 50;
}

static vfp_status_t write_outputs(study_t *st, const row_t *rows, int nrows, char *err, size_t errlen)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/order2.csv", st->dir);
    FILE *f = fopen(path, "w");
    if (!f) {
        snprintf(err, errlen, "%s: cannot write", path);
        return VFP_ERR;
    }
    fprintf(f, "scene,mode,size,bits,table_size,ref_psnr_db,ref_max,trilinear_psnr_db,trilinear_xi,smooth_psnr_db,smooth_xi,"
               "order2_bytes,total_bytes,largest_psnr_db\n");
    for (int i = 0; i < nrows; i++) {
        const row_t *r = &rows[i];
        fprintf(f, "%s,%s,%u,%u,%u,%.3f,%d,%.3f,%.5f,%.3f,%.5f,%zu,%zu,%.3f\n", st->scenes[r->scene].label,
                r->n2 ? "preint2" : "preint1", r->n2 ? r->n2 : r->table_size, r->bits, r->table_size, r->ref.psnr_db,
                r->ref.max_abs[3], r->tri.psnr_db, r->tri.mean_abs[3] / 255, r->smooth.psnr_db,
                r->smooth.mean_abs[3] / 255, r->order2_bytes, r->total_bytes, r->conv.psnr_db);
    }
    fclose(f);

    /* the plot: per scene, against the smooth truth and against the reference, by N2, one line per bits */
    snprintf(path, sizeof path, "%s/order2.gp", st->dir);
    if (!(f = fopen(path, "w"))) {
        snprintf(err, errlen, "%s: cannot write", path);
        return VFP_ERR;
    }
    int scenes[8], nscenes = 0;
    for (int i = 0; i < nrows; i++) {
        int seen = 0;
        for (int k = 0; k < nscenes; k++)
            seen |= scenes[k] == rows[i].scene;
        if (!seen && nscenes < 8)
            scenes[nscenes++] = rows[i].scene;
    }
    fprintf(f, "# order2.gp: preint2's 3D table, resolution and entry bits (volfix-sim study --order2-only)\n"
               "set terminal pngcairo size 1500,%d font ',10'\nset output 'order2.png'\nset datafile separator ','\n"
               "set grid\nset logscale x 2\nset xlabel 'N2 (3D table entries a side)'\nset key bottom right\n"
               "set multiplot layout %d,3 title 'preint2: 3D table resolution and entry bits'\n",
            380 * nscenes, nscenes);
    for (int k = 0; k < nscenes; k++) {
        const char *label = st->scenes[scenes[k]].label;
        for (int panel = 0; panel < 3; panel++) {
            int col = panel == 0 ? 10 : panel == 1 ? 14 : 6;
            fprintf(f, "set title '%s: %s'\nset ylabel 'PSNR (dB)'\n", label,
                    panel == 0 ? "against the smooth truth (lines: preint1 64, 256)" :
                    panel == 1 ? "against the reference with the largest 3D table" :
                                 "against the reference (fixed-point error; 50 dB)");
            fprintf(f, "plot ");
            for (int b = 0; b < NBITS; b++)
                fprintf(f, "%s'order2.csv' using (strcol(1) eq '%s' && strcol(2) eq 'preint2' && $4 == %u && $5 == 256 ? $3 : 1/0):%d "
                           "with linespoints title '%u-bit'", b ? ", " : "", label, bits[b], col, bits[b]);
            fprintf(f, ", 'order2.csv' using (strcol(1) eq '%s' && strcol(2) eq 'preint2' && $4 == 16 && $5 == 64 ? $3 : 1/0):%d "
                       "with linespoints dt 4 title '16-bit, pieces N 64'", label, col);
            if (panel == 0)
                fprintf(f, ", 'order2.csv' using (strcol(1) eq '%s' && strcol(2) eq 'preint1' && $3 == 64 ? 16 : 1/0):10:(112):(0) "
                           "with vectors nohead dt 2 lc rgb 'gray' title 'preint1 64', "
                           "'order2.csv' using (strcol(1) eq '%s' && strcol(2) eq 'preint1' && $3 == 256 ? 16 : 1/0):10:(112):(0) "
                           "with vectors nohead dt 3 lc rgb 'black' title 'preint1 256'\n", label, label);
            else if (panel == 2)
                fprintf(f, ", 50 with lines dt 2 lc rgb 'red' title '50 dB'\n");
            else
                fprintf(f, "\n");
        }
    }
    fprintf(f, "unset multiplot\n");
    fclose(f);
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot order2.gp 2>/dev/null", st->dir);
    int plotted = system(cmd) == 0;

    /* the recommendation: per board, among the configurations within 2 levels and 50 dB of the reference on
     * every scene whose renderer fits in the board's share on every scene, the one closest to the smooth truth
     * on average (ties within 0.05 dB: the smaller) */
    snprintf(path, sizeof path, "%s/order2.md", st->dir);
    if (!(f = fopen(path, "w"))) {
        snprintf(err, errlen, "%s: cannot write", path);
        return VFP_ERR;
    }
    fprintf(f, "# preint2's 3D table: resolution and entry bits\n\nWritten by `volfix-sim study --order2-only%s`. "
               "Per scene and configuration: PSNR against the double reference at full precision (the fixed-point "
               "error), against the trilinear and the smooth truth, and the renderer's memory (the 3D table and its "
               "pieces, and in all). %s\n\n| scene | mode | N | bits | vs reference dB (max) | trilinear truth dB "
               "| smooth truth dB | vs largest table dB | 3D table and pieces KB | renderer KB |\n"
               "|---|---|---|---|---|---|---|---|---|---|\n",
            st->quick ? " --quick" : "", plotted ? "![resolution and bits](order2.png)" : "(no gnuplot: no plot)");
    for (int i = 0; i < nrows; i++) {
        const row_t *r = &rows[i];
        char mode[32];
        snprintf(mode, sizeof mode, r->n2 ? "preint2 (pieces N %u)" : "preint1", r->table_size);
        fprintf(f, "| %s | %s | %u | %u | %.2f (%d) | %.2f | %.2f | %.2f | %.1f | %.1f |\n", st->scenes[r->scene].label,
                mode, r->n2 ? r->n2 : r->table_size, r->bits, r->ref.psnr_db,
                r->ref.max_abs[3], r->tri.psnr_db, r->smooth.psnr_db, r->conv.psnr_db, r->order2_bytes / 1024.0,
                r->total_bytes / 1024.0);
    }
    fprintf(f, "\n## Which size for which board\n\nA board's share of RAM for the renderer: all of it on a "
               "bare-metal microcontroller, half on a Linux board. Candidates: within 2 levels and 50 dB of the "
               "reference on every scene above, whose renderer (all of it: slices, run lists, tables, intermediate "
               "image) fits in the share on the first scene, Marschner-Lobb 41^3 (a volume a microcontroller "
               "holds); the choice is the smallest within 2 levels and 50 dB of the reference with the largest 3D table "
               "(%u a side) on every scene, or failing that the closest to it on average (the table's own error; "
               "against the truths every order is 14 to 20 dB away on these whole views, and a coarser table that "
               "blurs the peaks can score higher there, so the truths do not rank table sizes), within 0.05 dB the "
               "smaller.\n\n", st->quick ? sizes_quick[2] : sizes_full[6]);
    for (size_t b = 0; b < sizeof boards / sizeof boards[0]; b++) {
        double best_db = -1;
        const row_t *best = NULL;
        int best_same = 0;
        for (int i = 0; i < nrows; i++) {
            const row_t *r = &rows[i];
            if (!r->n2 || r->scene != scenes[0])
                continue;
            double sum = 0;
            int ok = 1, same = 1, n = 0;
            for (int j = 0; j < nrows; j++) {
                const row_t *q = &rows[j];
                if (q->n2 != r->n2 || q->bits != r->bits || q->table_size != r->table_size)
                    continue;
                ok &= fits(q) && (q->scene != scenes[0] || q->total_bytes <= boards[b].ram * boards[b].share);
                same &= q->conv.max_abs[3] <= 2 && q->conv.psnr_db >= 50;
                sum += q->conv.psnr_db;
                n++;
            }
            double db = n ? sum / n : -1;
            /* as good as the largest table: the smallest such; else the closest to it */
            int better = !best || (same && !best_same) ||
                         (same && best_same && r->order2_bytes < best->order2_bytes) ||
                         (!same && !best_same && (db > best_db + 0.05 ||
                                                  (fabs(db - best_db) <= 0.05 && r->order2_bytes < best->order2_bytes)));
            if (ok && better) {
                best = r;
                best_db = db;
                best_same = same;
            }
        }
        if (best)
            fprintf(f, "- %s: N2 = %u, %u-bit entries, pieces from a %u-entry 2D table (3D table and pieces %.1f KB, "
                       "renderer %.1f KB on %s; %.2f dB from the largest table on average)\n", boards[b].name, best->n2,
                    best->bits, best->table_size, best->order2_bytes / 1024.0, best->total_bytes / 1024.0,
                    st->scenes[best->scene].label, best_db);
        else
            fprintf(f, "- %s: no preint2 configuration fits; use preint1\n", boards[b].name);
    }
    fclose(f);
    return VFP_OK;
}

vfp_status_t study_order2(study_t *st, const char *data, char *err, size_t errlen)
{
    char path[1024];
    int scene_ids[4], nscene = 0;
    int s = study_add_scene(st, "o2-ml41-sharp", "phantom:marschner-lobb:41", "sharp", 30, 20, 1, st->quick ? 128 : 256,
                            err, errlen);
    if (s < 0)
        return VFP_ERR;
    scene_ids[nscene++] = s;
    if (data && !st->quick) {
        snprintf(path, sizeof path, "%s/neghip.nhdr", data);
        FILE *probe = fopen(path, "r");
        if (probe) {
            fclose(probe);
            if ((s = study_add_scene(st, "o2-neghip-sharp", path, "sharp", 135, 70, 1, 256, err, errlen)) < 0)
                return VFP_ERR;
            scene_ids[nscene++] = s;
        }
    }
    const uint32_t *sizes = st->quick ? sizes_quick : sizes_full;
    const int nsizes = st->quick ? 3 : 7;
    row_t *rows = calloc(MAX_ROWS, sizeof *rows);
    int nrows = 0;
    if (!rows) {
        snprintf(err, errlen, "out of memory");
        return VFP_ERR;
    }
    vfp_status_t status = VFP_OK;
    for (int k = 0; k < nscene && status == VFP_OK; k++) {
        int sc = scene_ids[k];
        uint8_t *tri = truth_image(st, sc, TRUTH_FILTER_TRILINEAR, err, errlen);
        uint8_t *smooth = tri ? truth_image(st, sc, TRUTH_FILTER_SMOOTH, err, errlen) : NULL;
        vf_params_t cp = study_default_params();
        cp.mode = VF_MODE_PREINT2;
        cp.table2_size = sizes[nsizes - 1];
        uint8_t *conv = smooth ? reference_image(st, sc, &cp, err, errlen) : NULL;
        if (!conv) {
            free(tri), free(smooth);
            status = VFP_ERR;
            break;
        }
        /* preint1 at 64 and 256 entries, for the plot's comparison lines */
        for (int t = 0; t < 2 && status == VFP_OK; t++) {
            vf_params_t p = study_default_params();
            p.table_size = t ? 256 : 64;
            uint8_t *ref = reference_image(st, sc, &p, err, errlen);
            row_t *r = &rows[nrows];
            *r = (row_t){.scene = sc, .n2 = 0, .bits = 16, .table_size = p.table_size};
            if (!ref || measure(st, sc, &p, ref, conv, tri, smooth, r, err, errlen))
                status = VFP_ERR;
            else
                nrows++;
            free(ref);
        }
        for (int n = 0; n < 2 * nsizes && status == VFP_OK; n++) {
            vf_params_t p = study_default_params();
            p.mode = VF_MODE_PREINT2;
            p.table2_size = sizes[n % nsizes];
            p.table_size = n < nsizes ? 256 : 64; /* the pieces' 2D table, in Q.30: 16 N^2 bytes */
            uint8_t *ref = reference_image(st, sc, &p, err, errlen);
            if (!ref) {
                status = VFP_ERR;
                break;
            }
            for (int b = 0; b < NBITS && status == VFP_OK && nrows < MAX_ROWS; b++) {
                p.table_bits = bits[b];
                row_t *r = &rows[nrows];
                *r = (row_t){.scene = sc, .n2 = p.table2_size, .bits = bits[b], .table_size = p.table_size};
                if (measure(st, sc, &p, ref, conv, tri, smooth, r, err, errlen))
                    status = VFP_ERR;
                else
                    nrows++;
            }
            free(ref);
        }
        free(tri), free(smooth), free(conv);
    }
    if (status == VFP_OK)
        status = write_outputs(st, rows, nrows, err, errlen);
    free(rows);
    return status;
}
