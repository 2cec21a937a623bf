#!/bin/sh
# SPDX-License-Identifier: MIT
# make install and make uninstall, as a packager runs them:
#   1. make install PREFIX=/usr/local DESTDIR=TMP from this build puts the libraries, the public headers,
#      volfix.pc, the programs and the boards (with the script a board names) where they belong, and rebuilds
#      nothing; a ten-line program builds with `pkg-config --cflags --libs volfix` (PKG_CONFIG_SYSROOT_DIR=TMP)
#      and prints vf_version(), which is core/volfix.h's version and CHANGELOG.md's newest; `pkg-config --static`
#      names the port layer's libraries; nothing installed mentions ../shared/data; make uninstall leaves nothing;
#   2. installed for real into a PREFIX of its own (a build of its own at -O0 without debugging information, since
#      the boards' folder is compiled into volfix), volfix finds a board by name (--board host-headless) and its knob script beside it, and
#      --version says the version.
cd "$(dirname "$0")/../.." || exit 2
build=${BUILD:-build}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
jobs=$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)

ok() { echo "ok - install/$1"; }
fail() { echo "not ok - install/$1: $2"; }

version=$(sed -n 's/^#define VF_VERSION_[A-Z]* *\([0-9]*\)$/\1/p' core/volfix.h | paste -sd. -)
dest=$tmp/dest
prefix=/usr/local
unset MAKEFLAGS MFLAGS

# 1. DESTDIR
if ! make --no-print-directory BUILD="$build" SAN="${SAN:-}" PREFIX=$prefix DESTDIR="$dest" install \
    >"$tmp/install.log" 2>&1; then
    fail "make install" "$(grep -m 3 -iE 'error|no rule|cannot' "$tmp/install.log" | tr '\n' ' ')"
    exit 0
fi
compiled=$(grep -cE '^(gcc|cc|clang|ar) ' "$tmp/install.log")
[ "$compiled" -eq 0 ] && ok "make install from a built tree rebuilds nothing" ||
    fail "make install rebuilds nothing" "$compiled compiler or archiver commands: $(grep -m 2 -E '^(gcc|ar) ' \
        "$tmp/install.log" | cut -c1-120 | tr '\n' ' ')"
expected="bin/volfix bin/volfix-sim lib/libvolfix.a lib/libvolfix-port.a lib/pkgconfig/volfix.pc
include/volfix/volfix.h include/volfix/vf_config.h share/volfix/boards/host-headless.script"
for b in boards/*.board; do expected="$expected share/volfix/boards/${b#boards/}"; done
missing=""
for f in $expected; do [ -f "$dest$prefix/$f" ] || missing="$missing $f"; done
extra=$(cd "$dest$prefix" && find . -type f | sed 's|^\./||' | while read -r f; do
    case " $(echo $expected) " in *" $f "*) ;; *) echo "$f" ;; esac
done)
[ -z "$missing" ] && [ -z "$extra" ] && ok "the files land under DESTDIR$prefix ($(echo $expected | wc -w) files)" ||
    fail "the installed files" "missing:${missing:- none}; unexpected: ${extra:-none}"
[ -x "$dest$prefix/bin/volfix" ] && [ -x "$dest$prefix/bin/volfix-sim" ] && ok "the programs are executable" ||
    fail "the programs are executable" "$(ls -l "$dest$prefix/bin" 2>&1 | tr '\n' ' ')"
if grep -l 'shared/data' "$dest$prefix"/bin/* "$dest$prefix"/lib/*.a >"$tmp/mention" 2>/dev/null; then
    fail "nothing installed looks for ../shared/data" "$(tr '\n' ' ' <"$tmp/mention")"
else
    ok "nothing installed looks for ../shared/data"
fi

# the ten-line program, built as a user of the installed library builds it
cat >"$tmp/hello.c" <<'EOF'
#include <stdio.h>
#include <string.h>
#include "volfix.h"

int main(void)
{
    printf("%s %d.%d.%d\n", vf_version(), VF_VERSION_MAJOR, VF_VERSION_MINOR, VF_VERSION_PATCH);
    return strcmp(vf_status_text(VF_OK), "ok") != 0;
}
EOF
pc() { PKG_CONFIG_PATH="$dest$prefix/lib/pkgconfig" PKG_CONFIG_SYSROOT_DIR="$dest" pkg-config "$@"; }
flags=$(pc --cflags --libs volfix 2>"$tmp/pc.err")
# shellcheck disable=SC2086 # the flags are words
if [ -z "$flags" ]; then
    fail "pkg-config --cflags --libs volfix" "$(cat "$tmp/pc.err")"
elif ! ${CC:-gcc} -o "$tmp/hello" "$tmp/hello.c" $flags >"$tmp/cc.log" 2>&1; then
    fail "a program builds with pkg-config's flags ($flags)" "$(head -n 3 "$tmp/cc.log" | tr '\n' ' ')"
elif [ "$("$tmp/hello")" != "$version $version" ]; then
    fail "the program prints vf_version()" "it printed '$("$tmp/hello")', expected '$version $version'"
else
    ok "a program built with pkg-config --cflags --libs volfix prints vf_version() $version"
fi
[ "$(pc --modversion volfix 2>&1)" = "$version" ] && ok "volfix.pc's version is $version" ||
    fail "volfix.pc's version" "$(pc --modversion volfix 2>&1), expected $version"
changelog=$(sed -n 's/^## \([0-9][0-9.]*\).*/\1/p' CHANGELOG.md | head -n 1)
[ "$changelog" = "$version" ] && ok "CHANGELOG.md's newest version is core/volfix.h's ($version)" ||
    fail "CHANGELOG.md's newest version" "'$changelog', expected $version"
