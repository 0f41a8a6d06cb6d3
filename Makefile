# modrt - one flat Makefile. User settings first; `make help` lists the targets.
#
#   REAL=double|float   scalar type of the runtime (real_t)
#   O=DIR               output directory (default build/host, build/host-float for REAL=float)
#   SAN=1               build with AddressSanitizer and UndefinedBehaviorSanitizer
#   CC=...              host compiler

REAL ?= double
SAN ?= 0
CC ?= gcc
# parallel jobs of the sub-makes `make test` runs
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
ifeq ($(REAL),float)
O ?= build/host-float
else
O ?= build/host
endif

# ---- flags: the same everywhere, so every target computes the same bits ----
CSTD     := -std=c11 -Wall -Wextra -Werror -ffp-contract=off -fno-math-errno
COPT     := -O2 -g -ffunction-sections -fdata-sections
CINC     := -Irt -Imodels -Iports -Iports/posix -Itools/modrt -Itests
CDEFS    :=
ifeq ($(REAL),float)
CDEFS    += -DRT_REAL_FLOAT
else ifneq ($(REAL),double)
$(error REAL must be double or float, not '$(REAL)')
endif
ifeq ($(SAN),1)
COPT     := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all
LDSAN    := -fsanitize=address,undefined
endif
CFLAGS_ALL = $(CSTD) $(COPT) $(CINC) $(CDEFS) -MMD -MP
# rt/ and models/ are freestanding: no libc, no libm, no builtins that call them
CFLAGS_FREE = $(CFLAGS_ALL) -ffreestanding

