/* SPDX-License-Identifier: MIT */
/*
 * vf_config.h: every build-time setting of the core in one place (as Lua's luaconf.h). Each has a default that
 * a build may override with -D.
 */
#ifndef VF_CONFIG_H
#define VF_CONFIG_H

/* Largest volume dimension along any axis. Run lengths and buffer tags are 16-bit, so at most 65535. */
#ifndef VF_MAX_DIM
#define VF_MAX_DIM 4096
#endif

/* Table sizes a renderer accepts, and the default. */
#ifndef VF_MIN_TABLE
#define VF_MIN_TABLE 2
#endif
#ifndef VF_MAX_TABLE
#define VF_MAX_TABLE 1024
#endif
#ifndef VF_DEFAULT_TABLE
#define VF_DEFAULT_TABLE 256
#endif

/* Most parts a frame's pre-integrated table can be built in side by side (vf_frame_t.table_parts); 1 for a
 * single-core build, whose begin always builds the whole table. */
#ifndef VF_MAX_TABLE_PARTS
#define VF_MAX_TABLE_PARTS 64
#endif

/* Most parts a transfer function's run-length encoding can be left in (vf_renderer_set_tf_begin: each principal
 * axis's slabs in ranges, a part a range of an axis); below 6 (a single-core build: VF_MAX_TABLE_PARTS 1) begin always
 * encodes the whole, and the parts' code and state are left out. */
#ifndef VF_MAX_ENCODE_PARTS
#define VF_MAX_ENCODE_PARTS (VF_MAX_TABLE_PARTS > 1 ? 48 : 1)
#endif

/* View tables: with the lut correction and nearest lookup in a 16-bit table, the lut is applied to every table
 * entry once a view rather than to every segment a frame (the same pixels for a fraction of the work, and a second
 * table's memory). 0 leaves them out (about 400 bytes of Cortex-M4 code), and the lut corrects each segment. */
#ifndef VF_VIEW_TABLE
#define VF_VIEW_TABLE 1
#endif

/* Tables built as they are read: a frame composited on one thread (vf_frame_t.one_thread) in the default
 * preint1 path builds only the blocks of the 2D table's diagonals its segments use. 0 leaves it out (one_thread then changes nothing). */
#ifndef VF_TABLE_ON_DEMAND
#define VF_TABLE_ON_DEMAND 1
#endif

/* The brute-force O(N^3) table builder, the incremental builder's test oracle (vf_table_preint with
 * VF_BUILDER_BRUTEFORCE, about 500 bytes of Cortex-M4 code): 0 leaves it out, and asking for it gives
 * VF_ERR_UNSUPPORTED. Renderers never use it. */
#ifndef VF_TABLE_ORACLE
#define VF_TABLE_ORACLE 1
#endif

/* The front-weighted (lit) tables of interpolated pre-integrated lighting (docs/algorithm.md section 7; tables.h,
 * vfi_table_out_t.lit_q15 and lit_u8; vf_table_preint_lit), about 4.8 KB of Cortex-M4 code as linked: 0 leaves
 * them out, the builders then never write lit outputs and vf_table_preint_lit gives VF_ERR_UNSUPPORTED. */
#ifndef VF_LIT_TABLES
#define VF_LIT_TABLES VF_LIGHTING /* the builds that light frames */
#endif

/* Renderers over prebuilt storage (vf_renderer_create_prebuilt: slices, normals and run lists made on a host and
 * kept in a device's read-only memory): 0 leaves the entry's checks and paths out (VF_ERR_UNSUPPORTED). */
#ifndef VF_PREBUILT
#define VF_PREBUILT 1
#endif

/* The core's own builders of the slices and normals from a volume (vf_renderer_create, set_window): 0 leaves them
 * out of a firmware whose renderers all take prebuilt storage (vf_renderer_create then gives VF_ERR_UNSUPPORTED). */
#ifndef VF_BUILD_SLICES
#define VF_BUILD_SLICES 1
#endif

/* Loops specialised for cases that the general ones also render, to the bit, for speed alone: point's loop of the
 * default path for table sizes other than 256 (engine's point frame at 128 entries: 64.7 M instructions, 86.0 M
 * with the general loop; callgrind, make bench's count), and the 2D table builder's block for grey transfer
 * functions (preint.c, block_dense_grey), and preint1's 256-entry rounding folded into its lerps (composite_order1.c,
 * plain_entry). 0 leaves them out (Cortex-M4 code: about 120 bytes for the loop, 226
 * for the block, `make mcu MCU_FEATURES=`). */
