/* SPDX-License-Identifier: MIT */
/* study_plots.c: the precision study's plots: for each, NAME.dat (the data) and NAME.gp (the gnuplot script) in the
 * study's directory, and NAME.png drawn by running gnuplot on them. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study_report.h"

/* A plot's data and gnuplot script, NAME.dat and NAME.gp in the study's directory; both or neither. */
static vfp_status_t open_plot(const study_t *st, const char *name, FILE **d, FILE **g, char *err, size_t errlen)
{
    char file[64];
    snprintf(file, sizeof file, "%s.dat", name);
    *d = study_open_file(st, file, err, errlen);
    snprintf(file, sizeof file, "%s.gp", name);
    *g = *d ? study_open_file(st, file, err, errlen) : NULL;
    if (*d && !*g) {
        fclose(*d);
        *d = NULL;
    }
    return *g ? VFP_OK : VFP_ERR;
}

/* What an empty panel plots (a study that ran none of its factor, as --lighting-only): gnuplot refuses a plot
 * whose every point is undefined, and on a logarithmic axis a constant needs a range of its own. */
#define EMPTY_PLOT "[1:2] 0 notitle lc rgb 'white'"

/* Data for one line of a plot: the runs of a scene and factor, value against a measure. */
static void write_series(FILE *f, const study_t *st, int scene, const char *factor, int truth)
{
    for (int i = 0; i < st->run_count; i++) {
        const study_run_t *r = &st->runs[i];
        if (r->scene != scene || strcmp(r->factor, factor) != 0)
            continue;
        const sim_diff_t *d = truth ? &r->vs_truth : &r->vs_reference;
        fprintf(f, "%s %.3f %d\n", r->value, d->psnr_db, d->max_abs[3]);
    }
    fprintf(f, "\n\n"); /* a gnuplot data set */
}

static vfp_status_t gnuplot(const study_t *st, const char *script, char *err, size_t errlen)
{
    char command[2048];
    snprintf(command, sizeof command, "cd '%s' && gnuplot '%s' 2>gnuplot.log", st->dir, script);
    if (system(command) != 0) {
        snprintf(err, errlen, "%s/%s: gnuplot failed (is gnuplot installed? see %s/gnuplot.log)", st->dir, script,
                 st->dir);
        return VFP_ERR;
    }
    return VFP_OK;
}

static vfp_status_t plot_bits(const study_t *st, char *err, size_t errlen)
{
    const char *stages[4] = {"table_bits", "sample_bits", "intermediate_bits", "warp_bits"};
    const char *titles[4] = {"table entries (bits)", "samples (fraction bits; 32 = exact)", "intermediate image (bits)",
                             "warp weights (fraction bits)"};
    FILE *d, *g;
    if (open_plot(st, "bits", &d, &g, err, errlen))
        return VFP_ERR;
    fprintf(g, "set terminal pngcairo size 1200,900 font ',10'\nset output 'bits.png'\n"
               "set multiplot layout 2,2 title 'Fixed-point error by precision of each stage (PSNR against the double "
               "reference, higher is better)'\nset grid\nset key bottom right\nset ylabel 'PSNR (dB)'\n");
    int block = 0;
    for (int k = 0; k < 4; k++) {
        int which[STUDY_MAX_SCENES], n = study_scenes_with(st, stages[k], which, STUDY_MAX_SCENES);
        fprintf(g, "set xlabel '%s'\nset yrange [20:100]\nplot ", titles[k]);
        for (int i = 0; i < n; i++) {
            write_series(d, st, which[i], stages[k], 0);
            fprintf(g, "%s'bits.dat' index %d using 1:2 with linespoints title '%s'", i ? ", " : "", block++,
                    st->scenes[which[i]].label);
        }
        if (n == 0)
            fprintf(g, EMPTY_PLOT);
        fprintf(g, "\n");
    }
    fprintf(g, "unset multiplot\n");
    fclose(d);
    fclose(g);
    return gnuplot(st, "bits.gp", err, errlen);
}

