/* SPDX-License-Identifier: MIT */
/*
 * prebuilt.c: renderers over prebuilt storage (volfix.h, vf_prebuilt_t): what a renderer exports for a host to
 * write into a device's read-only memory, the checks a renderer made over it passes first, and the adoption of its
 * run lists. renderer.c creates such renderers (vf_renderer_create_prebuilt) and leaves their builders alone.
 */
#include "arena.h"
#include "renderer.h"

vf_status_t vf_renderer_export(const vf_renderer_t *r, vf_prebuilt_t *pre)
{
    if (!r || !pre)
        return VF_ERR_NULL;
    if (!r->have_window || !r->have_tf || !r->have_runs)
        return VF_ERR_STATE;
    vfi_zero(pre, sizeof *pre);
    pre->window = r->window;
    for (int a = 0; a < 3; a++) {
        const vfi_layout_t *l = &r->layout[a];
        pre->slices[a] = r->slices[a];
        pre->slice_count[a] = vfi_slices_bytes(r->volume.dims, a);
        pre->row_start[a] = r->runs[a].row_start;
        pre->row_count[a] = (size_t)(l->nk - 1) * l->nj + 1;
        pre->pairs[a] = r->runs[a].pairs;
        pre->pair_count[a] = r->runs[a].row_start[pre->row_count[a] - 1];
#if VF_LIGHTING
        if (r->params.lighting) {
            pre->codes[a] = r->codes[a];
            pre->magnitudes[a] = r->magnitudes[a];
        }
#endif
    }
#if VF_LIGHTING
    if (r->params.lighting) {
        pre->unit = r->unit;
        pre->unit_count = 3 * (size_t)r->code_count;
    }
#endif
    pre->visible_from = r->cls.visible_from;
    return VF_OK;
}

/* Prebuilt storage fits these parameters and this volume: every array there and of its size (the lighting's
 * exactly when the parameters light, the run lists' when visible_from is given), the run lists whole. */
vf_status_t vfi_prebuilt_check(const vf_params_t *p, const vf_volume_t *vol, const vf_prebuilt_t *pre)
{
    if (pre->window.lo == pre->window.hi)
        return VF_ERR_WINDOW;
    const bool lit = VF_LIGHTING && p->lighting, runs = pre->visible_from != NULL;
    for (int a = 0; a < 3; a++) {
        vfi_layout_t l;
        vfi_layout(vol->dims, a, &l);
        if (!pre->slices[a] || (lit && (!pre->codes[a] || !pre->magnitudes[a])) ||
            (runs && (!pre->row_start[a] || !pre->pairs[a])))
            return VF_ERR_NULL;
        if (pre->slice_count[a] != vfi_slices_bytes(vol->dims, a) || (!lit && (pre->codes[a] || pre->magnitudes[a])) ||
            (runs && !vfi_runs_valid(pre->row_start[a], pre->row_count[a], pre->pairs[a], pre->pair_count[a], &l)))
            return VF_ERR_ARG;
    }
    if (lit && !pre->unit)
        return VF_ERR_NULL;
    if (lit ? pre->unit_count != 3 * (size_t)vfi_normal_code_count(vfi_normal_levels(p->normal_bits)) : pre->unit != NULL)
        return VF_ERR_ARG;
    return VF_OK;
}

bool vfi_prebuilt_adopt_runs(vf_renderer_t *r)
{
    const vf_prebuilt_t *pre = r->storage;
    if (!pre->visible_from)
        return false;
    for (int v = 0; v < 256; v++)
        if (pre->visible_from[v] != r->cls.visible_from[v])
            return false;
    for (int a = 0; a < 3; a++) {
        r->runs[a].row_start = pre->row_start[a];
        r->runs[a].pairs = pre->pairs[a];
        r->runs[a].nj = r->layout[a].nj;
    }
    return true;
}
