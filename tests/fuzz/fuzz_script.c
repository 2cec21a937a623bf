/* SPDX-License-Identifier: MIT */
/* fuzz_script.c: an input script (input = script), opened from a file as the viewer opens x.script for a board
 * with four knobs and two buttons (as boards/host-headless.board), then from a string (vfp_script_load_string)
 * with no board (any of VFP_MAX_KNOBS knobs and VFP_MAX_BUTTONS buttons); the events are read to the end and must
 * be what the script's checks promise. */
#include "board/board.h"
#include "fuzz.h"
#include "input/input.h"
#include "input/input_backends.h"

/* Reads every event: in time order, each naming a control of the board, a turn a non-zero number of detents. */
static void drain(vfp_input_t *in, int knobs, int buttons)
{
    vfp_event_t events[16];
    char err[VFP_ERR_LEN];
    uint64_t last = 0;
    int n;
    fz_show(NULL);
    while ((n = in->ops->read(in, events, 16, UINT64_MAX, err, sizeof err)) > 0)
        for (int i = 0; i < n; i++) {
            const vfp_event_t *e = &events[i];
            int controls = e->type == VFP_EV_TURN ? knobs : buttons;
            if (e->time_ns < last || (e->type != VFP_EV_QUIT && (e->control < 0 || e->control >= controls)) ||
                (e->type == VFP_EV_TURN && (e->steps == 0 || e->steps < -1000 || e->steps > 1000)))
                abort();
            last = e->time_ns;
        }
    if (n < 0 || in->ops->deadline_ns(in) != 0)
        abort();
    in->ops->close(in);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    const char *path = fz_write("x.script", data, size);
    vfp_board_t board;
    memset(&board, 0, sizeof board);
    board.knob_count = 4;
    board.button_count = 2;
    vfp_input_t in;
    char err[VFP_ERR_LEN];
    if (!fz_refused(vfp_input_script_ops.open(&in, &board, path, err, sizeof err), err, path))
        drain(&in, board.knob_count, board.button_count);

    if (memchr(data, 0, size))
        return 0; /* a string ends at its NUL; the file's NUL was the file reader's to refuse */
    char *text = malloc(size + 1);
    if (!text)
        abort();
    memcpy(text, data, size);
    text[size] = 0;
    if (!fz_refused(vfp_script_load_string(&in, NULL, text, "s.script", 1000, err, sizeof err), err, "s.script"))
        drain(&in, VFP_MAX_KNOBS, VFP_MAX_BUTTONS);
    free(text);
    return 0;
}
