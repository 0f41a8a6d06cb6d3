#!/bin/sh
# cli_io.sh - the command line at the edges of its input and output (issue 30): a run
# interrupted by SIGINT or SIGTERM (whole CSV rows, the replay log finished, the summary
# with status interrupted, exit 5, its replay stopping at the same tick), write errors (a
# full disk, a directory, no directory: the system's reason, still the summary and the
# finished log, exit 4), an include or a replay log that is not a regular file (refused
# with the reason, never read: a FIFO would block). Every process this starts is bounded
# by timeout and stopped by its PID.
# Usage: sh tests/cli_io.sh BUILD_DIR
set -u
B=${1:-build/host}
M=$B/modrt
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL cli_io: $*"; }

# ---- signals: a long run (1e5 s of pi_loop: 1e8 ticks) stopped after its first rows
# interrupt SIG OPTION...: runs modrt in the background with SIG at its default action (sh
# starts background jobs with SIGINT ignored), waits for the CSV's first rows, sends SIG
interrupt() {
    sig=$1; shift
    python3 -c 'import os, signal, sys
signal.signal(signal.SIGINT, signal.SIG_DFL)
os.execvp(sys.argv[1], sys.argv[1:])' timeout -s KILL 120 "$M" run pi_loop --t-end 100000 "$@" \
        >"$T/sum" 2>"$T/err" &
    pid=$!
    n=0
    while { [ ! -f "$T/run.csv" ] || [ "$(wc -l <"$T/run.csv")" -lt 1000 ]; } && [ $n -lt 600 ]; do
        sleep 0.1; n=$((n + 1)); done
    kill -"$sig" $pid 2>/dev/null
    wait $pid
}
for sig in INT TERM; do
    rm -f "$T/run.csv" "$T/run.mrl"
    interrupt $sig --csv "$T/run.csv" --record "$T/run.mrl"; rc=$?
    [ $rc -eq 5 ] && ok || bad "SIG$sig: exit $rc, expected 5 ($(head -2 "$T/err"))"
    grep -q '^status: interrupted$' "$T/sum" && ok || bad "SIG$sig: no status: interrupted"
    ticks=$(sed -n 's/^ticks: //p' "$T/sum")
    grep -q "^interrupted: SIG$sig at tick $ticks of 100000000$" "$T/sum" && ok ||
        bad "SIG$sig: $(grep '^interrupted' "$T/sum") (ticks $ticks)"
    # every row whole (4 fields, the file ends in a newline), the last at the tick reached
    # (pi_loop's base tick is 1 ms)
    [ "$(tail -c 1 "$T/run.csv" | od -An -c | tr -d ' ')" = '\n' ] && ok || bad "SIG$sig: CSV ends mid-row"
    awk -F, -v n="$ticks" 'NF != 4 { exit 1 } { last = $1 } END { d = last - n / 1000; exit !(d < 1e-9 && d > -1e-9) }' \
        "$T/run.csv" && ok || bad "SIG$sig: CSV rows or last time $(tail -1 "$T/run.csv") vs $ticks ticks"
    [ "$(($(wc -l <"$T/run.csv") - 1))" -eq $((ticks + 1)) ] && ok ||
        bad "SIG$sig: $(wc -l <"$T/run.csv") CSV lines for $ticks ticks"
    # the replay log ends in its end marker ("MRTE", count, last tick, how it ended, CRC-32)
    [ "$(tail -c 28 "$T/run.mrl" | head -c 4)" = MRTE ] && ok || bad "SIG$sig: replay log without its end marker"
    # its replay stops at the tick reached (it ran to the header's end time, 1e8 ticks):
    # the same ticks, rows and hash, and the summary says where the recorded run ended
    timeout -s KILL 120 "$M" replay "$T/run.mrl" --csv "$T/re.csv" >"$T/re" 2>&1; rc=$?
    [ "$(sed -n 's/^ticks: //p' "$T/re")" = "$ticks" ] &&
        [ "$(sed -n 's/^hash: //p' "$T/re")" = "$(sed -n 's/^hash: //p' "$T/sum")" ] &&
        cmp -s "$T/run.csv" "$T/re.csv" && ok ||
        bad "SIG$sig: replay: exit $rc, $(grep -E '^(ticks|hash)' "$T/re" | tr '\n' ' ')vs ticks $ticks $(grep '^hash' "$T/sum")"
    [ $rc -eq 5 ] && grep -q "^replayed: to tick $ticks of 100000000, where the recorded run ended (SIG$sig)$" "$T/re" &&
        ok || bad "SIG$sig: replay: exit $rc, $(grep -E '^(status|replayed)' "$T/re" | tr '\n' ' ')"
