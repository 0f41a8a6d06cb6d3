#!/bin/sh
# fuzz.sh - runs the scene-compiler fuzzer for SECONDS: libFuzzer on build/fuzz/corpus
# (seeded with every scene file, include and error case) with tests/scenec/scn.dict, or
# the fallback loop of fuzz_main.c on the same seeds. A crash fails with the input saved.
# Usage: sh tests/scenec/fuzz.sh FUZZER SECONDS
set -u
# FUZZ_SEED: libFuzzer's seed; 1 (make test) makes a run the prefix of any longer run
# with that seed, so a red CI reproduces here; 0 (make fuzz, the long runs) draws one
SEED=${FUZZ_SEED:-1}
BIN=$1 SECS=$2
C=build/fuzz/corpus
mkdir -p "$C" build/fuzz/crashes
cp models/scenes/*.scn tests/scenec/scenes/*.scn tests/scenec/scenes/inc/*.inc \
   tests/scenec/errors/*.scn "$C"/ 2>/dev/null
if "$BIN" -help=1 2>&1 | grep -q libFuzzer; then
    "$BIN" -max_total_time="$SECS" -seed="$SEED" -dict=tests/scenec/scn.dict -max_len=65536 -len_control=0 -timeout=20 \
        -rss_limit_mb=4096 -print_final_stats=1 -artifact_prefix=build/fuzz/crashes/ \
        "$C" > build/fuzz/fuzz.log 2>&1
    rc=$?
    grep -E '^stat::(number_of_executed_units|new_units_added|peak_rss_mb)' build/fuzz/fuzz.log
    grep -E 'cov: [0-9]+' build/fuzz/fuzz.log | tail -1
    if [ "$rc" -ne 0 ]; then
        grep -A30 -E 'ERROR|runtime error|deadly signal|timeout' build/fuzz/fuzz.log | head -40
        echo "fuzz: FAILED (see build/fuzz/fuzz.log, input in build/fuzz/crashes/)"
        exit 1
    fi
    echo "fuzz: libFuzzer ran $SECS s, no crash, leak or sanitizer report"
else
    "$BIN" "$SECS" "$C"/*
fi
