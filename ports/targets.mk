# targets.mk - cross targets of modrt: compiler, flags, port sources, QEMU command, size
# tool and availability check per target. Included by the top-level Makefile; defines
# variables (and one helper function) only, no rules.
#
# Per target t in $(CROSS_TARGETS):
#   TARGET_CC_t         compiler driver
#   TARGET_CFLAGS_t     TARGET_ARCH_t, plus -ffreestanding on bare metal (added to the common flags:
#                       -std=c11 -Wall -Wextra -Werror -ffp-contract=off -fno-math-errno -O2
#                       -ffunction-sections -fdata-sections); also used for .S files
#   TARGET_ARCH_t       the architecture part of TARGET_CFLAGS_t (also in TARGET_LDFLAGS_t:
#                       gcc picks libgcc's multilib from these flags at link time)
#   TARGET_LDFLAGS_t    link flags. They contain -lgcc: put them AFTER the objects on the
#                       link line ($(CC) ... $(OBJS) $(TARGET_LDFLAGS_t) -o app.elf)
#   TARGET_PORT_SRCS_t  the port's sources (.c and .S)
#   TARGET_RUN_t        command prefix that runs an ELF: $(TARGET_RUN_t) app.elf
#                       (bare metal: ends in -kernel; the ELF's exit status is QEMU's)
#   TARGET_SIZE_t       size tool;  TARGET_NM_t  nm tool
#   TARGET_CHECK_t      availability check (exit 0 when toolchain and emulator exist)
#   TARGET_VTIME_t      1 where time is virtual and deterministic (bare metal under
#                       -icount): a timer-paced run there must have no overruns
# TARGET_QEMU_EXTRA is spliced into every TARGET_RUN_t before the ELF, e.g. for the
# instruction-count plugin:  TARGET_QEMU_EXTRA='$(call insn_count_opts,m3,app.elf)'.
#
# Every bare-metal run uses -icount shift=0,sleep=off: one instruction = 1 ns of virtual
# time, and idle (WFI) jumps to the next timer deadline, so port_cycles() and tick
# timing are repeatable run to run. See ports/cortex-m/port.c and ports/riscv/port.c.

# QEMU_TIMEOUT bounds every emulated run (seconds): a guard against QEMU itself hanging,
# not a speed bound. The test images are bounded by their work instead (an instruction
# budget each, tests/cross/run.sh); the longest one, a quarter of the rv32 unit tests,
# takes well under a minute on an idle machine.
QEMU_TIMEOUT ?= 900

# Directory of this fragment ("ports" when included as ports/targets.mk).
PORTS_DIR := $(patsubst %/,%,$(dir $(lastword $(MAKEFILE_LIST))))

CROSS_TARGETS := m3 m4f m7 rv32 rv64 aarch64

TARGET_QEMU_EXTRA ?=

# ------------------------------------------------------------------ Cortex-M (MPS2)

# softfloat.c: correctly rounded binary64 helpers replacing libgcc's (whose ARM
# __aeabi_dadd/dsub mis-round some cancellations); empty where the FPU does doubles (M7)
CM_PORT_SRCS := $(PORTS_DIR)/cortex-m/startup.c $(PORTS_DIR)/cortex-m/port.c \
                $(PORTS_DIR)/common/libc_min.c $(PORTS_DIR)/common/softfloat.c
CM_LDFLAGS := -T$(PORTS_DIR)/cortex-m/link.ld -nostartfiles -nostdlib -Wl,--gc-sections -lgcc
CM_QEMU = timeout $(QEMU_TIMEOUT) qemu-system-arm -display none -monitor none -serial null \
          -chardev stdio,id=sh0 -semihosting-config enable=on,target=native,chardev=sh0 \
          -icount shift=0,sleep=off
CM_CHECK := command -v arm-none-eabi-gcc arm-none-eabi-size qemu-system-arm >/dev/null

