#!/bin/sh
# errors.sh - one bad scene per kind of error (tests/scenec/errors/*.scn): scenec --check
# must exit 1 with exactly the line the file's first `// expect: ` comment gives (or, if
# that ends in "...", a line beginning with the rest: for lists that grow, such as the
# model library), and `modrt run FILE.scn` must print the same after "modrt: ", exit 2.
# Usage: sh tests/scenec/errors.sh SCENEC MODRT
set -u
SCENEC=$1 M=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL errors: $*"; }

for f in tests/scenec/errors/*.scn; do
    want=$(sed -n 's|^// expect: ||p' "$f" | head -1)
    "$SCENEC" --check "$f" > "$T/out" 2> "$T/err"; rc=$?
    got=$(cat "$T/err")
    case $want in *...) prefix=${want%...}; [ "${got#"$prefix"}" != "$got" ] && got=$want;; esac
    if [ "$rc" -eq 1 ] && [ "$got" = "$want" ] && [ ! -s "$T/out" ]; then ok; else
        bad "$f (exit $rc)"; echo "  want: $want"; echo "  got:  $got"; fi
    "$M" run "$f" > "$T/out" 2> "$T/err"; rc=$?
    got=$(cat "$T/err")
    case $want in *...) prefix=${want%...}; [ "${got#"modrt: $prefix"}" != "$got" ] && got="modrt: $want";; esac
    [ "$rc" -eq 2 ] && [ "$got" = "modrt: $want" ] && ok || \
        bad "$f: modrt run (exit $rc): $(cat "$T/err")"
done
echo "errors: $(ls tests/scenec/errors/*.scn | wc -l) error kinds; $pass passed, $fail failed"
[ "$fail" -eq 0 ]
