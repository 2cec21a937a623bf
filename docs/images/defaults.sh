#!/bin/sh
# SPDX-License-Identifier: MIT
# The pictures of docs/defaults.md: the 16-bit default window before (the 0.5 and 99.5 percentiles) and after
# (the 99.99 percentile, capped at twice the 99.5's distance), on cthead and headsq with ct-skin-bone and on a
# generated volume of soft tissue with a wire. Usage: docs/images/defaults.sh (from the repository's top, after
# make; VOLFIX_DATA names the sample volumes, ../shared/data by default). Needs ImageMagick's montage and python3.
set -e
sim=${BUILD:-build}/volfix-sim
data=${VOLFIX_DATA:-../shared/data}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# the old windows, as the old default printed them
"$sim" render "$data/cthead.nhdr" --preset ct-skin-bone --view 180,90 --size 256x256 --window 0,2463 -o "$tmp/1.png"
"$sim" render "$data/cthead.nhdr" --preset ct-skin-bone --view 180,90 --size 256x256 -o "$tmp/2.png"
"$sim" render "$data/headsq.nhdr" --preset ct-skin-bone --size 256x256 --window 0,2408 -o "$tmp/3.png"
"$sim" render "$data/headsq.nhdr" --preset ct-skin-bone --size 256x256 -o "$tmp/4.png"
montage "$tmp/1.png" "$tmp/2.png" "$tmp/3.png" "$tmp/4.png" -tile 4x1 -geometry +2+2 docs/images/defaults-ct-window.png
# tests/host-sim/test_window16.c's volume: 96^3 uint16 tissue 1000..1999, a 4x4 wire of 0.05% of the voxels at 4x
python3 - "$tmp/wire.raw" <<'PY'
import struct, sys
N = 96
v = [1000 + (i * 7 + j * 13 + k * 5) % 1000 for k in range(N) for j in range(N) for i in range(N)]
wire, c = round(0.0005 * N ** 3), 1
while c * c * (N // 2) < wire:
    c += 1
for w in range(wire):
    v[((w % c) * N + N // 2 + (w // c) % c) * N + N // 4 + w // (c * c)] = 6000
open(sys.argv[1], "wb").write(struct.pack("<%dH" % len(v), *v))
PY
raw="--dims 96,96,96 --type uint16 --view 0,0 --size 256x256"
"$sim" render "$tmp/wire.raw" $raw --window 1005,1995 -o "$tmp/5.png"
"$sim" render "$tmp/wire.raw" $raw -o "$tmp/6.png"
montage "$tmp/5.png" "$tmp/6.png" -tile 2x1 -geometry +2+2 docs/images/defaults-wire.png