static vfp_status_t plot_table_size(const study_t *st, char *err, size_t errlen)
{
    const char *factors[2] = {"table_size_nearest", "table_size_bilinear"};
    FILE *d, *g;
    if (open_plot(st, "table_size", &d, &g, err, errlen))
        return VFP_ERR;
    fprintf(g, "set terminal pngcairo size 1200,450 font ',10'\nset output 'table_size.png'\n"
               "set multiplot layout 1,2 title 'Table size and lookup'\nset grid\nset logscale x 2\n"
               "set xlabel 'table entries N'\nset ylabel 'PSNR (dB)'\nset key bottom right\n");
    int block = 0;
    for (int truth = 1; truth >= 0; truth--) {
        fprintf(g, "set title '%s'\nplot ",
                truth ? "against the truth (the algorithm)" : "against the reference (fixed point)");
        int first = 1;
        for (int k = 0; k < 2; k++) {
            int which[STUDY_MAX_SCENES], n = study_scenes_with(st, factors[k], which, STUDY_MAX_SCENES);
            for (int i = 0; i < n; i++) {
                write_series(d, st, which[i], factors[k], truth);
                fprintf(g, "%s'table_size.dat' index %d using 1:2 with linespoints title '%s %s'", first ? "" : ", ",
                        block++, st->scenes[which[i]].label, k ? "bilinear" : "nearest");
                first = 0;
            }
        }
        fprintf(g, "%s\n", first ? EMPTY_PLOT : "");
    }
    fprintf(g, "unset multiplot\n");
    fclose(d);
    fclose(g);
    return gnuplot(st, "table_size.gp", err, errlen);
}

static vfp_status_t plot_orders(const study_t *st, char *err, size_t errlen)
{
    FILE *d, *g;
    if (open_plot(st, "orders", &d, &g, err, errlen))
        return VFP_ERR;
    fprintf(d, "scene");
    for (int m = 0; m < STUDY_MODES; m++)
        fprintf(d, " %s", vf_mode_name((vf_mode_t)m));
    fprintf(d, "\n");
    int which[STUDY_MAX_SCENES], n = study_scenes_with(st, "order", which, STUDY_MAX_SCENES);
    for (int i = 0; i < n; i++) {
        if (strncmp(st->scenes[which[i]].label, "ml41-peaks-", 11) == 0)
            continue; /* the peak-width sweep has its own plot */
        fprintf(d, "%s", st->scenes[which[i]].label);
        for (int m = 0; m < STUDY_MODES; m++) {
            const study_run_t *r = study_find(st, st->scenes[which[i]].label, "order", vf_mode_name((vf_mode_t)m));
            fprintf(d, " %.3f", r ? r->vs_truth.psnr_db : 0.0);
        }
        fprintf(d, "\n");
    }
    fprintf(g, "set terminal pngcairo size 1200,450 font ',10'\nset output 'orders.png'\n"
               "set title 'The orders against the ground truth, smooth and sharp transfer functions (higher is "
               "better)'\n"
               "set style data histogram\nset style histogram clustered gap 1\nset style fill solid 0.8 border -1\n"
               "set grid ytics\nset ylabel 'PSNR against the truth (dB)'\nset key top left\nset xtics rotate by -20\n"
               "set yrange [0:*]\nplot ");
    for (int m = 0; n && m < STUDY_MODES; m++)
        fprintf(g, "%s'orders.dat' using %d:xtic(1) title columnheader", m ? ", " : "", m + 2);
    fprintf(g, "%s\n", n ? "" : EMPTY_PLOT);
    fclose(d);
    fclose(g);
    return gnuplot(st, "orders.gp", err, errlen);
}

static vfp_status_t plot_memory(const study_t *st, char *err, size_t errlen)
{
    FILE *d, *g;
    if (open_plot(st, "memory", &d, &g, err, errlen))
        return VFP_ERR;
    int which[STUDY_MAX_SCENES], n = 0;
    for (int s = 0; s < st->scene_count; s++)
        if (strncmp(st->scenes[s].label, "fixed-", 6) != 0)
            which[n++] = s;
    for (int i = 0; i < n; i++) {
        for (int r = 0; r < st->run_count; r++)
            if (st->runs[r].scene == which[i] && st->runs[r].vs_truth.pixels)
                fprintf(d, "%.1f %.3f\n", (st->runs[r].memory.total + st->runs[r].band_bytes) / 1024.0,
                        st->runs[r].vs_truth.psnr_db);
        fprintf(d, "\n\n");
    }
    fprintf(g, "set terminal pngcairo size 900,600 font ',10'\nset output 'memory.png'\n"
               "set title 'Memory against error (every run with a truth)'\nset logscale x 2\nset grid\n"
               "set xlabel 'renderer memory (KB: slices, run lists, tables, intermediate image, band scratch)'\n"
               "set ylabel 'PSNR against the truth (dB)'\nset key outside right\nplot ");
    for (int i = 0; i < n; i++)
        fprintf(g, "%s'memory.dat' index %d using 1:2 with points pt 7 title '%s'", i ? ", " : "", i,
                st->scenes[which[i]].label);
    fprintf(g, "%s\n", n ? "" : EMPTY_PLOT);
    fclose(d);
    fclose(g);
    return gnuplot(st, "memory.gp", err, errlen);
}

