# SPDX-License-Identifier: MIT
# volfix: build, demo, tests and packaging.
#
#   make            build what this machine's packages allow: the core (build/libvolfix.a), the port layer, volfix,
#                   volfix-sim and the tests; one line names the backends and tests it left out, and their packages
#   make run        install missing packages (as root; otherwise say which), build, render the demo into out/
#   make test       install missing packages (as root; otherwise say which), build, run every suite, several at a
#                   time; ends with "N passed, N failed, N skipped" and fails when a suite failed or was skipped
#   make check      the fast tier: the core's and host-sim's unit tests and one small render per mode
#   make install    PREFIX=/usr/local DESTDIR=: libvolfix.a, libvolfix-port.a, the public headers, volfix.pc,
#                   volfix, volfix-sim and the boards (volfix --board NAME finds them); make uninstall removes them
#   make bench      benchmarks (timings are never asserted in tests)
#   make test-hw    the GPIO and USB display backends against real kernel interfaces in a Linux VM (qemu;
#                   tests/hw/README.md); downloads a Debian kernel and libgpiod 2.x into $(BUILD)/hw the first time
#   make test-cross the same frames bit for bit on aarch64 and 32-bit ARM (cross compilers, qemu-user)
#   make fuzz       every parser under libFuzzer with ASan and UBSan for FUZZ_SECONDS each (clang; tests/fuzz)
#   make test-asan  every test built with AddressSanitizer and UndefinedBehaviorSanitizer
#   make test-long  the viewer for 10,000 frames (flat memory) and under valgrind
#   make clean      removes every folder the build made: $(BUILD), $(BUILD)-*, build-*, out
#
# CROSS_COMPILE=aarch64-linux-gnu- builds with a cross compiler. SAN=1 builds with ASan and UBSan.
#
# The detected configuration (the optional packages found, libgpiod's major version, the backends and tests left
# out) is written to $(BUILD)/config.mk, and each group of compiler flags to a stamp in $(BUILD)/config/, each
# rewritten only when it changes. Every object depends on the stamp of its flags, so a package installed later
# rebuilds what it changes and nothing else: a backend's library the port layer, host-sim, the viewer and the
# tests (their flags carry the backends' defines), umockdev the one test that uses it; the core, whose flags no
# package changes, never. Header dependencies come from the compiler (-MMD -MP, $(BUILD)/**/*.d).

.DEFAULT_GOAL := all
CROSS_COMPILE ?=
CC      := $(CROSS_COMPILE)gcc
AR      := $(CROSS_COMPILE)ar

# ---- Cross builds: settings (make CROSS_COMPILE=aarch64-linux-gnu- or arm-linux-gnueabihf-; make test-cross) ----
# A build directory of their own (build-aarch64, build-armhf, unless BUILD is given); static executables, so that
# qemu-user runs them with no target root file system and they copy to a board as they are; the target's zlib and
# libpng from CROSS_SYSROOT (default: Debian's -dev packages for the target, unpacked into $(BUILD)/sysroot by
# tools/cross-sysroot.sh; CROSS_SYSROOT= uses the compiler's own paths, for multiarch -dev packages); pkg-config
# looks at the target's .pc files only, so an optional backend the target lacks is left out (and said so).
ifneq ($(CROSS_COMPILE),)
  CROSS_TRIPLET := $(patsubst %-,%,$(CROSS_COMPILE))
  CROSS_ARCH    := $(if $(filter %-gnueabihf,$(CROSS_TRIPLET)),armhf,$(firstword $(subst -, ,$(CROSS_TRIPLET))))
  CROSS_DEBARCH := $(if $(filter aarch64,$(CROSS_ARCH)),arm64,$(CROSS_ARCH))
  BUILD         ?= build-$(CROSS_ARCH)
  CROSS_SYSROOT ?= $(BUILD)/sysroot
  CROSS_CFLAGS  := $(if $(CROSS_SYSROOT),-I$(CROSS_SYSROOT)/usr/include)
  LDFLAGS       += -static $(if $(CROSS_SYSROOT),-L$(CROSS_SYSROOT)/usr/lib/$(CROSS_TRIPLET))
  PKG_CONFIG    ?= PKG_CONFIG_LIBDIR=/usr/lib/$(CROSS_TRIPLET)/pkgconfig:/usr/share/pkgconfig pkg-config --static
endif
# ---- end of cross-build settings; the rules are in the block "make test-cross" below ----

BUILD   ?= build
OPT     ?= -O2
# make run, test and the other test targets build with every processor, unless make was given its own -j
JOBS     = $(if $(filter -j%,$(MAKEFLAGS)),,-j$(shell getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1))

# The sample volumes (NRRD headers; ../shared/data/README.md says where they come from). This is the one place
# that names the default: the tests and tools get the folder from the environment, and so do the programs, which
# never look for it on their own.
VOLFIX_DATA ?= ../shared/data
export VOLFIX_DATA

# Where make install puts things; volfix finds the installed boards by name in BOARD_DIR.
PREFIX     ?= /usr/local
DESTDIR    ?=
BINDIR     := $(PREFIX)/bin
LIBDIR     := $(PREFIX)/lib
INCLUDEDIR := $(PREFIX)/include
BOARD_DIR  := $(PREFIX)/share/volfix/boards
# the version, from the one place it is written (core/volfix.h)
VERSION := $(shell sed -n 's/^\#define VF_VERSION_[A-Z]* *\([0-9]*\)$$/\1/p' core/volfix.h | paste -sd. -)

# The compiler writes each object's header dependencies beside it ($@.d); a header that disappears is a phony
# target (-MP), so that its removal is a change, not an error.
DEPFLAGS = -MMD -MP -MF $@.d -MT $@

# The core: freestanding C99, integer only, no libc.
CORE_CFLAGS := -std=c99 -ffreestanding -fno-builtin -Wall -Wextra -Wpedantic -Werror -Wshadow \
               -Wstrict-prototypes -Wmissing-prototypes -Wconversion -Wno-sign-conversion -fno-tree-loop-distribute-patterns $(OPT) -g
# Everything else: hosted C11 with POSIX. 64-bit file offsets and inode numbers on 32-bit targets too (armhf: readdir
# failed with EOVERFLOW on a file system with 64-bit inodes, so boards/ looked empty; make test-cross found it).
HOST_CFLAGS := -std=c11 -D_DEFAULT_SOURCE -D_POSIX_C_SOURCE=200809L -D_FILE_OFFSET_BITS=64 -Wall -Wextra -Wshadow $(OPT) -g \
               -Icore -Iport -Ihost-sim $(CROSS_CFLAGS)
