#!/bin/sh
# fuzz.sh - runs the link decoders' fuzzer for SECONDS (libFuzzer, or the fallback loop of
# tests/scenec/fuzz_main.c), prints its counts and the decoders' verdicts; a crash fails.
# Usage: sh tests/link/fuzz.sh FUZZER SECONDS [CORPUS [NAME]] (default: the link fuzzer's)
set -u
# FUZZ_SEED: libFuzzer's seed; 1 (make test) makes a run the prefix of any longer run
# with that seed, so a red CI reproduces here; 0 (make fuzz, the long runs) draws one
SEED=${FUZZ_SEED:-1}
BIN=$1 SECS=$2
C=${3:-build/fuzz/link-corpus} N=${4:-link}
mkdir -p "$C" build/fuzz/crashes
if "$BIN" -help=1 2>&1 | grep -q libFuzzer; then
    "$BIN" -max_total_time="$SECS" -seed="$SEED" -max_len=16384 -timeout=10 -print_final_stats=1 \
        -artifact_prefix=build/fuzz/crashes/$N- "$C" > build/fuzz/$N-fuzz.log 2>&1
    rc=$?
else
    "$BIN" "$SECS" "$C"/* > build/fuzz/$N-fuzz.log 2>&1
    rc=$?
fi
grep -E '^stat::number_of_executed_units|verdicts' build/fuzz/$N-fuzz.log | tail -2
if [ "$rc" -ne 0 ]; then
    grep -A30 -E 'ERROR|runtime error|deadly signal|timeout' build/fuzz/$N-fuzz.log | head -40
    echo "$N fuzz: FAILED (build/fuzz/$N-fuzz.log)"; echo "$N fuzz: 0 passed, 1 failed"
    exit 1
fi
if [ "$N" != link ]; then
    echo "$N fuzz: $SECS s, no crash, hang or sanitizer report: 1 passed, 0 failed"
    exit 0
fi
# the log reader must have been reached past its checks: the seeds hold valid logs of
# every version (tests/link/seed_packets.py)
acc=$(sed -n 's/.*logs accepted \([0-9]*\).*/\1/p' build/fuzz/link-fuzz.log | tail -1)
if [ "${acc:-0}" -eq 0 ]; then
    echo "link fuzz: no replay log accepted (the seeds hold no valid log): 0 passed, 1 failed"
    exit 1
fi
echo "link fuzz: $SECS s, no crash, hang or sanitizer report, $acc logs accepted: 1 passed, 0 failed"
