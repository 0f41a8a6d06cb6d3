#!/bin/sh
# cli.sh - tests of the host command line (tools/modrt/modrt.c): listing, info, runs,
# deterministic hashes, CSV output and one clear error line for every kind of bad input.
# Usage: sh tests/cli.sh BUILD_DIR
set -u
B=${1:-build/host}
M=$B/modrt
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0 fail=0

ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL cli: $*"; }

# expect_err "what" STATUS PATTERN -- command...: exit status and one stderr line matching
expect_err() {
    what=$1 want=$2 pat=$3; shift 3
    "$@" >"$T/out" 2>"$T/err"; rc=$?
    if [ "$rc" -ne "$want" ]; then bad "$what: exit $rc, expected $want"; return; fi
    if [ "$(wc -l <"$T/err")" -ne 1 ] || ! grep -q -- "$pat" "$T/err"; then
        bad "$what: stderr was: $(cat "$T/err")"; return; fi
    ok
}

hash_of() { grep '^hash: ' | sed 's/hash: //'; }

# list names every library scene
out=$($M list)
for s in oscillator vanderpol pi_loop bouncing_ball; do
    echo "$out" | grep -q "^$s " && ok || bad "list lacks $s"
done

# info shows order and loops
$M info pi_loop >"$T/info" && ok || bad "info pi_loop failed"
grep -q '^evaluation order: Plant Ref PI$' "$T/info" && ok || bad "info order: $(grep order "$T/info")"
grep -q 'potential: PI Plant; solved by ordering' "$T/info" && ok || bad "info lacks the potential loop"

# a run that ends inside a set's step says which values are not of its end time: the
# integrator's output held from 0.9 s, its state at 1.2 s (x = t: 0.9 and 1.2 recorded)
cat >"$T/end.scn" <<'SCN'
base tick (100 ms); end time (1 s);
define ss_system (I) with outputs (x) states (s = 0) by { x = s; der(s) = 1; };
load system (Q) of type (I);
set (main) method (rk4) step (300 ms);
record (Q.x, state Q.s);
SCN
$M run "$T/end.scn" --csv="$T/end.csv" >"$T/end.out" 2>&1
grep -q '^held_at_end.main: outputs from 0.90000000000000002 s, states at 1.2000000000000002 s$' \
    "$T/end.out" && ok || bad "held_at_end: $(grep -E 'held|status' "$T/end.out")"
tail -1 "$T/end.csv" | grep -q '^1,0.8999999999999999[0-9]*,1.2$' && ok ||
    bad "held_at_end record: $(tail -1 "$T/end.csv")"
$M run "$T/end.scn" --t-end=0.9 | grep -q '^held_at_end' && bad "held_at_end at 0.9 s" || ok

# --set values are judged as the scene's own: a point 0.5 m off its rods is refused
# (rt_init refuses it in a scene file), 0.5 mm off it is moved and counted; a friction
# mode against the velocity is refused
expect_err "set off joints" 2 "the initial state is refused: B3 starts 5.00e-01 m off its constraints" \
    $M run pendulum10 --set=B3.x=3.5
$M run pendulum10 --set=B3.x=3.0005 --t-end=0.01 | grep -q '^init_moved: 1 (last B3)' && ok ||
    bad "set near joints: $($M run pendulum10 --set=B3.x=3.0005 --t-end=0.01 2>&1 | grep -E 'status|init_moved')"
$M run pendulum10 --t-end=0.01 | grep -q '^init_moved: 0' && ok || bad "pendulum10 init_moved"
sed -e 's/M.v = -1; M.F = 0;/M.v = -1; M.mode = -1; M.F = 0;/' -e '/^\/\/ expect/d' \
    tests/scenec/errors/coulomb_mode.scn > "$T/coul.scn"
$M run "$T/coul.scn" | grep -q '^status: ok' && ok || bad "coulomb with its mode"
expect_err "set mode against v" 2 "mode must be +1 for v > 0 and -1 for v < 0" \
    $M run "$T/coul.scn" --set=M.v=1
# a loop whose scene value has no fixed point (y = u^2 / 4 + 5), set to one that has
# (c = 0.5: y = 2 - sqrt(2)): judged with the value set alone, status ok (before, the
# start's solve with the scene's value stayed counted, noconv 1, the run failed)
cat > "$T/loopset.scn" <<'SCN'
scene (loopset);
base tick (1 ms);
end time (0.05 s);
define ss_system (F) with inputs (u) outputs (y) parameters (c = 5, a = 0.25) by { y = a * u * u + c; };
load system (A) of type (F);
connect (A.y, A.u);
solve loops by (broyden);
set (main) method (rk4) step (10 ticks);
record (A.y);
SCN
$M run "$T/loopset.scn" | grep -q '^status: algebraic loop iteration did not converge' && ok ||
    bad "a loop without a fixed point: $($M run "$T/loopset.scn" | grep -E '^status|^noconv')"
