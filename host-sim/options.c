/* SPDX-License-Identifier: MIT */
/* options.c: parse the options volfix-sim's commands share (see options.h). */
#include "options.h"
#include "io/numbers.h"
#include "io/pngio.h"
#include "io/tf.h"
#include "truth/truth.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

const char sim_scene_help[] =
    "  --preset NAME        built-in transfer function: ramp (default), sharp, ct-bone, ct-skin-bone, mr-brain\n"
    "  --tf FILE            transfer function file (see README: 'scalar r g b a' per line)\n"
    "  --mode MODE          point (order 0), preint1 (order 1, pre-integrated; default), preclass\n"
    "                       (order 0 with voxels classified before interpolation, as VolPack) or preint2\n"
    "                       (order 2: slabs of two slices along the quadratic through three samples)\n"
    "  --view AZ,EL[,ROLL]  view angles in degrees, each -360..360 (default 30,20), or a named view in the\n"
    "                       patient frame: anterior, posterior, left, right, superior or inferior\n"
    "  --zoom Z             1 fits the volume's bounding sphere in the image; 1/256..256 (default 1)\n"
    "  --size WxH           output size in pixels, each 1..8192 (default 512x512)\n"
    "  --format F           rgb888 (default), rgb565 or xrgb8888\n"
    "  --window LO,HI       data values mapped to the transfer function's 0..1, two different finite numbers\n"
    "                       (default: from the data, docs/defaults.md)\n"
    "  --tf-move S,K        move the transfer function up by S windows and stretch it K times about the\n"
    "                       window's centre, as the viewer's level and width knobs do; S -100..100, K above\n"
    "                       0 and below 1000 (default 0,1)\n"
    "  --downsample N       average N x N x N blocks first, N 1..8 (the viewer's preview while a knob turns)\n"
    "  --table-size N       transfer-function table entries, 2..1024 (default 256)\n"
    "  --table-bits B       16 (default) or 8 bits per table value (half the memory)\n"
    "  --lookup L           nearest (default) or bilinear table lookup; preint2: nearest or trilinear\n"
    "  --table2-size N      preint2's 3D table, N^3 entries, N 16..128 (default 64)\n"
    "  --correction C       rebuild (default: tables for each view's slab length) or lut (tables built once,\n"
    "                       opacity and colour corrected through a lookup on opacity: with nearest lookup\n"
    "                       in a 16-bit table of up to 512 entries, not preclass, each view into a second\n"
    "                       table, else each segment)\n"
    "  --buffer B           slice (default: two slice-sized buffers) or image (one image-row buffer)\n"
    "  --rays N             rays per voxel column along each axis: 1, 2, 4, 8 or 16 (an intermediate image of\n"
    "                       N x N pixels per voxel, N^2 times the memory); the truth ignores it. Default: 1,\n"
    "                       2 for an anisotropic volume (one spacing at least twice the smallest)\n"
    "  --partial-slabs      where a ray crosses a side face of the volume between two slices, composite the part\n"
    "                       of the slab inside it (default: the whole slab or nothing)\n"
    "  --threads N          threads for the table, compositing and warping, 1..16 (default 1)\n"
    "Lighting (docs/algorithm.md section 7; not with --partial-slabs, where the transfer function's own shading\n"
    "gives way):\n"
    VFP_LIGHTING_HELP
    "  --dims X,Y,Z --type uint8|int8|uint16|int16 [--big-endian] [--spacing X,Y,Z]\n"
    "                       for raw voxel files: sizes 2..4096, spacings above 0 and at most 32767 (--spacing\n"
    "                       also overrides a file's own)\n"
    "  --series UID         the DICOM series to load from a folder holding several (default: the largest)\n"
    "VOLUME is a .nhdr/.nrrd, .nii/.nii.gz, .mhd/.mha, DICOM (a folder of slices or a file), .den or raw file, or\n"
    "phantom:NAME:N with NAME marschner-lobb, shepp-logan, sphere or cube (formats: docs/formats.md).\n";

static vfp_status_t bad(const char *option, const char *value, const char *expected)
{
    fprintf(stderr, "volfix-sim: %s %s: expected %s\n", option, value ? value : "(missing)", expected);
    return VFP_ERR;
}

/* The options that take no value: any other option followed by '' is given an empty value, which is an error
 * rather than a way back to the default. */
