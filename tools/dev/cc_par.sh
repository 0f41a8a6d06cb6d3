#!/bin/sh
# cc_par.sh - one program from many C files, each compiled on its own, JOBS (2) at a time,
# then linked with the same flags: the fuzzers' sanitized builds (tests/link/link.mk,
# tools/scenec/scenec.mk), which one compiler call over all of their files kept on one
# core. The objects go to OUT.objs/.
# Usage: JOBS=N sh tools/dev/cc_par.sh OUT "CC FLAGS..." "LIBS..." SOURCE...
set -u
out=$1 cc=$2 libs=$3
shift 3
dir=$out.objs
rm -rf "$dir" && mkdir -p "$dir" || exit 1
# the flags are words without spaces (-I paths, -D names): split on purpose; the
# inner script is meant for sh -c, its own $1..$3
# shellcheck disable=SC2016
printf '%s\n' "$@" | xargs -P "${JOBS:-2}" -I{} \
    sh -c 'o=$3/$(echo "$2" | tr / _).o; exec $1 -c "$2" -o "$o"' sh "$cc" {} "$dir" || exit 1
objs=
for f in "$@"; do objs="$objs $dir/$(echo "$f" | tr / _).o"; done
# shellcheck disable=SC2086
exec $cc $objs $libs -o "$out"
