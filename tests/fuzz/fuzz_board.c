/* SPDX-License-Identifier: MIT */
/* fuzz_board.c: a board file, read as the viewer reads x.board (vfp_board_load). */
#include "board/board.h"
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    const char *path = fz_write("x.board", data, size);
    vfp_board_t board;
    char err[VFP_ERR_LEN];
    if (fz_refused(vfp_board_load(&board, path, err, sizeof err), err, path))
        return 0;
    /* What the viewer relies on once a board is read. */
    if (board.knob_count < 0 || board.knob_count > VFP_MAX_KNOBS || board.button_count < 0 ||
        board.button_count > VFP_MAX_BUTTONS || !board.display[0] || !board.input[0] || board.threads < 1)
        abort();
    for (int i = 0; i < board.knob_count; i++)
        if (board.knobs[i].action < VFP_ACT_AZIMUTH || board.knobs[i].action > VFP_ACT_WIDTH)
            abort();
    for (int i = 0; i < board.button_count; i++)
        if (board.buttons[i].action < VFP_ACT_NEXT_PRESET || board.buttons[i].action >= VFP_ACT_COUNT)
            abort();
    return 0;
}
