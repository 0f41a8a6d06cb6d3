#!/bin/sh
# serial_qemu.sh - the controller link over a serial line with one side on an emulated
# Cortex-M (docs/link.md, "Over a serial line"), its UART0 on a QEMU pty:
#  1. the controller on the board: tools/examples/pi_firmware.c (the PI of pi_loop written
#     with the client library ports/common/linkclient.c) closes pi_link run by
#     `modrt run --link serial:PTY` in lock-step: trace and hash equal pi_loop's, and the
#     recorded log replays to the same hash; so does the firmware main loop printed in
#     docs/link.md, extracted from the page and built as it stands; and the firmware
#     behind a noisy line (garbage, a lost byte, a flipped bit, each way) keeps that hash;
#  2. the plant on the board: `make image TARGET=<t> SCENE=pi_link` (the link on the
#     UART, ports/common/image_link.c) against the C example controller in serial mode on
#     the host: the image's hash is the host run of pi_loop's, nothing bad or missing;
#  3. the same image in real time: every request answered or counted missing, none bad.
# Every QEMU and controller runs under `timeout`, talks only over its pty and is stopped
# by this script by its PID. Generous timeouts: a loaded machine makes it slower, never
# wrong (lock-step). Usage: sh tests/link/serial_qemu.sh TARGET (m3, m4f or m7)
set -u
t=${1:-m4f}
M=build/host/modrt
C=build/host/pi_controller
T=build/test-serial-qemu
mkdir -p $T
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL serial-qemu: $*"; }
field() { sed -n "s/^$1: //p" "$2"; }
pids=""
cleanup() { for p in $pids; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done; pids=""; }
trap cleanup EXIT
case $t in
m3) machine=mps2-an385 ;; m4f) machine=mps2-an386 ;; m7) machine=mps2-an500 ;;
*) echo "serial-qemu: target $t has no link UART (m3, m4f, m7)"; exit 2 ;;
esac

# qemu ELF: the board with UART0 on a new pty (its path in $PTY), console by semihosting
qemu() {
    : > $T/qemu.out
    timeout 300 qemu-system-arm -M $machine -display none -monitor none \
        -chardev pty,id=u0 -serial chardev:u0 -chardev stdio,id=sh0 \
        -semihosting-config enable=on,target=native,chardev=sh0 -kernel "$1" \
        > $T/qemu.out 2>&1 &
    QEMU=$!; pids="$pids $QEMU"
    i=0 PTY=
    while [ $i -lt 100 ] && [ -z "$PTY" ]; do
        PTY=$(sed -n 's/.*redirected to \(\/dev\/pts\/[0-9]*\).*/\1/p' $T/qemu.out)
        sleep 0.1; i=$((i + 1))
    done
    [ -n "$PTY" ] || bad "QEMU made no pty: $(cat $T/qemu.out)"
}

$M run pi_loop --csv $T/loop.csv > $T/loop.out
loop_hash=$(field hash $T/loop.out)
[ -n "$loop_hash" ] || bad "pi_loop printed no hash: every comparison with it would be empty"

# controller ELF LABEL: the controller firmware ELF in QEMU, the plant on the host
controller() {
    qemu "$1"
    $M run pi_link --link "serial:$PTY:115200" --link-timeout 30 --record $T/fw.mrl \
        --csv $T/fw.csv > $T/fw.out; rc=$?
    kill $QEMU 2>/dev/null; wait $QEMU 2>/dev/null
    h=$(field hash $T/fw.out)
    [ $rc -eq 0 ] && [ "$(field link_applied $T/fw.out)" = 301 ] &&
        [ "$(field link_bad $T/fw.out)" = 0 ] && ok ||
        bad "$2 on $t: exit $rc, $(grep '^link_' $T/fw.out | tr '\n' ' ')"
    [ "$h" = "$loop_hash" ] && ok || bad "$2 on $t: hash $h, pi_loop's $loop_hash"
    [ "$(tail -n +2 $T/fw.csv | cut -d, -f2-)" = "$(tail -n +2 $T/loop.csv | cut -d, -f2-)" ] &&
        ok || bad "$2 on $t: the trace differs from pi_loop's"
    rh=$($M replay $T/fw.mrl | sed -n 's/^hash: //p')
    [ "$rh" = "$h" ] && ok || bad "$2 on $t: replay $rh, live $h"
    echo "serial-qemu: $2 on $t: hash $h = pi_loop = replay; $(grep link_rtt_us $T/fw.out)"
}
controller build/$t/pi_firmware.elf "controller firmware"

# 1a. the firmware behind a noisy line (tests/link/serial_noise.py between modrt and the
# board's pty): the plant counts the four spoiling faults of the answers, the firmware's
# client library drops the requests' and answers the repeats from its copy; pi_loop's hash
qemu build/$t/pi_firmware.elf
: > $T/noise.out
faults='req:20=garbage,40=drop,60=flip,80=inside,100=delim'
faults="$faults;ans:30=garbage,50=drop,70=flip,90=inside,110=delim"
timeout 300 python3 tests/link/serial_noise.py --idle 5 --controller-dev "$PTY" \
    --faults "$faults" > $T/noise.out 2>&1 &
RELAY=$!; pids="$pids $RELAY"
i=0 plant=
while [ $i -lt 100 ] && [ -z "$plant" ]; do
    plant=$(sed -n 's/^plant //p' $T/noise.out); sleep 0.1; i=$((i + 1))
