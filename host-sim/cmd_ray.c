/* SPDX-License-Identifier: MIT */
/*
 * cmd_ray.c: volfix-sim ray: El Hajjar et al. 2008's study of one ray (their Figures 1-5): the trilinear signal
 * along the ray through one final pixel, its order 0, 1 and 2 reconstructions from shear-warp's samples at
 * spacing 1 and 2 slices, and the error xi of each. Writes CSVs, a gnuplot script and its picture.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "commands.h"
#include "scene.h"
#include "truth/truth.h"

#define PER_VOXEL 64 /* signal points per slice in ray.csv */
#define NOT_INSTALLED 127 /* the exit status of a command the shell (here execlp) does not find */

static const char usage_head[] =
    "usage: volfix-sim ray VOLUME [options] [--pixel X,Y] -o DIR\n"
    "Follow the ray through final pixel (X, Y) of the view and compare the trilinear signal along it with what\n"
    "shear-warp reconstructs from its samples on the slices: order 0 (piecewise constant), 1 (linear) and 2\n"
    "(a quadratic per slab of two spacings), at spacing 1 and 2 slices. xi = the integral of |signal -\n"
    "reconstruction| along the ray (scalar levels x slices). Writes DIR/ray.csv, DIR/xi.csv, DIR/ray.gp and,\n"
    "when gnuplot is installed, DIR/ray.png. The transfer-function and mode options do not apply.\n\n"
    "The third plot is what the renderers composite along the ray: point and preint1 per slice, and preint2's\n"
    "own segments (slabs from even slices, each quadratic clamped to its three samples, a last order-1 slab\n"
    "where the volume's last slice is odd), with its xi on its whole slabs in DIR/renderers.csv.\n\n"
    "  -o DIR               the folder to write (made if missing)\n"
    "  --pixel X,Y          the final-image position of the ray (default: the image centre)\n"
    "  --truth-filter F     the signal: trilinear (default), smooth (a phantom's own function where it has\n"
    "                       one, else catmull-rom), catmull-rom, bspline or analytic; the samples are its too\n";

static const char script[] =
    "# ray.gp: the plot of volfix-sim ray (El Hajjar et al. 2008, Figures 1-5). Run here: gnuplot ray.gp\n"
    "set terminal pngcairo size 1100,1300 font ',10'\n"
    "set output 'ray.png'\n"
    "set datafile separator ','\n"
    "set datafile missing 'nan'\n"
    "set key outside right top\n"
    "set grid\n"
    "set xlabel 'k (slices along the principal axis)'\n"
    "set ylabel 'scalar'\n"
    "set multiplot layout 3,1 title '%s'\n"
    "set title 'sample spacing 1 slice: xi0 %.4g, xi1 %.4g, xi2 %.4g'\n"
    "plot 'ray.csv' using 1:2 with lines lw 2 lc rgb 'black' title 'signal', \\\n"
    "     '' using 1:3 with lines lc rgb '#d95f02' title 'order 0', \\\n"
    "     '' using 1:4 with lines lc rgb '#1b9e77' title 'order 1', \\\n"
    "     '' using 1:5 with lines lc rgb '#7570b3' title 'order 2'\n"
    "set title 'sample spacing 2 slices: xi0 %.4g, xi1 %.4g, xi2 %.4g'\n"
    "plot 'ray.csv' using 1:2 with lines lw 2 lc rgb 'black' title 'signal', \\\n"
    "     '' using 1:6 with lines lc rgb '#d95f02' title 'order 0', \\\n"
    "     '' using 1:7 with lines lc rgb '#1b9e77' title 'order 1', \\\n"
    "     '' using 1:8 with lines lc rgb '#7570b3' title 'order 2'\n"
    "set title 'the renderers on k %g..%g (dotted: preint2 slab ends): xi point %.4g, preint1 %.4g, preint2 %.4g'\n"
    "do for [k=%d:%d:2] { set arrow from k, graph 0 to k, graph 1 nohead dt 3 lc rgb 'gray' }\n"
    "plot 'ray.csv' using 1:2 with lines lw 2 lc rgb 'black' title 'signal', \\\n"
    "     '' using 1:3 with lines lc rgb '#d95f02' title 'point', \\\n"
    "     '' using 1:4 with lines lc rgb '#1b9e77' title 'preint1', \\\n"
    "     '' using 1:9 with lines lw 2 lc rgb '#7570b3' title 'preint2 segments'\n"
    "unset multiplot\n";

