#!/usr/bin/python3
"""study.py - `make study` (issue #15): what accuracy costs in time, for the four paper
examples (pendulum10, pendulum10_actuated, beltgear, lane_change), on the host and on
Cortex-M4F and Cortex-M7. Writes docs/study.md and docs/study/*.svg (--mode full) or
checks a quick subset and writes only into build/study/ (--mode quick, `make test-study`).

For every example it generates variant scenes from the scene files as they are at run time
(tools/dev/study/scene.py: method, step, base tick, sets, stabilization, Newton and Broyden
bounds), and for each variant
  - the estimated global error of `modrt check` (the variant again at half its steps,
    Richardson), read at the same instants and signals, beside the error, to show how
    well the estimate tracks it,
  - the error against an independent reference (pendulum10: the chain in minimal
    coordinates, tools/dev/study/pendulum_ref.py and the long-double values of
    tests/whitebox/test_mbs_scene.c; the others: two fine single-rate runs of different
    methods, whose difference is the reference's own error and bounds the plotted range),
    computed by `modrt sweep`: one campaign per example and number type over the
    variants' scene files, its metric `error against` the reference as a table, at the
    reference's instants where every set of the variant has stepped,
  - the host's instructions per simulated second: callgrind counting rt_tick and
    rt_record only (`--toggle-collect`), over the first W simulated seconds,
  - Cortex-M7 and Cortex-M4F instructions per simulated second and the worst tick: a
    per-variant image (tests/cross/footprint_main.c) under QEMU with the counting plugin
    tools/dev/qemu/insn_count.c, over the first W seconds (shorter for software doubles),
  - host wall time per simulated second of the error run (secondary, noisy).
Every image's trace hash is checked against the host's run of the same variant."""
import argparse
import concurrent.futures as cf
import csv
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene as S  # noqa: E402
import svg  # noqa: E402

B = "build/study"
MODRT = {"double": "build/host/modrt", "float": "build/host-float/modrt"}
SCENEC = "build/host/scenec"
PLUGIN = "build/host/libinsn_count.so"
TOLS = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
# a run of the M4F in double executes about SOFT_RATIO times the M7's instructions (doubles
# in software, CROSS.md); its window is shortened so that it stays near SOFT_BUDGET
SOFT_RATIO, SOFT_BUDGET = 40, 1.5e9
# the windows of the most expensive configurations hold at most this many right-hand sides
# (counted by the error run; deterministic, unlike its time)
RHS_BUDGET = 40000
M7_HZ = 600e6  # docs/footprint.md: 600 MHz, one instruction per cycle (an assumption)
ORDER = {"euler": 1, "heun": 2, "bs3": 3, "rk4": 4, "dopri5": 5, "beuler": 1, "trap": 2,
         "sdirk2": 2, "sdirk3": 3, "ros2": 2}