ifeq ($(SAN),1)
  SANFLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
  CORE_CFLAGS += $(SANFLAGS)
  HOST_CFLAGS += $(SANFLAGS)
  LDFLAGS += $(SANFLAGS)
endif
CORE_CFLAGS += $(EXTRA_CFLAGS)

# ---- Detection: the optional packages, read once here ----------------------------------------------------------
# Optional backends are compiled in when pkg-config finds their library (port/display/display.h,
# port/input/input.h). A private libgpiod (the 2.x test in make test-hw) comes in through GPIOD_PKG_CONFIG_PATH.
# FOUND lists what was found with its version, LEFT_OUT what was left out as "what:Debian package[+package]".
PKG_CONFIG ?= pkg-config
PORT_LIBS  := -lpng -lz -lpthread -lm
have = $(shell $(PKG_CONFIG) --exists $(1) 2>/dev/null && echo 1)
modversion = $(shell $(PKG_CONFIG) --modversion $(1) 2>/dev/null)
PORT_DEFS :=
FOUND     :=
LEFT_OUT  :=
PC_REQUIRES := zlib libpng
ifeq ($(call have,libdrm),1)
  PORT_DEFS += -DVFP_HAVE_DRM $(shell $(PKG_CONFIG) --cflags libdrm)
  PORT_LIBS += $(shell $(PKG_CONFIG) --libs libdrm)
  FOUND += libdrm-$(call modversion,libdrm)
  PC_REQUIRES += libdrm
else
  LEFT_OUT += display-drm:libdrm-dev
endif
ifeq ($(call have,libusb-1.0),1)
  PORT_DEFS += -DVFP_HAVE_GUD $(shell $(PKG_CONFIG) --cflags libusb-1.0)
  PORT_LIBS += $(shell $(PKG_CONFIG) --libs libusb-1.0)
  FOUND += libusb-1.0-$(call modversion,libusb-1.0)
  PC_REQUIRES += libusb-1.0
  ifeq ($(call have,liblz4),1)
    PORT_DEFS += -DVFP_HAVE_LZ4
    PORT_LIBS += $(shell $(PKG_CONFIG) --libs liblz4)
    FOUND += liblz4-$(call modversion,liblz4)
    PC_REQUIRES += liblz4
  else
    LEFT_OUT += gud-lz4:liblz4-dev
  endif
else
  LEFT_OUT += display-gud:libusb-1.0-0-dev
endif
ifeq ($(call have,sdl2),1)
  PORT_DEFS += -DVFP_HAVE_SDL $(shell $(PKG_CONFIG) --cflags sdl2)
  PORT_LIBS += $(shell $(PKG_CONFIG) --libs sdl2)
  FOUND += sdl2-$(call modversion,sdl2)
  PC_REQUIRES += sdl2
else
  LEFT_OUT += display-and-input-sdl:libsdl2-dev
endif
GPIOD_PC = $(if $(GPIOD_PKG_CONFIG_PATH),PKG_CONFIG_PATH=$(GPIOD_PKG_CONFIG_PATH) PKG_CONFIG_SYSROOT_DIR=$(GPIOD_SYSROOT) )$(PKG_CONFIG)
ifeq ($(shell $(GPIOD_PC) --exists libgpiod 2>/dev/null && echo 1),1)
  GPIOD_VERSION := $(shell $(GPIOD_PC) --modversion libgpiod)
  GPIOD_MAJOR := $(firstword $(subst ., ,$(GPIOD_VERSION)))
  PORT_DEFS += -DVFP_HAVE_GPIOD -DVFP_GPIOD_MAJOR=$(GPIOD_MAJOR) $(shell $(GPIOD_PC) --cflags libgpiod)
  PORT_LIBS += $(shell $(GPIOD_PC) --libs libgpiod)
  FOUND += libgpiod-$(GPIOD_VERSION)
  PC_REQUIRES += libgpiod
else
  LEFT_OUT += input-gpiod:libgpiod-dev
endif
# tests/port/test_display_gud_usb.c plays a USB display through umockdev's API (libumockdev-dev) to the GUD
# backend; without either it is left out (Debian has no target -dev package of umockdev for the cross builds).
ifeq ($(call have,umockdev-1.0),1)
  UMOCKDEV_FLAGS := -DVFP_HAVE_UMOCKDEV $(shell $(PKG_CONFIG) --cflags umockdev-1.0)
  UMOCKDEV_LIBS  := $(shell $(PKG_CONFIG) --libs umockdev-1.0)
  FOUND += umockdev-1.0-$(call modversion,umockdev-1.0)
