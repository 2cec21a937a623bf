/* SPDX-License-Identifier: MIT */
/*
 * main.c: the volfix core on a Cortex-M4 (the MPS2 AN386 board, or qemu-system-arm -M mps2-an386).
 *
 * Renders the scene that gen_scene wrote into scene.h (an embedded volume, window, transfer function,
 * parameters and view, exactly as `volfix-sim render` takes them from the same options), composites it in
 * bands of SCENE_BAND_ROWS intermediate rows with one small scratch buffer, warps it into a frame, and prints
 * through semihosting:
 *
 *   hash H          FNV-1a 64 of the frame's pixel bytes, row by row: the same number as
 *                   `volfix-sim render ... --hash` (port/render/image.c vfp_image_hash)
 *   memory lines    the arena's high-water mark and what the renderer holds by part (vf_renderer_memory),
 *                   the band scratch, the frame and the stack a frame touched
 *   timer ticks     per stage, from the board's 25 MHz timer (under qemu -icount shift=0: instructions / 40)
 *
 * and exits with 0, or 2 (with the core's status text) when a call fails. All memory is static: the arena,
 * the scratch and the frame are sized at build time from the core's own size queries (gen_scene) and checked
 * here against the target's figures.
 */
#include <stddef.h>
#include <stdint.h>

#include "scene.h"
#include "semihost.h"
#include "startup.h"
#include "volfix.h"

/* The board's first CMSDK APB timer, a 32-bit down-counter at the 25 MHz peripheral clock (AN386; qemu's
 * SYSCLK_FRQ). On the board it measures time; under qemu -icount shift=0, where the virtual clock advances
 * one nanosecond per instruction, a tick is 40 instructions. Registers: control, value, reload. */
#define TIMER_CTRL (*(volatile uint32_t *)0x40000000u)
#define TIMER_VALUE (*(volatile uint32_t *)0x40000004u)
#define TIMER_RELOAD (*(volatile uint32_t *)0x40000008u)

/* The renderer's memory (vf_renderer_bytes and the run lists), one band's scratch (buffer slices and skip
 * links), and the frame. */
static unsigned char arena_buffer[SCENE_ARENA_BYTES] __attribute__((aligned(16)));
static unsigned char scratch[SCENE_SCRATCH_BYTES] __attribute__((aligned(16)));
static unsigned char frame[SCENE_HEIGHT * SCENE_WIDTH * SCENE_PIXEL_BYTES] __attribute__((aligned(4)));

static int failed(const char *what, vf_status_t status);
static void report(const char *label, size_t bytes, const char *after);
static uint64_t frame_hash(const vf_image_t *image);
static uint32_t ticks(void);
#if SCENE_PREBUILT
static size_t prebuilt_bytes(void);
#endif