def sh(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def make_var(name):
    return sh(["make", "-s", "print-" + name]).stdout.strip()


# ------------------------------------------------------------------ the examples

class Example:
    """one example: its scene, the error's signals and instants, windows, references"""

    def __init__(self, key, path, unit, what, signals, t_err, grid, window, window_soft):
        self.key, self.path, self.unit, self.what = key, path, unit, what
        self.sc = S.Scene(path)
        self.signals = signals(self.sc.records)
        self.t_err, self.grid, self.window, self.window_soft = t_err, grid, window, window_soft
        self.cfgs = []
        self.refs = []          # [(label, text)] fine runs; or pendulum10's own
        self.ref_rows = None    # {time key: {signal: value}}
        self.ref_err = None
        self.ref_note = ""
        self.ref_fn = None      # a function giving (rows, own error, note)
        self.extra_checks = []
        self.note = None        # a function giving a paragraph on the results

    def add(self, series, label, text, real="double", shipped=None, order=None):
        k = re.sub(r"[^A-Za-z0-9_.-]+", "_", "%s_%s_%s" % (series, label, real))
        if any(c["key"] == k for c in self.cfgs):
            return
        self.cfgs.append({"series": series, "label": label, "text": text, "real": real,
                          "shipped": shipped, "key": k, "order": order})


def sig_re(pattern):
    def pick(records):
        s = [r for r in records if re.match(pattern, r)]
        return s or list(records)
    return pick


def h_ms(h):
    return ("%g ms" % (h * 1e3)) if h >= 1e-4 else ("%g us" % (h * 1e6))


# the implicit methods reuse their Jacobian as a user would (the shipped single-rate
# scenes refresh it every 1024 steps): a refresh at every step costs 5 to 12 times as much
# (docs/multirate.md "The benchmark") and would make them lose to every explicit method
IMPLICIT_JAC = {"ros2": "1024", "trap": "1024", "sdirk2": "1024", "sdirk3": "1024",
                "beuler": "1024"}


def explicit_sweep(ex, sc, sweeps, real="double", stab=None, suffix="", order=True, extra=None):
    """single-rate variants: base tick = step"""
    for m, hs in sweeps:
        for h in hs:
            cl = dict(extra or {})
            if m in IMPLICIT_JAC and "jacobian" not in cl:
                cl["jacobian"] = IMPLICIT_JAC[m]
            text = S.variant(sc, tick=h, single=(m, cl), stab=stab)
            ex.add(m + suffix, h_ms(h), text, real=real,
                   order=ORDER[m] if order and not suffix else None)


def plan_pendulum10(quick):
    sc = S.Scene("models/scenes/pendulum10.scn")
    ex = Example("pendulum10", sc.path, "m",
                 "largest position error of B1..B10 at t = 2 s [m]",
                 sig_re(r"^B\d+\.(x|z)$"), 2.0, 2.0, 0.5, 0.1)
    ms = 1e-3
    if quick:
        explicit_sweep(ex, sc, [("rk4", [8 * ms, 4 * ms, 2 * ms]),
                                ("dopri5", [8 * ms, 4 * ms, 2 * ms])])
    else:
        explicit_sweep(ex, sc, [
            ("euler", [0.5 * ms, 0.25 * ms]),
            ("heun", [4 * ms, 2 * ms, 1 * ms, 0.5 * ms, 0.25 * ms]),
            ("bs3", [8 * ms, 4 * ms, 2 * ms, 1 * ms, 0.5 * ms]),
            ("rk4", [16 * ms, 8 * ms, 4 * ms, 2 * ms, 1 * ms, 0.5 * ms]),
            ("dopri5", [16 * ms, 8 * ms, 4 * ms, 2 * ms, 1 * ms]),
            ("sdirk3", [4 * ms, 2 * ms, 1 * ms]),
            ("ros2", [2 * ms, 1 * ms, 0.5 * ms]),
            ("trap", [2 * ms, 1 * ms]),
        ])
        for m, hs in (("rk4", [8 * ms, 4 * ms, 2 * ms, 1 * ms]),
                      ("dopri5", [16 * ms, 8 * ms, 4 * ms, 2 * ms])):
            explicit_sweep(ex, sc, [(m, hs)], stab="none", suffix=" no projection")
            explicit_sweep(ex, sc, [(m, hs)], stab=("baumgarte", 20, 100),
                           suffix=" Baumgarte (20, 100)")
            explicit_sweep(ex, sc, [(m, hs)], real="float", suffix=" float")
    shipped(ex, quick)
    return ex


def shipped(ex, quick, also=()):
    """the library scenes of this example's model, as they are, in double (and float)"""
    for path in [ex.path] + list(also):
        sc = S.Scene(path)
        ex.add("shipped", sc.name, S.variant(sc), shipped=sc.name)
        if not quick:
            ex.add("shipped float", sc.name, S.variant(sc), real="float", shipped=sc.name)


def same_model(path, others):
    """library scenes that include the same model file as path"""
    inc = re.findall(r'include\s+"([^"]+)"', open(path).read())
    out = []
    for p in others:
        if p != path and inc and re.findall(r'include\s+"([^"]+)"', open(p).read()) == inc:
            out.append(p)
    return out


def tune_schedules(ex, tols):
    """modrt tune's cheapest schedule for each tolerance, on the example's error signals"""
    out = []
    for tol in tols:
        r = sh([MODRT["double"], "tune", ex.path, "--tol", "%g" % tol,
                "--only", ",".join(ex.signals)])
        m = re.search(r"^schedule: (.*)$", r.stdout, re.M)
        if r.returncode == 0 and m:
            sched = dict((a, int(b)) for a, b in (x.split("=") for x in m.group(1).split()))
            out.append((tol, sched))
    return out


def multirate_sweeps(ex, quick, slow_methods, ratios, fast_variants, tune_tols):
    sc = ex.sc
    if len(sc.sets) < 2:
        return
    tick = sc.tick
    roles = sc.roles()
    for m in slow_methods:
        for r in ratios:
            ex.add("multirate %s + %s" % (m, sc.method_of(roles["fast"][0])),
                   "%d ticks" % r, S.variant(sc, mods={"slow": {"method": m,
                                                                "step": r * tick}}))
    for label, fmods, r in fast_variants:
        ex.add("multirate, fast set %s" % label, "%d ticks" % r,
               S.variant(sc, mods={"slow": {"step": r * tick}, "fast": fmods}))
    for tol, sched in tune_schedules(ex, tune_tols):
        mods = {n: {"step": k * tick} for n, k in sched.items()}
        ex.add("modrt tune", "tol %g: %s" % (tol, " ".join("%s %d" % x for x in sched.items())),
               S.variant(sc, mods=mods))


def stab_sweep(ex, sc):
    """a scene with joints: its own schedule without projection and with Baumgarte"""
    if re.search(r"\blink\s*\(", "\n".join(sc.stmts)):
        for label, st in (("no projection", "none"),
                          ("Baumgarte (20, 100)", ("baumgarte", 20, 100))):
            ex.add("shipped schedule, " + label, sc.name, S.variant(sc, stab=st))


def plan_actuated(quick):
    path = "models/scenes/pendulum10_actuated.scn"
    sc = S.Scene(path)
    ex = Example("pendulum10_actuated", path, "m",
                 "largest position error of B1..B10 every 0.128 s over 10 s [m]",
                 sig_re(r"^B\d+\.(x|z)$"), 10.0, 0.128, 0.256, 0.064)
    ms = 1e-3
    for label, m, h in (("dopri5", "dopri5", 5e-5), ("rk4", "rk4", 2.5e-5)):
        ex.refs.append((m, h))
    single = S.Scene("models/scenes/pendulum10_actuated_single.scn")
    if not quick:
        explicit_sweep(ex, sc, [("dopri5", [0.5 * ms, 0.25 * ms, 0.125 * ms]),
                                ("rk4", [0.25 * ms, 0.125 * ms]),
                                ("ros2", [1 * ms, 0.5 * ms, 0.25 * ms]),
                                ("trap", [1 * ms, 0.5 * ms, 0.25 * ms]),
                                ("sdirk2", [1 * ms, 0.5 * ms]),
                                ("sdirk3", [1 * ms, 0.5 * ms]),
                                ("beuler", [1 * ms, 0.5 * ms])], order=False)
        for n in (1, 2):
            ex.add("sdirk3 newton (N)", "1 ms, N = %d" % n,
                   S.variant(sc, tick=1 * ms, single=("sdirk3", {"newton": str(n)})))
        multirate_sweeps(ex, quick, ["bs3", "rk4", "dopri5"], [4, 8, 16, 32],
                         [("trap", {"method": "trap"}, 8), ("trap", {"method": "trap"}, 16),
                          ("trap", {"method": "trap"}, 32),
                          ("sdirk2 newton (1)", {"method": "sdirk2", "newton": "1"}, 16),
                          ("sdirk2 newton (2)", {"method": "sdirk2", "newton": "2"}, 16),
                          ("sdirk2 newton (4)", {"method": "sdirk2", "newton": "4"}, 16)],
                         [1e-2, 1e-3, 1e-4, 1e-5])
        stab_sweep(ex, sc)
    shipped(ex, quick, also=[single.path])
    return ex


def plan_beltgear(quick):
    path = "models/scenes/beltgear.scn"
    sc = S.Scene(path)
    ex = Example("beltgear", path, "rad/s",
                 "largest error of R1.omega, R2.omega every 5 ms over 0.5 s [rad/s]",
                 sig_re(r"^R\d+\.omega$"), 0.5, 0.005, 0.05, 0.02)
    # the reference: tools/dev/study/beltgear_ref.py; a fine run of modrt is compared with it
    ex.ref_fn = beltgear_refs
    ex.refs.append(("dopri5", 1e-6))
    ex.note = beltgear_note
    ms = 1e-3
    if quick:
        explicit_sweep(ex, sc, [("rk4", [0.2 * ms, 0.1 * ms, 0.05 * ms])])
    else:
        explicit_sweep(ex, sc, [
            ("euler", [0.02 * ms, 0.01 * ms]),
            ("heun", [0.1 * ms, 0.05 * ms, 0.025 * ms]),
            ("bs3", [0.25 * ms, 0.1 * ms, 0.05 * ms]),
            ("rk4", [1 * ms, 0.5 * ms, 0.25 * ms, 0.2 * ms, 0.1 * ms, 0.05 * ms]),
            ("dopri5", [1 * ms, 0.5 * ms, 0.25 * ms, 0.1 * ms, 0.05 * ms]),
            ("beuler", [0.1 * ms, 0.05 * ms]),
            ("trap", [1 * ms, 0.5 * ms, 0.25 * ms, 0.1 * ms]),
            ("sdirk2", [0.5 * ms, 0.25 * ms, 0.1 * ms]),
            ("sdirk3", [1 * ms, 0.5 * ms, 0.25 * ms, 0.1 * ms]),
            ("ros2", [1 * ms, 0.5 * ms, 0.25 * ms, 0.1 * ms]),
        ])
        for it in (1, 2, 3):
            ex.add("rk4, Broyden iterations (N)", "0.1 ms, N = %d" % it,
                   S.variant(sc, tick=0.1 * ms, single=("rk4", {}), loop_iter=it))
            ex.add("dopri5, Broyden iterations (N)", "0.25 ms, N = %d" % it,
                   S.variant(sc, tick=0.25 * ms, single=("dopri5", {}), loop_iter=it))
        for n in (1, 2):
            ex.add("sdirk3 0.25 ms, newton (N)", "N = %d" % n,
                   S.variant(sc, tick=0.25 * ms, single=("sdirk3", {"newton": str(n)})))
        explicit_sweep(ex, sc, [("rk4", [0.2 * ms, 0.1 * ms]),
                                ("dopri5", [0.5 * ms, 0.25 * ms])], real="float",
                       suffix=" float")
    shipped(ex, quick)
    return ex


def plan_lane_change(quick):
    path = "models/scenes/lane_change.scn"
    sc = S.Scene(path)
    ex = Example("lane_change", path, "m",
                 "largest error of the cars' positions (x, y) every 0.16 s over the run [m]",
                 sig_re(r"^V\d+\.(x|y)$"), None, 0.16, 0.32, 0.08)
    ms = 1e-3
    for label, m, h in (("dopri5", "dopri5", 0.1 * ms), ("rk4", "rk4", 0.05 * ms)):
        ex.refs.append((m, h))
    others = sorted("models/scenes/" + f for f in os.listdir("models/scenes")
                    if f.startswith("lane_change") and f.endswith(".scn"))
    if not quick:
        explicit_sweep(ex, sc, [("dopri5", [0.5 * ms, 0.25 * ms, 0.125 * ms]),
                                ("rk4", [0.25 * ms, 0.125 * ms]),
                                ("ros2", [1 * ms, 0.5 * ms]),
                                ("trap", [1 * ms, 0.5 * ms]),
                                ("sdirk2", [1 * ms, 0.5 * ms]),
                                ("sdirk3", [1 * ms]),
                                ("beuler", [1 * ms])], order=False)
        multirate_sweeps(ex, quick, ["bs3", "rk4", "dopri5"], [2, 5, 10, 20],
                         [("trap", {"method": "trap"}, 5),
                          ("sdirk2 newton (1)", {"method": "sdirk2", "newton": "1"}, 5),
                          ("sdirk2 newton (2)", {"method": "sdirk2", "newton": "2"}, 5),
                          ("sdirk2 newton (4)", {"method": "sdirk2", "newton": "4"}, 5)],
                         [1e-2, 1e-3, 1e-4, 1e-5])
        stab_sweep(ex, sc)
    shipped(ex, quick, also=same_model(path, others))
    return ex


# ------------------------------------------------------------------ running

# rows are keyed by their time in units of 1/TKEY s: a float run prints t = tick * dt in
# single precision (0.128000006), so a key in nanoseconds matched the reference only where
# t is a binary fraction, and its error was taken over those few instants
TKEY = 1e4


def tkey(t):
    return round(t * TKEY)


def read_csv(path, signals):
    rows = {}
    with open(path) as f:
        r = csv.reader(f)
        head = next(r)
        idx = [head.index(s) for s in signals if s in head]
        for row in r:
            rows[tkey(float(row[0]))] = [float(row[i]) for i in idx]
    return rows


def summary(text):
    return dict(re.findall(r"^([\w.]+): (.*)$", text, re.M))


def estimate_of(ex, path, real, every, te):
    """`modrt check --observe` on the variant: its largest estimated global error over the
    error's signals at the reference's instants, with the methods' order p and with each
    signal's observed order where that is lower (None when the check did not run), and
    its global_status"""
    est_csv = path[:-4] + ".est.csv"
    r = sh([MODRT[real], "check", path, "--t-end=%.17g" % te, "--every=%d" % every,
            "--observe", "--check-csv=" + est_csv])
    s = summary(r.stdout)
    if r.returncode not in (0, 1, 3) or not os.path.exists(est_csv):
        return None, None, s.get("global_status")
    p = int(s.get("check_order", "0").split()[0] or 0)
    scale = []  # per signal: (1 - 2^-p) / (1 - 2^-q) where q took p's place
    for sig in ex.signals:
        m = re.search(r"observed order ([\d.]+), below p", s.get("global_err." + sig, ""))
        q = float(m.group(1)) if m else None
        scale.append((1 - 2 ** -p) / (1 - 2 ** -q) if q and p else 1.0)
    rows = read_csv(est_csv, ex.signals)
    keys = [k for k in ex.ref_rows if k in rows and rows[k]]
    if not keys:
        return None, None, s.get("global_status")
    est = max(max(rows[k]) for k in keys)
    est_q = max(max(v * f for v, f in zip(rows[k], scale)) for k in keys)
    return est, est_q, s.get("global_status")


def t_err(ex):
    return ex.t_err if ex.t_err else ex.sc_t_end


def host_run(ex, path, real, every, t_end, csv_out):
    cmd = [MODRT[real], "run", path, "--t-end=%.17g" % t_end, "--every=%d" % every]
    if csv_out:
        cmd.append("--csv=" + csv_out)
    r = sh(cmd)
    return r.returncode, summary(r.stdout)


def window_of(ex, sc, soft=False, rhs_per_s=0):
    """the cost window: W (or the shorter one for software doubles), shortened so that it
    holds at most RHS_BUDGET right-hand sides (a deterministic count), a whole number of
    the variant's largest common step"""
    w = ex.window_soft if soft else ex.window
    if rhs_per_s * w > RHS_BUDGET:
        w = RHS_BUDGET / rhs_per_s
    lcm = S.lcm_ticks(sc.steps().values(), sc.tick)
    n = max(1, math.ceil(w / (lcm * sc.tick) - 1e-9)) * lcm
    return n


def callgrind(real, path, ticks, tick):
    r = sh(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
            "--collect-atstart=no", "--toggle-collect=rt_tick", "--toggle-collect=rt_record",
            MODRT[real], "run", path, "--t-end=%.17g" % (ticks * tick)])
    m = re.search(r"Collected : (\d+)", r.stderr)
    return (int(m.group(1)) if m else None), summary(r.stdout).get("hash")


