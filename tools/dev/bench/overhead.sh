#!/bin/sh
# overhead.sh - modular overhead of modrt against the hand-written monolith
# (tools/dev/bench/pendulum_mono.c, actuated_mono.c, actuated_mr_mono.c): instructions per
# simulated second of each side counted by callgrind inside the run only (--toggle-collect
# on modrt_ticks, mono_steps, amono_steps or amr_steps: start-up excluded), deterministic;
# prints one line per scene and method,
#   modular overhead <scene> <method>: <modrt / monolith>
# against the monolith with the dense Schur solve and the same embedded error estimate,
# then the same against the monolith without the estimate and with the Thomas solve;
# pendulum10_actuated_single with ROS2 (its monolith with modrt's evaluations, then with
# the Thomas solve; neither side evaluates f(t + h, x0): the model is autonomous over a
# step), and the multirate
# pendulum10_actuated last (bs3 chain in the background, ROS2 servo; its monolith with
# modrt's estimates, then without bs3's error estimate and the history monitors, and with
# the Thomas solve).
# Usage: sh tools/dev/bench/overhead.sh build/host/overhead_bench [SECONDS]
set -eu
B=$1
S=${2:-1}
count() { # side method -> instructions per simulated second
    f=$(mktemp)
    valgrind --tool=callgrind --callgrind-out-file=$f --toggle-collect="$3" \
        "$B" count "$1" "$2" "$S" > /dev/null 2>&1
    n=$(sed -n 's/^summary: //p' "$f")
    rm -f "$f"
    echo $((n / S))
}
for m in bs3 rk4 dopri5; do
    r=$(count modrt $m modrt_ticks)
    d=$(count mono $m mono_steps)
    n=$(count mono-noest $m mono_steps)
    t=$(count thomas $m mono_steps)
    awk -v m=$m -v r=$r -v d=$d -v n=$n -v t=$t 'BEGIN {
        printf "modular overhead pendulum10 %s: %.2f\n", m, r / d
        printf "  instructions per simulated s: modrt %d, monolith %d (dense, with estimate), %d (no estimate: %.2fx), %d (Thomas: %.2fx)\n", r, d, n, r / n, t, r / t }'
done
r=$(count modrt ros2 modrt_ticks)
d=$(count mono ros2 amono_steps)
t=$(count thomas ros2 amono_steps)
awk -v r=$r -v d=$d -v t=$t 'BEGIN {
    printf "modular overhead pendulum10_actuated_single ros2: %.2f\n", r / d
    printf "  instructions per simulated s: modrt %d, monolith %d (dense, as modrt evaluates), %d (Thomas: %.2fx)\n", r, d, t, r / t }'
r=$(count modrt bs3+ros2 modrt_ticks)
d=$(count mono bs3+ros2 amr_steps)
n=$(count mono-noest bs3+ros2 amr_steps)
t=$(count thomas bs3+ros2 amr_steps)
awk -v r=$r -v d=$d -v n=$n -v t=$t 'BEGIN {
    printf "modular overhead pendulum10_actuated bs3+ros2: %.2f\n", r / d
    printf "  instructions per simulated s: modrt %d, monolith %d (dense, with the estimates), %d (no estimates: %.2fx), %d (Thomas: %.2fx)\n", r, d, n, r / n, t, r / t }'
