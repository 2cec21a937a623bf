#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/orders-picture.sh: docs/images/orders.png, the same scenes in order 0, 1, 2 and the smooth truth. Top:
# phantom:marschner-lobb:41, sharp, 30,20, 256x256 (the truth is Marschner-Lobb's own function); bottom:
# brainsmall (VOLFIX_DATA, default ../shared/data), sharp, 30,20, zoom 1.8, 256x256 (the truth Catmull-Rom).
# Needs ImageMagick's montage. About 2 minutes on 2 cores (the two smooth truths).
cd "$(dirname "$0")/.." || exit 2
sim=${BUILD:-build}/volfix-sim
data=${VOLFIX_DATA:-../shared/data}
out=${1:-docs/images/orders.png}
command -v montage >/dev/null || { echo "orders-picture.sh: montage (ImageMagick) is not installed" >&2; exit 2; }
[ -f "$data/brainsmall.nhdr" ] || { echo "orders-picture.sh: $data/brainsmall.nhdr: missing (set VOLFIX_DATA)" >&2; exit 2; }
tmp=$(mktemp -d) || exit 2
trap 'rm -rf "$tmp"' EXIT
for scene in "ml|phantom:marschner-lobb:41|1" "brain|$data/brainsmall.nhdr|1.8"; do
    IFS='|' read -r name vol zoom <<END
$scene
END
    for m in "point|--mode point" "preint1|--mode preint1" "preint2|--mode preint2" "truth|--truth --truth-filter smooth"; do
        # shellcheck disable=SC2086
        "$sim" render "$vol" --preset sharp --view 30,20 --zoom "$zoom" --size 256x256 --threads 2 ${m#*|} \
            -o "$tmp/$name-${m%%|*}.png" >/dev/null || exit 1
    done
done
font=$(fc-match -f '%{file}' sans 2>/dev/null)
montage ${font:+-font "$font"} -label 'order 0: point' "$tmp/ml-point.png" -label 'order 1: preint1 (256)' \
    "$tmp/ml-preint1.png" -label 'order 2: preint2 (64^3)' "$tmp/ml-preint2.png" \
    -label "truth: Marschner-Lobb's function" "$tmp/ml-truth.png" -label 'order 0: point' "$tmp/brain-point.png" \
    -label 'order 1: preint1 (256)' "$tmp/brain-preint1.png" -label 'order 2: preint2 (64^3)' \
    "$tmp/brain-preint2.png" -label 'truth: Catmull-Rom' "$tmp/brain-truth.png" -tile 4x2 -geometry +4+4 \
    -pointsize 13 -background white "$out" && echo "wrote $out"
