#!/usr/bin/python3
"""speedup.py - `make speedup` (issue 14, goal 4): the multirate speedup at equal accuracy,
from deterministic instruction counts. For pendulum10_actuated (and lane_change) it sweeps
single-rate configurations (one set: method, step, Jacobian refresh interval) and
multirate ones (the slow set's method, macro step, in the tick or in the background, the
fast set's method, the slow set's inputs extrapolated or held), all written as variant
scenes of the scene file by tools/dev/study/scene.py, and for each

  - the error: the largest error of the example's signals (pendulum10_actuated: the
    positions of B1..B10) every GRID s over the whole run, against a fine single-rate
    reference (dopri5; its own error is its difference to a second one, rk4 at half its
    step), from the plain host binary (`modrt run --csv --every`);
  - clean: `modrt run` reports status ok and no counter other than events and substeps
    (a substep is a recovered step: reported, its cost counted, not a fault);
  - the cost: host instructions of rt_tick + rt_record (callgrind, --toggle-collect) per
    simulated second over a window from t = 0 that is a whole number of the variant's
    period: the least common multiple of every set's step and, for an implicit set, of
    its step times its Jacobian interval; at least WINDOW s. So the window holds whole
    slow steps and whole Jacobian cycles (the refresh at t = 0 included).

A window can miss work that depends on the data (the substeps of a ROS2 step above its
accuracy, with their fresh Jacobians; Newton iterations that vary along the run). So the
finalists, every clean configuration within a bound whose window count is within
FINALIST of the cheapest of its variant, are counted again over the whole run, and the
speedup is taken from those whole-run counts. Last, the cheapest multirate configuration
within the tightest bound is profiled (callgrind_annotate, inclusive counts): what its
slow set, its fast set and recording cost.

Compiled: the scenes ship compiled by scenec with the code it writes out for them
(docs/overhead.md), which the interpreter (`modrt run FILE.scn`) does not run. So every
finalist is also compiled (scenec, then tools/dev/bench/code_run.c linked with the
runtime and the models), its trace hash checked against the interpreter's and its
instructions of rt_tick + rt_record counted over the whole run; the speedup of the
cheapest of each variant among them is printed beside the interpreted one:
  multirate speedup <example> at <bound> m, compiled: <ratio> (...)

Prints the cheapest of each variant within each bound and the lines
  multirate speedup <example> at <bound> m: <ratio> (single <config> <insn/s>, multirate
  <config> <insn/s>)
and writes build/bench/speedup-<example>.csv (for svgplot), build/bench/speedup.txt and,
with --doc FILE, the Markdown between "<!-- bench:begin -->" and "<!-- bench:end -->"."""
import argparse
import concurrent.futures as cf
import csv
import hashlib
import json
import math
import os
import re
import subprocess
import sys
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "study"))
import scene as S  # noqa: E402

OUT = "build/bench/speedup"
MODRT = "build/host/modrt"
CODE = None  # compiled runs: {"scenec", "cc" (command and flags), "objs"}, from --code
WINDOW = 0.256     # shortest cost window [s] (then whole periods of the variant)
FINALIST = 1.25    # finalists: window count within this factor of the variant's cheapest
ACCURACY = "1e-2"  # every set's `accuracy` (the shipped implicit sets'): errest's threshold
BEGIN, END = "<!-- bench:begin -->", "<!-- bench:end -->"