$M run "$T/loopset.scn" --set=A.c=0.5 > "$T/loopset.out"
y0=$($M run "$T/loopset.scn" --set=A.c=0.5 --csv=- 2>/dev/null | sed -n '2p' | cut -d, -f2)
grep -q '^status: ok' "$T/loopset.out" && grep -q '^noconv: 0$' "$T/loopset.out" &&
    awk -v y="$y0" 'BEGIN { d = y - (2 - sqrt(2)); exit !(d < 1e-9 && d > -1e-9) }' && ok ||
    bad "a loop set to a fixed point: y(0) $y0, $(grep -E '^status|^noconv' "$T/loopset.out")"

# every scene runs clean, twice with the same 16-digit hash
for s in oscillator vanderpol pi_loop bouncing_ball; do
    h1=$($M run $s | hash_of); h2=$($M run $s | hash_of)
    echo "$h1" | grep -qE '^[0-9a-f]{16}$' && [ "$h1" = "$h2" ] && ok || bad "$s hash '$h1' vs '$h2'"
    $M run $s | grep -q '^status: ok$' && ok || bad "$s status not ok"
done

# the summary has the keys a script reads
$M run oscillator --t-end 0.5 >"$T/sum"
for k in ticks sim_time wall_s status hash; do
    grep -q "^$k: " "$T/sum" && ok || bad "summary lacks $k"
done
grep -q '^ticks: 500$' "$T/sum" && ok || bad "--t-end 0.5 did not give 500 ticks"

# CSV to stdout moves the summary to stderr, and the hash does not depend on it
$M run oscillator --t-end 0.01 --csv - >"$T/csv" 2>"$T/sum2"
[ "$(head -1 "$T/csv")" = "t,Osc.x" ] && ok || bad "csv header: $(head -1 "$T/csv")"
[ "$(wc -l <"$T/csv")" -eq 12 ] && ok || bad "csv rows: $(wc -l <"$T/csv")"
[ "$(hash_of <"$T/sum2")" = "$($M run oscillator --t-end 0.01 | hash_of)" ] && ok || bad "hash differs with --csv -"
# the recorded x at t = 0.01 against cos(2 pi 0.01) = 0.99802672842827156
awk -F, 'END { d = $2 - 0.99802672842827156; if (d < 0) d = -d; exit !(d < 1e-9) }' "$T/csv" \
    && ok || bad "csv value at 0.01 s"
$M run oscillator --t-end 0.01 --csv "$T/file.csv" --every 5 >/dev/null
[ "$(wc -l <"$T/file.csv")" -eq 4 ] && ok || bad "--every 5 rows: $(wc -l <"$T/file.csv")"

# --set changes the run; a parameter bit changes the hash
h0=$($M run oscillator --t-end 1 | hash_of)
h1=$($M run oscillator --t-end 1 --set Osc.omega=6.2831853071795871 | hash_of)
[ "$h0" != "$h1" ] && ok || bad "one-bit parameter change kept the hash"
$M run pi_loop --set Plant.T=0.25 --set PI.Kp=1.5 >/dev/null && ok || bad "--set pi_loop"

# the offline tuner picks the declared schedule of the actuated pendulum at 1e-4 m (its chain
# in the background: Jacobi coupling, 4 ticks; 8 ticks would give 3.7e-4 m)
$M tune pendulum10_actuated --tol 1e-4 | grep -q '^schedule: chain=4 servo=1$' && ok || bad "tune"

# conventions: usage on stderr with exit 2 without a command; --help on stdout, exit 0,
# for the program and every subcommand; --version; options before or after the scene,
# with --opt=value
$M >/dev/null 2>"$T/err"; [ $? -eq 2 ] && grep -q '^usage: modrt COMMAND' "$T/err" && ok || bad "no args"
for c in "" list kinds info run tune sizes docs-blocks; do
    $M $c --help >"$T/out" 2>"$T/err"; rc=$?
    [ $rc -eq 0 ] && [ ! -s "$T/err" ] && grep -q "^usage: modrt" "$T/out" && ok || bad "help of '$c' (exit $rc)"
