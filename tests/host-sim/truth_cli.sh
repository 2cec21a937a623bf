#!/bin/sh
# SPDX-License-Identifier: MIT
# The ground truth from the outside: compare --against truth, render --truth, and the ray study (volfix-sim ray)
# with and without gnuplot.
cd "$(dirname "$0")/../.." || exit 2
sim=${BUILD:-build}/volfix-sim
suite=truth-cli program=$sim
. tests/check.inc

# compare against the truth
if "$sim" compare phantom:sphere:24 --size 64x64 --against truth --json >"$tmp/out" 2>"$tmp/err" &&
    grep -q '"against": "truth"' "$tmp/out" && grep -q '"psnr_db": [0-9]' "$tmp/out" &&
    grep -q '"max_abs": ' "$tmp/out" && grep -q '"mean_abs": ' "$tmp/out" && grep -q '"over1_pct": ' "$tmp/out"; then
    ok "compare --against truth --json"
else
    fail "compare --against truth --json" "$(cat "$tmp/out" "$tmp/err" | head -n 3 | tr '\n' '|')"
fi
if "$sim" compare phantom:sphere:24 --size 64x64 --against reference --json >"$tmp/out" 2>&1 &&
    grep -q '"against": "reference"' "$tmp/out"; then
    ok "compare --against reference"
else
    fail "compare --against reference" "$(head -n 2 "$tmp/out")"
fi
expect_error "bad --against" "--against core: expected reference or truth" compare phantom:sphere:8 --against core
"$sim" compare --help >"$tmp/out" 2>&1 && grep -q -- '--against' "$tmp/out" && ok "compare --help names --against" ||
    fail "compare --help" "no --against"

# the smooth truth: a phantom's function, Catmull-Rom for data without one; unlit; only for the truth
if "$sim" compare phantom:marschner-lobb:21 --size 48x48 --preset sharp --against truth --truth-filter smooth \
    --json >"$tmp/smooth" 2>"$tmp/err" &&
    "$sim" compare phantom:marschner-lobb:21 --size 48x48 --preset sharp --against truth --json >"$tmp/tri" &&
    ! cmp -s "$tmp/smooth" "$tmp/tri" && grep -q '"psnr_db": [0-9]' "$tmp/smooth"; then
    ok "compare --truth-filter smooth differs from trilinear"
else
    fail "compare --truth-filter smooth" "$(cat "$tmp/err" "$tmp/smooth" | head -n 3 | tr '\n' '|')"
fi
"$sim" render phantom:shepp-logan:16 --size 32x32 --truth --truth-filter catmull-rom -o "$tmp/cr.png" \
    >/dev/null 2>"$tmp/err" && [ -s "$tmp/cr.png" ] && ok "render --truth --truth-filter catmull-rom" ||
    fail "render --truth-filter catmull-rom" "$(cat "$tmp/err")"
expect_error "bad --truth-filter" "--truth-filter cubic: expected trilinear, smooth, catmull-rom, bspline or analytic" \
    render phantom:sphere:8 --truth --truth-filter cubic -o "$tmp/x.png"
expect_error "--truth-filter without the truth" "--truth-filter: only the ground truth has a filter" \
    compare phantom:sphere:8 --truth-filter smooth
expect_error "analytic without a function" "has no analytic function" \
    render phantom:shepp-logan:8 --truth --truth-filter analytic -o "$tmp/x.png"
expect_error "smooth truth unlit only" "the lit truth reconstructs trilinearly only" \
    render phantom:sphere:8 --truth --truth-filter smooth --shade phong -o "$tmp/x.png"

# render the truth
if "$sim" render phantom:sphere:16 --size 48x40 --truth -o "$tmp/truth.png" >"$tmp/out" 2>"$tmp/err" &&
    [ -s "$tmp/truth.png" ] && grep -q '(ground truth)' "$tmp/out"; then
    ok "render --truth"
else
    fail "render --truth" "$(cat "$tmp/err")"
fi
expect_error "render --truth --reference" "give --reference or --truth, not both" render phantom:sphere:8 --truth \
    --reference -o "$tmp/x.png"
expect_error "compare takes no --truth" "--truth: unknown option" compare phantom:sphere:8 --truth

