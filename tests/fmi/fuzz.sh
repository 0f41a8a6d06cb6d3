#!/bin/sh
# fuzz.sh - runs the modelDescription.xml fuzzer (tests/fmi/fuzz_md.c) for SECONDS: libFuzzer
# on build/fuzz/fmi-corpus, seeded with the description of every test FMU (FMI 2.0 and
# 3.0) and with tests/fmi/md.dict, or the fallback loop of tests/scenec/fuzz_main.c on the
# same seeds. A crash fails with the input saved in build/fuzz/fmi-crashes/.
# Usage: sh tests/fmi/fuzz.sh FUZZER SECONDS FMI_DIR
set -u
# FUZZ_SEED: libFuzzer's seed; 1 (make test) makes a run the prefix of any longer run
# with that seed, so a red CI reproduces here; 0 (make fuzz, the long runs) draws one
SEED=${FUZZ_SEED:-1}
BIN=$1 SECS=$2 T=$3
C=build/fuzz/fmi-corpus
mkdir -p "$C" build/fuzz/fmi-crashes
for f in "$T"/fmu/*.fmu; do
    unzip -p "$f" modelDescription.xml > "$C/seed-$(basename "$f" .fmu).xml"
done
if "$BIN" -help=1 2>&1 | grep -q libFuzzer; then
    "$BIN" -max_total_time="$SECS" -seed="$SEED" -dict=tests/fmi/md.dict -max_len=16384 -timeout=20 \
        -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=build/fuzz/fmi-crashes/ \
        "$C" > build/fuzz/fmi-fuzz.log 2>&1
    rc=$?
    grep -E '^stat::(number_of_executed_units|new_units_added)' build/fuzz/fmi-fuzz.log
    if [ "$rc" -ne 0 ]; then
        grep -A30 -E 'ERROR|runtime error|deadly signal|timeout' build/fuzz/fmi-fuzz.log | head -40
        echo "fuzz-fmi: FAILED (see build/fuzz/fmi-fuzz.log, input in build/fuzz/fmi-crashes/)"
        exit 1
    fi
    echo "fuzz-fmi: libFuzzer ran $SECS s on the modelDescription.xml reader: 1 passed, 0 failed"
else
    "$BIN" "$SECS" "$C"/* && echo "fuzz-fmi: mutation loop ran $SECS s: 1 passed, 0 failed"
fi
