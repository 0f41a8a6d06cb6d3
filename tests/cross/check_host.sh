#!/bin/sh
# check_host.sh - ties the cross-test reference to the CLI: every scene's hash in the
# host scene image's log must equal the hash `modrt run SCENE` prints.
# Usage: sh tests/cross/check_host.sh MODRT SCENES_LOG
set -u
modrt=$1 log=$2 fail=0
while read -r _ name _ ticks _ status _ hash; do
    cli=$($modrt run "$name" | sed -n 's/^hash: //p')
    if [ "$cli" != "$hash" ]; then
        echo "check_host: $name: scene image hash $hash, modrt run hash $cli"
        fail=1
    fi
done < "$log"
[ "$fail" -eq 0 ] && echo "check_host: $(wc -l < "$log") scene hashes agree with modrt run"
exit $fail