done
$M -h | grep -q '^  run ' && ok || bad "-h lists run"
$M --help | grep -q '^  tune ' && ok || bad "--help lists tune"
$M --version | grep -qE '^modrt [0-9a-z.-]+ \((double|float)\)$' && ok || bad "--version: $($M --version)"
[ "$($M run --t-end=0.5 --every 10 oscillator | hash_of)" = "$($M run oscillator --t-end 0.5 --every=10 | hash_of)" ] \
    && ok || bad "option order or --opt=value changed the run"
$M run oscillator -- --t-end >/dev/null 2>&1; [ $? -eq 2 ] && ok || bad "-- ends the options"

# the block reference: every kind listed, each with units for every port, state, parameter
$M kinds >"$T/kinds"
[ "$(wc -l <"$T/kinds")" -ge 20 ] && ok || bad "kinds lists $(wc -l <"$T/kinds")"
$M info pt1 >"$T/kind" && grep -q '^kind: pt1$' "$T/kind" && grep -q '^  T  *\[s\]  default 1$' "$T/kind" \
    && ok || bad "info pt1: $(cat "$T/kind")"
# docs/blocks.md is generated from the same tables: it must be current (make docs)
$M docs-blocks | cmp -s - docs/blocks.md && ok || bad "docs/blocks.md is stale: run make docs"
# its rail example is the scene tests/scenec/test_scenec.c holds to the closed form
sed -n '/^## Example: a cart on a rail/,$p' docs/blocks.md | sed -n '/^```$/,/^```$/p' | sed '1d;$d' \
    | cmp -s - tests/scenec/scenes/lang_rail.scn && ok || bad "docs/blocks.md's rail example is not lang_rail.scn"
$M info pi_loop | grep -q '^  PI  *pi  *dss  *set main' && ok || bad "info shows set names"
$M info pi_loop | grep -q 'Kp=0.8 Ki=3$' && ok || bad "info shows parameter values"
if command -v python3 >/dev/null; then
    $M info pi_loop --json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["blocks"][1]["parameters"]["Kp"] == 0.8 and d["sets"][0]["name"] == "main"' \
        && ok || bad "info --json"
    $M info pt1 --json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert [p["unit"] for p in d["parameters"]] == ["-", "s"]' \
        && ok || bad "info KIND --json"
fi

# bad input: one clear line, exit 2, nothing crashes
expect_err "tune without tol" 2 "tune needs --tol" $M tune oscillator
# the transition method iterates nothing: no silent no-op (as the scene compiler)
# a set setting from the command line is the scene's clause (RT_SET_CFG_LIST): the same
# run as a scene file that says jacobian (1000), and a different one than the default
sed 's/method (rk4) step (1 tick);/method (sdirk2) step (1 tick) jacobian (1000);/' \
    models/scenes/oscillator.scn > "$T/osc_jac.scn"
h_file=$($M run "$T/osc_jac.scn" --t-end 1 | sed -n 's/^hash: //p')
h_opt=$($M run oscillator --method main=sdirk2 --jacobian main=1000 --t-end 1 | sed -n 's/^hash: //p')
h_def=$($M run oscillator --method main=sdirk2 --t-end 1 | sed -n 's/^hash: //p')
[ -n "$h_file" ] && [ "$h_file" = "$h_opt" ] && [ "$h_opt" != "$h_def" ] && ok || \
    bad "--jacobian: $h_opt, the scene's clause $h_file, default $h_def"
expect_err "jacobian for rk4" 2 "jacobian applies to the implicit methods that iterate only" \
    $M run oscillator --jacobian main=4
expect_err "newton for transition" 2 "newton applies to the implicit methods that iterate only; its method is transition" \
    $M run oscillator --method main=transition --newton main=2