def sh(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def h_ms(h):
    return "%g ms" % (h * 1e3) if h >= 1e-4 else "%g us" % (h * 1e6)


# ------------------------------------------------------------------ the examples

class Example:
    """a scene, the signals of its error, their grid, references, bounds, the sweep"""

    def __init__(self, key, path, signals, grid, refs, tols, what, whole=False):
        self.key, self.path, self.grid, self.refs, self.tols = key, path, grid, refs, tols
        self.whole = whole  # count every configuration over the whole run
        self.sc = S.Scene(path)
        self.signals = [r for r in self.sc.records if re.match(signals, r)]
        self.what = what
        self.t_end = end_time(self.sc)
        self.cfgs = []
        self.ladders = {}  # ladder -> its configurations, largest step first
        self.pruned = 0    # configurations a larger step of their ladder made needless
        self.outside = 0   # configurations run but outside every bound (not counted)
        self.sweep_note = ""
        self.rhs_insn = None  # instructions of one right-hand side (rhs_cost)

    def add(self, variant, desc, text, series, shipped=False, ladder=None):
        c = {"variant": variant, "desc": desc, "text": text, "series": series,
             "key": "%s%03d" % (variant[0], len(self.cfgs)), "shipped": shipped}
        self.cfgs.append(c)
        if ladder is not None:
            self.ladders.setdefault(ladder, []).append(c)


def end_time(sc):
    for s in sc.stmts:
        m = re.match(r"end\s+time\s*\((.*)\)$", s, re.S)
        if m:
            return S.parse_time(m.group(1))[0]
    raise SystemExit("speedup: %s has no end time" % sc.path)


def single_sweep(ex, explicit, implicit, jacs, newton=None):
    """one set at the step (base tick = step); implicit methods at each Jacobian interval
    (and at most `newton` Newton iterations per stage, if given)"""
    for m, hs in explicit:
        for h in hs:
            ex.add("single", "%s %s" % (m, h_ms(h)),
                   S.variant(ex.sc, tick=h, single=(m, {"accuracy": ACCURACY})),
                   "single " + m)
    for m, hs in implicit:
        for h in hs:
            for j in jacs:
                cl = {"jacobian": str(j), "accuracy": ACCURACY}
                if newton:
                    cl["newton"] = str(newton)
                ex.add("single", "%s %s, Jacobian every %d%s" % (
                    m, h_ms(h), j, ", newton %d" % newton if newton else ""),
                    S.variant(ex.sc, tick=h, single=(m, cl)), "single " + m)


# the single-rate competitors swept over their whole range (issue 32, goal 3): every method,
# every step of a ladder halving from the scene's tick, every Jacobian interval from 1 to
# never (the start only), every Newton count; see single_walk
EXPLICIT_ALL = ("euler", "heun", "bs3", "rk4", "dopri5")
NEWTON_METHODS = ("trap", "sdirk2", "sdirk3", "beuler")
JACS = tuple(2 ** i for i in range(13)) + (65535,)  # 1 .. 4096, and 65535: the start only
NEWTONS = (1, 2, 3, 4)


def jac_text(j):
    return "Jacobian at the start only" if j == 65535 else "Jacobian every %d" % j


def single_walk(ex, steps_explicit, steps_implicit):
    """every single-rate configuration as a ladder of steps, largest first: a method with
    its Jacobian interval and Newton count (run_example walks each ladder down only while
    its step misses the tightest bound: at a fixed step the work per step is the same, so
    a smaller step costs more per simulated second)"""
    for m in EXPLICIT_ALL:
        for h in steps_explicit:
            ex.add("single", "%s %s" % (m, h_ms(h)),
                   S.variant(ex.sc, tick=h, single=(m, {"accuracy": ACCURACY})),
                   "single " + m, ladder=(m,))
    for m in ("ros2",) + NEWTON_METHODS:
        for j in JACS:
            for nw in ((None,) if m == "ros2" else NEWTONS):
                for h in steps_implicit:
                    cl = {"jacobian": str(j), "accuracy": ACCURACY}
                    if nw:
                        cl["newton"] = str(nw)
                    ex.add("single", "%s %s, %s%s" % (
                        m, h_ms(h), jac_text(j), ", newton %d" % nw if nw else ""),
                        S.variant(ex.sc, tick=h, single=(m, cl)), "single " + m,
                        ladder=(m, j, nw))
                    c = ex.cfgs[-1]
                    c["group"], c["jac"] = (m, h, nw), j
                    # a Jacobian cycle as long as the window: its cost follows from the
                    # start-only run's (derive)
                    c["derive"] = j * h >= WINDOW - 1e-12 and not ex.whole
    ex.sweep_note = (
        "Single-rate competitors: every method of the runtime (%s explicit at %s; ROS2 and "
        "%s at %s), every Jacobian interval 1, 2, 4, ... 4096 steps and the start only, "
        "Newton counts 1-4 (at most that many iterations per stage; ROS2 has none). The "
        "steps halve from the scene's tick, which bounds them: the controller samples "
        "every tick. Each method, Jacobian interval and Newton count is a ladder walked "
        "from its largest step down only while the step misses the tightest bound with no "
        "fault: at a fixed step an explicit method does the same work per step, so a "
        "smaller step costs more per simulated second, and an implicit one refreshes its "
        "Jacobian as many times more often; a configuration outside every bound is run "
        "(error, status) but not counted. " % (
            ", ".join(EXPLICIT_ALL), ", ".join(h_ms(h) for h in steps_explicit),
            ", ".join(NEWTON_METHODS), ", ".join(h_ms(h) for h in steps_implicit)) + ("" if
        ex.whole else
        "Where the Jacobian cycle is at least the %g s window, the cost comes from the run "
        "with the Jacobian at the start only at the same step and Newton count, counted "
        "over two windows from t = 0 (%g and %g s, one refresh each): their difference is "
        "the work per step, the rest the refresh's, and the run's cost is the steps' plus "
        "one refresh per cycle (window 0 in the table; a run with a substep, which "
        "refreshes out of turn, is counted over the whole run instead). " % (
            WINDOW, WINDOW / 2, WINDOW)) + (
        "A configuration "
        "is left out as dominated when a run of %g s shows that its right-hand sides "
        "alone, at %g times the instructions of one (measured: rti_rhs in a short dopri5 "
        "run), cost more per simulated second than the cheapest configuration counted so "
        "far within the tightest bound with status ok: every method evaluates the whole "
        "model's right-hand side, so no method is cheaper than its evaluations." % (
            WINDOW, RHS_MARGIN)))


def no_background(text):
    return re.sub(r"(?m)^(set \(\w+\)[^;\n]*?)\s+background\b", r"\1", text)


def multirate_sweep(ex, slow_methods, ratios, fast_methods, fast_jac, held=True,
                    bgs=(True, False), newton=None):
    """slow set: method x macro step x (background, tick) x (inputs extrapolated, and held
    if held); fast set: method, Jacobian every fast_jac steps (at most `newton` Newton
    iterations per stage, if given), at the scene's step"""
    roles = ex.sc.roles()
    slow, fast = roles["slow"], roles["fast"]
    tick = ex.sc.tick
    for m in slow_methods:
        for r in ratios:
            for bg in bgs:
                for interp, how in (("extrapolate", "extrapolated"), ("hold", "held"))[
                        :2 if held else 1]:
                    for fm in fast_methods:
                        mods = {slow: {"method": m, "step": r * tick, "interpolation": interp,
                                       "accuracy": ACCURACY}}
                        for f in fast:
                            mods[f] = {"method": fm, "jacobian": str(fast_jac),
                                       "accuracy": ACCURACY}
                            if newton:
                                mods[f]["newton"] = str(newton)
                        text = S.variant(ex.sc, mods=mods)
                        if not bg:
                            text = no_background(text)
                        desc = "%s %s %s %d ticks (%s), inputs %s; %s %s%s%s" % (
                            slow, "background" if bg else "in the tick", m, r, h_ms(r * tick),
                            how, "+".join(fast), fm,
                            ", Jacobian %d" % fast_jac if fm in S.IMPLICIT else "",
                            ", newton %d" % newton if newton else "")
                        ex.add("multirate", desc, text, "multirate %s %s" % (
                            m, "background" if bg else "tick"))


def add_shipped(ex):
    """the scene as shipped (every set at ACCURACY, as every variant): its cost and error
    beside the swept multirate configurations, counted over the whole run"""
    mods = {name: {"accuracy": ACCURACY} for name, _ in ex.sc.sets}
    text = S.variant(ex.sc, mods=mods)
    sets = [re.sub(r"\s*members \([^)]*\)|\s*accuracy \([^)]*\)|;", "", ln).strip()
            for ln in text.splitlines() if ln.startswith("set (")]
    ex.add("multirate", "as shipped: " + "; ".join(re.sub(r"^set \((\w+)\)", r"\1", x)
                                                   for x in sets),
           text, "multirate shipped", shipped=True)


def sampled_blocks(sc):
    """the blocks the scene samples (`load system (...) ... period (...)`)"""
    out = []
    for st in sc.stmts:
        m = re.match(r"load\s+system\s*\(([^)]*)\).*\bperiod\s*\(", st, re.S)
        if m:
            out += [n.strip() for n in m.group(1).split(",")]
    return out


def split_sampled(text, fast, sampled, interp):
    """the variant with the sampled blocks of set `fast` in a set of their own, stepping
    every tick (nothing to integrate: the runtime does not step it) and reading the other
    sets by `interp`"""
    m = re.search(r"set \(%s\)(.*?)members \(([^)]*)\)" % fast, text, re.S)
    members = [n.strip() for n in m.group(2).split(",")]
    own = [n for n in members if n in sampled]
    rest = [n for n in members if n not in sampled]
    new = "set (%s_sampled) method (euler) step (1 ticks) interpolation (%s) members (%s);\n" % (
        fast, interp, ", ".join(own))
    stmt = text[m.start():m.end()].replace(m.group(2), ", ".join(rest))
    return text[:m.start()] + new + stmt + text[m.end():]


def split_sweep(ex, slow_methods, ratios, fast_method, fast_ratios, interps):
    """the slow set in the tick (inputs extrapolated); the fast set's sampled blocks in a
    set of their own every tick (`interp` from the slow set); the rest of the fast set by
    fast_method every fast ratio of ticks (the sampled outputs held over its step)"""
    roles = ex.sc.roles()
    slow, fast = roles["slow"], roles["fast"][0]
    sampled = sampled_blocks(ex.sc)
    tick = ex.sc.tick
    for m in slow_methods:
        for r in ratios:
            for fr in fast_ratios:
                for interp in interps:
                    mods = {slow: {"method": m, "step": r * tick, "interpolation": "extrapolate",
                                   "accuracy": ACCURACY},
                            fast: {"method": fast_method, "step": fr * tick,
                                   "accuracy": ACCURACY}}
                    text = no_background(S.variant(ex.sc, mods=mods))
                    text = split_sampled(text, fast, sampled, interp)
                    desc = "%s in the tick %s %d ticks (%s), inputs extrapolated; %s %s every " \
                           "%d ticks, its sampled blocks alone every tick (%s)" % (
                               slow, m, r, h_ms(r * tick), fast, fast_method, fr, interp)
                    ex.add("multirate", desc, text, "multirate %s split" % m)


def plan_actuated(quick):
    ms = 1e-3
    ex = Example("pendulum10_actuated", "models/scenes/pendulum10_actuated.scn",
                 r"^B\d+\.(x|z)$", 0.128, [("dopri5", 50e-6), ("rk4", 25e-6)], [1e-3, 1e-4],
                 "largest position error of B1..B10 every 0.128 s over 10 s [m]")
    if quick:
        single_sweep(ex, [("dopri5", [0.5 * ms])], [("ros2", [1 * ms])], [1024])
        multirate_sweep(ex, ["bs3"], [4, 16], ["ros2"], 64)
        return ex
    single_walk(ex, [1 * ms / 2 ** i for i in range(6)], [1 * ms / 2 ** i for i in range(3)])
    # the multirate side around its cheapest configurations (a narrower search there can
    # only make the speedup smaller): the servo set is linear (controller sampled, servo2
    # linear), so its transition matrix steps it exactly under the held command
    # (docs/solvers.md); the chain by Heun's method or bs3. No single-rate competitor can
    # take it: the chain is not linear
    multirate_sweep(ex, ["heun", "bs3"], [8, 16, 32], ["transition"], 64, held=False)
    # the controller (sampled every 1 ms) in a set of its own: the servo's transition step
    # may then take 2 or 4 ms under the held command, which the 1e-3 m bound allows
    split_sweep(ex, ["heun", "bs3"], [8, 16], "transition", [1, 2, 4], ["linear", "hermite"])
    add_shipped(ex)
    return ex


def plan_lane_change(quick):
    ms = 1e-3
    # the cost per step grows along the run (the first 0.64 s of bs3 at 1 ms cost a third
    # less per second than the whole 8 s): the window from t = 0 only screens (it makes
    # every configuration cheaper, by about as much), the finalists within FINALIST of
    # their variant's cheapest are counted over the whole run, which gives the speedup; a
    # cost derived from the start-only run (window 0) keeps the window's underestimate,
    # which favours the single-rate competitor. The quick sweep counts whole runs
    ex = Example("lane_change", "models/scenes/lane_change.scn", r"^V\d+\.(x|y)$", 0.16,
                 [("dopri5", 0.1 * ms), ("rk4", 0.05 * ms)], [1e-3, 1e-4],
                 "largest error of the cars' positions (x, y) every 0.16 s over 8 s [m]",
                 whole=quick)
    if quick:
        single_sweep(ex, [("bs3", [1 * ms])], [], [])
        multirate_sweep(ex, ["rk4"], [5], ["ros2"], 64)
        return ex
    # the single-rate competitors over their whole range, as pendulum10_actuated's
    single_walk(ex, [1 * ms / 2 ** i for i in range(6)], [1 * ms / 2 ** i for i in range(3)])
    multirate_sweep(ex, ["bs3", "rk4", "dopri5"], [5, 10, 20], ["ros2", "trap"], 64,
                    held=False)
    # every other macro step that divides the error's grid of 0.16 s (a step that does not
    # shows a held value up to a step old there), and Heun's method: at 10 ms every method
    # gives the same error, the coupling's, so the cheapest method at the longest step
    # within a bound wins
    multirate_sweep(ex, ["heun"], [5, 8, 10, 16, 20, 32, 40], ["ros2", "trap"], 64,
                    held=False)
    multirate_sweep(ex, ["bs3", "rk4"], [8, 16, 32, 40], ["ros2", "trap"], 64, held=False)
    add_shipped(ex)
    return ex


# ------------------------------------------------------------------ running

def summary(text):
    return dict(re.findall(r"^([\w.]+): (.*)$", text, re.M))


def read_csv(path, signals):
    rows = {}
    with open(path) as f:
        r = csv.reader(f)
        head = next(r)
        idx = [head.index(s) for s in signals]
        for row in r:
            rows[round(float(row[0]) * 1e9)] = [float(row[i]) for i in idx]
    return rows


def host_run(ex, path, tick):
    every = S._ticks(ex.grid, tick)
    out = path[:-4] + ".csv"
    r = sh([MODRT, "run", path, "--t-end=%.17g" % ex.t_end, "--every=%d" % every,
            "--csv=" + out])
    return r.returncode, summary(r.stdout), out


# the counters of a failed run (docs/solvers.md, "Status": severity 2)
FAULTS = ("nan", "event_limit", "event_noloc", "noconv", "singular", "degraded", "invariant",
          "unstable")


def clean_of(rc, s):
    """(no fault, status ok): the run completed (exit 0 or 3) with no counter of a failed
    run; and, stricter, with status ok (no step above its set's accuracy either)"""
    nofault = rc in (0, 3) and "status" in s and all(s.get(k, "0") == "0" for k in FAULTS)
    return nofault, nofault and rc == 0 and s.get("status") == "ok"


def error_of(ref, rows):
    worst, n = 0.0, 0
    for k, y0 in ref.items():
        y = rows.get(k)
        if y is None:
            return math.inf, n  # a row missing: the run ended early
        n += 1
        for a, b in zip(y, y0):
            d = abs(a - b) if a == a and b == b else math.inf
            worst = max(worst, d)
    return worst, n


def period_ticks(sc):
    """the variant's period: every set's step and every implicit set's Jacobian cycle"""
    n = 1
    for name, cl in sc.sets:
        d = dict(cl)
        k = S._ticks(sc.step_of(cl), sc.tick)
        ks = [k]
        if d.get("method", "rk4") in S.IMPLICIT:
            ks.append(k * int(d.get("jacobian", "1")))
        for v in ks:
            n = n * v // math.gcd(n, v)
    return n


def callgrind(path, ticks, tick, out="/dev/null", fns=("rt_tick", "rt_record")):
    r = sh(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out,
            "--collect-atstart=no"] + ["--toggle-collect=" + f for f in fns] +
           [MODRT, "run", path, "--t-end=%.17g" % (ticks * tick)])
    m = re.search(r"Collected : (\d+)", r.stderr)
    if not m:
        raise SystemExit("speedup: callgrind failed on %s: %s" % (path, r.stderr[-400:]))
    return int(m.group(1)), summary(r.stdout)