endif
GUD_USB_TEST := tests/port/test_display_gud_usb
GUD_USB_NEEDS  := $(if $(filter -DVFP_HAVE_GUD,$(PORT_DEFS)),,libusb-1.0-0-dev) $(if $(UMOCKDEV_FLAGS),,libumockdev-dev)
LEFT_OUT_TESTS := $(if $(strip $(GUD_USB_NEEDS)),$(GUD_USB_TEST):$(subst $() ,+,$(strip $(GUD_USB_NEEDS))))
# ---- DICOM through GDCM (port/io/dicom.cpp, the one C++ file; port/io/dicom.h says what it reads) ----
# Debian's libgdcm-dev has no pkg-config file, only CMake's package files, so GDCM is found in this order: GDCM_CFLAGS
# and GDCM_LIBS given to make (a private build); pkg-config's gdcm-3.0 or gdcm, for systems that ship one; the
# GDCMConfig.cmake of an installed GDCM (lib/TRIPLET/gdcm-X.Y/ or lib/gdcm-X.Y/ under /usr or /usr/local, in the
# cross sysroot for cross builds), with its headers in PREFIX/include/gdcm-X.Y and its libraries beside the
# CMake folder, as GDCMConfig.cmake itself computes them. Each candidate counts only when gdcmImageReader.h and
# libgdcmMSFF are really there (a static libgdcmMSFF.a for the static cross builds, which Debian does not ship), and
# a C++ compiler is. GDCM=0 leaves DICOM out.
CXX := $(CROSS_COMPILE)g++
ifneq ($(GDCM),0)
  ifneq ($(GDCM_LIBS),)
    GDCM_FOUND_BY := GDCM_LIBS
  else ifeq ($(call have,gdcm-3.0),1)
    GDCM_CFLAGS := $(shell $(PKG_CONFIG) --cflags gdcm-3.0)
    GDCM_LIBS   := $(shell $(PKG_CONFIG) --libs gdcm-3.0)
    GDCM_FOUND_BY := pkg-config
  else ifeq ($(call have,gdcm),1)
    GDCM_CFLAGS := $(shell $(PKG_CONFIG) --cflags gdcm)
    GDCM_LIBS   := $(shell $(PKG_CONFIG) --libs gdcm)
    GDCM_FOUND_BY := pkg-config
  else
    GDCM_TRIPLET := $(if $(CROSS_TRIPLET),$(CROSS_TRIPLET),$(shell $(CC) -print-multiarch 2>/dev/null))
    GDCM_ROOT    := $(if $(CROSS_COMPILE),$(CROSS_SYSROOT))
    GDCM_LIBEXT  := $(if $(CROSS_COMPILE),a,so)
    # each candidate as PREFIX|LIBDIR|VERSION-DIR (gdcm-3.0), the first one complete wins
    GDCM_CANDIDATES := $(foreach c,$(wildcard $(foreach p,/usr /usr/local,$(GDCM_ROOT)$(p)/lib/$(GDCM_TRIPLET)/gdcm-*/GDCMConfig.cmake \
                       $(GDCM_ROOT)$(p)/lib/gdcm-*/GDCMConfig.cmake)),$(patsubst %/,%,$(dir $(patsubst %/,%,$(dir $(c)))))|$(notdir $(patsubst %/,%,$(dir $(c)))))
    gdcm_libdir  = $(firstword $(subst |, ,$(1)))
    gdcm_incdir  = $(patsubst %/lib,%,$(patsubst %/lib/$(GDCM_TRIPLET),%,$(call gdcm_libdir,$(1))))/include/$(lastword $(subst |, ,$(1)))
    GDCM_PICK    := $(firstword $(foreach c,$(GDCM_CANDIDATES),$(if $(and $(wildcard $(call gdcm_incdir,$(c))/gdcmImageReader.h),$(wildcard $(call gdcm_libdir,$(c))/libgdcmMSFF.$(GDCM_LIBEXT))),$(c))))
    ifneq ($(GDCM_PICK),)
      GDCM_CFLAGS := -I$(call gdcm_incdir,$(GDCM_PICK))
      GDCM_LIBS   := -L$(call gdcm_libdir,$(GDCM_PICK)) -lgdcmMSFF -lgdcmIOD -lgdcmDICT -lgdcmDSED -lgdcmCommon
      GDCM_FOUND_BY := $(call gdcm_libdir,$(GDCM_PICK))/$(lastword $(subst |, ,$(GDCM_PICK)))/GDCMConfig.cmake
    endif
  endif
endif
ifneq ($(and $(GDCM_FOUND_BY),$(shell command -v $(CXX) 2>/dev/null)),)
  PORT_DEFS += -DVFP_HAVE_GDCM
  PORT_LIBS += $(GDCM_LIBS) -lstdc++
  PORT_CXX_OBJ := $(BUILD)/port/io/dicom.o
  FOUND += gdcm($(GDCM_FOUND_BY))
else
  LEFT_OUT += dicom:libgdcm-dev$(if $(shell command -v $(CXX) 2>/dev/null),,+g++)
endif
# ---- end of DICOM ----
# After the backends: HOST_CFLAGS is simply expanded, so PORT_DEFS must be complete when it is appended.
HOST_CFLAGS += $(EXTRA_CFLAGS) $(PORT_DEFS)
# ---- end of detection ----------------------------------------------------------------------------------------

