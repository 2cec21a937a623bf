#!/bin/sh
# SPDX-License-Identifier: MIT
# The smallest configuration of core/vf_config.h, the microcontroller's (the Makefile's MCU_FEATURES, read from it):
# tests/core/small_config.c built against it and against the whole core. The small core must refuse more than one ray, partial slabs, the
# brute-force table builder and preint2 with VF_ERR_UNSUPPORTED (which the whole core renders or builds), and render every
# other frame of the program exactly as the whole core does (108 frames: every mode, lookup and correction, 3
# views; and one renderer a mode, correction and table format through 6 views and a
# new transfer function. The whole core builds its tables in 3 parts, the small one in vf_renderer_begin; with the
# lut the whole core corrects a view table, the small one each segment).
cd "$(dirname "$0")/../.." || exit 2
out=${BUILD:-build}/small-config
rm -rf "$out" && mkdir -p "$out"
cc=${CC:-gcc}
flags="-std=c99 -O2 -Wall -Wextra -Werror -Icore $SMALL_CONFIG_CFLAGS"

small=$(${MAKE:-make} -s --no-print-directory print-MCU_FEATURES)
case "$small" in
*-DVF_MAX_RAYS=1*) ;;
*) echo "not ok - small-config/features: expected the Makefile's MCU_FEATURES, got '$small'"; exit 0 ;;
esac

build() { # name, extra flags
    $cc $flags $2 -o "$out/$1" tests/core/small_config.c core/*.c >"$out/$1.log" 2>&1 &&
        "$out/$1" >"$out/$1.txt" 2>>"$out/$1.log"
}
if ! build whole "" || ! build small "$small"; then
    echo "not ok - small-config/builds and runs: $(head -n 3 "$out"/*.log | tr '\n' ' ')"
    exit 0
fi

line() { sed -n "s/^$2: //p" "$out/$1.txt"; }
for option in "rays 2" "partial slabs" "brute-force table" "preint2"; do
    whole=$(line whole "$option") small=$(line small "$option")
    if [ "$whole" = VF_OK ] && [ "$small" = VF_ERR_UNSUPPORTED ]; then
        echo "ok - small-config/$option: the whole core renders it, the small core says $small"
    else
        echo "not ok - small-config/$option: the whole core '$whole' (expected VF_OK), the small core '$small' (expected VF_ERR_UNSUPPORTED)"
    fi
done

grep ' view ' "$out/whole.txt" >"$out/whole.frames"
grep ' view ' "$out/small.txt" >"$out/small.frames"
frames=$(grep -c . "$out/whole.frames")
rendered=$(grep -c ': ok ' "$out/whole.frames")
if [ "$frames" -ge 36 ] && [ "$rendered" = "$frames" ] && diff "$out/whole.frames" "$out/small.frames" >"$out/diff" 2>&1
then
    echo "ok - small-config/$frames frames with one ray and whole slabs identical to the whole core's"
else
    echo "not ok - small-config/frames: $rendered of $frames rendered; $(head -n 4 "$out/diff" | tr '\n' ' ')"
fi
