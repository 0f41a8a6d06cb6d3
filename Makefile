# modrt - one flat Makefile. User settings first; `make help` lists the targets.
#
#   REAL=double|float   scalar type of the runtime (real_t)
#   SAN=1               build with AddressSanitizer and UndefinedBehaviorSanitizer
#   FAULT=1             the fault-injection test build (-DRT_FAULT_INJECT=1)
#   O=DIR               output directory; by default keyed by everything that changes the
#                       object code: build/host, build/host-float, build/host-san, ...
#                       (cross targets: build/<target>, build/<target>-float)
#   CC=...              host compiler
#   V=1                 show every command (default: one line per step and test suite)

REAL ?= double
SAN ?= 0
FAULT ?= 0
CC ?= gcc
V ?= 0
# parallel jobs of the sub-makes `make test` runs
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
XSUF := $(if $(filter float,$(REAL)),-float)
O ?= build/host$(XSUF)$(if $(filter 1,$(SAN)),-san)$(if $(filter 1,$(FAULT)),-fault)
ifeq ($(V),1)
Q :=
else
Q := @
endif

.DEFAULT_GOAL := all

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
ifeq ($(FAULT),1)
CDEFS    += -DRT_FAULT_INJECT=1
endif
ifeq ($(SAN),1)
COPT     := -O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined,float-cast-overflow \
            -fno-sanitize-recover=all
LDSAN    := -fsanitize=address,undefined,float-cast-overflow
endif
CFLAGS_ALL = $(CSTD) $(COPT) $(CINC) $(CDEFS) -MMD -MP
# rt/ and models/ are freestanding: no libc, no libm, no builtins that call them; each
# layer sees only the headers it may include (rt/ its own, models/ rt/ and its own), so
# a wrong include fails the build (docs/architecture.md, "Layers")
CFLAGS_LAYER = $(CSTD) $(COPT) $(CDEFS) -MMD -MP -ffreestanding
CFLAGS_RT = $(CFLAGS_LAYER) -Irt
CFLAGS_MODELS = $(CFLAGS_LAYER) -Irt -Imodels

