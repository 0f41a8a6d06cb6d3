#!/usr/bin/env python3
"""mujoco_scale.py - MuJoCo 2.2.2 beside modrt on scale.sh's chains and trees at equal
accuracy (docs/overhead.md, "Beside MuJoCo"): instructions per simulated second of the
cheapest configuration of each that meets an accuracy bound.

Accuracy: the largest distance between a body's position at T and the reference's, over
all bodies. The reference of a chain is its tight program (pendulum_tight.c: Cartesian
points, the projection) by dopri5 at REF_H; the tree's, MuJoCo (generalized coordinates)
by RK4 at REF_H. Each is checked against the other formulation at REF_H where that run is
affordable (the "formulations agree" column).

The sweep: steps per second n on a geometric grid (GRID); for every method of each side
(modrt: euler, heun, bs3, rk4, dopri5 with the projection; MuJoCo: semi-implicit Euler and
RK4) the smallest n whose error and the errors of the next two larger n of the grid are all
within the bound (the error at one T is not monotonic in n). A side's cost is its
instructions per step (callgrind, toggle-collect on modrt_ticks or mj_steps, start-up
uncounted) times n; the table gives the cheapest method and n of each side.

Sizes where a run to T would take too long (MuJoCo's chains and trees of 300 and 1000
bodies, whose reference MuJoCo gives for the tree) are counted per step only, with the
method and n of the largest swept size (marked in the table); modrt's chain is swept at
every size against its tight program's reference.

Usage: mujoco_scale.py [--sweep N...] [--count N...] [--t T]   (after
       SCALE_BUILD_ONLY=1 sh tools/dev/bench/scale.sh: the modrt binaries)"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

B = "build/scale"
M = "build/mujoco"
COUNTS = M + "/counts.json"
RUNS = M + "/runs"  # RUNS.<binary>: positions of each run
BOUNDS = (1e-3, 1e-6)
REF_H = 1e-4
GRID = sorted({int(round(10 * 2 ** (i / 4))) for i in range(0, 57)})  # 10 .. 200000
MODRT = ("dopri5", "rk4", "bs3", "heun", "euler")  # high orders first: their costs bound
MUJOCO = ("rk4", "euler")                           # the lower orders' searches
CHECK_INSN = 5e10  # the reference's check by the other formulation is skipped beyond
RUN_INSN = 2e10  # instructions of one run to T beyond which a sweep stops going finer
                 # (some 10 s on an idle host; the sweep's extent is the same on every run)
COUNT_STEPS = {10: 20, 30: 10, 100: 4, 300: 2, 1000: 1}


def log(*a):
    print(*a, file=sys.stderr, flush=True)


def cached(path, key, files, compute):
    """compute() kept under key in the JSON file path while no file of files changes (the
    counts and runs of this script depend on its binaries and models only)"""
    def load():
        if os.path.exists(path):
            with open(path) as fh:
                return json.load(fh)
        return {}
    got = load().get(key)
    if got and got[1] >= max(os.path.getmtime(f) for f in files if os.path.isfile(f)):
        return got[0]
    v = compute()
    d = load()  # another run may have added to it meanwhile
    d[key] = (v, time.time())
    with open("%s.%d" % (path, os.getpid()), "w") as fh:
        json.dump(d, fh)
    os.replace("%s.%d" % (path, os.getpid()), path)
    return v


def positions(cmd):
    """every body's position at the end of the run cmd (kept in RUNS)"""
    def run():
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        return [tuple(map(float, line.split())) for line in out.splitlines()]
    name = os.path.basename(cmd[1] if cmd[0].endswith("mujoco_bench") else cmd[0])
    return [tuple(p) for p in cached("%s.%s.json" % (RUNS, name), " ".join(cmd), cmd[:2],
                                     run)]


def err(p, ref):
    """the largest distance between a body's position and the reference's"""
    assert len(p) == len(ref), (len(p), len(ref))
    return max(math.dist(a, b) for a, b in zip(p, ref))


