#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/eval-orders.sh: is second order better? Each scene's two truths (trilinear and smooth: a phantom's own
# function, Catmull-Rom for real volumes) are rendered once, then each configuration's core image is compared
# with both: PSNR and the ray error xi, the mean absolute difference of the final pixel colours in [0, 1] over
# all pixels and channels (docs/algorithm.md, section 8b), computed from the 8-bit images.
#
# usage: tools/eval-orders.sh [-o DIR] [--quick] [--scenes "NAME ..."]
#   -o DIR     keep the images and write DIR/orders.csv (default: a temporary folder, removed)
#   --quick    Marschner-Lobb 41^3 at 30,20 only (what tests/host-sim/orders.sh runs)
#   --scenes   a subset by name (ml41 neghip engine bucky brainsmall cthead ml64)
# Environment: BUILD (default build), VOLFIX_DATA (default ../shared/data), SIZE (default 256x256), THREADS (2).
# The held-back set (brainsmall, cthead, Marschner-Lobb 64^3) was fixed before any measurement of this script.
# How long: about 15 minutes on a 2-core machine for every scene, most of it the smooth truths.
cd "$(dirname "$0")/.." || exit 2
sim=${BUILD:-build}/volfix-sim
data=${VOLFIX_DATA:-../shared/data}
size=${SIZE:-256x256}
threads=${THREADS:-2}
out=""
quick=0
only=""
while [ $# -gt 0 ]; do
    case "$1" in
    -o) [ $# -ge 2 ] || { echo "eval-orders.sh: -o: expected a folder" >&2; exit 2; }; out=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --scenes) [ $# -ge 2 ] || { echo "eval-orders.sh: --scenes: expected names" >&2; exit 2; }; only=$2; shift 2 ;;
    *) echo "eval-orders.sh: $1: unknown option (expected -o DIR, --quick or --scenes \"NAMES\")" >&2; exit 2 ;;
    esac
done
[ -x "$sim" ] || { echo "eval-orders.sh: $sim: not built (run make)" >&2; exit 2; }
if [ -z "$out" ]; then
    out=$(mktemp -d) || exit 2
    trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out" || exit 2

# name, volume, held back (1) or not
scenes="ml41:phantom:marschner-lobb:41:0
neghip:$data/neghip.nhdr:0
engine:$data/engine.nhdr:0
bucky:$data/bucky.nhdr:0
brainsmall:$data/brainsmall.nhdr:1
cthead:$data/cthead.nhdr:1
ml64:phantom:marschner-lobb:64:1"
views="30,20 135,70"
[ $quick = 1 ] && { scenes="ml41:phantom:marschner-lobb:41:0"; views="30,20"; }
# the configurations: label and core options (equal slice count: every mode composites every slice; -r4: 4 x 4
# rays per voxel column, which lifts the one-ray-per-column floor shared by all orders)
configs="point|--mode point
preint1-64|--mode preint1 --table-size 64
preint1-128|--mode preint1 --table-size 128
preint1-256|--mode preint1
preint2-64|--mode preint2 --table2-size 64
preint2-128|--mode preint2 --table2-size 128
preint1-64-r4|--mode preint1 --table-size 64 --rays 4
preint2-64-r4|--mode preint2 --table2-size 64 --rays 4"

csv=$out/orders.csv
echo "scene,held_back,view,config,truth,psnr_db,xi" >"$csv"
metric() { # A.png B.png -> "psnr xi"
    "$sim" diff "$1" "$2" --json | awk '{
        match($0, /"psnr_db": *[-0-9.einf]+/); p = substr($0, RSTART, RLENGTH); sub(/.*: */, "", p);
        match($0, /"mean_abs": *[-0-9.e]+/); m = substr($0, RSTART, RLENGTH); sub(/.*: */, "", m);
        printf "%s %.5f\n", p, m / 255 }'
}
echo "$scenes" | while IFS=: read -r name vol1 vol2 vol3 held; do
    # phantom:NAME:N has two colons of its own
    case "$vol1" in phantom) vol="$vol1:$vol2:$vol3" ;; *) vol=$vol1; held=$vol2 ;; esac
    if [ -n "$only" ] && ! echo " $only " | grep -q " $name "; then continue; fi
    case "$vol" in phantom:*) ;; *) [ -f "$vol" ] || { echo "== $name: $vol missing, skipped" >&2; continue; } ;; esac
    for view in $views; do
        tag=$name-$(echo "$view" | tr , _)
        for truth in trilinear smooth; do
            "$sim" render "$vol" --preset sharp --view "$view" --size "$size" --threads "$threads" --truth \
                --truth-filter "$truth" -o "$out/$tag-truth-$truth.png" >/dev/null || exit 1
        done
        echo "$configs" | while IFS='|' read -r label opts; do
            # shellcheck disable=SC2086
            "$sim" render "$vol" --preset sharp --view "$view" --size "$size" --threads "$threads" $opts \
                -o "$out/$tag-$label.png" >/dev/null || exit 1
            for truth in trilinear smooth; do
                set -- $(metric "$out/$tag-$label.png" "$out/$tag-truth-$truth.png")
                echo "$name,$held,$(echo "$view" | tr , _),$label,$truth,$1,$2" >>"$csv"
            done
        done || exit 1
        echo "== $tag done" >&2
    done || exit 1
done || exit 1

# the table: one row per scene and view, PSNR / xi against each truth per configuration
awk -F, 'NR > 1 {
    key = $1 "," $3; if (!(key in seen)) { seen[key] = 1; order[++n] = key; held[key] = $2 }
    cell[key "," $4 "," $5] = sprintf("%.2f / %.4f", $6, $7); if (!($4 in cfgseen)) { cfgseen[$4] = 1; cfg[++nc] = $4 }
} END {
    for (t = 1; t <= 2; t++) {
        truth = t == 1 ? "smooth" : "trilinear"
        printf "\nAgainst the %s truth: PSNR dB / xi\n\n| scene | view |", truth
        for (c = 1; c <= nc; c++) printf " %s |", cfg[c]
        printf "\n|---|---|"; for (c = 1; c <= nc; c++) printf "---|"; printf "\n"
        for (i = 1; i <= n; i++) {
            split(order[i], kv, ","); v = kv[2]; sub(/_/, ",", v)
            printf "| %s%s | %s |", kv[1], held[order[i]] == 1 ? " (held back)" : "", v
            for (c = 1; c <= nc; c++) printf " %s |", cell[order[i] "," cfg[c] "," truth]
            printf "\n"
        }
    }
}' "$csv"