/* The gain of pre-integration over point sampling (PSNR against the truth) against the peaks' half-width. */
static vfp_status_t plot_peaks(const study_t *st, char *err, size_t errlen)
{
    FILE *d, *g;
    if (open_plot(st, "peaks", &d, &g, err, errlen))
        return VFP_ERR;
    for (int inside = 0; inside < 2; inside++) {
        for (int s = 0; s < st->scene_count; s++) {
            const char *label = st->scenes[s].label;
            double half;
            char rest[32] = "";
            if (sscanf(label, "ml41-peaks-%lf%31s", &half, rest) < 1 || (strcmp(rest, "-interior") == 0) != inside)
                continue;
            const study_run_t *pt = study_find(st, label, "order", "point");
            const study_run_t *pre = study_find(st, label, "order", "preint1");
            if (pt && pre)
                fprintf(d, "%.3f %.3f %.3f %.3f\n", half, pt->vs_truth.psnr_db, pre->vs_truth.psnr_db,
                        pre->vs_truth.psnr_db - pt->vs_truth.psnr_db);
        }
        fprintf(d, "\n\n");
    }
    fprintf(g, "set terminal pngcairo size 1200,450 font ',10'\nset output 'peaks.png'\n"
               "set multiplot layout 1,2 title 'Marschner-Lobb 41^3, three opacity peaks of varying width'\nset grid\n"
               "set xlabel 'half-width of each peak (fraction of the window)'\nset key bottom right\n"
               "set title 'against the truth'\nset ylabel 'PSNR (dB)'\n"
               "plot 'peaks.dat' index 0 using 1:2 with linespoints title 'point, whole view', "
               "'' index 0 using 1:3 with linespoints title 'preint1, whole view', "
               "'' index 1 using 1:2 with linespoints title 'point, interior', "
               "'' index 1 using 1:3 with linespoints title 'preint1, interior'\n"
               "set title 'preint1 closer than point by'\nset ylabel 'dB'\n"
               "plot 'peaks.dat' index 0 using 1:4 with linespoints title 'whole view', "
               "'' index 1 using 1:4 with linespoints title 'interior', 6 with lines dashtype 2 title '6 dB'\n"
               "unset multiplot\n");
    fclose(d);
    fclose(g);
    return gnuplot(st, "peaks.gp", err, errlen);
}

/* Distance from the truth against rays per voxel column on Marschner-Lobb (the rays sweep), and preint1's gain
 * over point: one line per mode and side-face rule, a data set each in rays.dat (only those that were run). */
static vfp_status_t plot_rays(const study_t *st, char *err, size_t errlen)
{
    static const unsigned rays[STUDY_RAYS_STEPS] = {1, 2, 4, 8, 16};
    FILE *d, *g;
    if (open_plot(st, "rays", &d, &g, err, errlen))
        return VFP_ERR;
    fprintf(g, "set terminal pngcairo size 1200,480 font ',10'\nset output 'rays.png'\n"
               "set multiplot layout 1,2 title 'Marschner-Lobb 41^3, sharp, 512x512, view 30,20: rays per voxel "
               "column (one slab per slice throughout)'\nset grid\nset logscale x 2\nset xtics (1, 2, 4, 8, 16)\n"
               "set xrange [0.8:20]\nset xlabel 'rays per voxel column along each axis (R; R = 8 is about one ray "
               "per output pixel)'\nset key bottom right\n");
    int block = 0, lines = 0;
    /* left: PSNR against the truth at claim 1's table size */
    fprintf(g, "set title 'distance from the truth, %u table entries (higher is closer)'\nset ylabel 'PSNR against "
               "the truth (dB)'\nset key top left maxrows 3\nset offsets 0, 0, 3, 0\nplot ", STUDY_CLAIM_TABLE);
    const vf_mode_t modes[3] = {VF_MODE_POINT, VF_MODE_PREINT1, VF_MODE_PRECLASS};
    for (int m = 0; m < 3; m++)
        for (int partial = 1; partial >= 0; partial--) {
            int points = 0;
            for (int k = 0; k < STUDY_RAYS_STEPS; k++) {
                const study_run_t *r = study_find_rays(st, "ml41-sharp", partial, STUDY_CLAIM_TABLE, rays[k], modes[m]);
                if (r && r->vs_truth.pixels) {
                    fprintf(d, "%u %.3f\n", rays[k], r->vs_truth.psnr_db);
                    points++;
                }
            }
            if (!points) /* gnuplot does not count empty data sets: write none */
                continue;
            fprintf(d, "\n\n");
            fprintf(g, "%s'rays.dat' index %d using 1:2 with linespoints lw 2 pt %d dashtype %d lc %d title '%s, "
                       "%s slabs'",
                    lines++ ? ", " : "", block++, 7 - 2 * partial, partial ? 1 : 2, m + 1, vf_mode_name(modes[m]),
                    partial ? "partial" : "whole");
        }
    fprintf(g, "%s\n", lines ? "" : EMPTY_PLOT);
    /* right: preint1's gain over point, each table size and side-face rule */
    fprintf(g, "set title 'preint1 closer to the truth than point by'\nset ylabel 'dB'\nset key bottom right "
               "maxrows 5\nset offsets 0, 0, 0, 0\nplot ");
    const unsigned sizes[2] = {256, STUDY_CLAIM_TABLE};
    lines = 0;
    for (int n = 1; n >= 0; n--)
        for (int partial = 1; partial >= 0; partial--) {
            int points = 0;
            for (int k = 0; k < STUDY_RAYS_STEPS; k++) {
                const study_run_t *pt = study_find_rays(st, "ml41-sharp", partial, sizes[n], rays[k], VF_MODE_POINT);
                const study_run_t *pre = study_find_rays(st, "ml41-sharp", partial, sizes[n], rays[k], VF_MODE_PREINT1);
                if (pt && pre && pt->vs_truth.pixels && pre->vs_truth.pixels) {
                    fprintf(d, "%u %.3f\n", rays[k], pre->vs_truth.psnr_db - pt->vs_truth.psnr_db);
                    points++;
                }
            }
            if (!points)
                continue;
            fprintf(d, "\n\n");
            fprintf(g, "%s'rays.dat' index %d using 1:2 with linespoints lw 2 pt %d dashtype %d lc %d title '%u "
                       "entries, %s slabs'",
                    lines++ ? ", " : "", block++, 7 - 2 * partial, partial ? 1 : 2, n ? 2 : 4, sizes[n],
                    partial ? "partial" : "whole");
        }
    fprintf(g, "%s6 with lines dashtype 3 lc rgb 'black' title 'the claim: 6 dB'\nunset multiplot\n",
            lines ? ", " : "");
    fclose(d);
    fclose(g);
    return gnuplot(st, "rays.gp", err, errlen);
}

