/* SPDX-License-Identifier: MIT */
/* options.h: the command-line options volfix-sim's commands share. */
#ifndef SIM_OPTIONS_H
#define SIM_OPTIONS_H

#include "volfix.h"
#include "io/lighting_opts.h"
#include "io/volume.h"

typedef struct sim_opts {
    const char *volume;        /* file or phantom:NAME:N */
    vfp_load_opts_t load;      /* --dims --type --big-endian --spacing (raw files) */
    const char *preset;        /* --preset NAME (default ramp) */
    const char *tf_file;       /* --tf FILE */
    const char *window;        /* --window LO,HI in data units */
    double tf_shift, tf_scale; /* --tf-move SHIFT,SCALE (vfp_tf_move; default 0,1) */
    vf_params_t params;        /* --mode --table-size */
    int rays_given;            /* --rays given: the spacing does not choose it (render/sampling.h) */
    vfp_lighting_opts_t lighting; /* --shade --light --material --gradient-opacity --normal-bits --shade-lookup */
    double azimuth, elevation, roll; /* --view AZ,EL[,ROLL] degrees */
    double zoom;               /* --zoom */
    uint32_t width, height;    /* --size WxH */
    vf_format_t format;        /* --format */
    int threads;               /* --threads */
    int reference;             /* --reference: render with the double reference */
    int truth;                 /* --truth (render), --against truth (compare): the ground-truth ray caster */
    int truth_filter;          /* --truth-filter: the truth's reconstruction, a truth_filter_t (0: trilinear) */
    int have_pixel;            /* --pixel X,Y given */
    double pixel[2];           /* --pixel X,Y: a final-image position */
    const char *out;           /* -o FILE */
    const char *diff;          /* --diff FILE */
    int json;                  /* --json */
    int hash;                  /* --hash (render) */
    int frames;                /* --frames (bench) */
    int matrix;                /* --matrix (bench) */
    int rounds;                /* --rounds (bench): 0 when not given (the command picks its default) */
} sim_opts_t;

/* Option groups a command accepts. */
enum {
    SIM_OPT_SCENE = 1,   /* volume, transfer function, mode, view, size, format, window, threads */
    SIM_OPT_OUT = 2,     /* -o */
    SIM_OPT_REF = 4,     /* --reference */
    SIM_OPT_DIFF = 8,    /* --diff */
    SIM_OPT_JSON = 16,   /* --json */
    SIM_OPT_FRAMES = 32, /* --frames */
    SIM_OPT_MATRIX = 64, /* --matrix */
    SIM_OPT_TRUTH = 128,  /* --truth */
    SIM_OPT_AGAINST = 256, /* --against reference|truth */
    SIM_OPT_PIXEL = 512,  /* --pixel X,Y */
    SIM_OPT_HASH = 1024,  /* --hash */
    SIM_OPT_ROUNDS = 2048, /* --rounds */
    SIM_OPT_OUT_DIR = 4096, /* -o names a folder (made when its files are written), not a PNG */
    SIM_OPT_FILTER = 8192,  /* --truth-filter for a command that always uses the truth's reconstruction (ray) */
};

/* Parse argv (after the command name). Returns VFP_OK, VFP_HELP_SHOWN when --help was asked (usage printed), or
 * VFP_ERR after printing a one-line error to stderr. */
vfp_status_t sim_parse(sim_opts_t *o, int argc, char **argv, unsigned groups, const char *usage);

/* What the parsed options promise to write and read, checked before any work (a volume loaded, a frame
 * rendered): -o and --diff writable (vfp_png_check_output; "-", standard output, for render's -o only), -o DIR
 * made, render given -o or --hash, --pixel inside the image, the window two different numbers, the preset
 * known. Returns VFP_OK, or VFP_ERR after printing a one-line error. */
vfp_status_t sim_check_options(const sim_opts_t *o, unsigned groups);

/* "point", "preint1", "preclass" or "preint2". Returns VFP_OK, or VFP_ERR for another text. */
vfp_status_t sim_parse_mode(const char *text, vf_mode_t *mode);

/* What preint2 takes and only it takes (its lookups, no partial slabs): VFP_OK, or VFP_ERR after a one-line error. */
vfp_status_t sim_check_order2(const vf_params_t *params);

/* The scene options' help text, for the commands' usage. */
extern const char sim_scene_help[];

#endif
