/* SPDX-License-Identifier: MIT */
/* test_controls.c: the viewer's input-to-view mapping (port/input/controls.c) and the overlay's font (overlay.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "input/controls.h"
#include "display/overlay.h"

static vfp_board_t board_with_knobs(void)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    vfp_action_t knobs[] = {VFP_ACT_AZIMUTH, VFP_ACT_ELEVATION, VFP_ACT_ZOOM, VFP_ACT_LEVEL, VFP_ACT_WIDTH,
                            VFP_ACT_ROLL};
    double steps[] = {5, 10, 10, 2, 10, 90};
    for (int i = 0; i < 6; i++) {
        b.knobs[i].action = knobs[i];
        b.knobs[i].step = steps[i];
    }
    b.knob_count = 6;
    vfp_action_t buttons[] = {VFP_ACT_NEXT_PRESET, VFP_ACT_NEXT_MODE, VFP_ACT_RESET, VFP_ACT_OVERLAY, VFP_ACT_QUIT};
    for (int i = 0; i < 5; i++)
        b.buttons[i].action = buttons[i];
    b.button_count = 5;
    return b;
}

static vfp_controls_t start(void)
{
    vfp_controls_t c;
    memset(&c, 0, sizeof c);
    c.azimuth = 30;
    c.elevation = 20;
    c.zoom = 1;
    c.tf_scale = 1;
    c.preset_count = 3;
    c.mode = VF_MODE_PREINT1;
    return c;
}

static unsigned turn(vfp_controls_t *c, const vfp_controls_t *home, const vfp_board_t *b, int knob, int steps)
{
    vfp_event_t ev = {VFP_EV_TURN, knob, steps, 0};
    return vfp_controls_apply(c, home, b, &ev);
}

static unsigned press(vfp_controls_t *c, const vfp_controls_t *home, const vfp_board_t *b, int button)
{
    vfp_event_t ev = {VFP_EV_PRESS, button, 0, 0};
    return vfp_controls_apply(c, home, b, &ev);
}

static void knobs_turn_the_view_and_wrap(void)
{
    vfp_board_t b = board_with_knobs();
    vfp_controls_t home = start(), c = home;
    CHECK_EQ(turn(&c, &home, &b, 0, 3), VFP_CHANGED_VIEW);
    CHECK_NEAR(c.azimuth, 45, 1e-12);
    turn(&c, &home, &b, 0, -10); /* 45 - 50 wraps to 355 */
    CHECK_NEAR(c.azimuth, 355, 1e-12);
    CHECK_EQ(turn(&c, &home, &b, 1, 40), VFP_CHANGED_VIEW); /* 20 + 400 wraps to 60 */
    CHECK_NEAR(c.elevation, 60, 1e-9);
    CHECK_EQ(turn(&c, &home, &b, 5, -1), VFP_CHANGED_VIEW);
    CHECK_NEAR(c.roll, 270, 1e-12);
    CHECK_EQ(turn(&c, &home, &b, 0, 0), 0); /* no detents, no change */
    CHECK_EQ(turn(&c, &home, &b, 6, 1), 0); /* a knob the board does not have */
    CHECK_EQ(turn(&c, &home, &b, -1, 1), 0);
}

static void zoom_compounds_and_clamps(void)
{
    vfp_board_t b = board_with_knobs();
    vfp_controls_t home = start(), c = home;
    turn(&c, &home, &b, 2, 3);
    CHECK_NEAR(c.zoom, 1.1 * 1.1 * 1.1, 1e-12);
    turn(&c, &home, &b, 2, -3); /* back by as many detents: back to where it was */
    CHECK_NEAR(c.zoom, 1, 1e-12);
    turn(&c, &home, &b, 2, 100);
    CHECK_NEAR(c.zoom, VFP_ZOOM_MAX, 0);
    CHECK_EQ(turn(&c, &home, &b, 2, 1), 0); /* at the limit nothing changes, so nothing is rendered */
    turn(&c, &home, &b, 2, -200);
    CHECK_NEAR(c.zoom, VFP_ZOOM_MIN, 0);
}

