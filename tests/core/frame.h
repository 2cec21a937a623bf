/* SPDX-License-Identifier: MIT */
/* frame.h: vf_renderer_begin with its options as arguments, for tests that begin many frames of a view and size. */
#ifndef TESTS_CORE_FRAME_H
#define TESTS_CORE_FRAME_H

#include <stddef.h>

#include "volfix.h"

/* view NULL passes a NULL frame, so that argument errors stay testable */
static inline vf_status_t begin_frame(vf_renderer_t *r, const vf_view_t *view, uint32_t w, uint32_t h,
                                      uint32_t table_parts, bool one_thread)
{
    if (!view)
        return vf_renderer_begin(r, NULL);
    const vf_frame_t frame = {.view = *view, .width = w, .height = h, .table_parts = table_parts,
                              .one_thread = one_thread};
    return vf_renderer_begin(r, &frame);
}

#endif
