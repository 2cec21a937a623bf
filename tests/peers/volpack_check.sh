#!/bin/sh
# SPDX-License-Identifier: MIT
# VolPack's own example image against volfix (tools/peers/volpack_check.sh, make volpack-check): VolPack renders its
# example classification of brainsmall without depth cueing, volfix the same classification with lit preclass.
# Checks: the two agree to >= 30 dB PSNR once aligned by whole pixels (the camera's known sub-voxel offset) and to
# >= 25 dB as rendered; VolPack's light (0.3, 0.3, 1.0) is volfix's -16.70,16.03 (from the upper left), which
# agrees better than the other signs by more than 10 dB; volpack_peer refuses --volfix-tf without --check.
# Needs Debian's libvolpack1-dev (tools/deps.sh test installs it) and the shared data.
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
data=${VOLFIX_DATA:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

ok() { echo "ok - peers/$1"; }
fail() { echo "not ok - peers/$1: $2"; }

if [ ! -r "$data/brainsmall.den" ]; then
    fail "data" "no brainsmall.den in VOLFIX_DATA='$data': set VOLFIX_DATA to the folder of sample volumes"
    exit 0
fi
# the VolPack client and the comparer, built as make bench-peers builds them (without a sanitizer: VolPack is not)
if ! ${MAKE:-make} --no-print-directory BUILD="$build" peers-progs >"$tmp/build.log" 2>&1; then
    fail "build" "make peers-progs failed (libvolpack1-dev installed? tools/deps.sh test): $(grep -m 2 -iE 'error|fatal' "$tmp/build.log" | tr '\n' ' ')"
    exit 0
fi

# check LIGHT: the comparison for volfix's light LIGHT; sets psnr, shifted
check() {
    CHECK_DIR=$tmp/check VOLPACK_LIGHT=$1 BUILD=$build VOLFIX_DATA=$data sh tools/peers/volpack_check.sh "$tmp/side.png" >"$tmp/out" 2>&1 ||
        { psnr="" shifted=""; return 1; }
    psnr=$(sed -n 's/^PSNR \([0-9.]*\) dB as rendered, \([0-9.]*\) dB after.*/\1/p' "$tmp/out")
    shifted=$(sed -n 's/^PSNR \([0-9.]*\) dB as rendered, \([0-9.]*\) dB after.*/\2/p' "$tmp/out")
    [ -n "$psnr" ] && [ -n "$shifted" ]
}
at_least() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 >= b + 0) }'; }

if check -16.70,16.03; then
    ours=$shifted
    if at_least "$shifted" 30; then ok "VolPack's example against volfix lit preclass: $shifted dB aligned (>= 30)"; else
        fail "aligned PSNR" "$shifted dB after the best whole-pixel shift, below 30: $(tail -n 1 "$tmp/out")"; fi
    if at_least "$psnr" 25; then ok "as rendered: $psnr dB (>= 25)"; else
        fail "PSNR as rendered" "$psnr dB, below 25"; fi
    if [ -s "$tmp/side.png" ]; then ok "the side-by-side image is written"; else fail "side by side" "no image"; fi
    worst=""
    for light in 16.70,16.03 16.70,-16.03 -16.70,-16.03; do
        if check "$light" && at_least "$ours" "$(awk -v s="$shifted" 'BEGIN { print s + 10 }')"; then :; else
            worst="$worst $light (${shifted:-failed} dB)"; fi
    done
    if [ -z "$worst" ]; then ok "VolPack's light (0.3, 0.3, 1.0) is volfix's -16.70,16.03: the other signs fit >= 10 dB worse"; else
        fail "light" "at $ours dB, not 10 dB better than:$worst"; fi
else
    fail "volpack-check" "tools/peers/volpack_check.sh failed: $(tail -n 2 "$tmp/out" | tr '\n' ' ')"
fi

"$build/peers/volpack_peer" "$data/brainsmall.den" --tf /dev/null --volfix-tf "$tmp/x.tf" >"$tmp/o" 2>"$tmp/e"
status=$?
if [ $status = 2 ] && [ "$(wc -l <"$tmp/e")" = 1 ] && grep -q -- '--volfix-tf .*: goes with --check' "$tmp/e"; then
    ok "--volfix-tf without --check: one line naming the option, status 2"
else
    fail "--volfix-tf refused" "status $status: $(tr '\n' ' ' <"$tmp/e")"
fi