static=$(pc --static --libs volfix 2>&1)
case "$static" in
*-lpng*-lz* | *-lz*-lpng*) ok "pkg-config --static --libs volfix adds the port layer's libraries" ;;
*) fail "pkg-config --static --libs volfix" "'$static' lacks libpng or zlib" ;;
esac

if make --no-print-directory BUILD="$build" SAN="${SAN:-}" PREFIX=$prefix DESTDIR="$dest" uninstall \
    >"$tmp/uninstall.log" 2>&1; then
    left=$(find "$dest" -type f; find "$dest" -depth -type d -name volfix)
    [ -z "$left" ] && ok "make uninstall removes every file and folder of volfix's" ||
        fail "make uninstall removes everything" "left: $(echo $left)"
else
    fail "make uninstall" "$(tail -n 3 "$tmp/uninstall.log" | tr '\n' ' ')"
fi

# 2. a PREFIX of its own: volfix finds its boards by name
own=$tmp/usr
if ! make --no-print-directory -j"$jobs" BUILD="$tmp/build" OPT=-O0 EXTRA_CFLAGS=-g0 PREFIX="$own" install \
    >"$tmp/own.log" 2>&1; then
    fail "make install PREFIX=$own" "$(grep -m 3 -iE 'error|no rule' "$tmp/own.log" | tr '\n' ' ')"
    exit 0
fi
printf '# nothing\n300 quit\n' >"$tmp/idle.script"
cd "$tmp" || exit 2 # away from the tree: nothing may come from it
if "$own/bin/volfix" --board host-headless phantom:sphere:16 --device "$tmp/frames" --log "$tmp/frames.log" \
    >"$tmp/run.out" 2>&1 && [ -s "$tmp/frames.log" ]; then
    ok "the installed volfix finds --board host-headless and the script beside it ($(wc -l <"$tmp/frames.log") frames)"
else
    fail "the installed volfix finds --board host-headless" "$(head -n 2 "$tmp/run.out" | tr '\n' ' ')"
fi
if "$own/bin/volfix" --board host-headless.board phantom:sphere:16 --script "$tmp/idle.script" \
    --device "$tmp/frames2" >"$tmp/named.out" 2>&1 && [ -n "$(ls "$tmp/frames2" 2>/dev/null)" ]; then
    ok "--board host-headless.board is the same installed board"
else
    fail "--board host-headless.board" "$(head -n 2 "$tmp/named.out" | tr '\n' ' ')"
fi
"$own/bin/volfix" --board nope phantom:sphere:16 >"$tmp/nope.out" 2>&1
status=$?
[ $status -eq 2 ] && grep -qF "no board of that name in $own/share/volfix/boards" "$tmp/nope.out" &&
    ok "an unknown board name: status 2 and where it looked" ||
    fail "an unknown board name" "status $status: $(cat "$tmp/nope.out")"
[ "$("$own/bin/volfix" --version)" = "volfix $version" ] &&
    [ "$("$own/bin/volfix-sim" --version)" = "volfix-sim $version" ] &&
    ok "the installed programs' --version: $version" ||
    fail "--version" "'$("$own/bin/volfix" --version 2>&1)' and '$("$own/bin/volfix-sim" --version 2>&1)'"
