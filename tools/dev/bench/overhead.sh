#!/bin/sh
# overhead.sh - modrt's overhead against hand-written programs of the same formulation and
# method: instructions per simulated second of each side counted by callgrind inside the
# run only (--toggle-collect on modrt_ticks, tight_steps, lane_tight_steps, mono_steps,
# amono_steps or amr_steps: start-up excluded), deterministic. Prints one line per scene
# and method,
#   overhead <scene> <method>: <modrt / tight program> (...)
# pendulum10 and lane_change_planar against their tight programs
# (tools/dev/bench/pendulum_tight.c, lane_tight.c) with and without modrt's error
# estimate, beside the old yardstick (the dense monolith,
# tools/dev/bench/pendulum_mono.c, with the estimate); pendulum10_actuated_single (ROS2) and
# the multirate pendulum10_actuated (bs3 chain in the background, ROS2 servo) against
# their monoliths, dense and Thomas. With a third argument DOC, the table is also
# written into DOC between its bench markers (docs/overhead.md).
# Usage: sh tools/dev/bench/overhead.sh build/host [SECONDS [DOC]]
set -eu
D=$1
S=${2:-1}
DOC=${3:-}
count() { # binary side method function -> instructions per simulated second
    f=$(mktemp)
    valgrind --tool=callgrind --callgrind-out-file=$f --toggle-collect="$4" \
        "$D/$1" count "$2" "$3" "$S" > /dev/null 2>&1
    n=$(sed -n 's/^summary: //p' "$f")
    rm -f "$f"
    echo $((n / S))
}
T=$(mktemp)
trap 'rm -f $T' EXIT
cat > $T <<'HDR'
| scene | method | modrt | tight program | modrt / tight | tight without estimate | modrt / that | old yardstick: dense monolith | modrt / that | modrt, table-driven path | that / tight |
|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|
HDR
for m in bs3 rk4 dopri5; do
    r=$(count tight_bench modrt $m modrt_ticks)
    g=$(count tight_bench modrt-tables $m modrt_ticks)
    t=$(count tight_bench tight $m tight_steps)
    n=$(count tight_bench tight-noest $m tight_steps)
    d=$(count overhead_bench mono $m mono_steps)
    awk -v m=$m -v r=$r -v t=$t -v n=$n -v d=$d -v g=$g -v T=$T 'BEGIN {
        printf "overhead pendulum10 %s: %.2f against the tight program (%.2f without the error estimate; the table-driven path %.2f); old yardstick, the dense monolith: %.2f\n", m, r / t, r / n, g / t, r / d
        printf "  instructions per simulated s: modrt %d, table-driven %d, tight %d, tight without estimate %d, dense monolith %d\n", r, g, t, n, d
        printf "| pendulum10 | %s | %d | %d | **%.2f** | %d | **%.2f** | %d | %.2f | %d | %.2f |\n", m, r, t, r / t, n, r / n, d, r / d, g, g / t >> T }'
done
r=$(count tight_bench lane-modrt rk4 modrt_ticks)
g=$(count tight_bench lane-modrt-tables rk4 modrt_ticks)
t=$(count tight_bench lane-tight rk4 lane_tight_steps)
n=$(count tight_bench lane-tight-noest rk4 lane_tight_steps)
awk -v r=$r -v g=$g -v t=$t -v n=$n -v T=$T 'BEGIN {
    printf "overhead lane_change_planar rk4: %.2f against the tight program (%.2f without the error estimate; the table-driven path %.2f)\n", r / t, r / n, g / t
    printf "  instructions per simulated s: modrt %d, table-driven %d, tight %d, tight without estimate %d\n", r, g, t, n
    printf "| lane_change_planar | rk4 5 ms (base tick 1 ms) | %d | %d | **%.2f** | %d | **%.2f** | - | - | %d | %.2f |\n", r, t, r / t, n, r / n, g, g / t >> T }'
r=$(count overhead_bench modrt ros2 modrt_ticks)
d=$(count overhead_bench mono ros2 amono_steps)
t=$(count overhead_bench thomas ros2 amono_steps)
awk -v r=$r -v d=$d -v t=$t -v T=$T 'BEGIN {
    printf "overhead pendulum10_actuated_single ros2: %.2f against the Thomas monolith; dense monolith: %.2f\n", r / t, r / d
    printf "  instructions per simulated s: modrt %d, Thomas monolith %d, dense monolith %d\n", r, t, d
    printf "| pendulum10_actuated_single | ros2 | %d | %d (Thomas monolith) | **%.2f** | - | - | %d | %.2f | - | - |\n", r, t, r / t, d, r / d >> T }'
