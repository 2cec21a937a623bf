#!/bin/sh
# SPDX-License-Identifier: MIT
# make bench: the frame-time protocol of Schulze et al. (90 frames, 2 degrees apart) as their Table 1 (every
# pre-integration variant against point sampling), the table builders, and instructions per frame from
# callgrind (which a noisy machine does not change). Frame times are measured in ROUNDS rounds (default 3):
# every variant's 90 frames once per round, the order rotated from round to round, ratios to point taken
# within a round; ms/frame is the median over rounds of each round's mean. Quote timings with the machine
# they came from.
# How long: 4 to 8 minutes on a 2-core machine, most of it the matrix (brainsmall's slow variants and preint2's
# 128^3 tables the longest);
# the tables, callgrind and the viewer take under a minute together. ROUNDS=1 saves about a minute.
cd "$(dirname "$0")/.." || exit 2
sim=${BUILD:-build}/volfix-sim
data=${VOLFIX_DATA:-}
size=${SIZE:-512x512}
rounds=${ROUNDS:-3}
if [ -n "$data" ] && [ -d "$data" ]; then
    volumes="$data/engine.nhdr $data/brainsmall.nhdr"
else
    volumes="phantom:shepp-logan:128"
    echo "== no sample volumes in VOLFIX_DATA='$data': a phantom stands in for engine and brainsmall"
fi

echo "== frame times, $size, preset ramp, 1 thread, $rounds rounds (progress on stderr)"
for v in $volumes; do
    "$sim" bench "$v" --matrix --rounds "$rounds" --preset ramp --size "$size" || exit 1
    echo
done

echo "== pre-integrated tables: incremental O(N^2) against the brute-force O(N^3) oracle"
for n in 256 1024; do
    "$sim" tables --preset sharp --size $n --repeat $([ $n = 256 ] && echo 9 || echo 1) || exit 1
done
echo

# A stale table is the serial part of a preint1 frame; with threads it is built in parts (vf_renderer_build_table_part).
v=$(echo $volumes | cut -d' ' -f1)
echo "== the table on threads: $(basename "$v") preint1, $size, the table rebuilt every frame, 3 rounds"
echo "   (one thread builds the diagonals as compositing reads them: its table time is begin's marking only)"
for n in 256 1024; do
    for t in 1 2; do
        "$sim" bench "$v" --table-size $n --threads $t --rounds 3 --preset ramp --size "$size" --json 2>/dev/null |
            sed -n 's/.*"ms_per_frame": \([0-9.]*\).*"tables_ms": \([0-9.]*\).*/\1 \2/p' |
            { read -r frame tables || exit 1
              printf 'table %4s, %s thread%s: frame %6.2f ms, of which the table %6.2f ms\n' $n $t \
                  "$([ $t = 1 ] || echo s)" "$frame" "$tables"; } || exit 1
    done
done
echo

# instructions VOLUME FRAMES [bench options]: callgrind's count of vfp_render_frame over the warm-up frame and
# FRAMES timed ones (inclusive), or nothing if callgrind gave none
instructions() {
    out=$(mktemp)
    v=$1 frames=$2
    shift 2
    valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect=vfp_render_frame \
        "$sim" bench "$v" --preset ramp --size "$size" --frames "$frames" --rounds 1 "$@" >/dev/null 2>&1
    total=$(sed -n 's/^summary: \([0-9]*\).*/\1/p' "$out")
    [ -z "$total" ] && total=$(sed -n 's/^totals: \([0-9]*\).*/\1/p' "$out")
    rm -f "$out"
    echo "$total"
}

