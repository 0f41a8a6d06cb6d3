# link.mk - the controller link's suites (docs/link.md); included by the Makefile.
#   make test-link        end to end over loopback with the example controllers (tests/link/link.sh)
#   make link-fuzz        the datagram and replay-log decoders under libFuzzer for FUZZ_TIME s
#   make test-link-fuzz   the same for 5 s (CI)

LINK_FUZZ_SRCS = tests/link/fuzz_link.c ports/common/link_wire.c ports/common/link_hmac.c \
                 tools/modrt/mrlog.c \
                 $(filter-out rt/registry.c,$(RT_SRCS))
LINK_FUZZ_FLAGS = $(CSTD) -g -O1 -Irt -Iports -Itools/modrt

build/fuzz/link-fuzz: $(LINK_FUZZ_SRCS) tests/scenec/fuzz_main.c
	@mkdir -p $(dir $@)
	@if command -v clang >/dev/null && echo 'int LLVMFuzzerTestOneInput(){return 0;}' | \
	    clang -x c -fsanitize=fuzzer - -o build/fuzz/probe-link 2>/dev/null; then \
	  JOBS=$(JOBS) sh tools/dev/cc_par.sh $@ "clang $(LINK_FUZZ_FLAGS) \
	    -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all" "" $(LINK_FUZZ_SRCS); \
	else \
	  $(CC) $(LINK_FUZZ_FLAGS) -fsanitize=address,undefined -fno-sanitize-recover=all \
	    $(LINK_FUZZ_SRCS) tests/scenec/fuzz_main.c -o $@; \
	fi

# seeds: good and bad packets and logs written by the unit and end-to-end tests
link-fuzz-seeds: build/host/tests
	@mkdir -p build/fuzz/link-corpus
	@build/host/tests link_ > /dev/null 2>&1; \
	 for f in build/test-link-*.mrl build/test-link/*.mrl; do \
	   [ -f "$$f" ] && { printf '\000'; cat "$$f"; } > build/fuzz/link-corpus/$$(basename $$f); done; \
	 python3 tests/link/seed_packets.py build/fuzz/link-corpus

link-fuzz: deps build/fuzz/link-fuzz link-fuzz-seeds
	FUZZ_SEED=0 sh tests/link/fuzz.sh build/fuzz/link-fuzz $(FUZZ_TIME)
test-link-fuzz: build/fuzz/link-fuzz link-fuzz-seeds
	@sh tests/link/fuzz.sh build/fuzz/link-fuzz 5

# the C example controller (a host program: POSIX sockets and the freestanding codec)
build/host/pi_controller: tools/examples/pi_controller.c ports/common/link_wire.c \
                          ports/common/link_hmac.c ports/common/linkframe.c \
                          ports/common/linkclient.c tools/modrt/serial.c
	@mkdir -p $(dir $@)
	$(Q)$(CC) $(CSTD) -O2 -Iports -Itools/modrt $^ -o $@

test-link: deps-host build/host/modrt build/host/pi_controller
	@bash tests/link/link.sh

TEST_SUITES += test-link test-link-fuzz
.PHONY: link-fuzz link-fuzz-seeds test-link test-link-fuzz

# the scene fingerprint of the replay log reads the programs of interpreted defines and
# the FMU file of an FMU block (tools/fmi/fmu.h)
$(call obj,tools/modrt/fingerprint.c): CINC += -I$(SCN_DIR) -Itools/fmi

# the link over a serial line on ptys: lock-step, real time, line noise (tests/link/serial.sh)
test-serial: deps-host build/host/modrt build/host/pi_controller
	@sh tests/link/serial.sh
TEST_SUITES += test-serial
.PHONY: test-serial

# the PI controller as Cortex-M firmware (tools/examples/pi_firmware.c) and the plant image
# pi_link with its link on the UART, for the QEMU rigs (tests/link/serial_qemu.sh)
SERIAL_QEMU_T ?= m4f
PI_FW_SRCS = tools/examples/pi_firmware.c ports/common/linkclient.c ports/common/linkframe.c \
             ports/common/link_wire.c ports/common/link_hmac.c ports/cortex-m/uart.c \
             $(TARGET_PORT_SRCS_$(SERIAL_QEMU_T))
build/$(SERIAL_QEMU_T)/pi_firmware.elf: $(PI_FW_SRCS) $(wildcard ports/common/*.h ports/cortex-m/*.h)
	@mkdir -p $(dir $@)
	$(Q)$(TARGET_CC_$(SERIAL_QEMU_T)) $(filter-out -MMD -MP,$(CROSS_CFLAGS)) \
	  $(TARGET_CFLAGS_$(SERIAL_QEMU_T)) $(PI_FW_SRCS) $(TARGET_LDFLAGS_$(SERIAL_QEMU_T)) -o $@
test-serial-qemu: deps build/host/modrt build/host/pi_controller $(SCENEC)
	@if $(MAKE) --no-print-directory -s check-target-$(SERIAL_QEMU_T) 2>/dev/null; then \
	  $(MAKE) --no-print-directory build/$(SERIAL_QEMU_T)/pi_firmware.elf && \
	  sh tests/link/serial_qemu.sh $(SERIAL_QEMU_T); \
	else echo "serial-qemu: skipped: the $(SERIAL_QEMU_T) toolchain or QEMU is missing"; fi
TEST_SUITES += test-serial-qemu
.PHONY: test-serial-qemu

# the serial link's round trips next to UDP's (docs/link.md; part of make bench)
serial-bench: build/host/modrt build/host/pi_controller
	@$(MAKE) --no-print-directory -s check-target-$(SERIAL_QEMU_T) 2>/dev/null && \
	  $(MAKE) --no-print-directory build/$(SERIAL_QEMU_T)/pi_firmware.elf; \
	 sh tools/dev/bench/serial_bench.sh build/host/modrt
.PHONY: serial-bench

# the serial link's frame receiver and client library under the fuzzer (5 s in make test)
FRAME_FUZZ_SRCS = tests/link/fuzz_frame.c ports/common/linkframe.c ports/common/linkclient.c \
                  ports/common/link_wire.c ports/common/link_hmac.c
build/fuzz/frame-fuzz: $(FRAME_FUZZ_SRCS) tests/scenec/fuzz_main.c
	@mkdir -p $(dir $@)
	@if command -v clang >/dev/null && echo 'int LLVMFuzzerTestOneInput(){return 0;}' | \
	    clang -x c -fsanitize=fuzzer - -o build/fuzz/probe-frame 2>/dev/null; then \
	  clang $(LINK_FUZZ_FLAGS) -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
	    $(FRAME_FUZZ_SRCS) -o $@; \
	else \
	  $(CC) $(LINK_FUZZ_FLAGS) -fsanitize=address,undefined -fno-sanitize-recover=all \
	    $(FRAME_FUZZ_SRCS) tests/scenec/fuzz_main.c -o $@; \
	fi
# seeds: framed requests of pi_link, whole and cut, from the unit test's encoder
frame-fuzz-seeds:
	@mkdir -p build/fuzz/frame-corpus
	@python3 tests/link/seed_frames.py build/fuzz/frame-corpus
test-frame-fuzz: build/fuzz/frame-fuzz frame-fuzz-seeds
	@sh tests/link/fuzz.sh build/fuzz/frame-fuzz 5 build/fuzz/frame-corpus frame
TEST_SUITES += test-frame-fuzz
.PHONY: frame-fuzz-seeds test-frame-fuzz