static void level_and_width_move_the_transfer_function(void)
{
    vfp_board_t b = board_with_knobs();
    vfp_controls_t home = start(), c = home;
    CHECK_EQ(turn(&c, &home, &b, 3, 5), VFP_CHANGED_TF);
    CHECK_NEAR(c.tf_shift, 0.10, 1e-12);
    CHECK_NEAR(c.azimuth, 30, 0); /* the view stays */
    turn(&c, &home, &b, 3, 1000);
    CHECK_NEAR(c.tf_shift, VFP_SHIFT_MAX, 0);
    CHECK_EQ(turn(&c, &home, &b, 4, -2), VFP_CHANGED_TF);
    CHECK_NEAR(c.tf_scale, 1 / 1.21, 1e-12); /* (1 + 10%)^-2 */
    turn(&c, &home, &b, 4, -1000);
    CHECK_NEAR(c.tf_scale, VFP_SCALE_MIN, 0);
}

static void buttons_cycle_reset_toggle_and_quit(void)
{
    vfp_board_t b = board_with_knobs();
    vfp_controls_t home = start(), c = home;
    CHECK_EQ(press(&c, &home, &b, 0), VFP_CHANGED_TF);
    CHECK_EQ(c.preset, 1);
    press(&c, &home, &b, 0);
    press(&c, &home, &b, 0);
    CHECK_EQ(c.preset, 0); /* three presets: round again */
    CHECK_EQ(press(&c, &home, &b, 1), VFP_CHANGED_MODE);
    CHECK_EQ(c.mode, (VF_MODE_PREINT1 + 1) % VF_MODE_COUNT);
    for (int i = 1; i < VF_MODE_COUNT; i++)
        press(&c, &home, &b, 1);
    CHECK_EQ(c.mode, VF_MODE_PREINT1);

    turn(&c, &home, &b, 0, 4);
    turn(&c, &home, &b, 3, 4);
    press(&c, &home, &b, 0);
    CHECK_EQ(press(&c, &home, &b, 2), VFP_CHANGED_VIEW | VFP_CHANGED_TF);
    CHECK_NEAR(c.azimuth, 30, 0);
    CHECK_NEAR(c.tf_shift, 0, 0);
    CHECK_EQ(c.preset, 1); /* reset keeps the preset and mode */
    CHECK_EQ(press(&c, &home, &b, 2), 0); /* already home */

    CHECK_EQ(press(&c, &home, &b, 3), VFP_CHANGED_OVERLAY);
    CHECK_EQ(c.overlay, 1);
    press(&c, &home, &b, 3);
    CHECK_EQ(c.overlay, 0);
    vfp_event_t release = {VFP_EV_RELEASE, 4, 0, 0};
    CHECK_EQ(vfp_controls_apply(&c, &home, &b, &release), 0);
    CHECK_EQ(press(&c, &home, &b, 4), VFP_CHANGED_QUIT);
    CHECK_EQ(c.quit, 1);
    c.quit = 0;
    vfp_event_t quit = {VFP_EV_QUIT, 0, 0, 0};
    CHECK_EQ(vfp_controls_apply(&c, &home, &b, &quit), VFP_CHANGED_QUIT);
    CHECK_EQ(c.quit, 1);

    c.preset_count = 1; /* one transfer function: the preset button has nothing to cycle */
    CHECK_EQ(press(&c, &home, &b, 0), 0);
}

/* One knob and three buttons, as a small board has: the knob cycles through the view, the light, shading and the
 * presets; a button cycles it, one toggles shading, one resets. */
