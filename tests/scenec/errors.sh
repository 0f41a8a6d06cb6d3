#!/bin/sh
# errors.sh - one bad scene per kind of error (tests/scenec/errors/*.scn): scenec --check
# must exit 1 with exactly the lines the file's `// expect: ` comments give, in order (a
# file with independent errors reports each; a line that ends in "..." matches a line
# beginning with the rest: for lists that grow, such as the model library), and
# `modrt run FILE.scn` must print the same, each line after "modrt: ", exit 2.
# Usage: sh tests/scenec/errors.sh SCENEC MODRT
set -u
SCENEC=$1 M=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL errors: $*"; }

# same WANT GOT PREFIX: every line of GOT is PREFIX and its line of WANT (or begins with
# it, less its "...")
same() {
    awk -v p="$3" 'NR == FNR { w[n++] = $0; next }
        { k = FNR - 1; if (k >= n) exit 1; x = p w[k]
          if (x ~ /\.\.\.$/) { x = substr(x, 1, length(x) - 3); if (substr($0, 1, length(x)) != x) exit 1 }
          else if ($0 != x) exit 1 }
        END { if (FNR != n) exit 1 }' "$1" "$2"
}

for f in tests/scenec/errors/*.scn; do
    sed -n 's|^// expect: ||p' "$f" > "$T/want"
    "$SCENEC" --check "$f" > "$T/out" 2> "$T/err"; rc=$?
    if [ "$rc" -eq 1 ] && same "$T/want" "$T/err" "" && [ ! -s "$T/out" ]; then ok; else
        bad "$f (exit $rc)"; sed 's/^/  want: /' "$T/want"; sed 's/^/  got:  /' "$T/err"; fi
    "$M" run "$f" > "$T/out" 2> "$T/err"; rc=$?
    [ "$rc" -eq 2 ] && same "$T/want" "$T/err" "modrt: " && ok || \
        bad "$f: modrt run (exit $rc): $(cat "$T/err")"
done
echo "errors: $(ls tests/scenec/errors/*.scn | wc -l) error kinds; $pass passed, $fail failed"
[ "$fail" -eq 0 ]
