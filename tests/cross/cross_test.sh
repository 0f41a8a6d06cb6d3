#!/bin/sh
# cross_test.sh - cross-test-<t>: every test image of one target under QEMU, each run
# bounded by its instruction budget (tests/cross/run.sh), one line per image:
#   softfloat   the binary64 results of the target's arithmetic against the host's
#   unit tests  the portable unit tests, in CROSS_PARTS images (no one emulated run long)
#   scenes      every library scene over its whole run, in CROSS_SCENE_PARTS images; each
#               scene's hash against the host image's (tied to `modrt run` by check_host.sh)
#   rt          pi_loop paced by the target's timer, against `modrt run pi_loop`
#   segments    (CROSS_LDSCRIPT) what a loader writes for each image inside the memory of
#               the target's link script (segments.py)
#   bg          (CROSS_BG_TARGETS) the background set preempted for real (check_bg.sh)
# Usage: sh tests/cross/cross_test.sh T BUILD_DIR HOST_DIR RUN VTIME BG_TICKS
#   RUN: the target's QEMU command with -plugin ...,limit=@BUDGET@ in it; VTIME: 1 where
#   time is virtual (no overrun may happen); BG_TICKS: ticks of the background run, or 0.
#   Environment: QEMU_TIMEOUT, CROSS_PARTS, CROSS_SCENE_PARTS, CROSS_BUDGET_SOFTFLOAT,
#   CROSS_BUDGET_TESTS, CROSS_BUDGET_SCENES, CROSS_BUDGET_RT, CROSS_JOBS (images at once, 2),
#   CROSS_LDSCRIPT (the target's link script; empty where the OS loads the image).
set -u
t=$1 B=$2 H=$3 RUN=$4 VTIME=$5 BG=$6
fail=0
say() { echo "cross-test $t: $*"; }

# run LABEL BUDGET_NAME ELF LOG: the image bounded by the budget the variable names
run() {
    eval "budget=\$$2"
    sh tests/cross/run.sh "cross-test $t: $1" "$RUN" "$budget" "$2" "$3" "$4"
}

# parts KIND BUDGET_NAME N: the images $B/KIND-<k>ofN.elf, CROSS_JOBS (2) at a time as a
# pool (each bounded by its own instruction budget, so how many share the cores changes
# no verdict); each leaves its log, its status in LOG.rc and what run.sh said in LOG.say
jobs=${CROSS_JOBS:-2}
parts() {
    eval "budget=\$$2"
    k=0
    while [ $k -lt "$3" ]; do echo $k; k=$((k + 1)); done |
        xargs -P "$jobs" -I{} sh -c 'l="$6-{}of$7.log"; sh tests/cross/run.sh "$1 {}" "$2" \
            "$3" "$4" "$6-{}of$7.elf" "$l" > "$l.say" 2>&1; echo $? > "$l.rc"' _ \
            "cross-test $t: $1 part" "$RUN" "$budget" "$2" - "$B/$1" "$3"
}

# what a loader writes for each image (its segments at their physical addresses, zeros
# included) inside the target's memory: a segment running past FLASH erased the code of
# images whose code + .bss exceeded 4 MB (ports/cortex-m/link.ld); the check itself must
# refuse an image given a memory too small for it
if [ -n "${CROSS_LDSCRIPT:-}" ]; then
    imgs="$B/softfloat.elf $B/rt.elf"
    k=0
    while [ $k -lt "$CROSS_PARTS" ]; do imgs="$imgs $B/tests-${k}of$CROSS_PARTS.elf"; k=$((k + 1)); done
    k=0
    while [ $k -lt "$CROSS_SCENE_PARTS" ]; do imgs="$imgs $B/scenes-${k}of$CROSS_SCENE_PARTS.elf"; k=$((k + 1)); done
    [ "$BG" -gt 0 ] && imgs="$imgs $B/rt_bg.elf"
    n=$(echo $imgs | wc -w)
    # shellcheck disable=SC2086 # one word per image
    if out=$(python3 tests/cross/segments.py "$CROSS_LDSCRIPT" $imgs 2>&1); then
        say "every image's load segments inside the memory of $CROSS_LDSCRIPT: $n passed, 0 failed"
    else
        bad=$(echo "$out" | cut -d: -f1 | sort -u | wc -l)
        echo "$out"; say "images written outside the target's memory: $((n - bad)) passed, $bad failed"; fail=1
    fi
    if python3 tests/cross/segments.py --region FLASH:0:0x1000 --region RAM:0x20000000:0x1000 \
           -- "$B/softfloat.elf" >/dev/null 2>&1; then
        say "segments.py passed an image larger than the memory given: 0 passed, 1 failed"; fail=1
    fi
fi

# binary64 arithmetic
if run softfloat CROSS_BUDGET_SOFTFLOAT "$B/softfloat.elf" "$B/softfloat.log"; then
    if diff "$H/softfloat.log" "$B/softfloat.log" >/dev/null; then
        say "binary64 result hashes equal to the host's: $(grep -c hash "$B/softfloat.log") passed, 0 failed"
    else
        diff "$H/softfloat.log" "$B/softfloat.log" | head -20
        say "binary64 result hashes differ from the host's: 0 passed, 1 failed"; fail=1
    fi
