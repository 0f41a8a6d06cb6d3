#!/bin/sh
# casts.sh - every float-to-integer conversion of the tools fed a value out of the integer
# type's range (issue 30, D2): the input is refused with one line and exit 2, and the
# sanitized build (SAN=1: -fsanitize=float-cast-overflow, no recovery) reports no
# undefined behaviour. Without the range checks the sanitizer aborts the run.
# Usage: sh tests/casts.sh MODRT_SAN   (a modrt built with SAN=1)
set -u
M=$1
export ASAN_OPTIONS=detect_leaks=0 # modrt keeps a compiled scene file until exit
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL casts: $*"; }

# expect2 WHAT PATTERN -- command: exit 2, one stderr line matching, no sanitizer report
expect2() {
    what=$1 pat=$2; shift 2
    "$@" >"$T/out" 2>"$T/err"; rc=$?
    if [ "$rc" -eq 2 ] && [ "$(wc -l <"$T/err")" -eq 1 ] && grep -q -- "$pat" "$T/err"; then ok
    else bad "$what: exit $rc: $(head -3 "$T/err")"; fi
}

# scenec (parse.c, link.c): an exchange period of 1e303 base ticks
sed -e 's/from file ("[a-z0-9]*")//' -e 's/every (10 ms)/every (1e300 s)/' \
    models/scenes/pi_link.scn > "$T/every.scn"
expect2 "import every (1e300 s)" "exchange period is not a whole number of base ticks" \
    "$M" run "$T/every.scn"
# study.c: a step of 1e311 base ticks, and one far below a tick
expect2 "--step main=1e308" "must be a whole number of base ticks" \
    "$M" run pi_loop --step main=1e308
expect2 "--step main=1e-300" "must be a whole number of base ticks" \
    "$M" run pi_loop --step main=1e-300
# rtloop.c: a base tick of 1e300 s has no period in nanoseconds
printf 'scene (big);\nbase tick (1e300 s); end time (1e300 s);\nload system (P) of type (pt1); P.u = 1;\nset (main) method (rk4) step (1 tick);\nrecord (P.y);\n' > "$T/big.scn"
expect2 "--realtime with a base tick of 1e300 s" "base tick too long for the real-time clock" \
    "$M" run "$T/big.scn" --realtime
echo "casts: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
