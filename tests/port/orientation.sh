#!/bin/sh
# SPDX-License-Identifier: MIT
# Orientation from every format (docs/formats.md): an asymmetric phantom (an L-shaped marker on the patient's left,
# a sphere on the right) written by tests/port/volumes.py in NRRD (LPS and RAS spaces; raw, gzip, ascii, hex),
# NIfTI-1 (sform, qform), NIfTI-2, MetaImage (TransformMatrix, AnatomicalOrientation alone; .mhd, .mha, zlib) and
# DICOM, each with its own order and signs of the axes, renders the same frame, bit for bit, as the phantom stored
# in LPS order, from every named view and an oblique one. Then the named views show what a radiologist expects:
# the marker (the brighter object) on the side of the picture where the patient's left is, never mirrored.
cd "$(dirname "$0")/../.." || exit 2
sim=${BUILD:-build}/volfix-sim
suite=orientation program=$sim
. tests/check.inc

if /usr/bin/python3 -c 'import pydicom' 2>/dev/null; then
    gen_opts=
else
    echo "skip - $suite/dicom: no pydicom to write the phantom as DICOM (apt-get install python3-pydicom)"
    gen_opts=--no-dicom
fi
if ! grep -q '^BACKENDS = .*GDCM' "${BUILD:-build}/config.mk" 2>/dev/null && [ -z "$gen_opts" ]; then
    echo "skip - $suite/dicom: volfix-sim is built without GDCM (apt-get install libgdcm-dev g++, then make)"
    gen_opts=--no-dicom
fi
# shellcheck disable=SC2086 # no option or one
if ! tests/port/volumes.py orient "$tmp/o" $gen_opts >"$tmp/gen.log" 2>&1; then
    fail "generate" "tests/port/volumes.py orient: $(tail -n 1 "$tmp/gen.log")"
    exit 0
fi
o=$tmp/o

views="anterior posterior left right superior inferior 30,20 200,-40,15"
for view in $views; do
    "$sim" render "$o/reference.nrrd" --hash --size 48x48 --view "$view" 2>&1 | cut -d' ' -f1 >"$tmp/ref-$view"
done
while IFS= read -r name; do
    differ=""
    for view in $views; do
        got=$("$sim" render "$o/$name" --hash --size 48x48 --view "$view" 2>&1)
        [ "${got%% *}" = "$(cat "$tmp/ref-$view")" ] || differ="$differ $view(${got%% *})"
    done
    if [ -z "$differ" ]; then
        ok "$name: the reference's frame from 8 views"
    else
        fail "$name" "frames differ from the reference's at$differ"
    fi
done <"$o/list"
if [ "$(wc -l <"$o/list")" -ge 13 ]; then ok "$(wc -l <"$o/list") files compared"; else fail "files" "$(wc -l <"$o/list") listed"; fi

# Which half of the picture is brighter: the marker (value 240) outshines the sphere (120) under the ramp preset.
# anterior: the patient's left on the picture's right, as a frontal view is read; posterior: the other way; from
# the feet (inferior, as axial slices are read) the left is on the right, from above on the left; from the
# patient's left side the face (and the marker, which is in front) is on the picture's left.
brighter() { # VIEW: "left" or "right", the brighter half of the frame
    "$sim" render "$o/reference.nrrd" --size 64x64 --view "$1" -o "$tmp/v.png" >/dev/null 2>&1 || { echo error; return; }
    l=$(convert "$tmp/v.png" -crop 32x64+0+0 +repage -colorspace gray -format '%[fx:mean]' info: 2>/dev/null)
    r=$(convert "$tmp/v.png" -crop 32x64+32+0 +repage -colorspace gray -format '%[fx:mean]' info: 2>/dev/null)
    awk -v l="$l" -v r="$r" 'BEGIN { if (l == "" || r == "") print "error"; else print (r > l * 1.2 ? "right" : l > r * 1.2 ? "left" : "even") }'
}
if ! command -v convert >/dev/null 2>&1; then
    fail "sides" "no ImageMagick convert to measure the frames (apt-get install imagemagick)"
else
    for pair in anterior:right posterior:left inferior:right superior:left left:left right:right; do
        view=${pair%%:*} want=${pair#*:}
        got=$(brighter "$view")
        if [ "$got" = "$want" ]; then
            ok "view $view: the marker on the picture's $want"
        else
            fail "view $view" "the marker on the picture's $got, expected $want"
        fi
    done
fi

expect_error "unknown view name" "--view front: expected AZ,EL or AZ,EL,ROLL in degrees, each -360..360, or anterior, posterior, left, right, superior or inferior" \
    render "$o/reference.nrrd" --view front --hash
