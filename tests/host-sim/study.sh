#!/bin/sh
# SPDX-License-Identifier: MIT
# The quick precision study (volfix-sim study --quick -o out/study): every plot, strip and table the report
# promises is there, and its numbers for the claims: pre-integration at least 6 dB closer to the truth than
# point sampling inside Marschner-Lobb 41^3 with the sharp preset, and in the whole view with the errors both
# orders share removed (16 x 16 rays per voxel column, partial slabs, 1024 entries), the core within a level of
# the reference there; the default configuration's fixed-point error at most 1 level of 255 on the shared
# volumes; the whole view's gain at the default configuration reported, with what it means.
cd "$(dirname "$0")/../.." || exit 2
sim=${BUILD:-build}/volfix-sim
dir=out/study
rm -rf "$dir"
mkdir -p out

suite=study
. tests/check.inc

if ! command -v gnuplot >/dev/null; then
    echo "skip - study: gnuplot is missing, which draws the report's plots (install gnuplot-nox fonts-dejavu-core)"
    exit 0
fi
if ! "$sim" study --quick -o "$dir" >out/study.log 2>&1; then
    fail "runs" "$(tail -n 3 out/study.log | tr '\n' ' ')"
    exit 0
fi
ok "study --quick runs ($(tail -n 1 out/study.log))"

missing=""
claim_strip=strip-ml41-sharp-rays16-partial-1024.png
for f in report.md results.csv summary.json bits.png table_size.png orders.png memory.png peaks.png rays.png \
         strip-ml41-sharp.png strip-ml41-sharp-interior.png strip-ml41-ramp.png $claim_strip; do
    [ -s "$dir/$f" ] || missing="$missing $f"
done
[ -z "$missing" ] && ok "every file written" || fail "every file written" "missing:$missing"

missing=""
for f in bits.png table_size.png orders.png memory.png peaks.png rays.png strip-ml41-sharp.png $claim_strip; do
    grep -q "($f)" "$dir/report.md" || missing="$missing $f"
done
for heading in "## The two claims" "## Bits per stage" "## Table size and lookup" "## Orders, smooth and sharp" \
               "## Rays per voxel column and partial slabs" "## Memory against error" "## Recommendations" \
               "Claim 1 without the errors both orders share" "(a) A Raspberry Pi class board" \
               "(b) A microcontroller with 256 KB of RAM" "| scene | value | PSNR vs reference |"; do
    grep -qF "$heading" "$dir/report.md" || missing="$missing '$heading'"
done
[ -z "$missing" ] && ok "report embeds every plot and table" || fail "report embeds every plot and table" "missing:$missing"

# the rays sweep's plot is a real plot: its data has claim 1's configuration
[ -s "$dir/rays.dat" ] && grep -q '^16 ' "$dir/rays.dat" && [ "$(head -c 4 "$dir/rays.png" | tail -c 3)" = "PNG" ] &&
    ok "rays.png plots the rays sweep (R = 16 in rays.dat)" ||
    fail "rays plot" "rays.dat or rays.png wrong"

rows=$(($(wc -l <"$dir/results.csv") - 1))
[ "$rows" -ge 80 ] && head -n 1 "$dir/results.csv" | grep -q '^scene,volume,preset' && ok "results.csv has $rows runs" ||
    fail "results.csv" "$rows rows"

# every row has the header's columns, once quoted fields (views, the fixed-point check's labels) are taken out
cols=$(head -n 1 "$dir/results.csv" | tr -cd , | wc -c)
bad=$(tail -n +2 "$dir/results.csv" | sed 's/"[^"]*"//g' | awk -F, -v c="$cols" 'NF - 1 != c' | head -n 1)
[ -z "$bad" ] && ok "every row of results.csv has the header's $((cols + 1)) columns" ||
    fail "results.csv columns" "a row with other than $((cols + 1)) columns: $(echo "$bad" | cut -c1-80)"

num() { sed -n "s/.*\"$1\": \([-0-9.]*\).*/\1/p" "$dir/summary.json"; }
gain=$(num interior_preint1_gain_db)
whole=$(num preint1_gain_db)
fixed=$(num default_fixed_point_max_abs)
cases=$(num default_fixed_point_cases)
awk "BEGIN { exit !($gain >= 6) }" && ok "preint1 $gain dB closer to the truth than point inside Marschner-Lobb 41^3 (sharp)" ||
    fail "preint1 at least 6 dB closer inside Marschner-Lobb" "measured $gain dB"
[ -n "$fixed" ] && [ "$cases" -ge 10 ] && [ "$fixed" -le 1 ] &&
    ok "default configuration within $fixed level of the reference over $cases renders" ||
    fail "default fixed-point error at most 1" "max $fixed over $cases renders$([ -f "${VOLFIX_DATA:-}/neghip.nhdr" ] ||
        echo " (no neghip.nhdr in VOLFIX_DATA='${VOLFIX_DATA:-}': set it to the folder of sample volumes)")"
# where the whole view's distance comes from: the exact integrals at shear-warp's own rays, warped, are closer to
# the truth than any mode's reference (else the floor's rays or warp do not line up with the renderer's), and on
# those rays pre-integration integrates better than point sampling
arr() { sed -n "s/.*\"$1\": \[\([-0-9.]*\), \([-0-9.]*\)\].*/\1 \2/p" "$dir/summary.json"; }
floor=$(num ml41_sharp_floor_db)
set -- $(arr reference_point_truth_db) $(arr reference_preint1_truth_db) $(arr integration_point_db) \
    $(arr integration_preint1_db)
