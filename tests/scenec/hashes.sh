#!/bin/sh
# hashes.sh - every scene file gives one trace hash, however it is run: compiled to C
# (SCENEC_RUN, linking build/gen), interpreted in host memory (scenec --run, and
# `modrt run FILE.scn`), and, for a library scene, `modrt run NAME` (the hand-written
# scene until the switch-over, the compiled one after it).
# Usage: sh tests/scenec/hashes.sh SCENEC MODRT SCENEC_RUN
set -u
SCENEC=$1 M=$2 RUN=$3
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0 skipped=""
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL hashes: $*"; }
hash_of() { sed -n 's/^hash: //p'; }

"$RUN" > "$T/compiled" || bad "scenec-run failed"
for f in models/scenes/*.scn tests/scenec/scenes/*.scn; do
    "$SCENEC" --run "$f" > "$T/interp"
    name=$(sed -n 's/^scene: //p' "$T/interp")
    hi=$(hash_of < "$T/interp")
    grep -q '^status: ok$' "$T/interp" && ok || bad "$f: interpreted status $(grep status "$T/interp")"
    hc=$(awk -v n="$name" '$1 == n { print $2 }' "$T/compiled")
    [ -n "$hi" ] && [ "$hi" = "$hc" ] && ok || bad "$f: interpreted $hi, compiled '$hc'"
    # modrt with scene files (after the patch of ports/posix/modrt.c)
    "$M" run "$f" > "$T/modrt" 2> "$T/err"
    if grep -q "unknown scene" "$T/err"; then
        skipped="$skipped $f"
    else
        [ "$(hash_of < "$T/modrt")" = "$hi" ] && ok || bad "$f: modrt run FILE.scn $(hash_of < "$T/modrt"), interpreted $hi"
    fi
    case $f in models/scenes/*)
        hm=$("$M" run "$name" | hash_of)
        [ "$hm" = "$hi" ] && ok || bad "$f: modrt run $name $hm, scene file $hi"
        echo "hashes: $name: compiled $hc = interpreted $hi = modrt run $name $hm";;
    *)  echo "hashes: $name: compiled $hc = interpreted $hi";;
    esac
done
[ -z "$skipped" ] || echo "hashes: modrt does not read scene files yet; skipped:$skipped"
echo "hashes: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
