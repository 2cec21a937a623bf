#!/bin/sh
# SPDX-License-Identifier: MIT
# The viewer (build/volfix) end to end on the headless board: scripted knob sessions write PNG frames and a log
# whose every line gives the volfix-sim render options of its frame; every frame must equal volfix-sim's picture
# pixel for pixel, previews (--downsample 2) and full-quality frames alike. Also: frames only when something
# changes, the last picture is full quality at the expected angles, SIGTERM leaves cleanly, and bad input gets
# one line naming what was wrong.
# run alone: the level session needs a frame within the 40 ms the knob rests at the top of its swing, which
# suites running beside it on the same processors can take away (tests/run.sh).
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
viewer=$build/volfix sim=$build/volfix-sim
data=${VOLFIX_DATA:-}
board=boards/host-headless.board
suite=viewer program=$viewer
. tests/check.inc

# frames_match NAME VOLUME DIR LOG: every frame in LOG is DIR/frame-N.png and equals volfix-sim render's picture
frames_match() {
    name=$1 volume=$2 dir=$3 log=$4
    n=0 bad=""
    while IFS= read -r line; do
        frame=$(echo "$line" | cut -d' ' -f2)
        opts=${line#*: }
        png=$(printf '%s/frame-%05d.png' "$dir" "$frame")
        # shellcheck disable=SC2086 # opts is a list of options
        if [ ! -f "$png" ]; then
            bad="frame $frame: $png is missing"
        elif ! "$sim" render "$volume" $opts -o "$tmp/sim.png" >/dev/null 2>"$tmp/sim.err"; then
            bad="frame $frame: volfix-sim render $opts failed: $(cat "$tmp/sim.err")"
        elif ! "$sim" diff "$png" "$tmp/sim.png" --max 0 >"$tmp/diff.out" 2>&1; then
            bad="frame $frame ($opts): $(cat "$tmp/diff.out")"
        fi
        [ -n "$bad" ] && break
        n=$((n + 1))
    done <"$log"
    files=$(find "$dir" -name 'frame-*.png' | wc -l)
    if [ -n "$bad" ]; then
        fail "$name" "$bad"
    elif [ "$n" -eq 0 ] || [ "$files" -ne "$n" ]; then
        fail "$name" "$n frames in the log, $files PNG files"
    else
        ok "$name ($n frames equal volfix-sim render)"
    fi
}

# run_viewer NAME ARGS...: run it, status in $status, output in $tmp/NAME.out and .err
run_viewer() {
    name=$1
    shift
    "$viewer" "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"
    status=$?
}

# 1. The spin session on engine (256x256x128, from the sample volumes) at 240x240 RGB565.
if [ ! -f "$data/engine.nhdr" ]; then
    fail "spin runs" "no engine.nhdr in VOLFIX_DATA='$data': set VOLFIX_DATA to the folder of sample volumes"
else
    run_viewer spin --board "$board" "$data/engine.nhdr" --script tests/viewer/spin.script --device "$tmp/spin" \
        --log "$tmp/spin.log"
fi
if [ ! -f "$data/engine.nhdr" ]; then
    :
elif [ $status -ne 0 ]; then
    fail "spin runs" "status $status: $(cat "$tmp/spin.err")"
else
    ok "spin runs"
    frames_match "spin frames equal volfix-sim" "$data/engine.nhdr" "$tmp/spin" "$tmp/spin.log"
    last=$(tail -n 1 "$tmp/spin.log")
    case "$last" in
    *" full "*"--view 90,30,0 --zoom 1.21"*"--format rgb565") ok "spin ends in full quality at 90,30 zoom 1.21" ;;
    *) fail "spin ends in full quality at 90,30 zoom 1.21" "last frame: $last" ;;
    esac
    frames=$(wc -l <"$tmp/spin.log")
    # 16 detents: at most one preview each, the first preview, a full frame at the start (if it beats the first
    # knob) and one at the end
    [ "$frames" -le 19 ] && ok "spin renders only for changes ($frames frames for 16 detents)" ||
        fail "spin renders only for changes" "$frames frames for 16 detents"
    grep -q 'input-to-frame latency over 16 inputs: median' "$tmp/spin.out" && ok "spin reports the latency" ||
        fail "spin reports the latency" "$(cat "$tmp/spin.out")"
