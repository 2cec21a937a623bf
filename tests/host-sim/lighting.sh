#!/bin/sh
# SPDX-License-Identifier: MIT
# Lighting from the outside (docs/usage.md, "Lighting"): with --shade none every scene of tests/cross/scenes gives
# the frame it gave before lighting came (the hashes below, of the commit before it), and so do those whose
# transfer function is unlit by default; each lighting option bad in each way exits 2 with one line naming the
# option and the accepted form, in volfix-sim and in volfix; the options do what they say (a lit frame differs,
# a transfer-function file's material and shade lines equal the options, --light alone means phong, partial
# slabs and explicit lighting refuse each other); the summary line names the lighting.
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
sim=$build/volfix-sim
data=${VOLFIX_DATA:-../shared/data}
suite=lighting program=$sim
. tests/check.inc

# 1. --shade none: the frames of before, bit for bit. One hash per scene of tests/cross/scenes, in its order,
#    rendered by volfix-sim render SCENE --hash at de9593b (main before lighting in the simulator); scene 10
#    (engine.nii.gz) since its volume is read in the patient frame (its sform turns x and y round: docs/formats.md).
cat >"$tmp/before" <<'EOF'
bc0810fbbd08bdd4
f113183a360189be
263e467f60061192
73f8aa7b92c299a5
3d141077e8584fc1
9b5c5cf61bb15943
34ede9d833c5056c
4eaeed538cf7b8ae
29dae506a579597e
ca2b77b1f4a4c2ed
171d7a1b599d8fcf
0b363ce43378bea9
ff29279be5306900
e644bb083d291f32
eb751d2327a8c3c3
56bbed3b8e81321c
6e431751526de325
064e8008be1e70a5
EOF
grep -vE '^[[:space:]]*(#|$)' tests/cross/scenes | sed "s|\\\$DATA|$data|g" >"$tmp/scenes"
if [ "$(wc -l <"$tmp/scenes")" -ne "$(wc -l <"$tmp/before")" ]; then
    fail "shade none" "tests/cross/scenes has $(wc -l <"$tmp/scenes") scenes, this suite knows $(wc -l <"$tmp/before")"
else
    i=0 differ="" same_default=0 lit_default=0
    while IFS= read -r scene; do
        i=$((i + 1))
        want=$(sed -n "${i}p" "$tmp/before")
        # shellcheck disable=SC2086 # a scene is a list of options
        got=$("$sim" render $scene --shade none --hash 2>&1 | cut -c1-16)
        [ "$got" = "$want" ] || differ="$differ $i($got)"
        # shellcheck disable=SC2086
        dflt=$("$sim" render $scene --hash 2>&1)
        case "$dflt" in
            *" phong "*) lit_default=$((lit_default + 1)) ;;
            "$want "*) same_default=$((same_default + 1)) ;;
            *) differ="$differ default$i($(echo "$dflt" | cut -c1-16))" ;;
        esac
    done <"$tmp/scenes"
    if [ -z "$differ" ]; then
        ok "--shade none: the $i scenes of tests/cross/scenes as before lighting, bit for bit ($same_default of them unlit by default too, $lit_default lit by their preset)"
    else
        fail "--shade none" "scenes that differ from before:$differ"
    fi
fi