def count(cmd, fn, steps):
    """instructions per step of cmd, counted by callgrind (kept in COUNTS: one MuJoCo step
    of 1000 bodies takes minutes)"""
    def measure():
        f = "%s/cg.%d" % (M, os.getpid())
        subprocess.run(["valgrind", "--tool=callgrind", "--instr-atstart=no",
                        "--toggle-collect=" + fn, "--callgrind-out-file=" + f] + cmd,
                       check=True, capture_output=True)
        with open(f) as fh:
            n = int(next(line for line in fh if line.startswith("summary:")).split()[1])
        os.remove(f)
        return n / steps
    return cached(COUNTS, " ".join(cmd), cmd[:2], measure)


def model(shape, n):
    xml = "%s/%s-%d.xml" % (M, shape, n)
    mjb = "%s/%s-%d.mjb" % (M, shape, n)
    if not os.path.exists(mjb):
        subprocess.run([sys.executable, "tools/dev/bench/mujoco_chain.py", shape, str(n), xml],
                       check=True)
        subprocess.run([M + "/mujoco_bench", xml, "save", mjb], check=True)
    return mjb


def sides(shape, n):
    """name -> (method -> command running to T at step h) of both sides"""
    sb = "%s/scale-%s-%d" % (B, shape, n)
    mjb = model(shape, n)
    return {"modrt": lambda meth, h, t: [sb, "run", meth, repr(h), repr(t)],
            "mujoco": lambda meth, h, t: [M + "/mujoco_bench", mjb, "run", meth, repr(h),
                                          repr(t)]}


def reference(shape, n, t, insn):
    """the reference positions at t, and the other formulation's command at REF_H (None
    where that run would pass CHECK_INSN instructions)"""
    s = sides(shape, n)
    if shape == "chain":
        ref = positions(["%s/scale-%s-%d" % (B, shape, n), "ref", repr(REF_H), repr(t)])
        other = s["mujoco"]("rk4", REF_H, t)
        cost = insn.get(("mujoco", "rk4"), math.inf) * t / REF_H
    else:
        ref = positions(s["mujoco"]("rk4", REF_H, t))
        other = s["modrt"]("dopri5", REF_H, t)
        cost = insn["modrt", "dopri5"] * t / REF_H
    return ref, other if cost <= CHECK_INSN else None


def sweep(cmd, ref, t, insn, best):
    """bound -> smallest n of GRID meeting it with the next two (none when the runs would
    pass RUN_INSN first, or cost more than best[bound], the side's cheapest so far: a
    finer step only costs more), and the errors"""
    found, errs = {}, []
    for n in GRID:
        if n * t * insn > RUN_INSN or all(b in found or n * insn > best.get(b, math.inf)
                                          for b in BOUNDS):
            break
        try:
            e = err(positions(cmd(1.0 / n, t)), ref)
        except subprocess.CalledProcessError:
            e = math.inf  # unstable or refused: fails every bound
        errs.append((n, e))
        for b in BOUNDS:
            if b not in found and len(errs) >= 3 and all(x <= b for _, x in errs[-3:]):
                found[b] = errs[-3][0]
        if len(found) == len(BOUNDS):
            break
    return found, errs


def swept(shape, side):
    """whether a side is swept at the sizes counted only: modrt's chain is (its tight
    program gives the reference at any N, a run of modrt to T costs at most 1e10
    instructions); MuJoCo's dense chain is not, nor the tree, whose reference is MuJoCo"""
    return shape == "chain" and side == "modrt"


