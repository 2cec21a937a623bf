#!/bin/sh
# SPDX-License-Identifier: MIT
# The picture of docs/defaults.md's anisotropic volumes: headsq (spacing 3.2, 3.2, 1.5) from the side with
# ct-skin-bone unlit, magnified twice, at one ray per voxel column, at the default for its spacing (2 x 2 rays) and the ground
# truth. Usage: docs/images/anisotropic.sh (from the repository's top, after make; VOLFIX_DATA names the sample
# volumes, ../shared/data by default). Needs ImageMagick's montage.
set -e
sim=${BUILD:-build}/volfix-sim
data=${VOLFIX_DATA:-../shared/data}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene="$data/headsq.nhdr --preset ct-skin-bone --shade none --view 90,0 --zoom 2 --size 256x256"
# shellcheck disable=SC2086 # scene is a list of options
"$sim" render $scene --rays 1 -o "$tmp/1.png"
# shellcheck disable=SC2086
"$sim" render $scene -o "$tmp/2.png"
# shellcheck disable=SC2086
"$sim" render $scene --truth -o "$tmp/3.png"
montage "$tmp/1.png" "$tmp/2.png" "$tmp/3.png" -tile 3x1 -geometry +2+2 docs/images/anisotropic.png
