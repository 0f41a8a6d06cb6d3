#!/bin/sh
# hang.sh - stands in for a unit-test image that never ends (the QEMU_TIMEOUT probe of
# cross_test.sh): the first lines such an image prints, then it waits, until the
# `timeout` in front of it ends it. Usage: sh tests/cross/hang.sh [ELF]
echo "tests: 3"
echo "ok   first"
exec sleep 60
