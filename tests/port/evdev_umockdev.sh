#!/bin/sh
# SPDX-License-Identifier: MIT
# The evdev backend on emulated input devices: umockdev-run builds a testbed with the devices described in
# tests/data/evdev/knobs.umockdev (two rotary-encoder overlays, one of them with two axes, and a gpio-keys node)
# and replays the recorded event streams (evemu format, as `umockdev-record --evemu-events` writes them) on
# /dev/input/event0..2 while the test binary opens them by path, as the viewer does, and checks the detents and
# presses they add up to. umockdev cannot unplug a device in a running testbed, so "removed" is tested through a
# pipe in the binary's own cases instead.
cd "$(dirname "$0")/../.." || exit 2
BUILD=${BUILD:-build}
bin=$BUILD/tests/port/test_input_evdev
data=tests/data/evdev

if ! command -v umockdev-run >/dev/null 2>&1; then
    echo "skip - evdev-umockdev: umockdev-run is missing (install umockdev)"
    exit 0
fi
if [ ! -x "$bin" ]; then
    echo "not ok - evdev-umockdev: $bin is not built"
    exit 1
fi
# umockdev works by LD_PRELOAD; a binary built with AddressSanitizer wants its runtime first, so let it be second.
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0" \
    umockdev-run -d "$data/knobs.umockdev" \
    -e "/dev/input/event0=$data/knob0.events" \
    -e "/dev/input/event1=$data/knob12.events" \
    -e "/dev/input/event2=$data/keys.events" \
    -- "$bin"