static void light_shade_and_cycling_knobs(void)
{
    vfp_board_t b;
    memset(&b, 0, sizeof b);
    b.knob_count = 2;
    b.knobs[0].action = VFP_ACT_AZIMUTH;
    b.knobs[0].step = 5;
    b.knobs[0].cycle_count = 5;
    static const vfp_action_t cycle[5] = {VFP_ACT_AZIMUTH, VFP_ACT_LIGHT_AZIMUTH, VFP_ACT_LIGHT_ELEVATION,
                                          VFP_ACT_SHADE, VFP_ACT_PRESET};
    static const double steps[5] = {5, 100, 30, 5, 5};
    for (int i = 0; i < 5; i++)
        b.knobs[0].cycle[i] = cycle[i], b.knobs[0].cycle_step[i] = steps[i];
    b.knobs[1].action = VFP_ACT_ZOOM; /* no cycle: the button leaves it alone */
    b.knobs[1].step = 10;
    b.knobs[1].cycle_count = 1;
    b.button_count = 3;
    b.buttons[0].action = VFP_ACT_CYCLE_KNOBS;
    b.buttons[1].action = VFP_ACT_TOGGLE_SHADE;
    b.buttons[2].action = VFP_ACT_RESET;
    vfp_controls_t home = start(), c;
    home.shade = -1;
    c = home;
    double step;

    CHECK_EQ(turn(&c, &home, &b, 0, 2), VFP_CHANGED_VIEW); /* page 0: azimuth */
    CHECK_NEAR(c.azimuth, 40, 0);
    CHECK_EQ(press(&c, &home, &b, 0), VFP_CHANGED_KNOBS);
    CHECK_EQ(vfp_controls_knob_action(&c, &b, 0, &step), VFP_ACT_LIGHT_AZIMUTH);
    CHECK_NEAR(step, 100, 0);
    CHECK_EQ(vfp_controls_knob_action(&c, &b, 1, &step), VFP_ACT_ZOOM);
    CHECK_EQ(turn(&c, &home, &b, 0, 2), VFP_CHANGED_LIGHT); /* 200 degrees: wraps to -160 */
    CHECK_NEAR(c.light_azimuth, -160, 1e-12);
    CHECK_NEAR(c.azimuth, 40, 0);
    turn(&c, &home, &b, 0, -4);
    CHECK_NEAR(c.light_azimuth, 160, 1e-12);
    press(&c, &home, &b, 0);
    CHECK_EQ(turn(&c, &home, &b, 0, 2), VFP_CHANGED_LIGHT);
    CHECK_NEAR(c.light_elevation, 60, 0);
    CHECK_EQ(turn(&c, &home, &b, 0, 2), VFP_CHANGED_LIGHT); /* stops straight above */
    CHECK_NEAR(c.light_elevation, 90, 0);
    CHECK_EQ(turn(&c, &home, &b, 0, 1), 0);
    press(&c, &home, &b, 0);
    c.shade_now = 0;
    CHECK_EQ(turn(&c, &home, &b, 0, 1), VFP_CHANGED_LIGHT); /* shade knob: clockwise on */
    CHECK_EQ(c.shade, 1);
    c.shade_now = 1;
    CHECK_EQ(turn(&c, &home, &b, 0, 3), 0); /* on already */
    CHECK_EQ(turn(&c, &home, &b, 0, -1), VFP_CHANGED_LIGHT);
    CHECK_EQ(c.shade, 0);
    press(&c, &home, &b, 0);
    CHECK_EQ(turn(&c, &home, &b, 0, 3), VFP_CHANGED_TF); /* preset knob: one preset a turn */
    CHECK_EQ(c.preset, 1);
    turn(&c, &home, &b, 0, -1);
    turn(&c, &home, &b, 0, -1);
    CHECK_EQ(c.preset, 2); /* back round */
    CHECK_EQ(press(&c, &home, &b, 0), VFP_CHANGED_KNOBS); /* after the last: azimuth again */
    CHECK_EQ(vfp_controls_knob_action(&c, &b, 0, &step), VFP_ACT_AZIMUTH);
    CHECK_NEAR(step, 5, 0);

    /* the shade button turns over what is shown, whatever the transfer function says */
    c.shade = -1;
    c.shade_now = 1;
    CHECK_EQ(press(&c, &home, &b, 1), VFP_CHANGED_LIGHT);
    CHECK_EQ(c.shade, 0);
    c.shade_now = 0;
    press(&c, &home, &b, 1);
    CHECK_EQ(c.shade, 1);

    /* reset brings the light home too */
    CHECK_EQ(press(&c, &home, &b, 2), VFP_CHANGED_VIEW | VFP_CHANGED_LIGHT);
    CHECK_NEAR(c.light_azimuth, 0, 0);
    CHECK_NEAR(c.light_elevation, 0, 0);
    CHECK_EQ(press(&c, &home, &b, 2), 0);

    b.knobs[0].cycle_count = 1; /* a board without cycles: the button does nothing */
    CHECK_EQ(press(&c, &home, &b, 0), 0);
}

