#!/bin/sh
# SPDX-License-Identifier: MIT
# make bench-peers: volfix and VolPack (Debian's libvolpack1-dev, VolPack 1.0b3) render the same four scenes in
# one run: brainsmall and engine, each with a "ramp" and a "sparse" grey transfer function; 512x512, parallel
# projection, FRAMES (90) frames over 180 degrees about the vertical axis, one thread (docs/peers.md).
#
# The camera: VolPack's rotation by A degrees about y (vpRotate) shows what volfix shows at azimuth -A, in the
# same orientation (no mirror); its window of +-0.75 is volfix's zoom D / (1.5 N). The turn is VolPack's A = 0,
# -2, ..., -178 and volfix's azimuth 0, 2, ..., 178: the same 90 views in the same order.
#
# First the image checks: tools/peers/volpack_peer must reproduce VolPack's own example image bit for bit
# (../shared/data/brainsmall.volpack-check.ppm, with depth cueing); then VolPack at A = COUNT_ANGLE against
# volfix at azimuth -A and, for contrast, at 180 + A (a mirror of nearly the same silhouette for a head), on
# brainsmall and on volpack_peer's phantom "boxes", which no mirror maps onto itself (camera.png,
# camera-boxes.png: VolPack | volfix | silhouettes). Then instructions per frame: callgrind counts one frame at
# A = COUNT_ANGLE (30), after a warm-up frame one step before it, in each program (--toggle-collect on the
# frame call, --dump-after it: the second dump). Then frame times, in ROUNDS (3) rounds: each round renders
# every renderer's turn once, one process each, in an order rotated from round to round; ms/frame is the median
# of the rounds' means, and a ratio is the median over rounds of the ratio within each round (the two turns ran
# close together on a shared machine).
#
# volfix takes a grey path where the transfer function is grey (the pre-integrated table's builder); each
# volfix mode is also counted with an RGB transfer function (blue 255/256 of grey at the top), and where that
# changes the count its figures get a column of their own.
#
# Output: the table (stdout, markdown); progress on stderr; files in $BUILD/peers. 5 to 8 minutes on the
# shared 2-core machine, half of it callgrind (JOBS=2 counts run side by side; counts do not depend on load).
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
data=${VOLFIX_DATA:-../shared/data}
rounds=${ROUNDS:-3}
frames=${FRAMES:-90}
count_angle=${COUNT_ANGLE:-30}
jobs=${JOBS:-2}
sim=$build/volfix-sim
peer=$build/peers/volpack_peer
compare=$build/peers/peer_compare
study=$build/peers/storage_study
out=$build/peers

for n in ROUNDS:$rounds FRAMES:$frames COUNT_ANGLE:$count_angle JOBS:$jobs; do
    case ${n#*:} in
        ''|*[!0-9]*|0) echo "bench-peers: ${n%%:*}=${n#*:}: expected a whole number above 0" >&2; exit 2 ;;
    esac
done
for f in "$sim" "$peer" "$compare" "$study"; do
    [ -x "$f" ] || { echo "bench-peers: $f: not built (run make bench-peers)" >&2; exit 2; }
done
for f in brainsmall.den brainsmall.nhdr engine.raw.gz engine.nhdr brainsmall.volpack-check.ppm; do
    [ -r "$data/$f" ] || { echo "bench-peers: $data/$f: missing (VOLFIX_DATA names the shared data folder)" >&2; exit 2; }