if [ $# -eq 8 ] && awk "BEGIN { exit !($floor > $1 && $floor > $2 && $floor > $3 && $floor > $4) }"; then
    ok "the one-ray-per-voxel floor ($floor dB) is above every reference render ($1 $2 $3 $4 dB)"
else
    fail "floor" "floor '$floor' dB, references '$*'"
fi
if [ $# -eq 8 ] && awk "BEGIN { exit !($7 > $5 + 2 && $8 > $6 + 2) }"; then
    ok "on shear-warp's own rays preint1 integrates closer than point ($7 vs $5, $8 vs $6 dB)"
else
    fail "integration alone" "point '$5 $6', preint1 '$7 $8'"
fi
# the whole view's claim is reported as it is, with the word the report uses for it
verdict=$(awk "BEGIN { print ($whole >= 6) ? \"holds\" : \"does NOT hold\" }")
said=$(sed -n 's/.*\*\*\([-0-9.]*\) dB closer\*\* (claim: at least 6 dB; \([^)]*\)).*/\1 \2/p' "$dir/report.md" | head -n 1)
awk "BEGIN { split(\"$said\", w, \" \"); exit !(w[1] - $whole < 0.006 && $whole - w[1] < 0.006) }" &&
    [ "${said#* }" = "$verdict" ] && ok "whole-view gain ($whole dB) reported with its verdict ($verdict)" ||
    fail "whole-view gain reported" "summary $whole dB ($verdict), report says '$said'"
# claim 1 with the errors both orders share removed: 16 x 16 rays, partial slabs, 1024 entries, the same slab
# count; at least 6 dB, the core within a level of the reference there and over the quick rays sweep, and the
# report says it with the same number and verdict
claim=$(num claim_gain_db)
cmax=$(num claim_max_abs_vs_reference)
rmax=$(num rays_max_abs_vs_reference)
rruns=$(num rays_runs)
if [ "$(num claim_measured)" = 1 ] && awk "BEGIN { exit !($claim >= 6) }"; then
    ok "preint1 $claim dB closer to the truth than point with 16 rays, partial slabs and 1024 entries ($(num claim_preint1_truth_psnr_db) vs $(num claim_point_truth_psnr_db) dB)"
else
    fail "claim 1 without the shared errors" "measured '$claim' dB"
fi
[ -n "$cmax" ] && [ "$cmax" -le 1 ] && [ "$rruns" -ge 3 ] && [ "$rmax" -le 1 ] &&
    ok "core within $rmax level of the reference over $rruns renders of the rays sweep (claim 1's: $cmax)" ||
    fail "rays sweep against the reference" "claim max '$cmax', sweep max '$rmax' over '$rruns' renders"
said=$(sed -n 's/.*\*\*Claim 1 without the errors both orders share\.\*\*.*\*\*\([-0-9.]*\) dB closer\*\* (claim: at least 6 dB; \([^)]*\)).*/\1 \2/p' "$dir/report.md" | head -n 1)
verdict=$(awk "BEGIN { print ($claim >= 6) ? \"holds\" : \"does NOT hold\" }")
awk "BEGIN { split(\"$said\", w, \" \"); exit !(w[1] - $claim < 0.006 && $claim - w[1] < 0.006) }" &&
    [ "${said#* }" = "$verdict" ] && grep -qF "($claim_strip)" "$dir/report.md" &&
    ok "claim 1 without the shared errors reported ($said) with its strip" ||
    fail "claim 1 without the shared errors reported" "summary $claim dB ($verdict), report says '$said'"
# the lighting stages: a plot each in the report, and their runs in results.csv: 14-bit normal codes within 50 dB
# of the reference with unquantised normals, the core's 14 fraction bits of shade and 8-bit front-weighted values
# within a level of their exact reference (docs/usage.md, "Lighting")
missing=""
for f in normal_bits.png shade_bits.png lit_table_bits.png; do
    [ -s "$dir/$f" ] && grep -q "($f)" "$dir/report.md" || missing="$missing $f"
done
grep -qF "## Lighting" "$dir/report.md" || missing="$missing '## Lighting'"
[ -z "$missing" ] && ok "the lighting stages' plots in the report" || fail "lighting plots" "missing:$missing"
row() { # FACTOR VALUE: "ref_psnr_db ref_max" of ml41-sharp-lit's run
    awk -F, -v f="$1" -v v="$2" 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
        $1 == "ml41-sharp-lit" && $(col["factor"] + 1) == f && $(col["value"] + 1) == v {
            print $(col["ref_psnr_db"] + 1), $(col["ref_max"] + 1) }' "$dir/results.csv"
}
# the view "30,20" is one quoted field holding a comma: every column after it is one further right
set -- $(row normal_bits 14) $(row shade_bits 14) $(row lit_table_bits 8)
if [ $# -eq 6 ] && awk "BEGIN { exit !($1 >= 50 && $4 <= 1 && $6 <= 1) }"; then
    ok "lit Marschner-Lobb: 14-bit normals $1 dB from unquantised ones; shade table at 14 fraction bits, lit table at 8 bits within a level"
else
    fail "lighting stages' figures" "normal_bits 14: '$1 $2', shade_bits 14: '$3 $4', lit_table_bits 8: '$5 $6'"
fi
