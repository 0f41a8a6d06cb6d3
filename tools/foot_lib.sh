# foot_lib.sh - what tools/footprint.sh and tools/effects.sh share: build one footprint
# image (make foot-elf), run it under QEMU with the instruction-count plugin
# (tools/qemu/insn_count.c) and read its sizes, stack, instruction counts, models and hash.
# Sourced (sh has no modules); the caller sets M (the host modrt) and so (the plugin).

# MHz of the stated clock of a target
mhz() { case $1 in m3) echo 72;; m4f) echo 168;; m7) echo 600;; rv32) echo 100;; *) echo 1000;; esac; }

# foot_measure TARGET SCENE REAL [SCN]: builds build/foot/<target>[-float]/<scene>.elf (a
# library scene, or the scene file SCN whose scene is named SCENE) and sets flash, ram
# (bytes), stack (high-water mark), stats ("min | median | max" instructions per tick),
# max, models (the kinds linked) and hash (the image's trace hash)
foot_measure() {
    fm_t=$1 fm_s=$2 fm_real=$3 fm_scn=${4:-} # sh has no locals: names the callers do not use
    fm_sfx=
    [ "$fm_real" = float ] && fm_sfx=-float
    make -s foot-elf T="$fm_t" S="$fm_s" REAL="$fm_real" ${fm_scn:+SCN="$fm_scn"} \
        ${FOOT_TICKS:+FOOT_TICKS="$FOOT_TICKS"}
    fm_elf=build/foot/$fm_t$fm_sfx/$fm_s.elf
    fm_size=$(make -s "print-TARGET_SIZE_$fm_t")
    fm_nm=$(make -s "print-TARGET_NM_$fm_t")
    set -- $($fm_size "$fm_elf" | awk 'NR == 2 {print $1, $2, $3}')
    flash=$(($1 + $2)) ram=$(($2 + $3))
    fm_addr=$($fm_nm "$fm_elf" | awk '$3 == "port_cycles" {print $1}')
    fm_run=$(make -s "print-TARGET_RUN_$fm_t")
    # the run command ends in -kernel: put the plugin before it
    fm_out=$(eval "$(echo "$fm_run" | sed "s|-kernel\$|-plugin $(pwd)/$so,addr=0x$fm_addr -d plugin -kernel|") $fm_elf" 2>&1 || true)
    hash=$(echo "$fm_out" | sed -n 's/.* hash \([0-9a-f]*\) .*/\1/p')
    stack=$(echo "$fm_out" | sed -n 's/.* stack \([0-9]*\).*/\1/p')
    stats=$(echo "$fm_out" | sed -n 's/.*min \([0-9]*\) median \([0-9]*\) max \([0-9]*\).*/\1 | \2 | \3/p')
    max=$(echo "$fm_out" | sed -n 's/.*max \([0-9]*\).*/\1/p')
    models=$($fm_nm "$fm_elf" | awk '$3 ~ /^mdl_.*_kind$/ {sub(/^mdl_/, "", $3); sub(/_kind$/, "", $3); print $3}' | sort | tr '\n' ' ')
}