def table(rows, swept, shapes):
    """the Markdown table of rows (shape, N, bound, modrt's (cost, method, n[, True: n
    of the largest swept size]) or None, MuJoCo's, the formulations' agreement), and the
    fitted exponents"""
    print("| shape | N | bound [m] | modrt insn/s | modrt method, steps/s | MuJoCo insn/s |"
          " MuJoCo integrator, steps/s | MuJoCo / modrt | formulations agree [m] |")
    print("|---|--:|--:|--:|---|--:|---|--:|--:|")
    for shape, n, b, mo, mj, agree in rows:
        def cell(x):
            if not x:
                return "-", "not reached"
            return "%.3g" % x[0], "%s, %d%s" % (x[1], x[2], " (N = %d's)" % swept
                                                if len(x) > 3 else "")
        r = "%.2f" % (mj[0] / mo[0]) if mo and mj else "-"
        print("| %s | %d | %.0e | %s | %s | %s | %s | **%s** | %s |" % (
            (shape, n, b) + cell(mo) + cell(mj) + (r, agree)))
    fits = []
    for shape in shapes:
        for b in BOUNDS:
            for si, side in ((3, "modrt"), (4, "MuJoCo")):
                pts = [(math.log(r[1]), math.log(r[si][0])) for r in rows
                       if r[0] == shape and r[2] == b and r[si]]
                if len(pts) >= 2:
                    k = len(pts)
                    sx, sy = sum(x for x, _ in pts), sum(y for _, y in pts)
                    sxx, sxy = sum(x * x for x, _ in pts), sum(x * y for x, y in pts)
                    p = (k * sxy - sx * sy) / (k * sxx - sx * sx)
                    fits.append("%s %.0e m %s %.2f" % (shape, b, side, p))
    print("\nFitted exponent p of cost = a N^p (least squares on log-log over the rows): %s."
          % ", ".join(fits))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sweep", type=int, nargs="*", default=[10, 30, 100])
    ap.add_argument("--count", type=int, nargs="*", default=[300, 1000])
    ap.add_argument("--shapes", nargs="*", default=["chain", "tree"])
    ap.add_argument("--t", type=float, default=1.0)
    a = ap.parse_args()
    os.makedirs(M, exist_ok=True)
    src, exe = "tools/dev/bench/mujoco_bench.c", M + "/mujoco_bench"
    if not os.path.exists(exe) or os.path.getmtime(exe) < os.path.getmtime(src):
        subprocess.run(["gcc", "-std=c11", "-O2", "-Wall", "-Wextra", "-Werror",
                        src, "-lmujoco", "-lm", "-o", exe], check=True)
    rows = []
    for shape in a.shapes:
        chosen = {}  # (side, bound) -> (method, n) of the largest swept size
        for n in a.sweep + a.count:
            s = sides(shape, n)
            meths = {"modrt": MODRT, "mujoco": MUJOCO}
            insn = {}
            for side, ms in meths.items():
                for meth in ms:
                    if side == "modrt":
                        cmd = ["%s/scale-%s-%d" % (B, shape, n), "modrt",
                               str(COUNT_STEPS[n]), meth, "0.001"]
                        fn = "modrt_ticks"
                    else:
                        cmd = [M + "/mujoco_bench", model(shape, n), "count", meth, "0.001",
                               str(COUNT_STEPS[n])]
                        fn = "mj_steps"
                    if n in a.count and not swept(shape, side) and (side, meth) not in {
                            (sd, c[0]) for (sd, _), c in chosen.items()}:
                        continue
                    insn[side, meth] = count(cmd, fn, COUNT_STEPS[n])
                    log("%s %d %s %s: %.0f instructions per step" % (shape, n, side, meth,
                                                                     insn[side, meth]))
            agree = "-"
            best = {}
            if n in a.sweep or swept(shape, "modrt"):
                ref, other = reference(shape, n, a.t, insn)
                agree = "%.1e" % err(positions(other), ref) if other else "not run"
                log("%s %d: reference and the other formulation at h = %g differ by %s m"
                    % (shape, n, REF_H, agree))
                for side, ms in meths.items():
                    if n in a.count and not swept(shape, side):
                        continue
                    for meth in ms:
                        found, errs = sweep(lambda h, t: s[side](meth, h, t), ref, a.t,
                                           insn[side, meth], {b: best[sd, b][0] for sd, b
                                                              in best if sd == side})
                        log("%s %d %s %s: %s" % (shape, n, side, meth, " ".join(
                            "%d:%.1e" % x for x in errs)))
                        for b, k in found.items():
                            c = insn[side, meth] * k
                            if (side, b) not in best or c < best[side, b][0]:
                                best[side, b] = (c, meth, k)
                if n in a.sweep:
                    chosen = {key: (v[1], v[2]) for key, v in best.items()}
            for (side, b), (meth, k) in chosen.items():
                if n in a.count and not swept(shape, side):
                    best[side, b] = (insn[side, meth] * k, meth, k, True)
            for b in BOUNDS:
                rows.append((shape, n, b, best.get(("modrt", b)), best.get(("mujoco", b)),
                             agree))
                log("row", rows[-1])
    table(rows, max(a.sweep), a.shapes)


if __name__ == "__main__":
    main()
