/* SPDX-License-Identifier: MIT */
/* fuzz_tf.c: a transfer-function file (vfp_tf_load, as x.tf), then what the programs do with one: map it through
 * the windows of an 8-bit and a 16-bit volume (vfp_tf_to_core), move it as the level and width knobs do
 * (vfp_tf_move), and hand the points to the core, which must accept them (vf_table_point), and build the lit
 * tables from them (vf_table_preint_lit): the 2D table vf_table_preint's to the bit, every front-weighted value
 * at most its entry's colour or opacity, every value at most 1.0; and a small order-2 table (vf_table_order2), lit
 * and not: the same entries either way and in two parts, mirrors of one opacity, every value at most 1.0, W_f + W_b
 * at most C and S_f' + S_b' at most a but for one LSB of rounding. */
#include "fuzz.h"
#include "io/tf.h"

#define TABLE_SIZE 32
#define TABLE2_SIZE 16

/* The order-2 table of the points (16^3 entries from a 32-entry 2D table), checked as the header says. */
static void order2(const vf_tf_t *tf, uint32_t slab_q16)
{
#if VF_ORDER2
    enum { VALUES = TABLE2_SIZE * TABLE2_SIZE * TABLE2_SIZE * 4 };
    static uint16_t whole[VALUES], halves[VALUES], lit_main[VALUES], lit[2 * VALUES];
    const bool lit_tables = VF_LIT_TABLES;
    const size_t bytes = vf_table2_scratch_bytes(TABLE_SIZE, lit_tables);
    void *scratch = malloc(bytes);
    vf_arena_t arena;
    vf_arena_init(&arena, scratch, bytes);
    if (!scratch || vf_table_order2(tf, TABLE_SIZE, TABLE2_SIZE, slab_q16, 0, 1, &arena, whole, NULL) != VF_OK ||
        vf_table_order2(tf, TABLE_SIZE, TABLE2_SIZE, slab_q16, 1, 2, &arena, halves, NULL) != VF_OK ||
        vf_table_order2(tf, TABLE_SIZE, TABLE2_SIZE, slab_q16, 0, 2, &arena, halves, NULL) != VF_OK ||
        memcmp(whole, halves, sizeof whole) != 0)
        abort();
    if (lit_tables && (vf_table_order2(tf, TABLE_SIZE, TABLE2_SIZE, slab_q16, 0, 1, &arena, lit_main, lit) != VF_OK ||
                       memcmp(whole, lit_main, sizeof whole) != 0))
        abort();
    for (uint32_t f = 0; f < TABLE2_SIZE; f++)
        for (uint32_t m = 0; m < TABLE2_SIZE; m++)
            for (uint32_t b = 0; b < TABLE2_SIZE; b++) {
                const size_t e = ((size_t)f * TABLE2_SIZE + m) * TABLE2_SIZE + b;
                const size_t mirror = ((size_t)b * TABLE2_SIZE + m) * TABLE2_SIZE + f;
                if (whole[e * 4 + 3] != whole[mirror * 4 + 3])
                    abort();
                for (int c = 0; c < 4; c++)
                    if (whole[e * 4 + c] > 32768 || (lit_tables && lit[e * 8 + c] + lit[e * 8 + 4 + c] >
                                                                       whole[e * 4 + (c < 3 ? c : 3)] + 1))
                        abort();
            }
    free(scratch);
#else
    (void)tf, (void)slab_q16;
#endif
}

/* The points for one volume and window, and the core's table from them. */
static void to_core(const vfp_tf_t *tf, const vfp_volume_t *vol, vf_window_t window)
{
    static vf_tf_point_t points[VF_MAX_TF_POINTS];
    uint32_t n = vfp_tf_to_core(tf, vol, window, points);
    if (n < 1 || n > VF_MAX_TF_POINTS)
        abort();
    vf_tf_t core_tf = {points, n};
    size_t bytes = vf_table_scratch_bytes(TABLE_SIZE);
    void *scratch = malloc(bytes);
    uint16_t table[TABLE_SIZE * 4];
    vf_arena_t arena;
    vf_arena_init(&arena, scratch, bytes);
    if (!scratch || vf_table_point(&core_tf, TABLE_SIZE, 65536, &arena, table) != VF_OK)
        abort();
#if VF_LIT_TABLES
    static uint16_t plain[TABLE_SIZE * TABLE_SIZE * 4], table2d[TABLE_SIZE * TABLE_SIZE * 4],
        lit[TABLE_SIZE * TABLE_SIZE * 4];
    const uint32_t slab_q16 = 40000 + (uint32_t)(n * 7919u % 200000u); /* a slab length that varies with the input */
    if (vf_table_preint(&core_tf, TABLE_SIZE, slab_q16, VF_BUILDER_INCREMENTAL, &arena, plain) != VF_OK ||
        vf_table_preint_lit(&core_tf, TABLE_SIZE, slab_q16, VF_BUILDER_INCREMENTAL, &arena, table2d, lit) != VF_OK ||
        memcmp(plain, table2d, sizeof plain) != 0)
        abort();
    for (size_t k = 0; k < sizeof lit / sizeof lit[0]; k++)
        if (lit[k] > table2d[k] || table2d[k] > 32768)
            abort();
#endif
    free(scratch);
    order2(&core_tf, 30000 + (uint32_t)(n * 104729u % 150000u));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_begin();
    const char *path = fz_write("x.tf", data, size);
    vfp_tf_t tf;
    char err[VFP_ERR_LEN];
    if (fz_refused(vfp_tf_load(&tf, path, err, sizeof err), err, path))
        return 0;
    /* An 8-bit volume with its full window; 16-bit CT with a NIfTI slope and intercept; and a negative slope,
     * whose window runs downwards. Only the type, slope and intercept matter here. */
    vfp_volume_t u8, ct, flipped;
    memset(&u8, 0, sizeof u8);
    u8.slope = 1;
    ct = u8;
    ct.core.type = VF_VOXEL_I16;
    ct.slope = 0.5;
    ct.inter = -1024;
    flipped = ct;
    flipped.slope = -2;
    to_core(&tf, &u8, (vf_window_t){0, 255});
    to_core(&tf, &ct, (vf_window_t){1800, 4400});
    to_core(&tf, &flipped, (vf_window_t){200, -300});
    vfp_tf_t moved = tf;
    vfp_tf_move(&moved, &ct, (vf_window_t){1800, 4400}, 0.25, 3);
    to_core(&moved, &ct, (vf_window_t){1800, 4400});
    return 0;
}
