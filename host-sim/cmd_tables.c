/* SPDX-License-Identifier: MIT */
/*
 * cmd_tables.c: volfix-sim tables: build a pre-integrated table with each builder (the core's O(N^2)
 * incremental one, its O(N^3) brute-force oracle), time them, measure them against the double reference
 * builder in LSB, and draw the table so a person can see it; with --lit, the same for the table with its
 * front-weighted values for lighting.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "options.h"
#include "io/numbers.h"
#include "io/pngio.h"
#include "ref/ref.h"
#include "render/render_mt.h"
#include "io/tf.h"

static const char usage[] =
    "usage: volfix-sim tables [--preset NAME | --tf FILE] [--size N] [--slab D] [--bits 8|16] [-o TABLE.png]\n"
    "                         [--json] [--repeat R] [--lit]\n"
    "       volfix-sim tables --order 2 ...   the order-2 (preint2) table: see volfix-sim tables --order 2 --help\n"
    "Build the pre-integrated table of a transfer function with the core's incremental O(N^2) builder (Lum et\n"
    "al. 2004) and with its brute-force O(N^3) oracle; print the build time of each (best of R runs) and the\n"
    "largest and mean difference from the double-precision reference builder, in LSB of the table format.\n\n"
    "  --preset NAME, --tf FILE   the transfer function (default: ramp); scalars 0..1 span the table\n"
    "  --size N             entries per axis, 2..1024 (default 256)\n"
    "  --slab D             slab length in voxels (default 1)\n"
    "  --bits B             16 (Q1.15, default) or 8 bits per value: the LSB the errors are counted in\n"
    "  --repeat R           time each builder R times and report the fastest (default 5; brute force at most 3)\n"
    "  -o FILE              draw the table: front entry across, back entry down, premultiplied colour on\n"
    "                       the left and opacity (grey) on the right\n"
    "  --lit                also build the table with its front-weighted values for lighting (D_f, S_f;\n"
    "                       docs/algorithm.md section 7) with each builder: their time beside the plain\n"
    "                       build's, the lit table's memory, and its values against the double reference's\n"
    "  --json               print one object: size, incremental_ms, bruteforce_ms, max_err_lsb, mean_err_lsb,\n"
    "                       and the same for the brute-force builder and between the two (with --lit also\n"
    "                       lit_incremental_ms, lit_bruteforce_ms, lit_max_err_lsb, lit_mean_err_lsb,\n"
    "                       lit_bruteforce_max_err_lsb, table_bytes, lit_table_bytes)\n";

typedef struct errors {
    double max, mean;
} errors_t;

/* Differences in LSB of a table with `bits` bits per value; 16-bit values are Q1.15. */
static errors_t against_double(const uint16_t *t, const double *ref, size_t entries, int bits)
{
    errors_t e = {0, 0};
    for (size_t i = 0; i < entries; i++)
        for (int c = 0; c < 4; c++) {
            double exact = ref[i * 4 + (c + 1) % 4]; /* the reference stores a, r, g, b; the core r, g, b, a */
            double got = t[i * 4 + c] / 32768.0, lsb = 1.0 / 32768;
            if (bits == 8) {
                got = floor(got * 255 + 0.5) / 255; /* what an 8-bit table holds */
                lsb = 1.0 / 255;
            }
            double d = fabs(got - exact) / lsb;
            e.max = d > e.max ? d : e.max;
            e.mean += d;
        }
    e.mean /= (double)entries * 4;
    return e;
}

static errors_t between(const uint16_t *a, const uint16_t *b, size_t entries)
{
    errors_t e = {0, 0};
    for (size_t i = 0; i < entries * 4; i++) {
        double d = abs((int)a[i] - (int)b[i]);
        e.max = d > e.max ? d : e.max;
        e.mean += d;
    }
    e.mean /= (double)entries * 4;
    return e;
}

/* The best of `repeat` builds; with lit_out, of the table and its front-weighted values together. */
static double build_ms(const vf_tf_t *tf, uint32_t n, uint32_t slab_q16, vf_builder_t builder, int repeat,
                       vf_arena_t *arena, uint16_t *out, uint16_t *lit_out, vf_status_t *status)
{
    double best = 1e30;
    for (int k = 0; k < repeat; k++) {
        double t0 = vfp_now_ms();
        *status = lit_out ? vf_table_preint_lit(tf, n, slab_q16, builder, arena, out, lit_out)
                          : vf_table_preint(tf, n, slab_q16, builder, arena, out);
        double ms = vfp_now_ms() - t0;
        best = ms < best ? ms : best;
    }
    return best;
}

