#!/bin/sh
# SPDX-License-Identifier: MIT
# DICOM through GDCM (port/io/dicom.cpp), from the outside: series written at test time by tests/port/volumes.py
# (pydicom) and compressed by GDCM's gdcmconv, loaded by volfix-sim and compared by frame hash with a NRRD holding
# the same voxels. Covers 8- and 16-bit, signed with a rescale (CT in HU), unsorted file names, one multi-frame
# file, RLE and JPEG-LS lossless, two series in one folder (the largest, the others listed, --series), and the
# refusals: a missing slice, a gantry tilt, a lone slice, a folder without images, an unknown --series; and the
# progress of a series of 120 slices. tools/deps.sh test installs python3-pydicom and libgdcm-tools.
cd "$(dirname "$0")/../.." || exit 2
sim=${BUILD:-build}/volfix-sim
suite=dicom program=$sim
. tests/check.inc

if ! grep -q '^BACKENDS = .*GDCM' "${BUILD:-build}/config.mk" 2>/dev/null; then
    echo "skip - $suite: volfix-sim is built without GDCM (apt-get install libgdcm-dev g++, then make)"
    exit 0
fi
if ! /usr/bin/python3 -c 'import pydicom' 2>/dev/null; then
    echo "skip - $suite: no pydicom to write the test series (apt-get install python3-pydicom)"
    exit 0
fi
if ! command -v gdcmconv >/dev/null 2>&1; then
    echo "skip - $suite: no gdcmconv to compress a series (apt-get install libgdcm-tools)"
    exit 0
fi
if ! tests/port/volumes.py dicom "$tmp/d" >"$tmp/gen.log" 2>&1; then
    fail "generate" "tests/port/volumes.py dicom: $(tail -n 1 "$tmp/gen.log")"
    exit 0
fi
d=$tmp/d

# hash NAME VOLUME ARGS...: the frame's hash into $tmp/NAME.hash, stderr into $tmp/NAME.err; fails the case on error
hash() {
    name=$1 vol=$2
    shift 2
    if "$sim" render "$vol" --hash --size 48x48 "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"; then
        cut -d' ' -f1 "$tmp/$name.out" >"$tmp/$name.hash"
        return 0
    fi
    fail "$name" "$(head -n 1 "$tmp/$name.err")"
    return 1
}
same() { # NAME A B: two hash files equal
    if cmp -s "$tmp/$2.hash" "$tmp/$3.hash"; then ok "$1"; else fail "$1" "$(cat "$tmp/$2.hash") != $(cat "$tmp/$3.hash")"; fi
}

# 16-bit signed, Rescale Intercept -1024: a window in HU on the series is the same raw window on the NRRD of its
# stored values, and the file names (z05.dcm, z02.dcm, ...) are not in slice order
for view in 30,20 anterior left superior; do
    hash "ct16-$view" "$d/ct16" --window -1324,-124 --view "$view" &&
        hash "ct16-nrrd-$view" "$d/ct16.nrrd" --window -300,900 --view "$view" &&
        same "16-bit signed, HU rescale, unsorted names, view $view" "ct16-$view" "ct16-nrrd-$view"
done
# the summary speaks the data's unit, HU here, as --window does (the frame is the NRRD's raw -300,900: above)
if grep -q 'window -1324,-124' "$tmp/ct16-30,20.out"; then
    ok "rescale: --window -1324,-124 HU is raw -300,900, and the summary says it in HU"
else
    fail "rescale" "$(cat "$tmp/ct16-30,20.out")"
fi
# the same slices as one Enhanced CT file, frames stored out of order, positions in the functional groups
hash mf "$d/ct16-multiframe.dcm" --window -1324,-124 && same "multi-frame file, frames sorted by position" mf ct16-nrrd-30,20
# a file of a series: the series in its folder
hash one-of "$d/ct16/z03.dcm" --window -1324,-124 && same "one slice's file loads its series" one-of ct16-nrrd-30,20

# compressed transfer syntaxes, decoded by GDCM
for codec in rle jpegls; do
    mkdir -p "$d/$codec"
    for f in "$d"/ct16/*.dcm; do
        gdcmconv --$codec "$f" "$d/$codec/${f##*/}" 2>>"$tmp/conv.log" || break
    done
    if ! gdcminfo "$d/$codec/z00.dcm" 2>/dev/null | grep -q -i -E 'RLE Lossless|JPEG-LS Lossless'; then
        fail "$codec" "gdcmconv --$codec did not compress: $(gdcminfo "$d/$codec/z00.dcm" 2>&1 | grep -i transfer)"
        continue
    fi
    hash "$codec" "$d/$codec" --window -1324,-124 && same "compressed ($codec lossless) equals the uncompressed" "$codec" ct16-nrrd-30,20
done

# 8-bit unsigned, sagittal slices: reordered into the patient frame as the NRRD with the same directions is
for view in anterior left inferior; do
    hash "mr8-$view" "$d/mr8" --view "$view" && hash "mr8-nrrd-$view" "$d/mr8.nrrd" --view "$view" &&
        same "8-bit unsigned sagittal in the patient frame, view $view" "mr8-$view" "mr8-nrrd-$view"