def rhs_of(s):
    return sum(float(v) for k, v in s.items() if k.startswith("rhs_evals."))


def run_cfg(ex, c, ref):
    # a configuration already swept (the same scene text, the same modrt) is read back: an
    # interrupted sweep resumes where it stopped
    cache = "%s/%s/%s.json" % (OUT, ex.key, hashlib.sha1(
        (c["text"] + CACHE_SALT).encode()).hexdigest()[:16])
    if os.path.exists(cache):
        with open(cache) as f:
            c.update(json.load(f))
    else:
        c = run_cfg1(ex, c, ref)
        keep = {k: c[k] for k in RESULTS if k in c}
        with open(cache + ".tmp", "w") as f:
            json.dump(keep, f)
        os.replace(cache + ".tmp", cache)
    # progress, one line per configuration (stderr: a long sweep can be followed)
    print("  swept %s: %s, error %.3g m, %s, insn/s %s" % (
        c["key"], c["desc"], c["err"], c["status"],
        "%.4g" % c["cost"] if c.get("cost") else "-"), file=sys.stderr, flush=True)
    return c


# dominance: a single-rate configuration whose right-hand sides alone cost more than the
# cheapest counted one within the tightest bound with status ok is left out after a
# short run (instructions of one right-hand side: RHS_MARGIN times the least measured)
RHS_MARGIN = 0.9