expect_err "unknown command" 2 "unknown command (modrt --help lists them): frobnicate" $M frobnicate
expect_err "unknown scene" 2 "unknown scene (modrt list names them): nope" $M run nope
expect_err "unknown info" 2 "unknown scene" $M info nope
expect_err "unknown option" 2 "run: unknown option (modrt run --help lists them): --fast" $M run oscillator --fast
expect_err "missing value" 2 "option needs a value (--t-end=S): --t-end" $M run oscillator --t-end
expect_err "flag with value" 2 "option takes no value: --realtime=1" $M run oscillator --realtime=1
expect_err "short option" 2 "options are long" $M run oscillator -x
expect_err "missing scene" 2 "run needs SCENE" $M run
expect_err "missing scene file" 2 "/nonexistent/x.scn: error: cannot read the scene file: No such file or directory" $M run /nonexistent/x.scn
expect_err "extra argument" 2 "run: unexpected argument: more" $M run oscillator more
expect_err "tune bad tol" 2 "tol expects a tolerance > 0" $M tune oscillator --tol=-1
expect_err "bad t-end" 2 "t-end expects" $M run oscillator --t-end -3
expect_err "nan t-end" 2 "t-end expects" $M run oscillator --t-end nan
expect_err "bad every" 2 "every expects" $M run oscillator --every 1.5
expect_err "bad set form" 2 "BLOCK.PARAM=VALUE" $M run oscillator --set Osc.omega
expect_err "bad set block" 2 "unknown block: Nobody" $M run oscillator --set Nobody.omega=1
expect_err "bad set param" 2 "no parameter or state named: zeta" $M run oscillator --set Osc.zeta=1
expect_err "bad set value" 2 "not a finite number" $M run oscillator --set Osc.omega=abc
expect_err "overflowing set value" 2 "not a finite number" $M run oscillator --set Osc.omega=1e999
# a subnormal value is a value (strtod says ERANGE for it): taken as it is
sub=$($M run oscillator --set Osc.omega=5e-324 --t-end 0.01 2>&1)
if echo "$sub" | grep -q '^status: ok'; then ok; else bad "subnormal --set refused: $sub"; fi
expect_err "bad set range" 2 "out of range" $M run pi_loop --set Plant.T=0
expect_err "bad csv path" 4 "cannot write the CSV file /nonexistent/x.csv: No such file or directory" $M run oscillator --csv /nonexistent/x.csv

# the global-error check (tools/modrt/check.c; the estimate against closed forms is in
# tests/hard/cases_global.py): what it cannot check is refused in one line
expect_err "check a live link" 2 "a live --link run cannot be checked" \
    $M run pi_link --check --link udp:127.0.0.1:9
expect_err "check real time" 2 "cannot be run again at half the steps" $M run oscillator --check --realtime
expect_err "global-tol without check" 2 "apply with --check" $M run oscillator --global-tol 1e-3
expect_err "bad global-tol" 2 "global-tol expects E or ATOL,RTOL" $M check oscillator --global-tol 1e-3,x
expect_err "check selects nothing" 2 "no recorded signal to check: Nobody" $M check oscillator --only Nobody
# the run beside the check is the run: the same hash
h1=$($M run oscillator | hash_of); h2=$($M run oscillator --check | hash_of)
[ -n "$h1" ] && [ "$h1" = "$h2" ] && ok || bad "run --check changes the run: $h1 $h2"
# --set and --t-end reach the half run too: x' = 0 x is exact at every step
$M check tests/hard/global_exp.scn --method main=euler --set G.lam=0 --t-end 1 >"$T/out"; rc=$?
[ $rc -eq 0 ] && grep -q '^global_err.G.y: 0 at' "$T/out" && grep -q '^check_compared: 100 ' "$T/out" \
    && ok || bad "check with --set: exit $rc, $(grep -e global_err -e compared "$T/out")"
# x' = x by euler to 20 s: every step within its accuracy, the answer 9 % off: flagged
$M check tests/hard/global_exp.scn --global-tol 1e-2 >"$T/out"; rc=$?
[ $rc -eq 3 ] && grep -q '^status: ok$' "$T/out" && grep -q '^global_status: doubtful$' "$T/out" \
    && grep -q '^global_tol: atol 0.01, rtol 0.01 ' "$T/out" && ok || bad "check global_exp: exit $rc"
$M run --help | grep -q "It says nothing about the global error" && ok || bad "run --help: no guarantee"