done

# two series in one folder: the largest loads, the other is listed on one line with its UID, description and size
if hash two "$d/two" && grep -q '^.*two: 2 series; loading 1.2.826.0.1.3680043.2.1125.7 "big one" (7 slices)' "$tmp/two.err" &&
    grep -q 'other series 1.2.826.0.1.3680043.2.1125.4 "small one" (4 slices): --series 1.2.826.0.1.3680043.2.1125.4' "$tmp/two.err" &&
    [ "$(wc -l <"$tmp/two.err")" -eq 2 ]; then
    ok "two series: the largest loaded, the other listed"
else
    fail "two series" "$(tr '\n' '|' <"$tmp/two.err")"
fi
if hash two-small "$d/two" --series 1.2.826.0.1.3680043.2.1125.4 && grep -q 'window 200,203' "$tmp/two-small.out" &&
    ! cmp -s "$tmp/two.hash" "$tmp/two-small.hash"; then
    ok "--series picks the smaller series (values 200..203)"
else
    fail "--series" "$(cat "$tmp/two-small.out")"
fi
if hash two-big "$d/two" --series 1.2.826.0.1.3680043.2.1125.7 && grep -q 'window 100,106' "$tmp/two-big.out"; then
    ok "--series picks the larger series (values 100..106)"
else
    fail "--series big" "$(cat "$tmp/two-big.out")"
fi
expect_error "unknown --series" "two: --series 1.2.3: no such series here (the series are: 1.2.826.0.1.3680043.2.1125.4, 1.2.826.0.1.3680043.2.1125.7)" \
    render "$d/two" --series 1.2.3 --hash

# refusals: exit 2, one line naming the file and the tag
expect_error "missing slice" "gap/slice003.dcm: (0020,0032) Image Position (Patient) is 4 mm after $d/gap/slice002.dcm's, where the slices are 2 mm apart: a missing slice" \
    render "$d/gap" --hash
expect_error "gantry tilt" "tilt/slice001.dcm: (0020,0032) Image Position (Patient) moves 0.728 mm sideways for 2 mm along the normal of (0020,0037) Image Orientation (Patient): a gantry tilt of 20.0 degrees" \
    render "$d/tilt" --hash
expect_error "lone slice" "has one slice: a volume needs at least 2" render "$d/one" --hash
expect_error "no images" "empty: is a directory with no DICOM images in it" render "$d/empty" --hash
# files cut short: Debian's GDCM asserts (abort) on them, which the reader turns into its one-line error
mkdir -p "$d/cut"
printf 'DICM' | dd of="$d/cut/bad.dcm" bs=1 seek=128 2>/dev/null
expect_error "only a preamble" "cut/bad.dcm: not a DICOM image that GDCM can read" render "$d/cut/bad.dcm" --hash
head -c 300 "$d/ct16/z00.dcm" >"$d/cut/header.dcm"
expect_error "cut in the header" "cut/header.dcm: not a DICOM image that GDCM can read" render "$d/cut/header.dcm" --hash
cp -r "$d/ct16" "$d/cut16"
size=$(wc -c <"$d/cut16/z04.dcm")
head -c $((size - 10)) "$d/ct16/z04.dcm" >"$d/cut16/z04.dcm"
expect_error "a slice cut in its pixel data" "cut16/z04.dcm: (7fe0,0010) Pixel Data is cut short" render "$d/cut16" --hash

# progress: 120 files, a few lines when stderr is a file, one line rewritten in place on a terminal
if hash many "$d/many" && grep -q 'reading DICOM headers 120/120' "$tmp/many.err" &&
    grep -q 'decoding DICOM slices 120/120' "$tmp/many.err" && [ "$(wc -l <"$tmp/many.err")" -le 12 ] &&
    ! grep -q "$(printf '\r')" "$tmp/many.err"; then
    ok "120 slices: $(wc -l <"$tmp/many.err") progress lines on a file"
else
    fail "progress to a file" "$(wc -l <"$tmp/many.err") lines: $(head -n 2 "$tmp/many.err" | tr '\n' '|')"
fi
if command -v script >/dev/null 2>&1; then
    script -qec "$sim render $d/many --hash --size 16x16" /dev/null >"$tmp/tty.out" 2>&1
    cr=$(tr -cd '\r' <"$tmp/tty.out" | wc -c)
    if [ "$cr" -ge 100 ] && grep -q 'decoding DICOM slices 120/120' "$tmp/tty.out"; then
        ok "120 slices on a terminal: one line rewritten in place ($cr carriage returns)"
    else
        fail "progress on a terminal" "$cr carriage returns: $(head -c 200 "$tmp/tty.out" | tr '\r\n' '||')"
    fi
else
    fail "progress on a terminal" "no script(1) to give volfix-sim a terminal (apt-get install bsdutils)"
fi
# --series and progress are not printed for a single series under 100 files
if [ ! -s "$tmp/ct16-30,20.err" ]; then ok "a small single series prints nothing on stderr"; else
    fail "quiet small series" "$(head -n 1 "$tmp/ct16-30,20.err")"; fi
