#!/bin/sh
# SPDX-License-Identifier: MIT
# make run: render a few images into out/ with the fixed-point core and say how far each is from the
# double-precision reference of the same algorithm. Needs no data: the phantoms are built in; the sample volumes
# come from the folder VOLFIX_DATA (make exports it) when it is there.
cd "$(dirname "$0")/.." || exit 2
sim=${BUILD:-build}/volfix-sim
compare=${BUILD:-build}/peers/peer_compare # two images side by side (built by make run; it needs libpng only)
data=${VOLFIX_DATA:-}
have_data() { [ -n "$data" ] && [ -f "$data/engine.nhdr" ] && [ -f "$data/cthead.nhdr" ]; }
mkdir -p out

show() { # output name, then volfix-sim compare arguments
    png=$1
    shift
    json=$("$sim" compare "$@" -o "$png" --json) || return 1
    max=$(echo "$json" | sed -n 's/.*"max_abs": \([0-9]*\).*/\1/p')
    mean=$(echo "$json" | sed -n 's/.*"mean_abs": \([0-9.]*\).*/\1/p')
    psnr=$(echo "$json" | sed -n 's/.*"psnr_db": \([0-9.]*\).*/\1/p')
    scene=$(echo "$json" | sed -n 's/.*"scene": "\([^"]*\)".*/\1/p')
    printf '  %-32s %s\n  %32s fixed point vs double: max %s of 255, mean %s, PSNR %s dB\n' "$png" "$scene" "" \
        "$max" "$mean" "$psnr"
}

echo "volfix demo: the fixed-point core renders, the double-precision reference checks every pixel"
show out/marschner-lobb.png phantom:marschner-lobb:64 --preset sharp --view 30,20 || exit 1
show out/shepp-logan.png phantom:shepp-logan:128 --preset ramp --view 0,-60 || exit 1
echo "Lit (Blinn-Phong from quantised gradient normals; the CT presets are lit by default, docs/usage.md \"Lighting\"):"
show out/marschner-lobb-lit.png phantom:marschner-lobb:64 --preset sharp --view 30,20 --shade phong --light 30,30 ||
    exit 1
if have_data; then
    # half resolution: the double reference of a lit 256x256x128 volume alone takes 10 s
    show out/engine-lit.png "$data/engine.nhdr" --preset ct-bone --view 30,20 --downsample 2 --threads 2 || exit 1
    show out/cthead-lit.png "$data/cthead.nhdr" --preset ct-skin-bone --view 180,90 --threads 2 || exit 1
    show out/brainsmall-lit.png "$data/brainsmall.nhdr" --preset mr-brain --shade phong --view 150,-20 --zoom 1.3 \
        --threads 2 || exit 1
    # one scene unlit and lit, side by side (the README's picture, docs/images/unlit-lit.png, is this file)
    pair="$data/engine.nhdr --preset ct-bone --view 30,20 --zoom 1.5 --size 384x384 --threads 2"
    # shellcheck disable=SC2086 # a list of options
    "$sim" render $pair --shade none -o out/unlit.png >/dev/null &&
        "$sim" render $pair -o out/lit.png >/dev/null &&
        "$compare" out/unlit.png out/lit.png --flip none --pair -o out/unlit-lit.png >/dev/null || exit 1
    echo "  out/unlit-lit.png                engine, ct-bone: --shade none | lit (volfix-sim render $(echo "$pair" |
        sed "s|$data/||"))"
else
    echo "  (no sample volumes in VOLFIX_DATA='$data': the CT engine and head are left out. For them, set"
    echo "   VOLFIX_DATA to a folder of NRRD volumes such as the volfix shared data, whose README.md names each"
    echo "   volume's public source: make run VOLFIX_DATA=DIR)"
fi
viewer=${BUILD:-build}/volfix
if [ -x "$viewer" ]; then
    vol=phantom:marschner-lobb:96
    have_data && vol="$data/engine.nhdr"
    echo "The viewer on the headless board, knobs played from boards/host-headless.script (3 s):"
    rm -rf out/frames
    "$viewer" --board boards/host-headless.board "$vol" --device out/frames --overlay | sed 's/^/  /' || exit 1
    echo "  frames in out/frames/ (with the frame-time overlay)"
fi
echo "Open the PNG files in out/. Try: $sim render --help, $viewer --help"
echo "On a desktop: $viewer --board boards/host-sdl.board phantom:marschner-lobb:96 (arrow keys turn it)"
