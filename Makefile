# volfix: build, demo and tests.
#
#   make            build the core (build/libvolfix.a), the port layer, volfix-sim and the tests
#   make run        install missing packages (as root), build, render the demo into out/
#   make test       install missing packages (as root), build, run every test; ends with "N passed, N failed"
#   make bench      benchmarks (timings are never asserted in tests)
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
HOST_CFLAGS += $(EXTRA_CFLAGS)
CORE_CFLAGS += $(EXTRA_CFLAGS)

PKG_CONFIG ?= pkg-config
PORT_LIBS  := -lz -lpng -lpthread -lm

CORE_SRC := $(wildcard core/*.c)
PORT_SRC := $(wildcard port/*.c)
SIM_SRC  := $(wildcard host-sim/*.c) $(wildcard host-sim/ref/*.c) $(wildcard host-sim/truth/*.c)
SIM_MAIN := host-sim/main.c

CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/%.o)
PORT_OBJ := $(PORT_SRC:%.c=$(BUILD)/%.o)
SIM_OBJ  := $(filter-out $(BUILD)/$(SIM_MAIN:.c=.o),$(SIM_SRC:%.c=$(BUILD)/%.o))

TEST_SRC  := $(wildcard tests/core/test_*.c tests/port/test_*.c tests/host-sim/test_*.c)
TEST_BIN  := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
TEST_LIB  := $(BUILD)/tests/check.o

LIBVOLFIX := $(BUILD)/libvolfix.a
LIBPORT   := $(BUILD)/libvolfix-port.a
LIBSIM    := $(BUILD)/libvolfix-sim.a
SIM       := $(BUILD)/volfix-sim

.PHONY: all run test bench deps clean check-core
all: $(LIBVOLFIX) $(LIBPORT) $(SIM) $(TEST_BIN)

$(BUILD)/core/%.o: core/%.c $(wildcard core/*.h) | $(BUILD)/core
	$(CC) $(CORE_CFLAGS) -c $< -o $@

$(BUILD)/port/%.o: port/%.c $(wildcard core/volfix.h core/vf_config.h port/*.h) | $(BUILD)/port
	$(CC) $(HOST_CFLAGS) -c $< -o $@

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

$(TEST_LIB): tests/check.c tests/check.h | $(BUILD)/tests
	$(CC) $(HOST_CFLAGS) -Itests -c $< -o $@

$(BUILD)/tests/%: tests/%.c $(TEST_LIB) $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) tests/check.h | $(BUILD)/tests/core \
                  $(BUILD)/tests/port $(BUILD)/tests/host-sim
	$(CC) $(HOST_CFLAGS) -Itests -o $@ $< $(TEST_LIB) $(LIBSIM) $(LIBPORT) $(LIBVOLFIX) $(LDFLAGS) $(PORT_LIBS)

$(BUILD)/core $(BUILD)/port $(BUILD)/host-sim/ref $(BUILD)/host-sim/truth $(BUILD)/tests $(BUILD)/tests/core \
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

clean:
	rm -rf $(BUILD) out
