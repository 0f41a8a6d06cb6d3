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
# context (foot_bg_begin() to foot_bg_end(), one interval per step). Each double row's
# image is built again with -DRT_SCENE_CODE=0: a third table sets the scene's written-out
# code (rt_scene_code) against the table-driven path, flash and instructions per tick.
# Usage: [FOOT_SCENES="a b"] [FOOT_CODE_TARGETS="m7"] sh tools/dev/footprint.sh \
#        "m3 m4f m7 rv32 rv64" ["m4f m7"]
set -eu
targets=$1
float_targets=${2:-}
M=build/host/modrt
MF=build/host-float/modrt
so=$(make -s print-INSN_COUNT_SO)
scenes=${FOOT_SCENES:-$($M list | awk '{print $1}')}

# the commit measured; dirty when a file other than the one being written differs from it
# (the redirection into docs/footprint.md has already emptied that one)
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
git diff --quiet HEAD -- . ':(exclude)docs/footprint.md' 2>/dev/null || commit="$commit-dirty"
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
CODE_ROWS=
# the targets whose double rows are measured again on the table-driven path
CODE_TARGETS=${FOOT_CODE_TARGETS-$targets} # (set empty: none)
# the same image built with -DRT_SCENE_CODE=0, beside the row foot_measure just measured
# (flash, stats, hash of the written-out code): a row of the second table
code_row() {
    f1=$flash st1=$stats h1=$hash max1=$max # (the caller's row is printed)
    FOOT_CFLAGS=-DRT_SCENE_CODE=0
    foot_measure "$2" "$1" double
    FOOT_CFLAGS=
    CODE_ROWS="$CODE_ROWS$(echo "$st1|$stats" | awk -F'|' -v s="$1" -v t="$2" -v f1="$f1" \
        -v f0="$flash" -v eq="$( [ "$h1" = "$hash" ] && echo yes || echo no)" '{
        r = ($5 > 0) ? $2 / $5 : 0; q = ($6 > 0) ? $3 / $6 : 0
        printf "| %s | %s | %d | %d | %.2f | %d | %d | %.2f | %d | %d | %.2f | %s |", s, t,
               f1, f0, (f0 > 0 ? f1 / f0 : 0), $2, $5, r, $3, $6, q, eq }')
"
    flash=$f1 stats=$st1 hash=$h1 max=$max1
}

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
    # last: it builds the scene's image again (the same file)
    case "$real: $CODE_TARGETS " in double:*" $t "*) code_row "$s" "$t";; esac
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

# the written-out code against the table-driven path, double
if [ -n "$CODE_ROWS" ]; then
    cat <<HDR

The library scenes run the code \`scenec\` wrote out for them (\`rt_scene_code\`,
docs/overhead.md): the images above. The same images built with \`-DRT_SCENE_CODE=0\` run
the table-driven path; double, each ratio written out over table-driven (a scene the
generator writes nothing out for has the same image both ways):

| scene | target | flash, written out | flash, table-driven | ratio | insn/tick median, written out | table-driven | ratio | max, written out | table-driven | ratio | hashes equal |
|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|:-:|
HDR
    printf '%s' "$CODE_ROWS"
fi

[ -z "$BG_ROWS" ] && exit 0
cat <<HDR

Background context of the scenes with a background set: per step of that set, the
instructions between \`foot_bg_begin()\` and \`foot_bg_end()\` (the step and its outputs,
run in PendSV on Cortex-M), and the tick context's slowest tick over its median (from the
first table): with the slow set's step out of the tick, what remains is the fast sets'
own variation (ROS2's Jacobian refresh every 64 steps, spread over the steps before it: one
column or one elimination stage a step) and the release and publication.

| scene | target | real | tick context max/median | background steps | insn/step min | median | max |
|---|---|---|---:|---:|---:|---:|---:|
HDR
printf '%s' "$BG_ROWS"
