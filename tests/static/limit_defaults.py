#!/usr/bin/env python3
"""limit_defaults.py - the defaults of the capacity limits come from their list: reads
RT_LIMIT_LIST (rt/rt_config.h, one row per limit: name, rt_sizes member, least, default,
what it counts) and writes the #ifndef RT_MAX_<NAME> block of every row into
rt/rt_limits.h, which the preprocessor cannot generate. Without --write it checks that
the committed rt/rt_limits.h is what the list gives and fails naming the rows that
differ (make test-static).
Usage: limit_defaults.py [--write] [RT_DIR]"""
import os
import re
import sys

HEAD = """/* rt_limits.h - the default of every capacity limit, written from RT_LIMIT_LIST
 * (rt_config.h) by tests/static/limit_defaults.py --write: edit the list, not this file
 * (make test-static fails when they differ). A build overrides any with -DRT_MAX_<NAME>. */
#ifndef RT_LIMITS_H
#define RT_LIMITS_H
"""


def split_args(text):
    """the top-level, comma-separated arguments of a macro call (strings and parentheses
    kept whole)"""
    args, depth, cur, i = [], 0, "", 0
    while i < len(text):
        ch = text[i]
        if ch == '"':
            j = i + 1
            while text[j] != '"':
                j += 2 if text[j] == "\\" else 1
            cur += text[i:j + 1]
            i = j + 1
            continue
        if ch in "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        if ch == "," and depth == 0:
            args.append(cur.strip())
            cur = ""
        else:
            cur += ch
        i += 1
    args.append(cur.strip())
    return args


def rows(config):
    """(name, field, least, default, what) of every row of RT_LIMIT_LIST"""
    text = re.sub(r"/\*.*?\*/", " ", config, flags=re.S).replace("\\\n", " ")
    m = re.search(r"#define RT_LIMIT_LIST\(L\)(.*)", text)
    if not m:
        sys.exit("limit_defaults: no #define RT_LIMIT_LIST(L) in rt_config.h")
    body, out, i = m.group(1), [], 0
    while True:
        i = body.find("L(", i)
        if i < 0:
            return out
        depth, j = 0, i + 1
        while True:  # the row's closing parenthesis
            if body[j] == '"':
                j = body.index('"', j + 1)
            elif body[j] == "(":
                depth += 1
            elif body[j] == ")":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        a = split_args(body[i + 2:j])
        if len(a) != 5:
            sys.exit("limit_defaults: a row of RT_LIMIT_LIST without 5 columns: L(%s)"
                     % body[i + 2:j])
        what = "".join(re.findall(r'"((?:[^"\\]|\\.)*)"', a[4]))
        out.append((a[0], a[1], a[2], re.sub(r"\s+", " ", a[3]), what))
        i = j + 1


def header(config):
    parts = [HEAD]
    for name, _field, _least, dflt, what in rows(config):
        parts.append("\n/* %s */\n#ifndef RT_MAX_%s\n#define RT_MAX_%s %s\n#endif\n"
                     % (what, name, name, dflt))
    parts.append("\n#endif /* RT_LIMITS_H */\n")
    return "".join(parts)


def main():
    args = [a for a in sys.argv[1:] if a != "--write"]
    rt = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                           "..", "..", "rt")
    want = header(open(os.path.join(rt, "rt_config.h")).read())
    path = os.path.join(rt, "rt_limits.h")
    if "--write" in sys.argv:
        with open(path, "w") as f:
            f.write(want)
        print("limit_defaults: wrote %s" % os.path.normpath(path))
        return 0
    have = open(path).read() if os.path.exists(path) else ""
    if have == want:
        print("limit_defaults: rt/rt_limits.h holds the default of every row of "
              "RT_LIMIT_LIST (%d)" % want.count("#ifndef RT_MAX_"))
        return 0
    blocks = lambda t: set(re.findall(r"#ifndef RT_MAX_\w+\n#define (RT_MAX_\w+ .*)", t))
    for d in sorted(blocks(want) ^ blocks(have)):
        print("limit_defaults: %s: %s" % ("list" if d in blocks(want) else "rt_limits.h", d))
    print("FAIL limit_defaults: rt/rt_limits.h differs from RT_LIMIT_LIST (rt/rt_config.h): "
          "python3 tests/static/limit_defaults.py --write")
    return 1


if __name__ == "__main__":
    sys.exit(main())
