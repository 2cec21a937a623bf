#!/bin/sh
# SPDX-License-Identifier: MIT
# make test-cross: the core's promise, bit-exact integer rendering, on the architectures users run it on.
#
#   1. the core's and the port layer's test suites (CROSS/tests/core/test_*, CROSS/tests/port/test_*) cross-built
#      for the target, run under qemu-user (host-sim's suites compare with double precision for minutes under
#      emulation, and the frames below cover what they render);
#   2. every scene of tests/cross/scenes rendered by the native volfix-sim and by the target's, for 1, 2 and 4
#      threads: `volfix-sim render SCENE --threads N --hash` must print the same FNV-1a hash of the frame's
#      pixel bytes (port/render/image.h) everywhere, and the threaded frames must equal the single-threaded one.
#
# The cross builds are static (Makefile, cross settings), so qemu-aarch64 and qemu-arm run them without a target
# root file system. Prints "ok - NAME" / "not ok - NAME: why" per check and ends with "N passed, N failed".
# Usage: tests/cross/run.sh NATIVE_BUILD CROSS_BUILD...   (a CROSS_BUILD named *-aarch64 or *-armhf)
cd "$(dirname "$0")/../.." || exit 2
[ $# -ge 2 ] || { echo "usage: tests/cross/run.sh NATIVE_BUILD CROSS_BUILD..." >&2; exit 2; }
native=$1
shift
data=${VOLFIX_DATA:-}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0 failed=0

ok() { echo "ok - cross/$1"; passed=$((passed + 1)); }
fail() { echo "not ok - cross/$1: $2"; failed=$((failed + 1)); }

qemu_for() {
    case "$1" in
        *-aarch64) echo qemu-aarch64 ;;
        *-armhf) echo qemu-arm ;;
        *) echo "" ;;
    esac
}

# The scenes: one per line, `volfix-sim render` options after the volume; $DATA is the sample volumes' folder,
# VOLFIX_DATA. Without it the lines naming $DATA fail (one failure, naming the variable); the phantoms still run.
scenes=$tmp/scenes
grep -vE '^[[:space:]]*(#|$)' tests/cross/scenes | while IFS= read -r line; do
    case "$line" in
        *'$DATA'*) [ -n "$data" ] && [ -d "$data" ] || continue ;;
    esac
    echo "$line" | sed "s|\\\$DATA|$data|g"
done >"$scenes"
if [ -z "$data" ] || [ ! -d "$data" ]; then
    fail "data" "VOLFIX_DATA='$data' is not a folder: the scenes of the sample volumes cannot run (set VOLFIX_DATA)"
fi
nscenes=$(grep -c . "$scenes")

# Lines of a hashes file (below) for scene I: its one-thread hash (or "error:"), and all of them as "N=HASH ".
one_hash() { awk -v i="$2" '$1 == i && $2 == 1 { print $3 }' "$1"; }
all_hashes() { awk -v i="$2" '$1 == i { printf "%s=%s ", $2, $3 }' "$1"; }

# hashes BUILD RUNNER OUT: one line per scene and thread count, "INDEX THREADS HASH" (or "... error: MESSAGE")
hashes() {
    build=$1 runner=$2 out=$3
    : >"$out"
    i=0
    while IFS= read -r scene; do
        i=$((i + 1))
        for threads in 1 2 4; do
            # shellcheck disable=SC2086 # a scene is a list of options
            h=$($runner "$build/volfix-sim" render $scene --threads $threads --hash 2>"$tmp/err") ||
                h="error: $(head -n 1 "$tmp/err")"
            echo "$i $threads $h" >>"$out"
        done
    done <"$scenes"
}

if [ ! -x "$native/volfix-sim" ]; then
    echo "not ok - cross/native: $native/volfix-sim is missing (make test-cross builds it)"
    echo "0 passed, 1 failed"
    exit 1
