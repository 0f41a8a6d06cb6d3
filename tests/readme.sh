#!/bin/sh
# readme.sh - the README's "Adding a block kind" example is a complete file: extracted
# from the README and compiled as a model (the flags of models/, -Werror), it must build.
set -u
CC=${CC:-cc}
f=build/test-readme/pt2.c
mkdir -p build/test-readme
awk '/^## Adding a block kind/ { s = 1 } s && /^```c$/ { c = 1; next } c && /^```$/ { exit }
     c { print }' README.md > $f
if [ ! -s $f ]; then echo "FAIL readme: no C block under 'Adding a block kind'"; echo "readme: 0 passed, 1 failed"; exit 1; fi
if $CC -std=c11 -Wall -Wextra -Werror -ffreestanding -Irt -Imodels -c $f -o build/test-readme/pt2.o; then
    echo "readme: 1 passed, 0 failed"
else
    echo "FAIL readme: the block-kind example does not compile"; echo "readme: 0 passed, 1 failed"; exit 1
fi
