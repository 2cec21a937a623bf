#!/bin/sh
# SPDX-License-Identifier: MIT
# make volpack-check: VolPack's own example image, rendered by VolPack and by volfix side by side.
#
# ../shared/data/brainsmall.volpack-check.ppm is VolPack's examples' image (classifyvolume.c, rendervolume.c):
# opacity = a density ramp (0 at 0 to 1 at 24) times a gradient-magnitude ramp (0 up to 5, 1 from 20), a minimum
# voxel opacity of 0.05, one white light (0.3, 0.3, 1.0) with ka 0.18, kd 0.35, ks 0.39 and shininess 10, depth
# cueing, a window of +-0.5, rotation 130 degrees about y then -15 about x, 256x256 luminance, a maximum ray
# opacity of 0.95. tools/peers/volpack_peer --check sets that up with VolPack's API (bench-peers checks it
# reproduces the .ppm bit for bit); here it renders it WITHOUT depth cueing, which volfix does not have, and writes
# the same classification for volfix (--volfix-tf: the density ramp as a lit transfer function, and the gradient
# ramp in volfix's 8-bit magnitudes). volfix renders it with `preclass`, VolPack's algorithm, lit, at the same
# camera (docs/peers.md): azimuth -130 = 230, elevation 15, zoom D / N = 1.54575 (D = |dims - 1|, N = 128), and
# VolPack's light as volfix names it, -16.70,16.03 (from the upper left; docs/peers.md, "The light").
#
# Prints the comparison (peer_compare: silhouettes, luminance difference, PSNR as rendered and after the best
# whole-pixel shift) and writes VolPack | volfix into OUT (default docs/images/volpack-check.png).
# Usage: tools/peers/volpack_check.sh [OUT.png]   (BUILD, VOLFIX_DATA as for make bench-peers; CHECK_DIR for the
# files, default $BUILD/peers/check; VOLPACK_LIGHT, volfix's light, default -16.70,16.03)
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
data=${VOLFIX_DATA:-../shared/data}
out_png=${1:-docs/images/volpack-check.png}
sim=$build/volfix-sim
peer=$build/peers/volpack_peer
compare=$build/peers/peer_compare
dir=${CHECK_DIR:-$build/peers/check} # the two renderings and the comparison
for f in "$sim" "$peer" "$compare"; do
    [ -x "$f" ] || { echo "volpack-check: $f: not built (run make volpack-check)" >&2; exit 2; }
done
for f in brainsmall.den brainsmall.nhdr; do
    [ -r "$data/$f" ] || { echo "volpack-check: $data/$f: missing (VOLFIX_DATA names the shared data folder)" >&2; exit 2; }
done
mkdir -p "$dir" || exit 2

light=${VOLPACK_LIGHT:--16.70,16.03}
# VolPack: the example without depth cueing; and the example's classification for volfix
gradient=$("$peer" "$data/brainsmall.den" --check --volfix-tf "$dir/check.tf" -o "$dir/volpack.png") || exit 1
# volfix: lit preclass, the classification's own material (check.tf's 'material' line)
vf_args="$data/brainsmall.nhdr --mode preclass --tf $dir/check.tf $gradient --light $light --size 256x256"
vf_args="$vf_args --zoom 1.545750 --view 230,15"
# shellcheck disable=SC2086 # a list of options
"$sim" render $vf_args -o "$dir/volfix.png" >/dev/null || exit 1
echo "VolPack: $peer $data/brainsmall.den --check -o $dir/volpack.png (the example without depth cueing)"
echo "volfix:  $sim render $vf_args -o $dir/volfix.png"
"$compare" "$dir/volpack.png" "$dir/volfix.png" --flip none --shift 3 --pair -o "$out_png" || exit 1
"$compare" "$dir/volpack.png" "$dir/volfix.png" --flip none --shift 3 --json >"$dir/compare.json" || exit 1
psnr=$(sed -n 's/.*"psnr": \([0-9.]*\).*/\1/p' "$dir/compare.json")
shifted=$(sed -n 's/.*"psnr_shifted": \([0-9.]*\).*/\1/p' "$dir/compare.json")
shift=$(sed -n 's/.*"psnr_shift": \[\([^]]*\)\].*/\1/p' "$dir/compare.json" | tr -d " ")
echo "PSNR $psnr dB as rendered, $shifted dB after the best whole-pixel shift (VolPack x+dx,y+dy on volfix x,y: $shift); VolPack | volfix: $out_png"
