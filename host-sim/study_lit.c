/* SPDX-License-Identifier: MIT */
/* study_lit.c: the lighting stages of the precision study (docs/algorithm.md section 7), each on its own around
 * the lit default (preint1, one headlight, VTK's material, 14-bit normals, bilinear shade lookup):
 *   normal_bits     the core with 8..16-bit normal codes against the double reference lit with unquantised
 *                   normals (section 7's gradients in double, normalised): the codes' error, and the core's
 *   shade_bits      the double reference with its shade table's L_d, L_s rounded to B fraction bits (the core
 *                   keeps 14) against the reference with them exact: what the table needs
 *   lit_table_bits  the double reference with its front-weighted table (D_f, S_f) rounded to B bits against the
 *                   reference with it exact, the plain table untouched: what the lit table needs
 *   shade_lookup    (full study) point and preint1 with each shade lookup, against the lit truth: the default's
 *                   reason
 * and against the lit truth for the runs of the core. Each stage's runs go into the study's list under its factor
 * (study_plots.c draws them, study_report.c tabulates them). */
#include <stdlib.h>
#include <string.h>

#include "io/pngio.h"
#include "study.h"

/* A scene of the study, lit with the default lighting (phong, whatever the preset says). */
static int lit_scene(study_t *st, const char *label, const char *volume, double az, double el, uint32_t size,
                     char *err, size_t errlen)
{
    int s = study_add_scene(st, label, volume, "sharp", az, el, 1, size, err, errlen);
    if (s < 0)
        return -1;
    sim_scene_t *sc = &st->scenes[s].scene;
    sc->params = study_lit_params();
    vf_lighting_default(&sc->lighting);
    return s;
}

vf_params_t study_lit_params(void)
{
    vf_params_t p = study_default_params();
    p.lighting = true;
    return p;
}

/* The double reference's image of a lit scene with these parameters and the study's knobs of its lighting. */
static uint8_t *reference_image(study_t *st, int scene, const vf_params_t *params, int exact_normals, int shade_bits,
                                int lit_table_bits, char *err, size_t errlen)
{
    sim_scene_t s = st->scenes[scene].scene; /* a copy: only the parameters change */
    s.params = *params;
    s.ref_exact_normals = exact_normals;
    s.ref_shade_bits = shade_bits;
    s.ref_lit_table_bits = lit_table_bits;
    vf_factor_t factor;
    vf_status_t fs = vf_factor(&factor, &s.vol.core, &s.view, s.width, s.height);
    if (fs != VF_OK) {
        snprintf(err, errlen, "cannot factor the view: %s", vf_status_text(fs));
        return NULL;
    }
    vf_image_t img;
    if (sim_render_reference(&s, &factor, &img, err, errlen))
        return NULL;
    uint8_t *rgb = malloc((size_t)img.width * img.height * 3);
    if (rgb)
        vfp_image_to_rgb(&img, rgb);
    else
        snprintf(err, errlen, "out of memory");
    sim_image_free(&img);
    return rgb;
}

/* A run of the lit study: image rgb (the core's, or the reference's with a knob) against ref and, when not NULL,
 * the truth. */
static study_run_t *add_run(study_t *st, int scene, const vf_params_t *params, const char *factor, const char *value,
                            const uint8_t *rgb, const uint8_t *ref, const uint8_t *truth, char *err, size_t errlen)
{
    if (st->run_count >= STUDY_MAX_RUNS) {
        snprintf(err, errlen, "too many runs");
        return NULL;
    }
    const size_t pixels = (size_t)st->scenes[scene].size * st->scenes[scene].size;
    study_run_t *run = &st->runs[st->run_count++];
    memset(run, 0, sizeof *run);
    run->scene = scene;
    run->params = *params;
    snprintf(run->factor, sizeof run->factor, "%s", factor);
    snprintf(run->value, sizeof run->value, "%s", value);
    sim_diff(rgb, ref, pixels, &run->vs_reference);
    if (truth)
        sim_diff(rgb, truth, pixels, &run->vs_truth);
    study_progress(st, run);
    return run;
}

/* The core's image with these parameters, and its run against ref and the truth (memory recorded). */
static vfp_status_t core_run(study_t *st, int scene, const vf_params_t *p, const char *factor, const char *value,
                             const uint8_t *ref, const uint8_t *truth, char *err, size_t errlen)
{
    const size_t pixels = (size_t)st->scenes[scene].size * st->scenes[scene].size;
    uint8_t *rgb = malloc(pixels * 3);
    if (!rgb) {
        snprintf(err, errlen, "out of memory");
        return VFP_ERR;
    }
    vf_memory_t memory;
    vfp_status_t status = study_render_core_memory(st, scene, p, rgb, &memory, err, errlen);
    study_run_t *run = status ? NULL : add_run(st, scene, p, factor, value, rgb, ref, truth, err, errlen);
    if (run)
        run->memory = memory;
    free(rgb);
    return run ? VFP_OK : VFP_ERR;
}

