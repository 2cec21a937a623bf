/* SPDX-License-Identifier: MIT */
/*
 * cmd_tables2.c: volfix-sim tables --order 2: build the order-2 table of a transfer function (docs/algorithm.md,
 * section 8) with the core, time it (the median of repeats, on one thread or in parts on several), give its
 * memory, and measure it against the double reference's build in LSB.
 */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "io/numbers.h"
#include "io/tf.h"
#include "ref/ref.h"
#include "render/render_mt.h"

static const char usage[] =
    "usage: volfix-sim tables --order 2 [--preset NAME | --tf FILE] [--size N2] [--table-size N] [--slab D]\n"
    "                         [--bits 8|16] [--lit] [--threads T] [--repeat R] [--json]\n"
    "Build the order-2 (preint2) table of a transfer function with the core: N2^3 entries, each the K = 16\n"
    "first-order pieces along the quadratic through its three scalars, composited (docs/algorithm.md,\n"
    "section 8). Print the build time (the median of R builds), the memory of the 3D table (and with --lit of its\n"
    "front- and back-weighted values) and of the Q.30 pieces it is built from, and the largest and mean\n"
    "difference of its values (and with --lit of its lighting values) from the double reference's build, in LSB of\n"
    "the table format.\n\n"
    "  --preset NAME, --tf FILE   the transfer function (default: ramp); scalars 0..1 span the table\n"
    "  --size N2            entries a side of the 3D table, 16..128 (default 64)\n"
    "  --table-size N       entries of the 2D table the pieces come from, 2..1024 (default 256)\n"
    "  --slab D             distance between slices in voxels, d: the table is for slabs of 2d (default 1)\n"
    "  --bits B             16 (Q1.15, default) or 8: the LSB the errors are counted in\n"
    "  --lit                also build the lighting values (W_f, W_b: eight values an entry more)\n"
    "  --threads T          build in T parts on T threads, each building its own pieces (default 1)\n"
    "  --repeat R           time R builds and report the median (default 5)\n"
    "  --json               print one object: size2, table_size, build_ms (median), build_ms_min, threads,\n"
    "                       table_bytes, lit_bytes, pieces_bytes, max_err_lsb, mean_err_lsb, reference_ms, and\n"
    "                       with --lit lit_max_err_lsb, lit_mean_err_lsb\n";

typedef struct part_job {
    const vf_tf_t *tf;
    uint32_t n, n2, slab_q16, part, parts;
    uint16_t *out, *lit;
    void *scratch;
    size_t scratch_bytes;
    vf_status_t status;
} part_job_t;

static void *build_part(void *arg)
{
    part_job_t *j = arg;
    vf_arena_t arena;
    vf_arena_init(&arena, j->scratch, j->scratch_bytes);
    j->status = vf_table_order2(j->tf, j->n, j->n2, j->slab_q16, j->part, j->parts, &arena, j->out, j->lit);
    return NULL;
}

/* One build in `threads` parts, each on its own thread (the first on this one); its wall time in ms. */
static double build_once(part_job_t *jobs, int threads, vf_status_t *status)
{
    pthread_t tid[VFP_MAX_THREADS];
    const double t0 = vfp_now_ms();
    for (int t = 1; t < threads; t++)
        if (pthread_create(&tid[t], NULL, build_part, &jobs[t]) != 0)
            jobs[t].status = VF_ERR_NOMEM, tid[t] = 0;
    build_part(&jobs[0]);
    for (int t = 1; t < threads; t++)
        if (tid[t])
            pthread_join(tid[t], NULL);
    const double ms = vfp_now_ms() - t0;
    *status = VF_OK;
    for (int t = 0; t < threads; t++)
        if (jobs[t].status != VF_OK)
            *status = jobs[t].status;
    return ms;
}

/* The largest and mean difference of `values` values an entry (core r, g, b, a order) from the reference's (a, r,
 * g, b order, by groups of four), in LSB of `bits`-bit values (8: the Q1.15 value rounded to 8 bits). */
