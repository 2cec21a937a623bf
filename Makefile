# volfix: build, demo and tests.
#
#   make            build the core (build/libvolfix.a), the port layer, volfix-sim and the tests
#   make run        install missing packages (as root), build, render the demo into out/
#   make test       install missing packages (as root), build, run every test; ends with "N passed, N failed"
#   make bench      benchmarks (timings are never asserted in tests)
#   make test-hw    the GPIO and USB display backends against real kernel interfaces in a Linux VM (qemu;
#                   tests/hw/README.md); downloads a Debian kernel and libgpiod 2.x into $(BUILD)/hw the first time
#   make clean
#
# CROSS_COMPILE=aarch64-linux-gnu- builds with a cross compiler. SAN=1 builds with ASan and UBSan.

CROSS_COMPILE ?=
CC      := $(CROSS_COMPILE)gcc
AR      := $(CROSS_COMPILE)ar
BUILD   ?= build
OPT     ?= -O2

# The core: freestanding C99, integer only, no libc.
CORE_CFLAGS := -std=c99 -ffreestanding -fno-builtin -Wall -Wextra -Wpedantic -Werror -Wshadow \
               -Wstrict-prototypes -Wmissing-prototypes -Wconversion -Wno-sign-conversion -fno-tree-loop-distribute-patterns $(OPT) -g
# Everything else: hosted C11 with POSIX.
HOST_CFLAGS := -std=c11 -D_DEFAULT_SOURCE -D_POSIX_C_SOURCE=200809L -Wall -Wextra -Wshadow $(OPT) -g \
               -Icore -Iport -Ihost-sim
ifeq ($(SAN),1)
  SANFLAGS := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
  CORE_CFLAGS += $(SANFLAGS)
  HOST_CFLAGS += $(SANFLAGS)
  LDFLAGS += $(SANFLAGS)
endif
CORE_CFLAGS += $(EXTRA_CFLAGS)

PKG_CONFIG ?= pkg-config
PORT_LIBS  := -lz -lpng -lpthread -lm

# Optional backends, compiled in when pkg-config finds their library (port/display.h, port/input.h). A private
# libgpiod (the 2.x test in make test-hw) comes in through GPIOD_PKG_CONFIG_PATH.
have = $(shell $(PKG_CONFIG) --exists $(1) 2>/dev/null && echo 1)
PORT_DEFS :=
ifeq ($(call have,libdrm),1)
  PORT_DEFS += -DVFP_HAVE_DRM $(shell $(PKG_CONFIG) --cflags libdrm)
  PORT_LIBS += $(shell $(PKG_CONFIG) --libs libdrm)
endif
ifeq ($(call have,libusb-1.0),1)
  PORT_DEFS += -DVFP_HAVE_GUD $(shell $(PKG_CONFIG) --cflags libusb-1.0)
  PORT_LIBS += $(shell $(PKG_CONFIG) --libs libusb-1.0)
  ifeq ($(call have,liblz4),1)
    PORT_DEFS += -DVFP_HAVE_LZ4
    PORT_LIBS += $(shell $(PKG_CONFIG) --libs liblz4)
  endif
endif
ifeq ($(call have,sdl2),1)
  PORT_DEFS += -DVFP_HAVE_SDL $(shell $(PKG_CONFIG) --cflags sdl2)
  PORT_LIBS += $(shell $(PKG_CONFIG) --libs sdl2)
endif
GPIOD_PC = $(if $(GPIOD_PKG_CONFIG_PATH),PKG_CONFIG_PATH=$(GPIOD_PKG_CONFIG_PATH) PKG_CONFIG_SYSROOT_DIR=$(GPIOD_SYSROOT) )$(PKG_CONFIG)
ifeq ($(shell $(GPIOD_PC) --exists libgpiod 2>/dev/null && echo 1),1)
  GPIOD_MAJOR := $(firstword $(subst ., ,$(shell $(GPIOD_PC) --modversion libgpiod)))
  PORT_DEFS += -DVFP_HAVE_GPIOD -DVFP_GPIOD_MAJOR=$(GPIOD_MAJOR) $(shell $(GPIOD_PC) --cflags libgpiod)
  PORT_LIBS += $(shell $(GPIOD_PC) --libs libgpiod)
endif
# After the backends: HOST_CFLAGS is simply expanded, so PORT_DEFS must be complete when it is appended.
HOST_CFLAGS += $(EXTRA_CFLAGS) $(PORT_DEFS)