done
$M run pi_link --link "serial:$plant" --link-timeout 10 > $T/noisy.out; rc=$?
kill $RELAY $QEMU 2>/dev/null; wait $RELAY $QEMU 2>/dev/null
[ $rc -eq 1 ] && [ "$(field hash $T/noisy.out)" = "$loop_hash" ] &&
    [ "$(field link_bad $T/noisy.out)" = 4 ] && [ "$(field link_missing $T/noisy.out)" = 0 ] &&
    ok || bad "firmware on $t behind a noisy line: exit $rc," \
        "$(grep '^\(hash\|link_\)' $T/noisy.out | tr '\n' ' ')"
echo "serial-qemu: firmware on $t behind a noisy line: hash = pi_loop;" \
    "$(grep '^link_\(bad\|resent\|dup\)' $T/noisy.out | tr '\n' ' ')"

# 1b. the main loop of docs/link.md, as printed there
awk '/^### A controller on a microcontroller/ { s = 1 } s && /^```c$/ { c = 1; next }
     c && /^```$/ { exit } c { print }' docs/link.md > $T/doc_fw.c
# shellcheck disable=SC2046 # the flag lists are meant to split
if [ -s $T/doc_fw.c ] && $(make -s print-TARGET_CC_$t) $(make -s print-CSTD) -O2 -Iports \
    $(make -s print-TARGET_CFLAGS_$t) $T/doc_fw.c ports/common/linkclient.c \
    ports/common/linkframe.c ports/common/link_wire.c ports/common/link_hmac.c \
    ports/cortex-m/uart.c \
    $(make -s print-TARGET_PORT_SRCS_$t) $(make -s print-TARGET_LDFLAGS_$t) -o $T/doc_fw.elf \
    > $T/doc_fw.log 2>&1; then
    ok; controller $T/doc_fw.elf "the firmware of docs/link.md"
else
    bad "the firmware main loop of docs/link.md does not build: $(head -5 $T/doc_fw.log)"
fi

# 2. the plant image in QEMU, the controller on the host
sh tools/image.sh $t pi_link "" "-DRT_IMAGE_LINK_TIMEOUT_US=20000000" "" "" 0 > $T/image.out 2>&1 ||
    bad "make image TARGET=$t SCENE=pi_link: $(cat $T/image.out)"
qemu build/image/$t/pi_link.elf
timeout 300 $C "serial:$PTY:115200" 60 > $T/ctl.out 2>&1 &
CTL=$!; pids="$pids $CTL"
wait $QEMU; rc=$?
kill $CTL 2>/dev/null; wait $CTL 2>/dev/null
line=$(grep '^rt scene pi_link' $T/qemu.out)
h=$(echo "$line" | sed -n 's/.* hash \([0-9a-f]*\).*/\1/p')
[ $rc -eq 0 ] && [ "$h" = "$loop_hash" ] && ok ||
    bad "plant on $t: exit $rc, hash $h: $(cat $T/qemu.out)"
echo "$line" | grep -q ' link_applied 301 link_bad 0 link_late 0 link_missing 0 ' && ok ||
    bad "plant on $t: $line"
counts=$(echo "$line" | sed 's/.*overruns 0//; s/ hash.*//')
echo "serial-qemu: plant image on $t: hash $h = pi_loop;$counts"

# 3. the plant image in real time (the timer paces the ticks, an answer is applied at the
# first tick after it arrived): whatever the timing, every answer is checked and counted
# and each request is either answered or counted missing (the last one's answer is never
# applied); the trace depends on the timing, so no hash is compared. Some answer must
# arrive, applied or counted late: on a loaded machine every one may come late (all 300
# late, none applied, was seen), which is the timing, not the link
sh tools/image.sh $t pi_link "" "-DRT_IMAGE_LINK_REALTIME=1" "" "" 0 > $T/image_rt.out 2>&1 &&
    cp build/image/$t/pi_link.elf $T/pi_link_rt.elf ||
    bad "make image TARGET=$t SCENE=pi_link (real time): $(cat $T/image_rt.out)"
qemu $T/pi_link_rt.elf
timeout 300 $C "serial:$PTY:115200" 60 > $T/ctl_rt.out 2>&1 &
CTL=$!; pids="$pids $CTL"
wait $QEMU
kill $CTL 2>/dev/null; wait $CTL 2>/dev/null
line=$(grep '^rt scene pi_link' $T/qemu.out)
num() { echo "$line" | sed -n "s/.* $1 \([0-9]*\).*/\1/p"; }
sent=$(num link_sent) applied=$(num link_applied) missing=$(num link_missing)
late=$(num link_late)
if [ "$(num ticks)" = 3000 ] && [ "$(num link_bad)" = 0 ] && [ "${sent:-0}" = 301 ] &&
    [ $((${applied:-0} + ${late:-0})) -ge 1 ] && [ $((applied + missing)) -ge 300 ] &&
    [ $((applied + missing)) -le 301 ]; then ok
else bad "plant on $t in real time: $(cat $T/qemu.out)"; fi
echo "serial-qemu: plant image on $t in real time: sent $sent, applied $applied, late $late, missing $missing"

cleanup
echo "serial-qemu: $pass passed, $fail failed"
[ $fail -eq 0 ]