CORE_SRC := $(wildcard core/*.c)
PORT_SRC := $(filter-out port/viewer/%,$(wildcard port/*/*.c))
SIM_SRC  := $(wildcard host-sim/*.c) $(wildcard host-sim/ref/*.c) $(wildcard host-sim/truth/*.c)
SIM_MAIN := host-sim/main.c
VIEWER_SRC := $(wildcard port/viewer/*.c)

CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/%.o)
PORT_OBJ := $(PORT_SRC:%.c=$(BUILD)/%.o)
SIM_OBJ  := $(filter-out $(BUILD)/$(SIM_MAIN:.c=.o),$(SIM_SRC:%.c=$(BUILD)/%.o))
VIEWER_OBJ := $(VIEWER_SRC:%.c=$(BUILD)/%.o)

TEST_SRC  := $(filter-out $(foreach w,$(LEFT_OUT_TESTS),$(firstword $(subst :, ,$(w))).c), \
             $(wildcard tests/core/test_*.c tests/port/test_*.c tests/host-sim/test_*.c))
TEST_BIN  := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
TEST_LIB  := $(BUILD)/tests/check.o

LIBVOLFIX := $(BUILD)/libvolfix.a
LIBPORT   := $(BUILD)/libvolfix-port.a
LIBSIM    := $(BUILD)/libvolfix-sim.a
SIM       := $(BUILD)/volfix-sim
VIEWER    := $(BUILD)/volfix
PC_FILE   := $(BUILD)/volfix.pc

# ---- The configuration stamps --------------------------------------------------------------------------------
# Each is rewritten only when its text changes (make compares the stamp's time after running its recipe), so an
# object that depends on it is rebuilt exactly when its flags change. The texts are taken here, with :=, so that
# target-specific flags (preint.o's) cannot leak into a stamp through a prerequisite.
CONFIG_MK      := $(BUILD)/config.mk
CORE_STAMP     := $(BUILD)/config/core.flags
HOST_STAMP     := $(BUILD)/config/host.flags
UMOCKDEV_STAMP := $(BUILD)/config/umockdev.flags
PREFIX_STAMP   := $(BUILD)/config/prefix.flags
CORE_TEXT      := $(CC) $(CORE_CFLAGS)
HOST_TEXT      := $(CC) $(HOST_CFLAGS) | $(LDFLAGS) | $(PORT_LIBS)
UMOCKDEV_TEXT  := $(UMOCKDEV_FLAGS) | $(UMOCKDEV_LIBS)
PREFIX_TEXT    := $(PREFIX)
# $(call quote,TEXT): TEXT as one single-quoted shell word
quote = '$(subst ','\'',$(strip $(1)))'
# $(call write_if_changed,WORDS): the recipe of a stamp: printf's quoted WORDS, one a line, into $@ if they differ.
# "+": it runs under make -n too, so that a dry run lists what a change of configuration really rebuilds.
write_if_changed = +@mkdir -p $(@D) && printf '%s\n' $(1) >$@.tmp$$$$ && \
                   { cmp -s $@.tmp$$$$ $@ && rm -f $@.tmp$$$$ || mv -f $@.tmp$$$$ $@; }

.PHONY: FORCE
FORCE:
$(CORE_STAMP): FORCE
	$(call write_if_changed,$(call quote,$(CORE_TEXT)))
$(HOST_STAMP): FORCE
	$(call write_if_changed,$(call quote,$(HOST_TEXT)))
$(UMOCKDEV_STAMP): FORCE
	$(call write_if_changed,$(call quote,$(UMOCKDEV_TEXT)))
$(PREFIX_STAMP): FORCE
	$(call write_if_changed,$(call quote,$(PREFIX_TEXT)))
# The whole configuration for people and scripts (tests/run.sh reads LEFT_OUT_TESTS), in make's syntax.
CONFIG_LINES := $(call quote,# volfix's build configuration as the Makefile detected it (rewritten when it changes)) \
    $(call quote,CC = $(CC)) $(call quote,CROSS_COMPILE = $(CROSS_COMPILE)) $(call quote,SAN = $(SAN)) \
    $(call quote,FOUND = $(FOUND)) $(call quote,GPIOD_MAJOR = $(GPIOD_MAJOR)) \
    $(call quote,BACKENDS = $(patsubst -DVFP_HAVE_%,%,$(filter -DVFP_HAVE_%,$(PORT_DEFS)))) \
    $(call quote,LEFT_OUT = $(LEFT_OUT)) $(call quote,LEFT_OUT_TESTS = $(LEFT_OUT_TESTS)) \
    $(call quote,PREFIX = $(PREFIX))
$(CONFIG_MK): FORCE
	$(call write_if_changed,$(CONFIG_LINES))

# One line after a build that left something out: what, and the packages that would bring it in.
comma  := ,
lparen := (
LEFT_OUT_ALL  := $(strip $(LEFT_OUT) $(LEFT_OUT_TESTS))
LEFT_OUT_PKGS := $(sort $(foreach w,$(LEFT_OUT_ALL),$(subst +, ,$(lastword $(subst :, ,$(w))))))
LEFT_OUT_WHAT := $(foreach w,$(LEFT_OUT_ALL),$(firstword $(subst :, ,$(w)))($(lastword $(subst :, ,$(w)))))
LEFT_OUT_LIST := $(subst +,$(comma) ,$(subst $(lparen), $(lparen),$(subst $() ,$(comma) ,$(strip $(LEFT_OUT_WHAT)))))
ifeq ($(CROSS_COMPILE),)
  LEFT_OUT_LINE := volfix: left out for want of packages: $(LEFT_OUT_LIST); sudo apt-get install $(LEFT_OUT_PKGS), \
                   then make again rebuilds what they change
else
  LEFT_OUT_LINE := volfix: $(CROSS_TRIPLET): left out for want of packages for the target: $(LEFT_OUT_LIST)
endif
# ---- end of the configuration stamps ---------------------------------------------------------------------------

.PHONY: all run test check bench test-hw hw-progs deps clean install uninstall
all: $(LIBVOLFIX) $(LIBPORT) $(SIM) $(if $(VIEWER_SRC),$(VIEWER)) $(TEST_BIN) $(CONFIG_MK)
	$(if $(LEFT_OUT_ALL),@echo $(call quote,$(LEFT_OUT_LINE)))

$(BUILD)/core/%.o: core/%.c $(CORE_STAMP)
	@mkdir -p $(@D)
	$(CC) $(CORE_CFLAGS) $(DEPFLAGS) -c $< -o $@

# preint.c's inner loops store seven 32- and 64-bit values a step and eight 16-bit ones a window; gcc's
# basic-block vectorizer (on at -O2 since gcc 12) first packs them into vector or word registers, which took more
# instructions than it saved (callgrind, 256-entry table: 8.09 M with it, 7.76 M without).
$(BUILD)/core/preint.o: CORE_CFLAGS += -fno-tree-slp-vectorize

# the viewer's main.c names the installed boards' folder
$(BUILD)/port/viewer/main.o: VIEWER_DEFS = -DVFP_BOARD_DIR='"$(BOARD_DIR)"'
$(BUILD)/port/viewer/main.o: $(PREFIX_STAMP)
$(BUILD)/port/viewer/%.o: port/viewer/%.c $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) $(VIEWER_DEFS) -Iport/viewer $(DEPFLAGS) -c $< -o $@

$(BUILD)/port/%.o: port/%.c $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) $(DEPFLAGS) -c $< -o $@

$(BUILD)/host-sim/%.o: host-sim/%.c $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) $(DEPFLAGS) -c $< -o $@

$(LIBVOLFIX): $(CORE_OBJ)
	rm -f $@ && $(AR) rcs $@ $^

$(LIBPORT): $(PORT_OBJ) $(PORT_CXX_OBJ)
	rm -f $@ && $(AR) rcs $@ $^

# the DICOM reader, the port layer's one C++ file: the host's flags but C++'s standard, and GDCM's headers; not
# -Wshadow, which in C++ flags core/volfix.h's function vf_factor for sharing its name with struct vf_factor
$(BUILD)/port/io/dicom.o: port/io/dicom.cpp $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CXX) -std=c++14 $(filter-out -std=% -D_POSIX_C_SOURCE=% -Wshadow,$(HOST_CFLAGS)) $(GDCM_CFLAGS) $(DEPFLAGS) \
	    -c $< -o $@

$(LIBSIM): $(SIM_OBJ)
	rm -f $@ && $(AR) rcs $@ $^

$(SIM): $(BUILD)/$(SIM_MAIN:.c=.o) $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) $(HOST_STAMP)
	$(CC) $(LDFLAGS) -o $@ $(filter-out $(HOST_STAMP),$^) $(PORT_LIBS)

$(VIEWER): $(VIEWER_OBJ) $(LIBPORT) $(LIBVOLFIX) $(HOST_STAMP)
	$(CC) $(LDFLAGS) -o $@ $(filter-out $(HOST_STAMP),$^) $(PORT_LIBS)

$(TEST_LIB): tests/check.c $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -Itests $(DEPFLAGS) -c $< -o $@

$(BUILD)/tests/%: tests/%.c $(TEST_LIB) $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -Itests $(DEPFLAGS) -o $@ $< $(TEST_LIB) $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) $(LDFLAGS) \
	      $(PORT_LIBS)

ifeq ($(filter $(GUD_USB_TEST):%,$(LEFT_OUT_TESTS)),)
$(BUILD)/$(GUD_USB_TEST): $(GUD_USB_TEST).c $(TEST_LIB) $(LIBPORT) $(LIBVOLFIX) $(HOST_STAMP) $(UMOCKDEV_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) $(UMOCKDEV_FLAGS) -Itests $(DEPFLAGS) -o $@ $< $(TEST_LIB) $(LIBPORT) $(LIBVOLFIX) \
	      $(LDFLAGS) $(PORT_LIBS) $(UMOCKDEV_LIBS)
else
$(BUILD)/$(GUD_USB_TEST):
	@echo "volfix: $(GUD_USB_TEST) is left out of this build: it needs $(strip $(GUD_USB_NEEDS))" >&2; exit 2
endif

deps:
	@sh tools/deps.sh $(DEPS_FOR)

run: DEPS_FOR = run
run: deps
	@$(MAKE) --no-print-directory $(JOBS) all $(BUILD)/peers/peer_compare
	@sh tools/demo.sh

test: DEPS_FOR = test
test: deps
	@$(MAKE) --no-print-directory $(JOBS) all
	@sh tests/run.sh

# make check: the edit-compile-test loop's tier, built and run in under a minute on two cores from a clean tree.
# The core's unit tests, host-sim's but its slow ones (the shared volumes rendered at several views, unlit, lit and
# in order 2, and every ray count: 12 to 64 s each alone; make test runs them), and one small render per mode
# against the reference (tests/host-sim/modes.sh). No packages installed, no port-layer or viewer tests.
CHECK_SLOW := $(addprefix $(BUILD)/tests/host-sim/,test_accuracy test_ref_rays test_lighting test_order2_accuracy \
                test_preint test_anisotropic)
CHECK_BIN  := $(filter-out $(CHECK_SLOW),$(filter $(BUILD)/tests/core/% $(BUILD)/tests/host-sim/%,$(TEST_BIN)))
check:
	@$(MAKE) --no-print-directory $(JOBS) $(SIM) $(CHECK_BIN) $(CONFIG_MK)
	@sh tests/run.sh $(CHECK_BIN) tests/host-sim/modes.sh

bench: all
	@sh tools/bench.sh

# make test-hw: the programs tests/hw/*.c run inside the VM, built here against this build's libraries
# (libgpiod 1.6 from the system); tests/hw/run.sh builds them again with BUILD=$(BUILD)/hw/gpiod2 and a private
# libgpiod 2.x (GPIOD_PKG_CONFIG_PATH, GPIOD_SYSROOT).
HW_SRC := $(wildcard tests/hw/*.c)
HW_BIN := $(HW_SRC:tests/hw/%.c=$(BUILD)/hw/bin/%)

hw-progs: $(HW_BIN)

$(BUILD)/hw/bin/%: tests/hw/%.c $(LIBPORT) $(LIBVOLFIX) $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -Itests/hw $(DEPFLAGS) -o $@ $< $(LIBPORT) $(LIBVOLFIX) $(LDFLAGS) $(PORT_LIBS)

test-hw: DEPS_FOR = hw
test-hw: deps
	@$(MAKE) --no-print-directory $(JOBS) all
	@BUILD=$(BUILD) MAKE="$(MAKE)" sh tests/hw/run.sh

# ---- make test-cross: the same frames, bit for bit, on x86-64, aarch64 and 32-bit ARM (tests/cross/run.sh) ----
# Builds $(BUILD) natively and $(BUILD)-aarch64, $(BUILD)-armhf with the cross compilers (settings at the top), runs
# the cross-built test suites under qemu-user and compares `volfix-sim render --hash` of a fixed set of scenes with
# the native ones. CROSS_COMPILE builds say which optional backends they leave out, as native ones do.
CROSS_TARGETS := aarch64-linux-gnu-:aarch64 arm-linux-gnueabihf-:armhf
.PHONY: test-cross
test-cross: DEPS_FOR = cross
test-cross: deps
	@$(MAKE) --no-print-directory $(JOBS) all
	@$(foreach t,$(CROSS_TARGETS),$(MAKE) --no-print-directory $(JOBS) CROSS_COMPILE=$(word 1,$(subst :, ,$(t))) \
	     BUILD=$(BUILD)-$(word 2,$(subst :, ,$(t))) all &&) true
	@sh tests/cross/run.sh $(BUILD) $(foreach t,$(CROSS_TARGETS),$(BUILD)-$(word 2,$(subst :, ,$(t))))

ifneq ($(CROSS_COMPILE),)
ifneq ($(CROSS_SYSROOT),)
$(PORT_OBJ) $(SIM_OBJ) $(BUILD)/$(SIM_MAIN:.c=.o) $(VIEWER_OBJ) $(TEST_LIB) $(TEST_BIN) $(HW_BIN): | $(CROSS_SYSROOT)/.unpacked
$(CROSS_SYSROOT)/.unpacked:
	sh tools/cross-sysroot.sh $(CROSS_DEBARCH) $(CROSS_TRIPLET) $(CROSS_SYSROOT)
endif
endif
# ---- end of make test-cross ----

# ---- Fuzzing: make fuzz, and the fuzz regression replay in make test (tests/fuzz/README.md) ----
# Every parser has a libFuzzer harness, tests/fuzz/fuzz_NAME.c (one LLVMFuzzerTestOneInput each).
# make test: each harness is also built with the normal compiler and flags (so SAN=1 too) and tests/fuzz/replay.c's
#   main() as $(BUILD)/tests/fuzz/replay_NAME; tests/fuzz/replay.sh feeds it every file of tests/fuzz/seeds/ and
#   tests/fuzz/regress/ (inputs that once found a bug).
# make fuzz [FUZZ_SECONDS=60] [FUZZ_JOBS=N]: builds the harnesses with clang, libFuzzer, ASan and UBSan in
#   $(FUZZ_BUILD) (core and port compiled the same way; the optional backends left out, so no detection: the
#   flags' stamp is the compiler's) and runs each for FUZZ_SECONDS, FUZZ_JOBS at a time (default: the processors
#   online), with its corpus in $(FUZZ_BUILD)/corpus/NAME seeded from tests/fuzz/seeds/NAME (tools/fuzz.sh). One
#   line per harness; fails if one crashed, leaked, hung or ran out of memory, with the input kept in
#   $(FUZZ_BUILD)/crashes/NAME/.
FUZZ_SRC    := $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_NAMES  := $(FUZZ_SRC:tests/fuzz/fuzz_%.c=%)
FUZZ_REPLAY := $(FUZZ_NAMES:%=$(BUILD)/tests/fuzz/replay_%)

all: $(FUZZ_REPLAY)

# --wrap: replay.c's malloc, calloc and realloc refuse what no input needs, as the fuzzer's -malloc_limit_mb does.
FUZZ_WRAP   := -Wl,--wrap=malloc -Wl,--wrap=calloc -Wl,--wrap=realloc
FUZZ_MAIN   := $(BUILD)/tests/fuzz/replay.o
$(FUZZ_MAIN): tests/fuzz/replay.c $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -Itests/fuzz $(DEPFLAGS) -c $< -o $@

$(BUILD)/tests/fuzz/replay_%: tests/fuzz/fuzz_%.c $(FUZZ_MAIN) $(LIBPORT) $(LIBVOLFIX) $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) -Itests/fuzz $(DEPFLAGS) -o $@ $< $(FUZZ_MAIN) $(LIBPORT) $(LIBVOLFIX) $(LDFLAGS) \
	      $(FUZZ_WRAP) $(PORT_LIBS)

FUZZ_CC      ?= clang
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_JOBS    ?=
FUZZ_CFLAGS  := -std=c11 -D_DEFAULT_SOURCE -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Wshadow -O1 -g -Icore -Iport \
                -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_OBJ     := $(CORE_SRC:%.c=$(FUZZ_BUILD)/%.o) $(PORT_SRC:%.c=$(FUZZ_BUILD)/%.o)
FUZZ_LIB     := $(FUZZ_BUILD)/libvolfix-fuzz.a
FUZZ_BIN     := $(FUZZ_NAMES:%=$(FUZZ_BUILD)/fuzz_%)
FUZZ_STAMP   := $(FUZZ_BUILD)/config/fuzz.flags
FUZZ_TEXT    := $(FUZZ_CC) $(FUZZ_CFLAGS)

.PHONY: fuzz fuzz-build
fuzz: DEPS_FOR = fuzz
fuzz: deps
	@$(MAKE) --no-print-directory $(JOBS) fuzz-build
	@FUZZ_JOBS=$(FUZZ_JOBS) sh tools/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_NAMES)

fuzz-build: $(FUZZ_BIN)

$(FUZZ_STAMP): FORCE
	$(call write_if_changed,$(call quote,$(FUZZ_TEXT)))

$(FUZZ_BUILD)/core/%.o: core/%.c $(FUZZ_STAMP)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link $(DEPFLAGS) -c $< -o $@

$(FUZZ_BUILD)/port/%.o: port/%.c $(FUZZ_STAMP)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link $(DEPFLAGS) -c $< -o $@

$(FUZZ_LIB): $(FUZZ_OBJ)
	rm -f $@ && ar rcs $@ $^

$(FUZZ_BUILD)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_LIB) $(FUZZ_STAMP)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -Itests/fuzz $(DEPFLAGS) -o $@ $< $(FUZZ_LIB) -lpng -lz -lpthread -lm
# ---- end of fuzzing ----

# ---- make mcu: the core on a Cortex-M4 microcontroller, and a firmware for the MPS2 AN386 board -------------
# The core is built for a Cortex-M4 with Debian's arm-none-eabi-gcc (Thumb-2, -Os, soft-float ABI: the core has
# no floating point; one section per function so that the link drops what the firmware does not call) into
# MCU_BUILD, then linked with boards/mps2-an386 (startup, semihosting, main; no libc, only libgcc's division
# helpers) into MCU_BUILD/fw.elf, which qemu-system-arm -M mps2-an386 runs. The firmware's scene comes from
# gen_scene, a host program linked against this build's libraries that takes the same options as volfix-sim
# render (MCU_SCENE), so the firmware's frame hash must equal `volfix-sim render $(MCU_SCENE) --hash`.
#   make mcu        build, print .text/.data/.bss of the core (per object, compiled and as linked) and firmware
#   make mcu-run    also run the firmware under qemu: its frame hash and memory report
# tests/mcu/mcu.sh (make test) runs it against the host's hash. Uses the native compiler for gen_scene.
MCU_BUILD     ?= build-mcu
MCU_CROSS     ?= arm-none-eabi-
MCU_SCENE     ?= $(VOLFIX_DATA)/bucky.nhdr --size 64x64 --format rgb565 --mode preint1 --preset ramp --view 30,20
MCU_BAND_ROWS ?= 8
MCU_GEN_OPTS  ?=
# the stack the firmware reserves (bytes; it reports how much a frame touched)
MCU_STACK     ?= 16384
MCU_DIR       := boards/mps2-an386
MCU_ARCH      := -mcpu=cortex-m4 -mthumb -mfloat-abi=soft
MCU_OPT       := -Os -g -ffunction-sections -fdata-sections -fno-tree-loop-distribute-patterns
# the core's own rules (CORE_CFLAGS without the host's optimisation, sanitizers and extra flags)
# The firmware's core leaves out what a 256 KB board does not use (vf_config.h): partial slabs, more than one
# ray per voxel column, the table built in parts on threads or as compositing reads it, view tables (the lut
# then corrects each segment), the brute-force table builder (the tests' oracle) and the front-weighted (lit)
# tables (4.8 KB; the firmware renders without lighting), order 2 (preint2: docs/performance.md gives its
# code and the RAM of its table) and renderers over prebuilt storage (boards/mps2-an386/README.md, a 64^3 volume
# in 256 KB: those firmwares build with -DVF_PREBUILT=1 -DVF_BUILD_SLICES=0), which keeps the core within
# the 24 KB code budget; and its loops look no entry up ahead: on a core without caches that would only add
# work, 17% more compositing time (qemu's instruction count: 79,819 ticks against 68,503).
MCU_FEATURES  ?= -DVF_PARTIAL_SLABS=0 -DVF_MAX_RAYS=1 -DVF_MAX_TABLE_PARTS=1 -DVF_VIEW_TABLE=0 -DVF_TABLE_ON_DEMAND=0 \
                 -DVF_TABLE_ORACLE=0 -DVF_SPECIAL_LOOPS=0 -DVF_LOOK_AHEAD=0 -DVF_LIGHTING=0 -DVF_ORDER2=0 -DVF_PREBUILT=0
MCU_CORE_CFLAGS := -std=c99 -ffreestanding -fno-builtin -Wall -Wextra -Wpedantic -Werror -Wshadow \
                   -Wstrict-prototypes -Wmissing-prototypes -Wconversion -Wno-sign-conversion $(MCU_ARCH) $(MCU_OPT) \
                   $(MCU_FEATURES)
MCU_FW_CFLAGS   := -std=c99 -ffreestanding -fno-builtin -Wall -Wextra -Werror -Wshadow $(MCU_ARCH) $(MCU_OPT) \
                   -Icore -I$(MCU_BUILD)
MCU_CORE_OBJ  := $(CORE_SRC:%.c=$(MCU_BUILD)/%.o)
MCU_FW_OBJ    := $(MCU_BUILD)/fw/startup.o $(MCU_BUILD)/fw/semihost.o $(MCU_BUILD)/fw/main.o $(MCU_BUILD)/fw/scene_data.o
MCU_ELF       := $(MCU_BUILD)/fw.elf
# -icount shift=0: the guest's clock advances one nanosecond per instruction, so the firmware's timer ticks
# (25 MHz) count instructions / 40, the same on any host
MCU_QEMU      := qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none -semihosting -icount shift=0

.PHONY: mcu mcu-run mcu-firmware
mcu: DEPS_FOR = mcu
mcu: deps
	@$(MAKE) --no-print-directory $(JOBS) mcu-firmware
	@sh $(MCU_DIR)/sizes.sh $(MCU_CROSS) $(MCU_BUILD)

mcu-run: DEPS_FOR = mcu
mcu-run: mcu
	@$(MCU_QEMU) -kernel $(MCU_ELF); status=$$?; echo "firmware exit status $$status"; exit $$status

mcu-firmware: $(MCU_ELF)

# The core's and the firmware's compiler flags (MCU_FEATURES among them) and the scene's options each in a
# stamp, so that `make mcu MCU_FEATURES=...` rebuilds the core rather than linking objects built with the old
# features, and a new MCU_SCENE regenerates the scene's header.
MCU_CORE_TEXT  := $(MCU_CROSS)gcc $(MCU_CORE_CFLAGS)
MCU_FW_TEXT    := $(MCU_CROSS)gcc $(MCU_FW_CFLAGS) stack $(MCU_STACK)
MCU_SCENE_TEXT := $(MCU_SCENE) --band-rows $(MCU_BAND_ROWS) $(MCU_GEN_OPTS)
$(MCU_BUILD)/core.flags: FORCE
	$(call write_if_changed,$(call quote,$(MCU_CORE_TEXT)))
$(MCU_BUILD)/fw.flags: FORCE
	$(call write_if_changed,$(call quote,$(MCU_FW_TEXT)))
$(MCU_BUILD)/scene.args: FORCE
	$(call write_if_changed,$(call quote,$(MCU_SCENE_TEXT)))

$(MCU_BUILD)/core/%.o: core/%.c $(MCU_BUILD)/core.flags
	@mkdir -p $(@D)
	$(MCU_CROSS)gcc $(MCU_CORE_CFLAGS) $(DEPFLAGS) -c $< -o $@

$(MCU_BUILD)/libvolfix.a: $(MCU_CORE_OBJ)
	rm -f $@ && $(MCU_CROSS)ar rcs $@ $^

$(MCU_BUILD)/gen_scene: $(MCU_DIR)/gen_scene.c $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) $(HOST_STAMP)
	@mkdir -p $(@D)
	$(CC) $(HOST_CFLAGS) $(DEPFLAGS) -o $@ $< $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) $(LDFLAGS) $(PORT_LIBS)

# gen_scene writes scene_data.S beside the header (with --prebuilt in MCU_GEN_OPTS, the arrays it .incbin's from
# scene_data.bin; else empty)
$(MCU_BUILD)/scene.h: $(MCU_BUILD)/gen_scene $(MCU_BUILD)/scene.args
	$(MCU_BUILD)/gen_scene $(MCU_SCENE) --band-rows $(MCU_BAND_ROWS) $(MCU_GEN_OPTS) -o $@
$(MCU_BUILD)/scene_data.S: $(MCU_BUILD)/scene.h
$(MCU_BUILD)/fw/scene_data.o: $(MCU_BUILD)/scene_data.S
	@mkdir -p $(@D)
	$(MCU_CROSS)gcc $(MCU_ARCH) -c $< -o $@

$(MCU_BUILD)/fw/%.o: $(MCU_DIR)/%.c $(MCU_BUILD)/scene.h $(MCU_BUILD)/fw.flags
	@mkdir -p $(@D)
	$(MCU_CROSS)gcc $(MCU_FW_CFLAGS) $(DEPFLAGS) -c $< -o $@

# -nostdlib: nothing from a C library, so a libc call anywhere (a memset the compiler made up included) fails
# the link; libgcc only for the 64-bit division helpers (__aeabi_uldivmod, __aeabi_ldivmod).
$(MCU_ELF): $(MCU_FW_OBJ) $(MCU_BUILD)/libvolfix.a $(MCU_DIR)/mps2-an386.ld $(MCU_BUILD)/fw.flags
	$(MCU_CROSS)gcc $(MCU_ARCH) -nostdlib -T $(MCU_DIR)/mps2-an386.ld -Wl,--gc-sections -Wl,--defsym=STACK_SIZE=$(MCU_STACK) \
	    -Wl,-Map=$(MCU_BUILD)/fw.map -o $@ $(MCU_FW_OBJ) $(MCU_BUILD)/libvolfix.a -lgcc
# ---- end of make mcu ----------------------------------------------------------------------------------------

# make print-VAR prints a variable's value for scripts: tests/core/small_config.sh builds the core with MCU_FEATURES,
# tests/run.sh asks for VOLFIX_DATA when it runs outside make.
print-%:
	@printf '%s\n' $(call quote,$($*))

# ---- make test-asan and make test-long -------------------------------------------------------------------------
# test-asan: everything built with AddressSanitizer and UndefinedBehaviorSanitizer (SAN=1: -fsanitize=address,
# undefined -fno-sanitize-recover=all) in $(BUILD)-asan, then the whole suite; any report fails its test.
# test-long: the viewer for 10,000 frames (memory must stay flat) and a session under valgrind (tests/long/run.sh).
.PHONY: test-asan test-long
test-asan: DEPS_FOR = test
test-asan: deps
	@$(MAKE) --no-print-directory $(JOBS) SAN=1 BUILD=$(BUILD)-asan all
	@SAN=1 BUILD=$(BUILD)-asan LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 sh tests/run.sh

test-long: DEPS_FOR = test
test-long: deps
	@$(MAKE) --no-print-directory $(JOBS) all
	@BUILD=$(BUILD) sh tests/long/run.sh
# ---- end of test-asan and test-long ------------------------------------------------------------------------------

# ---- make install and make uninstall -----------------------------------------------------------------------------
# The core's library and its public headers (in include/volfix/), the port layer's library, volfix.pc, the two
# programs, and the boards with the knob scripts they name (input.script). volfix.pc lists the port layer's
# libraries for static linking: pkg-config --static --libs volfix.
INSTALL       ?= install
PUBLIC_HEADERS := core/volfix.h core/vf_config.h
BOARD_FILES    := $(wildcard boards/*.board)
BOARD_SCRIPTS  := $(sort $(foreach b,$(BOARD_FILES),$(addprefix boards/,$(shell sed -n \
                  's/^input\.script *= *\([^ ]*\) *$$/\1/p' $(b)))))
INSTALLED      := $(BINDIR)/volfix $(BINDIR)/volfix-sim $(LIBDIR)/libvolfix.a $(LIBDIR)/libvolfix-port.a \
                  $(LIBDIR)/pkgconfig/volfix.pc $(PUBLIC_HEADERS:core/%=$(INCLUDEDIR)/volfix/%) \
                  $(BOARD_FILES:boards/%=$(BOARD_DIR)/%) $(BOARD_SCRIPTS:boards/%=$(BOARD_DIR)/%)

$(PC_FILE): $(HOST_STAMP) $(PREFIX_STAMP) core/volfix.h
	@mkdir -p $(@D)
	@printf '%s\n' 'prefix=$(PREFIX)' 'libdir=$${prefix}/lib' 'includedir=$${prefix}/include' '' \
	    'Name: volfix' \
	    'Description: fixed-point, pre-integrated shear-warp volume renderer (core and port layer)' \
	    'Version: $(VERSION)' 'Cflags: -I$${includedir}/volfix' \
	    'Libs: -L$${libdir} -lvolfix-port -lvolfix$(if $(SANFLAGS), $(SANFLAGS))' \
	    'Requires.private: $(PC_REQUIRES)' 'Libs.private: $(strip $(GDCM_LIBS) -lpthread -lm$(if $(PORT_CXX_OBJ), -lstdc++))' >$@

install: $(LIBVOLFIX) $(LIBPORT) $(SIM) $(VIEWER) $(PC_FILE)
	$(INSTALL) -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(LIBDIR)/pkgconfig $(DESTDIR)$(INCLUDEDIR)/volfix \
	    $(DESTDIR)$(BOARD_DIR)
	$(INSTALL) -m 755 $(VIEWER) $(SIM) $(DESTDIR)$(BINDIR)
	$(INSTALL) -m 644 $(LIBVOLFIX) $(LIBPORT) $(DESTDIR)$(LIBDIR)
	$(INSTALL) -m 644 $(PC_FILE) $(DESTDIR)$(LIBDIR)/pkgconfig
	$(INSTALL) -m 644 $(PUBLIC_HEADERS) $(DESTDIR)$(INCLUDEDIR)/volfix
	$(INSTALL) -m 644 $(BOARD_FILES) $(BOARD_SCRIPTS) $(DESTDIR)$(BOARD_DIR)

uninstall:
	rm -f $(addprefix $(DESTDIR),$(INSTALLED))
	-rmdir $(DESTDIR)$(BOARD_DIR) $(DESTDIR)$(PREFIX)/share/volfix $(DESTDIR)$(INCLUDEDIR)/volfix 2>/dev/null
# ---- end of make install and make uninstall ----------------------------------------------------------------------

# Every folder the build makes: this build's, its siblings (-asan, -aarch64, -armhf), the fuzz and firmware
# builds, and the demo's and the study's output.
clean:
	rm -rf $(sort $(BUILD) $(BUILD)-* build-* $(FUZZ_BUILD) $(MCU_BUILD) out)

# The compiler's header dependencies of every object and program this Makefile builds.
DEP_FILES := $(addsuffix .d,$(CORE_OBJ) $(PORT_OBJ) $(PORT_CXX_OBJ) $(SIM_OBJ) $(BUILD)/$(SIM_MAIN:.c=.o) $(VIEWER_OBJ) $(TEST_LIB) \
             $(TEST_BIN) $(BUILD)/$(GUD_USB_TEST) $(FUZZ_MAIN) $(FUZZ_REPLAY) $(HW_BIN) $(FUZZ_OBJ) $(FUZZ_BIN) \
             $(MCU_CORE_OBJ) $(MCU_FW_OBJ) $(MCU_BUILD)/gen_scene)
-include $(wildcard $(DEP_FILES))
$(sort $(DEP_FILES)): ;

# ---- make bench-peers: volfix and VolPack side by side (tools/peers/run.sh, docs/peers.md) ------------------------
# VolPack and valgrind from apt (tools/deps.sh peers); volfix's VolPack client and image comparer built into
# $(BUILD)/peers; then the same four scenes rendered by both, unlit and lit, timed and counted (10 to 15 minutes,
# progress on stderr).
.PHONY: bench-peers peers-deps peers-progs
peers-progs: $(BUILD)/peers/volpack_peer $(BUILD)/peers/peer_compare $(BUILD)/peers/storage_study
peers-deps:
	@sh tools/deps.sh peers

$(BUILD)/peers/volpack_peer: tools/peers/volpack_peer.c | peers-deps
	@mkdir -p $(@D)
	$(CC) -std=c11 -D_DEFAULT_SOURCE -O2 -g -Wall -Wextra -o $@ $< -lvolpack -lpng -lz -lm

# peer_compare needs libpng only: make run uses it too, for its unlit | lit picture
$(BUILD)/peers/peer_compare: tools/peers/peer_compare.c
	@mkdir -p $(@D)
	$(CC) -std=c11 -D_DEFAULT_SOURCE -O2 -g -Wall -Wextra -o $@ $< -lpng -lm

# storage_study: the bytes volfix's per-axis storage would take if it kept only the visible cells' voxels
$(BUILD)/peers/storage_study: tools/peers/storage_study.c
	@mkdir -p $(@D)
	$(CC) -std=c11 -D_DEFAULT_SOURCE -O2 -g -Wall -Wextra -o $@ $< -lz

bench-peers: $(BUILD)/volfix-sim $(BUILD)/peers/volpack_peer $(BUILD)/peers/peer_compare $(BUILD)/peers/storage_study
	@BUILD=$(BUILD) VOLFIX_DATA=$(VOLFIX_DATA) sh tools/peers/run.sh

# make volpack-check: VolPack's example image (without depth cueing) and volfix's lit preclass of the same
# classification side by side in docs/images/volpack-check.png, and their PSNR (tools/peers/volpack_check.sh)
.PHONY: volpack-check
volpack-check: $(BUILD)/volfix-sim $(BUILD)/peers/volpack_peer $(BUILD)/peers/peer_compare
	@BUILD=$(BUILD) VOLFIX_DATA=$(VOLFIX_DATA) sh tools/peers/volpack_check.sh
# ---- end of make bench-peers ---------------------------------------------------------------------------------------