static void against(const uint16_t *core, const double *ref, size_t count, int bits, double *worst, double *mean)
{
    *worst = 0, *mean = 0;
    for (size_t k = 0; k < count; k++) {
        const double exact = ref[k - k % 4 + (k % 4 + 1) % 4];
        double got = core[k] / 32768.0, lsb = 1.0 / 32768;
        if (bits == 8) {
            got = floor(got * 255 + 0.5) / 255;
            lsb = 1.0 / 255;
        }
        const double d = fabs(got - exact) / lsb;
        *worst = d > *worst ? d : *worst;
        *mean += d;
    }
    *mean /= (double)count;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static int bad(const char *option, const char *value, const char *expected)
{
    fprintf(stderr, "volfix-sim tables: %s %s: expected %s\n", option, value ? value : "(missing)", expected);
    return VFP_EXIT_ERR;
}

int sim_cmd_tables_order2(int argc, char **argv)
{
    const char *preset = NULL, *tf_file = NULL;
    long long n2 = 64, n = 256, bits = 16, repeat = 5, threads = 1;
    double slab = 1.0;
    int json = 0, lit = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return VFP_EXIT_OK;
        } else if (strcmp(a, "--json") == 0 || strcmp(a, "--lit") == 0) {
            *(a[2] == 'j' ? &json : &lit) = 1;
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
        } else if (strcmp(a, "--size") == 0) {
            if (!vfp_parse_integer(v, VF_MIN_TABLE2, VF_MAX_TABLE2, &n2))
                return bad(a, v, "an integer from 16 to 128");
        } else if (strcmp(a, "--table-size") == 0) {
            if (!vfp_parse_integer(v, VF_MIN_TABLE, VF_MAX_TABLE, &n))
                return bad(a, v, "an integer from 2 to 1024");
        } else if (strcmp(a, "--bits") == 0) {
            if (!vfp_parse_integer(v, 8, 16, &bits) || (bits != 8 && bits != 16))
                return bad(a, v, "8 or 16");
        } else if (strcmp(a, "--repeat") == 0) {
            if (!vfp_parse_integer(v, 1, 1000, &repeat))
                return bad(a, v, "1..1000");
        } else if (strcmp(a, "--threads") == 0) {
            if (!vfp_parse_integer(v, 1, VFP_MAX_THREADS, &threads))
                return bad(a, v, "an integer from 1 to 16");
        } else if (strcmp(a, "--slab") == 0) {
            if (!vfp_parse_number(v, 1.0 / 64, 64, &slab))
                return bad(a, v, "a length in voxels, 1/64..64");
        } else {
            fprintf(stderr, "volfix-sim tables: %s: unknown option (see --help)\n", a);
            return VFP_EXIT_ERR;
        }
        i++;
    }
    if (preset && tf_file) {
        fprintf(stderr, "volfix-sim tables: give --preset or --tf, not both\n");
        return VFP_EXIT_ERR;
    }
    char err[VFP_ERR_LEN];
    vfp_tf_t tf;
    if (tf_file ? vfp_tf_load(&tf, tf_file, err, sizeof err)
                : vfp_tf_preset(&tf, preset ? preset : "ramp", err, sizeof err)) {
        fprintf(stderr, "volfix-sim: %s\n", err);
        return VFP_EXIT_ERR;
    }
    vf_tf_point_t points[VF_MAX_TF_POINTS];
    uint32_t count = vfp_tf_to_core(&tf, NULL, (vf_window_t){0, 255}, points);
    vf_tf_t core_tf = {points, count};
    const uint32_t slab_q16 = (uint32_t)lround(slab * 65536);

    const size_t entries = (size_t)n2 * n2 * n2, scratch_bytes = vf_table2_scratch_bytes((uint32_t)n, lit);
    uint16_t *table = malloc(entries * 8), *lit_table = lit ? malloc(entries * 16) : NULL;
    double *ref = malloc(entries * 4 * sizeof(double)), *times = malloc(sizeof(double) * (size_t)repeat);
    part_job_t jobs[VFP_MAX_THREADS];
    int status = VFP_EXIT_ERR, have_scratch = 1;
    for (int t = 0; t < threads; t++) {
        jobs[t] = (part_job_t){&core_tf, (uint32_t)n, (uint32_t)n2, slab_q16, (uint32_t)t, (uint32_t)threads, table,
                               lit_table, malloc(scratch_bytes), scratch_bytes, VF_OK};
        have_scratch = have_scratch && jobs[t].scratch;
    }
    if (!table || (lit && !lit_table) || !ref || !times || !have_scratch) {
        fprintf(stderr, "volfix-sim: out of memory for a %lld^3 order-2 table\n", n2);
        goto done;
    }
    vf_status_t s = VF_OK;
    for (long r = 0; r < repeat && s == VF_OK; r++)
        times[r] = build_once(jobs, (int)threads, &s);
    if (s != VF_OK) {
        fprintf(stderr, "volfix-sim: cannot build the order-2 table: %s\n", vf_status_text(s));
        goto done;
    }
    qsort(times, (size_t)repeat, sizeof *times, cmp_double);
    const double median = repeat % 2 ? times[repeat / 2] : (times[repeat / 2 - 1] + times[repeat / 2]) / 2;

    ref_tf_point_t ref_tf[VF_MAX_TF_POINTS];
    for (uint32_t i = 0; i < count; i++)
        ref_tf[i] = (ref_tf_point_t){points[i].scalar_q8 / 256.0, points[i].r / 65535.0, points[i].g / 65535.0,
                                     points[i].b / 65535.0, points[i].a / 65535.0};
    const double t0 = vfp_now_ms();
    if (ref_order2_table(ref_tf, (int)count, (int)n, (int)n2, slab_q16 / 65536.0, ref)) {
        fprintf(stderr, "volfix-sim: the reference's order-2 build failed\n");
        goto done;
    }
    const double ref_ms = vfp_now_ms() - t0;
    double worst, mean, lit_worst = 0, lit_mean = 0;
    against(table, ref, entries * 4, (int)bits, &worst, &mean);
    if (lit) { /* the lighting values, eight an entry: the reference's in the same order by fours */
        double *ref_lit = malloc(entries * 8 * sizeof(double));
        if (!ref_lit || ref_order2_lit_table(ref_tf, (int)count, (int)n, (int)n2, slab_q16 / 65536.0, ref_lit)) {
            fprintf(stderr, "volfix-sim: the reference's order-2 lighting values failed\n");
            free(ref_lit);
            goto done;
        }
        against(lit_table, ref_lit, entries * 8, (int)bits, &lit_worst, &lit_mean);
        free(ref_lit);
    }
    const size_t value_bytes = bits == 8 ? 1 : 2;
    const size_t table_bytes = entries * 4 * value_bytes, lit_bytes = lit ? 2 * table_bytes : 0;
    const size_t pieces_bytes = (size_t)n * n * 16 * (lit ? 2 : 1);
    if (json) {
        printf("{\"order\": 2, \"size2\": %lld, \"table_size\": %lld, \"preset\": \"%s\", \"slab\": %g, \"bits\": %lld, "
               "\"lit\": %s, \"threads\": %lld, \"repeat\": %lld, \"build_ms\": %.3f, \"build_ms_min\": %.3f, "
               "\"table_bytes\": %zu, \"lit_bytes\": %zu, \"pieces_bytes\": %zu, \"max_err_lsb\": %.3f, "
               "\"mean_err_lsb\": %.4f, \"reference_ms\": %.1f",
               n2, n, tf.name, slab, bits, lit ? "true" : "false", threads, repeat, median, times[0], table_bytes,
               lit_bytes, pieces_bytes, worst, mean, ref_ms);
        if (lit)
            printf(", \"lit_max_err_lsb\": %.3f, \"lit_mean_err_lsb\": %.4f", lit_worst, lit_mean);
        printf("}\n");
    } else {
        printf("order-2 table, %s, %lld^3 entries from a %lld-entry 2D table, slabs of 2 x %g voxels%s\n", tf.name, n2, n,
               slab, lit ? ", lit" : "");
        printf("  build: %.3f ms (median of %lld, fastest %.3f) on %lld thread%s\n", median, repeat, times[0], threads,
               threads > 1 ? "s" : "");
        printf("  memory: 3D table %zu bytes (%lld-bit values), pieces %zu bytes (Q.30)\n", table_bytes, bits,
               pieces_bytes);
        if (lit)
            printf("  lighting values: %zu bytes more\n", lit_bytes);
        printf("  against the double build (%.0f ms): max %.3f, mean %.4f LSB of %lld-bit values\n", ref_ms, worst,
               mean, bits);
        if (lit)
            printf("  its lighting values: max %.3f, mean %.4f LSB\n", lit_worst, lit_mean);
    }
    status = VFP_EXIT_OK;
done:
    for (int t = 0; t < threads; t++)
        free(jobs[t].scratch);
    free(table);
    free(lit_table);
    free(ref);
    free(times);
    return status;
}
