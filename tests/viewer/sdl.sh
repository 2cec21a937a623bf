#!/bin/sh
# SPDX-License-Identifier: MIT
# The viewer in an SDL window on a real X server (Xvfb): keys typed with xdotool turn the volume through the
# SDL input backend, a screenshot of the screen shows the window holding exactly the picture volfix-sim
# renders for the logged view, and Escape (the board's quit button) ends it.
# Needs xvfb-run, xdotool and ImageMagick's import and convert (make test installs them: tools/deps.sh).
# run alone: keys are typed against the clock (xdotool, waits of a few seconds), which suites running beside it
# on the same processors can outrun (tests/run.sh).
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
viewer=$build/volfix sim=$build/volfix-sim
suite=viewer-sdl
. tests/check.inc
# Under AddressSanitizer (make SAN=1): SDL's X11 and D-Bus libraries keep allocations to the end that
# LeakSanitizer reports as leaks, some from libraries already unloaded (no name to suppress). The viewer's own
# memory is leak-checked by viewer.sh, whose png display runs the same loop without SDL.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"


# what it needs: the SDL backend compiled in, and the X tools
if ! grep -q '^BACKENDS = .*SDL' "$build/config.mk" 2>/dev/null; then
    echo "skip - viewer-sdl: the viewer is built without SDL (install libsdl2-dev, then make)"
    exit 0
fi
missing=""
for tool in xvfb-run:xvfb xauth:xauth xdotool:xdotool import:imagemagick convert:imagemagick; do
    command -v "${tool%%:*}" >/dev/null || missing="$missing ${tool#*:}"
done
if [ -n "$missing" ]; then
    echo "skip - viewer-sdl: missing tools (install$(echo "$missing" | tr ' ' '\n' | sort -u | tr '\n' ' ' |
        sed 's/ $//'))"
    exit 0
fi
if ! "$viewer" --help >/dev/null || ! grep -q '^display = sdl' boards/host-sdl.board; then
    fail "viewer" "no $viewer or boards/host-sdl.board"
    exit 1
fi

# Inside Xvfb: wait for the full-quality frame, type two Right arrows (azimuth +10), wait for its full frame,
# take the screenshot, press Escape.
cat >"$tmp/session.sh" <<EOF
"$viewer" --board boards/host-sdl.board phantom:marschner-lobb:64 --log "$tmp/log" >"$tmp/out" 2>&1 &
pid=\$!
wait_for() { i=0; while [ \$i -lt 100 ] && ! grep -q -- "\$1" "$tmp/log" 2>/dev/null; do sleep 0.1; i=\$((i + 1)); done; }
wait_for ' full .*--view 30,20,0 '
xdotool search --sync --name '^volfix' windowfocus --sync 2>/dev/null || true
xdotool key Right
sleep 0.2
xdotool key Right
wait_for ' full .*--view 40,20,0 '
import -window root "$tmp/shot.png"
xdotool key Escape
i=0; while [ \$i -lt 100 ] && kill -0 \$pid 2>/dev/null; do sleep 0.1; i=\$((i + 1)); done
kill -0 \$pid 2>/dev/null && { echo "still running after Escape" >"$tmp/how"; kill -TERM \$pid; }
wait \$pid
echo \$? >"$tmp/status"
EOF
timeout 120 xvfb-run -a -s "-screen 0 640x560x24" sh "$tmp/session.sh" >"$tmp/xvfb.out" 2>&1

status=$(cat "$tmp/status" 2>/dev/null)
[ "$status" = 0 ] && [ ! -f "$tmp/how" ] && grep -q '^volfix: [0-9]* frames' "$tmp/out" && ok "opens a window and quits on Escape" ||
    fail "opens a window and quits on Escape" "status '$status': $(cat "$tmp/how" "$tmp/out" "$tmp/xvfb.out" 2>/dev/null | head -n 5)"

last=$(tail -n 1 "$tmp/log" 2>/dev/null)
case "$last" in
*" full "*"--view 40,20,0 "*"--size 480x480"*) ok "two Right keys turn the azimuth by 10 degrees" ;;
*) fail "two Right keys turn the azimuth by 10 degrees" "last frame: $last" ;;
esac

# The window is centred on the 640x560 screen: its 480x480 picture starts at (80, 40).
opts=${last#*: }
# shellcheck disable=SC2086 # opts is a list of options
if [ -f "$tmp/shot.png" ] && convert "$tmp/shot.png" -crop 480x480+80+40 +repage "$tmp/window.png" &&
    "$sim" render phantom:marschner-lobb:64 $opts -o "$tmp/sim.png" >/dev/null &&
    "$sim" diff "$tmp/window.png" "$tmp/sim.png" --max 0 >"$tmp/diff" 2>&1; then
    ok "the screenshot shows volfix-sim's picture, pixel for pixel"
else
    fail "the screenshot shows volfix-sim's picture, pixel for pixel" "$(cat "$tmp/diff" 2>/dev/null)"
fi
