#!/bin/sh
# SPDX-License-Identifier: MIT
# An optional package that arrives after the first build. On a fresh clone `make run` once built the tests before
# `make test` installed umockdev, and nothing rebuilt them; port objects built without a backend were never
# rebuilt once its library appeared. This plays that in a copy of the tree, with pkg-config looking at a copy of
# the system's .pc files (PKG_CONFIG_LIBDIR) from which the optional packages' files are taken out, then put back:
#
#   1. plain make without the optional packages builds and says which backends and tests it left out;
#   2. the backends' libraries arrive (all but umockdev): make rebuilds the port layer and not the core, and the
#      port library it leaves is a clean build's (the same global symbols);
#   3. umockdev arrives: make rebuilds test_display_gud_usb and nothing else, and the suite passes;
#   4. make clean removes every folder the builds made.
#
# The builds are at -O0 without debugging information: what is checked is the Makefile, and they are the test's
# cost.
# Usage: tests/build/late_package.sh [TREE]   (TREE: the checkout whose Makefile is tested, default this one)
cd "$(dirname "$0")/../.." || exit 2
here=$(pwd)
src=${1:-$here}
tmp=$(mktemp -d)
trap '[ -n "${KEEP:-}" ] || rm -rf "$tmp"' EXIT
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)

ok() { echo "ok - late-package/$1"; }
fail() { echo "not ok - late-package/$1: $2"; }