static void view_in_binary_angles_with_the_panel_rotation(void)
{
    vfp_controls_t c = start();
    c.roll = 10;
    c.zoom = 1.5;
    vf_view_t v = vfp_controls_view(&c, 0);
    CHECK_EQ(v.azimuth, vfp_degrees_to_bau(30));
    CHECK_EQ(v.azimuth, 5461); /* 30/360 of 65536, rounded */
    CHECK_EQ(v.zoom_q16, 98304);
    CHECK_EQ(v.roll, vfp_degrees_to_bau(10));
    vf_view_t r = vfp_controls_view(&c, 90);
    CHECK_EQ(r.roll, vfp_degrees_to_bau(280)); /* rolled back by the mounting angle, wrapped */
    CHECK_EQ(r.azimuth, v.azimuth);
}

/* ---- overlay ---- */

static int lit(const vf_image_t *img, int x, int y)
{
    const uint8_t *p = (const uint8_t *)img->pixels + (size_t)y * img->stride +
                       (size_t)x * vf_format_bytes(img->format);
    return p[0] == 0xff;
}

static void overlay_draws_text_in_every_format(void)
{
    vf_format_t formats[] = {VF_FORMAT_RGB888, VF_FORMAT_RGB565, VF_FORMAT_XRGB8888};
    for (int f = 0; f < 3; f++) {
        vf_image_t img = {NULL, 40, 20, 40 * vf_format_bytes(formats[f]), formats[f]};
        img.pixels = calloc(img.height, img.stride);
        vfp_overlay_text(&img, 0, 0, 0, 1, "1");
        /* '1': row 0 of the glyph is 0x04, the middle column lit; the box's margin is one pixel */
        CHECK(lit(&img, 1 + 2, 1));
        CHECK(!lit(&img, 1 + 1, 1));
        CHECK(!lit(&img, 0, 0)); /* the box, dark */
        CHECK(((uint8_t *)img.pixels)[0] != 0 || formats[f] == VF_FORMAT_RGB565); /* box drawn */
        free(img.pixels);
    }
    CHECK_EQ(vfp_overlay_width("12", 1), 2 * 6 - 1 + 2);
    CHECK_EQ(vfp_overlay_height(2), 18);
}

static void overlay_turns_with_the_panel_and_clips(void)
{
    /* A 30x20 panel mounted at 90 degrees shows a 20-wide, 30-tall upright picture: the text drawn for it, turned
     * back by 90 degrees, must be the text drawn on an upright 20x30 image. */
    int rots[] = {90, 180, 270};
    for (int k = 0; k < 3; k++) {
        int rot = rots[k];
        uint32_t uw = rot == 180 ? 30 : 20, uh = rot == 180 ? 20 : 30;
        vf_image_t up = {calloc(uh, uw * 3), uw, uh, uw * 3, VF_FORMAT_RGB888};
        vf_image_t panel = {calloc(20, 30 * 3), 30, 20, 30 * 3, VF_FORMAT_RGB888};
        vfp_overlay_text(&up, 0, 1, 2, 1, "E7");
        vfp_overlay_text(&panel, rot, 1, 2, 1, "E7");
        int same = 1;
        for (int y = 0; y < (int)uh; y++)
            for (int x = 0; x < (int)uw; x++) {
                int px, py; /* where the upright pixel (x, y) lies in the panel's buffer, mounted clockwise */
                if (rot == 90) {
                    px = y;
                    py = 20 - 1 - x;
                } else if (rot == 180) {
                    px = 30 - 1 - x;
                    py = 20 - 1 - y;
                } else {
                    px = 30 - 1 - y;
                    py = x;
                }
                same &= lit(&up, x, y) == lit(&panel, px, py);
            }
        free(up.pixels);
        free(panel.pixels);
        CHECK_MSG(same, "rotation %d: the panel's text is not the upright text turned", rot);
    }
    /* Text running off every edge writes nothing outside the image (AddressSanitizer watches). */
    vf_image_t small = {calloc(5, 8 * 2), 8, 5, 16, VF_FORMAT_RGB565};
    vfp_overlay_text(&small, 0, -3, -4, 3, "WIDE TEXT 123");
    vfp_overlay_text(&small, 270, 6, 3, 2, "X");
    free(small.pixels);
}

