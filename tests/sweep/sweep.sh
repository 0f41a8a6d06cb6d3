#!/bin/sh
# sweep.sh - tests of `modrt sweep` (tools/modrt/sweep*.c, docs/sweeps.md): every metric
# against its closed form, the Monte-Carlo draws against their distributions, run k's
# line independent of the others, located errors, failed and timed-out runs as rows, and
# one campaign run three ways - local --jobs 2, GNU parallel, a Slurm array job on a
# single-node cluster this script starts and stops (slurmctld, slurmd, munged, by PID,
# loopback, config in a temporary directory, every daemon under `timeout`) - whose merged
# CSVs must be identical. An engine that is not installed or cannot start here is named
# with the reason, and the rest still runs.
# Usage: sh tests/sweep/sweep.sh BUILD_DIR
set -u
B=${1:-build/host}
M=$(cd "$B" && pwd)/modrt
D=$(cd "$(dirname "$0")" && pwd)
T=$(mktemp -d)
pids=""
cleanup() {
    for p in $pids; do kill "$p" 2>/dev/null; done
    for p in $pids; do i=0; while kill -0 "$p" 2>/dev/null && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done; done
    rm -rf "$T"
}
trap cleanup EXIT
pass=0 fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL sweep: $*"; }

# ---- metrics against closed forms (tests/sweep/metrics.scn says which) ----
$M sweep run "$D/metrics.swp" --out "$T/met" --jobs 1 2>/dev/null || bad "the metrics run failed"
R=$T/met/runs/000000.txt
grep -q '^status: ok$' "$R" && ok || bad "metrics run status: $(grep status "$R")"
# every metric against its closed form: NAME, the closed form (python), the tolerance
python3 - "$R" <<'EOF' || fail=$((fail + 1))
import math, sys
got = dict(l.split(": ", 1) for l in open(sys.argv[1]).read().splitlines() if ": " in l)
zeta = 0.3
over = math.exp(-math.pi * zeta / math.sqrt(1 - zeta * zeta))
# the servo's closed form y = 1 - exp(-zeta w t) (cos wd t + zeta/sqrt(1-zeta^2) sin wd t)
# at the ticks: it settles at the tick after the last one outside the band (the margin
# to the band's edges at the ticks is far above the integration error)
w, wd = 10, 10 * math.sqrt(1 - zeta * zeta)
y = [1 - math.exp(-zeta * w * k / 1000) * (math.cos(wd * k / 1000) + zeta /
     math.sqrt(1 - zeta * zeta) * math.sin(wd * k / 1000)) for k in range(2001)]
last_out = max(k for k in range(2001) if abs(y[k] - 1) > 0.02)
assert min(abs(abs(v - 1) - 0.02) for v in y) > 1e-7
checks = [
    ("servo_settle", (last_out + 1) / 1000, 1e-9),
    # first-order lag y = 1 - exp(-t/0.5): enters [0.98, 1.02] at T ln 50, seen at the
    # next tick (1 ms)
    ("lag_settle", 0.5 * math.log(50) + 0.0005, 0.0005),
    ("lag_settle_late", 0.5 * math.log(50) - 0.5 + 0.0005, 0.0005),
    ("lag_final", 1 - math.exp(-4), 1e-9),
    # from between ticks: the samples from the next tick on (1 ms), not the one before
    ("lag_min_off", 1 - math.exp(-0.002), 1e-9),
    ("lag_over", 0, 0),
    # over time, not per sample: (1/2) int_0^2 y dt and its RMS; the trapezoid's error is
    # below 2 h^2 max|f''| / 12 / 2 < 1e-6 (a rectangle rule's would be 2.5e-4)
    ("lag_mean", 0.5 * (2 - 0.5 * (1 - math.exp(-4))), 1e-6),
    ("lag_rms", math.sqrt(0.5 * (2 - 2 * 0.5 * (1 - math.exp(-4)) + 0.25 * (1 - math.exp(-8)))), 1e-6),
    # second-order servo: the peak falls between ticks; the sampled maximum is below it
    # by at most |y''| (dt/2)^2 / 2 < 5e-6
    ("servo_over", over - 2.5e-6, 2.5e-6),
    ("servo_max", 1 + over - 2.5e-6, 2.5e-6),
    # sines of 1 Hz over two periods: extremes at ticks; RMS over time (trapezoid: exact
    # for whole periods), not over samples (that would be 2 sqrt(1000/2001))
    ("s1_max", 2, 1e-12), ("s1_min", -2, 1e-12), ("s1_maxabs", 2, 1e-12),
    ("s1_rms", math.sqrt(2), 1e-12), ("s1_mean", 0, 1e-12),
    ("s1_rms_late", math.sqrt(2), 1e-12),
    ("diff_max", 1.5, 1e-12), ("diff_rms", 1.5 / math.sqrt(2), 1e-12),
]
bad = 0
for name, want, tol in checks:
    v = float(got.get("metric." + name, "nan"))
    if not abs(v - want) <= tol:
        print(f"FAIL sweep: metric {name} = {v}, closed form {want} (tolerance {tol})")
        bad += 1
