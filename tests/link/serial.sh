#!/bin/sh
# serial.sh - the controller link over a serial line (docs/link.md, "Over a serial line"),
# on pseudo-terminals of this machine: the C example controller in serial mode (the client
# library of a firmware controller) closes pi_link run by `modrt run --link serial:...` in
# lock-step: the trace is pi_loop's value for value (the same PI law in the scene), hash
# included, and the log replays to it; in soft real time the log replays to the live run.
# Line noise between them (tests/link/serial_noise.py: garbage, a lost byte, a flipped bit,
# noise inside a frame, a lost delimiter, both ways): every fault is counted on the side
# that received it, nothing bad is applied, the lost exchanges are sent again and the
# trace is still pi_loop's. Bad --link specs are refused with one line. Every helper runs
# under `timeout`, talks only over its ptys and is stopped by this script by its PID; the
# lock-step timeouts are generous (a loaded machine makes a run slower, never different).
set -u
M=build/host/modrt
C=build/host/pi_controller
T=build/test-serial
mkdir -p $T
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL serial: $*"; }
field() { sed -n "s/^$1: //p" "$2"; }
pids=""
cleanup() { for p in $pids; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done; pids=""; }
trap cleanup EXIT

# waitfor FILE PATTERN: the helper's line (at most 10 s)
waitfor() {
    i=0
    while [ $i -lt 100 ]; do
        v=$(sed -n "s/^$2 //p" "$1")
        [ -n "$v" ] && { echo "$v"; return 0; }
        sleep 0.1; i=$((i + 1))
    done
    return 1
}
# controller DEVICE: the C example in serial mode on DEVICE (or serial:pty), idle exit 3 s
controller() {
    : > $T/ctl.out
    timeout 60 $C "serial:$1" 3 > $T/ctl.out 2>&1 &
    CTL=$!; pids="$pids $CTL"
}
stop_ctl() { kill $CTL 2>/dev/null; wait $CTL 2>/dev/null; }
ctl_count() { sed -n "s/.*$1 \([0-9]*\).*/\1/p" $T/ctl.out; }

$M run pi_loop --csv $T/loop.csv > $T/loop.out
loop_hash=$(field hash $T/loop.out)
[ -n "$loop_hash" ] || bad "pi_loop printed no hash: every comparison with it would be empty"
rows() { tail -n +2 "$1" | cut -d, -f2-; }   # a trace without its time column
same_trace() { [ "$(rows "$1")" = "$(rows $T/loop.csv)" ]; }

# 1. lock-step over a pty: pi_loop's trace and hash, replayed to the same hash
controller pty
pty=$(waitfor $T/ctl.out pty) || bad "the controller made no pty: $(cat $T/ctl.out)"
$M run pi_link --link "serial:$pty:921600" --link-timeout 30 --record $T/ls.mrl \
    --csv $T/ls.csv > $T/ls.out; rc=$?
sleep 0.2; stop_ctl
h=$(field hash $T/ls.out)
[ $rc -eq 0 ] && [ "$(field link_applied $T/ls.out)" = 301 ] &&
    [ "$(field link_bad $T/ls.out)" = 0 ] &&
    ok || bad "lock-step: exit $rc, $(grep '^link_' $T/ls.out | tr '\n' ' ')"
[ "$h" = "$loop_hash" ] && ok || bad "lock-step hash $h, pi_loop's $loop_hash"
same_trace $T/ls.csv && ok || bad "lock-step trace differs from pi_loop's"
rh=$($M replay $T/ls.mrl | sed -n 's/^hash: //p')
[ "$rh" = "$h" ] && ok || bad "replay of the serial log: $rh, live $h"
echo "serial: lock-step over a pty: hash $h = pi_loop = replay; $(grep link_rtt_us $T/ls.out)"

