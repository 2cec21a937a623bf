/* SPDX-License-Identifier: MIT */
/*
 * main.c: volfix, the knob-driven viewer: options, set-up and the closing summary (the loop is loop.c).
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "io/numbers.h"
#include "viewer.h"

/* Where a board named without a slash (--board rpi4-spi-st7789) is looked for: the installed boards, set by the
 * Makefile from PREFIX. */
#ifndef VFP_BOARD_DIR
#define VFP_BOARD_DIR "/usr/local/share/volfix/boards"
#endif

static const char usage[] =
    "usage: volfix --board BOARD VOLUME [options]\n"
    "Show VOLUME on the board's display and turn it with the board's knobs (boards/README.md). While a knob\n"
    "turns, frames come from a half-resolution copy; full quality follows once the knobs rest.\n\n"
    "  --board BOARD        the board: display, inputs, what each knob and button does (required); a path\n"
    "                       with a slash is a board file, a name (rpi4-spi-st7789) one of the installed boards\n"
    "                       in " VFP_BOARD_DIR "\n"
    "  --preset NAME        transfer function to start with: ramp (default), sharp, ct-bone, ct-skin-bone or\n"
    "                       mr-brain; the preset button cycles through them all\n"
    "  --tf FILE            start with a transfer-function file (the preset button cycles it and the presets)\n"
    "  --window LO,HI       data values the transfer function's 0..1 spans, two different finite numbers\n"
    "                       (default: from the data, docs/defaults.md)\n"
    "  --mode MODE          point, preint1 (default), preclass or preint2; the mode button cycles them\n"
    "  --view AZ,EL[,ROLL]  first view in degrees, each -360..360 (default 30,20), or anterior, posterior,\n"
    "                       left, right, superior or inferior (the patient frame); the reset button comes\n"
    "                       back to it\n"
    "  --zoom Z             first zoom, 1 fitting the volume; 0.25..8 (default 1)\n"
    "  --script FILE        knob turns and presses from a file instead of the board's inputs\n"
    "                       (lines 'MS turn KNOB STEPS', 'MS press BUTTON', 'MS release BUTTON', 'MS quit')\n"
    "  --device PATH        the display device instead of the board's (png: the frames' directory)\n"
    "  --size WxH           picture size for the sdl and png displays instead of the board's, each 16..4096\n"
    "  --preview N          while a knob turns, render a copy N times smaller a side (default 2 for volumes\n"
    "                       of 64^3 voxels or more, else 1: off)\n"
    "  --idle-ms MS         full quality once the knobs rest this long (default: the board's, else 300)\n"
    "  --rays N             rays per voxel column along each axis in full-quality frames: 1, 2 or 4 (default\n"
    "                       1, and 2 for an anisotropic volume: one spacing at least twice the smallest)\n"
    "  --threads N          rendering threads, 1..16 (default: the board's, else the processors online)\n"
    "  --overlay            show the frame-time overlay from the start (the overlay button toggles it)\n"
    "  --log FILE           a line per frame shown: quality, time, input latency, memory, and the volfix-sim\n"
    "                       render options that give the same pixels\n"
    "  --frames N           leave after N frames, 1..1000000000 (long runs and tests); a script that ends\n"
    "                       without 'quit' then ends the run once its last picture is shown\n"
    "  --dims X,Y,Z --type uint8|int8|uint16|int16 [--big-endian] [--spacing X,Y,Z]   for raw voxel files:\n"
    "                       sizes 2..4096, spacings above 0 and at most 32767\n"
    "  --version            print the version and leave\n"
    "Lighting (docs/algorithm.md section 7), for every transfer function the preset button cycles to; each\n"
    "otherwise lit as it says itself:\n"
    VFP_LIGHTING_HELP
    "  --series UID         the DICOM series to show from a folder holding several (default: the largest)\n"
    "VOLUME is a .nhdr/.nrrd, .nii/.nii.gz, .mhd/.mha, DICOM (a folder or a file), .den or raw file, or\n"
    "phantom:NAME:N. Ctrl-C quits.\n";

