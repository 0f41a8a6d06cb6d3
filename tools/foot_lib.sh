# foot_lib.sh - what make image (tools/image.sh), tools/dev/footprint.sh and tools/dev/effects.sh share: build one footprint
# image (make foot-elf), run it under QEMU with the instruction-count plugin
# (tools/dev/qemu/insn_count.c) and read its sizes, stack, instruction counts, models and hash.
# Sourced (sh has no modules); the caller sets M (the host modrt) and so (the plugin).

# MHz of the stated clock of a target
mhz() { case $1 in m3) echo 72;; m4f) echo 168;; m7) echo 600;; rv32) echo 100;; *) echo 1000;; esac; }

# foot_count ELF TARGET FROM TO: runs the image under the plugin, counting the
# instructions from each call of symbol FROM to the next of symbol TO (the tick context:
# port_cycles to foot_tick_end; the background context: foot_bg_begin to foot_bg_end);
# prints the image's and the plugin's lines
foot_count() {
    fc_nm=$(make -s "print-TARGET_NM_$2")
    fc_a=$($fc_nm "$1" | awk -v s="$3" '$3 == s {print $1}')
    fc_b=$($fc_nm "$1" | awk -v s="$4" '$3 == s {print $1}')
    fc_run=$(make -s "print-TARGET_RUN_$2")
    # the run command ends in -kernel: put the plugin before it
    eval "$(echo "$fc_run" | sed "s|-kernel\$|-plugin $(pwd)/$so,addr=0x$fc_a,stop=0x$fc_b -d plugin -kernel|") $1" 2>&1 || true
}

# foot_measure TARGET SCENE REAL [SCN]: builds (with FOOT_CFLAGS if set) build/foot/<target>[-float]/<scene>.elf (a
# library scene, or the scene file SCN whose scene is named SCENE) and sets flash, ram
# (bytes), stack (high-water mark), stats ("min | median | max" instructions per tick),
# max, models (the kinds linked) and hash (the image's trace hash); fm_elf is the image
foot_measure() {
    fm_t=$1 fm_s=$2 fm_real=$3 fm_scn=${4:-} # sh has no locals: names the callers do not use
    fm_sfx=
    [ "$fm_real" = float ] && fm_sfx=-float
    make -s foot-elf T="$fm_t" S="$fm_s" REAL="$fm_real" ${fm_scn:+SCN="$fm_scn"} \
        ${FOOT_TICKS:+FOOT_TICKS="$FOOT_TICKS"} ${FOOT_CFLAGS:+FOOT_CFLAGS="$FOOT_CFLAGS"} ${FOOT_FMU:+FOOT_FMU="$FOOT_FMU"}
    fm_elf=build/foot/$fm_t$fm_sfx/$fm_s.elf
    fm_size=$(make -s "print-TARGET_SIZE_$fm_t")
    fm_nm=$(make -s "print-TARGET_NM_$fm_t")
    set -- $($fm_size "$fm_elf" | awk 'NR == 2 {print $1, $2, $3}')
    flash=$(($1 + $2)) ram=$(($2 + $3))
    fm_out=$(foot_count "$fm_elf" "$fm_t" port_cycles foot_tick_end)
    hash=$(echo "$fm_out" | sed -n 's/.* hash \([0-9a-f]*\) .*/\1/p')
    stack=$(echo "$fm_out" | sed -n 's/.* stack \([0-9]*\).*/\1/p')
    stats=$(echo "$fm_out" | sed -n 's/.*min \([0-9]*\) median \([0-9]*\) max \([0-9]*\).*/\1 | \2 | \3/p')
    max=$(echo "$fm_out" | sed -n 's/.*max \([0-9]*\).*/\1/p')
    models=$($fm_nm "$fm_elf" | awk '$3 ~ /^mdl_.*_kind$/ {sub(/^mdl_/, "", $3); sub(/_kind$/, "", $3); print $3}' | sort | tr '\n' ' ')
}
