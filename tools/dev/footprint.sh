#!/bin/sh
# footprint.sh - builds one image per library scene and target (only that scene, only its
# models, limits sized by `modrt sizes`), runs it under QEMU with the instruction-count
# plugin, and prints docs/footprint.md: flash and RAM (from the size tool), the stack
# high-water mark of the ticks (painted stack), instructions per tick (min/median/max over
# every tick, deterministic under -icount), the models linked, and the trace hash checked
# against the host's; then the slowest tick in microseconds at a stated clock and whether
# it fits the scene's own base tick; rows in binary32 (REAL=float) for the targets with a
# single-precision FPU, hashed against the host's float build. A scene with a background
# set (rt/bg.c) runs its steps between ticks (PendSV on Cortex-M): the tick context is
# counted from port_cycles() to foot_tick_end(), and a second table gives the background
# context (foot_bg_begin() to foot_bg_end(), one interval per step).
# Usage: [FOOT_SCENES="a b"] sh tools/dev/footprint.sh "m3 m4f m7 rv32 rv64" ["m4f m7"]
set -eu
targets=$1
float_targets=${2:-}
M=build/host/modrt
MF=build/host-float/modrt
so=$(make -s print-INSN_COUNT_SO)
scenes=${FOOT_SCENES:-$($M list | awk '{print $1}')}

commit=$(git describe --always --dirty 2>/dev/null || echo unknown)
cat <<HDR
# Footprint and cost per tick

