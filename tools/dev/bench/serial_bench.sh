#!/bin/sh
# serial_bench.sh - the serial link's figures of docs/link.md ("Over a serial line:
# figures"): pi_link in lock-step (301 exchanges, 2 values out and 1 back each) over UDP
# loopback, over a pty, over a line paced at 115,200 and 921,600 baud (8N1, by
# tests/link/serial_noise.py --baud), each with the C example controller, then with the
# controller firmware on a Cortex-M4F in QEMU (UART0 on a pty) directly and behind the
# paced line. Round trip p50 / p99 / max from modrt's summary; the bytes per exchange and
# the highest exchange rate each line allows, from the frame sizes. Wall-clock figures of a
# shared machine: printed and kept in build/bench/serial.txt, never asserted.
# Usage: sh tools/dev/bench/serial_bench.sh [MODRT]
set -u
M=${1:-build/host/modrt}
C=build/host/pi_controller
FW=build/m4f/pi_firmware.elf
O=build/bench
mkdir -p $O
pids=""
cleanup() { for p in $pids; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done; pids=""; }
trap cleanup EXIT
waitfor() { # FILE PATTERN: the helper's line, at most 10 s
    i=0
    while [ $i -lt 100 ]; do
        v=$(sed -n "s/^$2 //p" "$1"); [ -n "$v" ] && { echo "$v"; return 0; }
        sleep 0.1; i=$((i + 1))
    done
    return 1
}
# row LABEL SUMMARY: one table row from a run's summary
row() {
    rtt=$(sed -n 's/^link_rtt_us: p50 \([0-9.]*\) p99 \([0-9.]*\) max \([0-9.]*\)/\1 \2 \3/p' "$2")
    set -- "$1" $rtt "$(sed -n 's/^link_applied: //p' "$2")" "$(sed -n 's/^hash: //p' "$2")"
    printf '| %s | %s | %s | %s | %s | %s |\n' "$1" "$2" "$3" "$4" "$5" "$6"
}
# relay BAUD [DEVICE]: a paced line; its plant end in $PLANT, its controller end in $CTLDEV
relay() {
    : > $O/relay.out
    timeout 120 python3 tests/link/serial_noise.py --idle 3 --baud "$1" ${2:+--controller-dev "$2"} \
        > $O/relay.out 2>&1 &
    RELAY=$!; pids="$pids $RELAY"
    PLANT=$(waitfor $O/relay.out plant)
    CTLDEV=${2:-$(waitfor $O/relay.out controller)}
}
# qemu: the controller firmware on an M4F, UART0 on a pty ($QPTY)
qemu() {
    : > $O/qemu.out
    timeout 120 qemu-system-arm -M mps2-an386 -display none -monitor none -chardev pty,id=u0 \
        -serial chardev:u0 -chardev stdio,id=sh0 \
        -semihosting-config enable=on,target=native,chardev=sh0 -kernel $FW > $O/qemu.out 2>&1 &
    QEMU=$!; pids="$pids $QEMU"
    i=0 QPTY=
    while [ $i -lt 100 ] && [ -z "$QPTY" ]; do
        QPTY=$(sed -n 's/.*redirected to \(\/dev\/pts\/[0-9]*\).*/\1/p' $O/qemu.out)
        sleep 0.1; i=$((i + 1))
    done
}
run() { # OUT SPEC: pi_link in lock-step over SPEC
    $M run pi_link --link "$2" --link-timeout 20 > "$1" 2>&1
}

{
    # when and what was measured (docs/link.md's line): wall-clock figures hold for that
    # machine and day
    echo "Figures of commit \`$(git rev-parse --short HEAD 2>/dev/null || echo unknown)\`, measured $(date -u +%Y-%m-%d) on $(nproc) cores of $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)"
    echo "== pi_link in lock-step, 301 exchanges; round trip [us] from modrt's summary"
    echo "| link | p50 | p99 | max | applied | hash |"
    echo "|---|---:|---:|---:|---:|---|"
    timeout 60 $C 0 3 > $O/udp_ctl.out 2>&1 &
    pids="$pids $!"
    run $O/s_udp.out "udp:127.0.0.1:$(waitfor $O/udp_ctl.out port)"
    row "UDP loopback, C controller" $O/s_udp.out
    timeout 60 $C serial:pty 3 > $O/pty_ctl.out 2>&1 &
    pids="$pids $!"
    run $O/s_pty.out "serial:$(waitfor $O/pty_ctl.out pty)"
    row "pty, C controller" $O/s_pty.out
    for b in 115200 921600; do
        relay $b
        timeout 60 $C "serial:$CTLDEV" 3 > $O/ctl_$b.out 2>&1 &
        pids="$pids $!"
        run $O/s_line_$b.out "serial:$PLANT:$b"
        row "line at $b baud (paced pty), C controller" $O/s_line_$b.out
        cleanup
    done
    if [ -f $FW ] && command -v qemu-system-arm > /dev/null; then
        qemu
        run $O/s_qemu.out "serial:$QPTY"
        row "pty to QEMU M4F firmware (QEMU does not pace its UART)" $O/s_qemu.out
        cleanup
        for b in 115200 921600; do
            qemu
            relay $b "$QPTY"
            run $O/s_qemu_$b.out "serial:$PLANT:$b"
            row "line at $b baud to QEMU M4F firmware" $O/s_qemu_$b.out
            cleanup
        done
    else
        echo "(QEMU or $FW missing: the firmware rows are skipped)"
    fi
    echo
    echo "== what each line allows (frame sizes: docs/link.md; 8N1: 10 bits a byte)"
    hdr=$(sed -n 's/^#define LINK_HEADER \([0-9]*\).*/\1/p' ports/common/link_wire.h)
    awk -v hdr="$hdr" 'BEGIN {
        nexp = 2; nimp = 1
        q = hdr + 8 * nexp + 4; a = hdr + 8 * nimp + 4
        fq = q + 1 + int((q + 1) / 254) + 1 + 2; fa = a + 1 + int((a + 1) / 254) + 1 + 2
        printf "values per exchange: %d out, %d back; bytes: datagrams %d + %d, on the line %d + %d = %d\n", nexp, nimp, q, a, fq, fa, fq + fa
        printf "| baud | line time of one exchange [ms] | highest rate lock-step [Hz] | highest rate real time [Hz] |\n|---:|---:|---:|---:|\n"
        n = split("115200 921600", b, " ")
        for (i = 1; i <= n; i++)
            printf "| %d | %.2f | %.0f | %.0f |\n", b[i], 1e3 * 10 * (fq + fa) / b[i], b[i] / 10 / (fq + fa), b[i] / 10 / fq
    }'
} | tee $O/serial.txt
