#!/bin/sh
# image.sh - `make image`: builds a per-scene firmware image for one cross target from any
# scene file (or library scene name): scenec compiles the scene to C, `scenec --sizes`
# gives its exact limits, and the image links ports/common/image_main.c, the runtime and the
# models without registries (unused kinds are dropped by --gc-sections). docs/porting.md
# explains the pieces. Usage (through make, which passes its variables):
#   sh tools/image.sh TARGET SCENE CONSOLE EXTRA_CFLAGS [CLOCK_MHZ [TICKS [MEASURE]]]
# Then it says whether the scene meets its tick: the scene's footprint image (the same
# scene, runtime, models and limits, tests/cross/footprint_main.c) runs under QEMU with the
# instruction-count plugin for TICKS ticks (default: the whole scene, at most
# IMAGE_TICKS_MAX), and the slowest tick at CLOCK_MHZ (default: the target's stated clock
# of make footprint) is compared with the scene's base tick. MEASURE=0: the image only.
# IMAGE_MAIN (environment) names another application than ports/common/image_main.c (a
# test's, e.g. tests/fmi/snap_image.c); IMAGE_MAIN_CFLAGS (environment) are added to the
# application's compile alone (a test's: main compiled with other limits than the runtime).
set -u
target=$1 scene=$2 console=$3 extra=$4 clock=${5:-} ticks=${6:-} measure=${7:-1}
main=${IMAGE_MAIN:-ports/common/image_main.c}
IMAGE_TICKS_MAX=10000
targets=$(make -s print-CROSS_TARGETS)
fail() { echo "make image: $*" >&2; exit 2; }

case "$clock" in '' | *[!0-9.]* | .*) [ -z "$clock" ] || fail "CLOCK_MHZ '$clock' is not a clock in MHz (e.g. CLOCK_MHZ=400)" ;; esac
case "$ticks" in *[!0-9]* | 0) fail "TICKS '$ticks' is not a number of ticks" ;; esac
case "$measure" in 0 | 1) ;; *) fail "MEASURE '$measure': expected 0 (the image only) or 1" ;; esac
[ -n "$target" ] || fail "TARGET is missing; usage: make image TARGET=<$(echo $targets | tr ' ' '|')> SCENE=<file.scn|name> [CONSOLE=semihost|uart|itm|none]"
[ -n "$scene" ] || fail "SCENE is missing; usage: make image TARGET=$target SCENE=<file.scn|name> [CONSOLE=semihost|uart|itm|none]"
case " $targets " in *" $target "*) ;; *) fail "unknown TARGET '$target'; expected one of: $targets" ;; esac
case "$scene" in
*.scn) [ -r "$scene" ] || fail "SCENE '$scene': cannot read the file" ;;
*) [ -r "models/scenes/$scene.scn" ] || fail "SCENE '$scene' is neither a .scn file nor a library scene (modrt list)"
   scene=models/scenes/$scene.scn ;;
esac
case "$target" in
m3 | m4f | m7)
    case "${console:-semihost}" in
    semihost) cdef=-DCM_CONSOLE=CM_CONSOLE_SEMIHOST ;;
    uart) cdef=-DCM_CONSOLE=CM_CONSOLE_UART ;;
    itm) cdef=-DCM_CONSOLE=CM_CONSOLE_ITM ;;
    none) cdef=-DCM_CONSOLE=CM_CONSOLE_NONE ;;
    *) fail "unknown CONSOLE '$console'; expected semihost, uart, itm or none" ;;
    esac ;;
*) [ -z "$console" ] || fail "CONSOLE applies to the Cortex-M targets only (the $target port has one console)"
   cdef= ;;
esac
make -s "check-target-$target" 2>/dev/null || fail "the $target toolchain or QEMU is missing: run sh tools/install-deps.sh"

