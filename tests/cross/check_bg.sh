#!/bin/sh
# check_bg.sh - the background set preempted for real on a cross target: the timer-paced
# image (ports/common/image_main.c built with CROSS_BG_DEFS) must give the hash of
# `modrt run pendulum10_actuated` over the same ticks, with no overrun, no late step and
# at least one step preempted by a tick. Usage: sh tests/cross/check_bg.sh RUN ELF MODRT
# TICKS TARGET
set -u
run=$1 elf=$2 modrt=$3 ticks=$4 t=$5
log=${elf%.elf}.log
$run "$elf" > "$log" 2>&1 || { cat "$log"; echo "cross-test $t: background run failed"; exit 1; }
want=$($modrt run pendulum10_actuated --t-end "$(awk -v n="$ticks" 'BEGIN { print n / 1000 }')" |
       sed -n 's/^hash: //p')
got=$(sed -n 's/.* hash \([0-9a-f]*\).*/\1/p' "$log")
pre=$(sed -n 's/.* preempted \([0-9]*\).*/\1/p' "$log")
if [ "$got" != "$want" ] || ! grep -q ' overruns 0 .* late 0 ' "$log" || [ "${pre:-0}" -eq 0 ]; then
    cat "$log"
    echo "cross-test $t: background set in PendSV: hash $got, host $want (or overruns, late steps, no preemption)"
    exit 1
fi
echo "cross-test $t: background set in PendSV, preempted by SysTick: $(sed 's/^rt scene //' "$log")"