class Cross:
    """per-variant images: flags read once from the Makefile"""

    def __init__(self, targets):
        self.targets = targets
        # the library (study.mk) is the cross tests' objects, with their limits
        # (CROSS_TEST_DEFS): the variant's scene and its written-out code must see the same
        # rt_sim, or rt_init refuses the code (rt_scene_code.sim_layout)
        base = "%s -O2 -ffunction-sections -fdata-sections %s -DRT_KIND_DOCS=0 %s" % (
            make_var("CSTD"), make_var("CINC"), make_var("CROSS_TEST_DEFS"))
        self.cc, self.cflags, self.ldflags, self.run, self.nm = {}, {}, {}, {}, {}
        for t in targets:
            self.cc[t] = make_var("TARGET_CC_" + t)
            self.cflags[t] = base + " " + make_var("TARGET_CFLAGS_" + t)
            self.ldflags[t] = make_var("TARGET_LDFLAGS_" + t)
            self.run[t] = make_var("TARGET_RUN_" + t)
            self.nm[t] = make_var("TARGET_NM_" + t)

    def count(self, t, real, cfile, sym, ticks, out):
        sfx = "-float" if real == "float" else ""
        lib = "build/study/lib/%s%s" % (t, sfx)
        ports = open(lib + "/port.stamp").read().split()
        elf = out + ".elf"
        cmd = "%s %s %s -DFOOT_SCENE=%s -DFOOT_TICKS=%d tests/cross/footprint_main.c %s %s " \
              "%s/libstudy.a %s -o %s" % (self.cc[t], self.cflags[t],
                                          "-DRT_REAL_FLOAT" if real == "float" else "", sym,
                                          ticks, cfile, " ".join(ports), lib,
                                          self.ldflags[t], elf)
        r = sh(cmd, shell=True)
        if r.returncode:
            return {"error": "build: " + r.stderr[-300:]}
        addr = [ln.split()[0] for ln in sh([self.nm[t], elf]).stdout.splitlines()
                if ln.endswith(" port_cycles")][0]
        run = re.sub(r"-kernel$", "-plugin %s,addr=0x%s,dump=on -d plugin -kernel"
                     % (os.path.abspath(PLUGIN), addr), self.run[t])
        r = sh(run + " " + elf, shell=True)
        iv = [int(x) for x in re.findall(r"^insn_count: interval \d+ (\d+)$", r.stdout + r.stderr,
                                         re.M)]
        h = re.search(r" hash ([0-9a-f]+) ", r.stdout)
        if not iv or not h:
            return {"error": "run: " + (r.stdout + r.stderr)[-300:]}
        return {"sum": sum(iv), "max": max(iv), "ticks": len(iv), "hash": h.group(1)}


