#!/bin/sh
# docs_commit.sh - measured figures say which commit they belong to: every section of
# docs/footprint.md that tools/dev/footprint.sh or tools/dev/effects.sh writes, the
# benchmark of docs/mbs.md (tools/dev/bench/mbs_bench.c) and the wall-clock tables of
# docs/link.md start with "Figures of commit `X`", X a commit of this repository (issue 30:
# the flash figures trailed HEAD with nothing to tell).
set -u
pass=0 fail=0
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL docs_commit: $*"; }
for fs in 'docs/footprint.md:^# Footprint and cost per tick' \
          'docs/footprint.md:^## Effects of the lane change' 'docs/mbs.md:^## What accuracy costs' \
          'docs/link.md:^### Figures' 'docs/link.md:^## Measured'; do
    f=${fs%%:*} sec=${fs#*:}
    c=$(awk -v s="$sec" '$0 ~ s { on = 1; next } on && /^#/ { exit } on && /^Figures of commit `/ { print; exit }' "$f" |
        sed 's/^Figures of commit `\([^`]*\)`.*/\1/')
    if [ -z "$c" ]; then bad "$f: section '$sec' does not name its commit"; continue; fi
    if ! command -v git >/dev/null || ! git rev-parse --git-dir >/dev/null 2>&1; then ok; continue; fi
    git cat-file -e "${c%-dirty}^{commit}" 2>/dev/null && ok || bad "$f: '$c' is not a commit of this repository"
done
echo "docs_commit: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