print(f"{len(checks) - bad} passed, 0 failed")
sys.exit(1 if bad else 0)
EOF

# ---- the draws: in their bounds, with their distributions' moments ----
cat > "$T/draws.swp" <<'EOF'
scene (pi_loop);
seed (7);
draws (4000);
draw (Plant.K) uniform (1, 3);
draw (Plant.T) loguniform (0.01, 100);
draw (PI.Kp) normal (1, 0.1) within (0.8, 1.3);
EOF
$M sweep plan "$T/draws.swp" --out "$T/dr" > "$T/plan" 2>"$T/err" && ok || bad "plan: $(cat "$T/err")"
[ "$(wc -l < "$T/plan")" -eq 4000 ] && ok || bad "plan: $(wc -l < "$T/plan") lines, not 4000"
python3 - "$T/plan" <<'EOF' && ok || bad "the draws do not follow their distributions"
import math, re, sys
from statistics import NormalDist
v = {"Plant.K": [], "Plant.T": [], "PI.Kp": []}
for line in open(sys.argv[1]):
    for k, x in re.findall(r"--set (\S+)=(\S+)", line):
        v[k].append(float(x))
def ks(xs, cdf):  # Kolmogorov-Smirnov distance of the sample to cdf
    xs = sorted(xs); n = len(xs)
    return max(max((i + 1) / n - cdf(x), cdf(x) - i / n) for i, x in enumerate(xs))
crit = 1.95 / math.sqrt(4000)  # 0.1 % level
nd = NormalDist(1, 0.1); lo, hi = nd.cdf(0.8), nd.cdf(1.3)
checks = [
    all(1 <= x <= 3 for x in v["Plant.K"]), all(0.01 <= x <= 100 for x in v["Plant.T"]),
    all(0.8 <= x <= 1.3 for x in v["PI.Kp"]),
    ks(v["Plant.K"], lambda x: (x - 1) / 2) < crit,
    ks(v["Plant.T"], lambda x: (math.log10(x) + 2) / 4) < crit,
    ks(v["PI.Kp"], lambda x: (nd.cdf(x) - lo) / (hi - lo)) < crit,
]
if not all(checks):
    print("draw checks:", checks); sys.exit(1)