fi

# 2. Nothing happens: one preview, one full frame, nothing more.
printf '# nothing\n800 quit\n' >"$tmp/idle.script"
run_viewer idle --board "$board" phantom:marschner-lobb:64 --script "$tmp/idle.script" --device "$tmp/idle" \
    --log "$tmp/idle.log"
if [ $status -eq 0 ] && [ "$(wc -l <"$tmp/idle.log")" -eq 2 ] && sed -n 2p "$tmp/idle.log" | grep -q ' full '; then
    ok "an idle session shows a preview, then full quality, then nothing"
else
    fail "an idle session shows a preview, then full quality, then nothing" "status $status: $(cat "$tmp/idle.log")"
fi
frames_match "idle frames equal volfix-sim" phantom:marschner-lobb:64 "$tmp/idle" "$tmp/idle.log"

# 2b. An anisotropic volume (headsq, spacing 3.2, 3.2, 1.5): full-quality frames take 2 rays per voxel column,
# previews one, and the first line says so; each frame's log line still gives volfix-sim's same picture.
if [ -f "$data/headsq.nhdr" ]; then
    run_viewer aniso --board "$board" "$data/headsq.nhdr" --script "$tmp/idle.script" --device "$tmp/aniso" \
        --log "$tmp/aniso.log"
    if [ $status -eq 0 ] && grep -q 'anisotropic spacing 2.13x: unlit full-quality frames at 2 rays' "$tmp/aniso.out" &&
        sed -n 1p "$tmp/aniso.log" | grep -q ' preview .*--rays 1$' &&
        sed -n 2p "$tmp/aniso.log" | grep -q ' full .*--rays 2$'; then
        ok "headsq: full quality at 2 rays, previews at 1, said at start"
    else
        fail "headsq: full quality at 2 rays, previews at 1, said at start" \
            "status $status: $(cat "$tmp/aniso.out" "$tmp/aniso.log")"
    fi
    frames_match "headsq frames equal volfix-sim" "$data/headsq.nhdr" "$tmp/aniso" "$tmp/aniso.log"
    run_viewer aniso1 --board "$board" "$data/headsq.nhdr" --rays 1 --script "$tmp/idle.script" \
        --device "$tmp/aniso1" --log "$tmp/aniso1.log"
    sed -n 2p "$tmp/aniso1.log" | grep -q ' full .*--rays 1$' && ! grep -q anisotropic "$tmp/aniso1.out" &&
        ok "headsq with --rays 1: full quality at one ray" ||
        fail "headsq with --rays 1: full quality at one ray" "$(cat "$tmp/aniso1.out" "$tmp/aniso1.log")"
else
    fail "headsq session" "no headsq.nhdr in VOLFIX_DATA='$data'"
fi

# 3. The transfer function moving, presets and modes cycling (the latency session), on a phantom.
run_viewer level --board "$board" phantom:shepp-logan:64 --script tests/viewer/level.script --device "$tmp/level" \
    --log "$tmp/level.log"
if [ $status -ne 0 ]; then
    fail "level runs" "status $status: $(cat "$tmp/level.err")"
else
    frames_match "level frames equal volfix-sim" phantom:shepp-logan:64 "$tmp/level" "$tmp/level.log"
    last=$(tail -n 1 "$tmp/level.log")
    case "$last" in
    *" full "*"--tf-move 0,1 --preset sharp --mode preclass"*) ok "level: back to shift 0, next preset, next mode" ;;
    *) fail "level: back to shift 0, next preset, next mode" "last frame: $last" ;;
    esac
    grep -q -- '--tf-move 1,1 ' "$tmp/level.log" && ok "level: the function moved a whole window" ||
        fail "level: the function moved a whole window" "no frame with --tf-move 1,1"
fi

# 3b. Lighting from the knobs and buttons (tests/viewer/light.script): shading toggled on, the light moved by a
# knob that a button cycles, shading off and on from that knob; every frame (previews too) equals volfix-sim's
# picture with the lighting options its log line gives.
run_viewer light --board "$board" phantom:marschner-lobb:64 --preset sharp --script tests/viewer/light.script \
    --device "$tmp/light" --log "$tmp/light.log"