static vfp_status_t bad(const char *option, const char *value, const char *expected)
{
    fprintf(stderr, "volfix: %s %s: expected %s\n", option, value ? value : "(missing)", expected);
    return VFP_ERR;
}

static vfp_status_t parse_int(const char *text, int lo, int hi, int *out)
{
    long long n;
    if (!vfp_parse_integer(text, lo, hi, &n))
        return VFP_ERR;
    *out = (int)n;
    return VFP_OK;
}

/* The options that take no value: any other option followed by '' is given an empty value, an error rather than
 * a way back to the default ("--device ''" would otherwise write frames into a folder nobody named). */
static int is_flag(const char *a)
{
    return !strcmp(a, "--help") || !strcmp(a, "-h") || !strcmp(a, "--version") || !strcmp(a, "--overlay") ||
           !strcmp(a, "--big-endian");
}

typedef struct options {
    char board_path[1024]; /* --board NAME: the installed board's file */
    const char *board, *volume, *preset, *tf, *window, *script, *device, *log;
    vf_mode_t mode;
    double view[3], zoom;
    uint32_t width, height;
    int preview, idle_ms, threads, overlay, frames, rays;
    vfp_load_opts_t load;
    vfp_lighting_opts_t lighting;
} options_t;

static vfp_status_t parse(options_t *o, int argc, char **argv)
{
    memset(o, 0, sizeof *o);
    o->mode = VF_MODE_PREINT1;
    o->view[0] = 30;
    o->view[1] = 20;
    o->zoom = 1;
    o->preview = o->idle_ms = o->threads = -1;
    vfp_lighting_opts_init(&o->lighting);
    char err[VIEWER_ERR_LEN];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1, took;
        if (!*a) {
            fprintf(stderr, "volfix: '': an empty argument (expected an option or a volume)\n");
            return VFP_ERR;
        }
        if (vfp_is_empty(v) && a[0] == '-' && !is_flag(a)) {
            fprintf(stderr, "volfix: %s '': an empty value (expected a value; see volfix --help)\n", a);
            return VFP_ERR;
        }
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(usage, stdout);
            return VFP_HELP_SHOWN;
        } else if (!strcmp(a, "--version")) {
            printf("volfix %s\n", vf_version());
            return VFP_HELP_SHOWN;
        } else if (!strcmp(a, "--board") && v) {
            o->board = v;
        } else if (!strcmp(a, "--preset") && v) {
            int k = 0;
            while (vfp_tf_preset_names[k] && strcmp(v, vfp_tf_preset_names[k]))
                k++;
            if (!vfp_tf_preset_names[k])
                return bad(a, v, "ramp, sharp, ct-bone, ct-skin-bone or mr-brain");
            o->preset = v;
        } else if (!strcmp(a, "--tf") && v) {
            o->tf = v;
        } else if (!strcmp(a, "--window") && v) {
            double w[2];
            if (vfp_parse_list(v, w, 2, 2) != 2 || w[0] == w[1])
                return bad(a, v, "LO,HI: two different finite numbers in data units, for example 0,1000");
            o->window = v;
        } else if (!strcmp(a, "--script") && v) {
            o->script = v;
        } else if (!strcmp(a, "--device") && v) {
            o->device = v;
        } else if (!strcmp(a, "--log") && v) {
            o->log = v;
        } else if (!strcmp(a, "--mode")) {
            int m;
            for (m = 0; m < VF_MODE_COUNT && !(v && !strcmp(v, vf_mode_name((vf_mode_t)m))); m++)
                ;
            if (m == VF_MODE_COUNT)
                return bad(a, v, "point, preint1, preclass or preint2");
            o->mode = (vf_mode_t)m;
        } else if (!strcmp(a, "--view")) {
            double d[3] = {0, 0, 0};
            if (!v || vfp_view_named(v, d) != VFP_OK) {
                if (!vfp_parse_list(v, d, 2, 3) || !(fabs(d[0]) <= 360 && fabs(d[1]) <= 360 && fabs(d[2]) <= 360))
                    return bad(a, v, "AZ,EL or AZ,EL,ROLL in degrees, each -360..360, or " VFP_VIEW_NAMES);
            }
            memcpy(o->view, d, sizeof d);
        } else if (!strcmp(a, "--zoom")) {
            if (!vfp_parse_number(v, VFP_ZOOM_MIN, VFP_ZOOM_MAX, &o->zoom))
                return bad(a, v, "a zoom from 0.25 to 8");
        } else if (!strcmp(a, "--size")) {
            if (!vfp_parse_size(v, 16, 4096, &o->width, &o->height))
                return bad(a, v, "WxH, each an integer 16 to 4096");
        } else if (!strcmp(a, "--preview")) {
            if (parse_int(v, 1, 8, &o->preview))
                return bad(a, v, "an integer from 1 (off) to 8");
        } else if (!strcmp(a, "--idle-ms")) {
            if (parse_int(v, 0, 60000, &o->idle_ms))
                return bad(a, v, "milliseconds from 0 to 60000");
        } else if (!strcmp(a, "--rays")) {
            if (parse_int(v, 1, 4, &o->rays) || (o->rays & (o->rays - 1)))
                return bad(a, v, "1, 2 or 4");
        } else if (!strcmp(a, "--threads")) {
            if (parse_int(v, 1, VFP_MAX_THREADS, &o->threads))
                return bad(a, v, "an integer from 1 to 16");
        } else if (!strcmp(a, "--frames")) {
            if (parse_int(v, 1, 1000000000, &o->frames))
                return bad(a, v, "a number of frames, an integer from 1 to 1000000000");
        } else if (!strcmp(a, "--overlay")) {
            o->overlay = 1;
            takes = 0;
        } else if (!strcmp(a, "--dims") && v) {
            if (vfp_parse_dims(v, o->load.dims, err, sizeof err)) {
                fprintf(stderr, "volfix: --dims: %s\n", err);
                return VFP_ERR;
            }
            o->load.have_dims = 1;
        } else if (!strcmp(a, "--type") && v) {
            if (vfp_parse_type(v, &o->load.type, err, sizeof err)) {
                fprintf(stderr, "volfix: --type: %s\n", err);
                return VFP_ERR;
            }
            o->load.have_type = 1;
        } else if (!strcmp(a, "--series")) {
            if (!v || !v[0])
                return bad(a, v, "a DICOM Series Instance UID");
            o->load.series = v;
        } else if (!strcmp(a, "--big-endian")) {
            o->load.big_endian = 1;
            takes = 0;
        } else if (!strcmp(a, "--spacing")) {
            double *sp = o->load.spacing;
            if (vfp_parse_list(v, sp, 3, 3) != 3 || !(sp[0] > 0 && sp[1] > 0 && sp[2] > 0) ||
                !(sp[0] <= 32767 && sp[1] <= 32767 && sp[2] <= 32767))
                return bad(a, v, "X,Y,Z, three numbers above 0 and at most 32767");
            o->load.have_spacing = 1;
        } else if ((took = vfp_lighting_option(&o->lighting, "volfix", a, v)) != 0) {
            if (took < 0)
                return VFP_ERR;
        } else if (a[0] == '-' && !v && !is_flag(a)) {
            fprintf(stderr, "volfix: %s: unknown option or missing value (see volfix --help)\n", a);
            return VFP_ERR;
        } else if (a[0] != '-' && !o->volume) {
            o->volume = a;
            takes = 0;
        } else {
            fprintf(stderr, "volfix: unknown option or extra argument '%s' (see volfix --help)\n", a);
            return VFP_ERR;
        }
        i += takes;
    }
    if (!o->board || !o->volume) {
        fprintf(stderr, "volfix: %s (usage: volfix --board BOARD VOLUME [options]; see --help)\n",
                !o->board ? "no board given" : "no volume given");
        return VFP_ERR;
    }
    if (!strchr(o->board, '/')) {
        size_t n = strlen(o->board);
        const char *ext = n > 6 && !strcmp(o->board + n - 6, ".board") ? "" : ".board";
        if (!n || snprintf(o->board_path, sizeof o->board_path, "%s/%s%s", VFP_BOARD_DIR, o->board, ext) >=
                      (int)sizeof o->board_path) {
            fprintf(stderr, "volfix: --board '%s': expected a board name or a path to a board file\n", o->board);
            return VFP_ERR;
        }
        if (access(o->board_path, R_OK) != 0) {
            fprintf(stderr, "volfix: --board %s: no board of that name in %s (a board file's path needs a slash: "
                    "./%s)\n", o->board, VFP_BOARD_DIR, o->board);
            return VFP_ERR;
        }
        o->board = o->board_path;
    }
    if (o->preset && o->tf) {
        fprintf(stderr, "volfix: give --preset or --tf, not both\n");
        return VFP_ERR;
    }
    if (vfp_lighting_check(&o->lighting, err, sizeof err)) {
        fprintf(stderr, "volfix: %s\n", err);
        return VFP_ERR;
    }
    return VFP_OK;
}