static int is_flag(const char *a)
{
    static const char *const flags[] = {"--help", "-h", "--big-endian", "--hash", "--reference", "--partial-slabs",
                                        "--truth", "--json", "--matrix"};
    for (size_t i = 0; i < sizeof flags / sizeof flags[0]; i++)
        if (strcmp(a, flags[i]) == 0)
            return 1;
    return 0;
}

vfp_status_t sim_check_order2(const vf_params_t *p)
{
    const bool order2 = p->mode == VF_MODE_PREINT2;
    if (order2 && p->lookup == VF_LOOKUP_BILINEAR) {
        fprintf(stderr, "volfix-sim: --lookup bilinear: preint2 looks its 3D table up nearest or trilinear\n");
        return VFP_ERR;
    }
    if (!order2 && p->lookup == VF_LOOKUP_TRILINEAR) {
        fprintf(stderr, "volfix-sim: --lookup trilinear: only preint2 has a 3D table (--mode preint2); the other "
                        "modes take nearest or bilinear\n");
        return VFP_ERR;
    }
    if (order2 && p->partial_slabs) {
        fprintf(stderr, "volfix-sim: --partial-slabs: preint2 does not shorten its slabs at the side faces "
                        "(docs/algorithm.md, section 8)\n");
        return VFP_ERR;
    }
    return VFP_OK;
}

vfp_status_t sim_parse_mode(const char *text, vf_mode_t *mode)
{
    for (int m = 0; m < VF_MODE_COUNT; m++)
        if (text && strcmp(text, vf_mode_name((vf_mode_t)m)) == 0) {
            *mode = (vf_mode_t)m;
            return VFP_OK;
        }
    return VFP_ERR;
}