EOF
# run k's line depends on k alone: alone, in the full list, and with the draws reordered
sed -n 1235p "$T/plan" > "$T/one.a"
$M sweep plan "$T/draws.swp" --out "$T/dr" --index 1234 --count 1 > "$T/one.b"
cmp -s "$T/one.a" "$T/one.b" && ok || bad "line 1234 alone differs from the full plan's"
awk '/Plant.K/ { k = $0; next } { print } /Plant.T/ { print k }' "$T/draws.swp" > "$T/re.swp"
$M sweep plan "$T/re.swp" --out "$T/dr" --index 1234 --count 1 | sed "s|$T/re.swp|$T/draws.swp|" > "$T/one.c"
python3 - "$T/one.b" "$T/one.c" <<'EOF' && ok || bad "reordering the draws changed run 1234's values"
import re, sys
a, b = (sorted(re.findall(r"--set (\S+)", open(f).read())) for f in sys.argv[1:])
sys.exit(0 if a == b and a else 1)
EOF
sed 's/seed (7)/seed (8)/' "$T/draws.swp" > "$T/s8.swp"
[ "$($M sweep plan "$T/s8.swp" --out "$T/dr" --index 0 --count 1 | cut -f2- | sed 's/.*--index 0//')" != \
  "$(head -1 "$T/plan" | cut -f2- | sed 's/.*--index 0//')" ] && ok || bad "another seed drew the same values"
# 100 000 runs stream (the count, the last index)
cat > "$T/big.swp" <<'EOF'
scene (pi_loop);
draws (1000);
grid (PI.Kp) range (0.5, 1.5, 100);
draw (Plant.K) uniform (1.6, 2.4);
EOF
$M sweep plan "$T/big.swp" --out "$T/big" | awk -F'\t' 'END { print NR, $1 }' > "$T/bigcount"
[ "$(cat "$T/bigcount")" = "100000 99999" ] && ok || bad "100 000-run plan: $(cat "$T/bigcount")"

# the example of docs/sweeps.md plans its 1000 runs
[ "$($M sweep plan "$D/../../docs/sweeps/pi_loop_mc.swp" --out "$T/doc" | wc -l)" -eq 1000 ] && ok || \
    bad "docs/sweeps/pi_loop_mc.swp does not plan 1000 runs"

# ---- located errors ----
# expect_err NAME PATTERN CAMPAIGN-TEXT: plan fails with exit 2 and one line matching
expect_err() {
    printf '%s\n' "$3" > "$T/bad.swp"
    $M sweep plan "$T/bad.swp" --out "$T/bad" > /dev/null 2> "$T/err"; rc=$?
    if [ $rc -ne 2 ] || [ "$(wc -l < "$T/err")" -ne 1 ] || ! grep -q -- "$2" "$T/err"; then
        bad "$1: exit $rc, stderr: $(cat "$T/err")"; else ok; fi
}
expect_err "unknown statement" "bad.swp:2:1: error: unknown statement near 'grdi'" \
    "scene (pi_loop);
grdi (PI.Kp) values (1);"
expect_err "normal without bounds" "bad.swp:1:46: error: a normal draw needs its bounds: within (lo, hi) near ';'" \
    "scene (pi_loop); draw (PI.Kp) normal (1, 0.1);"
expect_err "bounds holding nothing" "bad.swp:1:47: error: the bounds hold less than 0.01 of the normal's probability near 'within'" \
    "scene (pi_loop); draw (PI.Kp) normal (1, 0.1) within (5, 6); draws (2);"
expect_err "no draws count" "error: variables are drawn but the campaign says not how often" \
    "scene (pi_loop); draw (PI.Kp) uniform (1, 2);"
expect_err "unrecorded signal" "bad.swp:2:27: error: scene pi_loop records no signal 'Plant.z' (it records: Ref.y, PI.c, Plant.y)" \
    "scene (pi_loop);
metric (m) max (Plant.y - Plant.z);"
expect_err "unterminated string" "bad.swp:1:8: error: string without its closing quote" \
    "scene (\"x.scn);"
expect_err "bad range" "bad.swp:1:31: error: range (lo, hi, n) needs a whole n >= 2" \
    "scene (pi_loop); grid (PI.Kp) range (1, 2, 1.5);"
expect_err "unknown block" "bad.swp:1:24: error: scene pi_loop has no block 'Plnt'" \
    "scene (pi_loop); grid (Plnt.K) values (1, 2);"
