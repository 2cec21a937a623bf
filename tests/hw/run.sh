#!/bin/sh
# SPDX-License-Identifier: MIT
# make test-hw: the GPIO and GUD display backends against real kernel interfaces, in a Linux VM (qemu, TCG).
# See tests/hw/README.md for what runs and why. Everything it needs comes from Debian's archive into $BUILD/hw/:
# Debian's own kernel (image, headers, kbuild, and the source for gpio-sim, built here out of tree), and
# libgpiod 2.x from trixie for a second build of the GPIO test. Prints the VM's "ok - " / "not ok - " lines and
# ends with "N passed, N failed"; exits 1 if anything failed or the VM did not finish in time.
#
# Usage: BUILD=build sh tests/hw/run.sh     (make test-hw does this, after make all and tools/deps.sh hw)
# Environment: HW_TIMEOUT (seconds for the VM, default 300), HW_KEEP_LISTS=1 (do not refresh the trixie lists)
# shellcheck disable=SC2086,SC3013 # $APT_OPTS and $MAKE are word lists on purpose; dash and bash have -nt
set -u
cd "$(dirname "$0")/../.." || exit 2
ROOT=$(pwd)
BUILD=${BUILD:-build}
case "$BUILD" in /*) ;; *) BUILD="$ROOT/$BUILD" ;; esac
HW="$BUILD/hw"
MAKE=${MAKE:-make}
TIMEOUT=${HW_TIMEOUT:-300}
ARCH_LIB=x86_64-linux-gnu
START=$(date +%s)

# A failure before the VM runs is one failed test, with its reason on one line.
setup_fail() {
    echo "not ok - hw/setup: $*"
    echo "0 passed, 1 failed"
    exit 1
}
step() { echo "# test-hw: $* ($(($(date +%s) - START)) s)"; }

mkdir -p "$HW" || setup_fail "cannot create $HW"
for tool in qemu-system-x86_64 cpio gzip xz depmod modprobe apt-get apt-cache dpkg-deb gcc-12 make ldd readelf; do
    command -v "$tool" >/dev/null 2>&1 ||
        setup_fail "$tool is missing: run 'sh tools/deps.sh hw' as root (or make test-hw, which does)"
done

# Quietly run a command, its output in a log; on failure the log's tail and a one-line reason.
logged() {
    log=$1
    why=$2
    shift 2
    if ! "$@" >"$log" 2>&1; then
        tail -n 15 "$log" | sed 's/^/#   /'
        setup_fail "$why (log: $log)"
    fi
}

# -------------------------------------------------------------------------------------------------------------
# 1. Debian's kernel: the version linux-image-amd64 depends on today, unpacked (never installed) under $HW.
APT_OPTS="-q -o APT::Sandbox::User=root"
updated=0
apt_update() {
    [ "$(id -u)" = 0 ] || setup_fail "the package lists are stale or missing: run 'apt-get update' as root"
    logged "$HW/apt-update.log" "apt-get update failed" apt-get update -q
    updated=1
}
# The kernel's names: IMAGE linux-image-6.1.0-56-amd64, KREL 6.1.0-56-amd64, KABI 6.1.0-56, KSER 6.1, KVER 6.1.192-2
resolve_kernel() {
    IMAGE=$(apt-cache depends linux-image-amd64 2>/dev/null |
        sed -n 's/^ *Depends: \(linux-image-[0-9][^ ]*\)$/\1/p' | head -n 1)
    [ -n "$IMAGE" ] || return 1
    KREL=${IMAGE#linux-image-}
    KABI=${KREL%-amd64}
    KSER=$(echo "$KREL" | cut -d. -f1,2)
    KVER=$(apt-cache show --no-all-versions "$IMAGE" 2>/dev/null | sed -n 's/^Version: //p' | head -n 1)
    [ -n "$KVER" ] || return 1
    K="$HW/kernel/${KREL}_$KVER"
    KROOT="$K/root"
    HEADERS="$KROOT/usr/src/linux-headers-$KREL"
}
download_kernel() {
    rm -rf "$K"
    mkdir -p "$K/debs" "$KROOT"
    (cd "$K/debs" && apt-get download $APT_OPTS "$IMAGE=$KVER" "linux-headers-$KREL=$KVER" \
        "linux-headers-$KABI-common=$KVER" "linux-kbuild-$KSER=$KVER" "linux-source-$KSER=$KVER") \
        >"$HW/download.log" 2>&1
}
if ! resolve_kernel; then
    apt_update
    resolve_kernel || setup_fail "apt-cache: linux-image-amd64 depends on no linux-image-* package with a version"
fi
step "kernel $IMAGE $KVER"

if [ ! -f "$K/.unpacked" ]; then
    step "downloading the kernel image, headers, kbuild and source (~220 MB, once)"
    if ! download_kernel; then
        # the lists may name a version the archive has dropped: refresh them once and take today's kernel
        [ $updated = 1 ] || { apt_update && resolve_kernel; } || setup_fail "no kernel version after apt-get update"
        [ -f "$K/.unpacked" ] || download_kernel || {
            tail -n 5 "$HW/download.log" | sed 's/^/#   /'
            setup_fail "apt-get download of $IMAGE $KVER and its headers, kbuild and source failed (log: $HW/download.log)"
        }
    fi
fi
if [ ! -f "$K/.unpacked" ]; then
    for deb in "$K"/debs/linux-image-*.deb "$K"/debs/linux-headers-*.deb "$K"/debs/linux-kbuild-*.deb; do
        dpkg-deb -x "$deb" "$KROOT" || setup_fail "dpkg-deb -x $deb failed"
    done
    # The headers' Makefile includes the common headers by their installed path; point it at ours.
    [ -f "$HEADERS/Makefile" ] || setup_fail "$HEADERS/Makefile missing from linux-headers-$KREL"
    echo "include $KROOT/usr/src/linux-headers-$KABI-common/Makefile" >"$HEADERS/Makefile"
    # gpio-sim's sources from the linux-source tarball (only the three files; the tarball is 140 MB)
    mkdir -p "$K/src"
    dpkg-deb --fsys-tarfile "$K"/debs/linux-source-*.deb |
        tar -xO "./usr/src/linux-source-$KSER.tar.xz" |
        tar -xJ -C "$K/src" "linux-source-$KSER/drivers/gpio/gpio-sim.c" "linux-source-$KSER/drivers/gpio/gpiolib.h" \
            "linux-source-$KSER/kernel/irq/irq_sim.c" ||
        setup_fail "could not extract gpio-sim.c, gpiolib.h and irq_sim.c from linux-source-$KSER"
    rm -rf "$K/debs"
    touch "$K/.unpacked"
fi
VMLINUZ="$KROOT/boot/vmlinuz-$KREL"
[ -f "$VMLINUZ" ] || setup_fail "$VMLINUZ missing (delete $K and run again)"

# -------------------------------------------------------------------------------------------------------------
# 2. gpio-sim, out of tree, with the interrupt simulator linked in (Debian's kernel has neither).
MOD="$K/gpio-sim"
if [ ! -f "$MOD/gpio-sim.ko" ] || [ tests/hw/gpio-sim/Kbuild -nt "$MOD/gpio-sim.ko" ] || [ "$0" -nt "$MOD/gpio-sim.ko" ]; then
    step "building gpio-sim.ko against linux-headers-$KREL"
    rm -rf "$MOD"
    mkdir -p "$MOD"
    S="$K/src/linux-source-$KSER"
    cp tests/hw/gpio-sim/Kbuild "$MOD/Kbuild"
    cp "$S/drivers/gpio/gpio-sim.c" "$MOD/gpio-sim-main.c"
    cp "$S/drivers/gpio/gpiolib.h" "$MOD/gpiolib.h"
    # The shim: irq_sim.c calls irq_to_desc(), which the kernel does not export to modules. The irq's handler is
    # handle_simple_irq (irq_sim_domain_map sets it), so generic_handle_irq(irq), which is exported and calls the
    # irq's handler with its descriptor, does exactly the same.
    sed 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$S/kernel/irq/irq_sim.c" >"$MOD/irq_sim.c"
    grep -q 'irq_to_desc' "$MOD/irq_sim.c" &&
        setup_fail "irq_sim.c of linux-source-$KSER calls irq_to_desc() in a way the shim in tests/hw/run.sh does not know"
    grep -q 'CONFIG_CC_VERSION_TEXT="gcc-12' "$HEADERS/.config" ||
        echo "# test-hw: note: the kernel was not built with gcc-12: $(grep CONFIG_CC_VERSION_TEXT "$HEADERS/.config")"
    logged "$MOD/build.log" "building gpio-sim.ko failed" make -C "$HEADERS" M="$MOD" modules
    [ -f "$MOD/gpio-sim.ko" ] || setup_fail "make produced no gpio-sim.ko (log: $MOD/build.log)"
    grep -q 'undefined!' "$MOD/build.log" && setup_fail "gpio-sim.ko has undefined symbols (log: $MOD/build.log)"
    mkdir -p "$KROOT/lib/modules/$KREL/extra"
    cp "$MOD/gpio-sim.ko" "$KROOT/lib/modules/$KREL/extra/gpio-sim.ko"
    depmod -b "$KROOT" "$KREL" || setup_fail "depmod on the unpacked kernel failed"
fi

# -------------------------------------------------------------------------------------------------------------
# 3. libgpiod 2.x from Debian trixie, into a private prefix through a private apt source list.
T="$HW/trixie"
PREFIX="$T/prefix"
GPIOD2_PC="$PREFIX/usr/lib/$ARCH_LIB/pkgconfig"
if [ ! -f "$T/.unpacked" ]; then
    step "downloading libgpiod 2.x from trixie"
    rm -rf "$T"
    mkdir -p "$T/lists/partial" "$T/cache/archives/partial" "$T/debs" "$PREFIX"
    # the mirror this machine's apt already uses (a CI proxy, say), else Debian's own
    MIRROR=$(sed -n 's|^URIs: *\(http[^ ]*/debian\)/*$|\1|p' /etc/apt/sources.list.d/*.sources 2>/dev/null | head -n 1)
    [ -n "$MIRROR" ] || MIRROR=$(sed -n 's|^deb \(http[^ ]*/debian\)/* .*|\1|p' /etc/apt/sources.list 2>/dev/null | head -n 1)
    echo "deb ${MIRROR:-http://deb.debian.org/debian} trixie main" >"$T/sources.list"
    TAPT="$APT_OPTS -o Dir::Etc::sourcelist=$T/sources.list -o Dir::Etc::sourceparts=- -o Dir::State::Lists=$T/lists
          -o Dir::Cache=$T/cache -o Debug::NoLocking=1"
    # shellcheck disable=SC2086
    logged "$T/update.log" "apt-get update of the private trixie list failed" apt-get $TAPT update
    # shellcheck disable=SC2086
    (cd "$T/debs" && apt-get $TAPT download libgpiod-dev/trixie libgpiod3/trixie) >"$T/download.log" 2>&1 ||
        { tail -n 5 "$T/download.log" | sed 's/^/#   /'; setup_fail "apt-get download libgpiod-dev/trixie libgpiod3/trixie failed (log: $T/download.log)"; }
    for deb in "$T"/debs/*.deb; do
        dpkg-deb -x "$deb" "$PREFIX" || setup_fail "dpkg-deb -x $deb failed"
    done
    [ -f "$GPIOD2_PC/libgpiod.pc" ] || setup_fail "trixie's libgpiod-dev has no $GPIOD2_PC/libgpiod.pc"
    rm -rf "$T/lists" "$T/cache"
    touch "$T/.unpacked"
fi

# -------------------------------------------------------------------------------------------------------------
# 4. The programs: with this build's libraries (libgpiod 1.6), and test_gpio again with libgpiod 2.x.
step "building the test programs"
logged "$HW/make-hw.log" "make hw-progs failed" $MAKE --no-print-directory BUILD="$BUILD" hw-progs
logged "$HW/make-gpiod2.log" "building test_gpio against libgpiod 2.x failed" \
    $MAKE --no-print-directory BUILD="$HW/gpiod2" GPIOD_PKG_CONFIG_PATH="$GPIOD2_PC" GPIOD_SYSROOT="$PREFIX" \
    "$HW/gpiod2/hw/bin/test_gpio"
needs() { readelf -d "$1" 2>/dev/null | grep -q "Shared library: \[$2\]"; }
needs "$BUILD/hw/bin/test_gpio" libgpiod.so.2 || setup_fail "$BUILD/hw/bin/test_gpio is not linked with libgpiod 1.6 (libgpiod.so.2)"
needs "$HW/gpiod2/hw/bin/test_gpio" libgpiod.so.3 ||
    setup_fail "$HW/gpiod2/hw/bin/test_gpio is not linked with libgpiod 2.x (libgpiod.so.3): the Makefile's GPIOD_PKG_CONFIG_PATH did not take"

# -------------------------------------------------------------------------------------------------------------
# 5. The initramfs: busybox, /init, the modules in load order, the programs and their shared libraries.
step "assembling the initramfs"
I="$HW/initramfs"
rm -rf "$I"
mkdir -p "$I/bin" "$I/dev" "$I/proc" "$I/sys" "$I/tmp" "$I/modules" "$I/lib/$ARCH_LIB" "$I/lib64" "$I/hw/bin" \
    "$I/hw/gpiod1" "$I/hw/gpiod2"
mknod -m 600 "$I/dev/console" c 5 1 2>/dev/null || true

BUSYBOX=/bin/busybox # from busybox-static; a dynamic one (package busybox) would need its libraries
if [ ! -x "$BUSYBOX" ] || readelf -l "$BUSYBOX" 2>/dev/null | grep -q 'program interpreter'; then
    BUSYBOX="$HW/busybox/bin/busybox"
    if [ ! -x "$BUSYBOX" ]; then
        mkdir -p "$HW/busybox"
        (cd "$HW/busybox" && apt-get download $APT_OPTS busybox-static && dpkg-deb -x busybox-static_*.deb .) \
            >"$HW/busybox.log" 2>&1 || setup_fail "no static busybox: apt-get download busybox-static failed (log: $HW/busybox.log)"
    fi
fi
cp "$BUSYBOX" "$I/bin/busybox"
cp tests/hw/init.in "$I/init"
chmod 755 "$I/init" "$I/bin/busybox"

# modules and their dependencies, in load order (modules.dep from depmod on the unpacked kernel)
MODS="configfs dummy_hcd libcomposite usb_f_fs usbtest gpio-sim"
: >"$I/modules/order"
for m in $MODS; do
    modprobe -d "$KROOT" -S "$KREL" --show-depends "$m" 2>"$HW/modprobe.log" ||
        setup_fail "module $m not found for $KREL: $(head -n 1 "$HW/modprobe.log")"
done | awk '$1 == "insmod" && !seen[$2]++ { print $2 }' >"$HW/modules.list"
[ -s "$HW/modules.list" ] || setup_fail "modprobe --show-depends listed no modules"
while read -r path; do
    base=$(basename "$path")
    cp "$path" "$I/modules/$base" || setup_fail "cannot copy $path"
    case "$base" in
    # usbtest binds to the GUD gadget's 1d50:614d, standing in for the gud driver Debian's kernel lacks
    usbtest.ko*) echo "$base vendor=0x1d50 product=0x614d" >>"$I/modules/order" ;;
    *) echo "$base" >>"$I/modules/order" ;;
    esac
done <"$HW/modules.list"

cp "$BUILD/hw/bin/test_gud" "$BUILD/hw/bin/gud_gadget" "$I/hw/bin/"
cp "$BUILD/hw/bin/test_gpio" "$I/hw/gpiod1/test_gpio"
cp "$HW/gpiod2/hw/bin/test_gpio" "$I/hw/gpiod2/test_gpio"
# shared libraries, as ldd resolves them here (libgpiod.so.3 from the trixie prefix, the rest from the system:
# trixie's libgpiod3 needs glibc >= 2.33 and bookworm has 2.36, so one libc serves both builds)
for prog in "$I/hw/bin/test_gud" "$I/hw/bin/gud_gadget" "$I/hw/gpiod1/test_gpio" "$I/hw/gpiod2/test_gpio"; do
    LD_LIBRARY_PATH="$PREFIX/usr/lib/$ARCH_LIB" ldd "$prog" || setup_fail "ldd $prog failed"
done >"$HW/ldd.log" 2>&1
grep -q 'not found' "$HW/ldd.log" && setup_fail "a shared library of the test programs is missing: $(grep 'not found' "$HW/ldd.log" | head -n 1)"
for lib in $(awk '$2 == "=>" && $3 ~ /^\// { print $3 } $1 ~ /^\/.*ld-linux/ { print $1 }' "$HW/ldd.log" | sort -u); do
    case "$lib" in
    */ld-linux-x86-64.so.2) cp -L "$lib" "$I/lib64/ld-linux-x86-64.so.2" ;;
    *) cp -L "$lib" "$I/lib/$ARCH_LIB/$(basename "$lib")" ;;
    esac || setup_fail "cannot copy $lib"
