#!/bin/sh
# run-suites.sh - what `make test` prints: runs each test suite (a make target) with its
# output in build/test-logs/<suite>.log, prints one line per suite with its counts and
# time, the log's tail when it fails, and ends with the grand total `N passed, N failed`.
# A suite's count is the sum of the `N passed, N failed` lines it printed; a suite that
# printed none counts as one check. With V=1 every suite's output goes to the console too.
# Each line also gives the suite's processor time over its wall time ("cpu 1.8x" on two
# busy cores): a suite far below the core count leaves cores idle.
#
# Usage: sh tools/dev/run-suites.sh MAKE SUITE...
set -u
MAKE_CMD=$1; shift
LOGS=build/test-logs
mkdir -p "$LOGS"
total_p=0 total_f=0 failed=""
t_all=$(date +%s)

# seconds of processor time (user + system) in the output of `times` (file $1), whose
# second line is what this shell's children used; `times` itself must run in this shell
# (in a command substitution it would count the subshell's children)
cpu_of() {
    tail -1 "$1" | awk '{ for (i = 1; i <= 2; i++) { split($i, a, /[ms]/); s += a[1] * 60 + a[2] } }
        END { printf "%.2f\n", s }'
}

# "P F": the sum of every "N passed, N failed" in a log
counts() {
    grep -oE '[0-9]+ passed, [0-9]+ failed' "$1" |
        awk '{p += $1; f += $3} END {printf "%d %d\n", p, f}'
}

for s in "$@"; do
    log=$LOGS/$s.log
    t0=$(date +%s.%N); times > "$LOGS/.times"; c0=$(cpu_of "$LOGS/.times")
    if [ "${V:-0}" = 1 ]; then
        { $MAKE_CMD --no-print-directory "$s" 2>&1; echo "rc=$?" > "$log.rc"; } | tee "$log"
        rc=$(sed 's/rc=//' "$log.rc"); rm -f "$log.rc"
    else
        $MAKE_CMD --no-print-directory -s "$s" > "$log" 2>&1; rc=$?
    fi
    t1=$(date +%s.%N); times > "$LOGS/.times"; c1=$(cpu_of "$LOGS/.times")
    pf=$(counts "$log")
    p=${pf% *} f=${pf#* }
    if [ "$p" -eq 0 ] && [ "$f" -eq 0 ]; then
        if [ "$rc" -eq 0 ]; then p=1; else f=1; fi
    elif [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        f=1 # it stopped with an error its counts do not show
    fi
    total_p=$((total_p + p)) total_f=$((total_f + f))
    printf '%-22s %6d passed, %d failed  %7.1f s  cpu %.1fx\n' "$s" "$p" "$f" \
        "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')" \
        "$(awk -v a="$t0" -v b="$t1" -v c="$c0" -v d="$c1" 'BEGIN { print (d - c) / (b - a) }')"
    if [ "$f" -ne 0 ]; then
        failed="$failed $s"
        [ "${V:-0}" = 1 ] || { echo "--- last lines of $log:"; tail -25 "$log" | sed 's/^/  /'; }
    fi
done

echo "test: $(($(date +%s) - t_all)) s;${failed:+ failed suites:$failed;} logs in $LOGS/"
echo "$total_p passed, $total_f failed"
[ "$total_f" -eq 0 ]