def rhs_cost(ex):
    """instructions of one evaluation of the scene's right-hand side (rti_rhs inclusive,
    explicit dopri5 in one set at half the tick, a short run)"""
    path = "%s/%s/rhs.scn" % (OUT, ex.key)
    with open(path, "w") as f:
        f.write(S.variant(ex.sc, tick=ex.sc.tick / 2, single=("dopri5", {})))
    r = sh(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
            "--collect-atstart=no", "--toggle-collect=rti_rhs", MODRT, "run", path,
            "--t-end=%.17g" % (64 * ex.sc.tick)])
    m = re.search(r"Collected : (\d+)", r.stderr)
    return int(m.group(1)) / rhs_of(summary(r.stdout))


def dominated(ex, c, path, tick):
    """True if a short run shows the configuration's right-hand sides alone cost more than
    the cheapest counted single-rate configuration within every bound, status ok"""
    best = [d["cost"] for d in ex.cfgs if d["variant"] == "single" and d.get("cost") and
            d["ok"] and d["err"] <= min(ex.tols) and d.get("window") is not None]
    if c["variant"] != "single" or not best or not ex.rhs_insn:
        return False
    n = S._ticks(WINDOW, tick)
    r = sh([MODRT, "run", path, "--t-end=%.17g" % (n * tick)])
    lb = rhs_of(summary(r.stdout)) / (n * tick) * ex.rhs_insn * RHS_MARGIN
    if lb <= min(best):
        return False
    c.update(status="dominated", clean=False, ok=False, substep=0, counters="", err=math.inf,
             rhs_run=None, cost=None, cost_run=None, window=None, period=None,
             rhs_window=None, lower_bound=lb)
    return True


CACHE_SALT = ""  # the modrt binary's hash and the window (main)
RESULTS = ("path", "tick", "status", "clean", "ok", "substep", "counters", "err", "rhs_run",
           "cost", "cost_run", "window", "period", "rhs_window", "per_step", "refresh",
           "run_steps", "lower_bound")


def run_cfg1(ex, c, ref):
    path = "%s/%s/%s.scn" % (OUT, ex.key, c["key"])
    with open(path, "w") as f:
        f.write(c["text"])
    sc = S.Scene(path)
    c["path"], c["tick"] = path, sc.tick
    if dominated(ex, c, path, sc.tick):
        return c
    rc, s, out = host_run(ex, path, sc.tick)
    c["status"] = s.get("status", "exit %d" % rc)
    c["clean"], c["ok"] = clean_of(rc, s)
    c["substep"] = int(s.get("substep", "0").split()[0])
    c["counters"] = ", ".join("%s %s" % (k, s[k]) for k in (
        "nan", "noconv", "singular", "degraded", "substep", "errest", "unstable", "damped")
        if s.get(k, "0") != "0")
    c["err"] = error_of(ref, read_csv(out, ex.signals))[0] if os.path.exists(out) and \
        rc in (0, 3) else math.inf
    c["rhs_run"] = rhs_of(s) / ex.t_end if s else None
    if not (c["clean"] and c["err"] <= max(ex.tols)):
        # outside every bound: no competitor, not counted
        c["cost"] = c["cost_run"] = c["window"] = c["period"] = c["rhs_window"] = None
        return c
    run = S._ticks(ex.t_end, sc.tick)
    if c.get("derive") and c["jac"] != 65535 and c["substep"] == 0:
        return c  # its cost follows from the start-only run's (derive_costs)
    if c.get("derive") and c["jac"] == 65535 and c["substep"] == 0:
        n1, n2 = S._ticks(WINDOW / 2, sc.tick), S._ticks(WINDOW, sc.tick)
        i1, _ = callgrind(path, n1, sc.tick)
        i2, sw = callgrind(path, n2, sc.tick)
        c["per_step"] = (i2 - i1) / (n2 - n1)
        c["refresh"] = i1 - n1 * c["per_step"]
        c["run_steps"] = run
        c["rhs_window"] = rhs_of(sw) / (n2 * sc.tick)
        c["window"] = c["period"] = 0
        c["cost"] = c["cost_run"] = (run * c["per_step"] + c["refresh"]) / ex.t_end
        return c
    return run_window(ex, c)


