#!/bin/sh
# sweep_bench.sh - the figures of docs/sweeps.md, "What a campaign costs": one campaign
# (docs/sweeps/pi_loop_mc.swp cut to N runs) run on one and two local processes, under GNU
# parallel, and as a Slurm array job on a single-node cluster (tests/sweep/slurm.sh) with
# 1, 2, 5, 10, 30 and 100 runs per array task. Per engine: the wall time by the clock around
# it, the CPU time its processes used (user + system of every process it waited for,
# getrusage; a shared machine's load stretches the wall time far more than this), the runs'
# own tick loops (from collect) and the load average while it ran. Slurm's runs are the
# daemons' descendants, not ours: its CPU time is slurmctld's and slurmd's with every job
# step (slurmd under tools/dev/bench/reaper.py, a subreaper that collects the double-forked
# slurmstepd); least-squares lines over the six jobs, wall = a + b * tasks and
# CPU = c + d * tasks, give what one array task costs. Prints Markdown. Wall-clock figures
# are never a test.
# Usage: sh tools/dev/bench/sweep_bench.sh BUILD_DIR [N]
set -u
B=${1:-build/host}
N=${2:-200}
M=$(cd "$B" && pwd)/modrt
R=$(cd "$(dirname "$0")/../../.." && pwd)
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
SLURM_LIFE=1800 SLURM_WAIT=20000
# slurmd under a subreaper: its job steps (double-forked slurmstepd, the runs under them)
# are reaped there, so their CPU time is counted; slurmctld's from /proc (own + reaped)
SLURMD_WRAP="python3 $R/tools/dev/bench/reaper.py $T/stepd.cpu"
slurm_cpu() { # CPU seconds of the cluster so far: slurmd's tree and slurmctld
    kill -USR1 "$reaper" 2>/dev/null; sleep 0.3
    awk -v t="$(getconf CLK_TCK)" -v d="$(cat "$T/stepd.cpu" 2>/dev/null || echo 0)" \
        '{ sub(/^.*\) /, ""); print d + ($12 + $13 + $14 + $15) / t }' "/proc/$(cat "$S/slurmctld.pid")/stat"
}
fit=""
if slurm_up; then
    reaper=$(echo $pids | awk '{ print $NF }')  # the last started: slurmd's wrapper
    for per in 1 2 5 10 30 100; do
        $M sweep slurm "$T/c.swp" --out "$T/sl$per" --per-task "$per" > /dev/null 2>&1
        tasks=$(( (N + per - 1) / per ))
        l0=$(load); c0=$(slurm_cpu); t0=$(date +%s.%N); slurm_run "$T/sl$per/sweep.sbatch"
        w=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
        c=$(awk -v a="$c0" -v b="$(slurm_cpu)" 'BEGIN { print b - a }')
        row "Slurm, $per run(s) per array task ($tasks tasks)" "$w $c" "$T/sl$per" "$l0"
        fit="$fit $tasks:$w:$c"
    done
    echo
    echo "$fit" | tr ' ' '\n' | awk -F: -v n0="$N" 'NF == 3 { n++; x += $1; y += $2; z += $3; xx += $1 * $1; xy += $1 * $2; xz += $1 * $3 }
        END { b = (n * xy - x * y) / (n * xx - x * x); a = (y - b * x) / n
              d = (n * xz - x * z) / (n * xx - x * x); e = (z - d * x) / n
              printf "Slurm (least squares over %d jobs of %d runs): wall = %.2f s + %.3f s per array task; CPU = %.2f s + %.1f ms per array task (the runs themselves: %.1f ms each)\n", n, n0, a, b, e, d * 1000, e / n0 * 1000 }'
else
    echo "(Slurm: $why)"
fi
