#!/bin/sh
# run.sh - the FMU suite (make test-fmi): the test FMUs of tests/fmi/models/ as FMI 2.0 and
# 3.0 in the scenes of tests/fmi/scenes/ (@V@: the version, @FMUS@: where they were built),
# their traces against closed forms (check.py), their hashes against the same equations in
# the scene language and against each other, `modrt info` of an FMU, and the bad-FMU corpus
# (bad.sh). Ends with "N passed, N failed".
#
# Usage: sh tests/fmi/run.sh BUILD_DIR FMI_DIR   (e.g. build/host build/host/fmi)
set -u
B=$1 T=$2
M=$B/modrt
FMUS=$(cd "$T/fmu" && pwd)
W=$T/run
rm -rf "$W" && mkdir -p "$W"
export MODRT_FMU_CACHE="$T/cache"
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $*"; }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
hash_of() { sed -n 's/^hash: //p' "$1"; }

# a scene of tests/fmi/scenes for version $2, run with its CSV; its summary in $W/$1$2.out
run() {
    sed "s#@V@#$2#g; s#@FMUS@#$FMUS#g" "tests/fmi/scenes/$1.scn" > "$W/$1$2.scn"
    "$M" run "$W/$1$2.scn" --csv "$W/$1$2.csv" > "$W/$1$2.out" 2>&1
    rc=$?
    if [ $rc -eq 0 ] && grep -q '^status: ok' "$W/$1$2.out"; then
        ok "$1 (FMI $2.0) runs, status ok, $(grep '^fmu\.' "$W/$1$2.out" | head -1)"
    else
        bad "$1 (FMI $2.0) exit $rc:"; cat "$W/$1$2.out"
    fi
}

closed() { # kind scene version tolerance
    if python3 tests/fmi/check.py "$1" "$W/$2$3.csv" "$4"; then ok "$2 (FMI $3.0) closed form"
    else bad "$2 (FMI $3.0) closed form"; fi
}

same_hash() { # what, file a, file b
    ha=$(hash_of "$2") hb=$(hash_of "$3")
    if [ -n "$ha" ] && [ "$ha" = "$hb" ]; then ok "$1: same hash $ha"
    else bad "$1: hashes differ ($ha, $hb)"; fi
}

for v in 2 3; do
    run ball_fmu $v && closed ball ball_fmu $v 1e-9
    run ball_h2_fmu $v && closed ball_h2 ball_h2_fmu $v 1e-9
    run stair_fmu $v && closed stair stair_fmu $v 0
    run osc_fmu $v && closed osc osc_fmu $v 1e-7
    run stepper_fmu $v && closed stepper stepper_fmu $v 1e-12
    run liftoff_fmu $v && closed liftoff liftoff_fmu $v 1e-9
    run probe_hold_fmu $v && closed probe_hold probe_hold_fmu $v 1e-12
done

# a tunable parameter written during the run (tests/fmi/setp.c: q = 3 after the row at
# 0.25 s): each probe takes it in event mode at its set's next instant (check.py)
for v in 2 3; do
    sed "s#@V@#$v#g; s#@FMUS@#$FMUS#g" tests/fmi/scenes/probe_param_fmu.scn > "$W/probe_param_fmu$v.scn"
    "$T/setp" "$W/probe_param_fmu$v.scn" 0.25 "$W/probe_param_fmu$v.csv" Pd.q=3 Pe.q=3 Pf.q=3 \
        > "$W/probe_param_fmu$v.out" 2>&1
    if [ "$(grep -c '^set P[def].q: ok$' "$W/probe_param_fmu$v.out")" = 3 ] &&
       grep -q '^status: ok$' "$W/probe_param_fmu$v.out"; then
        ok "probe_param_fmu (FMI $v.0): q written at 0.25 s, status ok"
    else bad "probe_param_fmu (FMI $v.0):"; cat "$W/probe_param_fmu$v.out"; fi
    closed probe_param probe_param_fmu $v 1e-12
done

