#!/bin/sh
# Install the Debian packages that `make run` or `make test` need, when they are missing.
# As root it runs apt-get itself; otherwise it prints the one command to run and fails.
# Usage: tools/deps.sh run|test|hw
set -u
for_what=${1:-run}

# the core and volfix-sim; the viewer's backends (displays, knobs) come with their libraries when present
need="gcc make pkg-config zlib1g-dev libpng-dev gnuplot-nox libdrm-dev libusb-1.0-0-dev liblz4-dev libsdl2-dev libgpiod-dev"
case "$for_what" in
  test) need="$need gcc-aarch64-linux-gnu gcc-arm-linux-gnueabihf valgrind umockdev libumockdev-dev xvfb xauth xdotool imagemagick" ;;
  # make test-hw: a Debian kernel in qemu (TCG), an initramfs from busybox, the gpio-sim module built out of tree
  hw) need="$need qemu-system-x86 busybox-static cpio kmod xz-utils gzip gcc-12 make binutils" ;;
esac

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
  echo "volfix: run this once, then try again:  sudo apt-get install -y$missing" >&2
  exit 1
fi
echo "volfix: installing$missing"
export DEBIAN_FRONTEND=noninteractive
# Install from the current package lists first; refresh them only if that fails (they may be stale or absent).
apt-get install -y -q $missing >/tmp/volfix-apt.log 2>&1 ||
  { apt-get update -q >>/tmp/volfix-apt.log 2>&1 && apt-get install -y -q $missing >>/tmp/volfix-apt.log 2>&1; } ||
  { tail -n 20 /tmp/volfix-apt.log >&2; echo "volfix: apt-get install failed (log: /tmp/volfix-apt.log)" >&2; exit 1; }
