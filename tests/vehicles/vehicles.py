#!/usr/bin/env python3
"""vehicles.py - checks of the vehicle models and the lane change (docs/vehicles.md), each
against an independent answer:
  * steady-state cornering of the single-track car: the yaw rate and lateral speed after
    20 s against the 2 x 2 steady-state system of the linear single-track model solved
    here, and the yaw rate against the closed form U delta / (L + K_us U^2);
  * a straight free roll (no steering, no drive): x = 20 t, y = psi = 0;
  * the ISO 3888-1 lane change of lane_change_planar: V1's footprint (CommonRoad vehicle
    1: 4.298 m x 1.674 m, centred between the axles) inside the cones of sections 1, 3
    and 5-6 (lane widths 1.1 b + 0.25, 1.2 b + 0.25, 1.3 b + 0.25 m; offset 3.5 m centre
    to centre), V2 within 0.75 m of V1's track at the same x, the tow bar's residual at
    rounding level, status ok.
Usage: vehicles.py MODRT"""
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
M, IZ, LF, LR, CF, CR = 1225.887, 1538.853, 0.88392, 1.50876, 158000.0, 170000.0
LENGTH, WIDTH = 4.298, 1.674
passed = failed = 0


def check(ok, what):
    global passed, failed
    if ok:
        passed += 1
    else:
        failed += 1
        print("FAIL vehicles: " + what)


def run(modrt, scene, *args):
    p = subprocess.run([modrt, "run", scene, "--csv", "-"] + list(args), capture_output=True,
                       text=True, timeout=120)
    lines = p.stdout.splitlines()
    head = lines[0].split(",") if lines else []
    rows = [[float(v) for v in ln.split(",")] for ln in lines[1:]]
    summ = dict(ln.split(": ", 1) for ln in p.stderr.splitlines() if ": " in ln)
    return p.returncode, summ, head, rows


