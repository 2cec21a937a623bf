#!/bin/sh
# SPDX-License-Identifier: MIT
# The target's zlib and libpng for a cross build, as static libraries and headers in a private directory:
# Debian's own -dev packages for that architecture, fetched with `apt-get download` and unpacked with dpkg-deb.
#
# Why not multiarch (`apt-get install libpng-dev:arm64`)? Multiarch packages are "Multi-Arch: same": the arm64
# and the amd64 copy must have the very same version, down to libc6-dev and linux-libc-dev that libpng-dev
# pulls in. Whenever the mirror's arm64 lists lag the amd64 ones (a security update, a point release) or the
# machine has older amd64 packages, apt refuses ("held broken packages"), and installing would upgrade the host's
# own libraries. Unpacked privately, the target's libraries have no tie to the host's. A build links them
# statically, so nothing of them is needed at run time (qemu-user or a board).
#
# Needs the architecture in apt's lists: `dpkg --add-architecture arm64 && apt-get update` (tools/deps.sh cross).
# Usage: tools/cross-sysroot.sh DEB_ARCH TRIPLET DIR     e.g. arm64 aarch64-linux-gnu build-aarch64/sysroot
set -u
arch=$1 triplet=$2 dir=$3
pkgs="zlib1g-dev:$arch libpng-dev:$arch"

fail() {
    echo "volfix: $*" >&2
    exit 1
}
for p in $pkgs; do
    apt-cache show "$p" >/dev/null 2>&1 ||
        fail "apt knows no $p: add the architecture once, as root: dpkg --add-architecture $arch && apt-get update (or: sudo sh tools/deps.sh cross)"
done
rm -rf "$dir" && mkdir -p "$dir/debs" || fail "cannot create $dir"
# shellcheck disable=SC2086
(cd "$dir/debs" && apt-get download -q -o APT::Sandbox::User=root $pkgs) >"$dir/download.log" 2>&1 ||
    { tail -n 5 "$dir/download.log" >&2; fail "apt-get download $pkgs failed (log: $dir/download.log)"; }
for deb in "$dir"/debs/*.deb; do
    dpkg-deb -x "$deb" "$dir" || fail "dpkg-deb -x $deb failed"
done
# Only the static libraries: a dangling libpng.so link must not turn a static link into a dynamic one.
rm -f "$dir/usr/lib/$triplet"/*.so
for f in usr/include/png.h usr/include/zlib.h "usr/lib/$triplet/libpng.a" "usr/lib/$triplet/libz.a"; do
    [ -e "$dir/$f" ] || fail "$f is missing from the unpacked packages in $dir"
done
rm -rf "$dir/debs"
echo "volfix: the $arch zlib and libpng (static) are in $dir"
touch "$dir/.unpacked"
