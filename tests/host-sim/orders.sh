#!/bin/sh
# SPDX-License-Identifier: MIT
# Is second order better? tools/eval-orders.sh --quick (Marschner-Lobb 41^3, sharp, 30,20, 128x128) and what the
# full evaluation (docs/study.md) supports there: at equal table resolution (64 a side) preint2 is closer than
# preint1 to the smooth truth (Marschner-Lobb's own function), in PSNR and in xi; and against the trilinear truth,
# which is linear between slices along the axis, preint1 stays the closer. (On neghip and bucky preint2 is not
# closer to the smooth truth: docs/study.md says so; this test asserts only what holds.)
cd "$(dirname "$0")/../.." || exit 2
sim=${BUILD:-build}/volfix-sim
suite=orders program=$sim
. tests/check.inc

if SIZE=128x128 sh tools/eval-orders.sh --quick -o "$tmp/eval" >"$tmp/table" 2>"$tmp/err" &&
    [ "$(head -n 1 "$tmp/eval/orders.csv")" = "scene,held_back,view,config,truth,psnr_db,xi" ]; then
    ok "eval-orders.sh --quick writes orders.csv"
    pick() { # config truth column(6 psnr, 7 xi)
        awk -F, -v c="$1" -v t="$2" -v k="$3" '$4 == c && $5 == t { print $k }' "$tmp/eval/orders.csv"
    }
    p2=$(pick preint2-64 smooth 6) p1=$(pick preint1-64 smooth 6)
    x2=$(pick preint2-64 smooth 7) x1=$(pick preint1-64 smooth 7)
    if awk -v a="$p2" -v b="$p1" -v x="$x2" -v y="$x1" 'BEGIN { exit !(a > b && x < y && y > 0) }'; then
        ok "ml41 30,20: preint2 closer to the smooth truth than preint1 at 64 ($p2 > $p1 dB, xi $x2 < $x1)"
    else
        fail "ml41 smooth truth" "preint2 $p2 dB xi $x2, preint1 $p1 dB xi $x1"
    fi
    t2=$(pick preint2-64 trilinear 6) t1=$(pick preint1-64 trilinear 6)
    if awk -v a="$t2" -v b="$t1" 'BEGIN { exit !(b > a && a > 0) }'; then
        ok "ml41 30,20: preint1 closer to the trilinear truth ($t1 > $t2 dB)"
    else
        fail "ml41 trilinear truth" "preint2 $t2 dB, preint1 $t1 dB"
    fi
    grep -q '^| ml41 | 30,20 |' "$tmp/table" && ok "eval-orders.sh prints the table" ||
        fail "eval-orders.sh table" "$(head -n 5 "$tmp/table" | tr '\n' '|')"
else
    fail "eval-orders.sh --quick" "$(cat "$tmp/err")"
fi

# the 3D table's precision study, quick: every configuration within 2 levels and 50 dB of the reference (the
# acceptance of the order-2 issue), 8-bit entries take less memory than 16-bit, a size for each board
if "$sim" study --order2-only --quick -o "$tmp/o2" >"$tmp/out" 2>"$tmp/err" && [ -s "$tmp/o2/order2.md" ]; then
    rows=$(awk -F, 'NR > 1' "$tmp/o2/order2.csv" | wc -l)
    bad=$(awk -F, 'NR > 1 && ($7 > 2 || $6 < 50) { print $2 " " $3 " " $4 "-bit: " $6 " dB, max " $7 }' \
        "$tmp/o2/order2.csv")
    [ "$rows" -eq 26 ] && [ -z "$bad" ] && ok "study --order2-only --quick: 26 runs, all within 2 levels and 50 dB" ||
        fail "study --order2-only" "$rows rows; $bad"
    if awk -F, '$2 == "preint2" && $3 == 64 && $5 == 256 { m[$4] = $12 } END { exit !(m[8] < m[16] && m[8] > 0) }' \
        "$tmp/o2/order2.csv"; then
        ok "study --order2-only: 8-bit 3D table smaller than 16-bit"
    else
        fail "study --order2-only memory" "$(grep 'preint2,64' "$tmp/o2/order2.csv" | head -n 4 | tr '\n' '|')"
    fi
    [ "$(grep -c '^- .* board: \|^- 256 KB microcontroller: ' "$tmp/o2/order2.md")" -eq 3 ] &&
        ok "study --order2-only: a size for each board" || fail "study --order2-only boards" "$(tail -n 4 "$tmp/o2/order2.md")"
else
    fail "study --order2-only --quick" "$(cat "$tmp/err" | tail -n 2)"
fi
