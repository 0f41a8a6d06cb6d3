#!/bin/sh
# link.sh - an FMU plant in the controller-in-the-loop mode (docs/fmi.md, docs/link.md):
# the oscillator test FMU (FMI 2.0 and 3.0) under tools/examples/pi_controller.py over the
# link on 127.0.0.1, lock-step, recorded; the live trace must equal, value for value, the
# run with both halves in the scene (the FMU's equations as a scene-language define under
# pi_loop's PI block: the same arithmetic), and `modrt replay` of the log gives the live
# hash, and refuses the log once the FMU file is replaced by another build (the other FMI
# version's: other bytes, the same interface). Every controller runs under `timeout` and is stopped and waited for by its PID.
# usage: sh tests/fmi/link.sh BUILD_DIR FMI_DIR
set -u
B=$1 T=$2
M=$B/modrt
W=$T/link
FMUS=$(cd "$T/fmu" && pwd)
mkdir -p "$W"
export MODRT_FMU_CACHE="$T/cache"
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $*"; }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
field() { sed -n "s/^$1: //p" "$2"; }

start() { # the Python example controller, bounded in time; PORT from its "port N" line
    rm -f "$W/ctl.out"
    timeout 60 python3 tools/examples/pi_controller.py --idle 5 > "$W/ctl.out" 2>&1 &
    CTL=$!
    PORT=
    for _ in $(seq 200); do
        PORT=$(sed -n 's/^port //p' "$W/ctl.out")
        [ -n "$PORT" ] && return 0
        sleep 0.1
    done
    bad "the controller did not start"; kill $CTL 2>/dev/null; wait $CTL 2>/dev/null; PORT=0
}
stop() { kill $CTL 2>/dev/null; wait $CTL 2>/dev/null; }

"$M" run tests/fmi/scenes/pi_loop_osc.scn --csv "$W/ref.csv" > "$W/ref.out" 2>&1
[ -s "$W/ref.csv" ] || bad "pi_loop_osc.scn did not run: $(cat "$W/ref.out")"

for v in 2 3; do
    # the scene runs a copy of the FMU, so that the replay below can find it replaced
    mkdir -p "$W/fmu$v" && cp "$FMUS/oscillator$v.fmu" "$W/fmu$v/"
    sed "s#@V@#$v#g; s#@FMUS@#$(cd "$W/fmu$v" && pwd)#g" tests/fmi/scenes/pi_link_fmu.scn \
        > "$W/pi_link_fmu$v.scn"
    start
    "$M" run "$W/pi_link_fmu$v.scn" --link "udp:127.0.0.1:$PORT" --record "$W/live$v.mrl" \
        --csv "$W/live$v.csv" > "$W/live$v.out" 2>&1
    rc=$?
    stop
    if [ $rc -eq 0 ] && grep -q '^status: ok$' "$W/live$v.out" &&
       [ "$(field link_applied "$W/live$v.out")" = 301 ]; then
        ok "FMI $v.0 plant under the link's controller: status ok, 301 answers applied"
    else bad "FMI $v.0 plant under the link's controller: exit $rc"; cat "$W/live$v.out"; fi
    # the trace against the in-scene loop, value for value (the time column aside)
    if [ -s "$W/live$v.csv" ] &&
       [ "$(tail -n +2 "$W/live$v.csv" | cut -d, -f2-)" = "$(tail -n +2 "$W/ref.csv" | cut -d, -f2-)" ]
    then ok "FMI $v.0 plant in the loop: the trace of the in-scene loop, value for value"
    else bad "FMI $v.0 plant in the loop: the trace differs from pi_loop_osc.scn's"; fi
    h=$(field hash "$W/live$v.out")
    rh=$("$M" replay "$W/live$v.mrl" 2>&1 | sed -n 's/^hash: //p')
    if [ -n "$h" ] && [ "$rh" = "$h" ]; then ok "FMI $v.0 plant in the loop: replay of the log = live hash $h"
    else bad "FMI $v.0 plant in the loop: replay hash '$rh', live '$h'"; fi
    o=$((v ^ 1)) # 2 <-> 3
    cp "$FMUS/oscillator$o.fmu" "$W/fmu$v/oscillator$v.fmu"
    "$M" replay "$W/live$v.mrl" > "$W/swap$v.out" 2>&1
    rc=$?
    if [ $rc -ne 0 ] && [ "$(wc -l < "$W/swap$v.out")" -eq 1 ] &&
       grep -q 'fingerprint' "$W/swap$v.out"; then
        ok "FMI $v.0 plant in the loop: the log refused once the FMU is replaced: $(cat "$W/swap$v.out")"
    else bad "FMI $v.0 plant in the loop: replay with the FMU replaced: exit $rc"; cat "$W/swap$v.out"; fi
done

echo "fmi-link: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