def sweep_errors(ex, jobs, sc_end):
    """the error runs of every configuration of ex: one `modrt sweep` campaign per number
    type over the configurations' scene files, its metric the error against the reference
    (written as B/KEY/ref.csv) at the reference's instants where every set has stepped;
    each configuration gets its run's status, exit code, wall time, right-hand sides and
    error (c["sweep"])"""
    d = "%s/%s" % (B, ex.key)
    with open(d + "/ref.csv", "w") as f:
        f.write(",".join(["t"] + ex.signals) + "\n")
        for k in sorted(ex.ref_rows):
            f.write(",".join([repr(k / TKEY)] + [repr(v) for v in ex.ref_rows[k]]) + "\n")
    te = ex.t_err or sc_end
    for real in sorted({c["real"] for c in ex.cfgs}):
        cfgs = [c for c in ex.cfgs if c["real"] == real]
        for c in cfgs:
            with open("%s/%s.scn" % (d, c["key"]), "w") as f:
                f.write(c["text"])
        camp = "%s/errors-%s.swp" % (d, real)
        with open(camp, "w") as f:
            f.write("campaign (study_%s_%s);\nend time (%.17g s);\ntimeout (3600 s);\n"
                    "grid scene values (%s);\nmetric (err) error against (\"ref.csv\");\n"
                    % (ex.key, real, te, ", ".join('"%s.scn"' % c["key"] for c in cfgs)))
        out = "%s/errors-%s" % (d, real)
        shutil.rmtree(out, ignore_errors=True)
        r = sh([MODRT[real], "sweep", "run", camp, "--out", out, "--jobs", str(jobs)])
        if r.returncode == 2:
            raise SystemExit("study: modrt sweep run %s: %s" % (camp, r.stderr[-500:]))
        for k, c in enumerate(cfgs):
            try:
                c["sweep"] = summary(open("%s/runs/%06d.txt" % (out, k)).read())
            except OSError:
                c["sweep"] = {"status": "missing"}


def run_cfg(ex, c, cross, sc_end):
    d = "%s/%s" % (B, ex.key)
    path = "%s/%s.scn" % (d, c["key"])
    sc = S.Scene(path)
    c["tick"] = sc.tick
    c["steps"] = sc.steps()
    c["methods"] = {n: sc.method_of(n) for n, _ in sc.sets}
    t0 = time.time()
    # error: from the campaign's run (sweep_errors)
    lcm = S.lcm_ticks(list(sc.steps().values()), sc.tick)
    every = S._ticks(ex.grid, sc.tick)
    every = every * lcm // math.gcd(every, lcm)  # where every set of it has stepped
    te = ex.t_err or sc_end
    s = c["sweep"]
    rc = int(s.get("exit", "1"))
    c["status"] = s.get("status", "no result")
    c["rc"] = rc
    if rc not in (0, 3) or "exit" not in s:
        c["fail"] = c["status"] + (" (%s)" % s["why"] if "why" in s else "")
        return c
    c["wall"] = float(s.get("wall_s", "nan")) / te
    err = float(s.get("metric.err", "nan"))
    # a NaN value compared is an infinite error; no instant compared, NaN
    c["err"] = math.inf if err != err and int(s.get("count.nan", "0")) else err
    c["err_at"], c["n_cmp"] = None, None
    c["est_p"], c["est"], c["global_status"] = estimate_of(ex, path, c["real"], every, te)
    c["rhs_per_s"] = sum(float(v) for k, v in s.items() if k.startswith("rhs_evals.")) / te
    # host instructions
    n = window_of(ex, sc, rhs_per_s=c["rhs_per_s"])
    ins, hh = callgrind(c["real"], path, n, sc.tick)
    c["host"] = ins / (n * sc.tick) if ins else None
    c["window"] = n * sc.tick
    c["host_hash"] = hh
    # cross
    if cross:
        cfile = path[:-4] + ".c"
        r = sh([SCENEC, "-o", cfile, path])
        sym = re.search(r"^const rt_scene (mdl_scene_\w+) = \{$", open(cfile).read(), re.M) \
            if r.returncode == 0 else None
        for t in cross.targets:
            soft = t == "m4f" and c["real"] == "double"
            nt = window_of(ex, sc, soft, c["rhs_per_s"]) if soft else n
            m7 = c.get("m7", {}).get("per_s")
            if soft and m7:  # software doubles: about SOFT_RATIO x the M7's instructions
                lcm = S.lcm_ticks(sc.steps().values(), sc.tick)
                fit = SOFT_BUDGET / (SOFT_RATIO * m7 * lcm * sc.tick)
                nt = min(nt, max(1, int(fit)) * lcm)
            if not sym:
                c[t] = {"error": "scenec: " + r.stderr[-200:]}
                continue
            res = cross.count(t, c["real"], cfile, sym.group(1), nt, "%s/%s-%s" % (
                d, c["key"], t))
            if "sum" in res:
                want = hh if nt == n else host_run(ex, path, c["real"], 1, nt * sc.tick,
                                                    None)[1].get("hash")
                res["hash_ok"] = res["hash"] == want
                res["per_s"] = res["sum"] / (nt * sc.tick)
                res["window"] = nt * sc.tick
            c[t] = res
    c["secs"] = time.time() - t0
    return c


def run_ref(ex, method, h, i, sc_end):
    """a fine single-rate run of the scene: (label, rows); should the scene have changed so
    that the run fails, the step is halved, twice at most"""
    for k in range(3):
        path = "%s/%s/ref%d.scn" % (B, ex.key, i)
        with open(path, "w") as f:
            f.write(S.variant(ex.sc, tick=h, single=(method, {})))
        sc = S.Scene(path)
        every = S._ticks(ex.grid, sc.tick)
        te = ex.t_err or sc_end
        rc, s = host_run(ex, path, "double", every, te, path[:-4] + ".csv")
        if rc in (0, 3):
            return "%s at %s" % (method, h_ms(h)), read_csv(path[:-4] + ".csv", ex.signals)
        h /= 2
    raise SystemExit("study: reference %s of %s failed: %s" % (method, ex.key,
                                                                s.get("status")))


