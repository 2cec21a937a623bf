#!/bin/sh
# SPDX-License-Identifier: MIT
# volfix's NIfTI and NRRD readers against the formats' reference libraries (docs/formats.md): every file of the
# orientation phantom (tests/port/volumes.py: NRRD in LPS and RAS, raw, gzip, ascii and hex; NIfTI-1 sform and
# qform, NIfTI-2) and the shared data's NRRD and NIfTI files, read by nifticlib (libnifti2) or teem (libteem) in
# tests/port/lib_compare.c and written back as a plain NRRD with the library's voxels and patient directions, render
# the same frame with volfix as the file itself, from two views: the readers agree on voxels, type, spacing and
# orientation. tools/deps.sh test installs libnifti2-dev and libteem-dev.
cd "$(dirname "$0")/../.." || exit 2
sim=${BUILD:-build}/volfix-sim
data=${VOLFIX_DATA:-../shared/data}
suite=libraries
. tests/check.inc

cc=${CC:-gcc}
if ! $cc -std=c11 -D_DEFAULT_SOURCE -Wall -Wextra -O1 -I/usr/include/nifti -o "$tmp/lib_compare" \
    tests/port/lib_compare.c -lnifti2 -lznz -lteem -lz -lm >"$tmp/cc.log" 2>&1; then
    echo "skip - $suite: cannot build tests/port/lib_compare.c against nifticlib and teem (apt-get install libnifti2-dev libteem-dev): $(head -n 1 "$tmp/cc.log")"
    exit 0
fi
if ! tests/port/volumes.py orient "$tmp/o" --no-dicom >"$tmp/gen.log" 2>&1; then
    fail "generate" "tests/port/volumes.py orient: $(tail -n 1 "$tmp/gen.log")"
    exit 0
fi

count=0
for f in "$tmp"/o/*.nrrd "$tmp"/o/*.nii "$data"/*.nhdr "$data"/*.nrrd "$data"/*.nii "$data"/*.nii.gz; do
    [ -f "$f" ] || continue
    case "$f" in *.nii | *.nii.gz) lib=nifti ;; *) lib=nrrd ;; esac
    name=${f##*/}
    if ! "$tmp/lib_compare" $lib "$f" "$tmp/lib.nrrd" 2>"$tmp/lib.err"; then
        fail "$name" "the library ($lib) did not read it: $(head -n 1 "$tmp/lib.err")"
        continue
    fi
    differ=""
    for view in anterior 30,20; do
        a=$("$sim" render "$f" --hash --size 48x48 --view $view 2>&1)
        b=$("$sim" render "$tmp/lib.nrrd" --hash --size 48x48 --view $view 2>&1)
        [ "${a%% *}" = "${b%% *}" ] || differ="$differ $view(${a%% *} vs ${b%% *})"
    done
    if [ -z "$differ" ]; then
        ok "$name: volfix and $([ $lib = nifti ] && echo nifticlib || echo teem) read the same volume"
    else
        fail "$name" "volfix and the library's volume render differently:$differ"
    fi
    count=$((count + 1))
done
if [ "$count" -ge 16 ]; then ok "$count files compared"; else fail "files" "only $count files compared (expected the phantom's 10 and the shared data's)"; fi
