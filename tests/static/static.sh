#!/bin/sh
# static.sh - the static checks of rt/, models/ and ports/ (docs/reliability.md): cppcheck
# (warning, portability, performance; inline suppressions carry their reason) and
# clang-tidy's bugprone-* and cert-* (.clang-tidy lists the two checks left out and why).
# Zero findings, or the suite fails with them listed.
set -u
T=build/static
mkdir -p $T
SRC="rt/*.c models/*.c ports/common/*.c ports/posix/*.c"
INC="-Irt -Imodels -Iports -Iports/posix -Ibuild/gen"
fail=0
# cppcheck beside clang-tidy (each keeps one core busy); its status through a file
# shellcheck disable=SC2086 # the source globs are meant to split
{ cppcheck --enable=warning,portability,performance --std=c11 -q --inline-suppr \
    --error-exitcode=1 -Irt -Imodels -Iports $SRC ports/cortex-m/*.c ports/riscv/*.c \
    > $T/cppcheck.txt 2>&1; echo $? > $T/cppcheck.rc; } &
cpid=$!
clang-tidy --quiet $SRC -- -std=c11 $INC > $T/tidy.txt 2>/dev/null || fail=1
for p in cortex-m:--target=arm-none-eabi riscv:--target=riscv64-unknown-elf; do
    clang-tidy --quiet ports/${p%%:*}/*.c -- -std=c11 ${p#*:} -ffreestanding $INC \
        -Iports/${p%%:*} >> $T/tidy.txt 2>/dev/null || fail=1
done
n2=$(grep -cE ': (warning|error):' $T/tidy.txt)
wait $cpid
[ "$(cat $T/cppcheck.rc)" = 0 ] || fail=1
n1=$(grep -cE ': (error|warning|portability|performance):' $T/cppcheck.txt)
files=$(ls $SRC ports/cortex-m/*.c ports/riscv/*.c | wc -l)
if [ $fail -ne 0 ] || [ "$n1" -ne 0 ] || [ "$n2" -ne 0 ]; then
    cat $T/cppcheck.txt $T/tidy.txt
    echo "static: $files files: cppcheck $n1 findings, clang-tidy $n2 findings"
    echo "static: 0 passed, 1 failed"
    exit 1
fi
echo "static: $files files: cppcheck 0 findings, clang-tidy 0 findings (bugprone-*, cert-*)"
echo "static: 2 passed, 0 failed"