#ifndef VF_SPECIAL_LOOPS
#define VF_SPECIAL_LOOPS 1
#endif

/* Bricks for the run encoder (runs.h): each 8x8x8 block of cells keeps its scalar range (2 bytes per 512 cells,
 * made per window), so that a transfer-function change settles whole empty and solid blocks without reading their
 * cells; the same run lists either way. 0 leaves them out (about 1 KB of Cortex-M4 code, and their memory), and
 * the encoder reads every cell. By default with the special loops, which the microcontroller leaves out too. */
#ifndef VF_RUN_BRICKS
#define VF_RUN_BRICKS VF_SPECIAL_LOOPS
#endif

/* The point and preint1 loops of the default path look each pixel's table entry up one open pixel ahead of its
 * blend (composite_order0.c, composite_order1.c), so that on a core that runs ahead the branches on the entry do
 * not wait for its load. 0: each entry looked up just before its blend, for cores without caches or out-of-order
 * execution (the microcontroller's: see the Makefile's MCU_FEATURES). The same frames either way. */
#ifndef VF_LOOK_AHEAD
#define VF_LOOK_AHEAD 1
#endif

/* Lighting (docs/algorithm.md, section 7): normals, shade tables, lit compositing and the front-weighted
 * pre-integrated table. 0 leaves it out, and a renderer asked for it gets VF_ERR_UNSUPPORTED. */
#ifndef VF_LIGHTING
#define VF_LIGHTING 1
#endif

/* Order 2 (docs/algorithm.md section 8, mode preint2): the 3D table of second-order pre-integration, built from
 * first-order pieces (preint2.c), and its compositing loop (composite_order2.c). 0 leaves it out, and a renderer
 * asked for preint2 gets VF_ERR_UNSUPPORTED. */
#ifndef VF_ORDER2
#define VF_ORDER2 1
#endif

/* Order-2 table sizes a renderer accepts (entries a side of the N2^3 table, vf_params_t.table2_size), and the
 * default. */
#ifndef VF_MIN_TABLE2
#define VF_MIN_TABLE2 16
#endif
#ifndef VF_MAX_TABLE2
#define VF_MAX_TABLE2 128
#endif
#ifndef VF_DEFAULT_TABLE2
#define VF_DEFAULT_TABLE2 64
#endif

/* Most control points in a transfer function. */
#ifndef VF_MAX_TF_POINTS
#define VF_MAX_TF_POINTS 1024
#endif

/* Largest ratio of the largest to the smallest voxel spacing. */
#ifndef VF_MAX_ANISOTROPY
#define VF_MAX_ANISOTROPY 64
#endif

/* Most rays per voxel column (vf_params_t.rays: 1, 2, 4, 8 or 16; a build for a microcontroller may keep only
 * 1, which drops the per-pixel sample positions), and the largest side of an intermediate image: skip links
 * and run positions are 16-bit. A renderer asked for more rays than the build has gets VF_ERR_UNSUPPORTED. */
#ifndef VF_MAX_RAYS
#define VF_MAX_RAYS 16
#endif

/* Partial slabs at the volume's side faces (vf_params_t.partial_slabs, composite_partial.c, about 3.5 KB of
 * Cortex-M4 code): 0 leaves them out, and a renderer asked for them gets VF_ERR_UNSUPPORTED. */
#ifndef VF_PARTIAL_SLABS
#define VF_PARTIAL_SLABS 1
#endif
#ifndef VF_MAX_INTERMEDIATE
#define VF_MAX_INTERMEDIATE 65535
#endif

/* Largest output image side. */
#ifndef VF_MAX_IMAGE
#define VF_MAX_IMAGE 8192
#endif

/* The hot compositing loops are written once and specialised by calling a static inline body with constant
 * arguments from small wrappers. Compilers that know the attribute are told to inline such a body always: GCC's
 * own heuristics leave a 40-line body out of line, and then test the constants per pixel. A build for size (-Os,
 * as the microcontroller's) keeps one copy instead. */
#ifndef VF_ALWAYS_INLINE
#if (defined(__GNUC__) || defined(__clang__)) && !defined(__OPTIMIZE_SIZE__)
#define VF_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define VF_ALWAYS_INLINE inline
#endif
#endif
/* And a wrapper whose loop should have the registers to itself is kept out of its caller. */
#ifndef VF_NOINLINE
#if defined(__GNUC__) || defined(__clang__)
#define VF_NOINLINE __attribute__((noinline))
#else
#define VF_NOINLINE
#endif
#endif

#endif /* VF_CONFIG_H */