name=$(basename "$scene" .scn)
# a binary32 image (REAL=float) goes beside the double one, never over it
real=$(make -s print-REAL)
dir=build/image/$target$( [ "$real" = float ] && echo -float)
mkdir -p "$dir"
build/host/scenec -o "$dir/$name.c" "$scene" || fail "scenec could not compile $scene (see above)"
sym=$(sed -n 's/^const rt_scene \(mdl_scene_[A-Za-z0-9_]*\) = {$/\1/p' "$dir/$name.c" | head -1)
[ -n "$sym" ] || fail "no scene table in $dir/$name.c"
sizes=$(build/host/scenec --sizes "$scene") || fail "scenec --sizes $scene failed (see above)"
# an FMU arena given in IMAGE_CFLAGS replaces the one scenec measured (docs/fmi.md)
case " $extra " in *" -DFMU_ARENA_BYTES="*) sizes=$(echo "$sizes" | sed 's/ -DFMU_ARENA_BYTES=[0-9]*//') ;; esac
# a background set steps at the port's level below the timer, in a second rt_sim
grep -q '\.bg = &rt_bg' "$dir/$name.c" && sizes="$sizes -DRT_IMAGE_BG=1"
# a controller link runs over the port's link UART (docs/link.md, "The plant on a board")
linksrc=
if grep -q '^static const rt_link link = {' "$dir/$name.c"; then
    case "$target" in
    m3 | m4f | m7) ;;
    *) fail "scene $name has a controller link: its image needs a port with a link UART (m3, m4f, m7), not $target" ;;
    esac
    [ "${console:-semihost}" != uart ] || fail "scene $name has a controller link on the UART: CONSOLE=uart would share it; use semihost, itm or none"
    sizes="$sizes -DRT_IMAGE_LINK=1"
    linksrc="ports/common/image_link.c ports/common/link_wire.c ports/common/link_hmac.c ports/common/linkframe.c ports/cortex-m/uart.c"
fi

cc=$(make -s "print-TARGET_CC_$target")
# FMU blocks (docs/fmi.md, "FMUs in images"): scenec wrote one "// fmu-build:" line each,
# BLOCK VERSION ID SOURCES WORDS...; their sources are compiled with their functions named
# <ID>_fmi*, FMI 3.0's calloc, malloc and free naming the static arena (fmu_arena.c), and
# linked with the importer's calling sequence built for targets (FMU_TARGET)
fmuobjs= fmusrc= fmulibc=
fmu_lines=$(sed -n 's#^// fmu-build: ##p' "$dir/$name.c")
if [ -n "$fmu_lines" ]; then
    # a toolchain without a C library (the RISC-V ones) gets the few headers FMU code may
    # use, declaring what the image gives it (tools/fmi/libc/)
    echo '#include <stdio.h>' | $cc $(make -s "print-TARGET_CFLAGS_$target") -E -x c - >/dev/null 2>&1 ||
        fmulibc="-isystem tools/fmi/libc"
    # fmu_libc.c stands in for the C library of ports that link none (-nostdlib); a port
    # that links its own (the POSIX one on aarch64) has these functions already
    libc_c=tools/fmi/fmu_libc.c
    case " $(make -s "print-TARGET_LDFLAGS_$target") " in *" -nostdlib "*) ;; *) libc_c= ;; esac
    fmusrc="tools/fmi/fmu_inst.c tools/fmi/fmu_state.c tools/fmi/fmu_call.c tools/fmi/fmu_arena.c $libc_c"
    echo "$fmu_lines" > "$dir/$name.fmu"
    seen=
    while read -r blk ver id src words; do
        # several blocks of one FMU share its functions: compiled once
        case " $seen " in *" $id "*) continue ;; esac
        seen="$seen $id"
        defs="-DFMI${ver}_FUNCTION_PREFIX=${id}_"
        [ "$ver" = 3 ] && defs="$defs -Dcalloc=fmu_arena_calloc -Dmalloc=fmu_arena_malloc -Dfree=fmu_arena_free"
        files= flags=
        for w in $words; do
            case "$w" in
            -I*) flags="$flags -I$src/${w#-I}" ;;
            -D*) flags="$flags $w" ;;
            -l*) ;;
            *) files="$files $src/$w" ;;
            esac
        done
        k=0
        for f in $files; do
            k=$((k + 1)) o=$dir/$name.fmu_${blk}_$k.o
            # shellcheck disable=SC2086 # the flag lists are meant to split
            $(make -s "print-TARGET_CC_$target") -std=c11 -O2 -w -ffp-contract=off -fno-math-errno \
                -ffunction-sections -fdata-sections $(make -s "print-TARGET_CFLAGS_$target") \
                -I"$src" $flags $defs $fmulibc -c "$f" -o "$o" || fail "the $target build of FMU $blk's $f failed (see above)"
            fmuobjs="$fmuobjs $o"
        done
    done < "$dir/$name.fmu"
