"""scene.py - variant scenes for the study (tools/dev/study/study.py): reads a scene file as it
is (includes inlined, comments dropped), and writes a variant with another base tick,
other set statements (one set for all, or a set's method, step, Newton or Jacobian
clauses changed), another stabilization or Broyden bound. Sets are also found by role:
`slow` is the set with the longest step, `fast` every other set, so a variant needs no
edit when a scene's sets are renamed."""
import math
import os
import re

IMPLICIT = {"beuler", "trap", "sdirk2", "sdirk3", "ros2"}
IMPLICIT_ONLY = ("newton", "jacobian", "tolerance", "substeps")
UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}


def _strip_comments(text):
    return re.sub(r'("(?:[^"\\\n]|\\.)*")|//[^\n]*',
                  lambda m: m.group(1) or "", text)


def read(path):
    """the scene's text with its includes inlined (relative to the including file)"""
    text = _strip_comments(open(path).read())

    def inc(m):
        return read(os.path.join(os.path.dirname(path), m.group(1)))
    return re.sub(r'\binclude\s+"([^"]+)"\s*;', inc, text)


def _split(text):
    """statements, split at ';' outside strings and braces"""
    out, cur, depth, quote = [], [], 0, False
    for ch in text:
        cur.append(ch)
        if ch == '"':
            quote = not quote
        elif not quote and ch == "{":
            depth += 1
        elif not quote and ch == "}":
            depth -= 1
        elif not quote and depth == 0 and ch == ";":
            s = "".join(cur)[:-1].strip()
            if s:
                out.append(s)
            cur = []
    return out


def parse_time(s):
    """'5 ms' -> (0.005, False); '16 ticks' -> (16, True)"""
    m = re.match(r"\s*([0-9.eE+-]+)\s*([a-z]*)\s*$", s)
    num, unit = float(m.group(1)), m.group(2) or "s"
    if unit in ("tick", "ticks"):
        return num, True
    return num * UNITS[unit], False


def fmt_time(t):
    """a time as an exact literal: whole ns where it is one"""
    ns = t * 1e9
    if abs(ns - round(ns)) < 1e-6 * max(1, ns):
        return "%d ns" % round(ns)
    return "%.17g s" % t


class Scene:
    def __init__(self, path):
        self.path = path
        self.stmts = _split(read(path))
        self.tick = None
        self.sets = []  # [(name, [(clause, arg)])]
        for s in self.stmts:
            m = re.match(r"base\s+tick\s*\((.*)\)$", s, re.S)
            if m:
                self.tick = parse_time(m.group(1))[0]
        for s in self.stmts:
            if re.match(r"set\s*\(", s):
                name = re.match(r"set\s*\(\s*(\w+)\s*\)", s).group(1)
                rest = s[re.match(r"set\s*\(\s*\w+\s*\)", s).end():]
                clauses = [(k, v.strip()) for k, v in re.findall(r"(\w+)\s*\(([^)]*)\)", rest)]
                # the one clause without an argument: the set steps in the background
                if re.search(r"\bbackground\b", re.sub(r"\([^)]*\)", "", rest)):
                    clauses.append(("background", None))
                self.sets.append((name, clauses))
        if not self.sets:  # the language's default: one set main, rk4 at the base tick
            self.sets = [("main", [("method", "rk4"), ("step", "1 tick")])]
        self.name = re.search(r"scene\s*\(\s*(\w+)\s*\)", "\n".join(self.stmts))
        self.name = self.name.group(1) if self.name else os.path.basename(path)[:-4]
        self.records = []
        for s in self.stmts:
            m = re.match(r"record\s*\((.*)\)$", s, re.S)
            if m:
                self.records = [r.strip().split()[-1] for r in m.group(1).split(",")]

    def step_of(self, clauses, tick=None):
        """a set's step in seconds"""
        d = dict(clauses)
        if "step" not in d:
            return tick or self.tick
        v, ticks = parse_time(d["step"])
        return v * self.tick if ticks else v

    def method_of(self, name):
        return dict(dict(self.sets)[name]).get("method", "rk4")

    def roles(self):
        """{'slow': name, 'fast': [names]} (slow: the longest step, the first of equals)"""
        steps = [(self.step_of(c), i, n) for i, (n, c) in enumerate(self.sets)]
        slow = max(steps, key=lambda s: (s[0], -s[1]))[2]
        return {"slow": slow, "fast": [n for n, _ in self.sets if n != slow]}

    def steps(self):
        return {n: self.step_of(c) for n, c in self.sets}


