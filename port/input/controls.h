/* SPDX-License-Identifier: MIT */
/*
 * controls.h: what the knobs and buttons control, and how an input event changes it. The viewer holds one
 * vfp_controls_t; the board file says which knob or button does what (board.h). Pure functions, tested alone.
 *
 * Units: angles in degrees (the view's kept in [0, 360); the light's azimuth in [-180, 180) and its elevation
 * in [-90, 90], relative to the viewer as --light takes them), zoom as a factor (1 fits the volume's bounding sphere), the
 * transfer function's shift in windows and its scale as a factor (vfp_tf_move in tf.h).
 */
#ifndef VFP_CONTROLS_H
#define VFP_CONTROLS_H

#include "board/board.h"
#include "input.h"
#include "volfix.h"

#define VFP_ZOOM_MIN 0.25
#define VFP_ZOOM_MAX 8.0
#define VFP_SHIFT_MAX 1.0   /* the transfer function moves at most one window either way */
#define VFP_SCALE_MIN 0.05
#define VFP_SCALE_MAX 20.0

typedef struct vfp_controls {
    double azimuth, elevation, roll;
    double zoom;
    double tf_shift, tf_scale;
    int preset;       /* which transfer function, 0 .. preset_count - 1 */
    int preset_count; /* how many the button cycles through */
    vf_mode_t mode;
    double light_azimuth, light_elevation; /* the first light, relative to the viewer (volfix --light AZ,EL) */
    int shade;        /* -1: each transfer function as it says; 0 off; 1 on (the shade knob or button) */
    int shade_now;    /* whether the frame shown is shaded: the viewer keeps it, the shade button turns it over */
    int knob_at[VFP_MAX_KNOBS]; /* which of its board cycle's actions each knob does now (0: knob.N.action) */
    int overlay;      /* the frame-time overlay is shown */
    int quit;
} vfp_controls_t;

/* What an event changed: the caller rebuilds only what it must. */
enum {
    VFP_CHANGED_VIEW = 1,    /* angles or zoom: a new frame */
    VFP_CHANGED_TF = 2,      /* shift, scale or preset: reclassify, then a new frame */
    VFP_CHANGED_MODE = 4,    /* the rendering mode: a new renderer */
    VFP_CHANGED_OVERLAY = 8, /* the overlay: the same picture, redrawn */
    VFP_CHANGED_QUIT = 16,
    VFP_CHANGED_LIGHT = 32,  /* the light or shading: relight (a new renderer when shading turns a renderer's
                              * lighting on or off), then a new frame */
    VFP_CHANGED_KNOBS = 64,  /* what the knobs do (cycle-knobs): the overlay says it */
};

/* The action knob n does now, and its step (its board cycle at c->knob_at[n]). */
vfp_action_t vfp_controls_knob_action(const vfp_controls_t *c, const vfp_board_t *board, int n, double *step);

/* Apply one event. `home` is where the reset button goes back to (the view and transfer function the viewer
 * started with; the preset and mode stay). Returns the VFP_CHANGED_ bits. */
unsigned vfp_controls_apply(vfp_controls_t *c, const vfp_controls_t *home, const vfp_board_t *board,
                            const vfp_event_t *event);

/* The core's view for these controls on a panel mounted at `rotation` degrees clockwise (0, 90, 180, 270):
 * the picture is rolled the other way, so that it stands upright on the mounted panel. */
vf_view_t vfp_controls_view(const vfp_controls_t *c, int rotation);

/* Degrees to the core's binary angle units (rounded), as volfix-sim's --view converts them. */
int32_t vfp_degrees_to_bau(double degrees);

#endif