def beltgear_refs(full):
    """beltgear's reference: tools/dev/study/beltgear_ref.py at 5e-6 s, its own error against
    1e-5 s"""
    r = sh([sys.executable, "tools/dev/study/beltgear_ref.py", "1e-5", "5e-6"])
    runs = []
    for ln in r.stdout.splitlines():
        v = [float(x) for x in ln.split()[2:]]
        runs.append({tkey(v[i]): [v[i + 1], v[i + 2]] for i in range(0, len(v), 3)})
    if len(runs) != 2:
        raise SystemExit("study: tools/dev/study/beltgear_ref.py failed: " + r.stderr[-300:])
    own = max(abs(a - b) for k in runs[1] for a, b in zip(runs[0][k], runs[1][k]))
    note = ("the belt gear as one ODE in five states with the drive train's loop solved in "
            "closed form, integrated piecewise (the command's jump at 10 ms is a step "
            "boundary) by RK4 in binary64 at 5e-6 s (tools/dev/study/beltgear_ref.py); against "
            "1e-5 s it moves by %.1e rad/s" % own)
    return runs[1], own, note


def pendulum_refs(full):
    """pendulum10's reference at t = 2 s: the long-double values stored in
    tests/whitebox/test_mbs_scene.c; in full mode also recomputed by pendulum_ref.py at two
    steps: the largest difference of the three is the reference's own error"""
    text = open("tests/whitebox/test_mbs_scene.c").read()
    block = re.search(r"ref_2s\[10\]\[2\] = \{(.*?)\};", text, re.S).group(1)
    vals = [float(v) for v in re.findall(r"-?\d+\.\d+(?:e-?\d+)?", block)]
    rows = {tkey(2.0): vals}
    if not full:
        return rows, None, "the chain in minimal coordinates (RK4 in long double at 5e-6 s, " \
            "tests/whitebox/test_mbs_scene.c)"
    r = sh([sys.executable, "tools/dev/study/pendulum_ref.py", "2e-4", "1e-4"])
    lines = [ln.split() for ln in r.stdout.splitlines() if ln.startswith("h ")]
    runs = [[float(v) for v in ln[2:]] for ln in lines]
    diff = max(abs(a - b) for run in runs for a, b in zip(run, vals))
    note = ("the chain in minimal coordinates (ten link angles, Lagrange's equations): the "
            "long-double values of tests/whitebox/test_mbs_scene.c (RK4 at 5e-6 s); recomputed "
            "independently by tools/dev/study/pendulum_ref.py (RK4 in binary64 at 2e-4 s and "
            "1e-4 s), which differs from them by at most %.1e m" % diff)
    return rows, diff, note


# ------------------------------------------------------------------ analysis

def ok(c):
    return "fail" not in c and c.get("err") is not None and c["err"] == c["err"]


def floor_of(ex):
    """the smallest error the plots and tables resolve: ten times the reference's own"""
    return max(1e-12, 10 * (ex.ref_err or 0))


def cheapest(ex, key, tol):
    cand = [c for c in ex.cfgs if ok(c) and c["err"] <= tol and cost(c, key)]
    return min(cand, key=lambda c: cost(c, key)) if cand else None


def cost(c, key):
    if key == "host":
        return c.get("host")
    v = c.get(key)
    return v.get("per_s") if isinstance(v, dict) else None


def describe(c):
    if c["shipped"] and c["series"] == "shipped":
        return "%s as shipped" % c["shipped"]
    return "%s, %s%s" % (c["series"], c["label"], "" if c["real"] == "double" or
                         "float" in c["series"] else " (float)")


def config_text(c):
    """the sets of a configuration in a few words"""
    parts = []
    for n, h in c["steps"].items():
        parts.append("%s %s %s" % (n, c["methods"][n], h_ms(h)))
    return ", ".join(parts) + ("" if c["real"] == "double" else ", float")


def orders(ex):
    """observed order between successive steps of each single-rate series"""
    out = []
    fl = floor_of(ex)
    for name in sorted({c["series"] for c in ex.cfgs if c.get("order")}):
        pts = sorted((c["tick"], c["err"]) for c in ex.cfgs
                     if c["series"] == name and ok(c) and c.get("order"))
        p = next(c["order"] for c in ex.cfgs if c["series"] == name)
        qs = []
        for (h1, e1), (h2, e2) in zip(pts, pts[1:]):
            if e1 > 10 * fl and e2 > 10 * fl and e2 < 1e-1:
                qs.append((h1, h2, math.log(e2 / e1) / math.log(h2 / h1)))
        out.append((name, p, qs))
    return out


def series_order(ex, name):
    """the observed order of a series between its two finest resolvable steps"""
    fl = floor_of(ex)
    pts = sorted((c["tick"], c["err"]) for c in ex.cfgs if c["series"] == name and ok(c)
                 and c["err"] > 10 * fl)
    if len(pts) < 2:
        return None
    (h1, e1), (h2, e2) = pts[0], pts[1]
    return math.log(e2 / e1) / math.log(h2 / h1) if e1 > 0 and e2 > 0 else None


def beltgear_note(ex):
    q = {m: series_order(ex, m) for m in ("rk4", "dopri5", "bs3", "sdirk3")}
    return ("The current command jumps at t = 10 ms, a step boundary of every configuration "
            "and a known time event of its step source (rt/tev.c): the step ending there "
            "evaluates the old command up to its end, the step from there the new one, so "
            "every method keeps its order across the jump. Observed orders at the finest "
            "steps: rk4 %s, dopri5 %s, sdirk3 %s, bs3 %s. The reference integrates the two "
            "pieces separately." % tuple(
                "%.2f" % v if v else "–" for v in (q["rk4"], q["dopri5"], q["sdirk3"], q["bs3"])))


def checks(ex, quick):
    """what must hold; a list of (ok, text)"""
    res = list(ex.extra_checks)
    fl = floor_of(ex)
    if ex.ref_err is not None:
        res.append((ex.ref_err * 10 <= fl, "%s: the reference's own error %.1e is below the "
                    "plotted range (from %.0e)" % (ex.key, ex.ref_err, fl)))
    for name, p, qs in orders(ex):
        if name not in ("euler", "heun", "bs3", "rk4", "dopri5"):
            continue  # implicit methods: reported, not checked (Jacobian reuse, splits)
        if qs:
            h1, h2, q = qs[0]  # the finest resolvable pair
            res.append((abs(q - p) <= 0.6, "%s: %s converges at order %.2f between %s and %s "
                        "(method order %d)" % (ex.key, name, q, h_ms(h1), h_ms(h2), p)))
        elif quick:
            res.append((False, "%s: %s: no pair of steps resolvable" % (ex.key, name)))
    for key in ("host", "m7"):
        prev = 0
        for tol in TOLS:
            c = cheapest(ex, key, tol)
            if not c:
                continue
            good = c["err"] <= tol and cost(c, key) >= prev and not any(
                ok(d) and d["err"] <= tol and cost(d, key) and cost(d, key) < cost(c, key)
                for d in ex.cfgs)
            prev = cost(c, key)
            res.append((good, "%s: the cheapest on %s within %g is consistent" % (
                ex.key, key, tol)))
    for c in ex.cfgs:
        for t in ("m7", "m4f"):
            v = c.get(t)
            if isinstance(v, dict) and "hash_ok" in v:
                res.append((v["hash_ok"], "%s: %s on %s: image hash equals the host's" % (
                    ex.key, describe(c), t)))
            elif isinstance(v, dict) and "error" in v:
                res.append((False, "%s: %s on %s: %s" % (ex.key, describe(c), t, v["error"])))
        if c["shipped"] and c["series"] == "shipped" and c["real"] == "double" and ok(c):
            r = sh([MODRT["double"], "run", c["shipped"], "--t-end=%.17g" % c["window"]])
            res.append((summary(r.stdout).get("hash") == c.get("host_hash"),
                        "%s: the variant of %s as shipped runs exactly the library scene "
                        "(same hash)" % (ex.key, c["shipped"])))
    return res