def steady_state(U, d):
    """v, r of m (v' + U r) = F_yf + F_yr, Iz r' = lf F_yf - lr F_yr at v' = r' = 0"""
    a11, a12 = -(CF + CR) / U, -(CF * LF - CR * LR) / U - M * U
    a21, a22 = -(LF * CF - LR * CR) / U, -(LF * LF * CF + LR * LR * CR) / U
    b1, b2 = -CF * d, -LF * CF * d
    det = a11 * a22 - a12 * a21
    return (b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det


def cornering(modrt):
    rc, summ, head, rows = run(modrt, os.path.join(HERE, "cornering.scn"))
    last = dict(zip(head, rows[-1]))
    v, r = steady_state(20.0, 0.02)
    L = LF + LR
    k_us = M * (LR / CF - LF / CR) / L
    r_closed = 20.0 * 0.02 / (L + k_us * 400.0)
    er, ev = abs(last["Car.r"] / r - 1), abs(last["Car.v"] / v - 1)
    print("vehicles: cornering: r %.9f (steady state %.9f, closed form %.9f), v %.9f (%.9f)"
          % (last["Car.r"], r, r_closed, last["Car.v"], v))
    check(rc == 0 and er < 1e-5 and ev < 1e-4 and abs(r / r_closed - 1) < 1e-12,
          "cornering: r off by %.3g, v by %.3g (exit %d)" % (er, ev, rc))
    check(abs(last["Car.ay"] - 20.0 * r) < 1e-4 * abs(20.0 * r),
          "cornering: ay %.6f, U r %.6f" % (last["Car.ay"], 20.0 * r))


def magic(alpha, ca, fz, mu=1.0, c=1.3, e=-0.5):
    d = mu * fz
    b = ca / (c * d)
    ba = b * alpha
    return d * math.sin(c * math.atan(ba - e * (ba - math.atan(ba))))


def steady_state_mf(U, d):
    """v, r of the Magic-Formula car in steady state: Newton's method on
    F_yf + F_yr - m U r = 0, lf F_yf - lr F_yr = 0 (finite-difference Jacobian)"""
    L, w = LF + LR, M * 9.81

    def res(v, r):
        fyf = magic(d - math.atan((v + LF * r) / U), CF, w * LR / L)
        fyr = magic(-math.atan((v - LR * r) / U), CR, w * LF / L)
        return fyf + fyr - M * U * r, LF * fyf - LR * fyr

    v, r = steady_state(U, d)  # the linear answer as the start
    for _ in range(50):
        f1, f2 = res(v, r)
        h = 1e-7
        a11, a21 = [(x - y) / h for x, y in zip(res(v + h, r), (f1, f2))]
        a12, a22 = [(x - y) / h for x, y in zip(res(v, r + h), (f1, f2))]
        det = a11 * a22 - a12 * a21
        dv, dr = (f1 * a22 - a12 * f2) / det, (a11 * f2 - a21 * f1) / det
        v, r = v - dv, r - dr
        if abs(dv) + abs(dr) < 1e-15:
            break
    return v, r


def cornering_mf(modrt):
    rc, summ, head, rows = run(modrt, os.path.join(HERE, "cornering_mf.scn"))
    last = dict(zip(head, rows[-1]))
    v, r = steady_state_mf(20.0, 0.04)
    vl, rl = steady_state(20.0, 0.04)
    er, ev = abs(last["Car.r"] / r - 1), abs(last["Car.v"] / v - 1)
    print("vehicles: cornering, Magic Formula: r %.9f (steady state %.9f; linear tires %.6f)"
          ", v %.9f (%.9f)" % (last["Car.r"], r, rl, last["Car.v"], v))
    check(rc == 0 and er < 1e-5 and ev < 1e-4 and abs(r / rl - 1) > 0.01,
          "cornering (Magic Formula): r off by %.3g, v by %.3g (exit %d)" % (er, ev, rc))


def free_roll(modrt):
    rc, summ, head, rows = run(modrt, os.path.join(HERE, "cornering.scn"), "--set",
                               "Steer.y0=0", "--set", "Steer.y1=0", "--set", "Kp.k=0")
    worst = max(max(abs(r[head.index("Car.x")] - 20 * r[0]), abs(r[head.index("Car.y")]),
                    abs(r[head.index("Car.psi")])) for r in rows)
    check(rc == 0 and worst < 1e-9, "free roll: off the straight line by %.3g" % worst)


def lanes(x, x0):
    """(centre, half width) of the lane at x, or None between the lane sections"""
    b = WIDTH
    s = x - x0
    if 0 <= s <= 15:
        return 0.0, (1.1 * b + 0.25) / 2
    if 45 <= s <= 70:
        return 3.5, (1.2 * b + 0.25) / 2
    if 95 <= s <= 125:
        return 0.0, (1.3 * b + 0.25) / 2
    return None


def corners(x, y, psi):
    """the footprint's corners: a box of LENGTH x WIDTH centred between the axles"""
    cx, cy = x + (LF - LR) / 2 * math.cos(psi), y + (LF - LR) / 2 * math.sin(psi)
    c, s = math.cos(psi), math.sin(psi)
    out = []
    for a in (LENGTH / 2, -LENGTH / 2):
        for b in (WIDTH / 2, -WIDTH / 2):
            out.append((cx + a * c - b * s, cy + a * s + b * c))
    return out


def lane_change(modrt, scene="lane_change_planar", x0=20.0):
    rc, summ, head, rows = run(modrt, scene)
    col = {h: i for i, h in enumerate(head)}
    worst = 1e9  # smallest margin to a cone line [m]
    for r in rows:
        for cx, cy in corners(r[col["V1.x"]], r[col["V1.y"]], r[col["V1.psi"]]):
            lane = lanes(cx, x0)
            if lane:
                worst = min(worst, lane[1] - abs(cy - lane[0]))
    # V2's lateral distance from V1's track at the same x (V1's track interpolated)
    xs = [r[col["V1.x"]] for r in rows]
    ys = [r[col["V1.y"]] for r in rows]
    dev, j = 0.0, 0
    for r in rows:
        x2 = r[col["V2.x"]]
        while j + 1 < len(xs) and xs[j + 1] < x2:
            j += 1
        if xs[0] <= x2 <= xs[-1] and j + 1 < len(xs) and xs[j + 1] > xs[j]:
            y1 = ys[j] + (ys[j + 1] - ys[j]) * (x2 - xs[j]) / (xs[j + 1] - xs[j])
            dev = max(dev, abs(r[col["V2.y"]] - y1))
    res = max(abs(r[col["V1.residual"]]) for r in rows)
    ay = max(abs(r[col["V1.ay"]]) for r in rows)
    print("vehicles: %s: smallest margin to the cones %.3f m, V2 off V1's track by at most "
          "%.3f m, tow-bar residual %.2g m, peak |ay| of V1 %.2f m/s^2, status %s"
          % (scene, worst, dev, res, ay, summ.get("status")))
    check(rc == 0, "%s: exit %d (%s)" % (scene, rc, summ.get("status")))
    check(worst > 0, "%s: V1 hits a cone (margin %.3f m)" % (scene, worst))
    check(dev < 0.75, "%s: V2 %.3f m off V1's track" % (scene, dev))
    check(res < 1e-12, "%s: tow-bar residual %.3g" % (scene, res))


def multirate(modrt):
    """lane_change (vehicles RK4 5 ms, steering chain ROS2 1 ms) and lane_change_single
    (all ROS2 1 ms) against a reference by another method (lane_change_single by SDIRK3
    at 1 ms): positions at the 5 ms instants, the servo's wheel angle at every tick"""
    runs = {}
    for name, args in (("ref", ["lane_change_single", "--method", "all=sdirk3"]),
                       ("lane_change", ["lane_change"]),
                       ("lane_change_single", ["lane_change_single"])):
        rc, summ, head, rows = run(modrt, *args)
        runs[name] = (rc, summ, head, rows)
    _, _, head, ref = runs["ref"]
    col = {h: i for i, h in enumerate(head)}
    pos = [col[k] for k in ("V1.x", "V1.y", "V2.x", "V2.y")]
    for name in ("lane_change", "lane_change_single"):
        rc, summ, _, rows = runs[name]
        e = max(abs(a[i] - b[i]) for a, b in zip(ref, rows) if round(a[0] * 1000) % 5 == 0
                for i in pos)
        ew = max(abs(a[col["Servo.delta"]] - b[col["Servo.delta"]]) for a, b in zip(ref, rows))
        print("vehicles: %s: largest position difference from the reference %.2g m, wheel "
              "angle %.2g rad, host %s s, status %s" % (name, e, ew, summ.get("wall_s"),
                                                        summ.get("status")))
        check(rc == 0 and e < 1e-4 and ew < 1e-4,
              "%s: %.3g m / %.3g rad from the reference" % (name, e, ew))


def main():
    modrt = sys.argv[1]
    cornering(modrt)
    cornering_mf(modrt)
    free_roll(modrt)
    lane_change(modrt)
    lane_change(modrt, "lane_change")
    lane_change(modrt, "lane_change_single")
    multirate(modrt)
    print("vehicles: %d passed, %d failed" % (passed, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