def run_window(ex, c):
    """instructions over a window of whole periods of the variant from t = 0"""
    sc = S.Scene(c["path"])
    run = S._ticks(ex.t_end, sc.tick)
    p = period_ticks(sc)
    n = max(1, math.ceil(WINDOW / (p * sc.tick) - 1e-9)) * p
    if ex.whole or n >= run:  # a period as long as the run (the Jacobian at the start)
        n = run
    ins, sw = callgrind(c["path"], n, sc.tick)
    c["window"] = n * sc.tick
    c["period"] = p * sc.tick
    c["cost"] = ins / c["window"]
    c["rhs_window"] = rhs_of(sw) / c["window"]
    if ex.whole or n == run:
        c["cost_run"] = c["cost"]
    return c


def derive_costs(ex):
    """the cost of a run whose Jacobian cycle is at least the window, from the start-only
    run at its step and Newton count: steps, plus one refresh per cycle"""
    base = {c["group"]: c for c in ex.cfgs if c.get("derive") and c["jac"] == 65535
            and c.get("per_step") is not None}
    for c in ex.cfgs:
        if not c.get("derive") or c["jac"] == 65535 or c.get("cost") is not None or \
                c.get("substep") or not (c["clean"] and c["err"] <= max(ex.tols)):
            continue
        b = base.get(c["group"])
        if b is None:  # the start-only run was outside every bound: count this one
            run_window(ex, c)
            continue
        cycles = math.ceil(b["run_steps"] / c["jac"])
        c["window"] = c["period"] = 0
        c["rhs_window"] = b["rhs_window"]
        c["cost"] = c["cost_run"] = (b["run_steps"] * b["per_step"] + cycles * b["refresh"]) \
            / ex.t_end


def run_full(ex, c):
    n = S._ticks(ex.t_end, c["tick"])
    ins, _ = callgrind(c["path"], n, c["tick"])
    c["cost_run"] = ins / ex.t_end
    return c


def run_code(ex, c):
    """the whole run of configuration c compiled by scenec with its written-out code
    (code_run.c): instructions of rt_tick + rt_record, its hash the interpreter's"""
    d = "%s/%s/code" % (OUT, ex.key)
    os.makedirs(d, exist_ok=True)
    base = "%s/%s" % (d, c["key"])
    n = S._ticks(ex.t_end, c["tick"])
    r = sh([CODE["scenec"], "-o", base + ".c", c["path"]])
    if r.returncode != 0:
        raise SystemExit("speedup: scenec failed on %s: %s" % (c["path"], r.stderr[-400:]))
    sym = re.search(r"^const rt_scene (mdl_scene_\w+) = \{$", open(base + ".c").read(), re.M)
    main = os.path.join(os.path.dirname(os.path.abspath(__file__)), "code_run.c")
    r = sh(CODE["cc"].split() + ["-DCODE_RUN_SCENE=" + sym.group(1), "-o", base, main,
                                 base + ".c"] + CODE["objs"].split() + ["-lm"])
    if r.returncode != 0:
        raise SystemExit("speedup: cannot build %s: %s" % (base, r.stderr[-400:]))
    r = sh(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
            "--collect-atstart=no", "--toggle-collect=rt_tick", "--toggle-collect=rt_record",
            base, str(n)])
    m = re.search(r"Collected : (\d+)", r.stderr)
    interp = summary(sh([MODRT, "run", c["path"], "--t-end=%.17g" % (n * c["tick"])]).stdout)
    mine = summary(r.stdout)
    if not m or mine.get("hash") != interp.get("hash"):
        raise SystemExit("speedup: %s compiled: hash %s, interpreted %s" % (
            c["path"], mine.get("hash"), interp.get("hash")))
    c["cost_code"] = int(m.group(1)) / ex.t_end
    return c


def run_tick_only(ex, c):
    """rt_tick alone over the whole run: the cost without recording"""
    n = S._ticks(ex.t_end, c["tick"])
    ins, _ = callgrind(c["path"], n, c["tick"], fns=("rt_tick",))
    c["cost_tick"] = ins / ex.t_end
    return c


def reference(ex):
    """the first reference's rows and its own error (its distance to the second)"""
    rows = []
    for i, (m, h) in enumerate(ex.refs):
        path = "%s/%s/ref%d.scn" % (OUT, ex.key, i)
        with open(path, "w") as f:
            f.write(S.variant(ex.sc, tick=h, single=(m, {})))
        rc, s, out = host_run(ex, path, h)
        if not clean_of(rc, s)[1]:
            raise SystemExit("speedup: reference %s at %s of %s: %s" % (
                m, h_ms(h), ex.key, s.get("status", "exit %d" % rc)))
        rows.append(read_csv(out, ex.signals))
    own, n = error_of(rows[0], rows[1])
    note = "one set, %s at %s; a second, %s at %s, differs from it by %.1e (%d instants)" % (
        ex.refs[0][0], h_ms(ex.refs[0][1]), ex.refs[1][0], h_ms(ex.refs[1][1]), own, n)
    return rows[0], own, note


# ------------------------------------------------------------------ analysis

# the criteria: a run with no fault (a step's estimate above its set's accuracy is allowed:
# the error against the reference decides), and, stricter, a run with status ok
CRITERIA = (("clean", "no fault"), ("ok", "status ok"))


def within(ex, variant, tol, crit, key="cost"):
    return [c for c in ex.cfgs if c["variant"] == variant and c[crit] and c["err"] <= tol
            and c.get(key)]


def cheapest(ex, variant, tol, crit, key="cost"):
    cand = within(ex, variant, tol, crit, key)
    return min(cand, key=lambda c: c[key]) if cand else None


def finalists(ex):
    out = []
    for crit, _ in CRITERIA:
        for tol in ex.tols:
            for v in ("single", "multirate"):
                best = cheapest(ex, v, tol, crit)
                if best:
                    out += [c for c in within(ex, v, tol, crit)
                            if c["cost"] <= FINALIST * best["cost"] and c not in out]
    return out


def winners(ex):
    """[(criterion, its label, bound, cheapest single, cheapest multirate)] by whole-run
    counts"""
    out = []
    for crit, label in CRITERIA:
        for tol in ex.tols:
            out.append((crit, label, tol, cheapest(ex, "single", tol, crit, "cost_run"),
                        cheapest(ex, "multirate", tol, crit, "cost_run")))
    return out


def call_tree(text):
    """callgrind_annotate --tree=caller: {(caller, callee): inclusive count} and each
    function's inclusive count (the sum over its callers)"""
    edges, incl, callers = {}, {}, []
    for ln in text.splitlines():
        m = re.match(r"^\s*([\d,]+) \([^)]*\)\s+([<*])\s+(\S+)", ln)
        if not m:
            callers = []
            continue
        v, fn = int(m.group(1).replace(",", "")), m.group(3).split(":")[-1]
        if m.group(2) == "<":
            callers.append((fn, v))
            continue
        for c, w in callers:
            edges[(c, fn)] = edges.get((c, fn), 0) + w
        incl[fn] = max(incl.get(fn, 0), sum(w for _, w in callers) if callers else v)
        callers = []
    return edges, incl