# ------------------------------------------------------------------ output

SERIES_STYLE = {}


def style(name, i):
    if name not in SERIES_STYLE:
        n = len(SERIES_STYLE)  # one style per series name over all figures
        SERIES_STYLE[name] = (svg.COLORS[n % 10], svg.MARKERS[n % len(svg.MARKERS)])
    return SERIES_STYLE[name]


def fig(ex, key, out_dir):
    names = []
    for c in ex.cfgs:
        if c["series"] not in names and c["series"] not in ("shipped", "shipped float"):
            names.append(c["series"])
    fl = floor_of(ex)
    series, stars = [], []
    for i, n in enumerate(names):
        col, mk = style(n, i)
        pts = [(cost(c, key), c["err"], c["label"]) for c in ex.cfgs
               if c["series"] == n and ok(c) and cost(c, key)]
        if pts:
            series.append({"name": n, "color": col, "marker": mk, "pts": pts,
                           "dash": "float" in n})
    for c in ex.cfgs:
        if c["shipped"] and c["series"].startswith("shipped") and ok(c) and cost(c, key):
            stars.append((cost(c, key), c["err"], c["shipped"] +
                          (" (float)" if c["real"] == "float" else "")))
    plat = {"host": "x86-64 host (callgrind)", "m7": "Cortex-M7 (QEMU)",
            "m4f": "Cortex-M4F (QEMU)"}[key]
    xlabel = {"host": "host instructions per simulated second (rt_tick + rt_record)",
              "m7": "Cortex-M7 instructions per simulated second",
              "m4f": "Cortex-M4F instructions per simulated second"}[key]
    top = None
    if key == "host":
        f = wall_factor(ex)
        if f:
            top = (f, "host wall time per simulated second [s] (at the median %.2f ns per "
                      "instruction of these runs)" % (f * 1e9))
    elif key == "m7":
        top = (1 / M7_HZ, "Cortex-M7 time per simulated second at 600 MHz [s]")
    ys = [p[1] for s in series for p in s["pts"]] + [s[1] for s in stars]
    ytop = 10 ** math.ceil(math.log10(max(ys))) if ys else 1
    ylo = 10 ** math.floor(math.log10(fl))
    note = ["open markers: below the", "reference's resolution;", "dashed: REAL=float"]
    path = "%s/%s-%s.svg" % (out_dir, ex.key, key)
    svg.plot(path, "%s: error against cost on the %s" % (ex.key, plat), xlabel,
             ex.what, series, stars,
             band=(fl, "below 10x the reference's own error: not resolved"),
             top=top, yrange=(ylo, max(ytop, ylo * 100)), note=note)
    return path


def wall_factor(ex):
    r = sorted(c["wall"] / c["host"] for c in ex.cfgs if ok(c) and c.get("host")
               and c.get("wall"))
    return r[len(r) // 2] if r else None


def fmt(v, digits=2):
    if v is None or v != v:
        return "–"
    return "%.*e" % (digits - 1, v) if v and (abs(v) < 1e-2 or abs(v) >= 1e5) else "%.3g" % v


def tables(ex):
    fl = floor_of(ex)
    o = ["| tolerance [%s] | cheapest on the host | error | estimate | host insn/s | host "
         "wall s/s | cheapest on Cortex-M7 | error | estimate | M7 insn/s | worst tick [insn] "
         "| max tick rate at 600 MHz (needed) |" % ex.unit,
         "|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|"]
    for tol in TOLS:
        if tol < fl:
            o.append("| %g | below the reference's resolution (%.0e) | | | | | | | | | | |" % (
                tol, fl))
            continue
        h, m = cheapest(ex, "host", tol), cheapest(ex, "m7", tol)
        row = ["%g" % tol]
        if h:
            row += [describe(h), fmt(h["err"]), fmt(h.get("est")), fmt(h["host"]),
                    fmt(h.get("wall"))]
        else:
            row += ["none of the configurations tried", "", "", "", ""]
        if m:
            mx = m["m7"]["max"]
            row += [describe(m), fmt(m["err"]), fmt(m.get("est")), fmt(m["m7"]["per_s"]),
                    "%d" % mx, "%s kHz (%s kHz)" % (fmt(M7_HZ / mx / 1e3, 3),
                                                   fmt(1e-3 / m["tick"], 3))]
        else:
            row += ["none of the configurations tried", "", "", "", "", ""]
        o.append("| " + " | ".join(row) + " |")
    return "\n".join(o)


def shipped_table(ex):
    o = ["| scene | real | sets | error [%s] | estimate | host insn/s | M7 insn/s | M4F insn/s "
         "| worst M7 tick [insn] | max tick rate at 600 MHz (needed) | cheapest on M7 at this "
         "error |" % ex.unit, "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|"]
    for c in ex.cfgs:
        if not (c["shipped"] and c["series"].startswith("shipped")):
            continue
        if not ok(c):
            o.append("| %s | %s | | failed: %s | | | | | | | |" % (c["shipped"], c["real"],
                                                                  c.get("fail")))
            continue
        best = cheapest(ex, "m7", c["err"])
        m7 = c.get("m7", {})
        rel = ""
        if best and m7.get("per_s"):
            rel = "%s: %s insn/s (%.2gx)" % (describe(best), fmt(best["m7"]["per_s"]),
                                            m7["per_s"] / best["m7"]["per_s"])
        mx = m7.get("max")
        o.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            c["shipped"], c["real"], config_text(c), fmt(c["err"]), fmt(c.get("est")),
            fmt(c.get("host")),
            fmt(m7.get("per_s")), fmt(c.get("m4f", {}).get("per_s")), mx or "–",
            ("%s kHz (%s kHz)" % (fmt(M7_HZ / mx / 1e3, 3), fmt(1e-3 / c["tick"], 3)))
            if mx else "–", rel))
    return "\n".join(o)