static vfp_status_t write_files(const char *dir, const truth_study_t *st, const char *about);

static int run_gnuplot(const char *dir);

int sim_cmd_ray(int argc, char **argv)
{
    sim_opts_t o;
    sim_scene_t scene;
    /* -o is checked before the volume is loaded, and the folder made when its files are written */
    vfp_status_t status = sim_scene_command(&o, &scene, argc, argv,
                                            SIM_OPT_OUT | SIM_OPT_OUT_DIR | SIM_OPT_PIXEL | SIM_OPT_FILTER,
                                            usage_head);
    if (status)
        return vfp_exit_status(status);

    char about[512];
    double px = o.have_pixel ? o.pixel[0] : (o.width - 1) / 2.0, py = o.have_pixel ? o.pixel[1] : (o.height - 1) / 2.0;
    sim_ref_inputs_t in;
    truth_study_t st = {0};
    if (sim_ref_inputs(&scene, &in)) {
        fprintf(stderr, "volfix-sim: out of memory\n");
        sim_scene_free(&scene);
        return VFP_EXIT_ERR;
    }
    truth_field_t field;
    int made = truth_field_init(&field, &in.vol, (truth_filter_t)o.truth_filter,
                                strcmp(scene.vol.format, "phantom") == 0 ? scene.vol.name : NULL, scene.window.lo,
                                scene.window.hi);
    if (made) {
        if (made == -2)
            fprintf(stderr, "volfix-sim: --truth-filter analytic: %s has no analytic function (phantom:NAME:N with "
                    "NAME marschner-lobb, sphere or cube)\n", scene.vol.name);
        else
            fprintf(stderr, "volfix-sim: out of memory\n");
        sim_ref_inputs_free(&in);
        sim_scene_free(&scene);
        return VFP_EXIT_ERR;
    }
    int traced = truth_study_ray_field(&in.vol, &field, &in.view, (int)o.width, (int)o.height, px, py, PER_VOXEL,
                                       &st);
    truth_field_free(&field);
    /* what the ray depends on: not the transfer function or the mode */
    const char *base = strrchr(scene.vol.name, '/');
    char view[64];
    snprintf(view, sizeof view, o.roll != 0 ? "%g,%g,%g" : "%g,%g", o.azimuth, o.elevation, o.roll);
    double lo, hi; /* in data units, as --window takes them */
    vfp_window_data(&scene.vol, scene.window, &lo, &hi);
    snprintf(about, sizeof about, "%s %ux%u view %s zoom %g window %.10g,%.10g, %s signal",
             base ? base + 1 : scene.vol.name, o.width, o.height, view, o.zoom, lo, hi,
             truth_filter_name((truth_filter_t)o.truth_filter));
    sim_ref_inputs_free(&in);
    sim_scene_free(&scene);
    if (traced != 0) {
        fprintf(stderr, "volfix-sim: pixel %g,%g: %s\n", px, py,
                traced > 0 ? "the ray misses the volume or crosses fewer than 4 of its slices (try a pixel nearer the "
                             "centre)"
                           : "out of memory");
        return VFP_EXIT_ERR;
    }
    char title[700];
    snprintf(title, sizeof title, "%s, pixel %g,%g", about, px, py);
    status = write_files(o.out, &st, title);
    if (status == VFP_OK) {
        printf("%s: ray through slices k %.2f..%.2f along %c%s (slab %.4f d_ref); reconstructions compared on "
               "k %g..%g\n",
               title, st.k_in, st.k_out, "xyz"[st.k_axis], st.k_flip ? " (looking along -k)" : "", st.slab, st.k_a,
               st.k_b);
        printf("xi = integral |signal - reconstruction| dk (scalar levels x slices)\n");
        printf("           spacing 1    spacing 2\n");
        for (int order = 0; order < 3; order++)
            printf("order %d    %-12.4f %.4f\n", order, st.xi[order][0], st.xi[order][1]);
        if (st.r_b > st.r_a)
            printf("the renderers on k %g..%g: xi point %.4f, preint1 %.4f, preint2 %.4f\n", st.r_a, st.r_b,
                   st.xi_r[0], st.xi_r[1], st.xi_r[2]);
        int plot = run_gnuplot(o.out);
        printf("wrote %s/ray.csv, %s/xi.csv, %s/renderers.csv, %s/ray.gp%s%s%s\n", o.out, o.out, o.out, o.out,
               plot == EXIT_SUCCESS ? ", " : "", plot == EXIT_SUCCESS ? o.out : "",
               plot == EXIT_SUCCESS ? "/ray.png" : "");
        if (plot == NOT_INSTALLED)
            fprintf(stderr, "volfix-sim: gnuplot is not installed: no ray.png (apt-get install gnuplot-nox)\n");
        else if (plot != EXIT_SUCCESS)
            fprintf(stderr, "volfix-sim: gnuplot failed on %s/ray.gp: no ray.png\n", o.out);
    }
    truth_study_free(&st);
    return vfp_exit_status(status);
}