done
command -v valgrind >/dev/null || { echo "bench-peers: valgrind: not installed (tools/deps.sh peers)" >&2; exit 2; }
mkdir -p "$out/count" || exit 2
rm -f "$out"/count/* "$out/times.txt" "$out/memory.txt"

say() { echo "bench-peers: $*" >&2; }
load_start=$(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)

# ---- transfer functions: grey level = opacity per unit length; zero up to T, then a ramp to 1 at 255 ----
# tf NAME T BLUE: BLUE is the top point's blue (1 for grey)
tf() {
    {
        echo "# $1: opacity per unit length and grey level 0 up to $2/255, then rising linearly to 1 at 255"
        echo "0 0 0 0 0"
        [ "$2" -gt 0 ] && awk -v t="$2" 'BEGIN { printf "%.10f 0 0 0 0\n", t / 255 }'
        echo "1 1 1 $3 1"
    } >"$out/$1.tf"
}
# sparse: the smallest T that leaves at most 20% of brainsmall's voxels above it is 20; 81% of engine is 0, so
# its T is 128 (docs/peers.md)
for t in 0 20 128; do
    name=$([ $t = 0 ] && echo ramp || echo sparse$t)
    tf "$name" $t 1
    tf "$name-rgb" $t 0.99609375
done

# ---- lighting: VolPack's Phong frame's light and material for volfix's lit columns ----
# VolPack's light (0.3, 0.3, 1.0), set in eye space, lights its images from the upper left: a sphere's upper left
# is its brightest part (docs/peers.md, "The light"). In volfix's terms, relative to the viewer, that is azimuth
# -atan(0.3 / 1.0) = -16.70 degrees (from the left) and elevation asin(0.3 / |(0.3, 0.3, 1)|) = 16.03
# (from above); make volpack-check measures it on VolPack's own example (the other signs fit worse).
vf_light="--shade phong --light -16.70,16.03 --material 0.18,0.35,0.39,10"

# ---- scenes: name, VolPack's volume arguments, volfix's volume, dims, transfer function ----
scenes=${SCENES:-brainsmall-ramp brainsmall-sparse engine-ramp engine-sparse}
scene() { # sets vp_vol, vf_vol, dims, tfname, zoom for scene $1
    case $1 in
        brainsmall-*) vp_vol="$data/brainsmall.den"; vf_vol="$data/brainsmall.nhdr"; dims=128,128,84 ;;
        engine-*) vp_vol="$data/engine.raw.gz --dims 256,256,128"; vf_vol="$data/engine.nhdr"; dims=256,256,128 ;;
    esac
    case $1 in
        *-ramp) tfname=ramp ;;
        brainsmall-sparse) tfname=sparse20 ;;
        engine-sparse) tfname=sparse128 ;;
    esac
    # VolPack's window of +-0.75 shows 512 / (1.5 N) pixels a voxel (N the largest dimension); volfix's zoom 1
    # fits the diagonal D = |dims - 1| in 512 pixels: the same scale at zoom D / (1.5 N)
    zoom=$(echo "$dims" | awk -F, '{ n = $1; if ($2 > n) n = $2; if ($3 > n) n = $3
        printf "%.6f", sqrt(($1 - 1) ^ 2 + ($2 - 1) ^ 2 + ($3 - 1) ^ 2) / (1.5 * n) }')
}

# volfix's azimuth for VolPack's angle A: -A, as 0..359
azimuth() { echo $(( (360 - $1 % 360) % 360 )); }

# renderer command NAME ANGLE FRAMES: the command line of one renderer for the current scene, first view at
# VolPack angle ANGLE (volfix azimuth -ANGLE), turning 2 degrees a frame; NAME is vp-phong, vp-rgb or
# vf-MODE[-rgb]
command_for() {
    case $1 in
        vp-*) echo "$peer $vp_vol --tf $out/$tfname.tf --shading ${1#vp-} --size 512x512 --window 0.75" \
                   "--angle $2 --step -2 --frames $3 --rounds 1 --json" ;;
        vf-*)
            m=${1#vf-} rgb="" lit=""
            case $m in *-rgb) rgb=-rgb m=${m%-rgb} ;; esac
            case $m in *-lit) lit=$vf_light m=${m%-lit} ;; esac
            echo "$sim bench $vf_vol --tf $out/$tfname$rgb.tf --mode $m --size 512x512 --zoom $zoom" \
                 "--view $(azimuth "$2"),0 --frames $3 --rounds 1 --threads 1 --json $lit" ;;
    esac
}
renderers="vp-phong vp-rgb"
for m in point preint1 preclass point-lit preint1-lit preclass-lit; do renderers="$renderers vf-$m vf-$m-rgb"; done

# ---- the image checks ----
say "checking the VolPack client against VolPack's own image (brainsmall.volpack-check.ppm)"
"$peer" "$data/brainsmall.den" --check --depth-cue -o "$out/check-depthcue.png" || exit 1
"$peer" "$data/brainsmall.den" --check -o "$out/check-no-depthcue.png" || exit 1
check=$("$compare" "$out/check-depthcue.png" "$data/brainsmall.volpack-check.ppm" --flip none --json) || exit 1
# camera NAME "VOLPACK VOLUME ARGS" "VOLFIX VOLUME ARGS" AZIMUTH: VolPack at A = count_angle (unshaded RGB, ramp)
# against volfix preclass at AZIMUTH; peer_compare's JSON at silhouette levels 0 and 8, a line each, into
# $out/NAME-AZIMUTH.txt, and the pictures side by side (level 8) into $out/NAME-AZIMUTH.png
camera() {
    "$peer" $2 --tf "$out/ramp.tf" --shading rgb --angle "$count_angle" -o "$out/$1-volpack.png" || return 1
    "$sim" render $3 --tf "$out/ramp.tf" --mode preclass --zoom "$cam_zoom" --view "$4,0" \
        -o "$out/$1-volfix-$4.png" >/dev/null || return 1
    "$compare" "$out/$1-volpack.png" "$out/$1-volfix-$4.png" --threshold 0 --shift 3 --json >"$out/$1-$4.txt" &&
        "$compare" "$out/$1-volpack.png" "$out/$1-volfix-$4.png" --threshold 8 --shift 3 --json \
            -o "$out/$1-$4.png" >>"$out/$1-$4.txt"
}
scene brainsmall-ramp
cam_zoom=$zoom
az_peer=$(azimuth "$count_angle")
az_brief=$(( (180 + count_angle) % 360 ))
say "the camera: VolPack at A = $count_angle against volfix at azimuth $az_peer (and $az_brief), zoom $zoom"
for az in $az_peer $az_brief; do
    camera camera "$vp_vol" "$vf_vol" $az || exit 1
    camera boxes "boxes --save $out/boxes.raw" "$out/boxes.raw --dims 128,128,84 --type uint8" $az || exit 1
done
cp "$out/camera-$az_peer.png" "$out/camera.png" && cp "$out/boxes-$az_peer.png" "$out/camera-boxes.png" || exit 1

# ---- instructions per frame ----
# count NAME: callgrind's count of the frame at A = count_angle (the second dump) into $out/count/SCENE.NAME
count() {
    case $1 in vp-*) fn=peer_frame ;; *) fn=vfp_render_frame ;; esac
    cg=$out/count/$s.$1.cg
    valgrind --tool=callgrind --callgrind-out-file="$cg" --toggle-collect=$fn --dump-after=$fn \
        $(command_for "$1" "$count_angle" 1) >/dev/null 2>"$cg.log"
    n=$(sed -n 's/^summary: \([0-9]*\).*/\1/p' "$cg.2" 2>/dev/null)
    [ -n "$n" ] && echo "$n" >"$out/count/$s.$1" && rm -f "$cg" "$cg".* && return 0
    say "callgrind gave no count for $s $1 (log: $cg.log)"
    return 1
}
started=$(date +%s)
for s in $scenes; do
    scene "$s"
    say "callgrind: $s, $(echo $renderers | wc -w) renderers, $jobs at a time ($(( $(date +%s) - started )) s so far)"
    running=0
    for r in $renderers; do
        count "$r" &
        running=$((running + 1))
        [ $running -ge "$jobs" ] && { wait; running=0; }
    done
    wait
    for r in $renderers; do [ -s "$out/count/$s.$r" ] || exit 1; done