# The system's .pc files, and which optional ones this machine has to arrive late.
mkdir -p "$tmp/pc-all" "$tmp/pc-none" "$tmp/pc-no-umockdev"
for d in $(pkg-config --variable pc_path pkg-config | tr ':' ' ') $(echo "${PKG_CONFIG_PATH:-}" | tr ':' ' '); do
    [ -d "$d" ] && cp -p "$d"/*.pc "$tmp/pc-all/" 2>/dev/null
done
backends=""
for m in libdrm libusb-1.0 liblz4 sdl2 libgpiod; do
    [ -f "$tmp/pc-all/$m.pc" ] && backends="$backends $m"
done
if [ -z "$backends" ] || [ ! -f "$tmp/pc-all/umockdev-1.0.pc" ]; then
    echo "skip - late-package: needs the optional packages' .pc files to take out and put back (install" \
        "libdrm-dev libusb-1.0-0-dev libsdl2-dev libgpiod-dev libumockdev-dev)"
    exit 0
fi
cp -p "$tmp/pc-all"/*.pc "$tmp/pc-none/"
cp -p "$tmp/pc-all"/*.pc "$tmp/pc-no-umockdev/"
for m in $backends umockdev-1.0; do rm -f "$tmp/pc-none/$m.pc"; done
rm -f "$tmp/pc-no-umockdev/umockdev-1.0.pc"

# The tree without its build folders (uncommitted changes included).
mkdir -p "$tmp/tree"
(cd "$src" && tar cf - --exclude='./build*' --exclude=./out --exclude=./.git .) | (cd "$tmp/tree" && tar xf -) ||
    { fail "copy" "cannot copy $src"; exit 0; }
cd "$tmp/tree" || exit 2
unset BUILD SAN MAKEFLAGS MFLAGS
build() { # PC_DIR LOG [TARGET...]: make at -O0 with pkg-config seeing PC_DIR
    pc=$1 log=$2
    shift 2
    PKG_CONFIG_LIBDIR=$pc make -j"$jobs" OPT=-O0 EXTRA_CFLAGS=-g0 "$@" >"$log" 2>&1
}
# the files a build wrote since the marker: objects, libraries and programs (not stamps, dependency files)
since() { find build -type f -newer "$1" ! -name '*.d' ! -path 'build/config*' | sort; }
mark() { touch "$1" && sleep 1; } # one second: file times that are coarse still tell the marker from a rebuild

# 1. nothing optional
if ! build "$tmp/pc-none" "$tmp/none.log"; then
    fail "make without the optional packages" "$(grep -m 3 -iE 'error|no rule' "$tmp/none.log" | tr '\n' ' ')"
    exit 0
fi
ok "make builds without the optional packages"
line=$(grep '^volfix: left out' "$tmp/none.log")
missing=""
for pkg in libdrm-dev libusb-1.0-0-dev libsdl2-dev libgpiod-dev libumockdev-dev test_display_gud_usb; do
    case "$line" in *"$pkg"*) ;; *) missing="$missing $pkg" ;; esac
done
[ -n "$line" ] && [ -z "$missing" ] && ok "make says what it left out: ${line#volfix: }" ||
    fail "make says what it left out" "expected a line 'volfix: left out...' naming$missing; got '$line'"

# 2. the backends' libraries arrive
mark "$tmp/before-backends"
core_before=$(ls -l --time-style=+%s.%N build/core/*.o 2>/dev/null | awk '{ print $6, $7 }')
if ! build "$tmp/pc-no-umockdev" "$tmp/backends.log"; then
    fail "make after the backends arrive" "$(grep -m 3 -iE 'error|no rule' "$tmp/backends.log" | tr '\n' ' ')"
    exit 0
fi
rebuilt=$(since "$tmp/before-backends")
port_objs=$(find build/port -name '*.o' | sort)
stale=$(for o in $port_objs; do echo "$rebuilt" | grep -qx "$o" || echo "$o"; done)
core_after=$(ls -l --time-style=+%s.%N build/core/*.o 2>/dev/null | awk '{ print $6, $7 }')
[ -n "$port_objs" ] && [ -z "$stale" ] && ok "the backends' arrival rebuilds every port object" ||
    fail "the backends' arrival rebuilds every port object" "not rebuilt: $(echo $stale | cut -c1-300)"
[ -n "$core_before" ] && [ "$core_before" = "$core_after" ] &&
    ok "the backends' arrival leaves the core alone ($(echo "$core_after" | grep -c .) objects)" ||
    fail "the backends' arrival leaves the core alone" "rebuilt: $(echo "$rebuilt" | grep '^build/core/' | tr '\n' ' ')"

# the port library is a clean build's with these packages
symbols() { nm -g --defined-only "$1" 2>/dev/null | awk 'NF == 3 { print $3 }' | sort; }
PKG_CONFIG_LIBDIR=$tmp/pc-no-umockdev make -j"$jobs" OPT=-O0 EXTRA_CFLAGS=-g0 BUILD=build-clean \
    build-clean/libvolfix-port.a >"$tmp/clean.log" 2>&1
symbols build/libvolfix-port.a >"$tmp/late.syms"
symbols build-clean/libvolfix-port.a >"$tmp/clean.syms"
if [ -s "$tmp/clean.syms" ] && cmp -s "$tmp/late.syms" "$tmp/clean.syms"; then
    ok "the port library after the arrival is a clean build's ($(grep -c . "$tmp/clean.syms") symbols)"
else
    fail "the port library after the arrival is a clean build's" \
        "symbols differ: $(diff "$tmp/late.syms" "$tmp/clean.syms" | grep '^[<>]' | head -n 5 | tr '\n' ' ')"
fi

# 3. umockdev arrives
mark "$tmp/before-umockdev"
if ! build "$tmp/pc-all" "$tmp/umockdev.log"; then
    fail "make after umockdev arrives" "$(grep -m 3 -iE 'error|no rule' "$tmp/umockdev.log" | tr '\n' ' ')"
    exit 0
fi
rebuilt=$(since "$tmp/before-umockdev")
[ "$rebuilt" = build/tests/port/test_display_gud_usb ] &&
    ok "umockdev's arrival rebuilds test_display_gud_usb and nothing else" ||
    fail "umockdev's arrival rebuilds test_display_gud_usb and nothing else" "rebuilt: '$(echo $rebuilt)'"
if ./build/tests/port/test_display_gud_usb >"$tmp/gud.out" 2>&1 && ! grep -q '^not ok' "$tmp/gud.out" &&
    grep -q '^ok - ' "$tmp/gud.out"; then
    ok "test_display_gud_usb passes after the arrival ($(grep -c '^ok - ' "$tmp/gud.out") cases)"
else
    fail "test_display_gud_usb passes after the arrival" "$(grep -m 2 -v '^ok' "$tmp/gud.out" | tr '\n' ' ')"
fi

# 4. make clean: every build folder (build-clean too), and the demo's out/
mkdir -p out
make clean >"$tmp/clean.log" 2>&1
left=$(ls -d build* out 2>/dev/null)
[ -z "$left" ] && ok "make clean removes build, build-* and out" || fail "make clean" "left: $(echo $left)"