int main(void)
{
    sh_puts("volfix on mps2-an386: " SCENE_ABOUT "\n");
    TIMER_RELOAD = 0xFFFFFFFFu;
    TIMER_VALUE = 0xFFFFFFFFu;
    TIMER_CTRL = 1u; /* enable, no interrupt */
    uint32_t t[6]; /* after create, window, transfer function, begin, composite, warp */

    vf_arena_t arena;
    vf_arena_init(&arena, arena_buffer, sizeof arena_buffer);
    vf_renderer_t *r = NULL;
#if SCENE_PREBUILT
    /* the slices, normals and run lists in read-only memory (gen_scene --prebuilt, scene_data.S) */
    vf_status_t s = vf_renderer_create_prebuilt(&r, &scene_params, &scene_volume, &scene_prebuilt, &arena);
    if (s != VF_OK)
        return failed("vf_renderer_create_prebuilt", s);
#else
    vf_status_t s = vf_renderer_create(&r, &scene_params, &scene_volume, &arena);
    if (s != VF_OK)
        return failed("vf_renderer_create", s);
#endif
    t[0] = ticks();
    if ((s = vf_renderer_set_window(r, scene_window)) != VF_OK)
        return failed("vf_renderer_set_window", s);
    t[1] = ticks();
    const vf_tf_t tf = {scene_tf_points, sizeof scene_tf_points / sizeof scene_tf_points[0]};
    if ((s = vf_renderer_set_tf(r, &tf)) != VF_OK) {
        if (s == VF_ERR_NOMEM)
            report("arena too small: ", vf_renderer_needed_bytes(r), " bytes needed\n");
        return failed("vf_renderer_set_tf", s);
    }
#if SCENE_LIGHTING
    /* a lit scene (a firmware whose core is built with VF_LIGHTING=1): its lights and material, per frame */
    if ((s = vf_renderer_set_lighting(r, &scene_lighting)) != VF_OK)
        return failed("vf_renderer_set_lighting", s);
#endif
    t[2] = ticks();

    /* One frame, as vf_renderer_draw does it but in bands: the scratch then holds SCENE_BAND_ROWS rows, not the whole
     * intermediate image's, and bands give the same pixels as one pass (they are what threads share). */
    const vf_image_t image = {frame, SCENE_WIDTH, SCENE_HEIGHT, SCENE_WIDTH * SCENE_PIXEL_BYTES, SCENE_FORMAT};
    const vf_frame_t frame_options = {.view = scene_view, .width = SCENE_WIDTH, .height = SCENE_HEIGHT};
    if ((s = vf_renderer_begin(r, &frame_options)) != VF_OK)
        return failed("vf_renderer_begin", s);
    t[3] = ticks();
    const uint32_t int_h = vf_renderer_factor(r)->int_h;
    for (uint32_t v0 = 0; v0 < int_h; v0 += SCENE_BAND_ROWS) {
        const uint32_t v1 = int_h - v0 < SCENE_BAND_ROWS ? int_h : v0 + SCENE_BAND_ROWS;
        if ((s = vf_renderer_composite_band(r, v0, v1, scratch, sizeof scratch)) != VF_OK)
            return failed("vf_renderer_composite_band", s);
    }
    t[4] = ticks();
    if ((s = vf_renderer_warp_band(r, &image, 0, SCENE_HEIGHT)) != VF_OK)
        return failed("vf_renderer_warp_band", s);
    t[5] = ticks();

    sh_puts("hash ");
    sh_puthex64(frame_hash(&image));
    sh_puts("\n");

    vf_memory_t m;
    vf_renderer_memory(r, &m);
    report("arena: peak ", arena.peak, " bytes");
    report(" of ", arena.size, " (renderer ");
    report("", m.renderer, ", slices ");
    report("", m.slices, ", runs ");
    report("", m.runs, ", classify ");
    report("", m.classify, ", tables ");
    report("", m.tables, ", intermediate ");
    report("", m.intermediate, "");
    if (m.normals) /* lighting: normal codes and gradient magnitudes per principal axis, the shade table */
        report(", normals ", m.normals, "");
    if (m.order2) /* preint2's 3D table and its pieces */
        report(", order2 ", m.order2, "");
    sh_puts(")\n");
    report("band scratch: ", vf_renderer_band_scratch_bytes(r, SCENE_BAND_ROWS), " bytes for ");
    report("", SCENE_BAND_ROWS, " rows (buffer slices and skip links; ");
    report("", vf_renderer_band_scratch_bytes(r, int_h), " for all ");
    report("", int_h, " rows at once)\n");
    report("frame: ", sizeof frame, " bytes\n");
#if SCENE_PREBUILT
    report("prebuilt in read-only memory: ", prebuilt_bytes(), " bytes; a new transfer function's run lists (this one's: ");
    report("", SCENE_RUNS_BYTES, ") are encoded in the arena\n");
#endif
    report("stack: ", startup_stack_used(), " bytes used");
    report(" of ", startup_stack_size(), "\n");
    report("timer ticks (25 MHz): window ", t[1] - t[0], ", transfer function ");
    report("", t[2] - t[1], ", begin ");
    report("", t[3] - t[2], ", composite ");
    report("", t[4] - t[3], ", warp ");
    report("", t[5] - t[4], "\n");
    return 0;
}

static int failed(const char *what, vf_status_t status)
{
    sh_puts(what);
    sh_puts(": ");
    sh_puts(vf_status_text(status));
    sh_puts("\n");
    return 2;
}

static void report(const char *label, size_t bytes, const char *after)
{
    sh_puts(label);
    sh_putu((uint32_t)bytes);
    sh_puts(after);
}

#if SCENE_PREBUILT
/* The prebuilt arrays' bytes, as scene_prebuilt counts them. */
static size_t prebuilt_bytes(void)
{
    const vf_prebuilt_t *p = &scene_prebuilt;
    size_t bytes = sizeof(uint16_t) * 256 + sizeof(int32_t) * p->unit_count;
    for (int a = 0; a < 3; a++)
        bytes += p->slice_count[a] * (p->codes[a] ? 4 : 1) + sizeof(uint32_t) * p->row_count[a] +
                 sizeof(uint16_t) * p->pair_count[a];
    return bytes;
}
#endif

static uint32_t ticks(void)
{
    return 0xFFFFFFFFu - TIMER_VALUE;
}

/* FNV-1a 64 over the pixel bytes, row by row: port/render/image.c's vfp_image_hash. */
static uint64_t frame_hash(const vf_image_t *image)
{
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    const size_t row_bytes = (size_t)image->width * vf_format_bytes(image->format);
    for (uint32_t y = 0; y < image->height; y++) {
        const unsigned char *row = (const unsigned char *)image->pixels + (size_t)y * image->stride;
        for (size_t i = 0; i < row_bytes; i++) {
            h ^= row[i];
            h *= UINT64_C(0x100000001b3);
        }
    }
    return h;
}