else
    tail -20 "$B/softfloat.log"; say "softfloat test failed"; fail=1
fi

# the unit tests, part by part, reported in order
parts tests CROSS_BUDGET_TESTS "$CROSS_PARTS"
k=0
while [ $k -lt "$CROSS_PARTS" ]; do
    p="$((k + 1))/$CROSS_PARTS" log="$B/tests-${k}of$CROSS_PARTS.log"
    cat "$log.say"
    if [ "$(cat "$log.rc")" = 0 ]; then
        say "unit tests $p: $(tail -1 "$log")"
    else
        grep -E '^FAIL|passed' "$log" | head -40; say "unit tests $p failed"; fail=1
    fi
    k=$((k + 1))
done

# the bounds themselves: the first unit-test image with a budget far too small, and an
# image that never ends (hang.sh) with a QEMU_TIMEOUT of 1 s, must stop, say which bound
# stopped them, and count the tests they never finished as failed (their lines are
# checked here, not counted)
probe() { # WHAT PATTERN RUN_VARIANT BUDGET
    out=$(QEMU_TIMEOUT=1 sh tests/cross/run.sh "probe" "$3" "$4" CROSS_BUDGET_PROBE \
              "$B/tests-0of$CROSS_PARTS.elf" "$B/probe.log" 2>&1)
    n=$(sed -n 's/^tests: //p' "$B/probe.log" | head -1)
    if echo "$out" | grep -q "^probe: $2" &&
       echo "$out" | grep -qE "^probe: [0-9]+ of ${n:-x} tests finished, [1-9][0-9]* never ran \(counted as failed\)"; then
        say "a run cut off by its $1 says so and counts the tests it never ran: 1 passed, 0 failed"
    else
        echo "$out" | sed 's/passed, /passed; /'; say "a run cut off by its $1: 0 passed, 1 failed"; fail=1
    fi
}
probe "instruction budget" "stopped after its budget of 20000000 instructions (CROSS_BUDGET_PROBE)" \
    "$RUN" 20000000
probe "QEMU_TIMEOUT" "timed out after 1 s (QEMU_TIMEOUT)" "timeout 1 sh tests/cross/hang.sh" 1

# every library scene over its whole run, against the host
: > "$B/scenes.log"
parts scenes CROSS_BUDGET_SCENES "$CROSS_SCENE_PARTS"
k=0
while [ $k -lt "$CROSS_SCENE_PARTS" ]; do
    p="$((k + 1))/$CROSS_SCENE_PARTS" log="$B/scenes-${k}of$CROSS_SCENE_PARTS.log"
    cat "$log.say"
    if [ "$(cat "$log.rc")" = 0 ]; then
        cat "$log" >> "$B/scenes.log"
    else
        tail -5 "$log"; say "scene image $p failed"; fail=1
    fi
    k=$((k + 1))
done
# each scene's line (ticks, status, hash) against the host image's
n=0 bad=0
while read -r line; do
    n=$((n + 1))
    name=$(echo "$line" | awk '{ print $2 }')
    want=$(grep "^scene $name " "$H/scenes.log")
    if [ "$line" != "$want" ]; then
        say "$line; host: $want"; bad=$((bad + 1))
    fi
done < "$B/scenes.log"
missing=$(($(wc -l < "$H/scenes.log") - n))
if [ "$bad" -eq 0 ] && [ "$missing" -eq 0 ]; then
    say "scene hashes over the whole run of each scene ($(awk '{ s += $4 } END { print s }' "$B/scenes.log") ticks in all) equal to the host's: $n passed, 0 failed"
else
    say "scene hashes: $((n - bad)) passed, $((bad + missing)) failed ($missing scenes without a result)"; fail=1
fi

# pi_loop paced by the target's timer
if run "timer-paced run" CROSS_BUDGET_RT "$B/rt.elf" "$B/rt.log"; then
    h=$(sed -n 's/.* hash \([0-9a-f]*\).*/\1/p' "$B/rt.log")
    if [ "$h" = "$("$H/modrt" run pi_loop | sed -n 's/^hash: //p')" ]; then
        say "timer-paced pi_loop: $(sed 's/^rt scene pi_loop //' "$B/rt.log")"
    else
        cat "$B/rt.log"; say "timer-paced hash differs"; fail=1
    fi
    if [ "$VTIME" = 1 ] && ! grep -q ' overruns 0 ' "$B/rt.log"; then
        say "overruns in deterministic virtual time"; fail=1
    fi
else
    cat "$B/rt.log"; say "timer-paced run failed"; fail=1
fi

if [ "$BG" -gt 0 ]; then
    sh tests/cross/check_bg.sh "$(printf '%s' "$RUN" | sed "s/@BUDGET@/$CROSS_BUDGET_RT/g")" \
        "$B/rt_bg.elf" "$H/modrt" "$BG" "$t" || fail=1
fi
exit $fail