expect_err "unknown parameter" "bad.swp:2:7: error: scene pi_loop has no parameter or state 'Plant.KK'" \
    "scene (pi_loop); draws (3);
draw (Plant.KK) uniform (1, 2);"
expect_err "a listed value out of range" "bad.swp:1:24: error: scene pi_loop refuses Plant.T = -1 (out of the parameter's range)" \
    "scene (pi_loop); grid (Plant.T) values (0.5, -1);"
expect_err "no scene" "error: the campaign names no scene" "seed (1);"

# ---- failed and timed-out runs are rows; --only-missing completes a table ----
# (pendulum10 for 5000 s is minutes of CPU on any machine: it cannot end in 50 ms)
cat > "$T/slow.swp" <<'EOF'
scene (pendulum10);
end time (5000 s);
timeout (50 ms);
grid (B1.m) values (1, 2);
EOF
$M sweep run "$T/slow.swp" --out "$T/slow" -j 2 2>/dev/null
$M sweep collect "$T/slow" > /dev/null 2>&1
[ "$(cut -d, -f2 "$T/slow/results.csv" | tail -n +2 | sort -u)" = timeout ] && ok || \
    bad "timed-out runs: $(cat "$T/slow/results.csv")"

# results of an earlier version of a campaign are stale: collect refuses until the runs
# are redone, --only-missing redoes them
mkdir -p "$T/st" && cp "$D/metrics.swp" "$D/metrics.scn" "$T/st/"
$M sweep run "$T/st/metrics.swp" --out "$T/st/out" -j 1 2>/dev/null
echo 'metric (extra) max (Lag.y);' >> "$T/st/metrics.swp"
$M sweep collect "$T/st/out" > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q 'the campaign file has changed since sweep.info' "$T/err" && ok || \
    bad "collect after an edit of the campaign: exit $rc, $(cat "$T/err")"
$M sweep run "$T/st/metrics.swp" --out "$T/st/out" -j 1 --only-missing 2> "$T/err"
grep -q '^sweep: 1 of 1 runs' "$T/err" && ok || bad "--only-missing after an edit: $(cat "$T/err")"
$M sweep collect "$T/st/out" 2>/dev/null | grep -q '^missing_or_stale: 0$' && \
    grep -q '^metric.extra: ' "$T/st/out/runs/000000.txt" && ok || bad "the edited campaign's run was not redone"

# a run that dies by a signal (here SIGXCPU: one second of CPU time, inherited by the
# run's process; the supervisor sleeps) is a row "crashed" naming the signal
cat > "$T/crash.swp" <<'EOF'
scene (pendulum10);
end time (4000 s);
grid (B1.m) values (1);
EOF
(ulimit -t 1; exec $M sweep run "$T/crash.swp" --out "$T/crash" -j 1 2>/dev/null)
grep -q '^status: crashed$' "$T/crash/runs/000000.txt" && grep -q '^why: the run ended by signal' "$T/crash/runs/000000.txt" && ok || \
    bad "a run killed by a signal: $(cat "$T/crash/runs/000000.txt")"

# ---- the lane change's cone margin (docs/sweeps.md): the campaign cut to two draws;
# run 1's metric against tests/vehicles/vehicles.py's footprint check over its trace ----
[ "$($M sweep plan "$D/../../docs/sweeps/lane_change_mc.swp" --out "$T/doc" | wc -l)" -eq 400 ] && ok || \
    bad "docs/sweeps/lane_change_mc.swp does not plan 400 runs"