/* The patient directions at the middle of each edge (vfp_overlay_directions): the letter L alone at the right edge,
 * R at the left, S at the top, I at the bottom, and nothing in the picture's middle. */
static void overlay_names_the_edges(void)
{
    const int w = 61, h = 41;
    vf_image_t img = {calloc((size_t)h, (size_t)w * 3), (uint32_t)w, (uint32_t)h, (uint32_t)w * 3, VF_FORMAT_RGB888};
    vfp_overlay_directions(&img, 0, 1, "L", "R", "S", "I");
    int box[4][4]; /* per edge (right, left, top, bottom): lit x0, x1, y0, y1 */
    for (int e = 0; e < 4; e++) {
        box[e][0] = box[e][2] = 1 << 20;
        box[e][1] = box[e][3] = -1;
    }
    int middle = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            if (!lit(&img, x, y))
                continue;
            int e = x >= w - 10 ? 0 : x < 10 ? 1 : y < 12 ? 2 : y >= h - 12 ? 3 : -1;
            if (e < 0) {
                middle++;
                continue;
            }
            box[e][0] = x < box[e][0] ? x : box[e][0];
            box[e][1] = x > box[e][1] ? x : box[e][1];
            box[e][2] = y < box[e][2] ? y : box[e][2];
            box[e][3] = y > box[e][3] ? y : box[e][3];
        }
    free(img.pixels);
    CHECK_EQ(middle, 0);
    for (int e = 0; e < 4; e++)
        CHECK_MSG(box[e][1] >= 0, "edge %d has no letter", e);
    /* right and left letters centred vertically, top and bottom centred horizontally */
    CHECK(box[0][2] > h / 2 - 8 && box[0][3] < h / 2 + 8 && box[1][2] > h / 2 - 8 && box[1][3] < h / 2 + 8);
    CHECK(box[2][0] > w / 2 - 6 && box[2][1] < w / 2 + 6 && box[3][0] > w / 2 - 6 && box[3][1] < w / 2 + 6);
    CHECK(box[0][1] >= w - 4 && box[1][0] <= 3 && box[2][2] <= 3 && box[3][3] >= h - 4);
}

CHECK_CASES({"knobs_turn_the_view_and_wrap", knobs_turn_the_view_and_wrap},
            {"overlay_names_the_edges", overlay_names_the_edges},
            {"light_shade_and_cycling_knobs", light_shade_and_cycling_knobs},
            {"zoom_compounds_and_clamps", zoom_compounds_and_clamps},
            {"level_and_width_move_the_transfer_function", level_and_width_move_the_transfer_function},
            {"buttons_cycle_reset_toggle_and_quit", buttons_cycle_reset_toggle_and_quit},
            {"view_in_binary_angles_with_the_panel_rotation", view_in_binary_angles_with_the_panel_rotation},
            {"overlay_draws_text_in_every_format", overlay_draws_text_in_every_format},
            {"overlay_turns_with_the_panel_and_clips", overlay_turns_with_the_panel_and_clips});
CHECK_RUN("port/controls")