/* front across, back down; colour left, opacity right */
static vfp_status_t draw(const char *path, const uint16_t *t, uint32_t n, char *err, size_t errlen)
{
    uint8_t *rgb = calloc((size_t)n * 2 * n, 3);
    if (!rgb) {
        snprintf(err, errlen, "out of memory");
        return VFP_ERR;
    }
    for (uint32_t back = 0; back < n; back++)
        for (uint32_t front = 0; front < n; front++) {
            const uint16_t *e = t + ((size_t)front * n + back) * 4;
            uint8_t *left = rgb + ((size_t)back * 2 * n + front) * 3, *right = left + (size_t)n * 3;
            for (int c = 0; c < 3; c++) {
                left[c] = (uint8_t)((e[c] * 255u + 16384u) >> 15);
                right[c] = (uint8_t)((e[3] * 255u + 16384u) >> 15);
            }
        }
    vfp_status_t status = vfp_png_write_rgb(path, rgb, 2 * n, n, err, errlen);
    free(rgb);
    return status;
}

int sim_cmd_tables(int argc, char **argv)
{
    /* --order 2: the order-2 table, its own command (cmd_tables2.c), given the other arguments; --order 1: this */
    for (int i = 0; i + 1 < argc; i++)
        if (strcmp(argv[i], "--order") == 0) {
            if (strcmp(argv[i + 1], "1") != 0 && strcmp(argv[i + 1], "2") != 0) {
                fprintf(stderr, "volfix-sim tables: --order %s: expected 1 or 2\n", argv[i + 1]);
                return VFP_EXIT_ERR;
            }
            const int order2 = argv[i + 1][0] == '2';
            for (int k = i; k + 2 < argc; k++)
                argv[k] = argv[k + 2];
            argc -= 2;
            if (order2)
                return sim_cmd_tables_order2(argc, argv);
            break;
        }
    const char *preset = NULL, *tf_file = NULL, *out = NULL;
    long n = 256, bits = 16, repeat = 5;
    double slab = 1.0;
    int json = 0, lit = 0;
    char err[VFP_ERR_LEN];
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        long long k;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return VFP_EXIT_OK;
        } else if (strcmp(a, "--json") == 0) {
            json = 1;
            continue;
        } else if (strcmp(a, "--lit") == 0) {
            lit = 1;
            continue;
        } else if (!v) {
            fprintf(stderr, "volfix-sim tables: %s: unknown option or missing value (see --help)\n", a);
            return VFP_EXIT_ERR;
        } else if (vfp_is_empty(v)) {
            fprintf(stderr, "volfix-sim tables: %s '': an empty value (expected a value; see --help)\n", a);
            return VFP_EXIT_ERR;
        } else if (strcmp(a, "--preset") == 0) {
            preset = v;
        } else if (strcmp(a, "--tf") == 0) {
            tf_file = v;
        } else if (strcmp(a, "-o") == 0) {
            out = v;
        } else if (strcmp(a, "--size") == 0) {
            if (!vfp_parse_integer(v, VF_MIN_TABLE, VF_MAX_TABLE, &k)) {
                fprintf(stderr, "volfix-sim tables: --size %s: expected an integer from 2 to 1024\n", v);
                return VFP_EXIT_ERR;
            }
            n = (long)k;
        } else if (strcmp(a, "--bits") == 0) {
            if (!vfp_parse_integer(v, 8, 16, &k) || (k != 8 && k != 16)) {
                fprintf(stderr, "volfix-sim tables: --bits %s: expected 8 or 16\n", v);
                return VFP_EXIT_ERR;
            }
            bits = (long)k;
        } else if (strcmp(a, "--repeat") == 0) {
            if (!vfp_parse_integer(v, 1, 1000, &k)) {
                fprintf(stderr, "volfix-sim tables: --repeat %s: expected an integer 1..1000\n", v);
                return VFP_EXIT_ERR;
            }
            repeat = (long)k;
        } else if (strcmp(a, "--slab") == 0) {
            if (!vfp_parse_number(v, 1.0 / 64, 128, &slab)) {
                fprintf(stderr, "volfix-sim tables: --slab %s: expected a length in voxels, 1/64..128\n", v);
                return VFP_EXIT_ERR;
            }
        } else {
            fprintf(stderr, "volfix-sim tables: %s: unknown option (see --help)\n", a);
            return VFP_EXIT_ERR;
        }
        i++;
    }
    if (out && (strcmp(out, "-") == 0 || vfp_png_check_output(out, err, sizeof err))) {
        fprintf(stderr, "volfix-sim tables: -o %s\n", strcmp(out, "-") == 0 ? "-: expected a file name (the report "
                        "is on standard output)" : err);
        return VFP_EXIT_ERR;
    }
    vfp_tf_t check;
    if (preset && vfp_tf_preset(&check, preset, err, sizeof err)) {
        fprintf(stderr, "volfix-sim tables: --preset %s: %s\n", preset, err);
        return VFP_EXIT_ERR;
    }
    if (preset && tf_file) {
        fprintf(stderr, "volfix-sim tables: give --preset or --tf, not both\n");
        return VFP_EXIT_ERR;
    }
    vfp_tf_t tf;
    if (tf_file ? vfp_tf_load(&tf, tf_file, err, sizeof err)
                : vfp_tf_preset(&tf, preset ? preset : "ramp", err, sizeof err)) {
        fprintf(stderr, "volfix-sim: %s\n", err);
        return VFP_EXIT_ERR;
    }
    vf_tf_point_t points[VF_MAX_TF_POINTS];
    vf_window_t whole = {0, 255};
    uint32_t count = vfp_tf_to_core(&tf, NULL, whole, points);
    vf_tf_t core_tf = {points, count};
    uint32_t slab_q16 = (uint32_t)lround(slab * 65536);

    const size_t entries = (size_t)n * (size_t)n;
    size_t scratch_bytes = vf_table_scratch_bytes((uint32_t)n);
    void *scratch = malloc(scratch_bytes);
    uint16_t *fast = malloc(entries * 8), *slow = malloc(entries * 8);
    uint16_t *fast_lit = lit ? malloc(entries * 8) : NULL, *slow_lit = lit ? malloc(entries * 8) : NULL;
    double *ref = malloc(entries * 4 * sizeof(double)), *ref_lit = lit ? malloc(entries * 4 * sizeof(double)) : NULL;
    ref_tf_point_t ref_tf[VF_MAX_TF_POINTS];
    vfp_status_t status = VFP_ERR;
    if (!scratch || !fast || !slow || !ref || (lit && (!fast_lit || !slow_lit || !ref_lit))) {
        fprintf(stderr, "volfix-sim: out of memory for %ldx%ld tables\n", n, n);
        goto done;
    }
    vf_arena_t arena;
    vf_arena_init(&arena, scratch, scratch_bytes);
    vf_status_t s1 = VF_OK, s2 = VF_OK, s3 = VF_OK, s4 = VF_OK; /* build_ms runs at least once */
    const int slow_repeat = repeat < 3 ? (int)repeat : 3;
    double fast_ms = build_ms(&core_tf, (uint32_t)n, slab_q16, VF_BUILDER_INCREMENTAL, (int)repeat, &arena, fast,
                              NULL, &s1);
    double slow_ms = build_ms(&core_tf, (uint32_t)n, slab_q16, VF_BUILDER_BRUTEFORCE, slow_repeat, &arena, slow, NULL,
                              &s2);
    double fast_lit_ms = 0, slow_lit_ms = 0;
    if (lit) { /* into other tables: the plain ones stay what vf_table_preint built */
        uint16_t *plain = malloc(entries * 8);
        if (!plain) {
            fprintf(stderr, "volfix-sim: out of memory for %ldx%ld tables\n", n, n);
            goto done;
        }
        fast_lit_ms = build_ms(&core_tf, (uint32_t)n, slab_q16, VF_BUILDER_INCREMENTAL, (int)repeat, &arena, plain,
                               fast_lit, &s3);
        slow_lit_ms = build_ms(&core_tf, (uint32_t)n, slab_q16, VF_BUILDER_BRUTEFORCE, slow_repeat, &arena, plain,
                               slow_lit, &s4);
        free(plain);
    }
    if (s1 != VF_OK || s2 != VF_OK || s3 != VF_OK || s4 != VF_OK) {
        const vf_status_t bad = s1 != VF_OK ? s1 : s2 != VF_OK ? s2 : s3 != VF_OK ? s3 : s4;
        fprintf(stderr, "volfix-sim: cannot build the table: %s\n", vf_status_text(bad));
        goto done;
    }
    for (uint32_t i = 0; i < count; i++)
        ref_tf[i] = (ref_tf_point_t){points[i].scalar_q8 / 256.0, points[i].r / 65535.0, points[i].g / 65535.0,
                                     points[i].b / 65535.0, points[i].a / 65535.0};
    double t0 = vfp_now_ms();
    if (ref_preint_table(ref_tf, (int)count, (int)n, slab_q16 / 65536.0, ref)) {
        fprintf(stderr, "volfix-sim: the reference builder failed\n");
        goto done;
    }
    double ref_ms = vfp_now_ms() - t0;
    if (lit && ref_lit_table(ref_tf, (int)count, (int)n, slab_q16 / 65536.0, ref_lit)) {
        fprintf(stderr, "volfix-sim: the reference's front-weighted builder failed\n");
        goto done;
    }
    errors_t ef = against_double(fast, ref, entries, (int)bits), es = against_double(slow, ref, entries, (int)bits);
    errors_t eb = between(fast, slow, entries);
    /* the reference's lit values are S_f, D_f r, g, b where its table has a, r, g, b: against_double pairs them */
    errors_t lf = {0, 0}, ls = {0, 0};
    if (lit) {
        lf = against_double(fast_lit, ref_lit, entries, (int)bits);
        ls = against_double(slow_lit, ref_lit, entries, (int)bits);
    }
    /* bytes of each table in the renderer: 4 values an entry, Q1.15 or 8 bits (as core/renderer.c keeps them) */
    const size_t table_bytes = entries * 4 * (bits == 8 ? 1 : 2);
    if (json) {
        printf("{\"size\": %ld, \"preset\": \"%s\", \"slab\": %g, \"bits\": %ld, \"incremental_ms\": %.4f, "
               "\"bruteforce_ms\": %.4f, \"speedup\": %.1f, \"reference_ms\": %.2f, \"max_err_lsb\": %.3f, "
               "\"mean_err_lsb\": %.4f, \"bruteforce_max_err_lsb\": %.3f, \"bruteforce_mean_err_lsb\": %.4f, "
               "\"incremental_vs_bruteforce_max_lsb\": %.0f",
               n, tf.name, slab, bits, fast_ms, slow_ms, slow_ms / fast_ms, ref_ms, ef.max, ef.mean, es.max, es.mean,
               eb.max);
        if (lit)
            printf(", \"lit_incremental_ms\": %.4f, \"lit_bruteforce_ms\": %.4f, \"lit_max_err_lsb\": %.3f, "
                   "\"lit_mean_err_lsb\": %.4f, \"lit_bruteforce_max_err_lsb\": %.3f, \"table_bytes\": %zu, "
                   "\"lit_table_bytes\": %zu",
                   fast_lit_ms, slow_lit_ms, lf.max, lf.mean, ls.max, table_bytes, table_bytes);
        printf("}\n");
    } else {
        printf("pre-integrated table, %s, %ldx%ld entries, slab %g voxels, errors in LSB of %ld-bit values\n",
               tf.name, n, n, slab, bits);
        printf("  incremental O(N^2): %9.3f ms   against double: max %.3f, mean %.4f LSB\n", fast_ms, ef.max, ef.mean);
        printf("  brute force O(N^3): %9.3f ms   against double: max %.3f, mean %.4f LSB\n", slow_ms, es.max, es.mean);
        printf("  incremental is %.1fx faster; the two differ by at most %.0f LSB of Q1.15\n", slow_ms / fast_ms,
               eb.max);
        if (lit) {
            printf("lit: with the front-weighted values D_f, S_f (%zu bytes beside the table's %zu)\n", table_bytes,
                   table_bytes);
            printf("  incremental O(N^2): %9.3f ms (%.1fx the plain build)   D_f, S_f against double: max %.3f, "
                   "mean %.4f LSB\n", fast_lit_ms, fast_lit_ms / fast_ms, lf.max, lf.mean);
            printf("  brute force O(N^3): %9.3f ms (%.1fx the plain build)   D_f, S_f against double: max %.3f, "
                   "mean %.4f LSB\n", slow_lit_ms, slow_lit_ms / slow_ms, ls.max, ls.mean);
        }
    }
    status = VFP_OK;
    if (out) {
        if (draw(out, fast, (uint32_t)n, err, sizeof err)) {
            fprintf(stderr, "volfix-sim: %s\n", err);
            status = VFP_ERR;
        } else if (!json) {
            printf("  drawn to %s: front entry across, back entry down; colour left, opacity right\n", out);
        }
    }
done:
    free(scratch);
    free(fast);
    free(slow);
    free(fast_lit);
    free(slow_lit);
    free(ref);
    free(ref_lit);
    return vfp_exit_status(status);
}
