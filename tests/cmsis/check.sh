#!/bin/sh
# check.sh - the board-neutral Cortex-M port (ports/cmsis) built the way docs/porting.md
# tells a firmware engineer to build it, by hand without `make image`, for a Cortex-M3
# (soft float, softfloat.c) and a Cortex-M4F, and run under QEMU (mps2 boards, whose
# memory map tests/cmsis/memory.ld gives in place of the board's): the image's trace hash
# must equal the host's `modrt run` of the same scene. QEMU does not model the DWT, so
# the cycle counter reads 0 there; SysTick paces the ticks.
# shellcheck disable=SC2010,SC2086 # the file and flag lists are meant to split
set -u
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL cmsis: $*"; }
command -v arm-none-eabi-gcc qemu-system-arm >/dev/null || { echo "cmsis: no arm toolchain or QEMU (sh tools/install-deps.sh)"; exit 1; }
out=build/cmsis
mkdir -p $out
scene=models/scenes/pi_loop.scn
want=$(build/host/modrt run $scene | sed -n 's/^hash: //p')

# -- the commands of docs/porting.md, "A board-neutral port", with the mps2 memory map --
build/host/scenec -o $out/scene.c $scene
SIZES=$(build/host/scenec --sizes $scene)
SYM=$(sed -n 's/^const rt_scene \(mdl_scene_[A-Za-z0-9_]*\) = {$/\1/p' $out/scene.c)
RT=$(ls rt/*.c | grep -v registry.c)
MODELS=$(ls models/*.c | grep -v registry.c)
for cpu in "m3:-mcpu=cortex-m3 -mthumb -mfloat-abi=soft:mps2-an385" \
           "m4f:-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard:mps2-an386"; do
    t=${cpu%%:*} rest=${cpu#*:}; CPU=${rest%%:*} board=${rest#*:}
    if arm-none-eabi-gcc $CPU -std=c11 -O2 -ffreestanding -ffunction-sections -fdata-sections \
        -ffp-contract=off -fno-math-errno -Irt -Imodels -Iports \
        -DRT_KIND_DOCS=0 $SIZES -DRT_SCENE=$SYM -DPORT_CORE_HZ=25000000 \
        ports/common/image_main.c $out/scene.c $RT $MODELS \
        ports/cortex-m/startup.c ports/cmsis/port.c ports/common/libc_min.c ports/common/softfloat.c \
        -Ltests/cmsis -Lports/cmsis -Tports/cmsis/link.ld -nostartfiles -nostdlib -Wl,--gc-sections -lgcc \
        -o $out/pi_loop-$t.elf; then ok; else bad "$t: the documented build failed"; continue; fi
    got=$(timeout 120 qemu-system-arm -M $board -display none -monitor none -serial null \
              -semihosting-config enable=on,target=native -icount shift=0,sleep=off \
              -kernel $out/pi_loop-$t.elf 2>&1 | sed -n 's/^rt scene .* hash \([0-9a-f]*\) status ok$/\1/p')
    if [ -n "$want" ] && [ "$got" = "$want" ]; then ok; echo "cmsis: $t pi_loop: hash $got = host"
    else bad "$t: image hash '$got', host '$want'"; fi
done
# the board's numbers alone: ports/cmsis/memory.ld (an STM32F407) links at 0x08000000
if arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard -std=c11 -O2 \
    -ffreestanding -ffunction-sections -fdata-sections -ffp-contract=off -fno-math-errno \
    -Irt -Imodels -Iports -DRT_KIND_DOCS=0 $SIZES -DRT_SCENE=$SYM -DPORT_CORE_HZ=168000000 \
    -DPORT_CONSOLE_SEMIHOST=0 ports/common/image_main.c $out/scene.c $RT $MODELS \
    ports/cortex-m/startup.c ports/cmsis/port.c ports/common/libc_min.c ports/common/softfloat.c \
    -Lports/cmsis -Tports/cmsis/link.ld -nostartfiles -nostdlib -Wl,--gc-sections -lgcc \
    -o $out/pi_loop-stm32f4.elf &&
   arm-none-eabi-nm $out/pi_loop-stm32f4.elf | grep -q '^08000000 .* cm_vector_table$' &&
   [ "$(arm-none-eabi-objdump -d $out/pi_loop-stm32f4.elf | grep -c bkpt)" = 0 ]; then ok
else bad "the STM32F407 link (vector table at 0x08000000, no semihosting) failed"; fi
# without PORT_CORE_HZ the port says what is missing
if arm-none-eabi-gcc -mcpu=cortex-m3 -mthumb -Iports -c ports/cmsis/port.c -o /dev/null 2>&1 |
   grep -q "define PORT_CORE_HZ"; then ok; else bad "no error without PORT_CORE_HZ"; fi
echo "cmsis: $pass passed, $fail failed"
[ $fail -eq 0 ]
