#!/bin/sh
# splice.sh - replaces the lines between "<!-- bench:NAME:begin -->" and
# "<!-- bench:NAME:end -->" of a document with a file (the benchmarks' tables in copies of
# docs/ under build/bench/). Usage: sh tools/dev/bench/splice.sh NAME DOC FILE
set -eu
grep -q "^<!-- bench:$1:begin -->" "$2" && grep -q "^<!-- bench:$1:end -->" "$2" ||
    { echo "splice.sh: $2 has no bench:$1 markers" >&2; exit 1; }
awk -v b="<!-- bench:$1:begin -->" -v e="<!-- bench:$1:end -->" -v f="$3" '
    $0 == b { print; while ((getline l < f) > 0) print l; skip = 1; next }
    $0 == e { skip = 0 } !skip' "$2" > "$2.tmp" && mv "$2.tmp" "$2"
