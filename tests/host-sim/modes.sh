#!/bin/sh
# SPDX-License-Identifier: MIT
# One small render per mode (point, preint1, preclass, preint2), the smoke test of make check: each writes its PNG
# within a level of the double reference of the same mode (which the core shares no arithmetic with), and the four
# modes give four different pictures.
cd "$(dirname "$0")/../.." || exit 2
sim=${BUILD:-build}/volfix-sim
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene="phantom:marschner-lobb:24 --size 64x64 --preset sharp --view 30,20"

hashes=""
for mode in point preint1 preclass preint2; do
    # shellcheck disable=SC2086 # the scene is a list of options
    json=$("$sim" compare $scene --mode $mode -o "$tmp/$mode.png" --json 2>&1)
    max=$(echo "$json" | sed -n 's/.*"max_abs": \([0-9]*\).*/\1/p')
    # shellcheck disable=SC2086
    hash=$("$sim" render $scene --mode $mode --hash 2>&1 | cut -d' ' -f1)
    if [ -n "$max" ] && [ "$max" -le 1 ] && [ -s "$tmp/$mode.png" ] && [ -n "$hash" ]; then
        echo "ok - modes/$mode: 64x64, within $max level of the reference"
    else
        echo "not ok - modes/$mode: largest difference '$max' levels (expected at most 1): $(echo "$json" | head -n 1)"
    fi
    hashes="$hashes $hash"
done
distinct=$(echo "$hashes" | tr ' ' '\n' | grep . | sort -u | grep -c .)
[ "$distinct" -eq 4 ] && echo "ok - modes/four modes, four pictures" ||
    echo "not ok - modes/four modes, four pictures: hashes$hashes"