/* ---- static functions ---------------------------------------------------------------------------------- */

/* Open dir/name for writing (path receives the name); on failure print one line and return NULL. */
static FILE *open_in(const char *dir, const char *name, char *path, size_t len)
{
    snprintf(path, len, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "volfix-sim: %s: cannot write\n", path);
    return f;
}

static vfp_status_t close_file(FILE *f, const char *path)
{
    if (fclose(f) == 0)
        return VFP_OK;
    fprintf(stderr, "volfix-sim: %s: cannot write\n", path);
    return VFP_ERR;
}

static vfp_status_t write_files(const char *dir, const truth_study_t *st, const char *about)
{
    if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "volfix-sim: -o %s: cannot make the folder: %s\n", dir, strerror(errno));
        return VFP_ERR;
    }
    char path[4096];
    FILE *f = open_in(dir, "ray.csv", path, sizeof path);
    if (!f)
        return VFP_ERR;
    fprintf(f, "t,signal,order0_1,order1_1,order2_1,order0_2,order1_2,order2_2,preint2\n");
    for (int r = 0; r < st->rows; r++) {
        const double *v = st->table + TRUTH_STUDY_COLS * r;
        fprintf(f, "%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7],
                v[8]);
    }
    if (close_file(f, path) || !(f = open_in(dir, "xi.csv", path, sizeof path)))
        return VFP_ERR;
    fprintf(f, "order,spacing,xi\n");
    for (int order = 0; order < 3; order++)
        for (int h = 1; h <= 2; h++)
            fprintf(f, "%d,%d,%.6f\n", order, h, st->xi[order][h - 1]);
    if (close_file(f, path) || !(f = open_in(dir, "renderers.csv", path, sizeof path)))
        return VFP_ERR;
    fprintf(f, "renderer,k_from,k_to,xi\n");
    for (int m = 0; m < 3 && st->r_b > st->r_a; m++)
        fprintf(f, "%s,%g,%g,%.6f\n", m == 0 ? "point" : m == 1 ? "preint1" : "preint2", st->r_a, st->r_b,
                st->xi_r[m]);
    if (close_file(f, path) || !(f = open_in(dir, "ray.gp", path, sizeof path)))
        return VFP_ERR;
    char quoted[700];
    size_t n = 0;
    for (const char *c = about; *c && n + 1 < sizeof quoted; c++)
        if (*c != '\'') /* the title sits in single quotes */
            quoted[n++] = *c;
    quoted[n] = 0;
    fprintf(f, script, quoted, st->xi[0][0], st->xi[1][0], st->xi[2][0], st->xi[0][1], st->xi[1][1], st->xi[2][1],
            st->r_a, st->r_b, st->xi_r[0], st->xi_r[1], st->xi_r[2], (int)st->r_a, (int)st->r_b);
    return close_file(f, path);
}

/* gnuplot ray.gp in dir; its messages go to our stderr. Returns its exit status: EXIT_SUCCESS, NOT_INSTALLED, or
 * another failure (EXIT_FAILURE when it could not be run or did not exit). */
static int run_gnuplot(const char *dir)
{
    fflush(stdout);
    pid_t pid = fork();
    if (pid < 0)
        return EXIT_FAILURE;
    if (pid == 0) {
        if (chdir(dir) != 0)
            _exit(EXIT_FAILURE);
        execlp("gnuplot", "gnuplot", "ray.gp", (char *)NULL);
        _exit(NOT_INSTALLED);
    }
    int wstatus;
    if (waitpid(pid, &wstatus, 0) != pid || !WIFEXITED(wstatus))
        return EXIT_FAILURE;
    return WEXITSTATUS(wstatus);
}
