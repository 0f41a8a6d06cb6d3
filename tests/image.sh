#!/bin/sh
# image.sh - tests of `make image` (tools/image.sh, docs/porting.md): a missing or wrong
# argument stops with one line and exit 2; a scene file outside the library builds for a
# RISC-V target and a library scene for Cortex-M with the UART console, and both images,
# run under QEMU, print the trace hash `modrt run` gives on the host; a CONSOLE=none image
# links no semihosting call (no bkpt), so it cannot lock up on a board without a debugger.
set -u
M=build/host/modrt
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL image: $*"; }

# usage errors: exit 2, one line naming what is missing
for args in "" "TARGET=m3" "TARGET=nosuch SCENE=pi_loop" "TARGET=m3 SCENE=no/such.scn" \
            "TARGET=rv32 SCENE=pi_loop CONSOLE=uart" "TARGET=m3 SCENE=pi_loop CONSOLE=lcd" \
            "TARGET=m7 SCENE=pi_loop CLOCK_MHZ=fast" "TARGET=m7 SCENE=pi_loop TICKS=0"; do
    # shellcheck disable=SC2086
    out=$(make -s image $args 2>&1 >/dev/null); rc=$?
    if [ $rc -ne 0 ] && [ "$(echo "$out" | grep -c '^make image: ')" = 1 ]; then ok
    else bad "make image $args: exit $rc, '$out'"; fi
done
out=$(make -s foot-elf 2>&1); rc=$?
if [ $rc -ne 0 ] && echo "$out" | grep -q '^usage: make foot-elf'; then ok; else bad "foot-elf without arguments: exit $rc"; fi

# hash of the image's one line against the host's run of the same scene
run_check() { # target elf scene-or-file qemu-command...
    t=$1 elf=$2 s=$3; shift 3
    want=$($M run "$s" | sed -n 's/^hash: //p')
    got=$("$@" "$elf" 2>&1 | sed -n 's/^rt scene .* hash \([0-9a-f]*\) status ok$/\1/p')
    if [ -n "$want" ] && [ "$got" = "$want" ]; then ok; echo "image: $t $s: hash $got = host"
    else bad "$t $s: image hash '$got', host '$want'"; fi
}

f=tests/scenec/scenes/lang_sets.scn
if make -s image MEASURE=0 TARGET=rv32 SCENE=$f >/dev/null; then
    run_check rv32 build/image/rv32/lang_sets.elf $f timeout 60 qemu-system-riscv32 -M virt \
        -bios none -display none -monitor none -serial stdio -icount shift=0,sleep=off -kernel
else bad "rv32 image of $f did not build"; fi

if make -s image MEASURE=0 TARGET=m3 SCENE=pi_loop CONSOLE=uart IMAGE_CFLAGS=-DCM_EXIT_SEMIHOST=1 >/dev/null; then
    run_check m3 build/image/m3/pi_loop.elf pi_loop timeout 60 qemu-system-arm -M mps2-an385 \
        -display none -monitor none -serial stdio -semihosting-config enable=on,target=native \
        -icount shift=0,sleep=off -kernel
else bad "m3 UART image did not build"; fi

# an application whose main is compiled with other limits than the runtime (here: the
# scene's exact torn inputs, the runtime 16), table-driven: its rt_sim is smaller than the
# runtime's, and rt_init refuses it in one line (writing only that line's text into it)
# before the run starts, and the image exits non-zero
if IMAGE_MAIN_CFLAGS="-URT_MAX_TORN -DRT_MAX_TORN=1" make -s image MEASURE=0 TARGET=m3 SCENE=pi_loop \
       IMAGE_CFLAGS="-DRT_SCENE_CODE=0 -URT_MAX_TORN -DRT_MAX_TORN=16" >/dev/null; then
    # shellcheck disable=SC2046 # the run command is meant to split into words
    out=$($(make -s print-TARGET_RUN_m3) build/image/m3/pi_loop.elf 2>&1); rc=$?
    if [ $rc -ne 0 ] && [ "$out" = "rt scene pi_loop init malformed scene: rt_sim compiled with other \
limits than the runtime (RT_MAX_*, REAL): build every file with the same (scenec --sizes)" ]; then ok
    else bad "m3 image whose main has other limits than the runtime: exit $rc, '$out'"; fi
else bad "m3 image whose main has other limits than the runtime did not build"; fi