CORE_SRC := $(wildcard core/*.c)
PORT_SRC := $(wildcard port/*.c)
SIM_SRC  := $(wildcard host-sim/*.c) $(wildcard host-sim/ref/*.c) $(wildcard host-sim/truth/*.c)
SIM_MAIN := host-sim/main.c
VIEWER_SRC := $(wildcard port/viewer/*.c)

CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/%.o)
PORT_OBJ := $(PORT_SRC:%.c=$(BUILD)/%.o)
SIM_OBJ  := $(filter-out $(BUILD)/$(SIM_MAIN:.c=.o),$(SIM_SRC:%.c=$(BUILD)/%.o))
VIEWER_OBJ := $(VIEWER_SRC:%.c=$(BUILD)/%.o)

TEST_SRC  := $(wildcard tests/core/test_*.c tests/port/test_*.c tests/host-sim/test_*.c)
TEST_BIN  := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
TEST_LIB  := $(BUILD)/tests/check.o

LIBVOLFIX := $(BUILD)/libvolfix.a
LIBPORT   := $(BUILD)/libvolfix-port.a
LIBSIM    := $(BUILD)/libvolfix-sim.a
SIM       := $(BUILD)/volfix-sim
VIEWER    := $(BUILD)/volfix

.PHONY: all run test bench test-hw hw-progs deps clean check-core
all: $(LIBVOLFIX) $(LIBPORT) $(SIM) $(if $(VIEWER_SRC),$(VIEWER)) $(TEST_BIN)

$(BUILD)/core/%.o: core/%.c $(wildcard core/*.h) | $(BUILD)/core
	$(CC) $(CORE_CFLAGS) -c $< -o $@

$(BUILD)/port/%.o: port/%.c $(wildcard core/volfix.h core/vf_config.h port/*.h) | $(BUILD)/port
	$(CC) $(HOST_CFLAGS) -c $< -o $@

$(BUILD)/port/viewer/%.o: port/viewer/%.c $(wildcard core/volfix.h port/*.h port/viewer/*.h) | $(BUILD)/port/viewer
	$(CC) $(HOST_CFLAGS) -Iport/viewer -c $< -o $@

$(BUILD)/host-sim/%.o: host-sim/%.c $(wildcard core/volfix.h port/*.h host-sim/*.h host-sim/ref/*.h) \
                       $(wildcard host-sim/truth/*.h) | $(BUILD)/host-sim/ref $(BUILD)/host-sim/truth
	$(CC) $(HOST_CFLAGS) -c $< -o $@

$(LIBVOLFIX): $(CORE_OBJ)
	rm -f $@ && $(AR) rcs $@ $^

$(LIBPORT): $(PORT_OBJ)
	rm -f $@ && $(AR) rcs $@ $^

$(LIBSIM): $(SIM_OBJ)
	rm -f $@ && $(AR) rcs $@ $^

$(SIM): $(BUILD)/$(SIM_MAIN:.c=.o) $(LIBSIM) $(LIBPORT) $(LIBVOLFIX)
	$(CC) $(LDFLAGS) -o $@ $^ $(PORT_LIBS)

$(VIEWER): $(VIEWER_OBJ) $(LIBPORT) $(LIBVOLFIX)
	$(CC) $(LDFLAGS) -o $@ $^ $(PORT_LIBS)

$(TEST_LIB): tests/check.c tests/check.h | $(BUILD)/tests
	$(CC) $(HOST_CFLAGS) -Itests -c $< -o $@

$(BUILD)/tests/%: tests/%.c $(TEST_LIB) $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) tests/check.h | $(BUILD)/tests/core \
                  $(BUILD)/tests/port $(BUILD)/tests/host-sim
	$(CC) $(HOST_CFLAGS) -Itests -o $@ $< $(TEST_LIB) $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) $(LDFLAGS) $(PORT_LIBS)

# tests/port/test_display_gud_usb.c plays a USB display through umockdev's API (libumockdev-dev), when present.
UMOCKDEV_FLAGS = $(if $(call have,umockdev-1.0),-DVFP_HAVE_UMOCKDEV $(shell $(PKG_CONFIG) --cflags umockdev-1.0))
UMOCKDEV_LIBS = $(if $(call have,umockdev-1.0),$(shell $(PKG_CONFIG) --libs umockdev-1.0))
$(BUILD)/tests/port/test_display_gud_usb: tests/port/test_display_gud_usb.c $(TEST_LIB) $(LIBPORT) $(LIBVOLFIX) \
                                          tests/check.h | $(BUILD)/tests/port
	$(CC) $(HOST_CFLAGS) $(UMOCKDEV_FLAGS) -Itests -o $@ $< $(TEST_LIB) $(LIBPORT) $(LIBVOLFIX) $(LDFLAGS) \
	      $(PORT_LIBS) $(UMOCKDEV_LIBS)

$(BUILD)/core $(BUILD)/port $(BUILD)/port/viewer $(BUILD)/host-sim/ref $(BUILD)/host-sim/truth $(BUILD)/tests $(BUILD)/tests/core \
$(BUILD)/tests/port $(BUILD)/tests/host-sim:
	mkdir -p $@

deps:
	@sh tools/deps.sh $(DEPS_FOR)

run: DEPS_FOR = run
run: deps
	@$(MAKE) --no-print-directory all
	@sh tools/demo.sh

test: DEPS_FOR = test
test: deps
	@$(MAKE) --no-print-directory all
	@sh tests/run.sh

bench: all
	@sh tools/bench.sh

# make test-hw: the programs tests/hw/*.c run inside the VM, built here against this build's libraries
# (libgpiod 1.6 from the system); tests/hw/run.sh builds them again with BUILD=$(BUILD)/hw/gpiod2 and a private
# libgpiod 2.x (GPIOD_PKG_CONFIG_PATH, GPIOD_SYSROOT).
HW_SRC := $(wildcard tests/hw/*.c)
HW_BIN := $(HW_SRC:tests/hw/%.c=$(BUILD)/hw/bin/%)

hw-progs: $(HW_BIN)

$(BUILD)/hw/bin/%: tests/hw/%.c $(wildcard tests/hw/*.h) $(LIBPORT) $(LIBVOLFIX) | $(BUILD)/hw/bin
	$(CC) $(HOST_CFLAGS) -Itests/hw -o $@ $< $(LIBPORT) $(LIBVOLFIX) $(LDFLAGS) $(PORT_LIBS)

$(BUILD)/hw/bin:
	mkdir -p $@

test-hw: DEPS_FOR = hw
test-hw: deps
	@$(MAKE) --no-print-directory all
	@BUILD=$(BUILD) MAKE="$(MAKE)" sh tests/hw/run.sh

clean:
	rm -rf $(BUILD) out