if [ $status -ne 0 ]; then
    fail "light runs" "status $status: $(cat "$tmp/light.err")"
else
    frames_match "light frames equal volfix-sim" phantom:marschner-lobb:64 "$tmp/light" "$tmp/light.log"
    last=$(tail -n 1 "$tmp/light.log")
    case "$last" in
    *" full "*"--tf-move 0.02,1 --preset sharp --mode preint1 --shade phong --light 29.99"*",-20.00"*)
        ok "light: shaded, the light at 30,-20, the knob back on level" ;;
    *) fail "light: shaded, the light at 30,-20, the knob back on level" "last frame: $last" ;;
    esac
    head -n 1 "$tmp/light.log" | grep -q -- '--shade none' && ok "light: the session starts unlit" ||
        fail "light: the session starts unlit" "first frame: $(head -n 1 "$tmp/light.log")"
    # after the light reached 30,-20: a frame unlit (the shade knob turned back), then lit again
    after=$(grep -n -- '--light 29.99[0-9]*,-20.00' "$tmp/light.log" | head -n 1 | cut -d: -f1)
    off=$(sed -n "${after:-1},\$p" "$tmp/light.log" | grep -c -- '--shade none')
    [ -n "$after" ] && [ "$off" -ge 1 ] && ok "light: shading turned off from the knob, then on again" ||
        fail "light: shading turned off from the knob, then on again" "$(cut -d: -f2- "$tmp/light.log" | tr '\n' '|')"
fi

# 4. A panel mounted a quarter turn, not square, without the preview: the view is rolled back by the mounting.
sed -e 's/^display.width = .*/display.width = 200/' -e 's/^display.height = .*/display.height = 120/' \
    -e 's/^display.format = .*/display.format = xrgb8888\ndisplay.rotation = 90/' "$board" >"$tmp/rot.board"
printf '100 turn 0 -2\n600 quit\n' >"$tmp/rot.script"
run_viewer rot --board "$tmp/rot.board" phantom:shepp-logan:32 --script "$tmp/rot.script" --device "$tmp/rot" \
    --log "$tmp/rot.log" --preview 1
if [ $status -eq 0 ] && tail -n 1 "$tmp/rot.log" | grep -q ' full .*--view 20,20,270 .*--size 200x120 --format xrgb8888$' &&
    ! grep -q preview "$tmp/rot.log"; then
    ok "rotation 90: roll 270, every frame full quality without the preview"
    frames_match "rotated frames equal volfix-sim" phantom:shepp-logan:32 "$tmp/rot" "$tmp/rot.log"
else
    fail "rotation 90: roll 270, every frame full quality without the preview" "status $status: $(cat "$tmp/rot.log" "$tmp/rot.err")"
fi

# 5. The overlay: drawn over a small corner only.
run_viewer overlay --board "$board" phantom:marschner-lobb:64 --script "$tmp/idle.script" --device "$tmp/ov" \
    --log "$tmp/ov.log" --overlay
opts=$(tail -n 1 "$tmp/ov.log" | sed 's/^[^:]*: //')
# shellcheck disable=SC2086
"$sim" render phantom:marschner-lobb:64 $opts -o "$tmp/ov-sim.png" >/dev/null 2>&1
pct=$("$sim" diff "$tmp/ov/frame-00001.png" "$tmp/ov-sim.png" --json 2>&1 | sed -n 's/.*"over1_pct": \([0-9.]*\).*/\1/p')
if [ -n "$pct" ] && awk -v p="$pct" 'BEGIN { exit !(p > 0.5 && p < 10) }'; then
    ok "overlay covers $pct% of the frame"
else
    fail "overlay covers a small part of the frame" "over1_pct '$pct'"
fi

