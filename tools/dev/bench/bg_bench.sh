#!/bin/sh
# bg_bench.sh - bounded work per tick and footprint (issue 14): the scene's per-scene image
# on the Cortex-M7 under QEMU (the footprint image, deterministic counts): its flash, RAM
# and stack, and its instructions per tick in the tick context (port_cycles() to
# foot_tick_end(): the tick interrupt's work) and in the background context (each step of
# the background set, run in PendSV), with the max/median of each; appended to
# build/bench/bg.txt. Skipped when the M7 toolchain or QEMU is missing.
# Usage: sh tools/dev/bench/bg_bench.sh [SCENE] [TARGET]
set -u
S=${1:-pendulum10_actuated}
T=${2:-m7}
O=build/bench
mkdir -p $O
if ! make -s "check-target-$T" 2>/dev/null; then
    echo "bench: $S on $T skipped (toolchain or QEMU missing)" | tee -a $O/bg.txt
    exit 0
fi
make -s build/host/libinsn_count.so
out=$(FOOT_SCENES=$S sh tools/dev/footprint.sh "$T")
# the scene's row of each table: flash | RAM | stack and the tick context's min | median |
# max, then the background table's max/median | steps | min | median | max
tick=$(echo "$out" | awk -F' [|] ' -v s="$S" '$1 == "| " s && NF > 10 {print $7, $8, $9; exit}')
mem=$(echo "$out" | awk -F' [|] ' -v s="$S" '$1 == "| " s && NF > 10 {print $4, $5, $6; exit}')
bg=$(echo "$out" | awk -F' [|] ' -v s="$S" '$1 == "| " s && NF < 10 {print $5, $6, $7, $8; exit}')
{
    set -- $mem
    echo "== $S on $T (QEMU, instructions, first 1000 ticks)"
    echo "footprint: flash $1 B, RAM $2 B, stack $3 B"
    set -- $tick
    awk -v a="$1" -v b="$2" -v c="$3" 'BEGIN { printf "tick context: per tick min %d median %d max %d, max/median %.2f\n", a, b, c, c / b }'
    if [ -n "$bg" ]; then
        set -- $bg
        awk -v n="$1" -v a="$2" -v b="$3" -v c="$4" 'BEGIN { printf "background context: %d steps, per step min %d median %d max %d, max/median %.2f\n", n, a, b, c, c / b }'
    else
        echo "background context: none (the scene has no background set)"
    fi
} | tee -a $O/bg.txt