def profile(ex, c, i):
    """the configuration's whole run under callgrind: total, call edges, inclusive counts"""
    n = S._ticks(ex.t_end, c["tick"])
    out = "%s/%s/profile%d.callgrind" % (OUT, ex.key, i)
    total, _ = callgrind(c["path"], n, c["tick"], out)
    r = sh(["callgrind_annotate", "--inclusive=yes", "--tree=caller", "--threshold=100", out])
    edges, incl = call_tree(r.stdout)
    return total, edges, incl


# ------------------------------------------------------------------ output

def shipped_lines(ex):
    """the scene as shipped against each bound's single-rate winner"""
    out = []
    for c in ex.cfgs:
        if not c["shipped"]:
            continue
        if not c.get("cost_run"):
            out.append("as shipped %s: error %s m, %s, not counted" % (
                ex.key, err_text(c["err"]), status_text(c)))
            continue
        for crit, label, tol, s, _ in winners(ex):
            if s and c[crit] and c["err"] <= tol:
                out.append("as shipped %s at %g m%s: %.3g (%s, error %s m, %.3g insn/s; "
                           "single %s %.3g insn/s)" % (
                               ex.key, tol, "" if crit == "clean" else ", status ok",
                               s["cost_run"] / c["cost_run"], c["desc"], err_text(c["err"]),
                               c["cost_run"], s["desc"], s["cost_run"]))
            elif s:
                out.append("as shipped %s at %g m%s: outside the bound (error %s m, %s)" % (
                    ex.key, tol, "" if crit == "clean" else ", status ok",
                    err_text(c["err"]), status_text(c)))
    return out


def fmt(v):
    return "%.2e" % v if v is not None and v == v else "-"


def line_code(ex, crit, tol):
    """the speedup of the cheapest compiled single-rate and multirate finalists"""
    s = cheapest(ex, "single", tol, crit, "cost_code")
    m = cheapest(ex, "multirate", tol, crit, "cost_code")
    if not s or not m:
        return None
    return "multirate speedup %s at %g m%s, compiled: %.3g (single %s %.3g insn/s, multirate " \
        "%s %.3g insn/s)" % (ex.key, tol, "" if crit == "clean" else ", status ok",
                             s["cost_code"] / m["cost_code"], s["desc"], s["cost_code"],
                             m["desc"], m["cost_code"])


def line_tick(ex, crit, tol, s, m):
    if not s or not m:
        return None
    return "without recording (rt_tick alone), %s, %g m: %.3g (single %.3g, multirate %.3g " \
        "insn/s)" % ("no fault" if crit == "clean" else "status ok", tol,
                     s["cost_tick"] / m["cost_tick"], s["cost_tick"], m["cost_tick"])


def line(ex, crit, tol, s, m):
    head = "multirate speedup %s at %g m%s: " % (ex.key, tol, "" if crit == "clean" else
                                                 ", status ok")
    if not s or not m:
        return head + "none (no %s configuration within the bound)" % (
            "single-rate" if not s else "multirate")
    return head + "%.3g (single %s %.3g insn/s, multirate %s %.3g insn/s)" % (
        s["cost_run"] / m["cost_run"], s["desc"], s["cost_run"], m["desc"], m["cost_run"])


def front(pts):
    """the points no cheaper point beats in error, cheapest first"""
    out = []
    for x, y in sorted(pts):
        if not out or y < out[-1][1]:
            out.append((x, y))
    return out


def write_csv(ex):
    """per series, the configurations without a fault on its work-precision front"""
    path = "build/bench/speedup-%s.csv" % ex.key
    series = {}
    for c in ex.cfgs:
        if c["clean"] and c["err"] < 1 and c["cost"]:
            series.setdefault(c["series"], []).append((c["cost"], max(c["err"], 1e-14)))
    with open(path, "w") as f:
        f.write("series,x,y\n")
        for name, pts in series.items():
            for x, y in front(pts):
                f.write("%s,%.6g,%.6g\n" % (name, x, y))
    return path


def err_text(e):
    return fmt(e) if e < 1e3 else "%.0e" % e if e < math.inf else "inf"


def status_text(c):
    if c["ok"]:
        return "ok" + (" (substep %s)" % c["substep"] if c["substep"] else "")
    if c["clean"]:
        return "errest: %s" % (c["counters"] or c["status"])
    # the status too: a fault may show only in it (a coupling lost counts as errest)
    return "**fault** (%s): %s" % (c["status"], c["counters"] or "no counter")


def results_md(ex, ref_note, splits):
    if ex.whole:
        how = "over the whole run of %g s, for every configuration" % ex.t_end
    else:
        how = ("over a window from t = 0 of whole periods of the variant (the least common "
               "multiple of every set's step and every implicit set's Jacobian cycle; at "
               "least %g s), and for the finalists (within %gx of the cheapest of their "
               "variant under a bound and criterion) over the whole run of %g s, which "
               "gives the speedup" % (WINDOW, FINALIST, ex.t_end))
    o = ["#### %s\n" % ex.key,
         "Error: %s. Reference: %s. Cost: host instructions of rt_tick + rt_record per "
         "simulated second (callgrind), %s. Every set at `accuracy (%s)`.%s\n" % (
             ex.what, ref_note, how, ACCURACY, "\n\n" + ex.sweep_note if ex.sweep_note
             else ""),
         "| criterion | bound | variant | cheapest configuration | error [m] "
         "| insn/s window | insn/s whole run |",
         "|---|---|---|---|---:|---:|---:|"]
    lines = []
    for crit, label, tol, s, m in winners(ex):
        for v, c in (("single", s), ("multirate", m)):
            o.append("| %s | %g m | %s | %s | %s | %s | %s |" % (
                label, tol, v, c["desc"] if c else "none", err_text(c["err"]) if c else "",
                fmt(c["cost"]) if c else "", fmt(c["cost_run"]) if c else ""))
        lines.append(line(ex, crit, tol, s, m))
    lines += shipped_lines(ex)
    o.append("")
    o += ["    " + ln for ln in lines]
    o.append("")
    code = [line_code(ex, crit, tol) for crit, _, tol, _, _ in winners(ex)]
    if any(code):
        o.append("Compiled, as the scenes ship: each finalist compiled by scenec with the code "
                 "it writes out (tools/dev/bench/code_run.c, its trace hash equal to the "
                 "interpreter's), instructions of rt_tick + rt_record over the whole run; the "
                 "cheapest of each variant:\n")
        o += ["    " + ln for ln in code if ln]
        o.append("")
    o.append("The same winners without recording (instructions of rt_tick alone over the "
             "whole run; recording every tick is part of both variants' fixed work):\n")
    o += ["- " + line_tick(ex, crit, tol, s, m) for crit, _, tol, s, m in winners(ex)
          if line_tick(ex, crit, tol, s, m)]
    o.append("")
    for sp in splits:
        o += [sp, ""]
    o.append("Every configuration, cheapest first within each variant (error over the run; "
             "instructions over the window%s; right-hand sides per simulated second over the "
             "window and over the whole run, which differ where the work depends on the "
             "data; status: ok, errest = a step's estimate above its set's accuracy (doubtful,"
             " no fault), **fault** (its status) = a failed run):\n" % (" (here the whole run)"
                                                          if ex.whole else ""))
    o.append("Configurations run: %d; outside every bound (error above %g m or a fault), "
             "not counted and not listed: %d; dominated by their right-hand sides alone "
             "(below): %d; smaller steps pruned: %d.\n" % (
                 len(ex.cfgs), max(ex.tols), ex.outside, getattr(ex, "dominated", 0),
                 ex.pruned))
    o.append("| variant | configuration | error [m] | status | insn/s | window [s] "
             "| rhs/s window | rhs/s run |")
    o.append("|---|---|---:|---|---:|---:|---:|---:|")
    for c in sorted([c for c in ex.cfgs if c["cost"]],
                    key=lambda c: (c["variant"] != "single", c["cost"])):
        o.append("| %s | %s | %s | %s | %s | %g | %.4g | %s |" % (
            c["variant"], c["desc"], err_text(c["err"]), status_text(c), fmt(c["cost"]),
            c["window"], c["rhs_window"], "%.4g" % c["rhs_run"] if c["rhs_run"] else "-"))
    o.append("")
    return "\n".join(o)


