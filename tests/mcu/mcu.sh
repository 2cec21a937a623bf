#!/bin/sh
# SPDX-License-Identifier: MIT
# The core on a microcontroller: builds the Cortex-M4 firmware for the MPS2 AN386 board (make mcu-firmware,
# boards/mps2-an386), runs it in qemu-system-arm, and requires the frame hash it prints to equal the host's
# `volfix-sim render SCENE --hash`, for the default scene and for one with every option changed; the firmware
# must end through semihosting with status 0. Also: the comparison tells another view's frame apart, a short
# arena ends in VF_ERR_NOMEM with status 2, an option the build leaves out in VF_ERR_UNSUPPORTED with status 2,
# the core at -Os calls nothing but libgcc's helpers, and its code stays within the 24 KB budget. Variants with
# order 2 and with lighting built in render their frames as the host does; a core that lights stays within 32 KB.
# neghip 64^3 lit and unlit over storage prebuilt into flash fits 256 KB of SRAM with the host's frame.
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
sim=$build/volfix-sim
mcu=$build/mcu # one firmware build directory, reused by every scene below (the core is compiled once)
data=${VOLFIX_DATA:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

ok() { echo "ok - mcu/$1"; }
fail() { echo "not ok - mcu/$1: $2"; }

missing=""
for tool in arm-none-eabi-gcc:gcc-arm-none-eabi qemu-system-arm:qemu-system-arm; do
    command -v "${tool%%:*}" >/dev/null || missing="$missing ${tool#*:}"
done
if [ -n "$missing" ]; then
    echo "skip - mcu: the firmware's compiler or emulator is missing (install$missing)"
    exit 0
fi

# The firmware's scene is the Makefile's MCU_SCENE: bucky, from the sample volumes.
if [ ! -f "$data/bucky.nhdr" ]; then
    fail "data" "no bucky.nhdr in VOLFIX_DATA='$data': set VOLFIX_DATA to the folder of sample volumes"
    exit 0
fi
volume=$data/bucky.nhdr
default="$volume --size 64x64 --format rgb565 --mode preint1 --preset ramp --view 30,20"
# every option away from its default, a roll, a zoom and another principal axis; 5-row bands do not divide the
# intermediate image, so the last band is a short one
changed="$volume --size 48x40 --format xrgb8888 --mode preint1 --preset sharp --view 200,-40,15 --zoom 1.3"
changed="$changed --table-size 64 --table-bits 8 --lookup bilinear --correction lut --buffer image"

# firmware NAME SCENE BAND_ROWS [GEN_OPTS [FEATURES [STACK]]]: build it (with the Makefile's MCU_FEATURES, or
# FEATURES and its own build directory; a stack of STACK bytes, else the Makefile's) and run it; $tmp/NAME.out gets
# its output, $tmp/NAME.status its exit status (124: the timeout ended it)
firmware() {
    name=$1 scene=$2 rows=$3 gen=${4:-} features=${5:-} stack=${6:-}
    dir=$mcu
    set --
    if [ -n "$features" ]; then dir=$mcu-$name; set -- MCU_FEATURES="$features"; fi
    if [ -n "$stack" ]; then set -- "$@" MCU_STACK="$stack"; fi
    if ! ${MAKE:-make} --no-print-directory BUILD="$build" SAN="${SAN:-}" MCU_BUILD="$dir" MCU_SCENE="$scene" \
        MCU_BAND_ROWS="$rows" MCU_GEN_OPTS="$gen" "$@" mcu-firmware >"$tmp/$name.build" 2>&1; then
        fail "$name" "make mcu-firmware failed: $(grep -m 3 -iE 'error|undefined' "$tmp/$name.build" | tr '\n' ' ')"
        return 1
    fi
    start=$(date +%s.%N)
    timeout 60 qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none -semihosting \
        -icount shift=0 -kernel "$dir/fw.elf" >"$tmp/$name.out" 2>&1
    echo $? >"$tmp/$name.status"
    end=$(date +%s.%N)
    echo "# $name: qemu ran $(awk "BEGIN { printf \"%.2f\", $end - $start }") s"
    sed 's/^/# /' "$tmp/$name.out"
}

# same_frame FIRMWARE_OUT SCENE_OPTION...: the hash the firmware printed equals the host's for the scene
same_frame() {
    out=$1
    shift
    fw=$(sed -n 's/^hash \([0-9a-f]\{16\}\)$/\1/p' "$out")
    host=$("$sim" render "$@" --hash 2>"$tmp/sim.err" | cut -d' ' -f1)
    [ -n "$fw" ] && [ -n "$host" ] && [ "$fw" = "$host" ]
}

check_frame() { # NAME SCENE
    name=$1 scene=$2
    status=$(cat "$tmp/$name.status")
    fw=$(sed -n 's/^hash //p' "$tmp/$name.out")
    # shellcheck disable=SC2086
    host=$("$sim" render $scene --hash 2>&1)
    if [ "$status" != 0 ]; then
        fail "$name frame" "the firmware exited with status $status: $(tail -n 2 "$tmp/$name.out" | tr '\n' ' ')"
    elif ! same_frame "$tmp/$name.out" $scene; then
        fail "$name frame" "firmware hash '$fw', host: $host"
    else
        ok "$name frame equals volfix-sim render's (hash $fw), exit status 0"
    fi
}

# 1. the default scene, and the comparison's own check: the host's frame of another view must not match
if firmware default "$default" 8; then
    check_frame default "$default"
    # shellcheck disable=SC2086
    if same_frame "$tmp/default.out" $(echo "$default" | sed 's/--view 30,20/--view 31,20/'); then
        fail "another view's hash" "the firmware's frame matched the host's frame of view 31,20"
    elif [ -z "$(sed -n 's/^hash //p' "$tmp/default.out")" ]; then
        fail "another view's hash" "the firmware printed no hash"
    else
        ok "another view's hash (31,20 against 30,20) is told apart"
    fi
    used=$(sed -n 's/^stack: \([0-9]*\) bytes used of \([0-9]*\)$/\1/p' "$tmp/default.out")
    size=$(sed -n 's/^stack: \([0-9]*\) bytes used of \([0-9]*\)$/\2/p' "$tmp/default.out")
    if [ -n "$used" ] && [ "$used" -gt 0 ] && [ "$used" -lt "$size" ]; then
        ok "stack measured: $used of $size bytes"
    else
        fail "stack" "expected 'stack: N bytes used of M' with 0 < N < M: $(grep '^stack' "$tmp/default.out")"
    fi

    # the core's code: nothing outside it but the compiler's helpers, and within budget
    arm-none-eabi-ld -r -o "$tmp/core.o" "$mcu"/core/*.o
    calls=$(arm-none-eabi-nm -u "$tmp/core.o" | awk '{ print $2 }' | grep -v '^__aeabi_' | tr '\n' ' ')
    if [ -z "$calls" ]; then ok "the core at -Os calls nothing but libgcc's __aeabi_ helpers"; else
        fail "core calls" "calls outside the core: $calls"; fi
    # the budget counts the core's code as linked into the firmware: what --gc-sections keeps of it
    text=$(sh boards/mps2-an386/sizes.sh arm-none-eabi- "$mcu" | sed -n 's/^core as linked into the firmware.*: text \([0-9]*\),.*/\1/p')
    if [ -n "$text" ] && [ "$text" -le 24576 ]; then ok "core .text as linked $text bytes <= 24 KB"; else
        fail "core .text" "${text:-no} bytes as linked, over the 24 KB (24576) budget"; fi
fi

# 2. every option changed
if firmware changed "$changed" 5; then
    check_frame changed "$changed"
fi

# 3. an arena short of what the host measured for the changed scene: the target's renderer struct is smaller
# than the host's (32-bit pointers), so 4 KB off to be short on any target
measured=$(sed -n 's/^#define SCENE_ARENA_BYTES \([0-9]*\)u$/\1/p' "$mcu/scene.h" 2>/dev/null)
short=$((${measured:-8192} - 4096))
if firmware short "$changed" 5 "--arena-bytes $short"; then
    status=$(cat "$tmp/short.status")
    if [ "$status" = 2 ] && grep -q '^vf_renderer_set_tf: the arena or scratch buffer is too small$' "$tmp/short.out" &&
        grep -q '^arena too small: [0-9]* bytes needed$' "$tmp/short.out"; then
        ok "a short arena ends in VF_ERR_NOMEM, with the bytes needed, and exit status 2"
    else
        fail "short arena" "status $status: $(tr '\n' ' ' <"$tmp/short.out")"
    fi
fi

# 4. an option the firmware's core leaves out (MCU_FEATURES: -DVF_MAX_RAYS=1) is refused, with exit status 2
if firmware rays "$default --rays 2" 8; then
    status=$(cat "$tmp/rays.status")
    if [ "$status" = 2 ] && grep -q '^vf_renderer_create: not supported by this build$' "$tmp/rays.out"; then
        ok "two rays a voxel column, which the firmware's core leaves out, end in VF_ERR_UNSUPPORTED and exit status 2"
    else
        fail "rays refused" "status $status: $(tr '\n' ' ' <"$tmp/rays.out")"
    fi
fi

# 5. order 2, which the firmware's core leaves out (-DVF_ORDER2=0), built in: its frame equals the host's, and the
# core at -Os still calls nothing but libgcc's helpers
features=$(${MAKE:-make} -s --no-print-directory print-MCU_FEATURES | sed 's/-DVF_ORDER2=0/-DVF_ORDER2=1/')
order2="$volume --size 64x64 --format rgb565 --mode preint2 --preset ramp --view 30,20 --table-size 32"
order2="$order2 --table-bits 8 --table2-size 16"
if firmware order2 "$order2" 8 "" "$features"; then
    check_frame order2 "$order2"
    arm-none-eabi-ld -r -o "$tmp/core2.o" "$mcu-order2"/core/*.o
    calls=$(arm-none-eabi-nm -u "$tmp/core2.o" | awk '{ print $2 }' | grep -v '^__aeabi_' | tr '\n' ' ')
    if [ -z "$calls" ]; then ok "the core with order 2 at -Os calls nothing but libgcc's __aeabi_ helpers"; else
        fail "core with order 2 calls" "calls outside the core: $calls"; fi
fi

# 6. lighting, which the default firmware's core leaves out (-DVF_LIGHTING=0), built in: a lit frame of each lit
# path equals the host's, and the core with lighting still calls nothing but libgcc's helpers. (a) Everything of
# lighting, preint1's front-weighted tables included (-DVF_LIGHTING=1): a lit preint1 frame; its core's size as
# linked is reported. (b) Lighting without the lit pre-integrated tables (-DVF_LIT_TABLES=0, about 4.8 KB): a lit
# point frame, and that core as linked within 32 KB, the budget of a core that lights.
# core_text DIR: the core's .text as linked into DIR's firmware
core_text() { sh boards/mps2-an386/sizes.sh arm-none-eabi- "$1" | sed -n 's/^core as linked into the firmware.*: text \([0-9]*\),.*/\1/p'; }
lit_light="--shade phong --light 30,20 --material 0.2,0.6,0.3,12"
features=$(${MAKE:-make} -s --no-print-directory print-MCU_FEATURES | sed 's/-DVF_LIGHTING=0/-DVF_LIGHTING=1/')
lit="$volume --size 64x64 --format rgb565 --mode preint1 --preset ramp --view 30,20 $lit_light"
if firmware lit "$lit" 8 "" "$features"; then
    check_frame lit "$lit"
    arm-none-eabi-ld -r -o "$tmp/core-lit.o" "$mcu-lit"/core/*.o
    calls=$(arm-none-eabi-nm -u "$tmp/core-lit.o" | awk '{ print $2 }' | grep -v '^__aeabi_' | tr '\n' ' ')
    if [ -z "$calls" ]; then ok "the core with lighting at -Os calls nothing but libgcc's __aeabi_ helpers"; else
        fail "core with lighting calls" "calls outside the core: $calls"; fi
    text=$(core_text "$mcu-lit")
    if [ -n "$text" ]; then ok "core .text with all of lighting, as linked: $text bytes (reported)"; else
        fail "core .text with lighting" "sizes.sh printed no linked size"; fi
fi
features=$(${MAKE:-make} -s --no-print-directory print-MCU_FEATURES |
    sed 's/-DVF_LIGHTING=0/-DVF_LIGHTING=1 -DVF_LIT_TABLES=0/')
litpoint="$volume --size 64x64 --format rgb565 --mode point --preset ramp --view 30,20 $lit_light"
if firmware litpoint "$litpoint" 8 "" "$features"; then
    check_frame litpoint "$litpoint"
    text=$(core_text "$mcu-litpoint")
    if [ -n "$text" ] && [ "$text" -le 32768 ]; then ok "core .text with lighting but not its tables, as linked: $text bytes <= 32 KB"; else
        fail "core .text with lighting" "${text:-no} bytes as linked, over the 32 KB (32768) budget"; fi
fi

# 7. neghip 64^3 on a 256 KB board: the slices, normals and run lists made on the host into the firmware's read-only
# memory (gen_scene --prebuilt, vf_renderer_create_prebuilt), a core without the builders they replace
# (-DVF_PREBUILT=1 -DVF_BUILD_SLICES=0), 12-bit normals, 64-entry 16-bit tables, a 4 KB stack. Lit preint1 at
# 128x128 RGB565 and the same unlit: each frame equals the host's, the firmware's whole SRAM (data + bss, the stack
# among them, as arm-none-eabi-size counts) is at most 256 KB, nothing of the slices or run lists is in the arena,
# and the core as linked is within 40 KB lit and 24 KB unlit.
if [ ! -f "$data/neghip.nhdr" ]; then
    fail "neghip data" "no neghip.nhdr in VOLFIX_DATA='$data'"
else
    base="$data/neghip.nhdr --size 128x128 --format rgb565 --mode preint1 --preset ramp --view 30,20"
    base="$base --table-size 64 --table-bits 16"
    for variant in lit unlit; do
        name=neghip-$variant
        if [ $variant = lit ]; then scene="$base --shade phong --normal-bits 12" lighting=1 budget=40960; else
            scene="$base" lighting=0 budget=24576; fi
        features=$(${MAKE:-make} -s --no-print-directory print-MCU_FEATURES |
            sed "s/-DVF_LIGHTING=0/-DVF_LIGHTING=$lighting/; s/-DVF_PREBUILT=0/-DVF_PREBUILT=1 -DVF_BUILD_SLICES=0/")
        firmware "$name" "$scene" 8 --prebuilt "$features" 4096 || continue
        check_frame "$name" "$scene"
        # Berkeley format: text data bss dec hex filename; .stack is NOLOAD in data memory, counted in bss
        sram=$(arm-none-eabi-size "$mcu-$name/fw.elf" | awk 'NR == 2 { print $2 + $3 }')
        if [ -n "$sram" ] && [ "$sram" -le 262144 ]; then ok "$name SRAM (data + bss + stack) $sram bytes <= 256 KB"; else
            fail "$name SRAM" "${sram:-no} bytes of data + bss, over 256 KB (262144)"; fi
        if grep -q '^arena: peak [0-9]* bytes of [0-9]* (renderer [0-9]*, slices 0, runs 0,' "$tmp/$name.out"; then
            ok "$name: slices and run lists read from read-only memory, none in the arena"
        else
            fail "$name arena" "expected slices 0, runs 0: $(grep '^arena' "$tmp/$name.out")"
        fi
        text=$(core_text "$mcu-$name")
        if [ -n "$text" ] && [ "$text" -le "$budget" ]; then ok "$name core .text as linked $text bytes <= $budget"; else
            fail "$name core .text" "${text:-no} bytes as linked, over $budget"; fi
    done
fi
