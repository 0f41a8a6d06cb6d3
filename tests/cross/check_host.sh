#!/bin/sh
# check_host.sh - ties the cross-test reference to the CLI: every scene's hash in the
# host scene image's log must equal the hash `modrt run SCENE --t-end T` prints for the
# same number of ticks. Usage: sh tests/cross/check_host.sh MODRT SCENES_LOG
set -u
modrt=$1 log=$2 fail=0
while read -r _ name _ ticks _ status _ hash; do
    dt=$($modrt info "$name" | sed -n 's/^base tick: \([^ ]*\) s$/\1/p')
    t_end=$(awk -v d="$dt" -v n="$ticks" 'BEGIN { printf "%.17g", d * n }')
    cli=$($modrt run "$name" --t-end "$t_end" | sed -n 's/^hash: //p')
    if [ "$cli" != "$hash" ]; then
        echo "check_host: $name: scene image hash $hash, modrt run hash $cli"
        fail=1
    fi
done < "$log"
[ "$fail" -eq 0 ] && echo "check_host: $(wc -l < "$log") scene hashes agree with modrt run"
exit $fail
