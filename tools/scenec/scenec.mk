# scenec.mk - the scene compiler (tools/scenec/, docs/scene-language.md) and the scenes it
# compiles. Included by the top-level Makefile after its sources section; uses its CC,
# CSTD, CFLAGS_ALL, CFLAGS_MODELS, O, RT_OBJS, MODEL_OBJS and obj.
#
#   make scenec        build/host/scenec, the compiler (always a double build: the C it
#                      writes holds the kinds' defaults as printed doubles)
#   make scenes        build/gen/scenes/<name>.c for every models/scenes/<name>.scn, and
#                      build/gen/scenes/registry.c (mdl_scenes)
#   make scenec-test   error corpus, language tests, compiled = interpreted hashes for
#                      every scene file, and the effects check (per-scene images)
#   make fuzz          the parser fuzzer for FUZZ_TIME seconds (default 60)
#   make fuzz-short    the same for 10 s (CI)

SCN_DIR      := tools/scenec
SCN_GEN      := build/gen/scenes
SCN_TGEN     := build/gen/scenec-test
SCN_FILES    := $(sort $(wildcard models/scenes/*.scn))
SCN_TFILES   := $(sort $(wildcard tests/scenec/scenes/*.scn))
SCENEC       := build/host/scenec
FUZZ_TIME    ?= 60

# the generated scenes: what the switch-over puts into MODEL_SRCS
SCN_GEN_SRCS := $(patsubst models/scenes/%.scn,$(SCN_GEN)/%.c,$(SCN_FILES)) $(SCN_GEN)/registry.c
SCN_TGEN_SRCS := $(patsubst tests/scenec/scenes/%.scn,$(SCN_TGEN)/%.c,$(SCN_TFILES)) \
                 $(SCN_TGEN)/registry.c
# what modrt links to read scene files (`modrt run FILE.scn`)
SCN_LIB_SRCS := $(addprefix $(SCN_DIR)/,lex.c parse.c expr.c lookup.c check.c sets.c link.c image.c \
                  vm.c emit.c spec.c host.c fmu.c)
SCN_LIB_OBJS  = $(call obj,$(SCN_LIB_SRCS))
# the model library without any scene (scenec and the test images bring their own)
SCN_MODEL_OBJS = $(filter-out $(O)/obj/models/scenes/% $(O)/obj/build/%,$(MODEL_OBJS))

.PHONY: scenec scenes scenec-test fuzz fuzz-short
.SECONDARY: $(SCN_GEN_SRCS) $(SCN_TGEN_SRCS)

scenec: $(SCENEC)
scenes: $(SCN_GEN_SRCS)

# modrt reads scene files through host.c; its include of scn_host.h finds tools/scenec
$(O)/modrt $(O)/tests: $(SCN_LIB_OBJS)
$(call obj,tools/modrt/modrt.c tools/modrt/cli.c tools/modrt/study.c): CINC += -I$(SCN_DIR)
$(O)/obj/tests/scenec/%.o: CINC += -I$(SCN_DIR)

ifeq ($(O),build/host)
# (linked under another name and renamed: the rules that run it never exec a file a
# writer may still hold open, which failed a clean build once with "Text file busy")
$(SCENEC): $(call obj,$(SCN_DIR)/scenec.c tools/fmi/fmu_export.c) $(SCN_LIB_OBJS) $(RT_OBJS) \
           $(SCN_MODEL_OBJS)
	$(CC) $(LDSAN) $^ $(FMI_LIBS) -o $@.tmp
	mv -f $@.tmp $@
else
# other builds (REAL=float, SAN=1, FAULT=1) use the double compiler of build/host
$(SCENEC): scenec-always
	@$(MAKE) --no-print-directory O=build/host REAL=double SAN=0 FAULT=0 $(SCENEC)
.PHONY: scenec-always
scenec-always:
endif

# ---- scene files -> C (dependencies on included files in <name>.d) ----
$(SCN_GEN)/%.c: models/scenes/%.scn $(SCENEC)
	@mkdir -p $(dir $@)
	$(SCENEC) -o $@ -M $(SCN_GEN)/$*.d $<
$(SCN_GEN)/registry.c: $(SCN_FILES) $(SCENEC)
	@mkdir -p $(dir $@)
	$(SCENEC) --registry -o $@ $(SCN_FILES)
$(SCN_TGEN)/%.c: tests/scenec/scenes/%.scn $(SCENEC)
	@mkdir -p $(dir $@)
	$(SCENEC) -o $@ -M $(SCN_TGEN)/$*.d $<
$(SCN_TGEN)/registry.c: $(SCN_TFILES) $(SCENEC)
	@mkdir -p $(dir $@)
	$(SCENEC) --registry --symbol scn_test_scenes -o $@ $(SCN_TFILES)

# generated scenes are model code: freestanding like models/
$(O)/obj/build/gen/%.o: build/gen/%.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CFLAGS_MODELS) -c $< -o $@

# ---- tests ----
# every compiled scene (library and language tests) run as `modrt run` does
$(O)/scenec-run: $(call obj,tests/scenec/run_compiled.c $(SCN_GEN_SRCS) $(SCN_TGEN_SRCS)) \
                 $(RT_OBJS) $(SCN_MODEL_OBJS)
	$(Q)$(CC) $(LDSAN) $^ -o $@
# the language's own tests (expressions, defines, error texts) on the in-house harness
$(O)/scenec-tests: $(call obj,tests/scenec/test_scenec.c tests/harness.c ports/posix/port.c) \
                   $(SCN_LIB_OBJS) $(RT_OBJS) $(SCN_MODEL_OBJS)
	$(Q)$(CC) $(LDSAN) $^ -o $@

scenec-test: $(SCENEC) $(O)/modrt $(O)/scenec-run $(O)/scenec-tests \
             $(call obj,$(SCN_GEN_SRCS))
	$(O)/scenec-tests
	sh tests/scenec/errors.sh $(SCENEC) $(O)/modrt
	REAL=$(REAL) sh tests/scenec/hashes.sh $(SCENEC) $(O)/modrt $(O)/scenec-run
	CC="$(CC)" CFLAGS="$(CFLAGS_ALL)" sh tests/scenec/effects.sh $(O)

# ---- fuzzing: libFuzzer where clang has it, else a deterministic mutation loop ----
SCN_FUZZ_SRCS = tests/scenec/fuzz_scenec.c $(SCN_LIB_SRCS) $(RT_SRCS) \
                $(filter-out models/scenes/%,$(wildcard models/*.c))
SCN_FUZZ_FLAGS = -std=c11 -O1 -g -ffp-contract=off -fno-math-errno $(CINC) -I$(SCN_DIR)
build/fuzz/scenec-fuzz: $(SCN_FUZZ_SRCS) tests/scenec/fuzz_main.c $(wildcard $(SCN_DIR)/*.h)
	@mkdir -p $(dir $@)
	@if echo 'int LLVMFuzzerTestOneInput(const char*d,long n){(void)d;(void)n;return 0;}' | \
	    clang -x c -fsanitize=fuzzer - -o build/fuzz/probe 2>/dev/null; then \
	  echo "fuzz: libFuzzer (clang -fsanitize=fuzzer,address,undefined)"; \
	  JOBS=$(JOBS) sh tools/dev/cc_par.sh $@ "clang $(SCN_FUZZ_FLAGS) \
	    -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all" "" $(SCN_FUZZ_SRCS); \
	else \
	  echo "fuzz: no libFuzzer; the mutation loop of tests/scenec/fuzz_main.c with ASan+UBSan"; \
	  $(CC) $(SCN_FUZZ_FLAGS) -fsanitize=address,undefined -fno-sanitize-recover=all \
	    $(SCN_FUZZ_SRCS) tests/scenec/fuzz_main.c -o $@; \
	fi
fuzz: deps build/fuzz/scenec-fuzz
	FUZZ_SEED=0 sh tests/scenec/fuzz.sh build/fuzz/scenec-fuzz $(FUZZ_TIME)
fuzz-short: build/fuzz/scenec-fuzz
	sh tests/scenec/fuzz.sh build/fuzz/scenec-fuzz 10