# a scene whose constraint rows fill its exactly sized multibody tables (two cars, one tow
# bar): an exact fit must initialise (it used to fail with "constraint rows exceed")
f=models/scenes/lane_change_planar.scn
if make -s image MEASURE=0 TARGET=m7 SCENE=$f >/dev/null; then
    # shellcheck disable=SC2046 # the run command is meant to split into words
    run_check m7 build/image/m7/lane_change_planar.elf lane_change_planar $(make -s print-TARGET_RUN_m7)
    # an effect the scene omits is not linked: its cars have linear tires, no Magic Formula
    if arm-none-eabi-nm build/image/m7/lane_change_planar.elf | grep -qw 'magic'; then
        bad "lane_change_planar (linear tires) links the Magic-Formula tire law"
    else ok; fi
else bad "m7 image of $f did not build"; fi

if make -s image MEASURE=0 TARGET=m7 SCENE=pi_loop CONSOLE=none >/dev/null; then
    n=$(arm-none-eabi-objdump -d build/image/m7/pi_loop.elf | grep -c 'bkpt')
    if [ "$n" = 0 ]; then ok; else bad "CONSOLE=none image has $n bkpt instructions"; fi
else bad "m7 CONSOLE=none image did not build"; fi
if make -s image MEASURE=0 TARGET=m7 SCENE=pi_loop >/dev/null &&
   [ "$(arm-none-eabi-objdump -d build/image/m7/pi_loop.elf | grep -c 'bkpt')" -gt 0 ]; then ok
else bad "the default (semihosting) image has no bkpt: the check above cannot fail"; fi

# REAL=float goes beside the double image (it used to overwrite it), and the command the
# build prints runs the image
if make -s image MEASURE=0 TARGET=m4f SCENE=pi_loop >/dev/null &&
   cmd=$(make -s image MEASURE=0 TARGET=m4f SCENE=pi_loop REAL=float | sed -n 's/^image: run it with: //p') &&
   [ -f build/image/m4f/pi_loop.elf ] && [ -f build/image/m4f-float/pi_loop.elf ] &&
   ! cmp -s build/image/m4f/pi_loop.elf build/image/m4f-float/pi_loop.elf; then ok
else bad "REAL=float and double images of pi_loop are not kept apart"; fi
# shellcheck disable=SC2086 # the printed command is meant to split into words
if [ -n "${cmd:-}" ] && $cmd 2>&1 | grep -q '^rt scene pi_loop .* status ok$'; then ok
else bad "the printed command '${cmd:-}' does not run the float image"; fi

