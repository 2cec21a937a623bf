#!/bin/sh
# make bench: the frame-time protocol of Schulze et al. (90 frames, 2 degrees apart) on the shared volumes,
# for both modes, and instructions per frame from callgrind (which a noisy machine does not change).
# Timings are medians and means of one run on this machine; quote them with the machine they came from.
cd "$(dirname "$0")/.." || exit 2
sim=${BUILD:-build}/volfix-sim
data=${VOLFIX_DATA:-../shared/data}
size=${SIZE:-512x512}
if [ -d "$data" ]; then volumes="$data/engine.nhdr $data/brainsmall.nhdr"; else volumes="phantom:shepp-logan:128"; fi

echo "== frame times ($size, preset ramp, 1 thread)"
for v in $volumes; do
    for mode in point preint1; do
        "$sim" bench "$v" --mode "$mode" --preset ramp --size "$size" || exit 1
        echo
    done
done

if command -v valgrind >/dev/null; then
    echo "== instructions per frame (callgrind, vfp_render_frame inclusive, 2 frames averaged)"
    for v in $volumes; do
        for mode in point preint1; do
            out=$(mktemp)
            valgrind --tool=callgrind --callgrind-out-file="$out" --toggle-collect=vfp_render_frame \
                "$sim" bench "$v" --mode "$mode" --preset ramp --size "$size" --frames 1 >/dev/null 2>&1
            total=$(sed -n 's/^summary: \([0-9]*\).*/\1/p' "$out")
            [ -z "$total" ] && total=$(sed -n 's/^totals: \([0-9]*\).*/\1/p' "$out")
            printf '%-24s %-8s %s instructions per frame\n' "$(basename "$v")" "$mode" "$((total / 2))"
            rm -f "$out"
        done
    done
else
    echo "(valgrind not installed: no instruction counts)"
fi