vfp_status_t sim_parse(sim_opts_t *o, int argc, char **argv, unsigned groups, const char *usage)
{
    memset(o, 0, sizeof *o);
    vf_params_default(&o->params);
    vfp_lighting_opts_init(&o->lighting);
    o->azimuth = 30;
    o->elevation = 20;
    o->zoom = 1;
    o->width = o->height = 512;
    o->format = VF_FORMAT_RGB888;
    o->threads = 1;
    o->frames = 90;
    o->tf_scale = 1;
    char err[VFP_ERR_LEN];
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1, took; /* how many arguments this option consumed after itself */
        if (!*a) {
            fprintf(stderr, "volfix-sim: '': an empty argument (expected an option or a volume)\n");
            return VFP_ERR;
        }
        if (vfp_is_empty(v) && a[0] == '-' && !is_flag(a)) {
            fprintf(stderr, "volfix-sim: %s '': an empty value (expected a value; see --help)\n", a);
            return VFP_ERR;
        }
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return VFP_HELP_SHOWN;
        } else if (a[0] != '-' && !o->volume && (groups & SIM_OPT_SCENE)) {
            o->volume = a;
            takes = 0;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--preset") == 0 && v) {
            o->preset = v;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--tf") == 0 && v) {
            o->tf_file = v;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--window") == 0 && v) {
            double w[2];
            if (vfp_parse_list(v, w, 2, 2) != 2 || w[0] == w[1])
                return bad(a, v, "LO,HI: two different finite numbers in data units, for example 0,1000");
            o->window = v;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--tf-move") == 0) {
            double m[2];
            if (vfp_parse_list(v, m, 2, 2) != 2 || !(m[1] > 0) || !(m[0] > -100 && m[0] < 100) || !(m[1] < 1000))
                return bad(a, v, "SHIFT,SCALE: a shift in windows (-100..100) and a scale above 0 and below 1000");
            o->tf_shift = m[0];
            o->tf_scale = m[1];
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--downsample") == 0) {
            long long n;
            if (!vfp_parse_integer(v, 1, 8, &n))
                return bad(a, v, "an integer from 1 to 8");
            o->load.downsample = (int)n;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--mode") == 0) {
            if (sim_parse_mode(v, &o->params.mode))
                return bad(a, v, "point, preint1, preclass or preint2");
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--table-bits") == 0) {
            if (v && strcmp(v, "8") == 0)
                o->params.table_bits = 8;
            else if (v && strcmp(v, "16") == 0)
                o->params.table_bits = 16;
            else
                return bad(a, v, "8 or 16");
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--lookup") == 0) {
            if (v && strcmp(v, "nearest") == 0)
                o->params.lookup = VF_LOOKUP_NEAREST;
            else if (v && strcmp(v, "bilinear") == 0)
                o->params.lookup = VF_LOOKUP_BILINEAR;
            else if (v && strcmp(v, "trilinear") == 0)
                o->params.lookup = VF_LOOKUP_TRILINEAR;
            else
                return bad(a, v, "nearest, bilinear or (preint2) trilinear");
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--table2-size") == 0) {
            long long n;
            if (!vfp_parse_integer(v, VF_MIN_TABLE2, VF_MAX_TABLE2, &n))
                return bad(a, v, "an integer from 16 to 128");
            o->params.table2_size = (uint32_t)n;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--correction") == 0) {
            if (v && strcmp(v, "rebuild") == 0)
                o->params.correction = VF_CORRECTION_REBUILD;
            else if (v && strcmp(v, "lut") == 0)
                o->params.correction = VF_CORRECTION_LUT;
            else
                return bad(a, v, "rebuild or lut");
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--buffer") == 0) {
            if (v && strcmp(v, "slice") == 0)
                o->params.buffer = VF_BUFFER_SLICE;
            else if (v && strcmp(v, "image") == 0)
                o->params.buffer = VF_BUFFER_IMAGE;
            else
                return bad(a, v, "slice or image");
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--rays") == 0) {
            long long n;
            if (!vfp_parse_integer(v, 1, 16, &n) || (n & (n - 1)))
                return bad(a, v, "1, 2, 4, 8 or 16");
            o->params.rays = (uint32_t)n;
            o->rays_given = 1;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--view") == 0) {
            double d[3] = {0, 0, 0};
            if (!v || vfp_view_named(v, d) != VFP_OK) {
                int n = vfp_parse_list(v, d, 2, 3);
                if (!n || !(fabs(d[0]) <= 360 && fabs(d[1]) <= 360 && fabs(d[2]) <= 360))
                    return bad(a, v, "AZ,EL or AZ,EL,ROLL in degrees, each -360..360, or " VFP_VIEW_NAMES);
            }
            o->azimuth = d[0];
            o->elevation = d[1];
            o->roll = d[2];
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--zoom") == 0) {
            double z;
            if (!vfp_parse_number(v, 1.0 / 256, 256, &z))
                return bad(a, v, "a number from 1/256 (0.00390625) to 256");
            o->zoom = z;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--size") == 0) {
            uint32_t w, h;
            if (!vfp_parse_size(v, 1, VF_MAX_IMAGE, &w, &h))
                return bad(a, v, "WxH, each an integer 1..8192");
            o->width = w;
            o->height = h;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--format") == 0) {
            if (v && strcmp(v, "rgb888") == 0)
                o->format = VF_FORMAT_RGB888;
            else if (v && strcmp(v, "rgb565") == 0)
                o->format = VF_FORMAT_RGB565;
            else if (v && strcmp(v, "xrgb8888") == 0)
                o->format = VF_FORMAT_XRGB8888;
            else
                return bad(a, v, "rgb888, rgb565 or xrgb8888");
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--table-size") == 0) {
            long long n;
            if (!vfp_parse_integer(v, VF_MIN_TABLE, VF_MAX_TABLE, &n))
                return bad(a, v, "an integer from 2 to 1024");
            o->params.table_size = (uint32_t)n;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--threads") == 0) {
            long long n;
            if (!vfp_parse_integer(v, 1, 16, &n))
                return bad(a, v, "an integer from 1 to 16");
            o->threads = (int)n;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--dims") == 0 && v) {
            if (vfp_parse_dims(v, o->load.dims, err, sizeof err)) {
                fprintf(stderr, "volfix-sim: --dims: %s\n", err);
                return VFP_ERR;
            }
            o->load.have_dims = 1;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--type") == 0 && v) {
            if (vfp_parse_type(v, &o->load.type, err, sizeof err)) {
                fprintf(stderr, "volfix-sim: --type: %s\n", err);
                return VFP_ERR;
            }
            o->load.have_type = 1;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--series") == 0) {
            if (!v || !v[0])
                return bad(a, v, "a DICOM Series Instance UID");
            o->load.series = v;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--big-endian") == 0) {
            o->load.big_endian = 1;
            takes = 0;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--spacing") == 0) {
            double *sp = o->load.spacing;
            if (vfp_parse_list(v, sp, 3, 3) != 3 || !(sp[0] > 0 && sp[1] > 0 && sp[2] > 0) ||
                !(sp[0] <= 32767 && sp[1] <= 32767 && sp[2] <= 32767))
                return bad(a, v, "X,Y,Z, three numbers above 0 and at most 32767");
            o->load.have_spacing = 1;
        } else if ((groups & SIM_OPT_OUT) && strcmp(a, "-o") == 0 && v) {
            o->out = v;
        } else if ((groups & SIM_OPT_HASH) && strcmp(a, "--hash") == 0) {
            o->hash = 1;
            takes = 0;
        } else if ((groups & SIM_OPT_REF) && strcmp(a, "--reference") == 0) {
            o->reference = 1;
            takes = 0;
        } else if ((groups & SIM_OPT_SCENE) && strcmp(a, "--partial-slabs") == 0) {
            o->params.partial_slabs = true;
            takes = 0;
        } else if ((groups & SIM_OPT_TRUTH) && strcmp(a, "--truth") == 0) {
            o->truth = 1;
            takes = 0;
        } else if ((groups & SIM_OPT_AGAINST) && strcmp(a, "--against") == 0) {
            if (v && strcmp(v, "truth") == 0)
                o->truth = 1;
            else if (v && strcmp(v, "reference") == 0)
                o->truth = 0;
            else
                return bad(a, v, "reference or truth");
        } else if ((groups & (SIM_OPT_TRUTH | SIM_OPT_AGAINST | SIM_OPT_FILTER)) && strcmp(a, "--truth-filter") == 0) {
            truth_filter_t filter;
            if (truth_filter_parse(v, &filter))
                return bad(a, v, "trilinear, smooth, catmull-rom, bspline or analytic");
            o->truth_filter = (int)filter;
        } else if ((groups & SIM_OPT_PIXEL) && strcmp(a, "--pixel") == 0) {
            double xy[2];
            if (vfp_parse_list(v, xy, 2, 2) != 2 || !(xy[0] >= 0 && xy[0] <= VF_MAX_IMAGE) ||
                !(xy[1] >= 0 && xy[1] <= VF_MAX_IMAGE))
                return bad(a, v, "X,Y, a final-image position in pixels, each 0..8192");
            o->pixel[0] = xy[0];
            o->pixel[1] = xy[1];
            o->have_pixel = 1;
        } else if ((groups & SIM_OPT_DIFF) && strcmp(a, "--diff") == 0 && v) {
            o->diff = v;
        } else if ((groups & SIM_OPT_JSON) && strcmp(a, "--json") == 0) {
            o->json = 1;
            takes = 0;
        } else if ((groups & SIM_OPT_MATRIX) && strcmp(a, "--matrix") == 0) {
            o->matrix = 1;
            takes = 0;
        } else if ((groups & SIM_OPT_FRAMES) && strcmp(a, "--frames") == 0) {
            long long n;
            if (!vfp_parse_integer(v, 1, 100000, &n))
                return bad(a, v, "a number of frames, 1..100000");
            o->frames = (int)n;
        } else if ((groups & SIM_OPT_ROUNDS) && strcmp(a, "--rounds") == 0) {
            long long n;
            if (!vfp_parse_integer(v, 1, 1000, &n))
                return bad(a, v, "a number of rounds, 1..1000");
            o->rounds = (int)n;
        } else if ((groups & SIM_OPT_SCENE) && (took = vfp_lighting_option(&o->lighting, "volfix-sim", a, v)) != 0) {
            if (took < 0)
                return VFP_ERR;
        } else if (a[0] == '-' && v == NULL) {
            fprintf(stderr, "volfix-sim: %s: unknown option or missing value (see --help)\n", a);
            return VFP_ERR;
        } else {
            fprintf(stderr, "volfix-sim: %s: unknown option or argument (see --help)\n", a);
            return VFP_ERR;
        }
        i += takes;
    }
    if ((groups & SIM_OPT_SCENE) && !o->volume) {
        fprintf(stderr, "volfix-sim: no volume given (see --help)\n");
        return VFP_ERR;
    }
    if (o->truth_filter != TRUTH_FILTER_TRILINEAR && !o->truth && !(groups & SIM_OPT_FILTER)) {
        fprintf(stderr, "volfix-sim: --truth-filter: only the ground truth has a filter (add %s)\n",
                (groups & SIM_OPT_AGAINST) ? "--against truth" : "--truth");
        return VFP_ERR;
    }
    if (o->reference && o->truth) {
        fprintf(stderr, "volfix-sim: give --reference or --truth, not both\n");
        return VFP_ERR;
    }
    if (o->params.partial_slabs && o->params.correction == VF_CORRECTION_LUT && !o->reference) {
        fprintf(stderr, "volfix-sim: --partial-slabs goes with --correction rebuild: the core does not shorten "
                        "lut-corrected slabs (docs/algorithm.md, section 4c)\n");
        return VFP_ERR;
    }
    if (vfp_lighting_check(&o->lighting, err, sizeof err)) {
        fprintf(stderr, "volfix-sim: %s\n", err);
        return VFP_ERR;
    }
    if (o->params.partial_slabs && (o->lighting.shade == 1 || o->lighting.light_count || o->lighting.have_material ||
                                    o->lighting.gradient_hi)) {
        fprintf(stderr, "volfix-sim: --partial-slabs does not go with lighting (--shade phong, --light, --material, "
                        "--gradient-opacity): docs/algorithm.md, section 7\n");
        return VFP_ERR;
    }
    if (o->preset && o->tf_file) {
        fprintf(stderr, "volfix-sim: give --preset or --tf, not both\n");
        return VFP_ERR;
    }
    return sim_check_order2(&o->params);
}