done

# ---- frame times ----
# The RGB variants are timed only where their count differs from grey's (else they are the same work).
started=$(date +%s)
for s in $scenes; do
    scene "$s"
    list=""
    for r in $renderers; do
        case $r in
            vf-*-rgb) cmp -s "$out/count/$s.$r" "$out/count/$s.${r%-rgb}" || list="$list $r" ;;
            *) list="$list $r" ;;
        esac
    done
    n=$(echo $list | wc -w)
    round=1
    while [ $round -le "$rounds" ]; do
        first=$(( (round - 1) * n / rounds % n ))
        i=0
        while [ $i -lt "$n" ]; do
            r=$(echo $list | cut -d' ' -f$(( (first + i) % n + 1 )))
            json=$($(command_for "$r" 0 "$frames")) || { say "$s $r failed"; exit 1; }
            ms=$(echo "$json" | sed -n 's/.*"ms_per_frame": \([0-9.]*\).*/\1/p')
            [ -n "$ms" ] || { say "$s $r: no ms_per_frame in its output"; exit 1; }
            echo "$s $r $round $ms" >>"$out/times.txt"
            if [ $round -eq 1 ]; then # what the renderer holds for the volume: VolPack's classified copies, volfix's arena
                bytes=$(echo "$json" | sed -n 's/.*"\(classified_bytes\|memory_bytes\)": \([0-9]*\).*/\2/p')
                echo "$s $r ${bytes:-0}" >>"$out/memory.txt"
            fi
            i=$((i + 1))
        done
        say "frame times: $s, round $round of $rounds done ($(( $(date +%s) - started )) s so far)"
        round=$((round + 1))
    done
