#!/bin/sh
# bad.sh - the bad-FMU corpus (tests/fmi/run.sh): FMUs broken in one way each, built by
# mkfmu.py from the good test models, and what modrt must say about each: a one-line error
# naming the problem before the run (exit 2), or a fault counted during it (exit 1, the
# runtime's nan counter and the FMU's first fault with its call and logged message).
# Prints "ok: ..." or "FAIL: ..." per case.
#
# Usage: sh tests/fmi/bad.sh BUILD_DIR FMI_DIR
set -u
B=$1 T=$2
M=$B/modrt
D=$T/bad
rm -rf "$D" && mkdir -p "$D"
D=$(cd "$D" && pwd)
export MODRT_FMU_CACHE="$T/cache-bad"
rm -rf "$MODRT_FMU_CACHE"
CF="-std=c11 -Wall -Wextra -Werror -O2 -fPIC -shared -Itools/fmi -Itests/fmi"

# name version model [mkfmu options...]: builds $D/name.fmu and a scene loading it
mk() {
    n=$1 v=$2 m=$3
    shift 3
    python3 tests/fmi/mkfmu.py --cc "${CC:-cc}" --cflags "$CF" --version "$v" --model "$m" \
        --out "$D/$n.fmu" "$@" || { echo "FAIL: $n: mkfmu"; return 1; }
    cat > "$D/$n.scn" <<SCN
scene (bad_$n);
base tick (1 ms);
end time (2 s);
load system (X) of type (fmu) from file ("$n.fmu");
record (X.h);
SCN
}

# name pattern: a one-line error before the run
refused() {
    "$M" run "$D/$1.scn" > "$D/$1.out" 2> "$D/$1.err"
    rc=$? lines=$(wc -l < "$D/$1.err")
    if [ $rc -eq 2 ] && [ "$lines" -eq 1 ] && grep -q "$2" "$D/$1.err"; then
        echo "ok: $1: refused in one line: $(cat "$D/$1.err")"
    else
        echo "FAIL: $1: exit $rc, $lines lines, expected one matching '$2':"; cat "$D/$1.err"
    fi
}

# name pattern: a fault counted during the run, with the FMU's account
counted() {
    "$M" run "$D/$1.scn" > "$D/$1.out" 2>&1
    rc=$?
    nan=$(sed -n 's/^nan: \([0-9]*\).*/\1/p' "$D/$1.out")
    if [ $rc -eq 1 ] && [ "${nan:-0}" -gt 0 ] && grep -q '^status: non-finite value' "$D/$1.out" &&
       grep "^fmu.X.first_fault:" "$D/$1.out" | grep -q "$2"; then
        echo "ok: $1: counted (nan $nan): $(grep '^fmu.X.first_fault' "$D/$1.out")"
    else
        echo "FAIL: $1: exit $rc, nan '$nan', expected a counted fault matching '$2':"
        cat "$D/$1.out"
    fi
}

for v in 2 3; do
    mk trunc$v $v bouncing --truncate 300 && refused trunc$v "not a readable zip archive"
    mk nomd$v $v bouncing --no-md && refused nomd$v "no modelDescription.xml"
    mk token$v $v bouncing --md-token "{00000000-0000-0000-0000-000000000000}" &&
        refused token$v "Instantiate.* failed for X: wrong"
    mk nosym$v $v bouncing --define FMU_BAD_NO_INDICATORS &&
        refused nosym$v "lacks fmi${v}GetEventIndicators"
    mk escape$v $v bouncing --extra "../escaped.txt" &&
        refused escape$v "entry '../escaped.txt' would be written outside"
    mk plat$v $v bouncing --platform win64 && refused plat$v "no binary for this platform.*win64"
    mk int$v $v bouncing --int-input n && refused int$v "variable 'n' (input .*Float64 scalars only"
    mk err$v $v bouncing --define FMU_BAD_ERROR_AT=0.5 &&
        counted err$v "Derivatives returned fmi${v}Error: injected failure"
    mk nan$v $v bouncing --define FMU_BAD_NAN_AT=0.5 && counted nan$v "non-finite derivative"
    mk loop$v $v bouncing --define FMU_BAD_LOOP && counted loop$v "did not converge in 64"
done
mk srcbreak3 3 bouncing --source-only --break-source &&
    refused srcbreak3 "building its sources failed (.* exit 1, log .*build.log)"
mk srcesc3 3 bouncing --source-only --source-name ../../evil.c &&
    refused srcesc3 "names a file outside sources/ or too many: refused"
for v in 2 3; do
    mk past$v $v stair --define FMU_BAD_NEXT_PAST && sed -i 's/record (X.h);/record (X.y);/' "$D/past$v.scn" &&
        counted past$v "nextEventTime 1 is not after the current time 1"
done
for v in 2 3; do # terminateSimulation from CompletedIntegratorStep: the FMU's termination
    mk term$v $v stepper --define FMU_BAD_STEP_TERMINATE=1 &&
        sed -i 's/record (X.h);/record (X.x);/' "$D/term$v.scn" &&
        counted term$v "asked to terminate the simulation at t = 1 (in CompletedIntegratorStep)"
done
mk nz3 3 bouncing --md-nz 2 && refused nz3 "declares 2 states and 2 event indicators, the binary 2 and 1"

# nothing escaped the cache
if find "$T" -name escaped.txt | grep -q .; then echo "FAIL: escape: a file was written outside"
else echo "ok: escape: no file written outside the FMU's directory"; fi