/* The transfer functions the preset button cycles: the --tf file first if there is one, then the presets. */
static vfp_status_t load_tfs(viewer_scene_t *s, const options_t *o, int *first, char *err, size_t errlen)
{
    s->tf_count = 0;
    *first = 0;
    if (o->tf) {
        if (vfp_tf_load(&s->tfs[0], o->tf, err, errlen))
            return VFP_ERR;
        snprintf(s->tf_args[0], sizeof s->tf_args[0], "--tf %s", o->tf);
        s->tf_count = 1;
    }
    for (int i = 0; vfp_tf_preset_names[i] && s->tf_count < VIEWER_MAX_TFS; i++) {
        vfp_tf_preset(&s->tfs[s->tf_count], vfp_tf_preset_names[i], err, errlen);
        snprintf(s->tf_args[s->tf_count], sizeof s->tf_args[0], "--preset %s", vfp_tf_preset_names[i]);
        if (o->preset && !strcmp(o->preset, vfp_tf_preset_names[i]))
            *first = s->tf_count;
        s->tf_count++;
    }
    if (o->preset && !*first && strcmp(o->preset, vfp_tf_preset_names[0])) {
        vfp_tf_t unused;
        return vfp_tf_preset(&unused, o->preset, err, errlen); /* its message lists the names */
    }
    return VFP_OK;
}