done

# ---- the table ----
echo "## volfix and VolPack, one run: $(date -u '+%Y-%m-%d %H:%M UTC'), $(uname -m), $(nproc) cores"
echo
echo "Load average (1, 5, 15 min) at the start: $load_start; at the end: $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null)."
echo
echo "VolPack $(dpkg-query -W -f='${Version}' libvolpack1-dev 2>/dev/null) (Debian), vpRenderClassifiedVolume;" \
     "$("$sim" --version 2>/dev/null | head -1)$(git diff --quiet HEAD 2>/dev/null || echo ', with uncommitted changes')."
echo "512x512, parallel, one thread, early termination at 1 - 2^-10 in both. M instructions per frame: callgrind, one"
echo "frame at A = $count_angle (volfix azimuth $az_peer) after a warm-up one step before. ms per frame: $frames frames," \
     "2 degrees apart, from A = 0 (volfix azimuth 0 up, VolPack A down); median of $rounds rounds' means."
echo
awk -v rounds="$rounds" -v countdir="$out/count" -v renderers="$renderers" -v scenes="$scenes" '
function median(a, n,    i, j, t) {
    for (i = 2; i <= n; i++) for (j = i; j > 1 && a[j] < a[j - 1]; j--) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2
}
function count_of(s, r,    f, v) { f = countdir "/" s "." r; v = ""; getline v < f; close(f); return v + 0 }
function ms(s, r,    a, k) { for (k = 1; k <= rounds; k++) a[k] = t[s, r, k]; return median(a, rounds) }
function ratio(s, r, p,    a, k) { for (k = 1; k <= rounds; k++) a[k] = t[s, r, k] / t[s, p, k]; return median(a, rounds) }
{ t[$1, $2, $3] = $4; timed[$1, $2] = 1 }
END {
    ns = split(scenes, sc, " "); nr = split(renderers, rd, " ")
    title["vp-phong"] = "VolPack Phong"; title["vp-rgb"] = "VolPack unshaded RGB"
    # a volfix RGB column where the RGB transfer function changes the count in some scene
    nc = 0
    for (i = 1; i <= nr; i++) {
        r = rd[i]
        if (r ~ /^vf-/) {
            name = substr(r, 4); sub(/-lit/, " lit", name); sub(/-rgb/, " RGB", name); title[r] = "volfix " name
        }
        if (r ~ /-rgb$/ && r ~ /^vf-/) {
            differs = 0
            for (j = 1; j <= ns; j++) if (count_of(sc[j], r) != count_of(sc[j], substr(r, 1, length(r) - 4))) differs = 1
            if (!differs) continue
        }
        col[++nc] = r
    }
    printf "| scene |"; for (c = 1; c <= nc; c++) printf " %s |", title[col[c]]; printf "\n|---|"
    for (c = 1; c <= nc; c++) printf "---|"; printf "\n"
    for (j = 1; j <= ns; j++) {
        s = sc[j]; name = s; sub(/-/, " ", name); printf "| %s |", name
        for (c = 1; c <= nc; c++) {
            r = col[c]
            if (((s, r) in timed)) printf " %.1f (%.1f ms) |", count_of(s, r) / 1e6, ms(s, r)
            else printf " = grey |"
        }
        printf "\n"
    }
    # ratios: instructions; ms (the median over rounds of the ratio within a round). A renderer whose RGB
    # variant was not timed (the same count as grey) stands for it.
    printf "\nUnlit volfix / VolPack: instructions, then ms per frame\n\n| scene |"
    for (c = 1; c <= nc; c++) if (col[c] ~ /^vf-/ && col[c] !~ /-lit/) printf " %s / Phong | %s / RGB |", substr(title[col[c]], 8), substr(title[col[c]], 8)
    printf "\n|---|"; for (c = 1; c <= nc; c++) if (col[c] ~ /^vf-/ && col[c] !~ /-lit/) printf "---|---|"; printf "\n"
    for (j = 1; j <= ns; j++) {
        s = sc[j]; name = s; sub(/-/, " ", name); printf "| %s |", name
        for (c = 1; c <= nc; c++) {
            r = col[c]; if (r !~ /^vf-/ || r ~ /-lit/) continue
            q = ((s, r) in timed) ? r : substr(r, 1, length(r) - 4)
            for (v = 1; v <= 2; v++) {
                p = v == 1 ? "vp-phong" : "vp-rgb"
                printf " %.2f; %.2f |", count_of(s, q) / count_of(s, p), ratio(s, q, p)
            }
        }
        printf "\n"
    }
    printf "\nLit volfix against unlit volfix (the same mode and channels) and against VolPack Phong: instructions, then ms\n\n| scene |"
    for (c = 1; c <= nc; c++) if (col[c] ~ /-lit/) printf " %s / unlit | %s / VolPack Phong |", substr(title[col[c]], 8), substr(title[col[c]], 8)
    printf "\n|---|"; for (c = 1; c <= nc; c++) if (col[c] ~ /-lit/) printf "---|---|"; printf "\n"
    for (j = 1; j <= ns; j++) {
        s = sc[j]; name = s; sub(/-/, " ", name); printf "| %s |", name
        for (c = 1; c <= nc; c++) {
            r = col[c]; if (r !~ /-lit/) continue
            q = ((s, r) in timed) ? r : substr(r, 1, length(r) - 4)
            u = q; sub(/-lit/, "", u); if (!((s, u) in timed)) u = substr(u, 1, length(u) - 4)
            printf " %.2f; %.2f |", count_of(s, q) / count_of(s, u), ratio(s, q, u)
            printf " %.2f; %.2f |", count_of(s, q) / count_of(s, "vp-phong"), ratio(s, q, "vp-phong")
        }
        printf "\n"
    }
}' "$out/times.txt" || exit 1

