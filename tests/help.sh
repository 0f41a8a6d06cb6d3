#!/bin/sh
# help.sh - `make help` lists every test suite `make test` runs (TEST_SUITES), each with
# what it tests, and `make hard`; the README says how to run one suite alone.
# Usage: sh tests/help.sh MAKE
set -u
MAKE_CMD=$1
pass=0 fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL help: $*"; }
suites=$($MAKE_CMD -s --no-print-directory print-TEST_SUITES)
help=$($MAKE_CMD -s --no-print-directory help)
for s in $suites; do
    echo "$help" | grep -qE "^  make $s +[a-z(]" && ok || bad "make help does not list $s"
done
echo "$help" | grep -q '^make hard ' && ok || bad "make help does not list make hard"
grep -q 'make test-<suite>\|make test-cli' README.md && ok || bad "README does not say how to run one suite"
echo "help: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