# 2. option errors: exit 2, one line naming the option and the accepted form, in both programs
scene="phantom:sphere:8 --size 16x16 --hash"
check_errors() { # PROGRAM_NAME ARGS_BEFORE...: every bad lighting option after them
    who=$1
    shift
    for bad in "--shade|flat|expected none or phong" \
        "--light|30|expected AZ,EL in degrees" "--light|30,20,10|expected AZ,EL in degrees" \
        "--light|400,0|azimuth -360..360" "--light|0,95|elevation -90..90" "--light|nan,0|expected AZ,EL" \
        "--light|1e999,0|expected AZ,EL" "--light|30,|expected AZ,EL" "--light|,30|expected AZ,EL" \
        "--material|0.1,0.7,0.2|expected KA,KD,KS,N" "--material|0.1,0.7,0.2,10,1|expected KA,KD,KS,N" \
        "--material|1.5,0.7,0.2,10|in [0, 1]" "--material|0.1,0.7,0.2,0|1..255" "--material|0.1,0.7,0.2,2.5|1..255" \
        "--material|0.1,-0.7,0.2,10|expected KA,KD,KS,N" "--gradient-opacity|40,20|0 <= LO < HI <= 255" \
        "--gradient-opacity|10,10|0 <= LO < HI <= 255" "--gradient-opacity|0,256|0 <= LO < HI <= 255" \
        "--gradient-opacity|0.5,30|integers" "--gradient-opacity|-1,30|LO,HI" "--gradient-opacity|10|LO,HI" \
        "--normal-bits|9|expected 8, 10, 12, 14 or 16" "--normal-bits|18|expected 8, 10, 12, 14 or 16" \
        "--normal-bits|14x|expected 8, 10, 12, 14 or 16" "--shade-lookup|linear|expected nearest or bilinear"; do
        opt=${bad%%|*} rest=${bad#*|} value=${rest%%|*} phrase=${rest#*|}
        # the option and its value, then the accepted form, which names what was wrong
        out=$(expect_error "$who $opt '$value'" "$opt $value: expected" "$@" "$opt" "$value")
        case "$out" in
            ok*) grep -qF -- "$phrase" "$tmp/err" && echo "$out" ||
                fail "$who $opt '$value'" "the message lacks '$phrase': $(cat "$tmp/err")" ;;
            *) echo "$out" ;;
        esac
    done
    expect_error "$who --light three times" "at most 2 lights" "$@" --light 0,0 --light 10,0 --light 20,0
    expect_error "$who --light missing" "--light (missing): expected AZ,EL" "$@" --light
    expect_error "$who --shade ''" "--shade '': an empty value" "$@" --shade ""
    expect_error "$who --shade none with --light" "--light goes with --shade phong" "$@" --shade none --light 10,0
    expect_error "$who --shade none with --material" "--material goes with --shade phong" "$@" --material 0,1,0,5 \
        --shade none
}
# shellcheck disable=SC2086 # the scene is a list of words
check_errors volfix-sim render $scene
program=$build/volfix
check_errors volfix --board boards/host-headless.board phantom:sphere:8 --frames 1
program=$sim
expect_error "partial slabs with --shade phong" "--partial-slabs does not go with lighting" render $scene \
    --partial-slabs --shade phong
expect_error "partial slabs with --gradient-opacity" "--partial-slabs does not go with lighting" render $scene \
    --gradient-opacity 1,9 --partial-slabs

# 3. the options do what they say
h() { "$sim" render phantom:marschner-lobb:24 --size 48x40 --preset sharp "$@" --hash 2>&1; }
unlit=$(h | cut -c1-16)
phong=$(h --shade phong | cut -c1-16)
[ "$phong" != "$unlit" ] && [ "$(h --light 0,0 | cut -c1-16)" = "$phong" ] &&
    [ "$(h --material 0.1,0.7,0.2,10 | cut -c1-16)" = "$phong" ] && [ "$(h --shade none | cut -c1-16)" = "$unlit" ] &&
    ok "--shade phong lights (--light or --material alone too, with the defaults: the same frame)" ||
    fail "--shade phong" "unlit $unlit, phong $phong, --light 0,0 $(h --light 0,0), --material $(h --material 0.1,0.7,0.2,10)"
distinct=""
for opts in "--light 40,30" "--light 0,0 --light -60,10" "--material 0.3,0.5,0.6,40" "--normal-bits 8" \
    "--shade-lookup bilinear" "--gradient-opacity 20,120" "--shade none --gradient-opacity 20,120" \
    "--mode point --shade-lookup bilinear" "--mode preclass --normal-bits 16"; do
    # shellcheck disable=SC2086
    got=$(h --shade phong $opts | cut -c1-16)
    case "$opts" in --shade\ none*) got=$(h $opts | cut -c1-16) ;; esac
    [ "$got" != "$phong" ] && [ "$got" != "$unlit" ] || distinct="$distinct '$opts'"