def reading(ex, key):
    """two sentences of reading for a figure, from the numbers"""
    fl = floor_of(ex)
    tight = [t for t in TOLS if t >= fl and cheapest(ex, key, t)]
    if not tight:
        return "No configuration reached 1e-2 %s." % ex.unit
    lo, hi = tight[-1], tight[0]
    a, b = cheapest(ex, key, hi), cheapest(ex, key, lo)
    s1 = ("The frontier runs from %s (%s %s, %s instructions per simulated second) to %s "
          "(%s %s, %s)" % (describe(a), fmt(a["err"]), ex.unit, fmt(cost(a, key)),
                           describe(b), fmt(b["err"]), ex.unit, fmt(cost(b, key))))
    s1 += ": %.2g times the cost for %.2g times the accuracy." % (
        cost(b, key) / cost(a, key), a["err"] / b["err"] if b["err"] else math.inf)
    ship = [c for c in ex.cfgs if c["shipped"] and c["series"] == "shipped" and ok(c)
            and cost(c, key)]
    s2 = []
    for c in ship:
        best = cheapest(ex, key, c["err"])
        if best:
            f = cost(c, key) / cost(best, key)
            s2.append("%s as shipped (%s %s) costs %s, %s" % (
                c["shipped"], fmt(c["err"]), ex.unit, fmt(cost(c, key)),
                "the cheapest configuration of its accuracy" if best is c or f <= 1.0001 else
                "about as much as the cheapest of at least its accuracy (%s)" % describe(best)
                if f < 1.05 else
                "%.2g times the cheapest of at least its accuracy (%s)" % (f, describe(best))))
    if key == "m4f":
        dbl = [c for c in ship if c["real"] == "double"]
        flt = [c for c in ex.cfgs if c["series"] == "shipped float" and ok(c)
               and cost(c, key)]
        if dbl and flt:
            s2.append("in float the same scene costs %.2g times less (%s %s error)" % (
                cost(dbl[0], key) / cost(flt[0], key), fmt(flt[0]["err"]), ex.unit))
    return s1 + " " + ("; ".join(s2) + "." if s2 else "")