# the scene compiler alone gives a per-scene build its limits, counted here by hand from
# the scene files: pi_loop has 3 blocks (step, pi, pt1), 1 state, 1 discrete state, 3
# inputs, 3 outputs, 3 + 2 + 2 parameters, 3 records; pendulum10 10 mass points (6 states,
# 6 outputs, 4 parameters, 3 velocities each), 22 records, 10 rods; empty tables count 1.
# Both have one set (no cross-set history), no roots (no event bracket), one sequence call
# per block, no loops. pendulum10's multibody tables: 10 rows; 19 touches (each rod its
# two points, J1 only B1); W keeps 19 x 3 entries; mass points have K = I (no predicted
# q) and a diagonal M = m I (no Y; 3 entries, 1/m and the 3 of the M^-1 k the written-out
# code keeps: 7 each); B1..B9 touch 2 rows (3 pairs), B10 1 (1
# pair): 28; a chain's A is tridiagonal, its L has 9 entries below the diagonal and no
# fill; 10 joint rows; point nodes need no Jacobian.
# (tests/image.sh runs images built with these limits against the host's hash)
want_pi="-DRT_MAX_BLOCKS=3 -DRT_MAX_X=1 -DRT_MAX_D=1 -DRT_MAX_U=3 -DRT_MAX_Y=3 -DRT_MAX_P=7"
want_pi="$want_pi -DRT_MAX_ROOTS=1 -DRT_MAX_SETS=1 -DRT_MAX_REC=3 -DRT_MAX_LOOPS=1 -DRT_MAX_TORN=1"
want_pi="$want_pi -DRT_MAX_IMPLICIT_N=1 -DRT_MAX_TRANSITION_N=0 -DRT_MAX_HIST_Y=1 -DRT_MAX_HELD_Y=0 -DRT_MAX_HELD_SIG=0 -DRT_MAX_EVENT_X=1 -DRT_MAX_SEQ=3"
want_pi="$want_pi -DRT_MAX_LOOP_HIST=1 -DRT_MAX_BG=1 -DRT_MAX_XPRED=0 -DRT_MAX_TEV=1 -DRT_MAX_KSTATE=0 -DRT_MAX_JOINTS=1 -DRT_MAX_MBS_Z=1 -DRT_MAX_MBS_Q=1"
want_pi="$want_pi -DRT_MAX_MBS_C=1 -DRT_MAX_MBS_BZ=1 -DRT_MAX_MBS_ROWS=1 -DRT_MAX_MBS_TOUCH=1"
want_pi="$want_pi -DRT_MAX_MBS_TW=1 -DRT_MAX_MBS_QT=1 -DRT_MAX_MBS_TY=1 -DRT_MAX_MBS_PAIRS=1"
want_pi="$want_pi -DRT_MAX_MBS_LNZ=1 -DRT_MAX_MBS_M=1 -DRT_MAX_MBS_JROWS=1 -DRT_MAX_MBS_JZ=1"
want_pe="-DRT_MAX_BLOCKS=10 -DRT_MAX_X=60 -DRT_MAX_D=1 -DRT_MAX_U=1 -DRT_MAX_Y=60 -DRT_MAX_P=40"
want_pe="$want_pe -DRT_MAX_ROOTS=1 -DRT_MAX_SETS=1 -DRT_MAX_REC=22 -DRT_MAX_LOOPS=1 -DRT_MAX_TORN=1"
want_pe="$want_pe -DRT_MAX_IMPLICIT_N=1 -DRT_MAX_TRANSITION_N=0 -DRT_MAX_HIST_Y=1 -DRT_MAX_HELD_Y=0 -DRT_MAX_HELD_SIG=0 -DRT_MAX_EVENT_X=1 -DRT_MAX_SEQ=10"
want_pe="$want_pe -DRT_MAX_LOOP_HIST=1 -DRT_MAX_BG=1 -DRT_MAX_XPRED=0 -DRT_MAX_TEV=0 -DRT_MAX_KSTATE=0 -DRT_MAX_JOINTS=10 -DRT_MAX_MBS_Z=30 -DRT_MAX_MBS_Q=30"
want_pe="$want_pe -DRT_MAX_MBS_C=10 -DRT_MAX_MBS_BZ=3 -DRT_MAX_MBS_ROWS=10 -DRT_MAX_MBS_TOUCH=19"
want_pe="$want_pe -DRT_MAX_MBS_TW=57 -DRT_MAX_MBS_QT=1 -DRT_MAX_MBS_TY=1 -DRT_MAX_MBS_PAIRS=28"
want_pe="$want_pe -DRT_MAX_MBS_LNZ=9 -DRT_MAX_MBS_M=70 -DRT_MAX_MBS_JROWS=10 -DRT_MAX_MBS_JZ=1"
[ "$(build/host/scenec --sizes models/scenes/pi_loop.scn)" = "$want_pi" ] && ok ||
    bad "scenec --sizes pi_loop: $(build/host/scenec --sizes models/scenes/pi_loop.scn)"
[ "$(build/host/scenec --sizes models/scenes/pendulum10.scn)" = "$want_pe" ] && ok ||
    bad "scenec --sizes pendulum10: $(build/host/scenec --sizes models/scenes/pendulum10.scn)"
[ "$($M sizes pi_loop)" = "$want_pi" ] && ok || bad "modrt sizes pi_loop: $($M sizes pi_loop)"
expect_err "scenec --sizes of a bad scene" 1 "error" build/host/scenec --sizes tests/scenec/errors/not_multibody.scn

# modrt info shows what rt_init reported about a scene it accepted
$M info tests/hard/joints_redundant.scn | grep -qx 'init: ok (reported: J2 repeats constraints of J1: solved with its multipliers zero)' \
    && ok || bad "modrt info does not show rt_init's report of a redundant joint"

# the trace does not depend on the order the scene lists its sets in
out=$(python3 tests/permute_sets.py $M) && ok || bad "set order changes a trace: $out"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