# will the scene meet its tick: instructions per tick under QEMU, and the slowest tick in
# time at the clock given (its microseconds are max / MHz), fitting the base tick or not
out=$(make -s image TARGET=m7 SCENE=pi_loop TICKS=200 CLOCK_MHZ=400 2>&1)
set -- $(echo "$out" | sed -n 's/^image: per tick over 200 ticks under QEMU: median \([0-9]*\), max \([0-9]*\) instructions (min \([0-9]*\)); stack \([0-9]*\) bytes$/\1 \2 \3 \4/p')
if [ $# = 4 ] && [ "$3" -le "$1" ] && [ "$1" -le "$2" ] && [ "$3" -gt 0 ] && [ "$4" -gt 0 ]; then ok
else bad "make image: no instructions per tick in '$out'"; fi
us=$(awk -v n="${2:-0}" 'BEGIN { printf "%.1f", n / 400 }')
dt_us=$($M info pi_loop | sed -n 's/^base tick: \([^ ]*\) s$/\1/p' | awk '{ printf "%g", $1 * 1e6 }')
if echo "$out" | grep -q "^image: slowest tick at 400 MHz, one instruction per cycle: $us us of the $dt_us us base tick .*: fits$" &&
   echo "$out" | grep -q '^image: trace hash [0-9a-f]* equals the host'; then ok
else bad "make image: slowest tick not $us us of $dt_us us, fitting, with the host's hash: '$out'"; fi
# a clock too slow for the scene's tick says so (the slowest tick takes max / 0.001 us)
clk=$(awk -v n="${2:-0}" -v d="$dt_us" 'BEGIN { printf "%g", n / d / 2 }')
if make -s image TARGET=m7 SCENE=pi_loop TICKS=200 CLOCK_MHZ=$clk 2>&1 | grep -q ': DOES NOT FIT$'; then ok
else bad "make image at $clk MHz (half of what pi_loop's slowest tick needs) does not say it does not fit"; fi

# source FMUs in images (docs/fmi.md, "FMUs in images"): the bouncing-ball test FMU as FMI
# 2.0 and 3.0 source FMUs (no binary), compiled into images with their functions prefixed
# and their memory from the static arena, on every cross target: 2.0 on m4f, rv32 and rv64,
# 3.0 on m3 (no FPU: the doubles in the C library's soft float, ports/common/softfloat.c),
# m7 and aarch64 (the POSIX port with glibc: no fmu_libc.c). Under QEMU, bounded by an
# instruction budget (tools/qemu/insn_count.c; a run takes 3.2e7 on m4f; aarch64's user-mode
# run by its timeout), each prints
# the hash of modrt's run of the same source FMU on the host, whose trace make test-fmi
# checks against the closed form, with the FMU arena scenec --sizes measured. An arena too small fails rt_init in one line.
W=build/image/fmu-test
rm -rf "$W" && mkdir -p "$W"
export MODRT_FMU_CACHE="$PWD/$W/cache"
budget=100000000
for v in 2 3; do
    python3 tests/fmi/mkfmu.py --cc "${CC:-cc}" --version $v --model bouncing --source-only \
        --out "$W/src_bouncing$v.fmu" --cflags "-std=c11 -O2 -fPIC -shared -Itools/fmi -Itests/fmi"
    sed "s#@V@#$v#g; s#@FMUS@/bouncing$v.fmu#$PWD/$W/src_bouncing$v.fmu#" tests/fmi/scenes/ball_fmu.scn \
        > "$W/fmu_ball$v.scn"
done
for tv in m4f:2 m3:3 rv32:2 m7:3 rv64:2 aarch64:3; do
    t=${tv%:*} v=${tv#*:} elf=build/image/${tv%:*}/fmu_ball${tv#*:}.elf
    # (m4f also measured: its instructions per tick over 200 ticks, and the measuring
    # image's hash against the host's run of the FMU scene)
    m=$([ "$t" = m4f ] && echo "TICKS=200" || echo "MEASURE=0")
    want=$($M run "$W/fmu_ball$v.scn" | sed -n 's/^hash: //p')
    if make -s image $m TARGET=$t SCENE="$W/fmu_ball$v.scn" > "$W/build$t$v.out" 2>&1; then
        # shellcheck disable=SC2046 # the run command is meant to split into words
        got=$(timeout 300 $(make -s "print-TARGET_RUN_$t" | sed "s/^timeout [0-9]* //; s#-kernel\$#-plugin \
              build/host/libinsn_count.so,limit=$budget -kernel#") "$elf" 2>&1)
        h=$(echo "$got" | sed -n 's/^rt scene .* hash \([0-9a-f]*\) status ok$/\1/p')
        if [ -n "$want" ] && [ "$h" = "$want" ]; then ok; echo "image: $t FMI $v.0 source FMU: hash $h = the host's run of it"
        else bad "$t FMI $v.0 source FMU: image hash '$h', host '$want': $got"; fi
        nm=$(make -s "print-TARGET_NM_$t")
        if [ "$t" = aarch64 ]; then # glibc, linked static, brings its own malloc: no
            # object of the image may call one
            heap=$($nm -u build/image/$t/fmu_ball$v.fmu_*.o build/image/$t/obj-fmu_ball$v/*.o |
                   grep -E ' U (calloc|malloc|realloc)$')
        else heap=$($nm "$elf" | grep -E ' T (calloc|malloc)$'); fi
        if [ -n "$heap" ]; then bad "the $t FMI $v.0 FMU image links a heap: $heap"; else ok; fi
        # the arena scenec --sizes measured on this (LP64) host, which the image above ran
        # with: the glue's instance (model_data 72, mode 4, has_next 4, next 8, name 8; 2.0
        # the callbacks' pointer 8, 3.0 environment and logger 16), "Ball" and its 0 (5, up
        # to 8), and the first snapshot's FMU state (model_data 72, mode 4, has_next 4, next
        # 8): 2.0 200, 3.0 208
        if grep -q "^image: FMU arena $((v == 2 ? 200 : 208)) bytes" "$W/build$t$v.out"; then ok
        else bad "$t FMI $v.0 image: not the arena the FMU needs: $(grep arena "$W/build$t$v.out")"; fi
    else bad "$t image of the FMI $v.0 source FMU did not build:"; cat "$W/build$t$v.out"; fi
    [ "$t" = m4f ] || continue
    if grep -q '^image: per tick over 200 ticks under QEMU: median [1-9][0-9]*, max [1-9]' "$W/build$t$v.out" &&
       grep -q '^image: trace hash [0-9a-f]* equals the host' "$W/build$t$v.out"; then ok
    else bad "make image of an FMU scene: no measurement: $(grep '^image:' "$W/build$t$v.out")"; fi
done
# (3.0 on m4f: the working 2.0 image stays beside it)
# shellcheck disable=SC2046
if make -s image MEASURE=0 TARGET=m4f SCENE="$W/fmu_ball3.scn" IMAGE_CFLAGS=-DFMU_ARENA_BYTES=64 >/dev/null 2>&1 &&
   timeout 300 $(make -s print-TARGET_RUN_m4f | sed 's/^timeout [0-9]* //') \
       build/image/m4f/fmu_ball3.elf 2>&1 | grep -q '^rt scene ball_fmu3 init parameter out of range: block Ball'
then ok; else bad "an FMU image with a 64-byte arena does not fail its rt_init in one line"; fi

# snapshots in an image (tests/fmi/snap_image.c as the application, docs/fmi.md
# "Snapshots"): a run snapshotted (rt_snapshot, the FMU's own state in it), run on across
# the FMU's events, restored and run on again. The stair (3.0: its counter lives in the
# FMU's memory; two blocks of one FMU) at tick 10 of 1/8 s, to 3 s; the ball (2.0: its
# state through allocateMemory) at 0.6 s, to 1.5 s. On m4f the straight, the run-on and
# the restored hash must all be the host's straight run of the same scene
# (tests/fmi/snap.c, whose restored rows make test-fmi checks against the closed forms)
for c in stair:3:10:24 bouncing:2:600:1500; do
    md=${c%%:*} r=${c#*:} v=${r%%:*} r=${r#*:} n1=${r%%:*} n2=${r#*:}
    s=$([ "$md" = stair ] && echo stair || echo ball)
    [ -e "$W/src_$md$v.fmu" ] || python3 tests/fmi/mkfmu.py --cc "${CC:-cc}" --version $v \
        --model $md --source-only --out "$W/src_$md$v.fmu" --cflags "-std=c11 -O2 -fPIC -shared -Itools/fmi -Itests/fmi"
    sed "s#@V@#$v#g; s#@FMUS@/$md$v.fmu#$PWD/$W/src_$md$v.fmu#" "tests/fmi/scenes/${s}_fmu.scn" > "$W/snap_$s$v.scn"
    dt=$([ "$md" = stair ] && echo 0.125 || echo 0.001)
    want=$(build/host/fmi/snap "$W/snap_$s$v.scn" "$(awk "BEGIN { print $n1 * $dt }")" "$(awk "BEGIN { print $n2 * $dt }")" \
           "$W/snap_$s$v.csv" | sed -n 's/^straight: //p')
    if IMAGE_MAIN=tests/fmi/snap_image.c make -s image MEASURE=0 TARGET=m4f SCENE="$W/snap_$s$v.scn" \
           IMAGE_CFLAGS="-DSNAP_N1=$n1 -DSNAP_N2=$n2" > "$W/snap$s$v.out" 2>&1; then
        # shellcheck disable=SC2046 # the run command is meant to split into words
        got=$(timeout 300 $(make -s print-TARGET_RUN_m4f | sed "s/^timeout [0-9]* //; s#-kernel\$#-plugin \
              build/host/libinsn_count.so,limit=$budget -kernel#") "build/image/m4f/snap_$s$v.elf" 2>&1)
        if [ -n "$want" ] && echo "$got" | grep -q "^snap scene ${s}_fmu$v snapshot ok restore ok straight $want on $want restored $want status ok\$"
        then ok; echo "image: m4f FMI $v.0 $s snapshotted at tick $n1, restored after tick $n2: hash $want = the host's"
        else bad "m4f FMI $v.0 $s snapshot: host $want, image: $got"; fi
    else bad "m4f snapshot image of the FMI $v.0 $s did not build:"; cat "$W/snap$s$v.out"; fi
done

echo "image: $pass passed, $fail failed"
[ $fail -eq 0 ]