DS=$(cd "$D/../../docs/sweeps" && pwd)
sed -e 's/^draws (400);/draws (2);/' -e "s|^scene (\"|scene (\"$DS/|" "$DS/lane_change_mc.swp" > "$T/lc2.swp"
$M sweep run "$T/lc2.swp" --out "$T/lc" -j 2 2> "$T/err"
line=$($M sweep plan "$T/lc2.swp" --out "$T/lc1" --index 1 --count 1 | cut -f2-)
eval "$line --csv $T/lc1.csv" 2>> "$T/err"
python3 - "$T/lc/runs/000001.txt" "$T/lc1.csv" "$D/../vehicles" <<'PY' && ok || bad "the lane change's margin metric ($(head -c 300 "$T/err"))"
import csv, sys
sys.path.insert(0, sys.argv[3])
from vehicles import lane_margin
try:
    got = dict(l.split(": ", 1) for l in open(sys.argv[1]).read().splitlines())
    rows = list(csv.DictReader(open(sys.argv[2])))
    want = min(lane_margin(float(r["V1.x"]), float(r["V1.y"]), float(r["V1.psi"]), 20.0)
               for r in rows)
    m = float(got["metric.margin"])
except (OSError, KeyError, ValueError) as e:
    sys.exit("lane change campaign: %s" % e)
# the draw moved the margin off the nominal car's 0.1536 m, and the metric is the check's
if not (got["status"] == "ok" and abs(m - want) <= 1e-12 and abs(m - 0.1536) > 1e-4):
    sys.exit("lane change run 1: metric.margin %r, footprint check %r, status %s"
             % (m, want, got["status"]))
PY

# ---- a grid of scene files and the error against a reference table (make study) ----
# metrics.scn's lag by Euler at 1 and 2 ticks (the set's step, in two scene files) against
# its closed form 1 - exp(-t/T) at a few instants: Euler's y_n = 1 - (1 - h/T)^n; at 3 ms
# the table says 5 (no solution): the 1-tick run's error is its distance to 5 there, while
# 3 ms is no step of the 2-tick set, so that run leaves the instant out
for k in 1 2; do
    sed "s/^set (main) method (rk4) step (1 tick);/set (main) method (euler) step ($k tick);/" \
        "$D/metrics.scn" > "$T/lag$k.scn"
done
python3 -c 'import math
print("t,Lag.y")
for t in (0.003, 0.1, 0.5, 1.0, 2.0): print("%r,%r" % (t, 5 if t == 0.003 else 1 - math.exp(-t / 0.5)))' > "$T/lag_ref.csv"
printf '%s\n' 'grid scene values ("lag1.scn", "lag2.scn");' \
    'metric (err) error against ("lag_ref.csv");' > "$T/err.swp"
$M sweep run "$T/err.swp" --out "$T/errm" -j 2 2> "$T/err.txt"
python3 - "$T/errm/runs" <<'PY' && ok || bad "error against a reference over a grid of scenes ($(head -c 300 "$T/err.txt"))"
import math, sys
for k, h in ((0, 0.001), (1, 0.002)):
    try:
        got = dict(l.split(": ", 1) for l in open("%s/%06d.txt" % (sys.argv[1], k)).read().splitlines())
        v = float(got["metric.err"])
    except (OSError, KeyError, ValueError) as e:
        sys.exit("error metric run %d: %s" % (k, e))
    ts = [t for t in (0.003, 0.1, 0.5, 1.0, 2.0) if abs(t / h - round(t / h)) < 1e-9]
    want = max(abs(1 - (1 - h / 0.5) ** round(t / h) - (5 if t == 0.003 else 1 - math.exp(-t / 0.5)))
               for t in ts)
    if got.get("scene_file") != "lag%d.scn" % (k + 1) or not abs(v - want) <= 1e-12:
        sys.exit("error metric run %d (%s): %r, closed form %r" % (k, got.get("scene_file"), v, want))
PY
printf 't,Lag.z\n0.1,1\n' > "$T/lag_bad.csv"
sed 's/lag_ref.csv/lag_bad.csv/' "$T/err.swp" > "$T/bad_ref.swp"
$M sweep plan "$T/bad_ref.swp" --out "$T/bad_ref" > /dev/null 2> "$T/err.txt"; rc=$?
[ $rc -eq 2 ] && grep -q "lag_bad.csv:1: error: scene sweep_metrics records no signal: Lag.z" "$T/err.txt" && ok ||
    bad "a reference table naming an unrecorded signal: exit $rc, $(cat "$T/err.txt")"