echo
echo "Memory for the volume, MB (10^6 bytes): VolPack's classified volume (the heap vpClassifyVolume keeps: three"
echo "run-length encoded copies of the voxels it does not find transparent, 4 bytes each here) against volfix's arena"
echo "(vf_memory: its per-axis copies, normals, run lists, tables and intermediate image; one thread)."
echo
awk -v scenes="$scenes" '
{ b[$1, $2] = $3 }
END {
    n = split("vp-phong vp-rgb vf-point vf-preint1 vf-preclass vf-point-lit vf-preint1-lit vf-preclass-lit", r, " ")
    printf "| scene | VolPack Phong | VolPack RGB | volfix point | preint1 | preclass | point lit | preint1 lit | preclass lit | preint1 lit / VolPack Phong | preint1 / VolPack RGB |\n"
    printf "|---|---|---|---|---|---|---|---|---|---|---|\n"
    ns = split(scenes, sc, " ")
    for (j = 1; j <= ns; j++) {
        s = sc[j]; name = s; sub(/-/, " ", name); printf "| %s |", name
        for (i = 1; i <= n; i++) printf " %.1f |", b[s, r[i]] / 1e6
        printf " %.2f | %.2f |\n", b[s, "vf-preint1-lit"] / b[s, "vp-phong"], b[s, "vf-preint1"] / b[s, "vp-rgb"]
    }
}' "$out/memory.txt" || exit 1

