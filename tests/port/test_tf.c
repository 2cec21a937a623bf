/* SPDX-License-Identifier: MIT */
/* test_tf.c: transfer-function files (port/io/tf.c) where tests/fuzz found or showed them wrong: scalars far outside
 * the window, lines longer than a buffer, NUL bytes; and how a file or preset says it is lit (the shade and
 * material lines, docs/usage.md). The file format's ordinary errors are in tests/host-sim/cli.sh. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/tf.h"
#include "volume_fixtures.h" /* fx_write: files in a private temporary directory */

static vfp_status_t load(vfp_tf_t *tf, const char *path, char *err, size_t errlen)
{
    err[0] = 0;
    vfp_status_t rc = vfp_tf_load(tf, path, err, errlen);
    if (getenv("VOLFIX_SHOW_ERRORS"))
        printf("# %s\n", rc ? err : "loaded");
    return rc;
}

/* A point at -1e308 is -inf once mapped to 0..255: the function's value at the window's bottom used to be inf/inf
 * (NaN, converted to uint16_t: undefined, 0 on x86). It is the value of the next point, as for any far point. */
static void far_scalars(void)
{
    const char *p = fx_write("far.tf", "-1e308 0 0 0 0\n0.2 1 0.8 0 0.05\n1e308 1 1 1 0.9\n", NULL, 0);
    vfp_tf_t tf;
    char err[VFP_ERR_LEN];
    CHECK_MSG(load(&tf, p, err, sizeof err) == 0, "%s", err);
    vfp_volume_t vol;
    memset(&vol, 0, sizeof vol);
    vol.slope = 1;
    vf_tf_point_t out[VF_MAX_TF_POINTS];
    uint32_t n = vfp_tf_to_core(&tf, &vol, (vf_window_t){0, 255}, out);
    CHECK_EQ(n, 3);
    CHECK_EQ(out[0].scalar_q8, 0);
    CHECK_EQ(out[0].r, 65535);
    CHECK_EQ(out[0].g, 52428);
    CHECK_EQ(out[0].a, 3277);
    CHECK_EQ(out[1].scalar_q8, 13056); /* 0.2 * 255 in Q8.8 */
    CHECK_EQ(out[2].scalar_q8, 65280);
    CHECK_EQ(out[2].r, 65535);
    CHECK_EQ(out[2].a, 3277); /* 1e308 is far: at 255 the function is still all but 0.05 */

    /* Moved by the level and width knobs until the far points overflow: the same. */
    vfp_tf_move(&tf, &vol, (vf_window_t){0, 255}, 0, 1e10);
    n = vfp_tf_to_core(&tf, &vol, (vf_window_t){0, 255}, out);
    CHECK(n >= 1 && n <= VF_MAX_TF_POINTS);
    for (uint32_t i = 1; i < n; i++)
        CHECK(out[i].scalar_q8 >= out[i - 1].scalar_q8);
}

/* Lines are read whole: a long comment is one line, and the line numbers after it are right (a 512-byte buffer
 * read the comment's tail as line 2). */