r=$(count overhead_bench modrt bs3+ros2 modrt_ticks)
d=$(count overhead_bench mono bs3+ros2 amr_steps)
t=$(count overhead_bench tight bs3+ros2 amr_steps)
n=$(count overhead_bench tight-noest bs3+ros2 amr_steps)
awk -v r=$r -v d=$d -v n=$n -v t=$t -v T=$T 'BEGIN {
    printf "overhead pendulum10_actuated bs3+ros2: %.2f against the tight program (%.2f without the estimates); old yardstick, the dense monolith: %.2f\n", r / t, r / n, r / d
    printf "  instructions per simulated s: modrt %d, tight %d, tight without estimates %d, dense monolith %d\n", r, t, n, d
    printf "| pendulum10_actuated (multirate) | bs3 chain every 4 ms in the background, ros2 servo | %d | %d | **%.2f** | %d | **%.2f** | %d | %.2f | - | - |\n", r, t, r / t, n, r / n, d, r / d >> T }'
# where the instructions go (dopri5, inclusive costs): modrt's parts against the tight
# program's
prof() { # binary side function -> callgrind file
    f=$(mktemp)
    valgrind --tool=callgrind --callgrind-out-file=$f --toggle-collect="$3" \
        "$D/$1" count "$2" dopri5 "$S" > /dev/null 2>&1
    echo $f
}
fr=$(prof tight_bench modrt modrt_ticks)
ft=$(prof tight_bench tight tight_steps)
inc() { # callgrind file, function pattern -> inclusive instructions per simulated s
    callgrind_annotate --inclusive=yes "$1" 2>/dev/null |
        awk -v p="$2" -v s=$S '$0 ~ p { gsub(",", "", $1); print int($1 / s); exit }'
}
tot=$(sed -n 's/^summary: //p' $fr); tt=$(sed -n 's/^summary: //p' $ft)
rhs=$(inc $fr 'rt/eval.c:rti_rhs \['); prj=$(inc $fr 'mbs_project.c:rti_mbs_project \[')
erk=$(inc $fr 'integ_erk.c:erk_step \[')
trhs=$(inc $ft 'pendulum_tight.c:accel \['); tprj=$(inc $ft 'pendulum_tight.c:project \[')
tstp=$(inc $ft 'pendulum_tight.c:step_dopri5[^ ]* \[')
rm -f $fr $ft
awk -v S=$S -v tot=$tot -v tt=$tt -v rhs=$rhs -v prj=$prj -v erk=$erk -v trhs=$trhs \
    -v tprj=$tprj -v tstp=$tstp -v T=$T 'BEGIN {
    tot /= S; tt /= S; ev = 1400 * S / S; st = 200
    printf "\nWhere the instructions go, pendulum10 dopri5, per simulated second (200 steps, 1,400 right-hand sides, the estimate ones included):\n\n" >> T
    printf "| part | modrt | tight program | modrt / tight | modrt per evaluation or step | tight per evaluation or step |\n|---|--:|--:|--:|--:|--:|\n" >> T
    printf "| right-hand sides (outputs, assembly, Schur complement, multipliers) | %d | %d | %.1f | %d | %d |\n", rhs, trhs, rhs / trhs, rhs / ev, trhs / ev >> T
    printf "| projection (eq. 10) and its residual check | %d | %d | %.1f | %d | %d |\n", prj, tprj, prj / tprj, prj / st, tprj / st >> T
    s = erk - rhs; ts = tstp - trhs
    printf "| stage sums and error estimate | %d | %d | %.1f | %d | %d |\n", s, ts, s / ts, s / st, ts / st >> T
    r = tot - erk - prj; tr = tt - tstp - tprj
    printf "| the tick around them (schedule, step bookkeeping, outputs, hooks) | %d | %d | - | %d | %d |\n", r, tr, r / st, tr / st >> T
    printf "| total | %d | %d | %.2f | %d | %d |\n", tot, tt, tot / tt, tot / st, tt / st >> T
    printf "profile pendulum10 dopri5 per simulated s: right-hand sides modrt %d tight %d (%.1fx), projection %d / %d (%.1fx), stage sums and estimate %d / %d (%.1fx), the rest %d / %d\n", rhs, trhs, rhs / trhs, prj, tprj, prj / tprj, s, ts, s / ts, r, tr }'
if [ -n "$DOC" ]; then
    awk -v T=$T '/^<!-- bench:begin -->/ { print; while ((getline l < T) > 0) print l; skip = 1; next }
        /^<!-- bench:end -->/ { skip = 0 } !skip' "$DOC" > "$DOC.tmp" && mv "$DOC.tmp" "$DOC"
fi