done

# SIGTERM to `timeout`, which passes it on to modrt and to its process group: two copies,
# the second possibly after the loop has ended; modrt still finishes (exit 5, summary, the
# log's end marker). "timeout" is that case as it happens (the window is short, a pass
# proves little); "burst" makes it certain: modrt's files close slowly (tests/slow_close.c,
# 0.2 s each, by LD_PRELOAD) and copies go to it without a pause for 0.6 s after the first
# or until it has exited, so that some arrive while it closes its files after the loop.
# Copies within STOP_AGAIN_S (tools/modrt/runner.c, 1 s) of the first are the first's.
cc -shared -fPIC -o "$T/slow_close.so" tests/slow_close.c -ldl ||
    bad "cannot build tests/slow_close.c"
for how in timeout burst; do
    rm -f "$T/run.csv" "$T/run.mrl"
    case $how in timeout) w="timeout -s KILL 120" ;; *) w="env LD_PRELOAD=$T/slow_close.so" ;; esac
    $w "$M" run pi_loop --t-end 100000 --csv "$T/run.csv" --record "$T/run.mrl" \
        >"$T/sum" 2>"$T/err" &
    pid=$!
    n=0
    while { [ ! -f "$T/run.csv" ] || [ "$(wc -l <"$T/run.csv")" -lt 1000 ]; } && [ $n -lt 600 ]; do
        sleep 0.1; n=$((n + 1)); done
    kill -TERM $pid 2>/dev/null
    if [ $how = burst ]; then
        sleep 0.6 & timer=$!
        while kill -0 $timer 2>/dev/null && kill -TERM $pid 2>/dev/null; do :; done
        kill $timer 2>/dev/null; wait $timer 2>/dev/null
    fi
    wait $pid; rc=$?
    [ $rc -eq 5 ] && grep -q '^interrupted: SIGTERM at tick' "$T/sum" &&
        [ "$(tail -c 28 "$T/run.mrl" | head -c 4)" = MRTE ] && ok ||
        bad "SIGTERM $how: exit $rc, $(grep -E '^(status|interrupted)' "$T/sum" | tr '\n' ' ')"
done

# the real-time clock too (its CSV rows are written by a thread from a ring)
rm -f "$T/run.csv"
interrupt INT --csv "$T/run.csv" --realtime; rc=$?
ticks=$(sed -n 's/^ticks: //p' "$T/sum")
[ $rc -eq 5 ] && grep -q "^interrupted: SIGINT at tick $ticks of 100000000$" "$T/sum" && ok ||
    bad "--realtime SIGINT: exit $rc: $(grep -E '^(status|interrupted)' "$T/sum")"
[ "$(($(wc -l <"$T/run.csv") - 1))" -eq $((ticks + 1)) ] &&
    awk -F, 'NF != 4 { exit 1 }' "$T/run.csv" && ok || bad "--realtime SIGINT: CSV rows for $ticks ticks"

