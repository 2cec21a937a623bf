/* SPDX-License-Identifier: MIT */
/* controls.c: input events to view and transfer-function changes (see controls.h). */
#include "controls.h"

#include <math.h>

static double wrap_degrees(double d)
{
    d = fmod(d, 360.0);
    return d < 0 ? d + 360.0 : d;
}

static double clamp(double v, double lo, double hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

static unsigned turn(vfp_controls_t *c, vfp_action_t action, double step, int steps)
{
    switch (action) {
    case VFP_ACT_AZIMUTH: c->azimuth = wrap_degrees(c->azimuth + steps * step); return VFP_CHANGED_VIEW;
    case VFP_ACT_ELEVATION: c->elevation = wrap_degrees(c->elevation + steps * step); return VFP_CHANGED_VIEW;
    case VFP_ACT_ROLL: c->roll = wrap_degrees(c->roll + steps * step); return VFP_CHANGED_VIEW;
    case VFP_ACT_ZOOM: {
        /* Per cent per detent, compounded, so that turning back by as many detents returns to the same zoom. */
        double zoom = clamp(c->zoom * pow(1 + step / 100, steps), VFP_ZOOM_MIN, VFP_ZOOM_MAX);
        if (zoom == c->zoom)
            return 0;
        c->zoom = zoom;
        return VFP_CHANGED_VIEW;
    }
    case VFP_ACT_LEVEL: {
        /* Snapped to 1e-9 so that detents up and as many down come back to exactly 0 (no 1e-17 left over). */
        double shift = clamp(round((c->tf_shift + steps * step / 100) * 1e9) / 1e9, -VFP_SHIFT_MAX, VFP_SHIFT_MAX);
        if (shift == c->tf_shift)
            return 0;
        c->tf_shift = shift;
        return VFP_CHANGED_TF;
    }
    case VFP_ACT_WIDTH: {
        double scale = clamp(c->tf_scale * pow(1 + step / 100, steps), VFP_SCALE_MIN, VFP_SCALE_MAX);
        if (scale == c->tf_scale)
            return 0;
        c->tf_scale = scale;
        return VFP_CHANGED_TF;
    }
    case VFP_ACT_LIGHT_AZIMUTH: {
        /* kept in [-180, 180): --light's range, and 0 the headlight */
        double az = wrap_degrees(c->light_azimuth + steps * step + 180) - 180;
        c->light_azimuth = az;
        return VFP_CHANGED_LIGHT;
    }
    case VFP_ACT_LIGHT_ELEVATION: {
        /* up to straight above or below, no further: past it the light would come from behind */
        double el = clamp(c->light_elevation + steps * step, -90, 90);
        if (el == c->light_elevation)
            return 0;
        c->light_elevation = el;
        return VFP_CHANGED_LIGHT;
    }
    case VFP_ACT_PRESET: {
        /* one preset a turn, whatever its detents: a fast turn should not skip presets unseen */
        if (c->preset_count < 2)
            return 0;
        c->preset = (c->preset + (steps * step > 0 ? 1 : c->preset_count - 1)) % c->preset_count;
        return VFP_CHANGED_TF;
    }
    case VFP_ACT_SHADE: {
        /* clockwise on, counter-clockwise off (a negative step the other way round) */
        int on = steps * step > 0;
        if (c->shade == on && c->shade_now == on)
            return 0;
        c->shade = on;
        return VFP_CHANGED_LIGHT;
    }
    default: return 0; /* a button's action on a knob: the board parser refuses it, nothing to do here */
    }
}

vfp_action_t vfp_controls_knob_action(const vfp_controls_t *c, const vfp_board_t *board, int n, double *step)
{
    const vfp_knob_t *k = &board->knobs[n];
    int at = k->cycle_count > 1 && c->knob_at[n] > 0 && c->knob_at[n] < k->cycle_count ? c->knob_at[n] : 0;
    *step = at ? k->cycle_step[at] : k->step;
    return at ? k->cycle[at] : k->action;
}

static unsigned press(vfp_controls_t *c, const vfp_controls_t *home, const vfp_board_t *board, vfp_action_t action)
{
    switch (action) {
    case VFP_ACT_TOGGLE_SHADE: c->shade = !c->shade_now; return VFP_CHANGED_LIGHT;
    case VFP_ACT_CYCLE_KNOBS: {
        unsigned changed = 0;
        for (int n = 0; n < board->knob_count && n < VFP_MAX_KNOBS; n++)
            if (board->knobs[n].cycle_count > 1) {
                c->knob_at[n] = (c->knob_at[n] + 1) % board->knobs[n].cycle_count;
                changed = VFP_CHANGED_KNOBS;
            }
        return changed;
    }
    case VFP_ACT_NEXT_PRESET:
        if (c->preset_count < 2)
            return 0;
        c->preset = (c->preset + 1) % c->preset_count;
        return VFP_CHANGED_TF;
    case VFP_ACT_NEXT_MODE: c->mode = (vf_mode_t)((c->mode + 1) % VF_MODE_COUNT); return VFP_CHANGED_MODE;
    case VFP_ACT_RESET: {
        vfp_controls_t was = *c;
        c->azimuth = home->azimuth;
        c->elevation = home->elevation;
        c->roll = home->roll;
        c->zoom = home->zoom;
        c->tf_shift = home->tf_shift;
        c->tf_scale = home->tf_scale;
        c->light_azimuth = home->light_azimuth;
        c->light_elevation = home->light_elevation;
        unsigned changed = 0;
        if (was.light_azimuth != c->light_azimuth || was.light_elevation != c->light_elevation)
            changed |= VFP_CHANGED_LIGHT;
        if (was.azimuth != c->azimuth || was.elevation != c->elevation || was.roll != c->roll || was.zoom != c->zoom)
            changed |= VFP_CHANGED_VIEW;
        if (was.tf_shift != c->tf_shift || was.tf_scale != c->tf_scale)
            changed |= VFP_CHANGED_TF;
        return changed;
    }
    case VFP_ACT_OVERLAY: c->overlay = !c->overlay; return VFP_CHANGED_OVERLAY;
    case VFP_ACT_QUIT: c->quit = 1; return VFP_CHANGED_QUIT;
    default: return 0;
    }
}

unsigned vfp_controls_apply(vfp_controls_t *c, const vfp_controls_t *home, const vfp_board_t *board,
                            const vfp_event_t *ev)
{
    switch (ev->type) {
    case VFP_EV_TURN:
        if (ev->control < 0 || ev->control >= board->knob_count || ev->steps == 0)
            return 0;
    {
        double step;
        vfp_action_t action = vfp_controls_knob_action(c, board, ev->control, &step);
        return turn(c, action, step, ev->steps);
    }
    case VFP_EV_PRESS:
        if (ev->control < 0 || ev->control >= board->button_count)
            return 0;
        return press(c, home, board, board->buttons[ev->control].action);
    case VFP_EV_QUIT: c->quit = 1; return VFP_CHANGED_QUIT;
    default: return 0; /* releases do nothing yet */
    }
}

int32_t vfp_degrees_to_bau(double degrees)
{
    return (int32_t)lround(degrees * VF_BAU_PER_TURN / 360.0);
}

vf_view_t vfp_controls_view(const vfp_controls_t *c, int rotation)
{
    vf_view_t v = {vfp_degrees_to_bau(c->azimuth), vfp_degrees_to_bau(c->elevation),
                   vfp_degrees_to_bau(wrap_degrees(c->roll - rotation)), (uint32_t)lround(c->zoom * 65536)};
    return v;
}
