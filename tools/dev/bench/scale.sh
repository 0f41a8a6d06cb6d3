#!/bin/sh
# scale.sh - how modrt's cost grows with the model (tools/dev/bench/scale_bench.c): per-step
# instructions of a chain of N mass points and of a tree (a spine with a point hanging
# from each of its points) for N = 10, 30, 100, 300, 1000, beside the chain's tight
# program (tools/dev/bench/pendulum_tight.c for N points), and the exponent p of a
# least-squares fit cost = a N^p over them. The scenes are built by scale_bench itself
# (scenec's statement limits hold hand-written scenes); the runtime is built once for them
# all with limits that hold the largest (BIG; the library's defaults, rt/rt_config.h, are
# left alone), and scale_bench's `sizes` prints each scene's exact sizes beside it. Exact
# sizes change the count by 0.1 % at N = 10 (loops over a limit), less above. Counted by
# callgrind over STEPS steps of dopri5 at 5 ms (toggle-collect on modrt_ticks or
# tight_steps; start-up outside). Prints a Markdown table and the lines
#   scaling <shape> <side>: cost ~ N^<p>
# Usage: sh tools/dev/bench/scale.sh [STEPS [N...]]
#        SCALE_DATA=FILE sh tools/dev/bench/scale.sh   the table of measured lines
#                                                  "shape N modrt tight" in FILE
#        SCALE_BUILD_ONLY=1 sh tools/dev/bench/scale.sh [STEPS [N...]]
#                                                  only build build/scale/scale-SHAPE-N
#                                                  (tools/dev/bench/mujoco_scale.py runs them)
set -eu
STEPS=${1:-20}
if [ $# -gt 0 ]; then shift; fi
NS=${*:-10 30 100 300 1000}
B=build/scale
mkdir -p $B
CF="$(make -s print-CSTD) -O2 -Irt -Imodels -Itools/dev/bench"
# limits for any scene here (bodies <= 1024): only for finding the exact sizes
BIG="-DRT_MAX_BLOCKS=1024 -DRT_MAX_X=6144 -DRT_MAX_Y=6144 -DRT_MAX_P=4096 -DRT_MAX_JOINTS=1024 \
 -DRT_MAX_MBS_Z=3072 -DRT_MAX_MBS_Q=3072 -DRT_MAX_MBS_C=1024 -DRT_MAX_MBS_TW=32768 \
 -DRT_MAX_MBS_TY=32768 -DRT_MAX_MBS_PAIRS=32768 -DRT_MAX_MBS_LNZ=32768 -DRT_MAX_SEQ=8192 \
 -DRT_MAX_MBS_ROWS=1024 -DRT_MAX_MBS_TOUCH=2048 -DRT_MAX_MBS_M=12288 -DRT_MAX_MBS_JROWS=1024"
count() { # binary side function -> instructions per step
    f=$(mktemp)
    valgrind --tool=callgrind --callgrind-out-file="$f" --toggle-collect="$3" "$1" "$2" \
        "$STEPS" > /dev/null 2>&1 || { echo "scale.sh: $1 $2 failed" >&2; rm -f "$f"; exit 1; }
    n=$(sed -n 's/^summary: //p' "$f")
    rm -f "$f"
    echo $((n / STEPS))
}
T=$(mktemp)
trap 'rm -f $T' EXIT
[ -z "${SCALE_DATA:-}" ] || { cp "$SCALE_DATA" "$T"; NS=; }
# the runtime and the point model, once, with BIG (again when a source, a header or this
# script is newer)
mkdir -p $B/obj
# shellcheck disable=SC2012 # plain file names: the newest header of the runtime
hdr=$(ls -t rt/*.h models/*.h | head -n 1)
[ -z "$NS" ] || for f in rt/*.c models/mbs_point.c; do
    [ "$f" = rt/registry.c ] && continue
    o=$B/obj/$(echo $f | tr / _ | sed 's/\.c$/.o/')
    # shellcheck disable=SC2086 # the flag lists are meant to split
    [ -n "$(find "$o" -newer "$f" -newer "$0" -newer "$hdr" 2>/dev/null)" ] ||
        gcc $CF $BIG -c $f -o "$o"
done
for shape in chain tree; do
    tree=0
    [ $shape = tree ] && tree=1
    for n in $NS; do
        d="-DSCALE_N=$n -DSCALE_TREE=$tree -DTIGHT_NB=$n"
        # shellcheck disable=SC2086
        gcc $CF $BIG $d tools/dev/bench/scale_bench.c tools/dev/bench/pendulum_tight.c $B/obj/*.o -lm \
            -o $B/scale-$shape-$n
        $B/scale-$shape-$n sizes > $B/sizes-$shape-$n.txt
        [ -z "${SCALE_BUILD_ONLY:-}" ] || continue
        r=$(count $B/scale-$shape-$n modrt modrt_ticks)
        t=-
        [ $shape = chain ] && t=$(count $B/scale-$shape-$n tight tight_steps)
        echo "$shape $n $r $t" >> $T
        echo "scaling $shape N = $n: modrt $r, tight $t instructions per step" >&2
    done
done
[ -z "${SCALE_BUILD_ONLY:-}" ] || exit 0
awk '
function fit(sh, col,    i, sx, sy, sxx, sxy, k, x, y) {
    k = 0; sx = sy = sxx = sxy = 0
    for (i = 1; i <= m; i++) if (s[i] == sh && v[i, col] != "-") {
        x = log(n[i]); y = log(v[i, col]); k++
        sx += x; sy += y; sxx += x * x; sxy += x * y }
    return (k * sxy - sx * sy) / (k * sxx - sx * sx)
}
{ m++; s[m] = $1; n[m] = $2; v[m, 3] = $3; v[m, 4] = $4 }
END {
    print "| shape | N (bodies = joints) | modrt insn/step | per body | tight program insn/step | per body | modrt / tight |"
    print "|---|--:|--:|--:|--:|--:|--:|"
    for (i = 1; i <= m; i++)
        if (v[i, 4] == "-")
            printf "| %s | %d | %d | %.0f | - | - | - |\n", s[i], n[i], v[i, 3], v[i, 3] / n[i]
        else
            printf "| %s | %d | %d | %.0f | %d | %.0f | %.2f |\n", s[i], n[i], v[i, 3], v[i, 3] / n[i], v[i, 4], v[i, 4] / n[i], v[i, 3] / v[i, 4]
    printf "\nFitted exponent p of cost = a N^p (least squares on log-log): modrt chain %.3f, modrt tree %.3f, tight chain %.3f.\n", fit("chain", 3), fit("tree", 3), fit("chain", 4)
    printf "scaling chain modrt: cost ~ N^%.3f\nscaling tree modrt: cost ~ N^%.3f\nscaling chain tight: cost ~ N^%.3f\n", fit("chain", 3), fit("tree", 3), fit("chain", 4) > "/dev/stderr"
}' $T