echo
echo "What volfix's lit storage would take if it kept only what the transfer function leaves visible, MB: the voxel"
echo "places a lit copy holds (1 byte of scalar, 2 of normal code, 1 of gradient magnitude: 4 bytes) summed over the"
echo "three principal axes, counted by storage_study (the corners of the visible cells; a lower bound) for today's"
echo "copies, the rows from a slice's first to last needed one, each row from its first to its last needed voxel"
echo "(with a 4-byte offset a row), the needed voxels only (with their run lists), and one axis of the last."
echo
echo "| scene | VolPack Phong | volfix lit today | slice rows | row spans | exact | exact / VolPack | one axis exact / VolPack |"
echo "|---|---|---|---|---|---|---|---|"
for s in $scenes; do
    scene "$s"
    case $s in brainsmall-*) raw="$data/brainsmall.raw" ;; *) raw="$data/engine.raw.gz" ;; esac
    case $tfname in ramp) t=0 ;; *) t=${tfname#sparse} ;; esac
    j=$("$study" "$raw" --dims "$dims" --threshold "$t") || exit 1
    vp=$(awk -v s="$s" '$1 == s && $2 == "vp-phong" { print $3 }' "$out/memory.txt")
    echo "$j" | awk -v s="$s" -v vp="$vp" '
    function f(k,    r) { r = $0; sub(".*\"" k "\": ", "", r); sub(/[,}].*/, "", r); return r + 0 }
    { name = s; sub(/-/, " ", name)
      ex = 4 * f("exact") + f("run_bytes")
      printf "| %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %.2f |\n", name, vp / 1e6, 4 * f("full") / 1e6,
             4 * f("slice_rows") / 1e6, (4 * f("row_span") + f("row_offsets_bytes")) / 1e6, ex / 1e6, ex / vp, ex / 3 / vp }'
done

echo
field() { echo "$1" | sed -n "s/.*\"$2\": \([^,}]*\).*/\1/p"; }
echo "Client check: VolPack's example classification and view with depth cueing against its own image" \
     "(brainsmall.volpack-check.ppm): max |difference| $(field "$check" max_abs) of 255, identical pixels" \
     "$(field "$check" identical). Without depth cueing: $out/check-no-depthcue.png."
echo "Camera: VolPack at A = $count_angle (unshaded RGB, ramp) against volfix preclass (zoom $cam_zoom); silhouettes' IoU"
echo "for VolPack's image as it is and flipped (none, lr, ud, both), then the best whole-pixel shift after the best flip"
echo "(VolPack's x+dx,y+dy on volfix's x,y), then the luminance difference after that flip:"
for name in camera boxes; do
    for az in $az_peer $az_brief; do
        label=$([ $az = $az_peer ] && echo "azimuth -A = $az" || echo "azimuth 180 + A = $az")
        while read -r c; do
            echo "  $name, $label, level > $(field "$c" threshold): $(echo "$c" | sed -n 's/.*"iou": {\([^}]*\)}.*/\1/p' | tr -d '"');" \
                 "best flip $(field "$c" best_flip | tr -d '"'), shift $(echo "$c" | sed -n 's/.*"best_shift": \[\([^]]*\)\].*/\1/p' | tr -d ' ')" \
                 "IoU $(field "$c" iou_shifted); |luminance difference| mean $(field "$c" mean_abs), max $(field "$c" max_abs)"
        done <"$out/$name-$az.txt"
    done
done
echo "Side by side (VolPack | volfix at azimuth $az_peer | silhouettes above 8: white both, red VolPack only, green"
echo "volfix only): $out/camera.png, $out/camera-boxes.png"