fi
start=$(date +%s)
hashes "$native" "" "$tmp/native"
# the native frames themselves: threads change nothing, every scene renders
i=0
while IFS= read -r scene; do
    i=$((i + 1))
    one=$(one_hash "$tmp/native" $i)
    case "$one" in
        "" | error*)
            fail "native/scene$i" "volfix-sim render $scene: $(awk -v i=$i '$1 == i && $2 == 1' "$tmp/native" |
                cut -d' ' -f3-)"
            continue
            ;;
    esac
    if [ "$(awk -v i=$i -v h="$one" '$1 == i && $3 != h' "$tmp/native")" ]; then
        fail "native/scene$i" "threads change the frame: $(all_hashes "$tmp/native" $i)"
    else
        ok "native/scene$i: 1, 2 and 4 threads give one frame"
    fi
done <"$scenes"
# a comparison of hashes proves something only if different frames hash differently: every scene is another picture
distinct=$(awk '$2 == 1 { print $3 }' "$tmp/native" | sort -u | grep -c .)
if [ "$distinct" -eq "$nscenes" ]; then
    ok "native/distinct: $nscenes scenes, $distinct different frames"
else
    fail "native/distinct" "$nscenes scenes give only $distinct different hashes"
fi
echo "# native ($native): $nscenes scenes x 1, 2, 4 threads in $(($(date +%s) - start)) s"

for cross in "$@"; do
    arch=${cross##*-}
    qemu=$(qemu_for "$cross")
    if [ -z "$qemu" ] || ! command -v "$qemu" >/dev/null; then
        fail "$arch" "no qemu-user for $cross (expected qemu-aarch64 or qemu-arm: make test-cross installs qemu-user)"
        continue
    fi
    if [ ! -x "$cross/volfix-sim" ]; then
        fail "$arch" "$cross/volfix-sim is missing (make test-cross builds it)"
        continue
    fi
    # the executables must be the target's, or the comparison proves nothing
    file_arch=$(od -An -tx1 -j18 -N2 "$cross/volfix-sim" | tr -d ' ')
    case "$arch:$file_arch" in
        aarch64:b700 | armhf:2800) ;;
        *) fail "$arch" "$cross/volfix-sim is not a $arch executable (ELF machine $file_arch)"; continue ;;
    esac

    # 1. the core's and the port layer's test suites
    start=$(date +%s)
    for t in "$cross"/tests/core/test_* "$cross"/tests/port/test_*; do
        [ -x "$t" ] || continue
        name=$(basename "$(dirname "$t")")/$(basename "$t")
        if "$qemu" "$t" >"$tmp/out" 2>&1; then
            n=$(grep -c '^ok - ' "$tmp/out")
            if grep -q '^not ok - ' "$tmp/out" || [ "$n" -eq 0 ]; then
                fail "$arch/$name" "$(grep -m 1 '^not ok - ' "$tmp/out" || echo 'no cases ran')"
            else
                ok "$arch/$name ($n cases)"
            fi
        else
            status=$?
            fail "$arch/$name" "status $status under $qemu: $(grep -m 1 -E '^not ok - |error' "$tmp/out" ||
                tail -n 1 "$tmp/out")"
        fi
    done
    echo "# $arch: core and port suites under $qemu in $(($(date +%s) - start)) s"
    [ -x "$cross/tests/port/test_display_gud_usb" ] ||
        echo "# $arch: test_display_gud_usb not built (no umockdev for the target; it runs natively in make test)"

    # 2. the frames
    start=$(date +%s)
    hashes "$cross" "$qemu" "$tmp/$arch"
    i=0
    while IFS= read -r scene; do
        i=$((i + 1))
        mine=$(all_hashes "$tmp/$arch" $i)
        theirs=$(all_hashes "$tmp/native" $i)
        if [ "$mine" = "$theirs" ] && ! echo "$mine" | grep -q error; then
            ok "$arch/frame$i: $scene (1, 2, 4 threads: $(one_hash "$tmp/$arch" $i))"
        else
            fail "$arch/frame$i" "$scene: $arch ${mine}differs from x86-64 $theirs"
        fi
    done <"$scenes"
    echo "# $arch: $nscenes scenes x 1, 2, 4 threads under $qemu in $(($(date +%s) - start)) s"
done

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