# ---- replay runs: set up as `modrt replay` sets them up (tools/modrt/replay.c) ----
# pi_link without its controller (--link none: the command holds 0) decays from
# Plant.y = 1 as y' = -y/T; a log recorded with --method, --step and --set replays to the
# live run, and the campaign's method, applied after the log's, gives the closed form of
# that method's step: euler (1 - h/T)^n, heun (1 - h/T + (h/T)^2/2)^n, h = 2 ms, n = 250
cp "$D/../../models/scenes/pi_link.scn" "$T/pl.scn"
rec="--link none --t-end 0.5 --method main=euler --step main=0.002 --set Plant.y=1"
h_live=$($M run "$T/pl.scn" $rec --record "$T/opt.mrl" | sed -n 's/^hash: //p')
printf '%s\n' 'replay ("opt.mrl");' 'grid method (main) values (euler, heun);' \
    'metric (y_end) final (Plant.y);' > "$T/rp.swp"
$M sweep run "$T/rp.swp" --out "$T/rp" -j 1 2> "$T/err"
h_rp=$(sed -n 's/^hash: //p' "$T/rp/runs/000000.txt" 2>/dev/null)
[ -n "$h_live" ] && [ "$h_rp" = "$h_live" ] && ok ||
    bad "a replay run of a log with --method/--step/--set: hash '$h_rp', live '$h_live' ($(head -c 300 "$T/err"))"
python3 - "$T/rp/runs/000000.txt" "$T/rp/runs/000001.txt" <<'PY' && ok || bad "replay runs against the closed forms"
import sys
want = [(1 - 0.004) ** 250, (1 - 0.004 + 0.004 ** 2 / 2) ** 250]
for path, w in zip(sys.argv[1:], want):
    try:
        got = float(dict(l.split(": ", 1) for l in open(path).read().splitlines())["metric.y_end"])
    except (OSError, KeyError, ValueError) as e:
        sys.exit("replay run: %s: %s" % (path, e))
    if not abs(got - w) <= 1e-12 * w:
        sys.exit("replay run %s: y_end %r, closed form %r" % (path, got, w))
PY
# a log whose scene changed since is refused before any task, as modrt replay refuses it
sed 's/Plant.T = 0.5;/Plant.T = 0.6;/' "$T/pl.scn" > "$T/pl.new" && mv "$T/pl.new" "$T/pl.scn"
$M sweep plan "$T/rp.swp" --out "$T/rp2" > /dev/null 2> "$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q "opt.mrl: recorded with scene fingerprint .*: the scene changed since" "$T/err" && ok ||
    bad "a replay of a changed scene: exit $rc, $(cat "$T/err")"
# a log of a run ended by SIGTERM replays to the tick the run reached, as modrt replay
# does (its end marker names the tick), not on to the scene's end time (1e9 ticks here)
cp "$D/../../models/scenes/pi_loop.scn" "$T/pi.scn"
$M run "$T/pi.scn" --t-end 1e6 --record "$T/int.mrl" > "$T/live.txt" 2>&1 &
pid=$!
# stopped a second after the run has opened its log (not after a fixed time from the
# start: a loaded machine may not have started the run), waiting at most 60 s for it
for _ in $(seq 600); do
    [ -e "$T/int.mrl" ] && break; sleep 0.1
done
sleep 1; kill -TERM $pid; wait $pid
printf '%s\n' 'replay ("int.mrl");' 'metric (y_end) final (Plant.y);' > "$T/int.swp"
timeout 120 $M sweep run "$T/int.swp" --out "$T/int" -j 1 2> "$T/err"
h_int=$(sed -n 's/^hash: //p' "$T/live.txt") n_int=$(sed -n 's/^ticks: //p' "$T/live.txt")
[ -n "$h_int" ] && [ "$(sed -n 's/^hash: //p' "$T/int/runs/000000.txt" 2>/dev/null)" = "$h_int" ] &&
    [ "$(sed -n 's/^ticks: //p' "$T/int/runs/000000.txt")" = "$n_int" ] && ok ||
    bad "a replay run of an interrupted log: live $n_int ticks $h_int; run $(grep -E '^(ticks|hash)' "$T/int/runs/000000.txt" 2>/dev/null | tr '\n' ' ')"