# a fixed parameter written during the run (the stair's period after the row at 1.25 s):
# a fault of the block at its next evaluation (the tick 1.375 s: the stair has no state to
# integrate), the instance not started again
for v in 2 3; do
    "$T/setp" "$W/stair_fmu$v.scn" 1.25 "$W/fixed$v.csv" S.period=1 > "$W/fixed$v.out" 2>&1
    if grep -q '^status: non-finite' "$W/fixed$v.out" &&
       grep -q '^fmu.S.first_fault: t = 1.375: parameter period is fixed: it cannot change after the start' "$W/fixed$v.out"
    then ok "stair (FMI $v.0): a fixed parameter written at 1.25 s is a fault at 1.375 s"
    else bad "stair (FMI $v.0): a fixed parameter written during the run:"; cat "$W/fixed$v.out"; fi
done

# more time events in one step than RT_TEV_PARTS_MAX parts (S3 every 0.03 s on steps of
# 1/8 s): counted (tev_limit), the run failed, never merged silently
for v in 2 3; do
    "$M" run "$W/stair_fmu$v.scn" --set S3.period=0.03 > "$W/many$v.out" 2>&1
    if grep -q '^status: more time events in one step than RT_TEV_PARTS_MAX' "$W/many$v.out" &&
       grep -q '^tev_limit: [1-9][0-9]* (last S3)' "$W/many$v.out"; then
        ok "stair (FMI $v.0) every 0.03 s on 1/8 s steps: $(grep '^tev_limit' "$W/many$v.out"), status failed"
    else bad "stair (FMI $v.0) every 0.03 s:"; cat "$W/many$v.out"; fi
done