def tracking(ex):
    """how the estimated global error (modrt check) tracks the error against the
    reference: est / err over the configurations whose error is resolved, with the
    methods' order and with the observed one"""
    fl = floor_of(ex)
    cs = [c for c in ex.cfgs if ok(c) and c.get("est") is not None and c["err"] > 10 * fl]
    if not cs:
        return "No configuration has a resolved error to compare the estimate with."

    def stats(key):
        q = sorted(c[key] / c["err"] for c in cs)
        return q[len(q) // 2], q[0], q[-1], sum(1 for v in q if 0.5 <= v <= 2)

    low = sorted(cs, key=lambda c: c["est"] / c["err"])[:3]
    flagged = [c for c in cs if c["err"] > 1e-3]
    said = sum(1 for c in flagged if c["est"] > 1e-3)
    return ("**The estimate of `modrt check --observe`** (the variant again at half and at "
            "a quarter of its steps, Richardson with the lowest order of its sets and "
            "couplings, or each signal's observed order where that is lower; read at the "
            "same instants and signals as the error) over the %d configurations whose error "
            "is resolved: estimate / error median %.2f, from %.2g to %.2g, within a factor 2 "
            "in %d; with the methods' order alone median %.2f, from %.2g to %.2g, within a "
            "factor 2 in %d. Of the %d with an error above 1e-3 %s, the estimate is above "
            "1e-3 in %d. Farthest below: %s." % ((len(cs),) + stats("est") + stats("est_p") + (
                len(flagged), ex.unit, said, "; ".join(
                    "%s (%.2g: %s against %s)" % (describe(c), c["est"] / c["err"],
                                                  fmt(c["est"]), fmt(c["err"]))
                    for c in low))))


def headline(ex, tol):
    c, m = cheapest(ex, "host", tol), cheapest(ex, "m7", tol)
    if not c or not m:
        return "%s to %g %s: none of the configurations tried" % (ex.key, tol, ex.unit)
    return ("%s to %g %s: on the host %s (%s insn/s, error %s); on Cortex-M7 %s (%s insn/s, "
            "worst tick %d insn, at most %s kHz at 600 MHz)" % (
                ex.key, tol, ex.unit, describe(c), fmt(c["host"]), fmt(c["err"]),
                describe(m), fmt(m["m7"]["per_s"]), m["m7"]["max"],
                fmt(M7_HZ / m["m7"]["max"] / 1e3, 3)))


def machine():
    cpu = "unknown CPU"
    try:
        for ln in open("/proc/cpuinfo"):
            if ln.startswith("model name"):
                cpu = ln.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    rev = sh(["git", "describe", "--always", "--dirty"]).stdout.strip()
    return "%s, %d cores, %s; modrt %s" % (cpu, os.cpu_count() or 0, os.uname().sysname + " "
                                           + os.uname().machine, rev)


def write_doc(exs, out_dir, started, elapsed, all_checks, jobs, where):
    o = ["# What accuracy costs in time",
         "",
         "Written by `make study` (tools/dev/study/study.py); do not edit by hand. Made %s UTC on "
         "%s, in %.0f s with %d jobs." % (time.strftime("%Y-%m-%d %H:%M", time.gmtime(started)),
                                        where, elapsed, jobs),
         "",
         "For each of the four paper examples: the error against an independent reference "
         "versus the cost, over every applicable method and a range of steps, projection on, "
         "off and Baumgarte for the multibody examples, single-rate and multirate schedules "
         "(including those `modrt tune` picks), double and float, and Newton and Broyden "
         "bounds; the implicit single-rate methods refresh their Jacobian every 1024 steps, "
         "as the shipped single-rate scenes do. Each configuration is a variant of the scene file as it is at run time "
         "(tools/dev/study/scene.py writes it: base tick, set statements, stabilization, loop "
         "bound), so the study follows the scenes when they change.",
         "",
         "**Cost.** Host: instructions of `rt_tick` and `rt_record` (with everything they "
         "call) counted by callgrind (`--toggle-collect`), deterministic run to run, unlike "
         "time on a shared machine; host wall time per simulated second of the error run is "
         "the secondary, noisy axis on top of the host figures. Cortex-M7 and Cortex-M4F: one "
         "image per configuration and target (tests/cross/footprint_main.c linked with the "
         "variant's generated C with the code scenec writes out for it, and the runtime and "
         "the models at the cross tests' limits: rt_config.h's defaults, a smaller "
         "RT_MAX_KSTATE), run "
         "under QEMU with the counting plugin tools/dev/qemu/insn_count.c, which counts the "
         "instructions of every tick (one `rt_tick` plus recording into the hash). All counts "
         "are taken over the first W simulated seconds of the run (W per example below, a "
         "whole number of the configuration's largest step; on the M4F in double, whose "
         "doubles run in software, at most W_soft and at most about %.1e instructions, "
         "which the M7's count predicts; and for the most expensive configurations at most "
         "%d right-hand sides, as the error run counts them) and scaled to one simulated second. The worst tick "
         "in that window gives the highest tick rate a 600 MHz Cortex-M7 sustains at one "
         "instruction per cycle (the assumption of docs/footprint.md; flash wait states and "
         "caches are not modelled), next to the rate the configuration needs (1 / base "
         "tick). Every image's trace hash equals the host's run of the same variant "
         "(checked, below)." % (SOFT_BUDGET, RHS_BUDGET),
         "",
         "**Error.** Against a reference that is not the configuration's own output: "
         "pendulum10 against the chain in minimal coordinates, beltgear against the same "
         "model written as one ODE (both in python, tools/dev/study/), whose own error is the "
         "difference of two steps; the others against a fine single-rate run of the same "
         "scene, whose own error is its difference to a second fine run with another method "
         "and step. The grey band in each "
         "figure lies below ten times that: errors there are not resolved (open markers sit "
         "on its floor), and the tables stop there. The error runs are one `modrt sweep` "
         "campaign per example and number type (build/study/KEY/errors-*.swp: a grid of the "
         "configurations' scene files, the metric `error against` the reference as a table, "
         "compared at the reference's instants where every set of the configuration has "
         "completed a step; docs/sweeps.md).",
         ""]
    for ex in exs:
        o += ["## %s" % ex.key, "",
              "Scene file `%s`; error: %s. Reference: %s. Cost window W = %g s (W_soft, M4F in "
              "double: %g s)." % (ex.path, ex.what, ex.ref_note, ex.window, ex.window_soft), ""]
        if ex.note:
            o += [ex.note(ex), ""]
        for key in ("host", "m7", "m4f"):
            o += ["![%s on %s](study/%s-%s.svg)" % (ex.key, key, ex.key, key), "",
                  reading(ex, key), ""]
        o += [tracking(ex), ""]
        o += ["Cheapest configuration for each tolerance:", "", tables(ex), "",
              "The shipped scenes of this model:", "", shipped_table(ex), ""]
        fails = [c for c in ex.cfgs if not ok(c)]
        if fails:
            o += ["Configurations that failed (not plotted): " + "; ".join(
                "%s (%s)" % (describe(c), c.get("fail")) for c in fails) + ".", ""]
        ords = orders(ex)
        if ords:
            o += ["Observed orders (successive steps, resolvable errors only): " + "; ".join(
                "%s %s" % (n, ", ".join("%.2f" % q for _, _, q in qs) or "–")
                for n, p, qs in ords) + ".", ""]
    o += ["## Checks", "", "`make test-study` runs a quick subset of these (STUDY=quick).", ""]
    bad = [t for good, t in all_checks if not good]
    o.append("%d checks, %d failed%s" % (len(all_checks), len(bad),
                                         (": " + "; ".join(bad)) if bad else "."))
    o += ["", "Headlines:", ""] + ["- " + headline(ex, tol) for ex in exs
                                   for tol in (1e-3, 1e-6) if tol >= floor_of(ex)]
    with open(os.path.join(out_dir, "..", "study.md") if out_dir.endswith("study")
              else os.path.join(out_dir, "study.md"), "w") as f:
        f.write("\n".join(o) + "\n")


# ------------------------------------------------------------------ main

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--mode", choices=["full", "quick"], default="full")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="", help="comma-separated example keys")
    a = ap.parse_args()
    quick = a.mode == "quick"
    started = time.time()
    where = machine()  # before the run rewrites the committed figures (git describe --dirty)
    plans = [plan_pendulum10, plan_actuated, plan_beltgear, plan_lane_change]
    if quick:
        plans = [plan_pendulum10, plan_beltgear]
    shutil.rmtree(B + "/runs", ignore_errors=True)
    exs = []
    for p in plans:
        ex = p(quick)
        if a.only and ex.key not in a.only.split(","):
            continue
        exs.append(ex)
        os.makedirs("%s/%s" % (B, ex.key), exist_ok=True)
    cross = Cross(["m7"] if quick else ["m7", "m4f"])
    pool = cf.ThreadPoolExecutor(a.jobs)
    ref_jobs = {}
    pend = None
    for ex in exs:
        ex.sc_end = S.parse_time(re.search(r"end\s+time\s*\((.*?)\)",
                                           "\n".join(ex.sc.stmts)).group(1))[0]
        if ex.key == "pendulum10":
            pend = pool.submit(pendulum_refs, not quick)
        for i, (method, h) in enumerate(ex.refs):
            ref_jobs[(ex.key, i)] = pool.submit(run_ref, ex, method, h, i, ex.sc_end)
    for ex in exs:
        if ex.key == "pendulum10":
            ex.ref_rows, ex.ref_err, ex.ref_note = pend.result()
        elif ex.ref_fn:
            ex.ref_rows, ex.ref_err, ex.ref_note = ex.ref_fn(not quick)
            for i in range(len(ex.refs)):
                label, rows = ref_jobs[(ex.key, i)].result()
                d = max((abs(a - b) for k in ex.ref_rows if k in rows
                         for a, b in zip(rows[k], ex.ref_rows[k])), default=math.inf)
                ex.extra_checks.append((d <= 1e-8, "%s: modrt, %s, agrees with the independent "
                                        "reference to %.1e %s" % (ex.key, label, d, ex.unit)))
                ex.ref_note += "; modrt with %s differs from it by %.1e %s" % (label, d, ex.unit)
        else:
            (la, ra), (lb, rb) = [ref_jobs[(ex.key, i)].result() for i in range(2)]
            ex.ref_rows = ra
            ex.ref_err = max((abs(a - b) for k in ra if k in rb
                              for a, b in zip(ra[k], rb[k])), default=math.inf)
            ex.ref_note = ("a fine single-rate run of the scene, %s; a second one, %s, differs "
                           "from it by at most %.1e %s, its own error" % (la, lb, ex.ref_err,
                                                                         ex.unit))
        print("study: %s: reference ready (own error %s), %d configurations" % (
            ex.key, ex.ref_err, len(ex.cfgs)), flush=True)
    for ex in exs:
        sweep_errors(ex, a.jobs, ex.sc_end)
        print("study: %s: %d error runs by modrt sweep (%.0f s)" % (
            ex.key, len(ex.cfgs), time.time() - started), flush=True)
    futs = [(ex, pool.submit(run_cfg, ex, c, cross, ex.sc_end)) for ex in exs for c in ex.cfgs]
    done = 0
    for ex, f in futs:
        f.result()
        done += 1
        if done % 20 == 0:
            print("study: %d of %d configurations (%.0f s)" % (done, len(futs),
                                                             time.time() - started), flush=True)
    all_checks = []
    for ex in exs:
        all_checks += checks(ex, quick)
    elapsed = time.time() - started
    out_dir = (B + "/quick") if quick else "docs/study"
    os.makedirs(out_dir, exist_ok=True)
    with open((out_dir if quick else B) + "/results.json", "w") as f:
        json.dump([{"key": ex.key, "ref_err": ex.ref_err, "cfgs": [
            {k: v for k, v in c.items() if k != "text"} for c in ex.cfgs]} for ex in exs],
            f, indent=1, default=str)
    for ex in exs:
        for key in (["host", "m7"] if quick else ["host", "m7", "m4f"]):
            fig(ex, key, out_dir)
    write_doc(exs, out_dir, started, elapsed, all_checks, a.jobs, where)
    bad = [t for good, t in all_checks if not good]
    for ex in exs:
        for tol in (1e-3, 1e-6):
            if tol >= floor_of(ex):
                print("study: " + headline(ex, tol))
    for t in bad:
        print("study: FAILED: " + t)
    print("study: %s mode, %d configurations, %.0f s, %s; checks: %d passed, %d failed" % (
        a.mode, len(futs), elapsed, "wrote docs/study.md and docs/study/*.svg" if not quick
        else "figures in " + out_dir, len(all_checks) - len(bad), len(bad)))
    return 1 if bad and quick else 0


if __name__ == "__main__":
    sys.exit(main())