static vfp_status_t setup(viewer_t *v, const options_t *o, char *err, size_t errlen)
{
    /* the log first: a path that cannot be written is found before any work */
    if (o->log && !(v->log = fopen(o->log, "w"))) {
        snprintf(err, errlen, "%s: cannot write the log: %s", o->log, strerror(errno));
        return VFP_ERR;
    }
    v->log_path = o->log;
    if (vfp_board_load(&v->board, o->board, err, errlen))
        return VFP_ERR;
    vfp_board_t *b = &v->board;
    if (o->device)
        snprintf(b->display_device, sizeof b->display_device, "%s", o->device);
    if (o->width) {
        b->width = o->width;
        b->height = o->height;
    }
    if (o->idle_ms >= 0)
        b->idle_ms = o->idle_ms;
    if (o->overlay)
        b->overlay = 1;
    v->script = o->script;
    if (!(v->display_ops = vfp_display_find(b->display, b, err, errlen)))
        return VFP_ERR;
    if (!(v->input_ops = vfp_input_find(o->script ? "script" : b->input, b, err, errlen)))
        return VFP_ERR;

    viewer_scene_t *s = &v->scene;
    if (vfp_volume_load(&s->full, o->volume, &o->load, err, errlen))
        return VFP_ERR;
    s->window = vfp_default_window(&s->full);
    if (o->window && vfp_parse_window(&s->full, o->window, &s->window, err, errlen))
        return VFP_ERR;
    int first;
    if (load_tfs(s, o, &first, err, errlen))
        return VFP_ERR;
    vf_params_default(&s->params);
    s->rays_given = o->rays > 0 ? (uint32_t)o->rays : 0;
    for (int k = 0; k < s->tf_count; k++) { /* each transfer function's lighting; renderers are made to suit */
        vf_params_t p = s->params;
        vfp_lighting_resolve(&o->lighting, &s->tfs[k], &p, &s->lighting[k]);
        s->lit[k] = p.lighting;
        s->params.normal_bits = p.normal_bits;
        s->params.shade_lookup = p.shade_lookup;
    }
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    s->threads = o->threads > 0 ? o->threads : b->threads > 0 ? b->threads : cpus < 1 ? 1 : cpus > 16 ? 16 : (int)cpus;
    const uint32_t *d = s->full.core.dims;
    uint64_t voxels = (uint64_t)d[0] * d[1] * d[2];
    s->preview_factor = o->preview > 0 ? o->preview : voxels >= 64 * 64 * 64 ? 2 : 1;
    if (s->preview_factor > 1 && vfp_volume_downsampled(&s->preview, &s->full, s->preview_factor, err, errlen))
        return VFP_ERR;

    vfp_controls_t *c = &v->controls;
    c->azimuth = o->view[0];
    c->elevation = o->view[1];
    c->roll = o->view[2];
    c->zoom = o->zoom;
    c->tf_scale = 1;
    c->preset = first;
    c->preset_count = s->tf_count;
    c->mode = o->mode;
    /* the light knobs move the first light, from where --light put it (the headlight by default) */
    c->light_azimuth = o->lighting.light_count ? o->lighting.light[0][0] : 0;
    c->light_elevation = o->lighting.light_count ? o->lighting.light[0][1] : 0;
    c->shade = -1;
    vf_lighting_t lighting;
    viewer_lighting(s, c, &lighting);
    c->shade_now = lighting.shade;
    c->overlay = b->overlay;
    v->home = *c;
    v->volume_arg = o->volume;
    v->max_frames = o->frames > 0 ? (unsigned)o->frames : 0;
    return VFP_OK;
}