# the ray study
dir="$tmp/ray"
if "$sim" ray phantom:marschner-lobb:41 --size 128x128 -o "$dir" >"$tmp/out" 2>"$tmp/err"; then
    rows=$(wc -l <"$dir/ray.csv")
    if [ "$(head -n 1 "$dir/ray.csv")" != "t,signal,order0_1,order1_1,order2_1,order0_2,order1_2,order2_2,preint2" ] ||
        [ "$rows" -lt 2000 ]; then
        fail "ray: ray.csv" "header '$(head -n 1 "$dir/ray.csv")', $rows lines"
    else
        ok "ray: ray.csv"
    fi
    if [ "$(head -n 1 "$dir/xi.csv")" = "order,spacing,xi" ] && [ "$(wc -l <"$dir/xi.csv")" -eq 7 ]; then
        ok "ray: xi.csv"
    else
        fail "ray: xi.csv" "$(tr '\n' '|' <"$dir/xi.csv")"
    fi
    # the El Hajjar ranking on a smooth signal: order 2 beats order 1 beats order 0 at spacing 1
    if awk -F, 'NR > 1 && $2 == 1 { xi[$1] = $3 } END { exit !(xi[2] < xi[1] && xi[1] < xi[0]) }' "$dir/xi.csv"; then
        ok "ray: xi falls with the order at spacing 1"
    else
        fail "ray: xi order" "$(tr '\n' '|' <"$dir/xi.csv")"
    fi
    grep -q '^order 2 ' "$tmp/out" && ok "ray: summary" || fail "ray: summary" "$(head -n 3 "$tmp/out")"
    if command -v gnuplot >/dev/null 2>&1; then
        [ -s "$dir/ray.png" ] && ok "ray: ray.png" || fail "ray: ray.png" "missing ($(cat "$tmp/err"))"
    else
        echo "# skip: gnuplot not installed, no ray.png expected"
    fi
else
    fail "ray" "status $?: $(cat "$tmp/err")"
fi

# preint2's own segments over the smooth signal (Marschner-Lobb's function): the renderers' xi rank point >
# preint1 > preint2 there, and at k = 2m + 1/2 the segment is the quadratic through the samples of slices 2m,
# 2m + 1, 2m + 2 (the renderer pairs slices from even k), clamped to their range
dir="$tmp/rays"
if "$sim" ray phantom:marschner-lobb:41 --size 128x128 --truth-filter smooth -o "$dir" >"$tmp/out" 2>"$tmp/err" &&
    grep -q 'smooth signal' "$tmp/out" && [ "$(head -n 1 "$dir/renderers.csv")" = "renderer,k_from,k_to,xi" ]; then
    if awk -F, 'NR > 1 { xi[$1] = $4 } END { exit !(xi["preint2"] < xi["preint1"] && xi["preint1"] < xi["point"]) }' \
        "$dir/renderers.csv"; then
        ok "ray: the renderers' xi on the smooth signal, preint2 < preint1 < point"
    else
        fail "ray: renderers' xi" "$(tr '\n' '|' <"$dir/renderers.csv")"
    fi
    if awk -F, 'NR == 2 { ra = $1 } NR > 1 && $9 != "nan" {
            k = $1 + 0; if (k == int(k)) s[k] = $2; if (k - int(k) == 0.5) half[k] = $9 }
        END { n = 0
            for (k in half) { m = int(k); if (m % 2) continue
                f = s[m]; mid = s[m + 1]; b = s[m + 2]; if (b == "") continue
                A = 2 * f - 4 * mid + 2 * b; B = -3 * f + 4 * mid - b; t = 0.25; p = (A * t + B) * t + f
                lo = f; if (mid < lo) lo = mid; if (b < lo) lo = b; hi = f; if (mid > hi) hi = mid; if (b > hi) hi = b
                if (p < lo) p = lo; if (p > hi) p = hi
                d = p - half[k]; if (d < 0) d = -d; if (d > 1e-3) { print "k " k ": " half[k] " not " p; exit 1 }
                n++ }
            exit !(n >= 10) }' "$dir/ray.csv"; then
        ok "ray: preint2 segments are the even-paired clamped quadratics"
    else
        fail "ray: preint2 segments" "not the renderer's slabs"
    fi
else
    fail "ray --truth-filter smooth" "$(cat "$tmp/err")"
fi

# without gnuplot: one line saying so, the CSVs all the same, status 0
if PATH=/nonexistent "$sim" ray phantom:marschner-lobb:41 --size 64x64 --pixel 30,33 -o "$tmp/nogp" >"$tmp/out" \
    2>"$tmp/err" && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q 'gnuplot' "$tmp/err" && [ -s "$tmp/nogp/ray.csv" ] &&
    [ -s "$tmp/nogp/xi.csv" ] && [ ! -e "$tmp/nogp/ray.png" ]; then
    ok "ray without gnuplot"
else
    fail "ray without gnuplot" "$(tr '\n' '|' <"$tmp/err")"
fi
expect_error "ray misses" "misses the volume or crosses fewer than 4" ray phantom:marschner-lobb:41 --size 64x64 \
    --pixel 0,0 -o "$tmp/miss"
expect_error "ray bad pixel" "--pixel 3: expected X,Y" ray phantom:sphere:8 --pixel 3 -o "$tmp/x"
expect_error "ray no output" "no output folder" ray phantom:sphere:8
"$sim" ray --help >"$tmp/out" 2>&1 && grep -q '^usage: volfix-sim ray' "$tmp/out" && ok "ray --help" ||
    fail "ray --help" "$(head -n 1 "$tmp/out")"
