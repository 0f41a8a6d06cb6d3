#!/bin/sh
# sweep_bench.sh - the figures of docs/sweeps.md, "What a campaign costs": one campaign
# (docs/sweeps/pi_loop_mc.swp cut to N runs) run on one and two local processes, under GNU
# parallel, and as a Slurm array job on a single-node cluster (tests/sweep/slurm.sh) with
# 1, 2, 5, 10, 30 and 100 runs per array task. Per engine: the wall time by the clock around
# it, the CPU time its processes used (user + system of every process it waited for,
# getrusage; a shared machine's load stretches the wall time far more than this), the runs'
# own tick loops (from collect) and the load average while it ran. For Slurm, whose runs
# are the daemons' children and not ours, the wall time per array task, and a least-squares
# line wall = a + b * tasks: b is what one array task costs on this cluster. Prints
# Markdown. Wall-clock figures are never a test.
# Usage: sh tools/bench/sweep_bench.sh BUILD_DIR [N]
set -u
B=${1:-build/host}
N=${2:-300}
M=$(cd "$B" && pwd)/modrt
R=$(cd "$(dirname "$0")/../.." && pwd)
T=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill "$p" 2>/dev/null; done; sleep 1; rm -rf "$T"' EXIT
sed "s/draws (1000)/draws ($N)/" "$R/docs/sweeps/pi_loop_mc.swp" > "$T/c.swp"
load() { cut -d' ' -f1 /proc/loadavg; }
# timed CMD: runs CMD (sh -c), prints "WALL CPU" [s]: CPU of every process it waited for
timed() {
    python3 -c 'import resource, subprocess, sys, time
t = time.monotonic(); subprocess.run(sys.argv[1], shell=True)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print("%.3f %.3f" % (time.monotonic() - t, r.ru_utime + r.ru_stime))' "$1"
}
row() { # ENGINE "WALL CPU" DIR LOAD0: one table row; CPU "-" when not ours
    $M sweep collect "$3" > "$T/collect.out" 2>/dev/null
    sum=$(sed -n 's/^run_wall_s_sum: //p' "$T/collect.out")
    nok=$(sed -n 's/^ok: //p' "$T/collect.out")
    awk -v e="$1" -v w="${2% *}" -v c="${2#* }" -v n="$N" -v s="$sum" -v l0="$4" -v l1="$(load)" \
        -v k="$nok" 'BEGIN {
        cpu = (c == "-") ? "-" : sprintf("%.1f", c / n * 1000)
        miss = (k == n) ? "" : sprintf(" (only %d runs ok)", k)
        printf "| %s%s | %.2f | %.1f | %s | %.2f | %s - %s |\n", e, miss, w, n / w, cpu, s, l0, l1 }'
}
echo "$N runs of pi_loop_mc, $(nproc) cores, $(date -u +%Y-%m-%dT%H:%MZ)"
echo
echo "| engine | wall [s] | runs/s | CPU per run [ms] | sum of the runs' tick loops [s] | load average (1 min), start - end |"
echo "|---|---|---|---|---|---|"
l0=$(load); r=$(timed "$M sweep run $T/c.swp --out $T/j1 -j 1 2>/dev/null"); row "local --jobs 1" "$r" "$T/j1" "$l0"
l0=$(load); r=$(timed "$M sweep run $T/c.swp --out $T/j2 -j 2 2>/dev/null"); row "local --jobs 2" "$r" "$T/j2" "$l0"
if command -v parallel > /dev/null; then
    l0=$(load)
    r=$(timed "$M sweep plan $T/c.swp --out $T/par | cut -f2- | parallel --will-cite -j 2 2>/dev/null")
    row "GNU parallel -j 2" "$r" "$T/par" "$l0"
fi
. "$R/tests/sweep/slurm.sh"
SLURM_LIFE=1800
fit=""
if slurm_up; then
    for per in 1 2 5 10 30 100; do
        $M sweep slurm "$T/c.swp" --out "$T/sl$per" --per-task "$per" > /dev/null 2>&1
        tasks=$(( (N + per - 1) / per ))
        l0=$(load); t0=$(date +%s.%N); slurm_run "$T/sl$per/sweep.sbatch"
        w=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
        row "Slurm, $per run(s) per array task ($tasks tasks)" "$w -" "$T/sl$per" "$l0"
        fit="$fit $tasks:$w"
    done
    echo
    echo "$fit" | tr ' ' '\n' | awk -F: 'NF == 2 { n++; x += $1; y += $2; xx += $1 * $1; xy += $1 * $2 }
        END { b = (n * xy - x * y) / (n * xx - x * x); a = (y - b * x) / n
              printf "Slurm: wall = %.2f s + %.3f s per array task (least squares over %d jobs)\n", a, b, n }'
else
    echo "(Slurm: $why)"
fi