# 1b. the authenticated mode over a pty: both ends with the same key, pi_loop's hash
printf 'a shared key of the serial test\n' > $T/key
: > $T/ctl.out
timeout 60 $C serial:pty 3 $T/key > $T/ctl.out 2>&1 &
CTL=$!; pids="$pids $CTL"
pty=$(waitfor $T/ctl.out pty)
$M run pi_link --link "serial:$pty" --link-key $T/key --link-timeout 30 > $T/key.out; rc=$?
stop_ctl
[ $rc -eq 0 ] && [ "$(field hash $T/key.out)" = "$loop_hash" ] &&
    [ "$(field link_applied $T/key.out)" = 301 ] && ok ||
    bad "authenticated over a pty: exit $rc, $(grep '^\(hash\|link_\)' $T/key.out | tr '\n' ' ')"

# 2. soft real time over a pty: the log reproduces whatever the timing did
controller pty
pty=$(waitfor $T/ctl.out pty)
$M run pi_link --link "serial:$pty" --realtime --t-end 1 --record $T/rt.mrl > $T/rt.out; rc=$?
stop_ctl
h=$(field hash $T/rt.out)
rh=$($M replay $T/rt.mrl | sed -n 's/^hash: //p')
[ -n "$h" ] && [ "$rh" = "$h" ] && [ "$(field link_bad $T/rt.out)" = 0 ] && ok ||
    bad "real time: replay $rh, live $h (exit $rc)"
echo "serial: soft real time: applied $(field link_applied $T/rt.out) of" \
    "$(field link_sent $T/rt.out); replay hash = live"

# 3. line noise both ways: counted where received, resent, pi_loop's trace
req='20=garbage,40=drop,60=flip,80=inside,100=delim'
ans='30=garbage,50=drop,70=flip,90=inside,110=delim'
rm -f $T/noise.out
timeout 60 python3 tests/link/serial_noise.py --idle 2 --faults "req:$req;ans:$ans" \
    > $T/noise.out 2>&1 &
RELAY=$!; pids="$pids $RELAY"
plant=$(waitfor $T/noise.out plant) && ctl=$(waitfor $T/noise.out controller) ||
    bad "the noise relay did not start: $(cat $T/noise.out)"
controller "$ctl"
$M run pi_link --link "serial:$plant" --link-timeout 10 --record $T/noise.mrl --csv $T/noise.csv \
    > $T/noisy.out; rc=$?
wait $CTL 2>/dev/null # it prints its counts after 3 s without input
kill $RELAY 2>/dev/null; wait $RELAY 2>/dev/null
[ "$(field hash $T/noisy.out)" = "$loop_hash" ] && same_trace $T/noise.csv && ok ||
    bad "noise changed the trace: hash $(field hash $T/noisy.out)"
# the answers' four spoiling faults reach the plant, the requests' four the controller; the
# six lost frames and the two held back by a lost delimiter are sent again
[ "$(field link_bad $T/noisy.out)" = 4 ] && [ "$(field link_applied $T/noisy.out)" = 301 ] &&
    [ "$(field link_missing $T/noisy.out)" = 0 ] && [ "$(field link_resent $T/noisy.out)" -ge 8 ] &&
    ok || bad "plant counts: $(grep '^link_' $T/noisy.out | tr '\n' ' ')"
[ "$(ctl_count refused)" = 4 ] && [ "$(ctl_count answered)" = 301 ] && ok ||
    bad "controller counts: $(cat $T/ctl.out)"
[ $rc -eq 1 ] && ok || bad "a run that received broken frames exits $rc, not 1"
rh=$($M replay $T/noise.mrl | sed -n 's/^hash: //p')
[ "$rh" = "$loop_hash" ] && ok || bad "replay of the noisy run: $rh"
echo "serial: line noise: plant $(grep '^link_\(bad\|resent\|dup\)' $T/noisy.out | tr '\n' ' ')"
echo "serial: line noise: controller $(cat $T/ctl.out | tail -1)"

# 4. bad specs: one line saying what and where, exit 2
for spec in serial:/nonexistent/tty serial:/dev/null "serial:/dev/null:123" serial:; do
    out=$($M run pi_link --link "$spec" 2>&1); rc=$?
    if [ $rc -eq 2 ] && [ "$(echo "$out" | wc -l)" = 1 ]; then ok
    else bad "--link $spec: exit $rc: $out"; fi
done

cleanup
echo "serial: $pass passed, $fail failed"
[ $fail -eq 0 ]
