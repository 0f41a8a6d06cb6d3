#!/bin/sh
# effects.sh - what each effect of the lane change costs (issue 13): the full lane_change,
# one variant per omitted effect (tests/vehicles/variants/lcv_*.scn: linear tires instead
# of the Magic Formula, planar single-track cars instead of the suspended chassis, no
# drag, ideal steering instead of V2's steering chain, no second vehicle) and the minimal
# lane_change_planar. Each is built as a Cortex-M7 footprint image (tools/foot_lib.sh:
# only its scene and the models it names) and run over the whole scene under QEMU with the
# instruction-count plugin, and run on the host under callgrind (instructions, so
# deterministic and independent of the machine's load). Prints the "Effects of the lane
# change" section of docs/footprint.md (make effects splices it in; make footprint
# appends it).
# Usage: sh tools/dev/effects.sh [TARGET]   (default m7)
set -eu
t=${1:-m7}
M=build/host/modrt
so=$(make -s print-INSN_COUNT_SO)
V=tests/vehicles/variants
. tools/foot_lib.sh

commit=$(git describe --always --dirty 2>/dev/null || echo unknown)
cat <<HDR

## Effects of the lane change

Figures of commit \`$commit\`.

Written by \`make effects\` (tools/dev/effects.sh; \`make footprint\` runs it too); do not edit
by hand. Each row omits one effect of the full \`lane_change\` (the variants are
\`tests/vehicles/variants/*.scn\`, kept out of the library); the last row omits them all.
Every effect is its own block kind or service, so an omitted one is neither linked nor
evaluated: the models column lists the kinds in the image. Cortex-M7 ($t, double):
flash, RAM and instructions per tick over the whole scene (8000 ticks of 1 ms; the tick
context only: the vehicles' background steps run in PendSV, outside it; the max is the
busiest tick: in \`lane_change\` a part of the steering set's spread Jacobian refresh
at the vehicles' publication, in
\`lane_change_planar\` (whose 5 ms step runs in the background too) a publication; the slowest tick in
microseconds at $(mhz "$t") MHz and one instruction per cycle), counted as above, the trace hash checked
against the host's. Host: instructions per simulated second, \`valgrind --tool=callgrind
modrt run FILE.scn\` over the 8 s divided by 8 (x86-64, gcc -O2; includes reading the
scene file, under 1 %).

| variant | omits | flash | RAM | insn/tick median | max | slowest tick [us] | hash = host | host insn per simulated s | vs full | models linked |
|---|---|---:|---:|---:|---:|---:|:-:|---:|---:|---|
HDR

# variant, scene file, what it omits
rows="lane_change models/scenes/lane_change.scn nothing (the full model)
lcv_linear_tires $V/lcv_linear_tires.scn nonlinear tires (car3d: linear)
lcv_planar $V/lcv_planar.scn suspension (st_car_mf: planar chassis)
lcv_no_drag $V/lcv_no_drag.scn aerodynamic drag
lcv_ideal_steering $V/lcv_ideal_steering.scn actuator dynamics (ideal steering)
lcv_one_vehicle $V/lcv_one_vehicle.scn the second vehicle
lane_change_planar models/scenes/lane_change_planar.scn all of them (the minimal scene)"

full=
# the rows come on descriptor 3: make, QEMU and valgrind read standard input
while read -r s f omits <&3; do
    t_end=$($M info "$f" | sed -n 's/^end time: \([^ ]*\) s$/\1/p')
    ticks=$(awk -v e="$t_end" -v d="$($M info "$f" | sed -n 's/^base tick: \([^ ]*\) s$/\1/p')" \
            'BEGIN { printf "%d", e / d + 0.5 }')
    FOOT_TICKS=$ticks foot_measure "$t" "$s" double "$f"
    want=$($M run "$f" | sed -n 's/^hash: //p')
    same=no
    [ "$hash" = "$want" ] && same=yes
    ir=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null "$M" run "$f" 2>&1 >/dev/null |
         sed -n 's/.*Collected : *\([0-9]*\).*/\1/p')
    per_s=$(awk -v n="$ir" -v e="$t_end" 'BEGIN { printf "%.3g", n / e }')
    [ -n "$full" ] || full=$per_s
    rel=$(awk -v a="$per_s" -v b="$full" 'BEGIN { printf "%.2f", a / b }')
    med=$(echo "$stats" | awk -F' [|] ' '{print $2}')
    us=$(awk -v n="${max:-0}" -v f="$(mhz "$t")" 'BEGIN { printf "%.0f", n / f }')
    echo "| $s | $omits | $flash | $ram | $med | $max | $us | $same | $per_s | $rel | $models|"
done 3<<ROWS
$rows
ROWS