Figures of commit \`$commit\`: a later change to the runtime, the models or the scenes
may move them until \`make footprint\` runs again.

Written by \`make footprint\` (tools/dev/footprint.sh); do not edit by hand. One image per
scene and target: \`tests/cross/footprint_main.c\`, the scene's const tables, the runtime
and only the models the scene names (\`-ffunction-sections -fdata-sections
-Wl,--gc-sections\`, no registries), compiled with the exact limits \`modrt sizes SCENE\`
prints. Instruction counts come from QEMU's TCG plugin \`tools/dev/qemu/insn_count.c\`,
counting guest instructions from the \`port_cycles()\` call the image makes before each
tick to the \`foot_tick_end()\` call after it: one interval is one \`rt_tick\` plus
recording the traced values into the hash (the tick context). Counts are deterministic (run under \`-icount shift=0\`). The stack column is the
high-water mark of the painted stack during the ticks (init excluded), measured, not a
static bound. Each image runs the first FOOT_TICKS ticks of its scene (default 1000, or
the whole scene if shorter); the host hash is taken over the same ticks. Flash = text + data, RAM = data + bss (static, the whole \`rt_sim\`), both in
bytes. Every image's trace hash is compared with \`modrt run\` on the host (the float rows
with the host's REAL=float build). The last two columns turn the slowest tick into time at
one instruction per cycle at a typical clock of each core (Cortex-M3 72 MHz, M4F 168 MHz,
M7 600 MHz, RV32 100 MHz, RV64 1 GHz: our assumption, not a measurement; flash wait
states make M3/M4F slower than that) and say whether it fits the scene's own base tick.
A scene with a background set (\`docs/multirate.md\`, "Background sets") steps that set
between ticks, in PendSV on Cortex-M (called from the image's loop elsewhere), with a
second \`rt_sim\` as its context (counted in RAM): the table counts its tick context only,
and the table after it the background context.

| scene | target | real | flash | RAM | stack | insn/tick min | median | max | hash = host | models linked | slowest tick [us] | fits its tick |
|---|---|---|---:|---:|---:|---:|---:|---:|:-:|---|---:|:-:|
HDR

. tools/foot_lib.sh

BG_ROWS=
# one row: scene, target, real (double|float), host hash, base tick [s]
row() {
    s=$1 t=$2 real=$3 want=$4 dt=$5 # sh has no locals: names the caller does not use
    foot_measure "$t" "$s" "$real"
    same=no
    [ "$hash" = "$want" ] && same=yes
    time=$(awk -v n="${max:-0}" -v f="$(mhz "$t")" -v dt="$dt" 'BEGIN {
        us = n / f; printf "%.1f | %s", us, (n > 0 && us <= dt * 1e6) ? "yes" : "no" }')
    echo "| $s | $t | $real | $flash | $ram | $stack | $stats | $same | $models | $time |"
    if $M info "$s" | grep -q '^ *background:'; then
        bg=$(foot_count "$fm_elf" "$t" foot_bg_begin foot_bg_end | \
             sed -n 's/.*intervals \([0-9]*\) min \([0-9]*\) median \([0-9]*\) max \([0-9]*\).*/\1 | \2 | \3 | \4/p')
        ratio=$(echo "$stats" | awk -F'|' '{ printf "%.2f", ($2 > 0 ? $3 / $2 : 0) }')
        BG_ROWS="$BG_ROWS| $s | $t | $real | $ratio | $bg |
"
    fi
}

for s in $scenes; do
    # the host reference over the same ticks as the image
    dt=$($M info "$s" | sed -n 's/^base tick: \([^ ]*\) s$/\1/p')
    ticks=$(make -s print-FOOT_TICKS)
    t_end=$(awk -v d="$dt" -v n="$ticks" 'BEGIN { printf "%.17g", d * n }')
    host=$($M run "$s" --t-end "$t_end" | sed -n 's/^hash: //p')
    hostf=
    [ -z "$float_targets" ] || hostf=$($MF run "$s" --t-end "$t_end" | sed -n 's/^hash: //p')
    for t in $targets; do
        if ! make -s "check-target-$t" 2>/dev/null; then
            echo "| $s | $t | | skipped: toolchain or QEMU missing | | | | | | | | | |"
            continue
        fi
        row "$s" "$t" double "$host" "$dt"
        case " $float_targets " in *" $t "*) row "$s" "$t" float "$hostf" "$dt";; esac
    done
done

# the written-out code against the table-driven path, one target, double
CODE_TARGET=m7
if make -s "check-target-$CODE_TARGET" 2>/dev/null; then
    cat <<HDR

The library scenes run the code \`scenec\` wrote out for them (\`rt_scene_code\`,
docs/overhead.md). The same images built with \`-DRT_SCENE_CODE=0\` run the table-driven
path; on $CODE_TARGET, double:

| scene | flash, written out | flash, table-driven | insn/tick median, written out | table-driven | max, written out | table-driven | hashes equal |
|---|---:|---:|---:|---:|---:|---:|:-:|
HDR
    for s in $scenes; do
        foot_measure "$CODE_TARGET" "$s" double
        f1=$flash st1=$stats h1=$hash
        FOOT_CFLAGS=-DRT_SCENE_CODE=0
        foot_measure "$CODE_TARGET" "$s" double
        FOOT_CFLAGS=
        echo "$st1|$stats" | awk -F'|' -v s="$s" -v f1="$f1" -v f0="$flash" -v eq="$( [ "$h1" = "$hash" ] && echo yes || echo no)" '{
            printf "| %s | %d | %d | %d | %d | %d | %d | %s |\n", s, f1, f0, $2, $5, $3, $6, eq }'
    done
fi

[ -z "$BG_ROWS" ] && exit 0
cat <<HDR

Background context of the scenes with a background set: per step of that set, the
instructions between \`foot_bg_begin()\` and \`foot_bg_end()\` (the step and its outputs,
run in PendSV on Cortex-M), and the tick context's slowest tick over its median (from the
table above): with the slow set's step out of the tick, what remains is the fast sets'
own variation (ROS2's Jacobian refresh every 64 steps, spread over the steps before it: one
column or one elimination stage a step) and the release and publication.

| scene | target | real | tick context max/median | background steps | insn/step min | median | max |
|---|---|---|---:|---:|---:|---:|---:|
HDR
printf '%s' "$BG_ROWS"
