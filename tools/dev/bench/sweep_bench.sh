#!/bin/sh
# sweep_bench.sh - the figures of docs/sweeps.md, "What a campaign costs": one campaign
# (docs/sweeps/pi_loop_mc.swp cut to N runs) run on one and two local processes, under GNU
# parallel, and as a Slurm array job on a single-node cluster (tests/sweep/slurm.sh) with
# one run per array task and with N/8; wall times by the clock around each engine, the
# runs' own times (their tick loops) from collect. Prints a Markdown table. Wall-clock
# figures: run it on an idle machine (they are never a test).
# Usage: sh tools/dev/bench/sweep_bench.sh BUILD_DIR [N]
set -u
B=${1:-build/host}
N=${2:-240}
M=$(cd "$B" && pwd)/modrt
R=$(cd "$(dirname "$0")/../../.." && pwd)
T=$(mktemp -d)
pids=""
trap 'for p in $pids; do kill "$p" 2>/dev/null; done; sleep 1; rm -rf "$T"' EXIT
sed "s/draws (1000)/draws ($N)/" "$R/docs/sweeps/pi_loop_mc.swp" > "$T/c.swp"
now() { date +%s.%N; }
row() { # ENGINE WALL DIR: the table row of one engine; the overhead against local -j 2
    sum=$($M sweep collect "$3" 2>/dev/null | sed -n 's/^run_wall_s_sum: //p')
    awk -v e="$1" -v w="$2" -v n="$N" -v s="$sum" -v j2="${J2:-}" 'BEGIN {
        o = (j2 == "") ? "" : sprintf("%+.1f", (w - j2) * 2 / n * 1000)
        printf "| %s | %.2f | %.1f | %.2f | %s |\n", e, w, n / w, s, o }'
}
echo "| engine | wall [s] | runs/s | sum of the runs' tick loops [s] | overhead per run over local -j 2 [ms of a core] |"
echo "|---|---|---|---|---|"
t0=$(now); $M sweep run "$T/c.swp" --out "$T/j1" -j 1 2>/dev/null
row "local --jobs 1" "$(awk -v a="$t0" -v b="$(now)" 'BEGIN { print b - a }')" "$T/j1"
t0=$(now); $M sweep run "$T/c.swp" --out "$T/j2" -j 2 2>/dev/null
J2=$(awk -v a="$t0" -v b="$(now)" 'BEGIN { print b - a }')
row "local --jobs 2" "$J2" "$T/j2"
if command -v parallel > /dev/null; then
    t0=$(now)
    $M sweep plan "$T/c.swp" --out "$T/par" | cut -f2- | parallel --will-cite -j 2 2>/dev/null
    row "GNU parallel -j 2" "$(awk -v a="$t0" -v b="$(now)" 'BEGIN { print b - a }')" "$T/par"
fi
. "$R/tests/sweep/slurm.sh"
SLURM_LIFE=600
if slurm_up; then
    for per in 1 $((N / 8)); do
        $M sweep slurm "$T/c.swp" --out "$T/sl$per" --per-task "$per" > /dev/null 2>&1
        t0=$(now); slurm_run "$T/sl$per/sweep.sbatch"
        row "Slurm, $per run(s) per array task" "$(awk -v a="$t0" -v b="$(now)" 'BEGIN { print b - a }')" "$T/sl$per"
    done
else
    echo "(Slurm: $why)"
fi
