#!/bin/sh
# exact_limits.sh - compiles rt/ and models/ with the exact limits of the library scenes
# that need the fewest (`modrt sizes SCENE`: arrays of one element), as a per-scene image
# or `make image` does, with -O2 -Werror: gcc's -Warray-bounds sees loops that can never
# run past such an array only at those sizes (an RT_MAX_D=1 build once failed in
# `make footprint`, which `make test` does not run). Compile only, nothing is linked.
# Usage: sh tests/static/exact_limits.sh MODRT JOBS "SCENE ..."
set -u
M=$1 J=$2 SCENES=$3
CC=${CC:-cc}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
fails=0 n=0
for s in $SCENES; do
    F=$("$M" sizes "$s" | tr '\n' ' ')
    if [ -z "$F" ]; then
        echo "exact_limits: modrt sizes $s printed nothing"; fails=$((fails + 1)); continue
    fi
    for f in rt/*.c models/*.c; do
        echo "$f"
    done | xargs -P "$J" -I{} sh -c \
        "$CC -std=c11 -Wall -Wextra -Werror -ffp-contract=off -fno-math-errno -O2 \
         -ffreestanding -Irt -Imodels $F -c {} -o /dev/null 2>>$T/$s.err || echo {} >> $T/$s.bad"
    n=$((n + 1))
    if [ -s "$T/$s.bad" ]; then
        echo "exact_limits: $s's limits ($F):"
        head -20 "$T/$s.err"
        fails=$((fails + 1))
    fi
done
echo "exact_limits: rt/ and models/ with the exact limits of $n scenes: $((n - fails)) passed, $fails failed"
[ "$fails" -eq 0 ]