/* One lighting stage (study_lit.c): NAME.png, PSNR against the stage's reference and, when its runs have one,
 * against the lit truth, one line per scene. */
static vfp_status_t plot_lit_stage(const study_t *st, const char *name, const char *title, const char *against,
                                   const char *xlabel, char *err, size_t errlen)
{
    FILE *d, *g;
    if (open_plot(st, name, &d, &g, err, errlen))
        return VFP_ERR;
    int which[STUDY_MAX_SCENES], n = study_scenes_with(st, name, which, STUDY_MAX_SCENES), truth = 0;
    for (int i = 0; i < st->run_count; i++)
        truth |= strcmp(st->runs[i].factor, name) == 0 && st->runs[i].vs_truth.pixels;
    fprintf(g, "set terminal pngcairo size %d,450 font ',10'\nset output '%s.png'\n"
               "set multiplot layout 1,%d title '%s'\nset grid\nset key bottom right\nset xlabel '%s'\n"
               "set ylabel 'PSNR (dB)'\n",
            truth ? 1200 : 700, name, truth ? 2 : 1, title, xlabel);
    int block = 0;
    for (int t = 0; t <= truth; t++) {
        fprintf(g, "set title 'against %s'\nplot ", t ? "the lit truth (the algorithm, lit)" : against);
        for (int i = 0; i < n; i++) {
            write_series(d, st, which[i], name, t);
            fprintf(g, "%s'%s.dat' index %d using 1:2 with linespoints title '%s'", i ? ", " : "", name, block++,
                    st->scenes[which[i]].label);
        }
        fprintf(g, "%s\n", n ? "" : EMPTY_PLOT);
    }
    fprintf(g, "unset multiplot\n");
    fclose(d);
    fclose(g);
    char script[64];
    snprintf(script, sizeof script, "%s.gp", name);
    return gnuplot(st, script, err, errlen);
}

vfp_status_t study_write_plots(const study_t *st, char *err, size_t errlen)
{
    if (!st->lighting_only &&
        (plot_bits(st, err, errlen) || plot_table_size(st, err, errlen) || plot_orders(st, err, errlen) ||
         plot_memory(st, err, errlen) || plot_peaks(st, err, errlen) || plot_rays(st, err, errlen)))
        return VFP_ERR;
    if (plot_lit_stage(st, "normal_bits", "Lit preint1: bits of the normal codes", "the reference with unquantised "
                       "normals (codes and fixed point)", "bits of a normal code", err, errlen) ||
        plot_lit_stage(st, "shade_bits", "Lit preint1: fraction bits of the shade table (the core keeps 14)",
                       "the reference with an exact shade table", "fraction bits of L_d and L_s", err, errlen) ||
        plot_lit_stage(st, "lit_table_bits", "Lit preint1: bits of the front-weighted table (D_f, S_f)",
                       "the reference with an exact front-weighted table", "bits of a front-weighted value", err,
                       errlen))
        return VFP_ERR;
    return VFP_OK;
}
