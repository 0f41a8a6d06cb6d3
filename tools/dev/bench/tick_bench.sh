#!/bin/sh
# tick_bench.sh - bounded ticks (issue 32, goal 5): every library scene's per-scene image on
# one target (default the Cortex-M7, double) under QEMU with the instruction-count plugin
# (tools/dev/footprint.sh, deterministic counts over the first FOOT_TICKS ticks), and its
# tick context's max/median (port_cycles() to foot_tick_end(): one rt_tick and recording;
# a background set's steps run outside it, in PendSV), against the bound 1.5. Prints a
# table and writes it to build/bench/ticks.md. Skipped when the toolchain or QEMU is
# missing. A benchmark, not a test: a scene above the bound is reported, not failed.
# Usage: sh tools/dev/bench/tick_bench.sh [TARGET]
set -u
T=${1:-m7}
O=build/bench
BOUND=1.5
mkdir -p $O
if ! make -s "check-target-$T" 2>/dev/null; then
    echo "bench: tick context max/median on $T skipped (toolchain or QEMU missing)" | tee $O/ticks.md
    exit 0
fi
make -s build/host/libinsn_count.so
out=$(sh tools/dev/footprint.sh "$T") || { echo "bench: footprint.sh failed on $T" >&2; exit 1; }
commit=$(git describe --always --dirty 2>/dev/null || echo unknown)
{
    echo "Tick context per scene on $T (double, first FOOT_TICKS ticks, instructions; commit \`$commit\`):"
    echo
    echo "| scene | median | max | max/median | <= $BOUND | hash = host |"
    echo "|---|---:|---:|---:|:-:|:-:|"
    # the rows of footprint.sh's first table: | scene | target | real | flash | RAM | stack |
    # min | median | max | hash = host | ...
    echo "$out" | awk -F' [|] ' -v t="$T" -v b="$BOUND" '$2 == t && $3 == "double" && NF > 10 {
        s = $1; sub(/^[|] /, "", s); r = $8 > 0 ? $9 / $8 : 0
        printf "| %s | %d | %d | %.2f | %s | %s |\n", s, $8, $9, r, r <= b ? "yes" : "no", $10 }'
} | tee $O/ticks.md