fi
cflags="$(make -s print-CSTD) -O2 -ffunction-sections -fdata-sections $(make -s print-CINC) \
 $(make -s print-CDEFS) -DRT_KIND_DOCS=0 $(make -s "print-TARGET_CFLAGS_$target")"
ldflags=$(make -s "print-TARGET_LDFLAGS_$target")
ports=$(make -s "print-TARGET_PORT_SRCS_$target")
rt=$(ls rt/*.c | grep -v '^rt/registry.c$')
models=$(ls models/*.c | grep -v '^models/registry.c$')
# every source compiled on its own, JOBS at a time (make passes JOBS; one compile of
# everything at once used to dominate `make test-image`), then linked in the listed order
obj=$dir/obj-$name
rm -rf "$obj" && mkdir -p "$obj"
export IMG_CC="$cc" IMG_FLAGS="$cflags $cdef $sizes -DRT_SCENE=$sym $extra${fmusrc:+ -DFMU_TARGET -Itools/fmi $fmulibc}" IMG_OBJ="$obj"
export IMG_MAIN="$main" IMG_MAIN_FLAGS="${IMAGE_MAIN_CFLAGS:-}"
srcs="$main $dir/$name.c $rt $models $ports $linksrc $fmusrc"
# shellcheck disable=SC2086,SC2016 # the lists are meant to split; $1 expands in the child
printf '%s\n' $srcs | xargs -P "${JOBS:-2}" -I{} sh -c \
    'o=$IMG_OBJ/$(echo "$1" | tr / _).o; m=; [ "$1" = "$IMG_MAIN" ] && m=$IMG_MAIN_FLAGS
     $IMG_CC $IMG_FLAGS $m -c "$1" -o "$o"' sh {} ||
    fail "the $target build of $scene failed (see above)"
objs=$(for f in $srcs; do printf '%s/%s.o ' "$obj" "$(echo "$f" | tr / _)"; done)
# shellcheck disable=SC2086 # the flag lists are meant to split
$cc $cflags $objs $fmuobjs $ldflags -o "$dir/$name.elf" || fail "the $target build of $scene failed (see above)"
size=$(make -s "print-TARGET_SIZE_$target")
echo "image: $dir/$name.elf (scene $sym, target $target, $real${console:+, console $console}${linksrc:+, link on the UART})"
$size "$dir/$name.elf" | tail -1 | awk '{printf "image: flash %d bytes, RAM %d bytes\n", $1 + $2, $2 + $3}'
arena=$(echo " $sizes $extra" | sed -n 's/.* -DFMU_ARENA_BYTES=\([0-9]*\).*/\1/p')
[ -z "$fmusrc" ] || echo "image: FMU arena ${arena:-16384 (the default: scenec could not measure it)} bytes (FMU_ARENA_BYTES)"
# how to run it: the target's QEMU command; a UART console prints on the serial port
run=$(make -s "print-TARGET_RUN_$target")
[ "${console:-semihost}" = uart ] && run=$(echo "$run" | sed 's/-serial null/-serial stdio/')
echo "image: run it with: $run $dir/$name.elf"
[ "$measure" = 1 ] || exit 0
# the measuring image (make foot-elf) links the FMU blocks as this image does
# shellcheck disable=SC2034 # read by foot_measure
[ -z "$fmusrc" ] || FOOT_FMU="-DFMU_TARGET -Itools/fmi $fmulibc $fmusrc $fmuobjs"

# will it meet its tick? (tools/foot_lib.sh measures as make footprint does)
# shellcheck disable=SC2034 # M and so are read by tools/foot_lib.sh
M=build/host/modrt so=$(make -s print-INSN_COUNT_SO)
. tools/foot_lib.sh
info=$($M info "$scene") || fail "modrt info $scene failed (see above)"
dt=$(echo "$info" | sed -n 's/^base tick: \([^ ]*\) s$/\1/p')
t_end=$(echo "$info" | sed -n 's/^end time: \([^ ]*\) s$/\1/p')
[ -n "$ticks" ] || ticks=$(awk -v e="$t_end" -v d="$dt" -v m=$IMAGE_TICKS_MAX 'BEGIN {
    n = int(e / d + 0.5); print n < m ? n : m }')
[ -n "$clock" ] || clock=$(mhz "$target")
# shellcheck disable=SC2034 # read by foot_measure
FOOT_TICKS=$ticks
# the path the image runs: the scene's written-out code, or with -DRT_SCENE_CODE=0 in
# IMAGE_CFLAGS the table-driven one (rt/rt_config.h); the measuring image runs the same
FOOT_CFLAGS=$(printf '%s\n' $extra | grep '^-DRT_SCENE_CODE=' | tail -1)
if [ "$FOOT_CFLAGS" = -DRT_SCENE_CODE=0 ]; then
    echo "image: the table-driven path (IMAGE_CFLAGS -DRT_SCENE_CODE=0)"
elif grep -q '^    \.code = &scene_code,$' "$dir/$name.c"; then
    echo "image: the code scenec wrote out for the scene (IMAGE_CFLAGS=-DRT_SCENE_CODE=0: the table-driven path)"
fi
foot_measure "$target" "${sym#mdl_scene_}" "$real" "$scene" ||
    fail "the measuring image of $scene on $target failed (see above)"
[ -n "$stats" ] || fail "no instruction counts from the run of $fm_elf under QEMU"
echo "$stats" | awk -F'|' -v n="$ticks" -v st="$stack" '{
    printf "image: per tick over %d ticks under QEMU: median %d, max %d instructions (min %d); stack %d bytes\n", n, $2, $3, $1, st }'