# 6. SIGTERM and SIGINT: the viewer leaves at once, cleanly, with its summary, in the status a shell gives a
# process the signal ended (143, 130). A script without quit keeps it running until then.
printf '100 turn 0 1\n' >"$tmp/forever.script"
for sig in TERM:143 INT:130; do
    "$viewer" --board "$board" phantom:sphere:32 --script "$tmp/forever.script" --device "$tmp/term${sig%:*}" \
        >"$tmp/term.out" 2>&1 &
    pid=$!
    i=0
    while [ $i -lt 50 ] && [ "$(find "$tmp/term${sig%:*}" -name '*.png' 2>/dev/null | wc -l)" -lt 2 ]; do
        sleep 0.1
        i=$((i + 1))
    done
    kill -"${sig%:*}" $pid
    wait $pid
    status=$?
    if [ $status -eq "${sig#*:}" ] && grep -q '^volfix: [0-9]* frames' "$tmp/term.out"; then
        ok "SIG${sig%:*} exits ${sig#*:} with the summary"
    else
        fail "SIG${sig%:*} exits ${sig#*:} with the summary" "status $status: $(cat "$tmp/term.out")"
    fi
done
# with --frames, the same script ends the run once its last picture is shown
if timeout 20 "$viewer" --board "$board" phantom:sphere:32 --script "$tmp/forever.script" --device "$tmp/ends" \
    --frames 100 >"$tmp/ends.out" 2>&1; then
    ok "a script without quit ends with --frames"
else
    fail "a script without quit ends with --frames" "status $?: $(tail -n 1 "$tmp/ends.out")"
fi

# 7. Bad input: status 2 and one line that says what was wrong.
expect_error "no board" "volfix: no board given" phantom:sphere:8
expect_error "no volume" "volfix: no volume given" --board "$board"
expect_error "missing board file" "boards/nope.board" --board boards/nope.board phantom:sphere:8
printf 'display = png\ninput = script\nknob.0.action = spin\n' >"$tmp/typo.board"
expect_error "board with a typo" "typo.board:3:" --board "$tmp/typo.board" phantom:sphere:8
expect_error "missing script" "nope.script" --board "$board" phantom:sphere:8 --script "$tmp/nope.script" --device "$tmp/x"
expect_error "missing volume" "nope.nhdr" --board "$board" "$tmp/nope.nhdr" --script "$tmp/idle.script" --device "$tmp/x"
expect_error "unknown preset" "--preset bones: expected ramp, sharp" --board "$board" phantom:sphere:8 --preset bones --script "$tmp/idle.script"
expect_error "bad preview" "--preview 0: expected an integer from 1 (off) to 8" --board "$board" phantom:sphere:8 --preview 0
expect_error "bad rays" "--rays 3: expected 1, 2 or 4" --board "$board" phantom:sphere:8 --rays 3
expect_error "unknown option" "unknown option or extra argument '--colour'" --board "$board" phantom:sphere:8 --colour red
touch "$tmp/file"
expect_error "frames directory is a file" "$tmp/file" --board "$board" phantom:sphere:8 --script "$tmp/idle.script" --device "$tmp/file"
"$viewer" --help >"$tmp/out" 2>&1 && grep -q '^usage: volfix --board BOARD VOLUME' "$tmp/out" && ok "--help" ||
    fail "--help" "$(head -n 2 "$tmp/out")"
version=$(sed -n 's/^#define VF_VERSION_[A-Z]* *\([0-9]*\)$/\1/p' core/volfix.h | paste -sd. -)
[ "$("$viewer" --version 2>&1)" = "volfix $version" ] && [ "$("$sim" --version 2>&1)" = "volfix-sim $version" ] &&
    ok "--version: volfix $version, as core/volfix.h says" ||
    fail "--version" "volfix says '$("$viewer" --version 2>&1)', volfix-sim '$("$sim" --version 2>&1)';" \
        "expected $version"
# --board NAME (no slash) is an installed board; the build's own volfix looks where make install puts them
dir=$("$viewer" --help | sed -n 's/^ *in \(\/.*\)$/\1/p')
expect_error "board name not installed" "--board host-nope: no board of that name in $dir" --board host-nope \
    phantom:sphere:8
[ -n "$dir" ] && ok "--help names the installed boards' folder ($dir)" || fail "--help names the boards' folder" \
    "$("$viewer" --help | grep -A 2 -- '--board')"