def _ticks(step, tick):
    k = step / tick
    if abs(k - round(k)) > 1e-9 * k or round(k) < 1:
        raise ValueError("step %g s is not a whole number of ticks of %g s" % (step, tick))
    return int(round(k))


def _set_stmt(name, clauses, tick, members=True):
    out = ["set (%s)" % name]
    method = dict(clauses).get("method", "rk4")
    for k, v in clauses:
        if k in IMPLICIT_ONLY and method not in IMPLICIT:
            continue
        if k == "members" and not members:
            continue
        if k == "step":
            v = "%d ticks" % _ticks(v, tick)
        out.append(k if v is None else "%s (%s)" % (k, v))
    return " ".join(out)


def variant(sc, tick=None, single=None, mods=None, stab=None, loop_iter=None):
    """text of a variant: tick [s]; single = (method, {clause: arg}) puts every system in
    one set `all` stepping every tick; mods = {set name or 'slow'/'fast': {clause: arg}}
    with 'step' in seconds; stab = 'project' | 'none' | ('baumgarte', alpha, beta);
    loop_iter: Broyden iterations"""
    tick = tick or sc.tick
    roles = sc.roles()
    by_name = {}
    for key, m in (mods or {}).items():
        names = [roles["slow"]] if key == "slow" else roles["fast"] if key == "fast" \
            else [key]
        for n in names:
            by_name.setdefault(n, {}).update(m)
    out, set_done, stab_done = [], False, False
    for s in sc.stmts:
        if re.match(r"base\s+tick\s*\(", s):
            out.append("base tick (%s)" % fmt_time(tick))
        elif re.match(r"set\s*\(", s):
            if single:
                if not set_done:
                    method, extra = single
                    cl = [("method", method), ("step", tick)] + list(extra.items())
                    out.append(_set_stmt("all", cl, tick))
                set_done = True
                continue
            name = re.match(r"set\s*\(\s*(\w+)\s*\)", s).group(1)
            clauses = [(k, v) for k, v in dict(sc.sets)[name]]
            cl = [(k, sc.step_of(clauses) if k == "step" else v) for k, v in clauses]
            if not any(k == "step" for k, _ in cl):
                cl.append(("step", sc.step_of(clauses)))
            for k, v in by_name.get(name, {}).items():
                if any(kk == k for kk, _ in cl):
                    cl = [(kk, v if kk == k else vv) for kk, vv in cl]
                else:
                    cl.append((k, v))
            out.append(_set_stmt(name, cl, tick))
        elif re.match(r"stabilization\s*\(", s):
            stab_done = True
            out.append(_stab(stab) if stab else s)
        elif re.match(r"solve\s+loops", s) and loop_iter:
            s = re.sub(r"\s*iterations\s*\([^)]*\)", "", s)
            out.append(s + " iterations (%d)" % loop_iter)
        else:
            out.append(s)
    if single and not set_done:
        method, extra = single
        out.append(_set_stmt("all", [("method", method), ("step", tick)] +
                             list(extra.items()), tick))
    if stab and not stab_done:
        out.append(_stab(stab))
    return ";\n".join(out) + ";\n"


def _stab(stab):
    if isinstance(stab, tuple):
        return "stabilization (baumgarte) alpha (%g) beta (%g)" % (stab[1], stab[2])
    return "stabilization (%s)" % stab


def lcm_ticks(steps, tick):
    """the least common multiple of the steps, in ticks"""
    n = 1
    for s in steps:
        k = _ticks(s, tick)
        n = n * k // math.gcd(n, k)
    return n