if command -v valgrind >/dev/null; then
    echo "== instructions per frame (callgrind, vfp_render_frame inclusive, 2 frames averaged)"
    for v in $volumes; do
        point= lut=
        for mode in point preint1 preclass; do
            total=$(instructions "$v" 1 --mode "$mode")
            if [ -z "$total" ]; then
                echo "$(basename "$v") $mode: callgrind gave no count" >&2
                continue
            fi
            printf '%-24s %-8s %s instructions per frame\n' "$(basename "$v")" "$mode" "$((total / 2))"
            [ "$mode" = point ] && point=$total
            # the same ratio by instructions; the frame-rate ratio (the matrix's "x point") differs from it, either way (README)
            [ "$mode" != point ] && [ -n "$point" ] &&
                awk -v v="$(basename "$v")" -v m="$mode" -v p="$point" -v q="$total" \
                    'BEGIN { printf "%-24s point / %s = %.2f (instructions per frame)\n", v, m, p / q }'
        done
        # the lut builds its table once, in the first frame: a frame after that is the difference of 3 and 1
        # timed frames (4 and 2 rendered) over 2; it corrects the view table for each view
        one=$(instructions "$v" 1 --mode preint1 --correction lut)
        three=$(instructions "$v" 3 --mode preint1 --correction lut)
        if [ -n "$one" ] && [ -n "$three" ] && [ -n "$point" ]; then
            lut=$(((three - one) / 2))
            printf '%-24s %-8s %s instructions per frame after the first (lut)\n' "$(basename "$v")" preint1 "$lut"
            awk -v v="$(basename "$v")" -v p="$point" -v q="$lut" \
                'BEGIN { printf "%-24s point / preint1 lut = %.2f (instructions per frame)\n", v, p / 2 / q }'
        fi
        # preint2, lut-corrected as in the matrix: a frame after the first, as for preint1's lut
        for cfg in "64 nearest" "128 nearest" "64 trilinear"; do
            set -- $cfg
            one=$(instructions "$v" 1 --mode preint2 --correction lut --table2-size "$1" --lookup "$2")
            three=$(instructions "$v" 3 --mode preint2 --correction lut --table2-size "$1" --lookup "$2")
            if [ -n "$one" ] && [ -n "$three" ] && [ -n "$point" ]; then
                p2=$(((three - one) / 2))
                printf '%-24s %-8s %s instructions per frame after the first (lut, %s^3, %s)\n' "$(basename "$v")" \
                    preint2 "$p2" "$1" "$2"
                [ -n "$lut" ] && awk -v v="$(basename "$v")" -v q="$lut" -v r="$p2" \
                    'BEGIN { printf "%-24s preint1 lut / preint2 = %.2f (instructions per frame)\n", v, q / r }'
            fi
        done
    done
    # the warp alone: callgrind's count of vfi_warp_band (inclusive, every band), the warm-up frame and one timed
    # frame averaged; bench-peers puts it beside VolPack's (docs/peers.md)
    echo
    echo "== the warp's instructions per frame (callgrind, vfi_warp_band inclusive, 2 frames averaged)"
    for v in $volumes; do
        for mode in point preint1 preclass; do
            out=$(mktemp)
            valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect=vfi_warp_band \
                "$sim" bench "$v" --preset ramp --size "$size" --frames 1 --rounds 1 --mode "$mode" >/dev/null 2>&1
            n=$(sed -n 's/^summary: \([0-9]*\).*/\1/p' "$out")
            rm -f "$out"
            if [ -n "$n" ]; then
                printf '%-24s %-8s %s warp instructions per frame\n' "$(basename "$v")" "$mode" $((n / 2))
            else
                echo "$(basename "$v") $mode: callgrind gave no count" >&2
            fi
        done
    done
else
    echo "(valgrind not installed: no instruction counts)"
fi

# Memory: the renderer's arena (vf_renderer_memory) by mode, unlit and lit, for one thread; make bench-peers sets
# it beside VolPack's classified volume.
echo
echo "== memory, $size, preset ramp, one thread: the arena in MiB (vf_renderer_memory)"
for v in $volumes; do
    for lit in "" "--shade phong"; do
        for mode in point preint1 preclass; do
            line=$("$sim" bench "$v" --preset ramp --size "$size" --frames 1 --rounds 1 --mode "$mode" $lit | grep '^memory:')
            printf '%-24s %-8s %-5s %s\n' "$(basename "$v")" "$mode" "$([ -n "$lit" ] && echo lit || echo unlit)" "${line#memory: }"
        done
    done
done

# The viewer's input-to-frame latency: a scripted session on the headless board (240x240 RGB565 PNG frames)
# while the level knob moves the transfer function every 40 ms (tests/viewer/level.script), with the
# half-resolution preview (the default) and without it (--preview 1: every frame from the full volume).
viewer=${BUILD:-build}/volfix
if [ -x "$viewer" ]; then
    v=$(echo $volumes | cut -d' ' -f1)
    echo
    echo "== viewer: input-to-frame latency, $(basename "$v") at 240x240, transfer function moving (level.script)"
    tmp=$(mktemp -d)
    for preview in 2 1; do
        "$viewer" --board boards/host-headless.board "$v" --script tests/viewer/level.script --device "$tmp/f" \
            --log "$tmp/log" --preview $preview | tail -n 1 | sed "s/^volfix:/preview $preview:/"
        # per frame: render (reclassification included) and present (PNG written) times, medians
        for col in 5 8; do
            awk -v c=$col -v all=$((preview == 1)) '$3 == "preview" || all { print $c }' "$tmp/log" | sort -n |
                awk '{ x[NR] = $1 } END { if (NR) printf "%s %.1f", NR, x[int((NR + 1) / 2)] }'
            echo
        done | { read -r n render; read -r _ present; echo "    $n frames: render median $render ms (reclassifying included), present median $present ms"; }
        rm -rf "$tmp/f"
    done
    rm -rf "$tmp"
fi