# ---- write errors: the reason, the summary, the log finished, exit 4
if [ -w /dev/full ]; then
    "$M" run pi_loop --csv /dev/full --record "$T/full.mrl" >"$T/sum" 2>"$T/err"; rc=$?
    [ $rc -eq 4 ] && ok || bad "--csv /dev/full: exit $rc"
    grep -q '^modrt: error writing the CSV file /dev/full: No space left on device$' "$T/err" && ok ||
        bad "--csv /dev/full: $(cat "$T/err")"
    grep -q '^status: ok$' "$T/sum" && grep -q '^ticks: 3000$' "$T/sum" && ok || bad "--csv /dev/full: no summary"
    [ "$(tail -c 28 "$T/full.mrl" | head -c 4)" = MRTE ] && ok || bad "--csv /dev/full: log unfinished"
    "$M" run pi_loop --csv - >/dev/full 2>"$T/err"; rc=$?
    [ $rc -eq 4 ] && grep -q 'error writing the CSV file -: No space left on device' "$T/err" && \
        grep -q '^hash: ' "$T/err" && ok || bad "--csv - >/dev/full: exit $rc: $(head -3 "$T/err")"
    "$M" run pi_loop >/dev/full 2>"$T/err"; rc=$?
    [ $rc -eq 4 ] && grep -q 'error writing the summary to stdout: No space left on device' "$T/err" && ok ||
        bad "summary >/dev/full: exit $rc: $(cat "$T/err")"
    "$M" run pi_loop --t-end 0.05 --realtime --rt-log /dev/full >"$T/sum" 2>"$T/err"; rc=$?
    [ $rc -eq 4 ] && grep -q 'error writing the --rt-log file /dev/full: No space left on device' "$T/err" && \
        grep -q '^ticks: 50$' "$T/sum" && ok || bad "--rt-log /dev/full: exit $rc: $(grep -v warning "$T/err")"
fi
# paths checked before the run: nothing runs, the reason, exit 4
mkdir "$T/dir"
for opt in csv rt-log record; do
    "$M" run pi_loop --realtime --$opt "$T/dir" >"$T/sum" 2>"$T/err"; rc=$?
    [ $rc -eq 4 ] && [ ! -s "$T/sum" ] && grep -q "Is a directory" "$T/err" && ok ||
        bad "--$opt DIR: exit $rc: $(cat "$T/err")"
    "$M" run pi_loop --realtime --$opt "$T/nodir/x" >"$T/sum" 2>"$T/err"; rc=$?
    [ $rc -eq 4 ] && [ ! -s "$T/sum" ] && grep -q "No such file or directory" "$T/err" && ok ||
        bad "--$opt in a missing directory: exit $rc: $(cat "$T/err")"
done

# ---- not regular files: refused with the reason, never opened (a FIFO would block)
mkfifo "$T/fifo.inc"
printf 'include "fifo.inc";\nbase tick (1 ms); end time (1 s);\nload system (P) of type (pt1); P.u = 1;\n' > "$T/inc.scn"
timeout 20 "$M" run "$T/inc.scn" >"$T/out" 2>"$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q "inc.scn:1:9: error: include is a FIFO ($T/fifo.inc), not a regular file near '\"fifo.inc\"'; expected a regular file" "$T/err" \
    && ok || bad "include of a FIFO: exit $rc: $(cat "$T/err")"
ln -s /dev/zero "$T/dev.inc"
sed 's/fifo.inc/dev.inc/' "$T/inc.scn" > "$T/inc2.scn"
timeout 20 "$M" run "$T/inc2.scn" >"$T/out" 2>"$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q "error: include is a character device" "$T/err" && ok || bad "include of /dev/zero: exit $rc: $(cat "$T/err")"
mkfifo "$T/main.scn"
timeout 20 "$M" run "$T/main.scn" >"$T/out" 2>"$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q "main.scn: error: cannot read the scene file: a FIFO, not a regular file" "$T/err" && ok ||
    bad "scene file a FIFO: exit $rc: $(cat "$T/err")"
timeout 20 "$M" replay "$T/dir" >"$T/out" 2>"$T/err"; rc=$?
[ $rc -eq 2 ] && [ "$(cat "$T/err")" = "modrt: replay: a directory, not a replay log: $T/dir" ] && ok ||
    bad "replay DIR: exit $rc: $(cat "$T/err")"
timeout 20 "$M" replay "$T/main.scn" >"$T/out" 2>"$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q "not a regular file" "$T/err" && ok || bad "replay FIFO: exit $rc: $(cat "$T/err")"

echo "cli_io: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
