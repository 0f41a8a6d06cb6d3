#!/bin/sh
# effects.sh - only the effects a scene calls for (issue 7): every compiled scene of
# build/gen/scenes is linked alone (tests/scenec/one_scene.c) with the whole runtime and
# model library, objects built with -ffunction-sections -fdata-sections and linked with
# -Wl,--gc-sections, run, and its image read with `nm -l` (symbols with their source
# files, from the debug information). The check fails when an image holds
#   - any symbol of a model unit (models/<unit>.c) that defines none of the scene's kinds,
#   - a kind (mdl_*_kind) the scene does not name,
#   - a runtime service the scene does not select: an integrator, a joint kind, the LSS
#     services, the multibody code (rt/mbs*.c, rt/joints.c) or the loop solver (rt/loop.c).
# A control image that forces the kinds registry in must fail the same check.
# Usage: CC=gcc CFLAGS='...' sh tests/scenec/effects.sh BUILD_DIR   (e.g. build/host)
set -u
O=$1
CC=${CC:-cc}
CFLAGS=${CFLAGS:--std=c11 -O2 -g -Irt -Imodels}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
RT=$(ls "$O"/obj/rt/*.o)
MODELS=$(ls "$O"/obj/models/*.o)
SERVICES="rt_mbs rt_broyden rt_lss_output rt_lss_deriv rt_euler rt_heun rt_bs3 rt_rk4
          rt_dopri5 rt_beuler rt_trap rt_sdirk2 rt_sdirk3 rt_ros2 rt_joint_sphdiff
          rt_joint_spherical rt_joint_revolute rt_joint_fixed"
fail=0

# which unit defines each kind: "mdl_x_kind unit"
for m in $MODELS; do
    nm --defined-only "$m" | awk -v u="$(basename "$m" .o)" '$3 ~ /^mdl_.*_kind$/ { print $3, u }'
done > "$T/kinds"

# does the image $1 (nm -l in $T/nm) hold a symbol of source file $2 (e.g. models/pi.c)?
has_unit() { grep -qE "[[:space:]](.*/)?$1:[0-9]+\$" "$T/nm"; }
# is symbol $1 defined in the image?
has_sym() { awk -v s="$1" '$3 == s && $2 != "U" { f = 1 } END { exit !f }' "$T/nm"; }

# check_image IMAGE SCENE_OBJECT: prints the foreign parts, returns 1 if there are any
check_image() {
    nm -u "$2" | awk '{ print $2 }' | sort -u > "$T/refs"
    grep -E '^mdl_.*_kind$' "$T/refs" > "$T/used"
    units=$(while read -r k; do awk -v k="$k" '$1 == k { print $2 }' "$T/kinds"; done \
            < "$T/used" | sort -u)
    nm -l "$1" > "$T/nm"
    foreign=""
    for m in $MODELS; do
        u=$(basename "$m" .o)
        echo "$units" | grep -qx "$u" && continue
        has_unit "models/$u.c" && foreign="$foreign models/$u.c"
    done
    for k in $(awk '$3 ~ /^mdl_.*_kind$/ { print $3 }' "$T/kinds"); do
        grep -qx "$k" "$T/used" || ! has_sym "$k" || foreign="$foreign $k"
    done
    for s in $SERVICES; do
        grep -qx "$s" "$T/refs" || ! has_sym "$s" || foreign="$foreign $s"
    done
    if ! grep -qx rt_mbs "$T/refs"; then
        for u in mbs mbs_asm mbs_project joints; do
            has_unit "rt/$u.c" && foreign="$foreign rt/$u.c"
        done
    fi
    grep -qx rt_broyden "$T/refs" || ! has_unit rt/loop.c || foreign="$foreign rt/loop.c"
    linked=$(echo "$units" | tr '\n' ' ')
    [ -z "$foreign" ] && { echo "models ${linked:-none}"; return 0; }
    echo "FOREIGN:$foreign"
    return 1
}

n=0
for s in "$O"/obj/build/gen/scenes/*.o; do
    name=$(basename "$s" .o)
    [ "$name" = registry ] && continue
    n=$((n + 1))
    $CC $CFLAGS -DSCN_ONE=mdl_scene_"$name" -c tests/scenec/one_scene.c -o "$T/main.o" &&
        $CC -Wl,--gc-sections "$T/main.o" "$s" $RT $MODELS -o "$T/$name" || { fail=1; continue; }
    run=$("$T/$name") || { echo "FAIL effects: $name image does not run"; fail=1; }
    report=$(check_image "$T/$name" "$s") || fail=1
    size=$(size "$T/$name" | awk 'NR == 2 { printf "text %6d data %5d", $1, $2 }')
    printf 'effects: %-26s %s  %s  (hash %s)\n' "$name" "$size" "$report" "${run##* }"
done
[ "$n" -gt 0 ] || { echo "FAIL effects: no compiled scenes in $O/obj/build/gen/scenes"; exit 1; }

# control: the same check on an image that drags in every kind must fail
first=$(ls "$O"/obj/build/gen/scenes/*.o | grep -v registry | head -1)
name=$(basename "$first" .o)
$CC $CFLAGS -DSCN_ONE=mdl_scene_"$name" -c tests/scenec/one_scene.c -o "$T/main.o"
$CC -Wl,--gc-sections -Wl,--undefined=mdl_kinds "$T/main.o" "$first" $RT $MODELS -o "$T/control"
if report=$(check_image "$T/control" "$first"); then
    echo "FAIL effects: the control image (with the kinds registry) passed the check"; fail=1
else
    echo "effects: control ($name, kinds registry forced in) caught: ${report#FOREIGN: }" |
        cut -c1-100
fi
[ "$fail" -eq 0 ] && echo "effects: ok, $n scene images hold only what their scenes name"
exit $fail