TARGET_CC_m3        := arm-none-eabi-gcc
TARGET_ARCH_m3      := -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
TARGET_CFLAGS_m3    := $(TARGET_ARCH_m3) -ffreestanding
TARGET_LDFLAGS_m3   := $(TARGET_ARCH_m3) $(CM_LDFLAGS)
TARGET_PORT_SRCS_m3 := $(CM_PORT_SRCS)
TARGET_RUN_m3        = $(CM_QEMU) -M mps2-an385 $(TARGET_QEMU_EXTRA) -kernel
TARGET_SIZE_m3      := arm-none-eabi-size
TARGET_NM_m3        := arm-none-eabi-nm
TARGET_CHECK_m3     := $(CM_CHECK)
TARGET_VTIME_m3     := 1

TARGET_CC_m4f        := arm-none-eabi-gcc
TARGET_ARCH_m4f      := -mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard
TARGET_CFLAGS_m4f    := $(TARGET_ARCH_m4f) -ffreestanding
TARGET_LDFLAGS_m4f   := $(TARGET_ARCH_m4f) $(CM_LDFLAGS)
TARGET_PORT_SRCS_m4f := $(CM_PORT_SRCS)
TARGET_RUN_m4f        = $(CM_QEMU) -M mps2-an386 $(TARGET_QEMU_EXTRA) -kernel
TARGET_SIZE_m4f      := arm-none-eabi-size
TARGET_NM_m4f        := arm-none-eabi-nm
TARGET_CHECK_m4f     := $(CM_CHECK)
TARGET_VTIME_m4f     := 1

TARGET_CC_m7        := arm-none-eabi-gcc
TARGET_ARCH_m7      := -mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard
TARGET_CFLAGS_m7    := $(TARGET_ARCH_m7) -ffreestanding
TARGET_LDFLAGS_m7   := $(TARGET_ARCH_m7) $(CM_LDFLAGS)
TARGET_PORT_SRCS_m7 := $(CM_PORT_SRCS)
TARGET_RUN_m7        = $(CM_QEMU) -M mps2-an500 $(TARGET_QEMU_EXTRA) -kernel
TARGET_SIZE_m7      := arm-none-eabi-size
TARGET_NM_m7        := arm-none-eabi-nm
TARGET_CHECK_m7     := $(CM_CHECK)
TARGET_VTIME_m7     := 1

# ------------------------------------------------------------------ RISC-V (QEMU virt)

# libc_min.c (ports/common) is shared by the bare-metal ports: plain C, no architecture code.
RV_PORT_SRCS := $(PORTS_DIR)/riscv/start.S $(PORTS_DIR)/riscv/port.c \
                $(PORTS_DIR)/common/libc_min.c
RV_LDFLAGS := -T$(PORTS_DIR)/riscv/link.ld -nostartfiles -nostdlib -Wl,--gc-sections \
              -Wl,--no-warn-rwx-segments -lgcc
RV_QEMU_OPTS = -M virt -bios none -display none -monitor none -serial stdio \
               -icount shift=0,sleep=off
RV_CHECK := command -v riscv64-unknown-elf-gcc riscv64-unknown-elf-size >/dev/null

# rv32imac soft-float: -misa-spec=2.2 keeps CSR instructions in the base ISA (binutils
# 2.40 wants _zicsr otherwise, and -march=rv32imac_zicsr selects no matching libgcc).
TARGET_CC_rv32        := riscv64-unknown-elf-gcc
TARGET_ARCH_rv32      := -misa-spec=2.2 -march=rv32imac -mabi=ilp32 -mcmodel=medlow
TARGET_CFLAGS_rv32    := $(TARGET_ARCH_rv32) -ffreestanding
TARGET_LDFLAGS_rv32   := $(TARGET_ARCH_rv32) $(RV_LDFLAGS)
TARGET_PORT_SRCS_rv32 := $(RV_PORT_SRCS)
TARGET_RUN_rv32        = timeout $(QEMU_TIMEOUT) qemu-system-riscv32 $(RV_QEMU_OPTS) $(TARGET_QEMU_EXTRA) -kernel
TARGET_SIZE_rv32      := riscv64-unknown-elf-size
TARGET_NM_rv32        := riscv64-unknown-elf-nm
TARGET_CHECK_rv32     := $(RV_CHECK) && command -v qemu-system-riscv32 >/dev/null
TARGET_VTIME_rv32     := 1

