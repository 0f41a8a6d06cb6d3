# study.mk - `make study`: what accuracy costs in time, over the four paper examples, on the
# host and on Cortex-M (tools/dev/study/study.py writes docs/study.md and docs/study/*.svg);
# `make test-study`: its quick subset (STUDY=quick), a test suite. Included by the Makefile.
#
# The cross images of the study link one generated scene against a library of the runtime
# and the models built once per target (the cross tests' objects: the default limits but
# CROSS_TEST_DEFS', which study.py compiles the scene with too; no per-scene sizes: a
# variant scene needs no rebuild of the runtime), the port's objects and the footprint
# application (tests/cross/footprint_main.c, which marks every tick for the counter).
STUDY_TARGETS := m4f m7
STUDY ?= full
STUDY_LIB_SRCS = tests/harness.c $(filter-out rt/registry.c,$(RT_SRCS)) \
                 $(filter-out models/registry.c build/gen/%,$(MODEL_SRCS))
define STUDY_LIB
build/study/lib/$(1)$(XSUF)/libstudy.a: $$(call cobj,$(1),$$(STUDY_LIB_SRCS))
	@mkdir -p $$(dir $$@)
	$(Q)rm -f $$@ && $$(patsubst %gcc,%ar,$$(TARGET_CC_$(1))) rcs $$@ $$^
build/study/lib/$(1)$(XSUF)/port.stamp: $$(call cobj,$(1),$$(TARGET_PORT_SRCS_$(1)))
	@mkdir -p $$(dir $$@)
	@echo $$^ > $$@
endef
$(foreach t,$(STUDY_TARGETS),$(eval $(call STUDY_LIB,$(t))))
STUDY_LIBS = $(foreach t,$(STUDY_TARGETS),build/study/lib/$(t)$(XSUF)/libstudy.a \
                                          build/study/lib/$(t)$(XSUF)/port.stamp)
study-libs: $(STUDY_LIBS)

# the host modrt in double and float, scenec, the counter plugin, the libraries in both
study-deps: deps build/host/modrt $(SCENEC) $(INSN_COUNT_SO)
	$(MAKE) --no-print-directory -j$(JOBS) REAL=float build/host-float/modrt
	$(MAKE) --no-print-directory -j$(JOBS) study-libs
	$(MAKE) --no-print-directory -j$(JOBS) REAL=float study-libs

study: study-deps
	python3 tools/dev/study/study.py --mode $(STUDY) --jobs $(JOBS)

TEST_SUITES += test-study
test-study: study-deps
	@python3 tools/dev/study/study.py --mode quick --jobs $(JOBS)
.PHONY: study study-deps study-libs test-study
