#!/usr/bin/env python3
"""permute_sets.py - the trace does not depend on the order in which a scene lists its
sets: every library scene with several sets, tests/scenec/scenes/lang_order.scn (a
throughput block in one set reading a sampled controller in another) and lang_cycle.scn
(three sets of one step coupled in a loop), run with their set statements in every order,
give the same trace hash. Usage: permute_sets.py MODRT"""
import glob
import itertools
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "build", "permute")


def split_sets(text):
    """(text before the sets, the set statements, text after): the statements that begin
    a line with `set (`, each up to its `;`, must stand together; comment lines between
    them go with the statement after them"""
    starts = [m.start() for m in re.finditer(r"(?m)^set \(", text)]
    if len(starts) < 2:
        return None
    stmts, end = [], starts[0]
    for s in starts:
        between = text[end:s]
        if any(ln.strip() and not ln.strip().startswith("//") for ln in between.split("\n")):
            return None  # a statement between the sets: leave the scene alone
        e = text.index(";", s) + 1
        stmts.append(between.strip("\n") + "\n" + text[s:e] if between.strip() else text[s:e])
        end = e
    return text[:starts[0]], stmts, text[end:]


def hash_of(modrt, path):
    p = subprocess.run([modrt, "run", path], capture_output=True, text=True, timeout=300)
    m = re.search(r"(?m)^hash: ([0-9a-f]+)$", p.stdout)
    return m.group(1) if m and p.returncode in (0, 3) else "exit %d: %s" % (p.returncode,
                                                                           p.stderr.strip())


def main():
    modrt = sys.argv[1]
    os.makedirs(OUT, exist_ok=True)
    for inc in glob.glob(os.path.join(ROOT, "models", "scenes", "*.inc")):
        shutil.copy(inc, OUT)
    scenes = sorted(glob.glob(os.path.join(ROOT, "models", "scenes", "*.scn")))
    for extra in ("lang_order.scn", "lang_cycle.scn"):
        scenes.append(os.path.join(ROOT, "tests", "scenec", "scenes", extra))
    passed = failed = 0
    for path in scenes:
        parts = split_sets(open(path).read())
        if not parts:
            continue
        head, stmts, tail = parts
        want = hash_of(modrt, path)
        name = os.path.basename(path)
        for k, order in enumerate(itertools.permutations(stmts)):
            if k == 0:
                continue  # the scene as written
            p = os.path.join(OUT, name)
            with open(p, "w") as f:
                f.write(head + "\n".join(order) + tail)
            got = hash_of(modrt, p)
            if got == want:
                passed += 1
            else:
                failed += 1
                print("FAIL permute: %s with its sets in another order: hash %s, as written %s"
                      % (name, got, want))
        print("permute: %s: %d orders of %d sets, hash %s" % (name, k + 1, len(stmts), want))
    print("permute: %d passed, %d failed" % (passed, failed))
    return 1 if failed or passed == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