def split_md(ex, c, label, total, edges, incl, single=None):
    """the cost of a multirate configuration by part: the slow set's method and
    projection, the fast set's method, the tick's fixed work, recording"""
    t = ex.t_end
    sc = S.Scene(c["path"])
    slow, fast = sc.roles()["slow"], "+".join(sc.roles()["fast"])

    def into(*fns, frm=None):
        return sum(v for (a, b), v in edges.items() if b in fns and (frm is None or a in frm))
    rec = incl.get("rt_record", 0)
    # the recorded multibody signals: a multi-tick set's computed in its refresh, the
    # others' in rt_record (rt/held.c); the refresh's share is what rt_record's calls of
    # rti_sig_value leave (the compiler may inline the refresh's callers of it, so no
    # edge of theirs is counted on)
    sig = into("signal", frm=("rti_sig_value",))
    sig_rec = into("rti_sig_value", frm=("rt_record",))
    sig_refresh = max(sig - sig_rec, 0)
    rows = [
        ("%s: method stages (erk_step: right-hand sides, multibody solve)" % slow,
         into("erk_step")),
        ("%s: projection (rti_mbs_project)" % slow, into("rti_mbs_project")),
        ("%s: method (ros2_step, dirk_step, transition_step: its right-hand sides, "
         "Jacobians, solves)" % fast, into("ros2_step", "dirk_step", "transition_step")),
        ("sampled controller (discrete_updates)", into("discrete_updates")),
        ("outputs at step ends and held copies (rti_outputs, copy_outputs, "
         "rti_held_before_step, rti_held_after_step from rt_tick and run_step)",
         into("rti_outputs", "copy_outputs.isra.0", "copy_outputs", "rti_held_before_step",
              "rti_held_after_step", frm=("rt_tick", "run_step"))),
        ("outputs at the tick (rti_held_renew, rt_refresh: full or renewed; without the "
         "held multibody signals)", into("rt_refresh", "refresh", "rti_held_renew",
                                         frm=("rt_tick",)) - sig_refresh),
        ("histories (rti_xset_push)", into("rti_xset_push")),
        ("background transition without the step (release_due, publish_due: copies)",
         incl.get("release_due", 0) + incl.get("publish_due", 0) - incl.get("run_step", 0)
         - into("rti_xset_push", frm=("publish_due", "publish"))),
        ("recording: recorded multibody signals (residuals, energies: rt/mbs.c signal; "
         "once per step of a set held between steps)", sig),
        ("recording: rt_record without them (the values read, the trace hash inline)",
         rec - sig_rec),
    ]
    rows.append(("rest of rt_tick (schedule, set overhead, checks)",
                 total - sum(v for _, v in rows)))
    o = ["Where the instructions of the cheapest multirate configuration within %g m "
         "(%s) go: %s (callgrind_annotate, inclusive counts over the whole run of %g s, per "
         "simulated second; %s steps inside rti_step_set %s):\n" % (
             ex.tols[-1], label, c["desc"], t, slow,
             "called from run_step (rt/bg.c), %.3g insn/s in all" % (
                 incl.get("run_step", 0) / t) if incl.get("run_step") else "from rt_tick"),
         "| part | insn/s | share |", "|---|---:|---:|"]
    for name, v in rows:
        o.append("| %s | %.3g | %.1f%% |" % (name, v / t, 100.0 * v / total))
    o.append("| **rt_tick + rt_record** | **%.3g** | 100%% |" % (total / t))
    slow_part = rows[0][1] + rows[1][1]
    rest = (total - slow_part) / t
    if single and rest > 0:
        o.append("\nWithout %s's stages and projection this configuration costs %.3g insn/s "
                 "(%.0f%%): with %s free, no configuration with this fast side gives more than "
                 "%.3g against the single-rate %.3g insn/s; a speedup of 20 needs the whole "
                 "at most %.3g insn/s, so %s at most %.3g insn/s (now %.3g: %.2g times "
                 "less)." % (slow, rest, 100.0 * (total - slow_part) / total, slow,
                             single["cost_run"] / rest, single["cost_run"],
                             single["cost_run"] / 20, slow, single["cost_run"] / 20 - rest,
                             slow_part / t, (slow_part / t) / max(single["cost_run"] / 20 -
                                                                  rest, 1e-300))
                 if single["cost_run"] / 20 > rest else
                 "\nWithout %s's stages and projection this configuration costs %.3g insn/s "
                 "(%.0f%%), more than the single-rate %.3g insn/s over 20: no configuration "
                 "with this fast side reaches a speedup of 20 (at most %.3g with %s free)." % (
                     slow, rest, 100.0 * (total - slow_part) / total, single["cost_run"],
                     single["cost_run"] / rest, slow))
    return "\n".join(o)