TARGET_CC_rv64        := riscv64-unknown-elf-gcc
TARGET_ARCH_rv64      := -march=rv64gc -mabi=lp64d -mcmodel=medany
TARGET_CFLAGS_rv64    := $(TARGET_ARCH_rv64) -ffreestanding
TARGET_LDFLAGS_rv64   := $(TARGET_ARCH_rv64) $(RV_LDFLAGS)
TARGET_PORT_SRCS_rv64 := $(RV_PORT_SRCS)
TARGET_RUN_rv64        = timeout $(QEMU_TIMEOUT) qemu-system-riscv64 $(RV_QEMU_OPTS) $(TARGET_QEMU_EXTRA) -kernel
TARGET_SIZE_rv64      := riscv64-unknown-elf-size
TARGET_NM_rv64        := riscv64-unknown-elf-nm
TARGET_CHECK_rv64     := $(RV_CHECK) && command -v qemu-system-riscv64 >/dev/null
TARGET_VTIME_rv64     := 1

# ------------------------------------------------------------------ AArch64 Linux (user mode)

# The POSIX port with glibc, linked static, run by qemu-aarch64 (the dynamic qemu-user
# binary: qemu-aarch64-static cannot load plugins). env -i: user-mode instruction counts
# depend on the size of the environment.
TARGET_CC_aarch64        := aarch64-linux-gnu-gcc
TARGET_ARCH_aarch64      :=
TARGET_CFLAGS_aarch64    :=
TARGET_LDFLAGS_aarch64   := -static -Wl,--gc-sections
TARGET_PORT_SRCS_aarch64 := $(PORTS_DIR)/posix/port.c $(PORTS_DIR)/posix/app_main.c
TARGET_RUN_aarch64        = timeout $(QEMU_TIMEOUT) env -i qemu-aarch64 $(TARGET_QEMU_EXTRA)
TARGET_SIZE_aarch64      := aarch64-linux-gnu-size
TARGET_NM_aarch64        := aarch64-linux-gnu-nm
TARGET_CHECK_aarch64     := command -v aarch64-linux-gnu-gcc aarch64-linux-gnu-size qemu-aarch64 >/dev/null
TARGET_VTIME_aarch64     := 0

# ------------------------------------------------------------------ instruction-count plugin

# Host-built TCG plugin (tools/dev/qemu/insn_count.c); build it with
#   $(INSN_COUNT_CC) $(INSN_COUNT_CFLAGS) -o $(INSN_COUNT_SO) $(INSN_COUNT_SRC)
INSN_COUNT_SRC    := tools/dev/qemu/insn_count.c
INSN_COUNT_SO     := build/host/libinsn_count.so
INSN_COUNT_CC     := gcc
INSN_COUNT_CFLAGS := -std=c11 -Wall -Wextra -Werror -O2 -shared -fPIC

# $(call insn_count_opts,<target>,<elf>): QEMU options that load the plugin with the
# marker on <elf>'s port_cycles, so it prints total instructions and min/median/max
# instructions between successive port_cycles() calls. Further plugin arguments go in
# INSN_COUNT_ARGS with a leading comma, e.g. INSN_COUNT_ARGS=,first=2,count=101,dump=on.
# Expanded when the recipe runs.
INSN_COUNT_ARGS ?=
insn_count_opts = -plugin $(abspath $(INSN_COUNT_SO)),addr=0x$(shell $(TARGET_NM_$(1)) $(2) | \
                  awk '$$3 == "port_cycles" { print $$1 }')$(INSN_COUNT_ARGS) -d plugin