# modrt check runs the scene again at half the steps (and a quarter: --observe) beside
# the run, on the same FMU instances: each run's FMU state and tally are kept apart and
# put in place around its ticks (tools/modrt/check.c), so the check's run is the straight
# run (its hash, its fmu. lines) and the half run sees every event the run does (before,
# they stepped one instance: the stair's half run saw none of its 8 time events, and a
# run of an FMU whose discrete state flips at its events was changed by the check)
for v in 2 3; do
    for s in stair_fmu ball_fmu; do
        "$M" check --observe "$W/$s$v.scn" > "$W/check_$s$v.out" 2>&1
        ev=$(sed -n 's/^check_events: \([0-9]*\), at half the steps \([0-9]*\);.*/\1 \2/p' "$W/check_$s$v.out")
        set -- $ev
        if [ "$(hash_of "$W/check_$s$v.out")" = "$(hash_of "$W/$s$v.out")" ] && [ $# -eq 2 ] &&
           [ "$1" = "$2" ] && [ "$1" -gt 0 ] && grep -q '^global_status: ok' "$W/check_$s$v.out" &&
           [ "$(grep '^fmu\.' "$W/check_$s$v.out")" = "$(grep '^fmu\.' "$W/$s$v.out")" ]; then
            ok "$s (FMI $v.0): modrt check's run is the run (hash $(hash_of "$W/$s$v.out"), fmu. lines), $1 events at h and h/2, global ok"
        else bad "$s (FMI $v.0) under modrt check:"; cat "$W/check_$s$v.out"; fi
    done
done

# snapshots (rt_snapshot / rt_restore, tests/fmi/snap.c): to t1, a snapshot, on to t2
# across the FMUs' events, restored, to t2 again: the rows after the restore against the
# closed form, and the hash of the straight run. The stair's counter lives in the FMU's
# memory, in none of the runtime's states: restored without the FMU state, its rows are
# off by the events between t1 and t2. An FMU that does not say it can save its state:
# rt_snapshot says so, and rt_restore refuses that snapshot
snap_check() { # scene version t1 t2 closed-form tolerance
    o=$W/snap_$1$2
    "$T/snap" "$W/$1$2.scn" "$3" "$4" "$o.csv" > "$o.out" 2>&1
    h0=$(sed -n 's/^straight: //p' "$o.out") h1=$(sed -n 's/^on: //p' "$o.out")
    h2=$(sed -n 's/^restored: //p' "$o.out")
    if grep -q '^snapshot: ok$' "$o.out" && grep -q '^restore: ok$' "$o.out" &&
       grep -q '^status: ok$' "$o.out" && [ -n "$h0" ] && [ "$h1" = "$h0" ] && [ "$h2" = "$h0" ] &&
       python3 tests/fmi/check.py "$5" "$o.csv" "$6" > "$o.chk"; then
        ok "$1 (FMI $2.0): snapshot at $3 s, restored after $4 s: the same hash $h0, $(cat "$o.chk")"
    else bad "$1 (FMI $2.0) snapshot and restore:"; cat "$o.out" "$o.chk"; fi
}
for v in 2 3; do
    snap_check stair_fmu $v 1.3 3 stair 0
    snap_check ball_fmu $v 0.6 1.5 ball 1e-9
    python3 tests/fmi/mkfmu.py --cc "${CC:-cc}" --version $v --model stair --no-state \
        --out "$W/nostate$v.fmu" --cflags "-std=c11 -O2 -fPIC -shared -Itools/fmi -Itests/fmi"
    sed "s#@V@#$v#g; s#@FMUS@/stair$v.fmu#$(cd "$W" && pwd)/nostate$v.fmu#" \
        tests/fmi/scenes/stair_fmu.scn > "$W/nostate$v.scn"
    "$T/snap" "$W/nostate$v.scn" 1.3 3 "$W/nostate$v.csv" > "$W/nostate$v.out" 2>&1
    if grep -q "^snapshot: a block's internal state cannot be saved" "$W/nostate$v.out" &&
       grep -q "^restore: a block's internal state cannot be saved" "$W/nostate$v.out"; then
        ok "stair without canGetAndSetFMUState (FMI $v.0): rt_snapshot says so, rt_restore refuses it"
    else bad "stair without canGetAndSetFMUState (FMI $v.0):"; cat "$W/nostate$v.out"; fi
    # nor can modrt check give its half run an instance state of its own: refused (exit 2)
    "$M" check "$W/nostate$v.scn" > "$W/nostate_check$v.out" 2>&1
    rc=$?
    if [ $rc -eq 2 ] && grep -q "internal state (an FMU's) cannot be saved, so the run at half the steps cannot have its own" "$W/nostate_check$v.out"; then
        ok "stair without canGetAndSetFMUState (FMI $v.0): modrt check refused"
    else bad "stair without canGetAndSetFMUState (FMI $v.0) under modrt check: exit $rc"; cat "$W/nostate_check$v.out"; fi
done

# source FMUs: no binary, sources/ built on the host (buildDescription.xml for 3.0, the
# <SourceFiles> of 2.0): the same bits as the binary FMUs
for v in 2 3; do
    for ms in bouncing:ball stair:stair; do
        m=${ms%:*} s=${ms#*:}
        python3 tests/fmi/mkfmu.py --cc "${CC:-cc}" --version $v --model $m --source-only \
            --out "$W/src_$m$v.fmu" --cflags "-std=c11 -O2 -fPIC -shared -Itools/fmi -Itests/fmi"
        sed "s#@V@#$v#g; s#@FMUS@/$m$v.fmu#$(cd "$W" && pwd)/src_$m$v.fmu#" \
            tests/fmi/scenes/${s}_fmu.scn > "$W/src_$s$v.scn"
        "$M" run "$W/src_$s$v.scn" > "$W/src_$s$v.out" 2>&1
        same_hash "$s: FMI $v.0 source FMU built here = binary FMU" "$W/src_$s$v.out" "$W/${s}_fmu$v.out"
    done
    # the oscillator and the feed-through, both in osc_fmu.scn
    for m in oscillator feedthrough; do
        python3 tests/fmi/mkfmu.py --cc "${CC:-cc}" --version $v --model $m --source-only \
            --out "$W/src_$m$v.fmu" --cflags "-std=c11 -O2 -fPIC -shared -Itools/fmi -Itests/fmi"
    done
    d=$(cd "$W" && pwd)
    sed "s#@V@#$v#g; s#@FMUS@/oscillator$v.fmu#$d/src_oscillator$v.fmu#;
         s#@FMUS@/feedthrough$v.fmu#$d/src_feedthrough$v.fmu#" tests/fmi/scenes/osc_fmu.scn > "$W/src_osc$v.scn"
    if grep -q '@FMUS@' "$W/src_osc$v.scn"; then bad "src_osc$v.scn still names a binary FMU"; fi
    "$M" run "$W/src_osc$v.scn" > "$W/src_osc$v.out" 2>&1
    same_hash "osc: FMI $v.0 source FMUs (oscillator, feed-through) built here = binary FMUs" \
        "$W/src_osc$v.out" "$W/osc_fmu$v.out"
done

# modrt sizes: the limits of a per-scene build and the FMU arena its image needs, the line
# scenec --sizes prints (one function: fmu_scn_sizes). The arena, from the glue's
# structures on this LP64 host (tests/image.sh): the instance (model_data 72, mode 4,
# has_next 4, next 8, name 8; 2.0 the callbacks' pointer 8, 3.0 environment and logger 16),
# "Ball" and its 0 (5, to 8), the first snapshot's FMU state (72 + 4 + 4 + 8): 2.0 200, 3.0 208
for v in 2 3; do
    want=$((v == 2 ? 200 : 208))
    "$M" sizes "$W/src_ball$v.scn" > "$W/sizes$v.out" 2>&1
    "$B/scenec" --sizes "$W/src_ball$v.scn" > "$W/sizes$v.sc" 2>&1
    if grep -q "^-DRT_MAX_BLOCKS=1 .* -DFMU_ARENA_BYTES=$want\$" "$W/sizes$v.out" &&
       cmp -s "$W/sizes$v.out" "$W/sizes$v.sc"; then
        ok "modrt sizes of the FMI $v.0 ball: -DFMU_ARENA_BYTES=$want, the line scenec --sizes prints"
    else bad "modrt sizes of the FMI $v.0 ball:"; cat "$W/sizes$v.out" "$W/sizes$v.sc"; fi
done
"$M" sizes pi_loop > "$W/sizes_pi.out" 2>&1
if grep -q '^-DRT_MAX_BLOCKS=' "$W/sizes_pi.out" && ! grep -q FMU_ARENA "$W/sizes_pi.out"
then ok "modrt sizes of a scene without FMU blocks: no FMU arena"; else bad "modrt sizes pi_loop:"; cat "$W/sizes_pi.out"; fi

# scenes holding an FMU block exported (docs/fmi.md, "FMU blocks in an exported FMU"): the
# source FMUs above compiled into the exported FMU, driven by the foreign master: the trace
# hash of modrt run of the scene, its rows against the closed form (the ball to 1e-9 m, the
# stair's counter, which lives in the inner FMU's memory, exactly), a state saved and
# restored (the inner FMU's with it) stepping to the same bits; the binary rebuilt from the
# exported sources alone, the same hash. An inner FMU that cannot save its state makes the
# exported one say so; a binary-only FMU is refused in one line naming the block
export_inner() { # outer FMI version, scene file (in $W), check.py kind, tolerance, summary of modrt run
    v=$1 s=$2 x=$W/xi$1_$2
    rm -rf "$x" && mkdir -p "$x"
    if ! "$B/scenec" --fmu "$x.fmu" --fmi-version "$v" "$W/$s.scn" 2> "$x.err"; then
        bad "scenec --fmu --fmi-version $v $s: $(cat "$x.err")"; return 1; fi
    unzip -q -d "$x" "$x.fmu"
    # its static arena: what scenec --sizes measures for an image of the scene
    a=$("$B/scenec" --sizes "$W/$s.scn" | sed -n 's/.* -DFMU_ARENA_BYTES=\([0-9]*\)$/\1/p')
    if [ -n "$a" ] && grep -q "^#define FMU_ARENA_BYTES $a\$" "$x/sources/fmu_blocks_arena.c"
    then ok "$s.fmu (FMI $v.0): its FMU arena $a bytes, as scenec --sizes measures"
    else bad "$s.fmu (FMI $v.0): arena '$a': $(grep ARENA "$x/sources/fmu_blocks_arena.c")"; fi
    if python3 "tests/fmi/check_md$v.py" "$x" > "$x.md"; then ok "$s.fmu (FMI $v.0 with an FMU block): $(cat "$x.md")"
    else bad "$s.fmu (FMI $v.0):"; cat "$x.md"; fi
    dt=$(sed -n 's/.*stepSize="\([^"]*\)".*/\1/p' "$x/modelDescription.xml")
    te=$(sed -n 's/.*stopTime="\([^"]*\)".*/\1/p' "$x/modelDescription.xml")
    MASTER_CSV="$x.csv" MASTER_DT=$dt MASTER_END=$te "$T/master" "$x" > "$x.master" 2>&1
    p=$(grep -c '^ok' "$x.master") f=$(grep -c '^FAIL' "$x.master")
    pass=$((pass + p)) fail=$((fail + f))
    grep -E '^(ok|FAIL)' "$x.master" | sed "s/\$/ ($s exported, FMI $v.0)/"
    same_hash "$s exported as FMI $v.0 with its FMU block, under the master = modrt run" "$x.master" "$5"
    if python3 tests/fmi/check.py "$3" "$x.csv" "$4" > "$x.chk"; then ok "$s exported (FMI $v.0), the master's rows: $(cat "$x.chk")"
    else bad "$s exported (FMI $v.0), the master's rows:"; cat "$x.chk"; fi
    id=$(sed -n 's/.*<CoSimulation modelIdentifier="\([^"]*\)".*/\1/p' "$x/modelDescription.xml")
    so=$x/binaries/$([ "$v" = 2 ] && echo linux64 || echo x86_64-linux)/$id.so
    rm -f "$so"
    python3 tests/fmi/build_sources.py "$x" "$so" &&
        MASTER_DT=$dt MASTER_END=$te "$T/master" "$x" > "$x.src" 2>&1
    same_hash "$s exported (FMI $v.0): its binary rebuilt from its sources = modrt run" "$x.src" "$5"
}
# the inner FMU that cannot save its state (below), made before the lanes use it
python3 tests/fmi/mkfmu.py --cc "${CC:-cc}" --version 3 --model stair --source-only --no-state \
    --out "$W/src_nostate3.fmu" --cflags "-std=c11 -O2 -fPIC -shared -Itools/fmi -Itests/fmi"
sed "s#@V@#3#g; s#@FMUS@/stair3.fmu#$(cd "$W" && pwd)/src_nostate3.fmu#" \
    tests/fmi/scenes/stair_fmu.scn > "$W/src_nostate3.scn"
"$M" run "$W/src_nostate3.scn" > "$W/src_nostate3.out" 2>&1
# two lanes side by side, as the exports of library scenes below (each export builds the
# runtime twice); a lane's counts are read from its ok / FAIL lines
inner_lane() { # FMI version of the exported FMUs
    v=$1
    export_inner $v src_ball$v ball 1e-9 "$W/src_ball$v.out"
    export_inner $v src_stair$v stair 0 "$W/src_stair$v.out"
    if grep -q "canGetAndSetFMUState=\"true\"\|canGetAndSetFMUstate=\"true\"" "$W/xi${v}_src_stair$v/modelDescription.xml" &&
       grep -q 'canBeInstantiatedOnlyOncePerProcess="true"' "$W/xi${v}_src_stair$v/modelDescription.xml"
    then ok "stair exported (FMI $v.0): canGetAndSetFMUState true, once per process"
    else bad "stair exported (FMI $v.0): capability flags"; fi
    if [ "$v" = 2 ]; then # an FMI 2.0 FMU block in an FMI 3.0 FMU
        export_inner 3 src_ball2 ball 1e-9 "$W/src_ball2.out"
    else # the inner FMU cannot save its state: neither can the exported one
        export_inner 3 src_nostate3 stair 0 "$W/src_nostate3.out"
    fi
}
inner_lane 3 > "$W/inner3.log" 2>&1 &
inner3=$!
(inner_lane 2) > "$W/inner2.log" 2>&1
wait $inner3
for v in 2 3; do
    cat "$W/inner$v.log"
    pass=$((pass + $(grep -c '^ok' "$W/inner$v.log"))) fail=$((fail + $(grep -c '^FAIL' "$W/inner$v.log")))
done
if grep -q 'canGetAndSetFMUState="false" canSerializeFMUState="false"' "$W/xi3_src_nostate3/modelDescription.xml"
then ok "an FMU block without canGetAndSetFMUState: the exported FMU's flags false"
else bad "the exported FMU of an FMU block without canGetAndSetFMUState claims it"; fi
# a binary-only FMU block: refused in one line naming it, nothing written
"$B/scenec" --fmu "$W/xbin.fmu" "$W/ball_fmu3.scn" > "$W/xbin.out" 2>&1
if [ $? -eq 1 ] && [ "$(wc -l < "$W/xbin.out")" = 1 ] && [ ! -e "$W/xbin.fmu" ] &&
   grep -q 'error: FMU of Ball: .* ships no sources (sources/): an image or an exported FMU' "$W/xbin.out"
then ok "scenec --fmu refuses a binary-only FMU block in one line"
else bad "scenec --fmu of a binary-only FMU block:"; cat "$W/xbin.out"; fi

# the same equations as defines of the scene language: the same bits (the ball's FMU is
# also stopped at each lift-off, which a define's root is not: docs/fmi.md)
for s in osc; do
    "$M" run "tests/fmi/scenes/${s}_scn.scn" > "$W/${s}_scn.out" 2>&1
    same_hash "$s: FMI 2.0 FMU = scene-language define" "$W/${s}_fmu2.out" "$W/${s}_scn.out"
done
for s in ball osc liftoff; do
    same_hash "$s: FMI 3.0 FMU = FMI 2.0 FMU" "$W/${s}_fmu3.out" "$W/${s}_fmu2.out"
done
same_hash "stair: FMI 3.0 FMU = FMI 2.0 FMU" "$W/stair_fmu3.out" "$W/stair_fmu2.out"
same_hash "stepper: FMI 3.0 FMU = FMI 2.0 FMU" "$W/stepper_fmu3.out" "$W/stepper_fmu2.out"
same_hash "probe_hold: FMI 3.0 FMU = FMI 2.0 FMU" "$W/probe_hold_fmu3.out" "$W/probe_hold_fmu2.out"
same_hash "probe_param: FMI 3.0 FMU = FMI 2.0 FMU" "$W/probe_param_fmu3.out" "$W/probe_param_fmu2.out"

# events: two per impact before 2 s, the impact and the return of h to h > 0 (every sign
# change of an FMU's indicator is reported, rt/step.c)
n=$(sed -n 's/^events: //p' "$W/ball_fmu2.out")
t1=$(python3 -c 'import math
g, e = 9.81, 0.7
t, v, n = math.sqrt(2 / g), math.sqrt(2 * g) * e, 0
while t < 2: n, t, v = n + 1, t + 2 * v / g, v * e
print(2 * n)')
if [ "$n" = "$t1" ]; then ok "ball: $n events (the impacts before 2 s and their lift-offs)"
else bad "ball: $n events, expected $t1"; fi

# a tunable parameter changed before the run (--set) takes effect: the feed-through gain
"$M" run "$W/osc_fmu2.scn" --set Ft.gain=3 --csv "$W/gain.csv" > "$W/gain.out" 2>&1
if python3 -c 'import csv,sys
r = list(csv.reader(open(sys.argv[1])))[1:]
sys.exit(0 if all(float(x[2]) == 3 * float(x[1]) + 0.5 for x in r) else 1)' "$W/gain.csv"
then ok "--set Ft.gain=3: y = 3 u1 + 0.5 on every row"; else bad "--set Ft.gain=3"; fi

# modrt info of an FMU file: causality, unit and start of every variable
"$M" info "$FMUS/bouncing3.fmu" > "$W/info.out" 2>&1
if grep -q '^g  *parameter  *fixed  *Float64  *4  *m/s2  *9.81$' "$W/info.out" &&
   grep -q '^states: 2$' "$W/info.out" && grep -q '^event_indicators: 1$' "$W/info.out"; then
    ok "modrt info bouncing3.fmu lists g (parameter, m/s2, 9.81), 2 states, 1 indicator"
else bad "modrt info bouncing3.fmu:"; cat "$W/info.out"; fi

# scenec writes C for targets: an FMU system without sources is refused at its load
# statement, in one line, and nothing is written (a source FMU in an image: tests/image.sh)
"$B/scenec" -o "$W/scenec.c" "$W/ball_fmu2.scn" > "$W/scenec.out" 2>&1
if [ $? -eq 1 ] && [ "$(wc -l < "$W/scenec.out")" = 1 ] && [ ! -e "$W/scenec.c" ] &&
   grep -q 'error: FMU of Ball: .* ships no sources (sources/)' "$W/scenec.out"; then
    ok "scenec refuses a binary-only FMU system for an image in one line"
else bad "scenec:"; cat "$W/scenec.out"; fi

# export: library scenes as FMI 3.0 and 2.0 Co-Simulation FMUs, driven by a foreign master
# (master.c): the trace hash of one-tick steps = modrt run's; 10-tick steps and a restored
# FMU state give the same bits; steps off the tick grid refused; the description keeps the
# schema's rules (check_md3.py, check_md2.py; also xmllint against the standard's schema
# when FMI3_XSD / FMI2_XSD name its fmi3ModelDescription.xsd / fmi2ModelDescription.xsd);
# the binary built again from the FMU's own sources (its buildDescription.xml) gives the
# same hash
export_fmu() { # FMI version, scene, extra modrt run options
    v=$1 s=$2 x=$W/x$1_$2
    shift 2
    rm -rf "$x" && mkdir -p "$x"
    if ! "$B/scenec" --fmu "$x.fmu" --fmi-version "$v" "models/scenes/$s.scn" 2> "$x.err"; then
        bad "scenec --fmu --fmi-version $v $s: $(cat "$x.err")"; return 1; fi
    unzip -q -d "$x" "$x.fmu"
    if python3 "tests/fmi/check_md$v.py" "$x" > "$x.md"; then ok "$s.fmu (FMI $v.0): $(cat "$x.md")"
    else bad "$s.fmu (FMI $v.0):"; cat "$x.md"; fi
    xsd=$( [ "$v" = 2 ] && echo "${FMI2_XSD:-}" || echo "${FMI3_XSD:-}")
    if [ -n "$xsd" ]; then
        if xmllint --noout --schema "$xsd" "$x/modelDescription.xml" 2> "$x.xsd"; then
            ok "$s.fmu (FMI $v.0): xmllint against $xsd"
        else bad "$s.fmu (FMI $v.0): xmllint:"; cat "$x.xsd"; fi
    fi
    dt=$(sed -n 's/.*stepSize="\([^"]*\)".*/\1/p' "$x/modelDescription.xml")
    te=$(sed -n 's/.*stopTime="\([^"]*\)".*/\1/p' "$x/modelDescription.xml")
    "$M" run "$s" "$@" > "$x.run" 2>&1
    env MASTER_DT="$dt" MASTER_END="$te" ${PI_CSV:+MASTER_PI_CSV="$PI_CSV"} "$T/master" "$x" \
        > "$x.master" 2>&1
    grep -E '^(ok|FAIL)' "$x.master" | while read -r l; do echo "$l ($s, FMI $v.0)"; done
    p=$(grep -c '^ok' "$x.master") f=$(grep -c '^FAIL' "$x.master")
    pass=$((pass + p)) fail=$((fail + f))
    same_hash "$s (FMI $v.0): the exported FMU under a foreign master = modrt run" "$x.master" "$x.run"
    so=$x/binaries/$([ "$v" = 2 ] && echo linux64 || echo x86_64-linux)/$s.so
    python3 tests/fmi/build_sources.py "$x" "$so" &&
        MASTER_DT=$dt MASTER_END=$te "$T/master" "$x" > "$x.src" 2>&1
    same_hash "$s (FMI $v.0): the FMU's binary built from its sources = modrt run" "$x.src" "$x.run"
}
"$M" run pi_loop --csv "$W/pi_loop_ref.csv" > /dev/null 2>&1
# the two versions side by side (each exports and builds the runtime four times); a lane's
# lines are counted once it has ended
lane() { # FMI version
    for s in pi_loop oscillator bouncing_ball; do export_fmu "$1" $s; done
    PI_CSV=$W/pi_loop_ref.csv export_fmu "$1" pi_link --link none
}
lane 3 > "$W/lane3.log" 2>&1 &
lane3=$!
(lane 2) > "$W/lane2.log" 2>&1 # a subshell, as lane 3: its counts are read from its lines
wait $lane3
for v in 3 2; do
    cat "$W/lane$v.log"
    pass=$((pass + $(grep -c '^ok' "$W/lane$v.log"))) fail=$((fail + $(grep -c '^FAIL' "$W/lane$v.log")))
done

# source FMUs name their functions with the model identifier (FMI2_FUNCTION_PREFIX,
# FMI3_FUNCTION_PREFIX) unless the importer builds a shared object
# (FMI*_OVERRIDE_FUNCTION_PREFIX); two of them (pi_loop and oscillator) link into one object
for v in 2 3; do
    for s in pi_loop oscillator; do
        x=$W/x${v}_$s/sources
        ${CC:-cc} -std=c11 -c -I"$x" -I"$x/rt" -I"$x/models" "$x/fmi${v}cs.c" -o "$W/fmi${v}cs_$s.o"
    done
    if nm "$W/fmi${v}cs_pi_loop.o" | grep -q " T pi_loop_fmi${v}DoStep$" &&
       ! nm "$W/fmi${v}cs_pi_loop.o" | grep -q " T fmi${v}DoStep$" &&
       ${CC:-cc} -r -nostdlib "$W/fmi${v}cs_pi_loop.o" "$W/fmi${v}cs_oscillator.o" -o "$W/fmi${v}cs_both.o" &&
       nm "$W/fmi${v}cs_both.o" | grep -q " T oscillator_fmi${v}DoStep$"
    then ok "FMI $v.0 sources compiled as source FMUs: pi_loop_fmi${v}DoStep, no plain fmi${v}DoStep; pi_loop's and oscillator's link into one object"
    else bad "FMI $v.0 source FMU function names:"; nm "$W/fmi${v}cs_pi_loop.o" | grep DoStep; fi
done

# the 2.0 checker can fail: outputs missing from InitialUnknowns (the schema allows it,
# the specification does not)
mkdir -p "$W/x2_broken" && cp -r "$W/x2_pi_loop/." "$W/x2_broken/"
sed -i '/<InitialUnknowns>/,/<\/InitialUnknowns>/d' "$W/x2_broken/modelDescription.xml"
if python3 tests/fmi/check_md2.py "$W/x2_broken" | grep -q "InitialUnknowns lack the outputs"; then
    ok "check_md2 refuses outputs missing from InitialUnknowns"
else bad "check_md2 accepted a broken description"; fi

# the schema checker can fail: a description without its unit definitions
mkdir -p "$W/x_broken" && cp -r "$W/x3_pi_loop/." "$W/x_broken/"
sed -i '/UnitDefinitions\|<Unit /d' "$W/x_broken/modelDescription.xml"
if python3 tests/fmi/check_md3.py "$W/x_broken" | grep -q "not in UnitDefinitions"; then
    ok "check_md3 refuses a unit missing from UnitDefinitions"
else bad "check_md3 accepted a broken description"; fi

# the broken FMUs: each a one-line error or a counted fault
out=$(sh tests/fmi/bad.sh "$B" "$T")
echo "$out"
p=$(echo "$out" | grep -c '^ok:') f=$(echo "$out" | grep -c '^FAIL:')
pass=$((pass + p)) fail=$((fail + f))

echo "test-fmi: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
