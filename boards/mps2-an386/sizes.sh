#!/bin/sh
# SPDX-License-Identifier: MIT
# The sizes `make mcu` prints: the core for a Cortex-M4 per object as compiled (.text includes constants, as
# arm-none-eabi-size counts them), the core as linked into the firmware (what --gc-sections kept, read from the
# link map), the largest functions, and the firmware as a whole.
# Usage: sizes.sh CROSS_PREFIX MCU_BUILD
cross=${1:-arm-none-eabi-} dir=${2:-build-mcu}

echo "core for Cortex-M4 (-Os, Thumb-2), as compiled:"
"${cross}size" -t "$dir"/core/*.o | sed "s|$dir/core/||; s/^/  /"

# Input sections by the archive or object they came from, after garbage collection. A map line is
# " .text.name  0xADDR  0xSIZE  FILE", or the name alone on one line and the rest on the next.
awk '
    /^Linker script and memory map/ { on = 1; next }
    !on { next }
    /^ \.[^ ]+$/ { pending = $1; next }
    /^ \.[^ ]+ +0x[0-9a-f]+ +0x[0-9a-f]+ / { add($1, $3, $4); pending = ""; next }
    pending != "" && /^ +0x[0-9a-f]+ +0x[0-9a-f]+ / { add(pending, $2, $3) }
    { pending = "" }
    function hex(text,    i, n) {
        n = 0
        for (i = 3; i <= length(text); i++) n = n * 16 + index("0123456789abcdef", substr(text, i, 1)) - 1
        return n
    }
    function add(section, size, file,    kind, who) {
        kind = section ~ /^\.(text|rodata)/ ? "text" : section ~ /^\.data/ ? "data" : section ~ /^\.bss/ ? "bss" : ""
        if (kind == "") return
        who = file ~ /libvolfix\.a\(/ ? "core" : file ~ /libgcc\.a\(/ ? "libgcc" : "firmware"
        total[who, kind] += hex(size)
    }
    END {
        printf "core as linked into the firmware (--gc-sections): text %d, data %d, bss %d bytes\n",
               total["core", "text"], total["core", "data"], total["core", "bss"]
        printf "libgcc helpers linked (64-bit division): text %d bytes\n", total["libgcc", "text"]
        printf "firmware code (startup, semihosting, main, the scene): text %d, data %d, bss %d bytes\n",
               total["firmware", "text"], total["firmware", "data"], total["firmware", "bss"]
    }' "$dir/fw.map"

"${cross}nm" -S -t d "$dir/fw.elf" |
    awk '$4 == "scene_voxels" { printf "  of which the embedded volume (scene_voxels, constant): %d bytes\n", $2 }'
echo "largest core functions, as compiled (bytes):"
"${cross}nm" -S -t d "$dir"/core/*.o | awk 'NF == 4 && $3 ~ /^[tT]$/ { print $2 + 0, $4 }' | sort -n |
    tail -n 8 | awk '{ printf "  %6d %s\n", $1, $2 }' | sort -rn

echo "firmware $dir/fw.elf:"
"${cross}size" "$dir/fw.elf" | sed "s|$dir/||; s/^/  /"
"${cross}size" -A "$dir/fw.elf" | awk '$1 ~ /^\.(text|ARM\.exidx|stack|data|bss)$/ { printf "  %-12s %8d bytes at 0x%08x\n", $1, $2, $3 }'