def splice(path, text):
    doc = open(path).read()
    a, b = doc.find(BEGIN), doc.find(END)
    if a < 0 or b < a:
        raise SystemExit("speedup: %s has no %s ... %s" % (path, BEGIN, END))
    doc = doc[:a + len(BEGIN)] + "\n" + text.rstrip() + "\n" + doc[b:]
    open(path, "w").write(doc)


# ------------------------------------------------------------------ main

def run_example(ex, pool, log):
    os.makedirs("%s/%s" % (OUT, ex.key), exist_ok=True)
    t0 = time.time()
    ref, own, note = reference(ex)
    log("%s: reference %s" % (ex.key, note))
    if own > ex.tols[-1] / 100:
        log("%s: WARNING the reference's own error %.1e is above 1/100 of %g m" % (
            ex.key, own, ex.tols[-1]))
    ex.rhs_insn = rhs_cost(ex)
    log("%s: one right-hand side costs %.0f instructions" % (ex.key, ex.rhs_insn))
    rungs = {id(c) for lad in ex.ladders.values() for c in lad[1:]}
    list(pool.map(lambda c: run_cfg(ex, c, ref), [c for c in ex.cfgs if id(c) not in rungs]))
    # the ladders: the next smaller step only where this one misses the tightest bound
    pruned = []
    for r in range(1, max([len(v) for v in ex.ladders.values()] or [0])):
        todo = []
        for lad in ex.ladders.values():
            if r >= len(lad) or lad[r - 1] in pruned:
                continue
            if lad[r - 1]["clean"] and lad[r - 1]["err"] <= min(ex.tols):
                pruned += lad[r:]
            else:
                todo.append(lad[r])
        list(pool.map(lambda c: run_cfg(ex, c, ref), todo))
    ex.cfgs = [c for c in ex.cfgs if c not in pruned]
    derive_costs(ex)
    ex.pruned = len(pruned)
    ex.dominated = len([c for c in ex.cfgs if c["status"] == "dominated"])
    ex.outside = len([c for c in ex.cfgs if c.get("cost") is None]) - ex.dominated
    log("%s: %d configurations run, %d of them outside every bound, %d smaller steps "
        "pruned (%.0f s)" % (ex.key, len(ex.cfgs), ex.outside, ex.pruned, time.time() - t0))
    fin = [c for c in finalists(ex) if not ex.whole and c.get("cost_run") is None]
    fin += [c for c in ex.cfgs if c["shipped"] and c.get("cost") and not ex.whole and
            c.get("cost_run") is None and c not in fin]
    list(pool.map(lambda c: run_full(ex, c), fin))
    if CODE:
        code = fin + [c for c in finalists(ex) if c not in fin]
        list(pool.map(lambda c: run_code(ex, c), code))
        log("%s: %d finalists compiled and counted over the whole run (%.0f s)" % (
            ex.key, len(code), time.time() - t0))
    if not ex.whole:
        log("%s: %d finalists counted over the whole run (%.0f s)" % (ex.key, len(fin),
                                                                      time.time() - t0))
    for c in fin:
        log("  %-9s %-88s window %.3e run %.3e (%+.1f%%)" % (
            c["variant"], c["desc"], c["cost"], c["cost_run"],
            100 * (c["cost_run"] / c["cost"] - 1)))
    lines, profiled, splits = [], [], []
    won = []
    for _, _, _, s, m in winners(ex):
        won += [c for c in (s, m) if c and c not in won]
    list(pool.map(lambda c: run_tick_only(ex, c), won))
    for crit, label, tol, s, m in winners(ex):
        for v, c in (("single", s), ("multirate", m)):
            log("%s, %s, within %g m: cheapest %s: %s" % (
                ex.key, label, tol, v, "%s, error %.2e m, %.3e insn/s (window %.3e)" % (
                    c["desc"], c["err"], c["cost_run"], c["cost"]) if c else "none"))
        lines.append(line(ex, crit, tol, s, m))
        # the cost split of each criterion's cheapest multirate configuration at the
        # tightest bound
        if m and tol == ex.tols[-1] and m not in profiled:
            profiled.append(m)
            total, edges, incl = profile(ex, m, len(profiled))
            splits.append(split_md(ex, m, label, total, edges, incl, s))
            log(splits[-1])
    lines += shipped_lines(ex)
    for ln in lines:
        log(ln)
    for crit, label, tol, s, m in winners(ex):
        if line_tick(ex, crit, tol, s, m):
            log(line_tick(ex, crit, tol, s, m))
        if line_code(ex, crit, tol):
            log(line_code(ex, crit, tol))
    write_csv(ex)
    return results_md(ex, note, splits)


def main():
    global MODRT
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--jobs", type=int, default=2, help="parallel runs (default 2)")
    ap.add_argument("--modrt", default=MODRT, help="the host modrt (default %(default)s)")
    ap.add_argument("--quick", action="store_true", help="a few configurations (smoke test)")
    ap.add_argument("--only", default="pendulum10_actuated,lane_change",
                    help="examples, comma-separated")
    ap.add_argument("--doc", help="Markdown file whose bench markers receive the results")
    ap.add_argument("--code", nargs=3, metavar=("SCENEC", "CC", "OBJS"),
                    help="also compile the finalists: scenec, the compiler with its flags, "
                    "the runtime's and the models' objects")
    a = ap.parse_args()
    MODRT = a.modrt
    global CODE
    if a.code:
        CODE = {"scenec": a.code[0], "cc": a.code[1], "objs": a.code[2]}
    global CACHE_SALT
    with open(MODRT, "rb") as f:
        CACHE_SALT = hashlib.sha1(f.read()).hexdigest() + " %g" % WINDOW
    os.makedirs("build/bench", exist_ok=True)
    txt = open("build/bench/speedup.txt", "w")

    def log(s):
        print(s, flush=True)
        txt.write(s + "\n")
    started = time.time()
    plans = {"pendulum10_actuated": plan_actuated, "lane_change": plan_lane_change}
    mds = []
    with cf.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for key in a.only.split(","):
            mds.append(run_example(plans[key](a.quick), pool, log))
    head = ("Deterministic counts (`make speedup`, tools/dev/bench/speedup.py), %d jobs, %.0f s "
            "at %s.\n" % (a.jobs, time.time() - started, sh(["git", "rev-parse", "--short",
                                                              "HEAD"]).stdout.strip()))
    md = head + "\n" + "\n".join(mds)
    open("build/bench/speedup.md", "w").write(md)
    if a.doc:
        splice(a.doc, md)
    log("speedup: %.0f s; build/bench/speedup.md, speedup.txt, speedup-*.csv" % (
        time.time() - started))


if __name__ == "__main__":
    main()