done
(cd "$I" && find . | LC_ALL=C sort | cpio -o -H newc --quiet | gzip -1) >"$HW/initramfs.gz" ||
    setup_fail "cpio of the initramfs failed"

# -------------------------------------------------------------------------------------------------------------
# 6. Boot it and read the console.
step "booting the VM (qemu TCG; log: $HW/console.log)"
CONSOLE="$HW/console.log"
# One CPU, as on the smallest boards; with two, the kernel's gpio-cdev itself merges edges that come faster than
# its interrupt thread runs (tests/hw/README.md), and "full speed" would test that instead of the backend.
# -icount: the guest's clock counts its own instructions (1 ns each) and skips its idle time, so a busy host (CI)
# cannot stretch a 1 ms glitch past a 10 ms debounce window, and waiting costs no real time.
timeout -k 10 "$TIMEOUT" qemu-system-x86_64 -accel tcg -icount shift=0,sleep=off -m 512 -smp 1 \
    -kernel "$VMLINUZ" -initrd "$HW/initramfs.gz" \
    -append "console=ttyS0 quiet panic=-1" -nographic -no-reboot -net none </dev/null >"$CONSOLE" 2>&1
qemu_status=$?
tr -d '\r' <"$CONSOLE" >"$CONSOLE.txt"
grep -E '^(ok|not ok) - |^# ' "$CONSOLE.txt"
passed=$(grep -c '^ok - ' "$CONSOLE.txt")
failed=$(grep -c '^not ok - ' "$CONSOLE.txt")
summary=$(grep -E '^[0-9]+ passed, [0-9]+ failed$' "$CONSOLE.txt" | tail -n 1)
if [ -z "$summary" ]; then
    if [ "$qemu_status" = 124 ] || [ "$qemu_status" = 137 ]; then
        echo "not ok - hw/vm: the VM printed no summary within $TIMEOUT s (console: $CONSOLE)"
    else
        echo "not ok - hw/vm: the VM stopped (qemu status $qemu_status) without a summary (console: $CONSOLE)"
    fi
    grep -vE '^(ok|not ok) - |^# ' "$CONSOLE.txt" | tail -n 15 | sed 's/^/#   /'
    failed=$((failed + 1))
elif [ "$summary" != "$passed passed, $failed failed" ]; then
    echo "not ok - hw/vm: the VM counted '$summary' but its console shows $passed ok and $failed not ok lines"
    failed=$((failed + 1))
fi
step "done"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