int main(int argc, char **argv)
{
#ifdef __GLIBC__
    /* Renderers are re-made at other sizes as modes, presets and transfer functions change. glibc would raise its
     * mmap threshold after the first large free and then serve those arenas from the heap, where they fragment
     * and the process grows over a long session; a fixed threshold keeps them in mmap, given back on free. 32 KB
     * rather than glibc's 128 KB puts frame images and band scratch there too, so that they cannot fragment the
     * heap either: tests/long holds the peak resident size of 10,000 frames within its bound. */
    mallopt(M_MMAP_THRESHOLD, 32 * 1024);
#endif
    options_t o;
    vfp_status_t status = parse(&o, argc, argv);
    if (status)
        return vfp_exit_status(status);
    viewer_t v;
    memset(&v, 0, sizeof v);
    char err[VIEWER_ERR_LEN] = "";
    /* from here on SIGINT and SIGTERM end every stage (a FIFO read waiting for its writer, the loop) cleanly,
     * with status 130 or 143 as a shell reports a process the signal ended */
    status = viewer_signals_catch(err, sizeof err);
    if (status == VFP_OK)
        status = setup(&v, &o, err, sizeof err);
    if (status) {
        if (!viewer_signal_caught())
            fprintf(stderr, "volfix: %s\n", err);
    } else if (!viewer_signal_caught()) {
        status = viewer_loop(&v);
    }
    if (v.log && fclose(v.log) != 0 && status == VFP_OK) {
        fprintf(stderr, "volfix: %s: cannot write the log: %s\n", o.log, strerror(errno));
        status = VFP_ERR;
    }
    vfp_volume_free(&v.scene.full);
    vfp_volume_free(&v.scene.preview);
    int sig = viewer_signal_caught();
    viewer_signals_release();
    return sig ? 128 + sig : vfp_exit_status(status);
}
