#!/bin/sh
# rt_bench.sh - the soft real-time figures of docs/link.md ("Real time on Linux"): a 1 kHz
# scene (pi_loop) for SECONDS (default 60) on the real-time clock, its wake-up latency,
# execution time and deadline misses; then the same with the Python example controller in
# the loop over loopback (pi_link), its round trip. Wall-clock figures of a shared machine:
# printed and kept in build/bench/rt.txt, never asserted.
set -u
M=${1:-build/host/modrt}
S=${2:-60}
O=build/bench
mkdir -p $O
{
    # when and what was measured (docs/link.md's line): wall-clock figures hold for that
    # machine and day
    echo "Figures of commit \`$(git rev-parse --short HEAD 2>/dev/null || echo unknown)\`, measured $(date -u +%Y-%m-%d) on $(nproc) cores of $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)"
    echo "== pi_loop, 1 kHz, $S s, real-time clock, no controller"
    $M run pi_loop --realtime --t-end "$S" --rt-log $O/rt_lat.csv |
        grep -E '^(ticks|status|overrun|rt_sched|latency_us|exec_us|deadline_misses|skipped|trace_dropped):'
    echo "== pi_link, 1 kHz (the PI sampled every 10 ms), $S s, Python controller over loopback"
    timeout $((S + 30)) python3 tools/examples/pi_controller.py --idle 5 > $O/ctl.out 2>&1 &
    CTL=$!
    PORT=
    for _ in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
        PORT=$(sed -n 's/^port //p' $O/ctl.out)
        [ -n "$PORT" ] && break
        sleep 0.1
    done
    $M run pi_link --realtime --t-end "$S" --link udp:127.0.0.1:$PORT |
        grep -E '^(ticks|status|link_rtt_us|link_applied|link_missing|link_late|latency_us|exec_us|deadline_misses):'
    kill $CTL 2>/dev/null; wait $CTL 2>/dev/null
} | tee $O/rt.txt
