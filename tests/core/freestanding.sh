#!/bin/sh
# SPDX-License-Identifier: MIT
# The core's rules, proved by the compilers: freestanding C99, no floating point, nothing from libc.
# - aarch64 with -mgeneral-regs-only rejects any floating-point value, operation or register;
# - linking with -nostdlib and --no-undefined fails on any call into libc (or anywhere outside the core);
# - the core includes no header beyond stdint.h, stddef.h, stdbool.h and limits.h.
cd "$(dirname "$0")/../.." || exit 2
out=${BUILD:-build}/freestanding
rm -rf "$out" && mkdir -p "$out"
flags="-std=c99 -ffreestanding -fno-builtin -Wall -Wextra -Wpedantic -Werror -O2 -fPIC -fno-tree-loop-distribute-patterns"

check() { # name, command...
    name=$1
    shift
    if "$@" >"$out/log" 2>&1; then
        echo "ok - freestanding/$name"
    else
        echo "not ok - freestanding/$name: $(head -n 3 "$out/log" | tr '\n' ' ')"
    fi
}

build_lib() { # compiler, extra flags, output
    cc=$1 extra=$2 lib=$3
    objs=""
    for src in core/*.c; do
        obj="$out/$(basename "$src" .c)-$(basename "$lib" .so).o"
        $cc $flags $extra -c "$src" -o "$obj" || return 1
        objs="$objs $obj"
    done
    $cc -nostdlib -shared -Wl,--no-undefined $extra -o "$lib" $objs
}

check "x86-64 links with -nostdlib" build_lib gcc "" "$out/libvolfix-host.so"
# the smallest configuration of vf_config.h (a microcontroller's: no partial slabs, one ray per voxel column)
check "x86-64 without partial slabs and with one ray links with -nostdlib" \
    build_lib gcc "-DVF_PARTIAL_SLABS=0 -DVF_MAX_RAYS=1" "$out/libvolfix-small.so"
if command -v aarch64-linux-gnu-gcc >/dev/null; then
    check "aarch64 -mgeneral-regs-only (no floating point) links with -nostdlib" \
        build_lib aarch64-linux-gnu-gcc "-mgeneral-regs-only" "$out/libvolfix-a64.so"
else
    echo "skip - freestanding/aarch64: aarch64-linux-gnu-gcc is missing (install gcc-aarch64-linux-gnu)"
fi

# 32-bit ARM without a divide instruction needs the compiler's own helpers (__aeabi_uidiv), which live in
# libgcc, not libc: link the core into one object and allow exactly those as undefined.
arm_helpers_only() {
    objs=""
    for src in core/*.c; do
        arm-linux-gnueabihf-gcc $flags -march=armv7-a+fp -c "$src" -o "$out/$(basename "$src" .c)-arm.o" || return 1
        objs="$objs $out/$(basename "$src" .c)-arm.o"
    done
    arm-linux-gnueabihf-ld -r -o "$out/core-arm.o" $objs || return 1
    undefined=$(arm-linux-gnueabihf-nm -u "$out/core-arm.o" | awk '{print $2}' | grep -v '^__aeabi_')
    [ -z "$undefined" ] || { echo "calls outside the core: $undefined"; return 1; }
}
if command -v arm-linux-gnueabihf-gcc >/dev/null; then
    check "armv7 calls nothing but compiler helpers" arm_helpers_only
else
    echo "skip - freestanding/armv7: arm-linux-gnueabihf-gcc is missing (install gcc-arm-linux-gnueabihf)"
fi

bad=$(grep -hoE '#include[[:space:]]*<[^>]+>' core/*.c core/*.h | sed -E 's/.*<([^>]+)>/\1/' | sort -u |
      grep -vxE 'stdint.h|stddef.h|stdbool.h|limits.h' | tr '\n' ' ')
if [ -z "$bad" ]; then echo "ok - freestanding/system headers"; else echo "not ok - freestanding/system headers: $bad"; fi
