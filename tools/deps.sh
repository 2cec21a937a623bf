#!/bin/sh
# SPDX-License-Identifier: MIT
# Install the Debian packages that `make run` or `make test` need, when they are missing.
# As root it runs apt-get itself; otherwise it prints what is missing and the one command that installs it, and
# carries on: the build leaves out what it cannot build (and says so), and tests/run.sh counts every suite that
# cannot run as skipped, which fails make test, so nothing missing passes unnoticed. An apt-get that fails is
# reported the same way.
# Usage: tools/deps.sh run|test|hw|fuzz|mcu|cross|peers
set -u
for_what=${1:-run}

# the core and volfix-sim; the viewer's backends (displays, knobs) come with their libraries when present
need="gcc libc6-dev make pkg-config zlib1g-dev libpng-dev gnuplot-nox fonts-dejavu-core"
need="$need libdrm-dev libusb-1.0-0-dev liblz4-dev libsdl2-dev libgpiod-dev"
# DICOM: GDCM and a C++ compiler for port/io/dicom.cpp, its one C++ file
need="$need libgdcm-dev g++"
case "$for_what" in
  test) need="$need gcc-aarch64-linux-gnu gcc-arm-linux-gnueabihf libc6-dev-arm64-cross libc6-dev-armhf-cross"
        need="$need valgrind umockdev libumockdev-dev xvfb xauth xdotool imagemagick"
        # tests/port/dicom.sh and orientation.sh: series written by pydicom, compressed by GDCM's gdcmconv;
        # tests/port/libraries.sh: the NIfTI and NRRD readers against nifticlib and teem
        need="$need python3-pydicom libgdcm-tools libnifti2-dev libteem-dev"
        need="$need gcc-arm-none-eabi qemu-system-arm" # tests/mcu: the firmware for a Cortex-M4 board under qemu
        need="$need libvolpack1-dev" ;; # tests/peers: VolPack's example image against volfix
  # make test-hw: a Debian kernel in qemu (TCG), an initramfs from busybox, the gpio-sim module built out of tree
  hw) need="$need qemu-system-x86 busybox-static cpio kmod xz-utils gzip gcc-12 make binutils" ;;
  # make fuzz: clang and its libFuzzer, ASan and UBSan runtimes (compiler-rt)
  fuzz) need="$need clang libclang-rt-14-dev" ;;
  # make mcu: the core and a firmware for a Cortex-M4 (arm-none-eabi-gcc), run on the MPS2 AN386 board in qemu
  mcu) need="$need gcc-arm-none-eabi qemu-system-arm" ;;
  # make bench-peers: Debian's VolPack for volfix's own client of it (tools/peers), callgrind for the counts
  peers) need="$need libvolpack1-dev valgrind" ;;
  # make test-cross: Debian's cross compilers with their C libraries, and qemu-user to run what they build; the
  # target's zlib and libpng come from apt's lists for arm64 and armhf (tools/cross-sysroot.sh), added below
  cross) need="$need gcc-aarch64-linux-gnu gcc-arm-linux-gnueabihf libc6-dev-arm64-cross libc6-dev-armhf-cross"
         need="$need qemu-user" ;;
esac

# make test-cross downloads the targets' -dev packages: apt must know the two architectures.
foreign=""
if [ "$for_what" = cross ]; then
  for arch in arm64 armhf; do
    dpkg --print-foreign-architectures | grep -qx "$arch" || foreign="$foreign $arch"
  done
fi
if [ -n "$foreign" ]; then
  if [ "$(id -u)" != 0 ]; then
    echo "volfix: apt does not know the architectures$foreign, which the cross builds' zlib and libpng come from;" >&2
    add=$(for a in $foreign; do printf 'dpkg --add-architecture %s && ' "$a"; done)
    echo "volfix: to add them:  sudo sh -c '${add}apt-get update'" >&2
  else
    echo "volfix: adding the architectures$foreign to apt (for the cross builds' zlib and libpng)"
    for arch in $foreign; do
      dpkg --add-architecture "$arch" || echo "volfix: dpkg --add-architecture $arch failed" >&2
    done
    apt-get update -q >/tmp/volfix-apt.log 2>&1 ||
      { tail -n 20 /tmp/volfix-apt.log >&2; echo "volfix: apt-get update failed (log: /tmp/volfix-apt.log)" >&2; }
  fi
fi

missing=""
for p in $need; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)
  case "$status" in
    *"install ok installed"*) ;;
    *) missing="$missing $p" ;;
  esac
done
[ -z "$missing" ] && exit 0

if [ "$(id -u)" != 0 ]; then
  echo "volfix: missing packages:$missing" >&2
  echo "volfix: to install them:  sudo apt-get install -y --no-install-recommends$missing" >&2
  echo "volfix: carrying on without them: what needs them is left out, and the tests that need them are skipped" >&2
  exit 0
fi
echo "volfix: installing$missing"
export DEBIAN_FRONTEND=noninteractive
# Install from the current package lists first; refresh them only if that fails (they may be stale or absent).
# --no-install-recommends: what is listed is what is needed (gcc-arm-none-eabi alone recommends 1.5 GB of newlib).
apt-get install -y -q --no-install-recommends $missing >/tmp/volfix-apt.log 2>&1 ||
  { apt-get update -q >>/tmp/volfix-apt.log 2>&1 &&
    apt-get install -y -q --no-install-recommends $missing >>/tmp/volfix-apt.log 2>&1; } ||
  { tail -n 20 /tmp/volfix-apt.log >&2; echo "volfix: apt-get install failed (log: /tmp/volfix-apt.log); carrying on" \
      "without$missing: what needs them is left out or skipped" >&2; }
