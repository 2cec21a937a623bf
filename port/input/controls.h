/*
 * controls.h: what the knobs and buttons control, and how an input event changes it. The viewer holds one
 * vfp_controls_t; the board file says which knob or button does what (board.h). Pure functions, tested alone.
 *
 * Units: angles in degrees (kept in [0, 360)), zoom as a factor (1 fits the volume's bounding sphere), the
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
};

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
