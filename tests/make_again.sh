#!/bin/sh
# make_again.sh - `make` is idempotent: after a complete build, a second `make all` writes
# no file (no scene regenerated, nothing recompiled or relinked). A dependency on something
# that is not a file (issue 30: pi_link.d listed the pseudo-file `<import from Ctrl>`) makes
# make rebuild its target every time; this catches any such rule.
# Usage: sh tests/make_again.sh MAKE BUILD_DIR
set -u
MAKE_CMD=$1 B=$2
stamp=$(mktemp)
trap 'rm -f "$stamp"' EXIT
$MAKE_CMD --no-print-directory -s O="$B" all >/dev/null 2>&1 || { echo "FAIL make: make all failed"; exit 1; }
touch "$stamp"
$MAKE_CMD --no-print-directory -s O="$B" all >/dev/null 2>&1
changed=$(find "$B" build/gen -type f -newer "$stamp" | head -5)
if [ -n "$changed" ]; then
    echo "FAIL make: a second make all wrote: $(echo $changed)"
    echo "make again: 0 passed, 1 failed"; exit 1
fi
echo "make again: nothing rebuilt; 1 passed, 0 failed"