# ---- sources ----
RT_SRCS     := $(wildcard rt/*.c)
# the library scenes are compiled from models/scenes/*.scn by scenec (tools/scenec/)
MODEL_SRCS  := $(wildcard models/*.c) build/gen/scenes/registry.c \
               $(patsubst models/scenes/%.scn,build/gen/scenes/%.c,$(wildcard models/scenes/*.scn))
POSIX_SRCS  := ports/posix/port.c tools/modrt/runner.c tools/modrt/tune.c tools/modrt/cli.c \
               tools/modrt/info.c tools/modrt/study.c tools/modrt/check.c tools/modrt/rtloop.c tools/modrt/trace.c tools/modrt/link.c tools/modrt/mrlog.c ports/common/link_wire.c \
               tools/modrt/link_udp.c tools/modrt/fingerprint.c ports/common/link_hmac.c \
               tools/modrt/link_serial.c tools/modrt/serial.c ports/common/linkframe.c tools/modrt/replay.c \
               $(wildcard tools/modrt/sweep*.c)
# the tests of the API (tests/rt, tests/models, tests/host: rt.h alone) and the white-box
# tests of the runtime's parts (tests/whitebox: rt_sim.h, rti.h); tests/static/api_only.py
TEST_SRCS   := tests/harness.c tests/testutil.c tests/registry.c \
               $(wildcard tests/rt/*.c tests/models/*.c tests/whitebox/*.c)
HOST_TEST_SRCS := tests/host/main.c tests/host/registry.c \
                  $(wildcard tests/host/test_*.c tests/whitebox/host/test_*.c) \
                  ports/common/linkclient.c

obj = $(patsubst %.c,$(O)/obj/%.o,$(1))
RT_OBJS    := $(call obj,$(RT_SRCS))
MODEL_OBJS := $(call obj,$(MODEL_SRCS))
# an rt_sim allocated under other limits than the runtime's, which rt_init must refuse
$(call obj,tests/whitebox/host/test_layout.c): CDEFS += -DRT_MAX_X=512

# the scene language: scenec, generated scenes, modrt's scene files (docs/scene-language.md)
include tools/scenec/scenec.mk
# FMUs as block kinds on the host (tools/fmi/, docs/fmi.md): linked into modrt and the tests
include tools/fmi/fmi.mk

.PHONY: all help test unit demo bench check-freestanding cross-test footprint clean \
        $(addprefix cross-test-,$(CROSS_TARGETS)) $(addprefix check-target-,$(CROSS_TARGETS)) \
        foot-elf image effects

all: $(O)/modrt $(O)/svgplot $(SCENEC)

help:
	@echo "make              build the CLI (modrt), the scene compiler (scenec) and svgplot"
	@echo "                  into $(O)/"
	@echo "make demo         run the demo scene, write its trace and SVG plots into build/demo/"
	@echo "make test         every test suite, one line each, ending in 'N passed, N failed'"
	@echo "                  (V=1: every command and all output; logs in build/test-logs/;"
	@echo "                  about 25 min on 2 idle cores, README.md 'Tests'). One suite alone:"
	@$(foreach t,$(TEST_SUITES),printf '  make %-22s %s\n' '$(t)' '$(or $(TEST_HELP_$(t)),$(TEST_HELP_$(firstword $(subst cross-test-,cross-test ,$(t)))))';)
	@echo "make hard         the hard-case suite at full size (long), table in build/hard-table.md"
	@echo "make bench        benchmarks: figures into build/bench/ (make docs: into docs/)"
	@echo "make speedup      the multirate speedup at equal accuracy from instruction counts"
	@echo "                  (part of bench; a few minutes; SPEEDUP_JOBS=2)"
	@echo "make mujoco-scale MuJoCo 2.2.2 beside modrt on the scaling chains and trees at equal"
	@echo "                  accuracy (part of bench; installs libmujoco-dev; about 15 minutes)"
	@echo "make docs         refresh the committed figures and references under docs/"
	@echo "make cross-test   every cross target under QEMU (cross-test-<t>: one; targets:"
	@echo "                  $(CROSS_TARGETS))"
	@echo "make footprint    flash, RAM and instructions per tick of every scene on every target"
	@echo "make effects      what each effect of the lane change costs (M7 and host; a few minutes)"
	@echo "make study        what accuracy costs: docs/study.md and docs/study/*.svg, the four"
	@echo "                  paper examples on the host, Cortex-M4F and M7 (STUDY=quick: a subset)"
	@echo "make image TARGET=<t> SCENE=<file.scn|name> [CONSOLE=semihost|uart|itm|none]"
	@echo "           [REAL=float] [IMAGE_CFLAGS=...] [CLOCK_MHZ=...] [TICKS=...] [MEASURE=0]"
	@echo "                  a firmware image of one scene (docs/porting.md) into"
	@echo "                  build/image/<t>/ (REAL=float: binary32, into build/image/<t>-float/);"
	@echo "                  IMAGE_CFLAGS are added to the compile, e.g. -DCM_EXIT_SEMIHOST=1;"
	@echo "                  prints the QEMU command that runs it, then instructions per tick"
	@echo "                  (median/max over TICKS ticks under QEMU), stack, and whether the"
	@echo "                  slowest tick fits the base tick at CLOCK_MHZ (default: the"
	@echo "                  target's clock of make footprint); MEASURE=0 builds only"
	@echo "make hard         the hard-case suite at full length, table into build/hard-table.md"
	@echo "make test-<suite> one suite of make test: $(patsubst test-%,%,$(filter test-%,$(TEST_SUITES)))"
	@echo "                  (also check-freestanding, cross-test-<t>)"
	@echo "make fuzz         the scene-language fuzzer for $(FUZZ_TIME) s"
	@echo "make test-fmi     FMUs: import (FMI 2.0/3.0 ME), export (3.0 CS), the bad corpus;"
	@echo "                  make fuzz-fmi: the modelDescription.xml fuzzer (docs/fmi.md)"
	@echo "make deps         install what the targets need (tools/install-deps.sh)"
	@echo "make clean        remove build/"
	@echo "settings: REAL=double|float SAN=1 O=DIR V=1 CC=..."

# what a target needs that make cannot build: installed through tools/install-deps.sh
# when this user can (root or sudo), otherwise one line names the command to run
deps:
	@sh tools/install-deps.sh --auto all
deps-host:
	@sh tools/install-deps.sh --auto host
deps-bench:
	@sh tools/install-deps.sh --auto bench

# rt/ and models/ build freestanding; ports, tests and tools build hosted
$(O)/obj/rt/%.o: rt/%.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS_RT) -c $< -o $@
$(O)/obj/models/%.o: models/%.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS_MODELS) -c $< -o $@
$(O)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS_ALL) -c $< -o $@

$(O)/modrt: $(call obj,tools/modrt/modrt.c $(POSIX_SRCS) $(FMI_SRCS)) $(RT_OBJS) $(MODEL_OBJS)
	$(Q)$(CC) $(LDSAN) $^ -lpthread $(FMI_LIBS) -o $@

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
	$(Q)$(CC) $(CSTD) -O2 $< -lm -o $@

$(O)/tests: $(call obj,$(TEST_SRCS) $(HOST_TEST_SRCS) $(POSIX_SRCS) $(FMI_SRCS)) $(RT_OBJS) $(MODEL_OBJS)
	$(Q)$(CC) $(LDSAN) $^ -lpthread -lm $(FMI_LIBS) -o $@

# ---- tests ----
unit: $(O)/tests
	$(O)/tests

# rt/ and models/ linked together may leave undefined only compiler-emitted helpers
# (_GLOBAL_OFFSET_TABLE_ is the linker symbol of position-independent host code)
FREE_ALLOWED := memcpy memset memmove memcmp _GLOBAL_OFFSET_TABLE_
# (the objects build JOBS at a time: make test runs each suite without -j)
$(O)/freestanding.o: $(RT_OBJS) $(MODEL_OBJS)
	@$(CC) -r -nostdlib -o $@ $^
# ... and rt/, models/ compile with the smallest exact limits a per-scene image takes
EXACT_LIMIT_SCENES ?= oscillator pi_loop bouncing_ball
check-freestanding:
	+@$(MAKE) --no-print-directory -j$(JOBS) $(O)/freestanding.o $(O)/modrt
	@bad=$$(nm -u $(O)/freestanding.o | awk '{print $$NF}' | sort -u | \
	  grep -vxE '$(subst $() ,|,$(FREE_ALLOWED))'); \
	if [ -n "$$bad" ]; then echo "check-freestanding: rt/ or models/ call outside themselves:"; \
	  echo "$$bad"; exit 1; fi; \
	echo "check-freestanding: $(words $(RT_OBJS) $(MODEL_OBJS)) objects, no libc or libm: 1 passed, 0 failed"
	@CC=$(CC) sh tests/static/exact_limits.sh $(O)/modrt $(JOBS) "$(EXACT_LIMIT_SCENES)"

# every suite is a make target; `make test` runs them one after another, one line each,
# and ends with the grand total (tools/dev/run-suites.sh). Other makefiles add theirs to
# TEST_SUITES.
TEST_SUITES = check-freestanding test-unit test-san test-float test-faults test-cli test-scenec \
               test-fuzz test-fmi $(addprefix cross-test-,$(CROSS_TARGETS))
# one line each for `make help`
TEST_HELP_check-freestanding := rt/ and models/ link without libc or libm, compile at tiny exact limits
TEST_HELP_test-unit := the unit tests on the host (tests/rt, models, host, whitebox)
TEST_HELP_test-san := the unit tests under ASan and UBSan, out-of-range casts (casts.sh)
TEST_HELP_test-float := the unit tests of the REAL=float build
TEST_HELP_test-faults := fault injection (tests/faults/, FAULT=1, sanitized)
TEST_HELP_test-cli := the command line of modrt: cli.sh, cli_io.sh, make_again.sh, limits.py
TEST_HELP_test-scenec := scene compiler: error corpus, language tests, hashes, effects
TEST_HELP_test-fuzz := the scene fuzzer for 10 s, inputs up to 64 KB
TEST_HELP_cross-test := one target under QEMU: arithmetic, unit tests, whole scene runs
TEST_HELP_test-image := per-scene firmware images (make image) against the host hash
TEST_HELP_test-link := the controller link end to end (UDP, real time, replay)
TEST_HELP_test-link-fuzz := the datagram and replay-log fuzzer for 5 s
TEST_HELP_test-hard := the hard-case suite at CI sizes (make hard: full size)
TEST_HELP_test-static := file graph and docs tables of rt/, tools; cppcheck, clang-tidy
TEST_HELP_test-vehicles := the vehicle models against their references
TEST_HELP_test-study := the quick configurations (make study: all)
TEST_HELP_test-fmi := own test FMUs against closed forms, bad FMUs, export round trip
TEST_HELP_test-serial := the link over a pty: lock-step, real time, replay, line noise
TEST_HELP_test-serial-qemu := firmware controller and plant image on a Cortex-M in QEMU
TEST_HELP_test-frame-fuzz := the serial frame decoder fuzzer (COBS, resync) for 5 s
TEST_HELP_test-sweep := modrt sweep: metrics, draws, errors; local, GNU parallel, Slurm
test: deps
	@V=$(V) sh tools/dev/run-suites.sh "$(MAKE) JOBS=$(JOBS) V=$(V)" $(TEST_SUITES)
test-unit:
	$(MAKE) --no-print-directory -j$(JOBS) unit
test-san:
	$(MAKE) --no-print-directory -j$(JOBS) SAN=1 unit
	$(MAKE) --no-print-directory -j$(JOBS) SAN=1 build/host-san/modrt
	sh tests/casts.sh build/host-san/modrt
test-float:
	$(MAKE) --no-print-directory -j$(JOBS) REAL=float unit
# fault injection (tests/faults/test_faults.c): a build with the hooks of rti.h
$(O)/faults: $(call obj,tests/faults/test_faults.c tests/harness.c tests/testutil.c \
                      ports/posix/port.c) $(RT_OBJS) $(MODEL_OBJS)
	$(Q)$(CC) $(LDSAN) $^ -lm -o $@
faults: $(O)/faults
	$(O)/faults
test-faults:
	$(MAKE) --no-print-directory -j$(JOBS) FAULT=1 SAN=1 faults
test-cli:
	$(MAKE) --no-print-directory -j$(JOBS) all
	sh tests/make_again.sh "$(MAKE)" $(O)
	sh tests/cli.sh $(O)
	sh tests/cli_io.sh $(O)
	sh tests/help.sh "$(MAKE)"
	sh tests/docs_commit.sh
	sh tests/readme.sh
	python3 tests/scenec/limits.py $(O)/modrt
test-scenec:
	$(MAKE) --no-print-directory -j$(JOBS) scenec-test
test-fuzz:
	$(MAKE) --no-print-directory fuzz-short
.PHONY: deps deps-host test-unit test-san test-float test-faults faults test-cli test-scenec test-fuzz docs FORCE

# ---- cross targets (ports/targets.mk: compilers, flags, QEMU commands) ----
include ports/targets.mk
CROSS_CFLAGS := $(CSTD) -O2 -ffunction-sections -fdata-sections $(CINC) $(CDEFS) -DRT_KIND_DOCS=0 -MMD -MP
# the cross-test images (unit tests, scenes, rt.elf) hold no FMU: the blocks' internal
# state in a snapshot needs only the unit tests' few bytes there, and the host default
# (16 KB per rt_state) would not fit the unit-test images' copies of rt_sim in 4 MB of RAM.
# Per-scene images (foot-elf, make image) take the scene's own sizes instead. Their roots
# likewise: 16 (the library scenes have at most 2; the host's 48 leave room for two per
# located switch of a defined system).
# TU_CROSS: the long unit tests run their shorter span (tests/testutil.h, TU_FULL)
CROSS_TEST_DEFS := -DRT_MAX_KSTATE=256 -DTU_CROSS=1 -DRT_MAX_ROOTS=16
CROSS_TEST_SRCS := tests/cross/tests_main.c tests/harness.c tests/testutil.c tests/registry.c \
                   $(wildcard tests/rt/*.c tests/models/*.c tests/whitebox/*.c)
CROSS_SCENE_SRCS := tests/cross/scenes_main.c tests/harness.c
CROSS_RT_SRCS := ports/common/image_main.c
# the background set preempted for real (cross-test-<t> of these targets): pendulum10_actuated
# ticked in SysTick every 30 us of virtual time (30,000 instructions under -icount), its
# chain stepping in PendSV below it, preempted by the ticks that fall while it runs (a
# chain step takes longer than the 30 us between two ticks; at 80 or 100 us each step
# fits between two ticks, and nothing is preempted)
CROSS_BG_TARGETS := m7
CROSS_BG_TICKS := 1000
CROSS_BG_DEFS = -DRT_SCENE=mdl_scene_pendulum10_actuated -DRT_IMAGE_BG=1 \
                -DRT_IMAGE_TICKS=$(CROSS_BG_TICKS) -DRT_IMAGE_PERIOD_US=30
CROSS_SOFTFLOAT_SRCS := tests/cross/softfloat_test.c tests/harness.c
# The unit tests run as several images, and each library scene as an image of its own
# (tests/cross/tests_main.c, scenes_main.c), so that no one emulated run is long. Each
# run is bounded by an instruction budget (tests/cross/run.sh, the limit of
# tools/dev/qemu/insn_count.c), set from what rv32 (binary64 in software, the most
# expensive target) executed, with room to grow: softfloat 6.6e7; a tenth of the unit
# tests at most 4.0e10; pendulum10_actuated_single's whole run about 3.2e10; the
# timer-paced pi_loop 4e7. An image that runs past its budget stops and names it (raise it when
# many tests are added).
CROSS_PARTS := 10
CROSS_SCENE_PARTS = $(words $(SCN_FILES))
CROSS_PART_LIST = $(shell seq 0 $$(($(CROSS_PARTS) - 1)))
CROSS_SCENE_PART_LIST = $(shell seq 0 $$(($(CROSS_SCENE_PARTS) - 1)))
CROSS_BUDGET_SOFTFLOAT := 400000000
CROSS_BUDGET_TESTS := 100000000000
CROSS_BUDGET_SCENES := 120000000000
CROSS_BUDGET_RT := 1000000000
cobj = $(patsubst %,build/$(1)$(XSUF)/obj/%.o,$(basename $(2)))

# the host's binary64 results are the reference for every target's arithmetic
$(O)/softfloat: $(call obj,$(CROSS_SOFTFLOAT_SRCS) ports/posix/app_main.c ports/posix/port.c)
	$(CC) $(LDSAN) $^ -o $@

# the host's scene image is the reference every target must reproduce bit for bit
$(O)/scenes: $(call obj,tests/cross/scenes_main.c tests/harness.c ports/posix/app_main.c \
             ports/posix/port.c) $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -o $@

define CROSS_RULES
build/$(1)$(XSUF)/obj/%.o: %.c
	@mkdir -p $$(dir $$@)
	$(Q)$$(TARGET_CC_$(1)) $$(CROSS_CFLAGS) $$(TARGET_CFLAGS_$(1)) $$(CROSS_TEST_DEFS) -c $$< -o $$@
build/$(1)$(XSUF)/obj/%.o: %.S
	@mkdir -p $$(dir $$@)
	$(Q)$$(TARGET_CC_$(1)) $$(TARGET_CFLAGS_$(1)) -c $$< -o $$@
build/$(1)$(XSUF)/tests.elf: $$(call cobj,$(1),$$(CROSS_TEST_SRCS) $$(RT_SRCS) $$(MODEL_SRCS) \
                      $$(TARGET_PORT_SRCS_$(1)))
	$(Q)$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
# part K of N of the unit tests (tests/cross/tests_main.c), and of the scenes
build/$(1)$(XSUF)/obj/tests/cross/tests_main-%.o: tests/cross/tests_main.c
	@mkdir -p $$(dir $$@)
	$(Q)$$(TARGET_CC_$(1)) $$(CROSS_CFLAGS) $$(TARGET_CFLAGS_$(1)) $$(CROSS_TEST_DEFS) \
	  -DTH_PART=$$(word 1,$$(subst of, ,$$*)) -DTH_PARTS=$$(word 2,$$(subst of, ,$$*)) -c $$< -o $$@
build/$(1)$(XSUF)/tests-%.elf: build/$(1)$(XSUF)/obj/tests/cross/tests_main-%.o \
                      $$(call cobj,$(1),$$(filter-out tests/cross/tests_main.c,$$(CROSS_TEST_SRCS)) \
                      $$(RT_SRCS) $$(MODEL_SRCS) $$(TARGET_PORT_SRCS_$(1)))
	$(Q)$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
build/$(1)$(XSUF)/obj/tests/cross/scenes_main-%.o: tests/cross/scenes_main.c
	@mkdir -p $$(dir $$@)
	$(Q)$$(TARGET_CC_$(1)) $$(CROSS_CFLAGS) $$(TARGET_CFLAGS_$(1)) $$(CROSS_TEST_DEFS) \
	  -DSC_PART=$$(word 1,$$(subst of, ,$$*)) -DSC_PARTS=$$(word 2,$$(subst of, ,$$*)) -c $$< -o $$@
build/$(1)$(XSUF)/scenes-%.elf: build/$(1)$(XSUF)/obj/tests/cross/scenes_main-%.o \
                       $$(call cobj,$(1),tests/harness.c $$(RT_SRCS) $$(MODEL_SRCS) \
                       $$(TARGET_PORT_SRCS_$(1)))
	$(Q)$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
build/$(1)$(XSUF)/rt.elf: $$(call cobj,$(1),$$(CROSS_RT_SRCS) $$(RT_SRCS) $$(MODEL_SRCS) \
                   $$(TARGET_PORT_SRCS_$(1)))
	$(Q)$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
build/$(1)$(XSUF)/softfloat.elf: $$(call cobj,$(1),$$(CROSS_SOFTFLOAT_SRCS) $$(TARGET_PORT_SRCS_$(1)))
	$(Q)$$(TARGET_CC_$(1)) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
build/$(1)$(XSUF)/rt_bg.elf: ports/common/image_main.c $$(call cobj,$(1),$$(RT_SRCS) $$(MODEL_SRCS) \
                      $$(TARGET_PORT_SRCS_$(1)))
	$(Q)$$(TARGET_CC_$(1)) $$(filter-out -MMD -MP,$$(CROSS_CFLAGS)) $$(TARGET_CFLAGS_$(1)) $$(CROSS_TEST_DEFS) \
	  $$(CROSS_BG_DEFS) $$^ $$(TARGET_LDFLAGS_$(1)) -o $$@
# every run bounded by its instruction budget (tests/cross/run.sh); QEMU_TIMEOUT guards
# against QEMU itself hanging
cross-test-$(1): TARGET_QEMU_EXTRA = -plugin $(abspath $(INSN_COUNT_SO)),limit=@BUDGET@
# the images build JOBS at a time (make test runs each suite without -j), then run
cross-test-$(1):
	+@$(MAKE) --no-print-directory -j$(JOBS) cross-build-$(1)
	@QEMU_TIMEOUT=$(QEMU_TIMEOUT) CROSS_PARTS=$(CROSS_PARTS) CROSS_SCENE_PARTS=$(CROSS_SCENE_PARTS) \
	 CROSS_BUDGET_SOFTFLOAT=$(CROSS_BUDGET_SOFTFLOAT) CROSS_BUDGET_TESTS=$(CROSS_BUDGET_TESTS) \
	 CROSS_BUDGET_SCENES=$(CROSS_BUDGET_SCENES) CROSS_BUDGET_RT=$(CROSS_BUDGET_RT) \
	 CROSS_LDSCRIPT=$$(patsubst -T%,%,$$(filter -T%,$$(TARGET_LDFLAGS_$(1)))) \
	 sh tests/cross/cross_test.sh $(1) build/$(1)$(XSUF) $(O) "$$(TARGET_RUN_$(1))" \
	   "$$(TARGET_VTIME_$(1))" $(if $(filter $(1),$(CROSS_BG_TARGETS)),$(CROSS_BG_TICKS),0)
.PHONY: cross-build-$(1)
cross-build-$(1): $(INSN_COUNT_SO) build/$(1)$(XSUF)/softfloat.elf $(O)/softfloat.log \
                 $$(foreach k,$$(CROSS_PART_LIST),build/$(1)$(XSUF)/tests-$$(k)of$$(CROSS_PARTS).elf) \
                 $$(foreach k,$$(CROSS_SCENE_PART_LIST),build/$(1)$(XSUF)/scenes-$$(k)of$$(CROSS_SCENE_PARTS).elf) \
                 $(O)/scenes.log build/$(1)$(XSUF)/rt.elf $(O)/modrt \
                 $(if $(filter $(1),$(CROSS_BG_TARGETS)),build/$(1)$(XSUF)/rt_bg.elf)
endef
$(foreach t,$(CROSS_TARGETS),$(eval $(call CROSS_RULES,$(t))))
.SECONDARY: $(foreach t,$(CROSS_TARGETS), \
              $(foreach k,$(CROSS_PART_LIST),build/$(t)$(XSUF)/obj/tests/cross/tests_main-$(k)of$(CROSS_PARTS).o) \
              $(foreach k,$(CROSS_SCENE_PART_LIST),build/$(t)$(XSUF)/obj/tests/cross/scenes_main-$(k)of$(CROSS_SCENE_PARTS).o))

$(O)/softfloat.log: $(O)/softfloat
	$(O)/softfloat > $@

$(O)/scenes.log: $(O)/scenes $(O)/modrt
	$(O)/scenes > $@
	@sh tests/cross/check_host.sh $(O)/modrt $@

# every target whose toolchain and emulator are installed; the others are named
cross-test: deps
	@ran=""; skipped=""; \
	for t in $(CROSS_TARGETS); do \
	  if $(MAKE) --no-print-directory -s check-target-$$t 2>/dev/null; then \
	    $(MAKE) --no-print-directory cross-test-$$t || exit 1; ran="$$ran $$t"; \
	  else skipped="$$skipped $$t"; fi; done; \
	echo "cross-test: ran:$${ran:- none}; skipped (toolchain or QEMU missing):$${skipped:- none}"
$(foreach t,$(CROSS_TARGETS),$(eval check-target-$(t): ; @$$(TARGET_CHECK_$(t))))

# ---- footprint: one image per scene and target, sized by `modrt sizes` ----
FOOT_TARGETS := m3 m4f m7 rv32 rv64
FOOT_FLOAT_TARGETS := m4f m7 # the targets with a binary32 FPU get REAL=float rows too
# everything but the registries: a scene names its kinds and methods directly
FOOT_SRCS = tests/cross/footprint_main.c tests/harness.c \
            $(filter-out rt/registry.c,$(RT_SRCS)) \
            $(filter-out models/registry.c models/scenes/% build/gen/%,$(MODEL_SRCS))
footprint: deps build/host/modrt $(INSN_COUNT_SO) scenes
	$(MAKE) --no-print-directory REAL=float build/host-float/modrt
	sh tools/dev/footprint.sh "$(FOOT_TARGETS)" "$(FOOT_FLOAT_TARGETS)" > docs/footprint.md
	sh tools/dev/effects.sh >> docs/footprint.md
	@echo "footprint: wrote docs/footprint.md"
# the effects of the lane change alone (Cortex-M7 and the host, a few minutes): replaces
# the section "Effects of the lane change" at the end of docs/footprint.md
effects: deps build/host/modrt $(SCENEC) $(INSN_COUNT_SO)
	sh tools/dev/effects.sh > build/effects.md
	awk '/^## Effects of the lane change$$/ { exit } { print }' docs/footprint.md | \
	    sed -e :a -e '/^\n*$$/{$$d;N;ba' -e '}' > build/footprint.md
	cat build/effects.md >> build/footprint.md
	mv build/footprint.md docs/footprint.md
	@echo "effects: wrote the section of docs/footprint.md"
# one image: make foot-elf T=<target> S=<scene> (the flags come from modrt sizes); a scene
# outside the library: SCN=<file.scn> too, S its scene name (scenec compiles and sizes it);
# FOOT_CFLAGS=-DRT_SCENE_CODE=0: the table-driven path instead of the scene's written-out code
FOOT_TICKS ?= 1000
FOOT_GEN = $(if $(SCN),build/foot/gen/$(S).c,build/gen/scenes/$(S).c)
FOOT_SIZES = $(if $(SCN),$(shell build/host/scenec --sizes $(SCN)),$(shell build/host/modrt sizes $(S)))
# FOOT_FMU: a scene's FMU blocks, as tools/image.sh passes them (the importer's sources with
# -DFMU_TARGET, the FMU objects it compiled for the target)
FOOT_FMU ?=
# a scene with a background set runs it in PendSV (tests/cross/footprint_main.c)
FOOT_BG = $(shell build/host/modrt info $(or $(SCN),$(S)) | grep -q '^ *background:' && echo -DFOOT_BG=1)
foot-elf: $(call cobj,$(T),$(TARGET_PORT_SRCS_$(T)))
	@[ -n "$(T)" ] && [ -n "$(S)" ] || { echo "usage: make foot-elf T=<target> S=<scene> [SCN=<file.scn>]" >&2; exit 2; }
	@mkdir -p build/foot/$(T)$(XSUF) build/foot/gen
	@$(if $(SCN),build/host/scenec -o $(FOOT_GEN) $(SCN))
	@$(TARGET_CC_$(T)) $(filter-out -MMD -MP,$(CROSS_CFLAGS)) $(TARGET_CFLAGS_$(T)) \
	  $(FOOT_SIZES) $(FOOT_BG) $(FOOT_CFLAGS) \
	  -DFOOT_SCENE=mdl_scene_$(S) -DFOOT_TICKS=$(FOOT_TICKS) $(FOOT_SRCS) $(FOOT_GEN) \
	  $(FOOT_FMU) $^ $(TARGET_LDFLAGS_$(T)) -o build/foot/$(T)$(XSUF)/$(S).elf
$(INSN_COUNT_SO): $(INSN_COUNT_SRC)
	@mkdir -p $(dir $@)
	$(INSN_COUNT_CC) $(INSN_COUNT_CFLAGS) -o $@ $<
# ---- image: one scene file on one target (docs/porting.md) ----
# make image TARGET=m4f SCENE=path/to/my.scn [CONSOLE=semihost|uart|itm|none] [IMAGE_CFLAGS=...]
image: deps build/host/modrt $(SCENEC) $(INSN_COUNT_SO)
	@JOBS=$(JOBS) sh tools/image.sh "$(TARGET)" "$(SCENE)" "$(CONSOLE)" "$(IMAGE_CFLAGS)" \
	    "$(CLOCK_MHZ)" "$(TICKS)" "$(MEASURE)"
TEST_SUITES += test-image
# the CMSIS port's hand-built images beside `make image`'s (their build dirs are apart)
test-image: deps build/host/modrt $(SCENEC) $(INSN_COUNT_SO) build/host/fmi/snap
	+@mkdir -p build/cmsis; sh tests/cmsis/check.sh > build/cmsis/check.log 2>&1 & p=$$!; \
	 sh tests/image.sh; r=$$?; wait $$p; c=$$?; cat build/cmsis/check.log; \
	 [ $$r -eq 0 ] && [ $$c -eq 0 ]

# prints a make variable (used by tools/dev/footprint.sh)
print-%:
	@echo '$($*)'

# ---- benchmarks: figures and plots into docs/ (never timed tests) ----
$(O)/mbs_bench: $(call obj,tools/dev/bench/mbs_bench.c tools/dev/bench/bench_doc.c) $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -lm -o $@
$(O)/multirate_bench: $(call obj,tools/dev/bench/multirate_bench.c tools/dev/bench/bench_doc.c) \
                     $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -lm -o $@
$(O)/overhead_bench: $(call obj,tools/dev/bench/overhead_bench.c tools/dev/bench/pendulum_mono.c \
                    tools/dev/bench/actuated_mono.c tools/dev/bench/actuated_mr_mono.c) \
                    $(RT_OBJS) $(MODEL_OBJS)
	$(CC) $(LDSAN) $^ -lm -o $@
$(O)/tight_bench: $(call obj,tools/dev/bench/tight_bench.c tools/dev/bench/pendulum_tight.c \
                  tools/dev/bench/lane_tight.c) \
                  $(RT_OBJS) $(MODEL_OBJS)
	$(Q)$(CC) $(LDSAN) $^ -lm -o $@
# modrt against the hand-written programs (docs/overhead.md): the trajectory checks (fail
# the target when they differ), then instruction counts, ratios and the scaling with the
# model's size, spliced into a copy of docs/overhead.md in build/bench/
SCALE_STEPS ?= 10 # steps each scaling run counts
overhead: $(O)/overhead_bench $(O)/tight_bench
	@mkdir -p build/bench
	$(O)/overhead_bench check
	$(O)/tight_bench check
	@cp docs/overhead.md build/bench/
	@sh tools/dev/bench/overhead.sh $(O) 1 build/bench/overhead.md | tee build/bench/overhead.txt
	sh tools/dev/bench/scale.sh $(SCALE_STEPS) > build/bench/scale.md
	@sh tools/dev/bench/splice.sh scale build/bench/overhead.md build/bench/scale.md
	@cat build/bench/scale.md
.PHONY: overhead
# MuJoCo 2.2.2 (Debian's libmujoco-dev, a bench-only dependency) beside modrt on the scaling
# chains and trees at equal accuracy, both swept over method and step (docs/overhead.md,
# "Beside MuJoCo"), spliced into build/bench/overhead.md after overhead's tables
mujoco-scale: deps-bench overhead
	python3 tools/dev/bench/mujoco_scale.py > build/bench/mujoco.md
	@sh tools/dev/bench/splice.sh mujoco build/bench/overhead.md build/bench/mujoco.md
	@cat build/bench/mujoco.md
.PHONY: mujoco-scale deps-bench
# the multirate speedup at equal accuracy (issue 14, goal 4; docs/multirate.md, "The
# benchmark"): single-rate and multirate sweeps of pendulum10_actuated and lane_change,
# errors from the host binary, costs from callgrind's instruction counts; spliced into a
# copy of docs/multirate.md in build/bench/, with the work-precision plot
SPEEDUP_JOBS ?= 2
# the finalists are also compiled by scenec (the code it writes out, as the scenes ship)
# and linked with the runtime and the models (tools/dev/bench/code_run.c)
SPEEDUP_OBJS = $(RT_OBJS) $(call obj,$(wildcard models/*.c))
speedup: $(O)/modrt $(O)/svgplot $(SCENEC) $(SPEEDUP_OBJS)
	@mkdir -p build/bench
	@cp docs/multirate.md build/bench/
	python3 tools/dev/bench/speedup.py --modrt $(O)/modrt --jobs $(SPEEDUP_JOBS) \
	    --code $(SCENEC) "$(CC) $(CSTD) $(COPT) $(CINC) $(CDEFS)" "$(SPEEDUP_OBJS)" \
	    --doc build/bench/multirate.md
	$(O)/svgplot --xy --logx --logy \
	    -t "pendulum10_actuated: error against instructions" \
	    -x "host instructions per simulated s (rt_tick + rt_record)" \
	    -y "largest position error every 0.128 s [m]" \
	    -o build/bench/multirate_bench.svg build/bench/speedup-pendulum10_actuated.csv
.PHONY: speedup
# benchmarks write into build/bench/ only (documents are spliced into copies there);
# `make docs` runs them and copies the figures over the committed ones in docs/
BENCH_DOCS := mbs.md mbs_bench.svg multirate.md multirate_bench.svg overhead.md
RT_BENCH_S ?= 60 # seconds of each real-time run of the bench
bench: $(O)/mbs_bench $(O)/svgplot $(O)/modrt overhead mujoco-scale speedup serial-bench
	@mkdir -p build/bench
	@cp docs/mbs.md build/bench/
	$(O)/mbs_bench --csv build/bench/mbs.csv --doc build/bench/mbs.md \
	    --commit $$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
	$(O)/svgplot --xy --logx --logy -t "pendulum10: position error at 2 s against host CPU time" \
	    -x "host CPU s per simulated s" -y "largest position error at 2 s [m]" \
	    -o build/bench/mbs_bench.svg build/bench/mbs.csv
	@sh tools/dev/bench/rt_bench.sh $(O)/modrt $(RT_BENCH_S)
	@rm -f build/bench/bg.txt
	@sh tools/dev/bench/bg_bench.sh pendulum10 m7
	@sh tools/dev/bench/bg_bench.sh pendulum10_actuated m7
	@sh tools/dev/bench/tick_bench.sh m7
	@echo "bench: figures in build/bench/ (make docs copies them into docs/)"

# the committed references and figures: the block reference from the kinds' tables, and
# the benchmark figures
docs: bench docs/blocks.md
	cp $(addprefix build/bench/,$(BENCH_DOCS)) docs/
	@echo "docs: refreshed docs/blocks.md and $(BENCH_DOCS)"
docs/blocks.md: $(O)/modrt
	$(O)/modrt docs-blocks > $@

# ---- demo ----
# the paper's first example: the 10-body pendulum; plot the tip, the middle, the first body
DEMO_SCENE ?= pendulum10
DEMO_COLS ?= B1.x=bob 1 horizontal,B1.z=bob 1 vertical,B5.x=bob 5 horizontal,B5.z=bob 5 vertical,B10.x=bob 10 horizontal,B10.z=bob 10 vertical
DEMO_YLABEL ?= position [m]
DEMO_PLOT = $(O)/svgplot -o build/demo/$(DEMO_SCENE)
demo: deps-host $(O)/modrt $(O)/svgplot
	@mkdir -p build/demo
	$(O)/modrt run $(DEMO_SCENE) --csv build/demo/$(DEMO_SCENE).csv
	$(DEMO_PLOT).svg -t "$(DEMO_SCENE)" $(if $(DEMO_COLS),-c "$(DEMO_COLS)") -y "$(DEMO_YLABEL)" \
	    build/demo/$(DEMO_SCENE).csv
ifeq ($(DEMO_SCENE),pendulum10)
	$(DEMO_PLOT)-energy.svg -t "pendulum10: energy (conserved: the chain is passive)" \
	    -c "B1.energy=total energy of the chain" -y "energy [J]" build/demo/pendulum10.csv
	$(DEMO_PLOT)-residual.svg -t "pendulum10: constraint residual after projection" \
	    -c "B1.residual=largest joint violation" -y "residual [m]" build/demo/pendulum10.csv
	@echo "demo: energy and residual plots build/demo/pendulum10-energy.svg, -residual.svg"
endif
	@echo "demo: trace build/demo/$(DEMO_SCENE).csv, plot build/demo/$(DEMO_SCENE).svg"
	$(O)/modrt run lane_change --csv build/demo/lane_change.csv
	sh tools/lane_view.sh build/demo/lane_change.csv > build/demo/lane_change_top.csv
	$(O)/svgplot --xy --lines -W 1000 -H 360 -x "x along the track [m]" -y "y [m]" \
	    -t "lane_change: paths of both spatial cars through the ISO 3888-1 cones at 20 m/s" \
	    -o build/demo/lane_change-top.svg build/demo/lane_change_top.csv
	$(O)/svgplot -o build/demo/lane_change-steer.svg -t "lane_change: steering" \
	    -c "Driver.delta=V1 (driver),Tow.delta=V2 command,Servo.delta=V2 (servo)" \
	    -y "steering angle [rad]" build/demo/lane_change.csv
	$(O)/svgplot -o build/demo/lane_change-ay.svg -t "lane_change: lateral acceleration" \
	    -c "V1.ay=V1,V2.ay=V2" -y "lateral acceleration [m/s^2]" build/demo/lane_change.csv
	$(O)/svgplot -o build/demo/lane_change-roll.svg -t "lane_change: roll of the chassis" \
	    -c "V1.roll=V1,V2.roll=V2" -y "roll angle [rad]" build/demo/lane_change.csv
	@echo "demo: lane change build/demo/lane_change-top.svg, -steer.svg, -ay.svg, -roll.svg"

clean:
	rm -rf build

include tests/link/link.mk

-include $(shell find build -name '*.d' 2>/dev/null)
# the dependency files are written by the compilers as they go: no rule makes them (else
# make would chain built-in rules to remake each one it includes)
%.d: ;
include tests/hard/hard.mk
include tests/static/static.mk
include tests/vehicles/vehicles.mk
include tools/dev/study/study.mk
include tests/sweep/sweep.mk