vfp_status_t sim_check_options(const sim_opts_t *o, unsigned groups)
{
    char err[VFP_ERR_LEN];
    if ((groups & SIM_OPT_HASH) && !o->out && !o->hash) {
        fprintf(stderr, "volfix-sim render: no output file (-o OUT.png, or --hash)\n");
        return VFP_ERR;
    }
    const char *pngs[2] = {(groups & SIM_OPT_OUT) && !(groups & SIM_OPT_OUT_DIR) ? o->out : NULL,
                           (groups & SIM_OPT_DIFF) ? o->diff : NULL};
    for (int k = 0; k < 2; k++) {
        if (!pngs[k])
            continue;
        /* standard output carries the other commands' reports; render alone (SIM_OPT_HASH) writes its PNG there */
        if (strcmp(pngs[k], "-") == 0 && !(groups & SIM_OPT_HASH) ) {
            fprintf(stderr, "volfix-sim: %s -: expected a file name (only render writes its PNG to standard "
                            "output)\n", k ? "--diff" : "-o");
            return VFP_ERR;
        }
        if (vfp_png_check_output(pngs[k], err, sizeof err)) {
            fprintf(stderr, "volfix-sim: %s %s\n", k ? "--diff" : "-o", err);
            return VFP_ERR;
        }
    }
    if ((groups & SIM_OPT_OUT_DIR) && !o->out) {
        fprintf(stderr, "volfix-sim ray: no output folder (-o DIR)\n");
        return VFP_ERR;
    }
    if ((groups & SIM_OPT_OUT_DIR) && o->out) {
        /* the folder is made when the files are written, so that input found bad later leaves nothing behind:
         * here it is an existing folder that can be written into, or a new one whose parent can */
        struct stat st;
        char parent[4096];
        const char *slash = strrchr(o->out, '/');
        snprintf(parent, sizeof parent, "%.*s", slash ? (slash == o->out ? 1 : (int)(slash - o->out)) : 1,
                 slash ? o->out : ".");
        const char *dir = stat(o->out, &st) == 0 ? o->out : parent;
        if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode) || access(dir, W_OK) != 0) {
            fprintf(stderr, "volfix-sim: -o %s: expected a folder volfix-sim can write into (or make)\n", o->out);
            return VFP_ERR;
        }
    }
    if (o->have_pixel && !(o->pixel[0] < o->width && o->pixel[1] < o->height)) {
        fprintf(stderr, "volfix-sim: --pixel %g,%g: expected a position inside the %ux%u image\n", o->pixel[0],
                o->pixel[1], o->width, o->height);
        return VFP_ERR;
    }
    vfp_tf_t tf;
    if (o->preset && vfp_tf_preset(&tf, o->preset, err, sizeof err)) {
        fprintf(stderr, "volfix-sim: --preset %s: %s\n", o->preset, err);
        return VFP_ERR;
    }
    return VFP_OK;
}