done
[ -z "$distinct" ] && ok "each lighting option changes the frame" || fail "each lighting option changes the frame" \
    "the same frame as plain phong or unlit:$distinct"
# a transfer-function file's lines, and the options winning over them
{ echo "shade phong"; echo "material 0.3 0.5 0.6 40"; echo "0 0 0 0 0"; echo "0.5 1 0.5 0.2 0.3"; echo "1 1 1 1 0.8"; } \
    >"$tmp/lit.tf"
{ echo "0 0 0 0 0"; echo "0.5 1 0.5 0.2 0.3"; echo "1 1 1 1 0.8"; } >"$tmp/plain.tf"
t() { "$sim" render phantom:marschner-lobb:24 --size 48x40 "$@" --hash 2>&1 | cut -c1-16; }
[ "$(t --tf "$tmp/lit.tf")" = "$(t --tf "$tmp/plain.tf" --shade phong --material 0.3,0.5,0.6,40)" ] &&
    [ "$(t --tf "$tmp/lit.tf" --shade none)" = "$(t --tf "$tmp/plain.tf")" ] &&
    [ "$(t --tf "$tmp/lit.tf" --material 0.1,0.7,0.2,10)" = "$(t --tf "$tmp/plain.tf" --shade phong)" ] &&
    [ "$(t --tf "$tmp/plain.tf")" != "$(t --tf "$tmp/plain.tf" --shade phong)" ] &&
    ok "a transfer function's shade and material lines equal the options, and the options win" ||
    fail "transfer-function lighting" "the frames differ from the options'"
# with partial slabs a preset's own shading gives way: ct-bone is lit by default, but not with them
pb() { "$sim" render phantom:cube:16 --size 40x40 --preset ct-bone --mode preclass "$@" --hash 2>&1; }
case "$(pb)" in *" phong "*) dflt=lit ;; *) dflt=unlit ;; esac
[ "$dflt" = lit ] && [ "$(pb --partial-slabs | cut -c1-16)" = "$(pb --partial-slabs --shade none | cut -c1-16)" ] &&
    ok "ct-bone is lit by default, and unlit with --partial-slabs" ||
    fail "ct-bone and partial slabs" "default $dflt; $(pb --partial-slabs)"
# the summary lines name the lighting
"$sim" render phantom:sphere:16 --size 32x32 --preset sharp --light 30,10 --light -20,5 --material 0.2,0.6,0.3,25 \
    --normal-bits 12 --shade-lookup nearest --gradient-opacity 5,60 -o "$tmp/s.png" >"$tmp/out" 2>&1
"$sim" compare phantom:sphere:16 --size 32x32 --preset sharp --shade none --gradient-opacity 5,60 --json \
    >"$tmp/cmp" 2>&1
grep -qF "phong light 30,10+-20,5 material 0.2,0.6,0.3,25 normals 12 bits, nearest shade gradient-opacity 5,60" \
    "$tmp/out" && grep -qF "sharp window 0,255 unshaded gradient-opacity 5,60\"" "$tmp/cmp" &&
    ok "render and compare name the lighting" || fail "summary lines" "$(cat "$tmp/out" "$tmp/cmp")"
# help
for cmd in render compare bench; do
    "$sim" $cmd --help 2>&1 | grep -q -- '--gradient-opacity LO,HI' && ok "volfix-sim $cmd --help has the lighting" ||
        fail "volfix-sim $cmd --help" "no lighting options"
done
"$build/volfix" --help 2>&1 | grep -q -- '--shade-lookup L' && ok "volfix --help has the lighting" ||
    fail "volfix --help" "no lighting options"