awk -v n="$max" -v f="$clock" -v dt="$dt" -v def="$( [ "$clock" = "$(mhz "$target")" ] && echo " (the stated clock of $target; set CLOCK_MHZ=...)")" 'BEGIN {
    us = n / f; fit = us <= dt * 1e6
    printf "image: slowest tick at %g MHz%s, one instruction per cycle: %.1f us of the %g us base tick (%.0f %%): %s\n",
        f, def, us, dt * 1e6, 100 * us / (dt * 1e6), fit ? "fits" : "DOES NOT FIT" }'
if echo "$info" | grep -q '^ *background:'; then
    foot_count "$fm_elf" "$target" foot_bg_begin foot_bg_end |
        sed -n 's/.*intervals \([0-9]*\) min \([0-9]*\) median \([0-9]*\) max \([0-9]*\).*/image: background context: \1 steps, median \3, max \4 instructions per step (min \2)/p'
fi
if [ "$real" = double ]; then # the float image's reference is the host's float build
    host=$($M run "$scene" --t-end "$(awk -v d="$dt" -v n="$ticks" 'BEGIN { printf "%.17g", d * n }')" |
           sed -n 's/^hash: //p')
    [ "$hash" = "$host" ] && echo "image: trace hash $hash equals the host's over the same ticks" ||
        echo "image: trace hash $hash differs from the host's $host over the same ticks"
fi
