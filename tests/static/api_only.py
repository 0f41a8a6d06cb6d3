#!/usr/bin/env python3
"""api_only.py - applications, models and API tests read the runtime through rt/rt.h alone.

Outside rt/ and the white-box tests (tests/whitebox/, and tests/faults/, the fault-injection
build that drives rt/'s hooks) and scenec's code writer (tools/scenec/spec.c, which writes
the plan out as C), no C file
  - reads a part of rt_sim's storage layout (rt/rt_sim.h): `.plan.`, `->state[`, `.work.`,
    `.stats.`, ... (rt_stats_of, rt_ticks_done, rt_trace_hash, rt_output, rt_block_x, ...
    read them), nor the background hand-over counters;
  - includes an internal header of rt/ (rti.h, rti_mbs.h, linalg.h);
and no API test (tests/**/test_*.c outside the white-box folders) includes rt/rt_sim.h:
such a test compiles against rt.h alone, so a change of the layout cannot break it. An
application or harness may include rt_sim.h only to allocate an rt_sim or an rt_state.

Usage: api_only.py [ROOT]  (the repository, default .); exit 0 clean, 1 with one line per
finding, FILE:LINE: what."""
import os
import re
import sys

SCANNED = ("models", "ports", "tools", "tests")
WHITE_BOX = ("tests/whitebox/", "tests/faults/",
             # scenec's code writer: a back end of rt/, it writes the plan rt_init built
             # out as C constants, and the code it writes runs inside rt/ (rt_scene.code)
             "tools/scenec/spec.c")
INTERNAL = ("rti.h", "rti_mbs.h", "linalg.h")
PARTS = re.compile(r"(?:\.|->)\s*(plan|state|work|stats)\s*(?:\.|->|\[)"
                   r"|(?:\.|->)\s*(bg_released|bg_finished)\b")
INCLUDE = re.compile(r'^\s*#\s*include\s*"(?:[^"]*/)?([^"/]+)"', re.M)


def strip(text):
    """comments and string and character literals blanked, newlines kept (line numbers)"""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (min(j, n) - i - 1) + (c if j < n else ""))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def check(root, rel):
    text = open(os.path.join(root, rel), encoding="utf-8", errors="replace").read()
    found = []
    line_of = lambda pos: text.count("\n", 0, pos) + 1
    for m in INCLUDE.finditer(text):
        name = m.group(1)
        if name in INTERNAL:
            found.append((line_of(m.start()), "includes rt/%s, an internal header of the "
                          "runtime (a white-box test lives in tests/whitebox/)" % name))
        if name == "rt_sim.h" and os.path.basename(rel).startswith("test_") \
                and rel.startswith("tests/"):
            found.append((line_of(m.start()), "an API test includes rt/rt_sim.h: test "
                          "through rt.h, or move it to tests/whitebox/"))
    code = strip(text)
    for m in PARTS.finditer(code):
        part = m.group(1) or m.group(2)
        found.append((line_of(m.start()), "reads rt_sim's %s (the layout of rt/rt_sim.h): "
                      "use an accessor of rt/rt.h" % part))
    return found


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    bad = nfiles = 0
    for top in SCANNED:
        for d, dirs, files in os.walk(os.path.join(root, top)):
            dirs.sort()
            for f in sorted(files):
                if not f.endswith((".c", ".h")):
                    continue
                rel = os.path.relpath(os.path.join(d, f), root).replace(os.sep, "/")
                if rel.startswith(WHITE_BOX):
                    continue
                nfiles += 1
                for line, what in check(root, rel):
                    print("%s:%d: %s" % (rel, line, what))
                    bad += 1
    print("api_only: %d files outside rt/ and the white-box tests, %d finding(s)%s"
          % (nfiles, bad, ": they read the runtime through rt/rt.h alone" if bad else ""))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