static void long_lines(void)
{
    char text[2048];
    int n = snprintf(text, sizeof text, "# ");
    memset(text + n, 'c', 900);
    snprintf(text + n + 900, sizeof text - (size_t)n - 900, "\n0 0 0 0 0 %*s\n1 1 1 1 1\n", 700, "# padded");
    const char *p = fx_write("long.tf", text, NULL, 0);
    vfp_tf_t tf;
    char err[VFP_ERR_LEN];
    CHECK_MSG(load(&tf, p, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(tf.count, 2);
    CHECK_NEAR(tf.points[1].a, 1.0, 0);

    snprintf(text + n + 900, sizeof text - (size_t)n - 900, "\n0 0 0 0 0\nbad\n");
    p = fx_write("long-bad.tf", text, NULL, 0);
    CHECK_EQ(load(&tf, p, err, sizeof err), VFP_ERR);
    char want[600];
    snprintf(want, sizeof want, "%s:3: expected a control point 'scalar r g b a' (five numbers)", p);
    CHECK_MSG(strcmp(err, want) == 0, "got '%s', expected '%s'", err, want);
}

/* A NUL byte is refused, as in board files (it used to end the line silently, dropping what followed). */
static void nul_byte(void)
{
    const char *p = fx_write("nul.tf", "0 0 0 0 0\n1 1 1 1 1", "\0 # the rest\n", 14);
    vfp_tf_t tf;
    char err[VFP_ERR_LEN];
    CHECK_EQ(load(&tf, p, err, sizeof err), VFP_ERR);
    char want[600];
    snprintf(want, sizeof want, "%s:2: expected text, found a NUL byte", p);
    CHECK_MSG(strcmp(err, want) == 0, "got '%s', expected '%s'", err, want);
}

/* shade and material lines: read anywhere in the file, later lines win; a file without them says nothing (-1),
 * so old files keep their look; the presets say theirs */
static void look_lines(void)
{
    vfp_tf_t tf;
    char err[VFP_ERR_LEN];
    const char *p = fx_write("lit.tf", "0 0 0 0 0\nshade phong   # lit\nmaterial 0.3 0.5 0.25 40\n1 1 1 1 1\n", NULL, 0);
    CHECK_MSG(load(&tf, p, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(tf.count, 2);
    CHECK_EQ(tf.look.shade, 1);
    CHECK_EQ(tf.look.have_material, 1);
    CHECK(tf.look.ka == 0.3 && tf.look.kd == 0.5 && tf.look.ks == 0.25 && tf.look.shininess == 40);
    p = fx_write("unlit.tf", "shade phong\nshade none\n0 0 0 0 0\n", NULL, 0);
    CHECK_MSG(load(&tf, p, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(tf.look.shade, 0);
    CHECK_EQ(tf.look.have_material, 0);
    p = fx_write("old.tf", "0 0 0 0 0\n1 1 1 1 1\n", NULL, 0);
    CHECK_MSG(load(&tf, p, err, sizeof err) == 0, "%s", err);
    CHECK_EQ(tf.look.shade, -1);
    CHECK_EQ(tf.look.have_material, 0);
    const char *lit[] = {"ct-bone", "ct-skin-bone"}, *unlit[] = {"ramp", "sharp", "mr-brain"};
    for (int k = 0; k < 2; k++) {
        CHECK(vfp_tf_preset(&tf, lit[k], err, sizeof err) == VFP_OK);
        CHECK_MSG(tf.look.shade == 1 && !tf.look.have_material, "%s", lit[k]);
    }
    for (int k = 0; k < 3; k++) {
        CHECK(vfp_tf_preset(&tf, unlit[k], err, sizeof err) == VFP_OK);
        CHECK_MSG(tf.look.shade == 0 && !tf.look.have_material, "%s", unlit[k]);
    }
}

/* a bad shade or material line: its file and line, and the accepted form */
static void look_errors(void)
{
    static const struct {
        const char *line, *message;
    } bad[] = {
        {"shade flat", "expected 'shade phong' or 'shade none'"},
        {"shade", "expected 'shade phong' or 'shade none'"},
        {"shade phong none", "expected 'shade phong' or 'shade none'"},
        {"material 0.1 0.7 0.2", "expected 'material KA KD KS N'"},
        {"material 0.1 0.7 0.2 10 3", "expected 'material KA KD KS N'"},
        {"material 1.1 0.7 0.2 10", "in [0, 1]"},
        {"material 0.1 0.7 0.2 0", "from 1 to 255"},
        {"material 0.1 0.7 0.2 9.5", "an integer shininess"},
        {"material 0.1 nan 0.2 9", "expected 'material KA KD KS N'"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        char text[128], want[160];
        snprintf(text, sizeof text, "0 0 0 0 0\n%s\n1 1 1 1 1\n", bad[k].line);
        const char *p = fx_write("bad.tf", text, NULL, 0);
        vfp_tf_t tf;
        char err[VFP_ERR_LEN];
        CHECK_MSG(load(&tf, p, err, sizeof err) == VFP_ERR, "'%s' was accepted", bad[k].line);
        snprintf(want, sizeof want, "bad.tf:2: ");
        CHECK_MSG(strstr(err, want) && strstr(err, bad[k].message) && !strchr(err, '\n'), "'%s': %s", bad[k].line,
                  err);
    }
}

CHECK_CASES({"far_scalars", far_scalars}, {"long_lines", long_lines}, {"nul_byte", nul_byte},
            {"look_lines", look_lines}, {"look_errors", look_errors});
CHECK_RUN("tf")