/* A reference run with one knob against the exact reference exact. */
static vfp_status_t knob_run(study_t *st, int scene, const char *factor, unsigned bits, const uint8_t *exact,
                             char *err, size_t errlen)
{
    const vf_params_t p = study_lit_params();
    const int shade = strcmp(factor, "shade_bits") == 0;
    uint8_t *rgb = reference_image(st, scene, &p, 0, shade ? (int)bits : 0, shade ? 0 : (int)bits, err, errlen);
    char value[16];
    snprintf(value, sizeof value, "%u", bits);
    study_run_t *run = rgb ? add_run(st, scene, &p, factor, value, rgb, exact, NULL, err, errlen) : NULL;
    free(rgb);
    return run ? VFP_OK : VFP_ERR;
}

/* Every stage on one lit scene. */
static vfp_status_t stages(study_t *st, int scene, char *err, size_t errlen)
{
    const int quick = st->quick;
    const vf_params_t def = study_lit_params();
    const uint8_t *truth = study_truth(st, scene, err, errlen);
    uint8_t *unquantised = truth ? reference_image(st, scene, &def, 1, 0, 0, err, errlen) : NULL;
    uint8_t *exact = unquantised ? reference_image(st, scene, &def, 0, 0, 0, err, errlen) : NULL;
    vfp_status_t status = exact ? VFP_OK : VFP_ERR;
    /* the quick study: fewer points, the core's own among them (14-bit codes, 14 fraction bits of shade, 8- and
     * 16-bit tables) */
    static const unsigned normal_bits[] = {8, 10, 12, 14, 16}, shade_bits[] = {4, 6, 8, 10, 12, 14, 16},
                          lit_bits[] = {4, 6, 8, 10, 12, 16};
    static const unsigned quick_shade[] = {4, 8, 14}, quick_lit[] = {4, 8, 16};
    for (size_t k = 0; status == VFP_OK && k < sizeof normal_bits / sizeof *normal_bits; k++) {
        if (quick && normal_bits[k] == 10)
            continue;
        vf_params_t p = def;
        p.normal_bits = normal_bits[k];
        char value[16];
        snprintf(value, sizeof value, "%u", normal_bits[k]);
        status = core_run(st, scene, &p, "normal_bits", value, unquantised, truth, err, errlen);
    }
    const unsigned *shades = quick ? quick_shade : shade_bits, *lits = quick ? quick_lit : lit_bits;
    const size_t n_shades = quick ? 3 : sizeof shade_bits / sizeof *shade_bits;
    const size_t n_lits = quick ? 3 : sizeof lit_bits / sizeof *lit_bits;
    for (size_t k = 0; status == VFP_OK && k < n_shades; k++)
        status = knob_run(st, scene, "shade_bits", shades[k], exact, err, errlen);
    for (size_t k = 0; status == VFP_OK && k < n_lits; k++)
        status = knob_run(st, scene, "lit_table_bits", lits[k], exact, err, errlen);
    /* the shade lookup against the truth (the core's reference for each is the exact-codes one of its mode) */
    for (int m = 0; status == VFP_OK && !quick && m < 2; m++)
        for (int lookup = 0; status == VFP_OK && lookup <= VF_LOOKUP_BILINEAR; lookup++) { /* nearest, bilinear */
            vf_params_t p = def;
            p.mode = m ? VF_MODE_PREINT1 : VF_MODE_POINT;
            p.shade_lookup = (vf_lookup_t)lookup;
            uint8_t *ref = reference_image(st, scene, &p, 0, 0, 0, err, errlen);
            char value[32];
            snprintf(value, sizeof value, "%s-%s", vf_mode_name(p.mode), vf_lookup_name(p.shade_lookup));
            status = ref ? core_run(st, scene, &p, "shade_lookup", value, ref, truth, err, errlen) : VFP_ERR;
            free(ref);
        }
    free(unquantised);
    free(exact);
    return status;
}

vfp_status_t study_lit(study_t *st, const char *data, char *err, size_t errlen)
{
    /* Marschner-Lobb always; in the full study the other sharp scenes of the lit acceptance (docs/algorithm.md,
     * "Lit truth"), when the shared volumes are there */
    int s = lit_scene(st, "ml41-sharp-lit", "phantom:marschner-lobb:41", 30, 20, 256, err, errlen);
    if (s < 0 || stages(st, s, err, errlen))
        return VFP_ERR;
    static const char *const shared[][2] = {{"neghip.nhdr", "neghip-sharp-lit"}, {"engine.nhdr", "engine-sharp-lit"},
                                            {"bucky.nhdr", "bucky-sharp-lit"}};
    for (size_t k = 0; !st->quick && k < sizeof shared / sizeof *shared; k++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", data, shared[k][0]);
        FILE *f = fopen(path, "r");
        if (!f)
            continue;
        fclose(f);
        s = lit_scene(st, shared[k][1], path, 30, 20, 256, err, errlen);
        if (s < 0 || stages(st, s, err, errlen))
            return VFP_ERR;
    }
    return VFP_OK;
}