# ---- sources ----
RT_SRCS     := $(wildcard rt/*.c)
# the library scenes are compiled from models/scenes/*.scn by scenec (tools/scenec/)
MODEL_SRCS  := $(wildcard models/*.c) build/gen/scenes/registry.c \
               $(patsubst models/scenes/%.scn,build/gen/scenes/%.c,$(wildcard models/scenes/*.scn))
POSIX_SRCS  := ports/posix/port.c tools/modrt/runner.c tools/modrt/tune.c tools/modrt/cli.c \
               tools/modrt/info.c
TEST_SRCS   := tests/harness.c tests/testutil.c tests/registry.c $(wildcard tests/rt/*.c tests/models/*.c)
HOST_TEST_SRCS := tests/host/main.c tests/host/registry.c $(wildcard tests/host/test_*.c)

obj = $(patsubst %.c,$(O)/obj/%.o,$(1))
RT_OBJS    := $(call obj,$(RT_SRCS))
MODEL_OBJS := $(call obj,$(MODEL_SRCS))

# the scene language: scenec, generated scenes, modrt's scene files (docs/scene-language.md)
include tools/scenec/scenec.mk

.PHONY: all help test unit demo bench check-freestanding cross-test footprint clean \
        $(addprefix cross-test-,$(CROSS_TARGETS)) $(addprefix check-target-,$(CROSS_TARGETS)) \
        foot-elf

all: $(O)/modrt $(O)/svgplot

help:
	@echo "make            build the CLI and tools into $(O)/"
	@echo "make demo       run the demo scene, write its trace and an SVG plot"
	@echo "make test       every test: freestanding check, unit tests (plain, sanitized,"
	@echo "                float), CLI checks, cross tests where toolchains exist"
	@echo "make bench      work-precision and cost figures"
	@echo "make clean      remove build/"

# rt/ and models/ build freestanding; ports, tests and tools build hosted
$(O)/obj/rt/%.o: rt/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_FREE) -c $< -o $@
$(O)/obj/models/%.o: models/%.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_FREE) -c $< -o $@
$(O)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS_ALL) -c $< -o $@

$(O)/modrt: $(call obj,tools/modrt/modrt.c $(POSIX_SRCS)) $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -o $@

# the version `modrt --version` prints: the git description, rewritten only when it changes
$(call obj,tools/modrt/modrt.c): build/gen/version.h
$(call obj,tools/modrt/modrt.c): CINC += -Ibuild/gen
build/gen/version.h: FORCE
	@mkdir -p $(dir $@)
	@v=$$(git describe --always --dirty 2>/dev/null || echo unknown); \
	 echo "#define MODRT_VERSION \"$$v\"" > $@.tmp; \
	 cmp -s $@.tmp $@ && rm -f $@.tmp || mv $@.tmp $@
FORCE:

$(O)/svgplot: tools/svgplot.c
	@mkdir -p $(dir $@)
	$(CC) $(CSTD) -O2 $< -lm -o $@

$(O)/tests: $(call obj,$(TEST_SRCS) $(HOST_TEST_SRCS) $(POSIX_SRCS)) $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -lm -o $@

# ---- tests ----
unit: $(O)/tests
	$(O)/tests

# rt/ and models/ linked together may leave undefined only compiler-emitted helpers
# (_GLOBAL_OFFSET_TABLE_ is the linker symbol of position-independent host code)
FREE_ALLOWED := memcpy memset memmove memcmp _GLOBAL_OFFSET_TABLE_
check-freestanding: $(RT_OBJS) $(MODEL_OBJS)
	@$(CC) -r -nostdlib -o $(O)/freestanding.o $^
	@bad=$$(nm -u $(O)/freestanding.o | awk '{print $$NF}' | sort -u | \
	  grep -vxE '$(subst $() ,|,$(FREE_ALLOWED))'); \
	if [ -n "$$bad" ]; then echo "check-freestanding: rt/ or models/ call outside themselves:"; \
	  echo "$$bad"; exit 1; fi; echo "check-freestanding: ok ($(words $^) objects, no libc or libm)"

test: check-freestanding
	$(MAKE) --no-print-directory -j$(JOBS) unit
	$(MAKE) --no-print-directory -j$(JOBS) O=build/host-san SAN=1 unit
	$(MAKE) --no-print-directory -j$(JOBS) REAL=float unit
	$(MAKE) --no-print-directory -j$(JOBS) all
	sh tests/cli.sh $(O)
	$(MAKE) --no-print-directory -j$(JOBS) scenec-test
	$(MAKE) --no-print-directory fuzz-short
	$(MAKE) --no-print-directory -j$(JOBS) cross-test

# ---- cross targets (ports/targets.mk: compilers, flags, QEMU commands) ----
include ports/targets.mk
CROSS_CFLAGS := $(CSTD) -O2 -ffunction-sections -fdata-sections $(CINC) $(CDEFS) -DRT_KIND_DOCS=0 -MMD -MP
CROSS_TEST_SRCS := tests/cross/tests_main.c tests/harness.c tests/testutil.c tests/registry.c \
                   $(wildcard tests/rt/*.c tests/models/*.c)
CROSS_SCENE_SRCS := tests/cross/scenes_main.c tests/harness.c
CROSS_RT_SRCS := tests/cross/rt_main.c tests/harness.c
CROSS_SOFTFLOAT_SRCS := tests/cross/softfloat_test.c tests/harness.c
cobj = $(patsubst %,build/$(1)/obj/%.o,$(basename $(2)))

# the host's binary64 results are the reference for every target's arithmetic
$(O)/softfloat: $(call obj,$(CROSS_SOFTFLOAT_SRCS) ports/posix/app_main.c ports/posix/port.c)
	$(CC) $(LDSAN) $^ -o $@

# the host's scene image is the reference every target must reproduce bit for bit
$(O)/scenes: $(call obj,tests/cross/scenes_main.c tests/harness.c ports/posix/app_main.c \
             ports/posix/port.c) $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -o $@

define CROSS_RULES
build/$(1)/obj/%.o: %.c
	@mkdir -p $$(dir $$@)
	$$(TARGET_CC_$(1)) $$(CROSS_CFLAGS) $$(TARGET_CFLAGS_$(1)) -c $$< -o $$@
build/$(1)/obj/%.o: %.S
	@mkdir -p $$(dir $$@)
	$$(TARGET_CC_$(1)) $$(TARGET_CFLAGS_$(1)) -c $$< -o $$@
build/$(1)/tests.elf: $$(call cobj,$(1),$$(CROSS_TEST_SRCS) $$(RT_SRCS) $$(MODEL_SRCS) \
                      $$(TARGET_PORT_SRCS_$(1)))
	$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
build/$(1)/scenes.elf: $$(call cobj,$(1),$$(CROSS_SCENE_SRCS) $$(RT_SRCS) $$(MODEL_SRCS) \
                       $$(TARGET_PORT_SRCS_$(1)))
	$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
build/$(1)/rt.elf: $$(call cobj,$(1),$$(CROSS_RT_SRCS) $$(RT_SRCS) $$(MODEL_SRCS) \
                   $$(TARGET_PORT_SRCS_$(1)))
	$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
build/$(1)/softfloat.elf: $$(call cobj,$(1),$$(CROSS_SOFTFLOAT_SRCS) $$(TARGET_PORT_SRCS_$(1)))
	$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
cross-test-$(1): build/$(1)/tests.elf build/$(1)/scenes.elf build/$(1)/rt.elf \
                 build/host/scenes.log build/$(1)/softfloat.elf build/host/softfloat.log
	@$$(TARGET_RUN_$(1)) build/$(1)/softfloat.elf > build/$(1)/softfloat.log 2>&1 || \
	  { cat build/$(1)/softfloat.log; echo "cross-test $(1): softfloat test failed"; exit 1; }
	@if diff build/host/softfloat.log build/$(1)/softfloat.log; then \
	  echo "cross-test $(1): $$$$(grep -c hash build/$(1)/softfloat.log) binary64 result hashes equal the host's"; \
	else echo "cross-test $(1): binary64 result hashes differ from the host's"; exit 1; fi
	@echo "cross-test $(1): unit tests"
	@$$(TARGET_RUN_$(1)) build/$(1)/tests.elf > build/$(1)/tests.log 2>&1 || \
	  { grep -E 'FAIL|passed' build/$(1)/tests.log; echo "cross-test $(1): unit tests failed"; exit 1; }
	@tail -1 build/$(1)/tests.log
	@$$(TARGET_RUN_$(1)) build/$(1)/scenes.elf > build/$(1)/scenes.log 2>&1 || \
	  { cat build/$(1)/scenes.log; echo "cross-test $(1): scene image failed"; exit 1; }
	@if diff build/host/scenes.log build/$(1)/scenes.log; then \
	  echo "cross-test $(1): $$$$(wc -l < build/$(1)/scenes.log) scene hashes equal the host's"; \
	else echo "cross-test $(1): scene hashes differ from the host's"; exit 1; fi
	@$$(TARGET_RUN_$(1)) build/$(1)/rt.elf > build/$(1)/rt.log 2>&1 || \
	  { cat build/$(1)/rt.log; echo "cross-test $(1): timer-paced run failed"; exit 1; }
	@h=$$$$(sed -n 's/.* hash //p' build/$(1)/rt.log); \
	if [ "$$$$h" = "$$$$(build/host/modrt run pi_loop | sed -n 's/^hash: //p')" ]; then \
	  echo "cross-test $(1): timer-paced pi_loop: $$$$(sed 's/^rt scene pi_loop //' build/$(1)/rt.log)"; \
	else cat build/$(1)/rt.log; echo "cross-test $(1): timer-paced hash differs"; exit 1; fi
	@if [ "$$(TARGET_VTIME_$(1))" = 1 ] && ! grep -q ' overruns 0 ' build/$(1)/rt.log; then \
	  echo "cross-test $(1): overruns in deterministic virtual time"; exit 1; fi
endef
$(foreach t,$(CROSS_TARGETS),$(eval $(call CROSS_RULES,$(t))))

build/host/softfloat.log: build/host/softfloat
	build/host/softfloat > $@

build/host/scenes.log: build/host/scenes build/host/modrt
	build/host/scenes > $@
	@sh tests/cross/check_host.sh build/host/modrt $@

# every target whose toolchain and emulator are installed; the others are named
cross-test:
	@ran=""; skipped=""; \
	for t in $(CROSS_TARGETS); do \
	  if $(MAKE) --no-print-directory -s check-target-$$t 2>/dev/null; then \
	    $(MAKE) --no-print-directory cross-test-$$t || exit 1; ran="$$ran $$t"; \
	  else skipped="$$skipped $$t"; fi; done; \
	echo "cross-test: ran:$${ran:- none}; skipped (toolchain or QEMU missing):$${skipped:- none}"
$(foreach t,$(CROSS_TARGETS),$(eval check-target-$(t): ; @$$(TARGET_CHECK_$(t))))

# ---- footprint: one image per scene and target, sized by `modrt sizes` ----
FOOT_TARGETS := m3 m4f m7 rv32 rv64
# everything but the registries: a scene names its kinds and methods directly
FOOT_SRCS = tests/cross/footprint_main.c tests/harness.c \
            $(filter-out rt/registry.c,$(RT_SRCS)) \
            $(filter-out models/registry.c models/scenes/% build/gen/%,$(MODEL_SRCS))
footprint: build/host/modrt $(INSN_COUNT_SO) scenes
	sh tools/footprint.sh "$(FOOT_TARGETS)" > docs/footprint.md
	@echo "footprint: wrote docs/footprint.md"
# one image: make foot-elf T=<target> S=<scene> (the flags come from modrt sizes)
FOOT_TICKS ?= 1000
foot-elf: $(call cobj,$(T),$(TARGET_PORT_SRCS_$(T)))
	@mkdir -p build/foot/$(T)
	@$(TARGET_CC_$(T)) $(filter-out -MMD -MP,$(CROSS_CFLAGS)) $(TARGET_CFLAGS_$(T)) \
	  $(shell build/host/modrt sizes $(S)) \
	  -DFOOT_SCENE=mdl_scene_$(S) -DFOOT_TICKS=$(FOOT_TICKS) $(FOOT_SRCS) build/gen/scenes/$(S).c \
	  $^ $(TARGET_LDFLAGS_$(T)) -o build/foot/$(T)/$(S).elf
$(INSN_COUNT_SO): $(INSN_COUNT_SRC)
	@mkdir -p $(dir $@)
	$(INSN_COUNT_CC) $(INSN_COUNT_CFLAGS) -o $@ $<
# prints a make variable (used by tools/footprint.sh)
print-%:
	@echo '$($*)'

# ---- benchmarks: figures and plots into docs/ (never timed tests) ----
$(O)/mbs_bench: $(call obj,tools/bench/mbs_bench.c tools/bench/bench_doc.c) $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -lm -o $@
$(O)/multirate_bench: $(call obj,tools/bench/multirate_bench.c tools/bench/bench_doc.c) \
                     $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -lm -o $@
bench: $(O)/mbs_bench $(O)/multirate_bench $(O)/svgplot
	@mkdir -p build/bench
	$(O)/mbs_bench --csv build/bench/mbs.csv --doc docs/mbs.md
	$(O)/svgplot --xy --logx --logy -t "pendulum10: position error at 2 s against host CPU time" \
	    -x "host CPU s per simulated s" -y "largest position error at 2 s [m]" \
	    -o docs/mbs_bench.svg build/bench/mbs.csv
	$(O)/multirate_bench --csv build/bench/multirate.csv --doc docs/multirate.md
	$(O)/svgplot --xy --logx --logy \
	    -t "pendulum10_actuated: position error at 10 s against host CPU time" \
	    -x "host CPU s per run of 10 s" -y "largest position error at 10 s [m]" \
	    -o docs/multirate_bench.svg build/bench/multirate.csv

# ---- demo ----
# the paper's first example: the 10-body pendulum; plot the tip, the middle, the first body
DEMO_SCENE ?= pendulum10
DEMO_COLS ?= B1.x,B1.z,B5.x,B5.z,B10.x,B10.z
demo: $(O)/modrt $(O)/svgplot
	@mkdir -p build/demo
	$(O)/modrt run $(DEMO_SCENE) --csv build/demo/$(DEMO_SCENE).csv
	$(O)/svgplot -t "$(DEMO_SCENE)" $(if $(DEMO_COLS),-c $(DEMO_COLS)) \
	    -o build/demo/$(DEMO_SCENE).svg build/demo/$(DEMO_SCENE).csv
	@echo "demo: trace build/demo/$(DEMO_SCENE).csv, plot build/demo/$(DEMO_SCENE).svg"

clean:
	rm -rf build

-include $(shell find build -name '*.d' 2>/dev/null)
