#!/bin/sh
# hashes.sh - every scene file gives one trace hash, however it is run: compiled to C
# (SCENEC_RUN links build/gen), interpreted in host memory (`modrt run FILE.scn`, and in
# double builds also `scenec --run FILE.scn`), and, for a library scene, `modrt run NAME`
# (the hand-written scene before the switch-over, the compiled one after it).
# Usage: REAL=double|float sh tests/scenec/hashes.sh SCENEC MODRT SCENEC_RUN
set -u
SCENEC=$1 M=$2 RUN=$3 REAL=${REAL:-double}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL hashes: $*"; }
hash_of() { sed -n 's/^hash: //p'; }

"$RUN" > "$T/compiled" || bad "$RUN failed"
for f in models/scenes/*.scn tests/scenec/scenes/*.scn; do
    "$SCENEC" --run "$f" > "$T/interp"
    name=$(sed -n 's/^scene: //p' "$T/interp")
    hc=$(awk -v n="$name" '$1 == n { print $2 }' "$T/compiled")
    st=$(awk -v n="$name" '$1 == n { $1 = $2 = ""; print substr($0, 3); exit }' "$T/compiled")
    # the language's own scenes must run clean; a library scene's status is its own test's
    case $f in tests/*) [ "$st" = ok ] && ok || bad "$f: status $st";; esac
    line="$name ($st): compiled $hc"
    # scenec --run is the double interpreter
    if [ "$REAL" = double ]; then
        hs=$(hash_of < "$T/interp")
        [ "$hs" = "$hc" ] && ok || bad "$f: scenec --run $hs, compiled $hc"
        line="$line = scenec --run $hs"
    fi
    # modrt reads scene files through the same compiler and the bytecode VM
    "$M" run "$f" > "$T/modrt" 2> "$T/err"
    hm=$(hash_of < "$T/modrt")
    [ "$hm" = "$hc" ] && ok || bad "$f: modrt run FILE.scn $hm, compiled $hc"
    line="$line = modrt run FILE.scn $hm"
    case $f in models/scenes/*)
        hn=$("$M" run "$name" | hash_of)
        [ "$hn" = "$hc" ] && ok || bad "$f: modrt run $name $hn, compiled $hc"
        line="$line = modrt run $name $hn";;
    esac
    echo "hashes ($REAL): $line"
done
echo "hashes ($REAL): $pass passed, $fail failed"
[ "$fail" -eq 0 ]
