#!/bin/sh
# run.sh - one image under QEMU, bounded by the work of the guest rather than by the
# machine's load: the target's run command carries the instruction-count plugin with
# limit=@BUDGET@ (tools/dev/qemu/insn_count.c), replaced here by BUDGET, so an image that
# runs away stops after BUDGET instructions however loaded the machine is; QEMU_TIMEOUT
# (the `timeout` in the command) is left as a guard against QEMU itself hanging. A run
# cut off either way says which, and a unit-test image (it prints "tests: N" first)
# counts the tests it never finished as failed: "P passed, F failed" with F = the
# failures seen plus the tests never run.
# Usage: sh tests/cross/run.sh LABEL RUN BUDGET BUDGET_NAME ELF LOG
#   exits with QEMU's status (0: the image passed)
set -u
LABEL=$1 RUN=$2 BUDGET=$3 BNAME=$4 ELF=$5 LOG=$6
cmd=$(printf '%s' "$RUN" | sed "s/@BUDGET@/$BUDGET/g")
$cmd "$ELF" > "$LOG" 2>&1
rc=$?
why=""
if grep -q '^insn_count: stopped after' "$LOG"; then
    why="stopped after its budget of $BUDGET instructions ($BNAME)"
elif [ $rc -eq 124 ] || [ $rc -eq 137 ]; then
    why="timed out after ${QEMU_TIMEOUT:-?} s (QEMU_TIMEOUT)"
fi
[ -z "$why" ] && exit $rc
echo "$LABEL: $why"
n=$(sed -n 's/^tests: //p' "$LOG" | head -1)
if [ -n "$n" ]; then
    done_=$(grep -c '^ok ' "$LOG")
    bad=$(grep '^FAIL' "$LOG" | awk '{ print $2 }' | sort -u | wc -l)
    never=$((n - done_ - bad))
    [ $never -lt 0 ] && never=0
    echo "$LABEL: $done_ of $n tests finished, $never never ran (counted as failed)"
    echo "$LABEL: 0 passed, $((bad + never)) failed"
fi
exit $rc