# and ends as the live run ended and as modrt replay ends it: interrupted, exit 5
$M replay "$T/int.mrl" > "$T/replay.txt" 2>&1; rc=$?
grep -q '^status: interrupted$' "$T/live.txt" && grep -q '^status: interrupted$' "$T/replay.txt" &&
    [ $rc -eq 5 ] && grep -q '^status: interrupted$' "$T/int/runs/000000.txt" &&
    grep -q '^exit: 5$' "$T/int/runs/000000.txt" && ok ||
    bad "a replay run of an interrupted log: modrt replay exit $rc, $(grep '^status' "$T/replay.txt"); campaign $(grep -E '^(status|exit)' "$T/int/runs/000000.txt" 2>/dev/null | tr '\n' ' ')"

# ---- one campaign, three engines, identical CSVs ----
$M sweep run "$D/engines.swp" --out "$T/local" -j 2 2>/dev/null
$M sweep collect "$T/local" > "$T/local.out" 2>/dev/null
grep -q '^missing_or_stale: 0$' "$T/local.out" && ok || bad "local: $(cat "$T/local.out")"
[ "$(grep -c ',"non-finite value",' "$T/local/results.csv")" -eq 24 ] && ok || \
    bad "local: the failing tuning's 24 runs are not rows with their status"
rm "$T/local/runs/000003.txt" "$T/local/runs/000030.txt" "$T/local/runs/000047.txt"
$M sweep collect "$T/local" > "$T/miss.out" 2>/dev/null
[ "$(grep -c ',missing,' "$T/local/results.csv")" -eq 3 ] && ok || bad "3 deleted results are not 3 rows with status missing"
cp "$T/local/results.csv" "$T/with-missing.csv"
$M sweep run "$D/engines.swp" --out "$T/local" -j 2 --only-missing 2> "$T/om.err"
grep -q '^sweep: 3 of 48 runs' "$T/om.err" && ok || bad "--only-missing: $(cat "$T/om.err")"
$M sweep collect "$T/local" > /dev/null 2>&1
grep -q ',missing,' "$T/local/results.csv" && bad "--only-missing left rows missing" || ok

if command -v parallel > /dev/null; then
    $M sweep plan "$D/engines.swp" --out "$T/par" | cut -f2- | parallel --will-cite -j 2 2>/dev/null
    $M sweep collect "$T/par" > /dev/null 2>&1
    cmp -s "$T/local/results.csv" "$T/par/results.csv" && ok || bad "GNU parallel's CSV differs from the local one"
else
    echo "sweep: GNU parallel is not installed (sh tools/install-deps.sh): its engine not tested"
fi

. "$D/slurm.sh"
if slurm_up; then
    $M sweep slurm "$D/engines.swp" --out "$T/slurm-out" --per-task 6 > /dev/null 2>&1
    slurm_run "$T/slurm-out/sweep.sbatch"
    $M sweep collect "$T/slurm-out" > /dev/null 2>&1
    if [ -z "$(ls "$T/slurm-out/runs" 2>/dev/null)" ]; then
        # the cluster came up but launched nothing (a container without the privileges
        # slurmd needs): the environment, not the campaign; its logs say why
        echo "sweep: the single-node Slurm launched no task, its engine not tested:" \
             "$(tail -1 "$S/slurmd.log" 2>/dev/null)"
    else
        cmp -s "$T/local/results.csv" "$T/slurm-out/results.csv" && ok || bad "Slurm's CSV differs from the local one"
    fi
else
    echo "sweep: single-node Slurm could not start here, its engine not tested: $why"
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
