# fmi.mk - FMUs on the host (tools/fmi/, docs/fmi.md) and their tests (tests/fmi/).
# Included by the top-level Makefile after scenec.mk; uses its CC, CFLAGS_ALL, O, obj.
#
#   make test-fmi      the FMU suite: the test FMUs (FMI 2.0 and 3.0) built from
#                      tests/fmi/*.c, traces against closed forms, hashes against
#                      scene-language equivalents, the bad-FMU corpus, the reader fuzzer (short)
#   make fuzz-fmi      the modelDescription.xml fuzzer for FUZZ_TIME seconds

FMI_DIR   := tools/fmi
FMI_SRCS  := $(addprefix $(FMI_DIR)/,fmu_md.c fmu_zip.c fmu_model.c fmu_build.c fmu_call.c \
               fmu_inst.c fmu_state.c fmu_info.c fmu_scn.c fmu_emit.c)
FMI_LIBS  := -lzip -lexpat -ldl
FMI_TDIR  := $(O)/fmi
$(call obj,$(FMI_SRCS)): CINC += -I$(FMI_DIR) -I$(SCN_DIR)
$(call obj,tools/modrt/modrt.c tools/modrt/cli.c tools/modrt/check.c): CINC += -I$(FMI_DIR)
# scenec loads FMU systems too (their C for an image, tools/fmi/fmu_emit.c)
ifeq ($(O),build/host)
$(SCENEC): $(call obj,$(FMI_SRCS))
endif
# the exporter (linked into scenec) finds the sources an exported FMU is built from here
$(call obj,$(SCN_DIR)/scenec.c): CINC += -I$(FMI_DIR) -I$(SCN_DIR)
$(call obj,$(FMI_DIR)/fmu_export.c): CINC += -I$(FMI_DIR) -I$(FMI_DIR)/cs -I$(SCN_DIR)
$(call obj,$(FMI_DIR)/fmu_export.c $(FMI_DIR)/fmu_build.c): CDEFS += -DMODRT_SRC_DIR='"$(CURDIR)"'

# ---- the test FMUs: one C file per model, built for each FMI version ----
FMI_MODELS := $(basename $(notdir $(wildcard tests/fmi/models/*.c)))
FMI_TEST_FMUS := $(foreach v,2 3,$(foreach m,$(FMI_MODELS),$(FMI_TDIR)/fmu/$(m)$(v).fmu))

# an FMU: the shared library under its platform's directory, its description at the root
$(FMI_TDIR)/fmu/%2.fmu: tests/fmi/models/%.c tests/fmi/models/%.json tests/fmi/fmi_model.h tests/fmi/fmi_glue.c \
                        tests/fmi/mkfmu.py $(FMI_DIR)/fmi_api.h
	@mkdir -p $(dir $@)
	$(Q)python3 tests/fmi/mkfmu.py --cc "$(CC)" --version 2 --model $* --out $@ \
	  --cflags "-std=c11 -Wall -Wextra -Werror -O2 -fPIC -shared -I$(FMI_DIR) -Itests/fmi"
$(FMI_TDIR)/fmu/%3.fmu: tests/fmi/models/%.c tests/fmi/models/%.json tests/fmi/fmi_model.h tests/fmi/fmi_glue.c \
                        tests/fmi/mkfmu.py $(FMI_DIR)/fmi_api.h
	@mkdir -p $(dir $@)
	$(Q)python3 tests/fmi/mkfmu.py --cc "$(CC)" --version 3 --model $* --out $@ \
	  --cflags "-std=c11 -Wall -Wextra -Werror -O2 -fPIC -shared -I$(FMI_DIR) -Itests/fmi"

fmi-fmus: $(FMI_TEST_FMUS)

# ---- the modelDescription.xml reader fuzzed: libFuzzer, else the mutation loop ----
FMI_FUZZ_SRCS = tests/fmi/fuzz_md.c $(FMI_DIR)/fmu_md.c
build/fuzz/fmi-md-fuzz: $(FMI_FUZZ_SRCS) $(FMI_DIR)/fmu_md.h tests/scenec/fuzz_main.c
	@mkdir -p $(dir $@)
	@if echo 'int LLVMFuzzerTestOneInput(const char*d,long n){(void)d;(void)n;return 0;}' | \
	    clang -x c -fsanitize=fuzzer - -o build/fuzz/probe 2>/dev/null; then \
	  clang -std=c11 -O1 -g -I$(FMI_DIR) -fsanitize=fuzzer,address,undefined \
	    -fno-sanitize-recover=all $(FMI_FUZZ_SRCS) -lexpat -o $@; \
	else \
	  $(CC) -std=c11 -O1 -g -I$(FMI_DIR) -fsanitize=address,undefined -fno-sanitize-recover=all \
	    $(FMI_FUZZ_SRCS) tests/scenec/fuzz_main.c -lexpat -o $@; \
	fi
fuzz-fmi: build/fuzz/fmi-md-fuzz fmi-fmus
	FUZZ_SEED=0 sh tests/fmi/fuzz.sh build/fuzz/fmi-md-fuzz $(FUZZ_TIME) $(FMI_TDIR)

test-fmi: all fmi-fmus build/fuzz/fmi-md-fuzz $(FMI_TDIR)/master $(FMI_TDIR)/snap $(FMI_TDIR)/setp
	sh tests/fmi/run.sh $(O) $(FMI_TDIR)
	sh tests/fmi/link.sh $(O) $(FMI_TDIR)
	sh tests/fmi/fuzz.sh build/fuzz/fmi-md-fuzz 10 $(FMI_TDIR)

.PHONY: fmi-fmus fuzz-fmi test-fmi

# the foreign master of exported Co-Simulation FMUs (tests/fmi/master.c)
$(FMI_TDIR)/master: tests/fmi/master.c $(FMI_DIR)/fmu_md.c $(FMI_DIR)/fmu_md.h $(FMI_DIR)/fmi_api.h
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CSTD) -O2 -I$(FMI_DIR) tests/fmi/master.c $(FMI_DIR)/fmu_md.c -lexpat -ldl -lm -o $@

# snapshots of runs with FMU blocks (tests/fmi/snap.c): the scene compiler's host library,
# the FMU loader and the runtime, as modrt links them
$(FMI_TDIR)/snap: $(call obj,tests/fmi/snap.c $(FMI_SRCS)) $(SCN_LIB_OBJS) $(RT_OBJS) $(SCN_MODEL_OBJS)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(LDSAN) $^ $(FMI_LIBS) -lm -o $@
$(call obj,tests/fmi/snap.c): CINC += -I$(FMI_DIR) -I$(SCN_DIR)

# parameters written during a run with FMU blocks (tests/fmi/setp.c), linked as snap is
$(FMI_TDIR)/setp: $(call obj,tests/fmi/setp.c $(FMI_SRCS)) $(SCN_LIB_OBJS) $(RT_OBJS) $(SCN_MODEL_OBJS)
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(LDSAN) $^ $(FMI_LIBS) -lm -o $@
$(call obj,tests/fmi/setp.c): CINC += -I$(FMI_DIR) -I$(SCN_DIR)
